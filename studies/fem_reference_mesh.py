"""Is the section 3 full-FEM reference resolved at the smallest contact areas?

The paper's FEM has 120 x 90 elements on the 0.25 mm cell (2.1 um columns). At 50 mm/s and
0.15 MPa the contact fraction is 0.011-0.019, i.e. 2.7-4.7 um of contact in the whole cell:
a patch spans one or two columns. This study runs the validation's own full-FEM tasks (the
quick level's config and cache keys, with ``full_mesh``/``full_grading`` set) at 120 x 90
and at a finer or differently graded mesh, compares them realization by realization, and
computes eq. 28 with either as the reference. The quick level of ``studies/validate.py``
uses 240 x 90 graded x4 (1.04 um columns, the law cell's), which this study showed
converged.

Everything goes through the validation cache, so a killed run resumes and ``make
validate`` reuses these solves. Run single-threaded, e.g.::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies fem_reference_mesh --workers 2 \\
        --law-pressures 0.05 0.1 0.2 0.5 1 2 4 6 \\
        --law-velocity 10 50 --law-coarse-mesh 60x45 120x45:g4 \\
        --report docs/validation/fem_reference_mesh.md

and a cheaper candidate reference on a few realizations (no eq. 28 then)::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies fem_reference_mesh --workers 2 \\
        50:0.15 50:0.8 10:0.8 --mesh 240x45:g8 --against 240x90 --realizations 0 4 \\
        --report docs/validation/fem_reference_graded.md

The law part compares law cells (the high-slope wave alone) on coarser or graded meshes
with the paper's 120 x 90.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np
import xarray as xr

import rubbercontact as rc
from rubbercontact.hybrid.law import effective_law
from rubbercontact.inputs import build_material
from rubbercontact.pipeline import make_runner
from rubbercontact.pipeline.plan import full_fem_task
from rubbercontact.pipeline.setup import translated_to_zero_phase

from . import _compare as compare
from . import _validation_report as vreport
from . import validate
from ._rows import publish

DESCRIPTION = "Is the section 3 full-FEM reference resolved at the smallest contact areas?"

ROOT = Path(__file__).resolve().parents[1]
# (velocity [mm/s], pressure [MPa]) in the order they are run: smallest areas first
DEFAULT_LOADS = ["50:0.15", "50:0.35", "10:0.15", "50:0.8", "10:0.35", "10:0.8"]


def _full_config(mesh: tuple[int, int], grading: float, workers: int, cache: Path):
    """The quick validation's section 3 config with the full FEM on ``mesh``/``grading``."""
    quick = validate.case_config("section3", "quick", workers, cache, Path("/tmp"))
    data = quick.model_dump(mode="json", exclude_none=True)
    data["fem"]["full_mesh"] = list(mesh)
    data["fem"]["full_grading"] = grading
    return rc.config.parse_config(data, source=f"section3 (quick, full mesh {mesh}, "
                                                f"grading {grading:g})")


def _solve(cfg, loads, progress="log", realizations=None) -> dict:
    """``{(v, p): [(μ, A, compute time [s]) per realization]}`` of the config's full FEM
    (cached; the time is that of the original solve); all realizations unless a subset of
    indices is given."""
    mat = build_material(cfg.material)
    reals = rc.roughness.section3().realizations(cfg.realizations, seed=cfg.seed)
    chosen = range(len(reals)) if realizations is None else realizations
    tasks, index = [], []
    for v, p in loads:
        for ir in chosen:
            real = reals[ir]
            tasks.append(full_fem_task(cfg, real, mat, v, p))
            index.append((v, p, ir))
    results = make_runner(cfg, progress=progress)(tasks)
    out: dict = {}
    for (v, p, _ir), res in zip(index, results, strict=True):
        ok = isinstance(res, xr.Dataset)     # a failure (TaskFailure) counts as missing
        out.setdefault((v, p), []).append(
            (float(res["friction"]), float(res["contact_fraction"]), float(res["wall_time"]))
            if ok else (np.nan, np.nan, np.nan))
    return out


def _law_points(cfg, mesh, pressures, velocity, grading: float = 1.0,
                periods: int = 3) -> xr.Dataset:
    """The config's law FEM (high-slope wave alone) at ``pressures`` on ``mesh`` (cached)."""
    reals = rc.roughness.section3().realizations(cfg.realizations, seed=cfg.seed)
    hs0 = translated_to_zero_phase(reals[0].partition(cfg.surface.m2_threshold)[0])
    return effective_law(hs0, build_material(cfg.material), pressures, [velocity], mesh=mesh,
                         height_ratio=cfg.fem.height_ratio, periods=periods,
                         steps_per_period=cfg.fem.steps_per_period,
                         contact_points=cfg.fem.contact_points,
                         history_order=cfg.fem.history_order, grading=grading,
                         runner=make_runner(cfg, progress="log"))


def law_report(cfg, coarse_mesh, fine_mesh, pressures, velocity,
               coarse_grading=1.0, periods: int = 3, fine_grading: float = 1.0) -> str:
    coarse = _law_points(cfg, coarse_mesh, pressures, velocity, coarse_grading, periods)
    fine = _law_points(cfg, fine_mesh, pressures, velocity, fine_grading, periods)
    name = _mesh_name(coarse_mesh, coarse_grading)
    fine_name = _mesh_name(fine_mesh, fine_grading)
    lines = ["", f"## The law cell (high-slope wave alone, {velocity:g} mm/s): {name}", "",
             f"Law mesh {name} against {fine_name}"
             + (" (the paper's mesh)" if fine_name == "120x90" else "") + ", "
             f"both with {cfg.fem.steps_per_period} steps per period (the same dt) and "
             f"{periods} periods; compute "
             "time per solve in brackets (as run, with other jobs sharing the two cores, so "
             "indicative):", "",
             f"| p̄ [MPa] | {name} μ (A) [s] | {fine_name} μ (A) [s] | μ ratio | A ratio |",
             "|---|---|---|---|---|"]
    for p in pressures:
        c, f = coarse.sel(pressure=p, velocity=velocity), fine.sel(pressure=p, velocity=velocity)
        lines.append(f"| {p:g} | {float(c['friction']):.3f} ({float(c['contact_fraction']):.4f})"
                     f" [{float(c['wall_time']):.0f}] | {float(f['friction']):.3f} "
                     f"({float(f['contact_fraction']):.4f}) [{float(f['wall_time']):.0f}] | "
                     f"{float(f['friction']) / float(c['friction']):.3f} | "
                     f"{float(f['contact_fraction']) / float(c['contact_fraction']):.3f} |")
    return "\n".join(lines) + "\n"


def _with_reference(ds: xr.Dataset, fine: dict) -> xr.Dataset:
    """The validation dataset with the FEM replaced by ``fine`` at its loads."""
    ds = ds.copy(deep=True)
    for (v, p), vals in fine.items():
        mu, a, _ = np.array(vals).T
        sel = {"model": "fem", "velocity": v, "pressure": p}
        ds["friction"].loc[sel] = mu
        ds["contact_fraction"].loc[sel] = a
    return compare.with_realization_means(ds)


def report(ds: xr.Dataset, coarse: dict, fine: dict, name: str, base: str,
           realizations=None) -> str:
    """The study's Markdown: ``coarse`` (mesh ``base``) against ``fine`` (``name``) per
    realization, and, when every realization ran, eq. 28 with either as the reference."""
    reals = list(range(ds.sizes["realization"]) if realizations is None else realizations)
    lines = [f"# Section 3 full-FEM reference: {base} against {name}", "",
             "Generated by `studies/fem_reference_mesh.py`: the validation's quick-level "
             f"full-FEM tasks (realizations {', '.join(map(str, reals))}, 240 steps per "
             f"period, 3 periods) at {base} and at {name}, at the loads below; everything "
             "else (hybrids, VHS and the FEM at other loads) from "
             "`docs/validation/section3/results.nc`. The paper's element count is "
             "120 x 90.", "",
             f"| v [mm/s] | σ0 [MPa] | r | FEM {base} μ (A) | FEM {name} μ (A) | ratio | "
             "VHS μ (A) | windowed μ (A) |", "|---|---|---|---|---|---|---|---|"]
    for (v, p), vals in fine.items():
        s = ds.sel(velocity=v, pressure=p)
        for ir, (mu_f, a_f, _), (mu_c, a_c, _) in zip(reals, vals, coarse[(v, p)],
                                                       strict=True):
            vhs = s.sel(model="vhs", realization=ir)
            win = s.sel(model="hybrid-windowed", realization=ir)
            lines.append(
                f"| {v:g} | {p:g} | {ir} | {mu_c:.3f} ({a_c:.4f}) | {mu_f:.3f} ({a_f:.4f}) | "
                f"{mu_f / mu_c:.3f} | {float(vhs['friction']):.3f} "
                f"({float(vhs['contact_fraction']):.4f}) | {float(win['friction']):.3f} "
                f"({float(win['contact_fraction']):.4f}) |")
        if len(reals) < ds.sizes["realization"]:
            continue
        mf, mc = np.nanmean([x[0] for x in vals]), np.nanmean([x[0] for x in coarse[(v, p)]])
        af, ac = np.nanmean([x[1] for x in vals]), np.nanmean([x[1] for x in coarse[(v, p)]])
        lines.append(f"| {v:g} | {p:g} | mean | {mc:.3f} ({ac:.4f}) | {mf:.3f} ({af:.4f}) | "
                     f"{mf / mc:.3f} | {float(s['friction_mean'].sel(model='vhs')):.3f} "
                     f"({float(s['contact_fraction_mean'].sel(model='vhs')):.4f}) | "
                     f"{float(s['friction_mean'].sel(model='hybrid-windowed')):.3f} "
                     f"({float(s['contact_fraction_mean'].sel(model='hybrid-windowed')):.4f}) |")
    t_fine = {k: np.nansum([x[2] for x in vals]) for k, vals in fine.items()}
    t_coarse = {k: np.nansum([x[2] for x in coarse[k]]) for k in fine}
    lines += ["", "Compute time of these full-FEM solves (sum over the realizations, one core "
              "each, as run; two workers on two cores): " + "; ".join(
                  f"{v:g} mm/s, {p:g} MPa: {t_coarse[(v, p)]:.0f} s at {base}, "
                  f"{t_fine[(v, p)]:.0f} s at {name}" for (v, p) in fine)
              + f". Together {sum(t_fine.values()) / sum(t_coarse.values()):.2f}x."]
    if len(reals) < ds.sizes["realization"]:
        return "\n".join(lines) + "\n"
    paper, refined = _with_reference(ds, coarse), _with_reference(ds, fine)
    before, after = compare.eq28_at_equal_area(paper), compare.eq28_at_equal_area(refined)
    ci = compare.eq28_intervals(refined)
    lines += ["", "Eq. 28 at equal contact area (areas log-spaced over the range every "
              f"model's sweep covers, as in VALIDATION.md), with the {base} reference and "
              f"with the {name} reference at the loads above (the FEM at any other load from "
              "the results file):", "",
              "| v [mm/s] | reference | areas | pointwise hybrid | windowed hybrid | VHS |",
              "|---|---|---|---|---|---|"]
    for label, errs in ((base, before), (name, after)):
        for v, (areas, e) in errs.items():
            lines.append(f"| {v:g} | {label} | {areas.min():.3f}-{areas.max():.3f} | "
                         f"{100 * e['hybrid']:.1f} % | {100 * e['hybrid-windowed']:.1f} % | "
                         f"{100 * e['vhs']:.1f} % |")
    lines += ["", f"With the {name} reference, the 90 % interval of a "
              "paired bootstrap over the 5 realizations (2000 resamples; the sampling "
              "uncertainty of comparing realization means): " + "; ".join(
                  f"{v:g} mm/s " + ", ".join(
                      f"{m} {vreport.interval_text(*interval)} %"
                      for m, interval in c.items())
                  for v, c in ci.items()) + "."]
    lines += ["", "Sensitivity to the FEM's contact area (eq. 28 compares at equal area, and "
              "the FEM area at the smallest loads moves by several per cent between meshes; "
              "docs/validation/contact_area_resolution.md): the same errors with every FEM "
              "contact fraction multiplied by a factor, friction unchanged:", "",
              "| FEM area factor | " + " | ".join(
                  f"{v:g} mm/s windowed | {v:g} mm/s VHS" for v in after) + " |",
              "|---|" + "---|---|" * len(after)]
    for factor, errs in compare.area_sensitivity(refined).items():
        lines.append(f"| {factor:g} | " + " | ".join(
            f"{100 * errs[v]['hybrid-windowed']:.1f} % | {100 * errs[v]['vhs']:.1f} %"
            if v in errs else " | " for v in after) + " |")
    return "\n".join(lines) + "\n"


def _mesh(spec: str, grading: float = 1.0) -> tuple[tuple[int, int], float]:
    """``"NXxNY[:gG]"`` -> ``((NX, NY), G)``; ``grading`` when no ``:g`` is given."""
    mesh, _, g = spec.lower().partition(":g")
    nx, ny = (int(x) for x in mesh.split("x"))
    return (nx, ny), float(g) if g else grading


def _mesh_name(mesh: tuple[int, int], grading: float) -> str:
    return f"{mesh[0]}x{mesh[1]}" + (f" graded x{grading:g}" if grading != 1.0 else "")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("loads", nargs="*", default=DEFAULT_LOADS, help="V:P pairs")
    ap.add_argument("--mesh", default="240x90",
                    help="full mesh studied, NXxNY[:gG] (rows graded x4 unless G is given)")
    ap.add_argument("--against", default="120x90",
                    help="full mesh it is compared with (default: the paper's element count)")
    ap.add_argument("--realizations", type=int, nargs="*",
                    help="only these realizations (no eq. 28 then)")
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--cache", type=Path, default=ROOT / ".validation-cache")
    ap.add_argument("--results", type=Path,
                    default=ROOT / "docs" / "validation" / "section3" / "results.nc")
    ap.add_argument("--report", type=Path)
    ap.add_argument("--law-pressures", type=float, nargs="*", default=[],
                    help="also compare the law cell at these pressures [MPa]")
    ap.add_argument("--law-velocity", type=float, nargs="*", default=[50.0])
    ap.add_argument("--law-mesh", default="120x90",
                    help="law mesh the others are compared with, NXxNY[:gG]")
    ap.add_argument("--law-coarse-mesh", nargs="*", default=["60x45"],
                    help="meshes compared with --law-mesh, NXxNY[:gG] (G: row grading)")
    ap.add_argument("--law-periods", type=int, default=3,
                    help="sliding periods of the law cells compared (3: as first run)")
    ap.add_argument("--skip-full", action="store_true", help="only the law cell part")
    args = ap.parse_args(argv)
    mesh, grading = _mesh(args.mesh, 4.0)
    loads = [tuple(float(x) for x in s.split(":")) for s in args.loads]
    base_mesh, base_grading = _mesh(args.against, 4.0)
    coarse_cfg = _full_config(base_mesh, base_grading, args.workers, args.cache)
    fine_cfg = _full_config(mesh, grading, args.workers, args.cache)
    text = ""
    if not args.skip_full:
        fine = _solve(fine_cfg, loads, realizations=args.realizations)
        coarse = _solve(coarse_cfg, loads, realizations=args.realizations)
        text = report(xr.load_dataset(args.results), coarse, fine, _mesh_name(mesh, grading),
                      _mesh_name(base_mesh, base_grading), args.realizations)
    if args.law_pressures:
        fine_law_mesh, fine_law_grading = _mesh(args.law_mesh)
        if args.skip_full:
            text = ("# Law cell meshes\n\nGenerated by `python -m studies fem_reference_mesh "
                    + " ".join(argv if argv is not None else sys.argv[1:]) + "`: the quick "
                    "validation's law cell (section 3 high-slope wave) on other meshes.\n")
        for spec in args.law_coarse_mesh:
            law_mesh, law_grading = _mesh(spec)
            for velocity in args.law_velocity:
                text += law_report(coarse_cfg, law_mesh, fine_law_mesh, args.law_pressures,
                                   velocity, law_grading, args.law_periods, fine_law_grading)
    return publish(text, args.report)


if __name__ == "__main__":
    raise SystemExit(main())
