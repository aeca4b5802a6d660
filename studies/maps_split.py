"""Does the hybrid's scale split hold on height maps? Linear-law hybrid against the 2D VHS.

The 3D analogue of ``studies/scale_separation.py``: a map made of one high-slope band and
one low-slope band is solved by the viscoelastic half-space (VHS, the 2D BEM) as a whole,
and by the hybrid: the map split by octave bands (``rubbercontact.roughness.split_map``), the
high-slope band's law the VHS solution of its cell alone (``linear_law_map``), the low-slope
map by the 2D BEM with that law, read pointwise (the paper's eqs. 6, 8) or at the pressure
averaged over the cell (``windowing2d``). With the linear law the difference is the
hybrid's scale split alone, free of any FEM effect. The 2D mean-field theory on the map's
spectrum is run beside them.

Surfaces (square maps of side ``L = 2 λ_ls``, sliding along x; SBR, 10 mm/s, hard wall):

- low-slope band: the octave band of ``λ_ls = ratio × λ_hs`` (ratio 2, 4, 16), isotropic,
  random phases (seeded), rms slope along x ``m2_ls`` (0.3 or 0.94);
- high-slope band, ``λ_hs = 0.0625 mm``, rms slope along x 1.33 (the paper's wave), either
  ``crate``: the paper's wave along x plus the same wave along y (random phases), periodic on
  the cell, which is then the map's high-slope part itself: the scale split alone, as in
  1D; or ``band``: the isotropic octave band of ``λ_hs`` with random phases, which the cell
  (one, two or four periods ``λ_hs`` in x and y) holds only on its coarse lattice.

Grids: 16 points per ``λ_hs`` (64² … 512²), the cell at the same spacing; a resolution check
at 32 points per ``λ_hs`` for ratios 2 and 4. Rows are kept in
``docs/validation/maps_split.jsonl`` (a rerun resumes).

Run (about 25 min on one core)::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies maps_split \
        --report docs/validation/maps_split.md
"""

from __future__ import annotations

import argparse
import subprocess
import time
import warnings
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

from rubbercontact import meanfield
from rubbercontact.hybrid.maps import (
    MapHybridOptions,
    linear_law_map,
    solve_map,
    solve_map_hybrid,
)
from rubbercontact.materials import sbr
from rubbercontact.roughness.maps import HeightMap
from rubbercontact.roughness.mapsplit import split_map
from rubbercontact.roughness.mapstats import map_psd
from rubbercontact.roughness.mapsynth import realize

from ._rows import append_row, publish, read_rows
from ._templates import render

DESCRIPTION = ("Does the hybrid's scale split hold on height maps? Linear-law hybrid against "
               "the 2D VHS by wavelength ratio.")

HS_WAVELENGTH, HS_AMPLITUDE = 0.0625, 0.01867
HS_SLOPE = 2 * np.pi / HS_WAVELENGTH * HS_AMPLITUDE / np.sqrt(2)   # 1.33
RATIOS = (2, 4, 16)
M2_LS = (0.3, 0.94)
PRESSURES = (0.15, 0.35)
SEEDS = (1, 2)
VELOCITY = 10.0
#: (high-slope band, cell periods) of the main table
KINDS = (("crate", 1), ("band", 1), ("band", 2), ("band", 4))
POINTS = 16
CHECK_POINTS = 32
ROOT = Path(__file__).resolve().parent.parent
ROWS = ROOT / "docs" / "validation" / "maps_split.jsonl"


def band_heights(side: float, n: int, wavelength: float, slope_x: float, seed: int
                 ) -> np.ndarray:
    """An isotropic octave band ``[q/√2, √2 q)``, ``q = 2π/wavelength``, on an ``n²`` grid
    of side ``side`` [mm]: equal variance per mode, rms slope along x ``slope_x``, random
    phases. Built on the coarsest grid that holds the band and Fourier-interpolated, so the
    same seed gives the same surface at every resolution."""
    n0 = 4 * int(np.ceil(np.sqrt(2) * side / wavelength)) + 4
    q = 2 * np.pi * np.fft.fftfreq(n0, side / n0)
    qy, qx = np.meshgrid(q, q, indexing="ij")
    k, qc = np.hypot(qx, qy), 2 * np.pi / wavelength
    power = np.where((k >= qc / np.sqrt(2)) & (k < qc * np.sqrt(2)), 1.0, 0.0)
    power *= slope_x**2 / np.sum(qx**2 * power)
    coarse = HeightMap(realize(power, seed), (side, side), periodic=True)
    return coarse.resampled((n, n)).heights


def crate_heights(side: float, n: int, seed: int) -> np.ndarray:
    """The paper's high-slope wave along x plus the same wave along y, random phases."""
    phase = np.random.default_rng(seed).uniform(0, 2 * np.pi, 2)
    x = np.arange(n) * side / n
    q = 2 * np.pi / HS_WAVELENGTH
    return HS_AMPLITUDE * (np.sin(q * x[None, :] + phase[0]) + np.sin(q * x[:, None] + phase[1]))


def surface(kind: str, ratio: int, m2_ls: float, seed: int, points: int) -> HeightMap:
    """The two-band map of one case (module docstring)."""
    side = 2 * ratio * HS_WAVELENGTH
    n = int(round(points * side / HS_WAVELENGTH))
    high = (crate_heights(side, n, seed) if kind == "crate"
            else band_heights(side, n, HS_WAVELENGTH, HS_SLOPE, seed))
    low = band_heights(side, n, ratio * HS_WAVELENGTH, m2_ls, 1000 + seed)
    return HeightMap(high + low, (side, side), periodic=True,
                     source={"kind": kind, "ratio": ratio, "m2_ls": m2_ls, "seed": seed})


def run_case(kind: str, periods: int, ratio: int, m2_ls: float, seed: int, points: int,
             material) -> list[dict]:
    """VHS, hybrid (pointwise and windowed) and mean-field at every load of one map."""
    hm = surface(kind, ratio, m2_ls, seed, points)
    split = split_map(hm, 1.0, cell_points=points * periods, cell_periods=periods)
    t0 = time.perf_counter()
    law = linear_law_map(split.cell, material, VELOCITY)
    t_law = time.perf_counter() - t0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")           # the crate's anisotropy is by design
        psd = map_psd(hm)
    rows = []
    for p in PRESSURES:
        t0 = time.perf_counter()
        vhs = solve_map(hm, material, VELOCITY, p)
        t_vhs = time.perf_counter() - t0
        point = solve_map_hybrid(split, law, material, VELOCITY, p,
                                 MapHybridOptions(window=False))
        win = solve_map_hybrid(split, law, material, VELOCITY, p)
        mf = meanfield.solve(psd, material, VELOCITY, p)
        rows.append({"kind": kind, "cell_periods": periods, "ratio": ratio, "m2_ls": m2_ls,
                     "seed": seed, "points": points, "n": hm.shape[0], "pressure": p,
                     "vhs_mu": vhs.friction, "vhs_area": vhs.contact_fraction,
                     "hybrid_mu": point.friction, "hybrid_area": point.contact_fraction,
                     "windowed_mu": win.friction, "windowed_area": win.contact_fraction,
                     "meanfield_mu": mf.friction, "meanfield_area": mf.contact_fraction,
                     "t_vhs": t_vhs, "t_hybrid": win.elapsed, "t_law": t_law})
    return rows


def cases() -> list[tuple]:
    main = [(k, c, r, m, s, POINTS) for k, c in KINDS for r in RATIOS for m in M2_LS
            for s in SEEDS]
    check = [(k, c, r, 0.94, SEEDS[0], CHECK_POINTS) for k, c in KINDS[:2] for r in (2, 4)]
    return main + check


def run(rows_path: Path) -> list[dict]:
    """Every case not yet in ``rows_path`` (resumable), then all rows."""
    done = {tuple(r[k] for k in ("kind", "cell_periods", "ratio", "m2_ls", "seed", "points"))
            for r in read_rows(rows_path)}
    material = sbr()
    for case in cases():
        if case in done:
            continue
        for row in run_case(*case, material):
            append_row(rows_path, row)
    return read_rows(rows_path)


# -- report -------------------------------------------------------------------------------
def _err(a: float, b: float) -> str:
    return f"{100 * (a / b - 1):+.0f} %"


def _mean(rows: list[dict], key: str) -> float:
    return float(np.mean([r[key] for r in rows]))


def table(rows: list[dict], kind: str, periods: int) -> tuple[str, dict]:
    """The case table of one high-slope kind (means over seeds) and mean |errors| per ratio."""
    lines = ["| λ_ls/λ_hs | m2_ls | σ0 [MPa] | VHS μ (A) | hybrid μ (A) | error | windowed "
             "μ (A) | error | mean-field μ (A) | error |", "|" + "---|" * 10]
    errors: dict = {}
    for ratio in RATIOS:
        for m2 in M2_LS:
            for p in PRESSURES:
                sel = [r for r in rows if r["kind"] == kind and r["cell_periods"] == periods
                       and r["points"] == POINTS and r["ratio"] == ratio and r["m2_ls"] == m2
                       and r["pressure"] == p]
                if not sel:
                    continue
                v = {k: _mean(sel, k) for k in sel[0] if k.endswith(("_mu", "_area"))}
                cells = [f"{v[m + '_mu']:.3f} ({v[m + '_area']:.3f})"
                         for m in ("vhs", "hybrid", "windowed", "meanfield")]
                lines.append(f"| {ratio} | {m2:g} | {p:g} | {cells[0]} | {cells[1]} | "
                             f"{_err(v['hybrid_mu'], v['vhs_mu'])} | {cells[2]} | "
                             f"{_err(v['windowed_mu'], v['vhs_mu'])} | {cells[3]} | "
                             f"{_err(v['meanfield_mu'], v['vhs_mu'])} |")
                for m in ("hybrid", "windowed", "meanfield"):
                    errors.setdefault((ratio, m), []).append(
                        abs(v[m + "_mu"] / v["vhs_mu"] - 1))
    return "\n".join(lines), errors


def summary(all_errors: dict) -> str:
    lines = ["| λ_ls/λ_hs | " + " | ".join(f"{k} cell {c}: hybrid / windowed" for k, c in KINDS)
             + " |", "|" + "---|" * (1 + len(KINDS))]
    for ratio in RATIOS:
        cells = []
        for key in KINDS:
            e = all_errors.get(key, {})
            cells.append(" / ".join(f"{100 * np.mean(e[(ratio, m)]):.0f} %"
                                    f" ({100 * np.max(e[(ratio, m)]):.0f} %)"
                                    if (ratio, m) in e else "–"
                                    for m in ("hybrid", "windowed")))
        lines.append(f"| {ratio} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def resolution(rows: list[dict]) -> str:
    lines = ["| high-slope band | λ_ls/λ_hs | σ0 [MPa] | points/λ_hs | VHS μ (A) | hybrid "
             "error | windowed error |", "|" + "---|" * 7]
    for kind, periods in KINDS[:2]:
        for ratio in (2, 4):
            for p in PRESSURES:
                for pts in (POINTS, CHECK_POINTS):
                    sel = [r for r in rows if r["kind"] == kind and r["cell_periods"] == periods
                           and r["ratio"] == ratio and r["m2_ls"] == 0.94 and r["pressure"] == p
                           and r["seed"] == SEEDS[0] and r["points"] == pts]
                    if not sel:
                        continue
                    r = sel[0]
                    lines.append(f"| {kind} | {ratio} | {p:g} | {pts} | {r['vhs_mu']:.3f} "
                                 f"({r['vhs_area']:.3f}) | {_err(r['hybrid_mu'], r['vhs_mu'])} "
                                 f"| {_err(r['windowed_mu'], r['vhs_mu'])} |")
    return "\n".join(lines)


def findings(rows: list[dict], all_errors: dict) -> dict:
    """The numbers the findings quote, from the rows."""
    def pct(x: float) -> str:
        return f"{100 * x:.0f} %"

    crate = all_errors.get(("crate", 1), {})
    out = {f"crate_{m}": ", ".join(pct(np.mean(crate[(r, m)])) if (r, m) in crate else "–"
                                   for r in RATIOS) for m in ("hybrid", "windowed")}
    cells = []
    for kind, periods in KINDS[1:]:
        e = all_errors.get((kind, periods), {})
        vals = [x for r in RATIOS for x in e.get((r, "hybrid"), [])]
        cells.append(pct(np.mean(vals)) if vals else "–")
    out["band_cells"] = ", ".join(cells)
    main = [r for r in rows if r["points"] == POINTS]
    for name in ("mu", "area"):
        change = np.mean([r[f"meanfield_{name}"] / r[f"vhs_{name}"] - 1 for r in main])
        out[f"mf_{name}"] = f"{100 * change:+.0f} %"
    moves = []
    for r32 in (r for r in rows if r["points"] == CHECK_POINTS):
        key = ("kind", "cell_periods", "ratio", "m2_ls", "seed", "pressure")
        r16 = [r for r in rows if r["points"] == POINTS and all(r[k] == r32[k] for k in key)]
        for m in ("hybrid", "windowed"):
            if r16:
                moves.append(abs(r32[m + "_mu"] / r32["vhs_mu"] - r16[0][m + "_mu"]
                                 / r16[0]["vhs_mu"]))
    out["resolution"] = f"{100 * max(moves):.1f}" if moves else "–"
    return out


def cost(rows: list[dict]) -> str:
    parts = []
    for n in sorted({r["n"] for r in rows}):
        sel = [r for r in rows if r["n"] == n]
        parts.append(f"{n}²: VHS {np.median([r['t_vhs'] for r in sel]):.2g} s, hybrid "
                     f"{np.median([r['t_hybrid'] for r in sel]):.2g} s")
    laws = {(r["points"] * r["cell_periods"]): r["t_law"] for r in rows}
    parts.append("law of a cell: " + ", ".join(f"{k}² {v:.2g} s" for k, v in sorted(laws.items())))
    return "; ".join(parts)


def report(rows: list[dict]) -> str:
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    out = [render("maps_split", "title"),
           render("maps_split", "intro", date=datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC"),
                  commit=commit, seeds=len(SEEDS), points=POINTS, check=CHECK_POINTS)]
    all_errors = {}
    for kind, periods in KINDS:
        text, errors = table(rows, kind, periods)
        all_errors[(kind, periods)] = errors
        block = {"crate": "table_crate", "band": "table_band"}[kind]
        out += [render("maps_split", block, periods=periods), text]
    out += [render("maps_split", "summary"), summary(all_errors),
            render("maps_split", "findings", **findings(rows, all_errors)),
            render("maps_split", "resolution"), resolution(rows),
            render("maps_split", "cost", cost=cost(rows))]
    return "\n\n".join(out) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m studies maps_split", description=DESCRIPTION)
    ap.add_argument("--report", type=Path, default=None, help="write the Markdown report here")
    ap.add_argument("--rows", type=Path, default=ROWS, help="resumable rows (JSON lines)")
    args = ap.parse_args(argv)
    return publish(report(run(args.rows)), args.report)
