"""How many realizations does the section 3 comparison need at one velocity?

The quick validation compares realization means of 5 random-phase realizations, and the
FEM friction varies between realizations by up to 25 % at one load, so the eq. 28 error at
50 mm/s carries a wide sampling interval. This study reruns the quick level's section 3
case at the chosen velocities with more realizations (the first 5 are the validation's:
the phases are drawn in sequence from the same seed) and the full FEM on a cheaper mesh
that docs/validation/fem_reference_graded.md found equivalent to the validation's
240 x 90 (240 x 45 rows graded x8: friction within 0.6 %, area within 2.8 %). It reports
eq. 28 at equal area with its bootstrap interval for the first 5 and for all realizations,
and the cheaper mesh against the validation's 240 x 90 realization by realization.

Everything goes through the validation cache (the law is the validation's), so a killed
run resumes. Run single-threaded, e.g.::

    OMP_NUM_THREADS=1 .venv/bin/python benchmarks/sampling_study.py --workers 2 \\
        --velocities 50 --realizations 10 --report docs/validation/sampling_study.md
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np
import xarray as xr

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))

import validate  # noqa: E402
from _rows import publish  # noqa: E402
from fem_reference_mesh import _mesh, _mesh_name  # noqa: E402

import rubbercontact as rc  # noqa: E402

MODELS = ("hybrid-windowed", "vhs", "hybrid")


def study_config(velocities, realizations: int, mesh, grading: float, workers: int,
                 cache: Path, outdir: Path):
    """The quick validation's section 3 config at ``velocities`` with ``realizations``
    realizations and the full FEM on ``mesh`` / ``grading``."""
    quick = validate._config("section3", "quick", workers, cache, outdir, realizations)
    data = quick.model_dump(mode="json", exclude_none=True)
    data["velocities"] = [float(v) for v in velocities]
    data["fem"]["full_mesh"] = list(mesh)
    data["fem"]["full_grading"] = grading
    data["output"]["directory"] = str(outdir)
    return rc.config.parse_config(data, source=f"section3 (quick, {realizations} "
                                                f"realizations, full mesh {mesh}, grading "
                                                f"{grading:g})")




def _spread_lines(ds: xr.Dataset) -> list[str]:
    """Mean, standard deviation and standard error of the mean of μ and A per load."""
    n = ds.sizes["realization"]
    lines = ["| v [mm/s] | σ0 [MPa] | model | μ mean ± s.d. (s.e.) | A mean ± s.d. (s.e.) |",
             "|---|---|---|---|---|"]
    for v in ds["velocity"].values:
        for p in ds["pressure"].values:
            for m in ("fem", "hybrid-windowed", "vhs"):
                s = ds.sel(velocity=v, pressure=p, model=m)
                mu, a = s["friction"].values, s["contact_fraction"].values
                lines.append(
                    f"| {v:g} | {p:g} | {m} | {np.mean(mu):.3f} ± {np.std(mu, ddof=1):.3f} "
                    f"({np.std(mu, ddof=1) / np.sqrt(n):.3f}) | {np.mean(a):.4f} ± "
                    f"{np.std(a, ddof=1):.4f} ({np.std(a, ddof=1) / np.sqrt(n):.4f}) |")
    return lines


def _against_reference(ds: xr.Dataset, ref: xr.Dataset, name: str, base: str) -> list[str]:
    """The study's FEM against the validation's (``ref``) on the realizations both ran."""
    n = min(ds.sizes["realization"], ref.sizes["realization"])
    lines = [f"| v [mm/s] | σ0 [MPa] | r | FEM {base} μ (A) | FEM {name} μ (A) | μ ratio | "
             "A ratio |", "|---|---|---|---|---|---|---|"]
    ratios_mu, ratios_a = [], []
    for v in ds["velocity"].values:
        for p in ds["pressure"].values:
            for ir in range(n):
                sel = {"velocity": v, "pressure": p, "model": "fem", "realization": ir}
                a, b = ds.sel(sel), ref.sel(sel)
                mu_a, mu_b = float(a["friction"]), float(b["friction"])
                ca, cb = float(a["contact_fraction"]), float(b["contact_fraction"])
                ratios_mu.append(mu_a / mu_b)
                ratios_a.append(ca / cb)
                lines.append(f"| {v:g} | {p:g} | {ir} | {mu_b:.3f} ({cb:.4f}) | {mu_a:.3f} "
                             f"({ca:.4f}) | {mu_a / mu_b:.3f} | {ca / cb:.3f} |")
    lines += ["", f"Over these {len(ratios_mu)} tests the friction ratio {name} / {base} is "
              f"{min(ratios_mu):.3f}-{max(ratios_mu):.3f} (mean {np.mean(ratios_mu):.3f}) and "
              f"the area ratio {min(ratios_a):.3f}-{max(ratios_a):.3f} (mean "
              f"{np.mean(ratios_a):.3f})."]
    return lines


def report(ds: xr.Dataset, ref: xr.Dataset | None, name: str, base: str,
           warnings_seen: list[str]) -> str:
    n = ds.sizes["realization"]
    lines = [f"# Section 3 with {n} realizations", "",
             "Generated by `benchmarks/sampling_study.py`: the quick validation's section 3 "
             f"case (law, loads {', '.join(f'{p:g}' for p in ds['pressure'].values)} MPa, "
             "VHS, hybrids) at "
             f"{', '.join(f'{v:g}' for v in ds['velocity'].values)} mm/s with {n} "
             f"realizations, and the full FEM on {name} (240 steps per period, "
             f"{ds.attrs.get('full_periods', 3)} periods at most). The first 5 realizations "
             "are the validation's. Eq. 28 at equal area as in VALIDATION.md; in brackets "
             "the 90 % interval of a paired bootstrap over the realizations (2000 resamples).",
             "", "| v [mm/s] | realizations | areas | windowed hybrid | VHS | pointwise hybrid |",
             "|---|---|---|---|---|---|"]
    for k in sorted({5, n}):
        sub = validate.with_realization_means(ds.isel(realization=slice(0, k)))
        ci = validate._eq28_intervals(sub, models=MODELS)
        for v, (areas, e) in validate.eq28_at_equal_area(sub, MODELS).items():
            lines.append(f"| {v:g} | {k} | {areas.min():.3f}-{areas.max():.3f} | " + " | ".join(
                f"{100 * e[m]:.1f} % ({validate._interval_text(*ci[v][m])})" for m in MODELS)
                + " |")
    lines += ["", "Spread between realizations (sample standard deviation; s.e. = s.d./√n, "
              "the standard error of the realization mean):", ""] + _spread_lines(ds)
    lines += ["", validate._per_realization_sentence(ds)]
    lines += ["", "Compute time of this case (each solve's own time, also for solves taken "
              "from the cache; two workers on two cores, so indicative):", ""]
    lines += validate._cost_lines(ds)
    if ref is not None:
        lines += ["", f"## The study's full FEM ({name}) against the validation's ({base})",
                  ""] + _against_reference(ds, ref, name, base)
    unsteady = [w for w in warnings_seen if "steady" in w]
    if unsteady:
        lines += ["", "Warnings of the run about steadiness:", ""] + [f"- {w}" for w in unsteady]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--velocities", type=float, nargs="+", default=[50.0])
    ap.add_argument("--realizations", type=int, default=10)
    ap.add_argument("--mesh", default="240x45:g8", help="full mesh, NXxNY[:gG]")
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--cache", type=Path, default=ROOT / ".validation-cache")
    ap.add_argument("--outdir", type=Path, default=ROOT / "results" / "sampling_study",
                    help="results.nc and figures go here")
    ap.add_argument("--reference", type=Path,
                    default=ROOT / "docs" / "validation" / "section3" / "results.nc",
                    help="the validation's results, whose FEM the study's is compared with")
    ap.add_argument("--report", type=Path)
    args = ap.parse_args(argv)
    mesh, grading = _mesh(args.mesh, 4.0)
    cfg = study_config(args.velocities, args.realizations, mesh, grading, args.workers,
                       args.cache, args.outdir)
    ds, _wall, _figs, msgs = validate._run("sampling_study", cfg, args.outdir.parent)
    ref = xr.load_dataset(args.reference) if args.reference.exists() else None
    if ref is not None:
        fem = json.loads(ref.attrs["config"])["fem"]
        base = _mesh_name(tuple(fem.get("full_mesh") or fem["mesh"]),
                          fem.get("full_grading", 1.0))
    else:
        base = ""
    text = report(ds, ref, _mesh_name(mesh, grading), base, msgs)
    return publish(text, args.report)


if __name__ == "__main__":
    raise SystemExit(main())
