"""How many realizations does the section 3 comparison need at one velocity?

The quick validation compares realization means of 5 random-phase realizations, and the
FEM friction varies between realizations by up to 25 % at one load, so the eq. 28 error at
50 mm/s carries a wide sampling interval. This study reruns the quick level's section 3
case at the chosen velocities with more realizations (the first 5 are the validation's:
the phases are drawn in sequence from the same seed) and the full FEM on a cheaper mesh
that docs/validation/fem_reference_graded.md found equivalent to the validation's
240 x 90 (240 x 45 rows graded x8: friction within 0.6 %, area within 2.8 %). It reports
eq. 28 at equal area with its bootstrap interval for the first 5 and for all realizations,
and its full FEM against another run's (``--reference``, default the validation's)
test by test.

``--min-creep-times K`` slides every FEM test, the law's and the full cell's, K longest
retardation times of the material instead of the validation's fixed 0.75 mm: at 50 mm/s
those tests end inside the bulk creep transient (docs/validation/fem_steadiness.md). With
``--reference`` set to the fixed-distance run it measures what settling changes, in the
full FEM and in the windowed hybrid. ``--law-min-creep-times K`` does so for the law's points
alone (at 10 mm/s the full FEM's three 25 ms periods already slide 4.6 retardation times,
while the period rule stops the law after three of its 6.25 ms periods): the law is built
first on its own and the run reads it as ``law.file``.

Everything goes through the validation cache (the law is the validation's unless the
sliding changes), seeded from the tracked FEM results of ``validate.py``, so a killed run
resumes. Run single-threaded, e.g.::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies sampling_study --workers 2 \\
        --velocities 50 --realizations 10 --report docs/validation/sampling_study.md
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
import xarray as xr

import rubbercontact as rc
from rubbercontact.hybrid.law import law_from_results
from rubbercontact.io.results import write_law

from . import _compare as compare
from . import _section3_report as s3report
from . import _validation_report as vreport
from . import validate
from ._rows import publish
from .fem_reference_mesh import _mesh, _mesh_name

DESCRIPTION = "How many realizations does the section 3 comparison need at one velocity?"

ROOT = Path(__file__).resolve().parents[1]
MODELS = ("hybrid-windowed", "vhs", "hybrid")


def study_config(velocities, realizations: int, mesh, grading: float, workers: int,
                 cache: Path, outdir: Path, min_creep_times: float | None = None,
                 law_file: Path | None = None):
    """The quick validation's section 3 config at ``velocities`` with ``realizations``
    realizations and the full FEM on ``mesh`` / ``grading``; with ``min_creep_times``
    every FEM test (law and full) slides that many longest retardation times; with
    ``law_file`` the hybrids read that law instead of building one."""
    quick = validate.case_config("section3", "quick", workers, cache, outdir, realizations)
    data = quick.model_dump(mode="json", exclude_none=True)
    data["velocities"] = [float(v) for v in velocities]
    data["fem"]["full_mesh"] = list(mesh)
    data["fem"]["full_grading"] = grading
    data["output"]["directory"] = str(outdir)
    if min_creep_times is not None:
        data["fem"]["min_creep_times"] = float(min_creep_times)
    if law_file is not None:
        data["law"] = {"file": str(law_file)}
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


def _against_reference(ds: xr.Dataset, ref: xr.Dataset, name: str, base: str,
                       model: str = "fem") -> list[str]:
    """The study's ``model`` against the reference run's on the realizations both ran."""
    n = min(ds.sizes["realization"], ref.sizes["realization"])
    lines = [f"| v [mm/s] | σ0 [MPa] | r | {model} {base} μ (A) | {model} {name} μ (A) | "
             "μ ratio | A ratio |", "|---|---|---|---|---|---|---|"]
    ratios_mu, ratios_a = [], []
    for v in ds["velocity"].values:
        for p in ds["pressure"].values:
            for ir in range(n):
                sel = {"velocity": v, "pressure": p, "model": model, "realization": ir}
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


def _same_tests(ds: xr.Dataset, ref: xr.Dataset, model: str) -> bool:
    """Whether ``model`` gave identical numbers in both runs on the realizations both ran."""
    n = min(ds.sizes["realization"], ref.sizes["realization"])
    sel = {"model": model, "realization": slice(0, n), "velocity": ds["velocity"].values}
    return all(np.array_equal(ds[k].sel(sel).values, ref[k].sel(sel).values)
               for k in ("friction", "contact_fraction"))


def _law_against_reference(ds: xr.Dataset, ref: xr.Dataset) -> list[str]:
    """The law points of this run against the reference's (same velocities and pressures)."""
    lines = ["| v [mm/s] | p̄ [MPa] | μ reference → this run | α reference → this run | "
             "ū [um] reference → this run | status (this run) |", "|---|---|---|---|---|---|"]
    for v in ds["velocity"].values:
        for p in ds["law_pressure"].values:
            sel = {"velocity": v, "law_pressure": p}
            a, b = ref.sel(sel), ds.sel(sel)
            mu = (float(a["law_friction"]), float(b["law_friction"]))
            al = (float(a["law_contact_fraction"]), float(b["law_contact_fraction"]))
            u = (1e3 * float(a["law_mean_separation"]), 1e3 * float(b["law_mean_separation"]))
            lines.append(f"| {v:g} | {p:g} | {mu[0]:.3f} → {mu[1]:.3f} "
                         f"({100 * (mu[1] / mu[0] - 1):+.1f} %) | {al[0]:.4f} → {al[1]:.4f} "
                         f"({100 * (al[1] / al[0] - 1):+.1f} %) | {u[0]:.2f} → {u[1]:.2f} | "
                         f"{str(b['law_status'].values)} |")
    return lines


def law_sliding(ds: xr.Dataset) -> float:
    """The law's minimum sliding time [s] (0: the period rule alone), from its provenance."""
    attrs = json.loads(ds.attrs.get("law_attrs", "{}"))
    return float(json.loads(attrs.get("fem_options", "{}")).get("min_sliding_time", 0.0))


def run_name(ds: xr.Dataset) -> str:
    """Full-FEM mesh and sliding of a run (and the law's when it slid longer)."""
    fem = json.loads(ds.attrs["config"])["fem"]
    name = _mesh_name(tuple(fem.get("full_mesh") or fem["mesh"]), fem.get("full_grading", 1.0))
    k = fem.get("min_creep_times")
    name += (f", at least {k:g} retardation times of sliding" if k else
             f", {fem.get('full_periods') or fem['periods']} periods at most")
    law_time = law_sliding(ds)
    if law_time and not k:
        name += f"; the law slid at least {1e3 * law_time:.1f} ms"
    return name


def report(ds: xr.Dataset, ref: xr.Dataset | None, warnings_seen: list[str]) -> str:
    n = ds.sizes["realization"]
    name = run_name(ds)
    creep = json.loads(ds.attrs["config"])["fem"].get("min_creep_times")
    plural = "s" if n > 1 else ""
    if creep:
        title = (f"# Section 3 with creep-settled sliding ({creep:g} retardation times, {n} "
                 f"realization{plural})")
    elif law_sliding(ds):
        title = (f"# Section 3 with a creep-settled law ({1e3 * law_sliding(ds):.1f} ms of "
                 f"sliding per law point, {n} realization{plural})")
    else:
        title = f"# Section 3 with {n} realization{plural}"
    lines = [title, "",
             "Generated by `studies/sampling_study.py`: the quick validation's section 3 "
             f"case (law, loads {', '.join(f'{p:g}' for p in ds['pressure'].values)} MPa, "
             "VHS, hybrids) at "
             f"{', '.join(f'{v:g}' for v in ds['velocity'].values)} mm/s with {n} "
             f"realization{'s' if n > 1 else ''}, and the full FEM on {name} (240 steps per "
             "period). The realizations are drawn in sequence from the validation's seed, so "
             "the first 5 are the validation's. Eq. 28 at equal area as in VALIDATION.md; in "
             "brackets the 90 % interval of a paired bootstrap over the realizations (2000 "
             "resamples).",
             "", "| v [mm/s] | realizations | areas | windowed hybrid | VHS | pointwise hybrid |",
             "|---|---|---|---|---|---|"]
    for k in sorted({min(5, n), n}):
        for v, (areas, e, ci) in compare.eq28_first(ds, k, MODELS).items():
            lines.append(f"| {v:g} | {k} | {areas.min():.3f}-{areas.max():.3f} | " + " | ".join(
                f"{100 * e[m]:.1f} %" + (f" ({vreport.interval_text(*ci[m])})"
                                         if m in ci else "") for m in MODELS) + " |")
    if n >= 2:
        lines += ["", "Spread between realizations (sample standard deviation; s.e. = "
                  "s.d./√n, the standard error of the realization mean):", ""]
        lines += _spread_lines(ds)
    lines += ["", s3report.per_realization_sentence(ds)]
    lines += ["", "Compute time of this case (each solve's own time, also for solves taken "
              "from the cache; two workers on two cores, so indicative):", ""]
    lines += vreport.cost_lines(ds)
    if ref is not None:
        base = run_name(ref)
        # the hybrid differs only when the law did (e.g. longer sliding)
        same_law = ref["law_friction"].equals(ds["law_friction"]) if "law_friction" in ref \
            and "law_friction" in ds else True
        if not same_law:
            lines += ["", f"## The law: this run ({name}) against the reference ({base})", ""]
            lines += _law_against_reference(ds, ref)
        for model in ("fem",) if same_law else ("fem", "hybrid-windowed"):
            if model == "fem" and not same_law and _same_tests(ds, ref, model):
                lines += ["", "The full FEM is the reference's, test for test (the law alone "
                          "changed)."]
                continue
            lines += ["", f"## {model}: this run ({name}) against the reference ({base})",
                      ""] + _against_reference(ds, ref, "this run", "reference", model)
        m = min(n, ref.sizes["realization"])
        sub = compare.with_realization_means(
            ref.isel(realization=slice(0, m)).sel(velocity=ds["velocity"].values))
        lines += ["", f"The reference's eq. 28 at equal area over its first {m} "
                  "realization(s): " + "; ".join(
                      f"{v:g} mm/s " + ", ".join(f"{mm} {100 * e[mm]:.1f} %" for mm in MODELS)
                      for v, (_a, e) in compare.eq28_at_equal_area(sub, MODELS).items())
                  + "."]
    unsteady = [w for w in warnings_seen if "steady" in w]
    if unsteady:
        lines += ["", "Warnings of the run about steadiness:", ""] + [f"- {w}" for w in unsteady]
    return "\n".join(lines) + "\n"


def creep_settled_law(args, mesh, grading) -> Path:
    """Build the law alone (no full FEM), every point sliding ``--law-min-creep-times``
    retardation times; return its ``law.nc`` in ``--outdir``."""
    cfg = study_config(args.velocities, 1, mesh, grading, args.workers, args.cache,
                       args.outdir / "law", args.law_min_creep_times)
    cfg = cfg.model_copy(update={"models": ["hybrid-windowed"]})
    ds = rc.pipeline.run(cfg, progress="log")
    return write_law(law_from_results(ds), args.outdir / "law.nc")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--velocities", type=float, nargs="+", default=[50.0])
    ap.add_argument("--realizations", type=int, default=10)
    ap.add_argument("--mesh", default="240x45:g8", help="full mesh, NXxNY[:gG]")
    ap.add_argument("--min-creep-times", type=float,
                    help="slide every FEM test this many longest retardation times "
                         "(fem.min_creep_times; default: the validation's sliding)")
    ap.add_argument("--law-min-creep-times", type=float,
                    help="slide the law's FEM points (only) this many longest retardation "
                         "times; the full FEM keeps the validation's sliding")
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--cache", type=Path, default=ROOT / ".validation-cache")
    ap.add_argument("--outdir", type=Path, default=ROOT / "results" / "sampling_study",
                    help="results.nc and figures go here")
    ap.add_argument("--reference", type=Path,
                    default=ROOT / "docs" / "validation" / "section3" / "results.nc",
                    help="results of another run (default: the validation's) to compare "
                         "with test by test")
    ap.add_argument("--report", type=Path)
    args = ap.parse_args(argv)
    validate.seed_cache(validate.REFERENCE_CACHE, args.cache)
    mesh, grading = _mesh(args.mesh, 4.0)
    law_file = None
    if args.law_min_creep_times is not None:
        law_file = creep_settled_law(args, mesh, grading)
    cfg = study_config(args.velocities, args.realizations, mesh, grading, args.workers,
                       args.cache, args.outdir, args.min_creep_times, law_file)
    ds, _wall, _figs, msgs = validate.run_case(args.outdir.name, cfg, args.outdir.parent)
    ref = xr.load_dataset(args.reference) if args.reference.exists() else None
    return publish(report(ds, ref, msgs), args.report)


if __name__ == "__main__":
    raise SystemExit(main())
