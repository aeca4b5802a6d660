"""Why the hybrid's contact area is too large on the section 3 surface, and what that does
against the full FEM.

The hybrid reads the high-slope law (paper eqs. 1-3), a mean over one cell of a periodic
array of crests on a *flat* base, under the low-slope contact. Its windowed reading has
18-26 % more contact area than the VHS with the linear law and than the FEM with the FEM law
(VALIDATION.md, **Area, not friction**). Two causes are separated here:

- **load sharing**: how the low-slope solve shares the load among the discrete crests
  (the windowed reading averages over the crests' phase; a narrow patch then straddles two
  cells, and with ``α_hs`` concave in the load that adds area);
- **curvature**: on section 3 the low-slope waves are only 2 and 4 times ``λ_hs`` and steep,
  so a crest sits on a low-slope bump of comparable curvature. A Hertz-like contact of width
  ``a ~ sqrt(F R)`` at fixed load is narrower by ``sqrt(κ_hs / (κ_hs + κ_ls))``, with
  ``κ_hs`` the crest's curvature and ``κ_ls = -z_ls''`` at the crest; the law, made on a
  flat base, does not know it.

Readings of the same law (each also with its contact fraction multiplied by that curvature
factor at the crest, "+ curvature"):

- *windowed*: the package's ``hybrid-windowed`` (law at the low-slope pressure averaged over
  one ``λ_hs``; the curvature taken at every point, as the window's crest is there);
- *patch* (experimental): each connected low-slope contact patch tiled by ``λ_hs`` cells
  centred on its centre of force, the law read at each cell's load;
- *crest-resolved* (experimental, ``scale_separation.crest_resolved_loads``);
- *law at VHS crest loads* (diagnostic, linear law only): the VHS's own load on each crest;
- *law at FEM crest loads* (diagnostic, FEM law, full FEM from the cache): the full FEM's own
  face pressure summed per crest cell.

Part 1 uses the linear law (the VHS of the high-slope wave alone), so a reading that
shares the load and shapes the contacts right reproduces the VHS. Part 2 uses the
validation's FEM law against the validation's full FEM, for the realizations whose full-FEM
tests are in the cache (else from the sampling studies' per-test tables). Part 3 compares
the two laws. Run (about 10 minutes for both speeds on one core)::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies crest_curvature \\
        --report docs/validation/crest_curvature.md
"""

from __future__ import annotations

import argparse
import re
import subprocess
import warnings
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
import xarray as xr

import rubbercontact as rc
from rubbercontact.hybrid.law import linear_law, tabulated_law_from_dict
from rubbercontact.hybrid.metrics import mean_relative_error
from rubbercontact.hybrid.tasks import halfspace_task
from rubbercontact.hybrid.windowing import law_in_pressure, window_average
from rubbercontact.inputs import build_material, build_surface
from rubbercontact.pipeline.plan import full_fem_task
from rubbercontact.pipeline.setup import translated_to_zero_phase
from rubbercontact.roughness import SineSeries
from rubbercontact.sweep import ResultCache

from . import _compare as compare
from . import sampling_study, validate
from ._rows import publish
from .crest_section3 import law_tables
from .scale_separation import crest_cells, crest_loads, crest_resolved_loads

DESCRIPTION = ("Why the hybrid's contact area is too large on the "
               "section 3 surface, and what that does against the full FEM.")

ROOT = Path(__file__).resolve().parents[1]
#: Per-test full-FEM tables of the sampling studies, read when the cache lacks the tests.
TABLES = {10.0: ROOT / "docs" / "validation" / "sampling_study_10mms.md",
          50.0: ROOT / "docs" / "validation" / "sampling_study.md"}
READINGS = ("windowed", "patch", "crest-resolved", "law at VHS crest loads")


def curvature_factor(hs: SineSeries, ls: SineSeries, x: np.ndarray) -> np.ndarray:
    """``sqrt(κ_hs / (κ_hs + κ_ls(x)))``: the width of a Hertz-like contact at fixed load on a
    crest of curvature ``κ_hs`` standing on a low-slope surface of convexity
    ``κ_ls = -z_ls''(x)``, relative to the flat base of the law's cell. ``κ_hs`` is the crest
    curvature of the high-slope part (sqrt(2) x its rms curvature: exact for one sine); the
    denominator is bounded below by ``κ_hs / 5`` (a crest in a deep low-slope trough)."""
    xx = np.linspace(0.0, float(np.max(hs.wavelengths)), 1024, endpoint=False)
    k_hs = np.sqrt(2.0 * np.mean(hs.curvatures(xx) ** 2))
    k_ls = -ls.curvatures(np.asarray(x, float))
    return np.sqrt(k_hs / np.maximum(k_hs + k_ls, 0.2 * k_hs))


def patch_cells(pressure: np.ndarray, period: float, lam: float
                ) -> tuple[np.ndarray, np.ndarray]:
    """``(loads [MPa], centres [mm])`` of ``λ_hs`` cells tiling each connected patch of
    ``pressure > 0`` from the patch's centre of force (a patch narrower than ``λ_hs`` puts its
    whole force on one cell)."""
    n = pressure.size
    dx = period / n
    on = pressure > 1e-9 * pressure.max()
    if on.all():
        patches = [np.arange(n)]
    else:
        s0 = int(np.argmin(on))                       # start the scan off contact
        rolled = np.roll(on, -s0).astype(int)
        edges = np.diff(np.r_[0, rolled, 0])
        patches = [(np.arange(a, b) + s0) % n
                   for a, b in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1),
                                   strict=True)]
    loads, centres = [], []
    for idx in patches:
        x = (idx[0] + np.arange(idx.size)) * dx        # unwrapped
        f = pressure[idx]
        xc = float((f * x).sum() / f.sum())
        k0 = int(np.floor((x[0] - xc) / lam + 0.5))
        k1 = int(np.ceil((x[-1] + dx - xc) / lam - 0.5))
        for k in range(k0, k1 + 1):
            a, b = xc + (k - 0.5) * lam, xc + (k + 0.5) * lam
            overlap = np.clip(np.minimum(x + dx, b) - np.maximum(x, a), 0.0, dx)
            load = float((f * overlap).sum()) / lam
            if load > 0:
                loads.append(load)
                centres.append((xc + k * lam) % period)
    return np.asarray(loads), np.asarray(centres)


def readings(real: SineSeries, period: float, table: dict, material, velocity: float,
             pressure: float, n: int, m2_threshold: float, with_vhs: bool,
             fem_profile: tuple[np.ndarray, np.ndarray] | None = None) -> dict:
    """``{name: (μ, A, A with the curvature factor)}`` of every reading of ``table`` on one
    realization and load (``"VHS"`` too when ``with_vhs``; ``"law at FEM crest loads"``
    when the full FEM's face pressure ``(x, p)`` is given, in the zero-phase frame of
    :func:`~rubbercontact.pipeline.plan.full_fem_task`)."""
    hs, ls = real.partition(m2_threshold)
    lam = float(np.min(hs.wavelengths))
    sig, alpha, tau = law_in_pressure(table)
    hy = halfspace_task(ls.as_dict(), period, material.as_dict(), velocity, pressure, n=n,
                        interface_law=table, keep_profile=True)
    p_ls, mu_ls = hy["pressure_profile"].values, float(hy["friction_ls"])
    x = np.arange(n) * period / n
    _, crests = crest_cells(hs, period, n)
    x_crest = crests * period / n

    def read(loads, where, weight):
        a = np.interp(loads, sig, alpha) * weight
        return (mu_ls + float(np.sum(np.interp(loads, sig, tau) * weight)) / pressure,
                float(a.sum()), float((a * curvature_factor(hs, ls, where)).sum()))

    pbar = np.maximum(window_average(p_ls, period, lam), 0.0)
    out = {"windowed": read(pbar, x, np.full(n, 1.0 / n))}
    loads, centres = patch_cells(p_ls, period, lam)
    out["patch"] = read(loads, centres, np.full(loads.size, lam / period))
    loads = crest_resolved_loads(ls, hs, period, table, material, velocity, pressure, n=n)
    out["crest-resolved"] = read(loads, x_crest, np.full(loads.size, 1.0 / loads.size))
    if with_vhs:
        vhs = rc.halfspace.solve_sliding(real, period, material, velocity, pressure, n=n)
        loads = crest_loads(np.asarray(vhs.pressure), hs, period)
        out["law at VHS crest loads"] = read(loads, x_crest,
                                             np.full(loads.size, 1.0 / loads.size))
        out["VHS"] = (vhs.friction, vhs.contact_fraction, vhs.contact_fraction)
    if fem_profile is not None:
        hs_t, ls_t = translated_to_zero_phase(real).partition(m2_threshold)
        x_f, p_f = fem_profile
        # Nodal face pressure (force per deformed face length) times the node's projected
        # share of the cell is its vertical force: deposit that on the grid.
        x_f = np.mod(x_f, period)
        xs = np.r_[x_f[-1] - period, x_f, x_f[0] + period]
        share = 0.5 * (xs[2:] - xs[:-2])
        grid = np.zeros(n)
        np.add.at(grid, np.floor(x_f / period * n).astype(int) % n, p_f * share * n / period)
        loads = crest_loads(grid, hs_t, period)
        _, crests_t = crest_cells(hs_t, period, n)
        a = np.interp(loads, sig, alpha) / loads.size
        out["law at FEM crest loads"] = (
            mu_ls + float(np.mean(np.interp(loads, sig, tau))) / pressure, float(a.sum()),
            float((a * curvature_factor(hs_t, ls_t, crests_t * period / n)).sum()))
        out["FEM force closure"] = (float(grid.mean()) / pressure,) * 3
    return out


def _pct(x: float, ref: float) -> str:
    return f"{100 * (x / ref - 1):+.1f}"


def linear_part(cfg, velocity: float, realizations, material, base) -> list[str]:
    """Each reading of the linear law against the VHS, means over the realizations."""
    acc: dict = {}
    for real in realizations:
        table = linear_law(real.partition(cfg.surface.m2_threshold)[0], material, velocity)
        for p in cfg.loads.pressures:
            r = readings(real, base.period, table, material, velocity, float(p),
                         cfg.halfspace.n, cfg.surface.m2_threshold, with_vhs=True)
            acc.setdefault(float(p), []).append(r)
    lines = [f"| {velocity:g} | σ0 [MPa] | VHS μ (A) | "
             + " | ".join(f"{k}: μ (A, A + curvature)" for k in READINGS) + " |",
             "|---|---|---|" + "---|" * len(READINGS)]
    lines[0] = lines[0].replace(f"| {velocity:g} |", "| v [mm/s] |", 1)
    for p, rs in acc.items():
        mean = {k: np.mean([r[k] for r in rs], axis=0) for k in rs[0]}
        mv, av, _ = mean["VHS"]
        cells = [f"{mean[k][0]:.3f} ({mean[k][1]:.4f}, {mean[k][2]:.4f}): "
                 f"{_pct(mean[k][0], mv)} / {_pct(mean[k][1], av)}, {_pct(mean[k][2], av)} %"
                 for k in READINGS]
        lines.append(f"| {velocity:g} | {p:g} | {mv:.3f} ({av:.4f}) | " + " | ".join(cells)
                     + " |")
    return lines


def fem_from_cache(cfg, velocity: float, realizations, material, cache: Path) -> list:
    """Per realization, the full FEM's ``[(μ, A)]`` per load from the cache, for the first
    realizations that have every load."""
    store = ResultCache(cache)
    out = []
    for real in realizations:
        entries = [store.load(full_fem_task(cfg, real, material, velocity, float(p)).key())
                   for p in cfg.loads.pressures]
        if any(e is None or e.status != "ok" for e in entries):
            break
        out.append([(float(e.result["friction"]), float(e.result["contact_fraction"]),
                     (e.result["x_fem"].values, e.result["pressure_profile"].values))
                    for e in entries])
    return out


def fem_from_table(path: Path, cfg, velocity: float) -> list:
    """The same from a sampling-study report's per-test table (its study-mesh column, the
    validation's full FEM, 3 and 4 decimals), for the realizations listed at every load."""
    pressures = [float(p) for p in cfg.loads.pressures]
    found = {}
    for line in path.read_text().splitlines():
        m = re.match(r"\| ([\d.]+) \| ([\d.]+) \| (\d+) \| [\d.]+ \([\d.]+\) \| "
                     r"([\d.]+) \(([\d.]+)\) \|", line)
        if m and float(m.group(1)) == velocity and float(m.group(2)) in pressures:
            found[int(m.group(3)), float(m.group(2))] = (float(m.group(4)), float(m.group(5)))
    out = []
    for r in range(len(found)):
        if not all((r, p) in found for p in pressures):
            break
        out.append([found[r, p] for p in pressures])
    return out


def fem_part(cfg, velocity: float, realizations, material, base, table, fem: list
             ) -> list[str]:
    """Readings of the FEM law against the full FEM ``fem`` (from :func:`fem_from_cache` or
    :func:`fem_from_table`): eq. 28 at equal area and σ0."""
    pressures = [float(p) for p in cfg.loads.pressures]
    rows, closure = [], []
    for real, fem_row in zip(realizations, fem, strict=False):
        row = []
        for p, fem_pa in zip(pressures, fem_row, strict=True):
            profile = fem_pa[2] if len(fem_pa) > 2 else None
            r = readings(real, base.period, table, material, velocity, p, cfg.halfspace.n,
                         cfg.surface.m2_threshold, with_vhs=True, fem_profile=profile)
            vals = {"fem": fem_pa[:2], "vhs": r["VHS"][:2]}
            names = [*READINGS[:3]] + (["law at FEM crest loads"] if profile else [])
            for k in names:
                vals[k] = r[k][:2]
                vals[k + " + curvature"] = (r[k][0], r[k][2])
            if profile:
                closure.append(r["FEM force closure"][0])
            row.append(vals)
        rows.append(row)
    models = list(rows[0][0])
    arr = np.array([[[row[ip][m] for ip in range(len(pressures))] for row in rows]
                    for m in models])                 # (model, realization, pressure, 2)
    dims = ("model", "velocity", "realization", "pressure")
    ds = xr.Dataset({"friction": (dims, arr[:, None, ..., 0]),
                     "contact_fraction": (dims, arr[:, None, ..., 1])},
                    coords={"model": models, "velocity": [velocity],
                            "realization": np.arange(len(rows)), "pressure": pressures})
    ds = compare.with_realization_means(ds)
    others = tuple(models[1:])
    eq = compare.eq28_first(ds, None, models=others)[velocity]
    areas, e, ci = eq
    fm = ds["friction_mean"].sel(velocity=velocity)
    lines = [f"| model | eq. 28 at equal area ({areas.min():.3f}-{areas.max():.3f}) | "
             "eq. 28 at equal σ0 | " + " | ".join(f"μ (A) at {p:g} MPa" for p in pressures)
             + " |", "|---|---|---|" + "---|" * len(pressures)]
    for m in models:
        at_area = (f"{100 * e[m]:.1f} % ({100 * ci[m][0]:.1f}-{100 * ci[m][1]:.1f})"
                   if m in e and m in ci else ("" if m == "fem" else f"{100 * e[m]:.1f} %"))
        e_load = mean_relative_error(fm.sel(model="fem").values, fm.sel(model=m).values)
        at_load = "" if m == "fem" else f"{100 * e_load:.1f} %"
        at = ds.sel(model=m, velocity=velocity)
        cells = [f"{float(at['friction_mean'].sel(pressure=p)):.3f} "
                 f"({float(at['contact_fraction_mean'].sel(pressure=p)):.4f})"
                 for p in pressures]
        lines.append(f"| {m} | {at_area} | {at_load} | " + " | ".join(cells) + " |")
    if closure:
        lines += ["", "*Law at FEM crest loads* (diagnostic): the full FEM's own face pressure at "
                  "the end of the test, summed per crest cell, read through the law with the "
                  "hybrid's μ_ls. Its nodal pressures on their projected shares of the face carry "
                  f"{min(closure):.3f}-{max(closure):.3f} of the applied load."]
    return lines


def law_part(velocity: float, fem_table: dict, linear_table: dict) -> list[str]:
    """``ū`` and ``μ_hs`` of the FEM law against the linear law at the same pressures."""
    def at(table, p):
        law = tabulated_law_from_dict(table)
        u = np.linspace(table["separation"][0], table["separation"][-1], 20000)
        s = law.pressure(u)
        sig, _, tau = law_in_pressure(table)
        return 1e3 * float(np.interp(-p, -s, u)), float(np.interp(p, sig, tau)) / p

    cells = []
    for p in (0.1, 0.3, 1.0, 2.0, 4.0):
        (uf, mf), (ul, ml) = at(fem_table, p), at(linear_table, p)
        cells.append(f"| {velocity:g} | {p:g} | {uf:.2f} | {ul:.2f} | {mf:.3f} | {ml:.3f} |")
    return cells


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--velocities", type=float, nargs="+", default=[10.0, 50.0])
    ap.add_argument("--realizations", type=int, default=10)
    ap.add_argument("--cache", type=Path, default=ROOT / ".validation-cache")
    ap.add_argument("--report", type=Path)
    args = ap.parse_args(argv)
    validate.seed_cache(validate.REFERENCE_CACHE, args.cache)
    cfg = sampling_study.study_config(args.velocities, args.realizations, (240, 45), 8.0, 1,
                                      args.cache, Path("/tmp/crest_curvature"))
    material = build_material(cfg.material)
    base = build_surface(cfg.surface).series
    reals = base.realizations(args.realizations, seed=cfg.seed)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tables = law_tables(cfg)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True).stdout.strip()
    lines = ["# The hybrid's contact area on the section 3 surface: load sharing and the "
             "curvature under the crests", "",
             f"Generated by `studies/crest_curvature.py` ({datetime.now(UTC):%Y-%m-%d %H:%M}"
             f" UTC, commit {commit}). Section 3 surface of the quick validation, "
             f"{args.realizations} realizations, 0.15 / 0.35 / 0.8 MPa; the readings are "
             "described in the script's docstring. Errors in per cent: μ / A, A + curvature.",
             "", "## 1. Linear law against the VHS", ""]
    for v in args.velocities:
        lines += linear_part(cfg, v, reals, material, base) + [""]
    lines += ["## 2. The validation's FEM law against the validation's full FEM", ""]
    for v in args.velocities:
        fem = fem_from_cache(cfg, v, reals, material, args.cache)
        source = "the cache"
        table = TABLES.get(v)
        if len(fem) < 2 and table is not None and table.exists():
            fem, source = fem_from_table(table, cfg, v), f"`{table.relative_to(ROOT)}`"
        fem = fem[:len(reals)]
        if len(fem) < 2:
            lines += [f"{v:g} mm/s: fewer than 2 realizations of full FEM available.", ""]
            continue
        lines += [f"{v:g} mm/s, the first {len(fem)} realizations (full FEM from {source}):",
                  "", *fem_part(cfg, v, reals, material, base, tables[v], fem), ""]
    lines += ["## 3. The FEM law against the linear law", "",
              "| v [mm/s] | p̄ [MPa] | ū FEM [um] | ū linear [um] | μ_hs FEM | μ_hs linear |",
              "|---|---|---|---|---|---|"]
    hs0 = reals[0].partition(cfg.surface.m2_threshold)[0]
    for v in args.velocities:
        lines += law_part(v, tables[v], linear_law(hs0, material, v))
    return publish("\n".join(lines) + "\n", args.report)


if __name__ == "__main__":
    raise SystemExit(main())
