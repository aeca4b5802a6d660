"""``make validate``: reproduce the paper's results and write VALIDATION.md.

Cases (each a bundled example config, optionally reduced):

- ``section3``: the three-wave validation of paper §3 — eq. 28 error of the hybrid and
  the VHS against full FEM at 10 and 50 mm/s over contact areas 0.01 … 0.1, next to the
  paper's 2.9 % and 7.1 %, and the cost of each model;
- ``asphalt``: paper §4 on Table 2 — high-slope law, Fig. 7 and Fig. 9 analogues, and the
  paper's observation that the VHS over-weights the shortest wavelengths, in numbers;
- ``captif``: the real CAPTIF road profiles end to end (fit → partition → law → hybrid).

``--level paper`` runs the configs as bundled (paper resolution: hours of FEM);
``--level quick`` reduces realizations, meshes and load points so that the whole set runs
in about an hour on 2 cores. Every FEM test is the steady solver's (the default; a point it
cannot converge falls back to the time-stepped test, and the reports count those). Results
are cached (``--cache``), so a rerun or a killed run resumes.

The FEM solves behind the committed VALIDATION.md are kept, checksummed, in
``docs/validation/reference-cache`` (a few MB; its README lists what it holds): every run
first copies those the working cache lacks (``--reference-cache``), so a fresh clone
recomputes only the solves missing there. ``--export-reference`` copies the FEM solves a
run used into it; ``--prune-reference`` deletes those no case of the run used.
"""

from __future__ import annotations

import argparse
import platform
import subprocess
import sys
import time
import warnings
from datetime import UTC, datetime
from pathlib import Path

import rubbercontact as rc
from rubbercontact.config import load_config
from rubbercontact.io.results import write_results
from rubbercontact.pipeline import make_runner
from rubbercontact.plotting.figures import plot_all
from rubbercontact.sweep import ResultCache, equivalence

from ._compare import extended_phase_data, phase_average_data, short_wave_share
from ._headline import headline_table, write_headline
from ._section3_report import section3_report
from ._templates import render
from ._validation_report import (
    asphalt_report,
    captif_report,
    fem_solves,
    steady_vs_transient,
    what_changed,
)

DESCRIPTION = "Reproduce the paper's results and write VALIDATION.md (make validate)."

ROOT = Path(__file__).resolve().parents[1]
REFERENCE_CACHE = ROOT / "docs" / "validation" / "reference-cache"
#: Section 3 with the time-stepped FEM, frozen for comparison ('What changed').
TRANSIENT_SECTION3 = ROOT / "docs" / "validation" / "section3_transient.md"
#: The expensive tasks worth keeping: the law points and the full-FEM tests.
FEM_FUNCTIONS = ("fem_task",)

#: Section 3's law pressures [MPa] at the quick level (the asphalt case shares the cell and
#: reads the same points from the cache).
LAW_PRESSURES = [0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 4.0, 6.0, 8.0]

#: The quick level: each case reduced so that the set runs on 2 cores, its FEM cached. The
#: FEM is the steady solver (fem.solver = "steady", the default): no time steps, periods or
#: sliding distance to choose. Why these meshes, loads and realization counts (and what each
#: costs or changes) is said in VALIDATION.md's section 3 ("Reduced", "Why 240 columns",
#: "Steady sliding") from the studies in docs/validation/ (fem_convergence,
#: fem_reference_mesh, law_cell_graded, sampling_study, steady_time_step).
QUICK = {
    # 6 realizations (10 with the time-stepped FEM, docs/validation/section3_transient.md):
    # the steady full FEM costs 20-170 s a test on the shared 2-core machine, and 6 × 3
    # loads × 2 speeds plus the 25 extended-load tests fit in about an hour
    "section3": {"realizations": 6,
                 "loads": {"contact_areas": None, "pressures": [0.15, 0.35, 0.8]},
                 "fem": {"mesh": [120, 23], "grading": 8.0,
                         "full_mesh": [240, 45], "full_grading": 8.0},
                 # the law as VALIDATION.md's figures were rendered with (its FEM points
                 # are in the reference cache); the run's coverage line says how far the
                 # local pressures go beyond it
                 "law": {"pressures": LAW_PRESSURES, "extend": False}},
    # the same law cell and mesh as section 3: the law comes from its cache
    "asphalt": {"realizations": 3, "halfspace": {"n": 8192},
                "fem": {"mesh": [120, 23], "grading": 8.0},
                "law": {"pressures": LAW_PRESSURES[1:], "extend": False}},
    # the CAPTIF road as the example runs it (the law cell's automatic mesh, its crests
    # rounded to the profiles' sampling, the law extended to the local pressures and its
    # quasi-static check), on a coarser half-space grid
    "captif": {"realizations": 3, "halfspace": {"n": 8192}},
}
#: Realizations of the cheap models behind section 3's phase-averaged rows: the study's
#: 1000. With 100 the cheap models' own sampling moved the headline eq. 28 by more than its
#: other changes (docs/validation/headline_shift.md); 1000 costs about 20 min on 2 cores.
QUICK_PHASE_REALIZATIONS = 1000
#: Section 3's extended loads at the quick level ({velocity: {load: realizations}}): of
#: _compare.EXTENDED_LOADS only the top load at 50 mm/s, where the question is whether the
#: settled FEM reaches the paper's areas up to 0.1, on 3 realizations; the others are left
#: out for compute (the steady full FEM took 2-4 min a test on the shared 2-core machine).
QUICK_EXTENDED_LOADS = {50.0: {2.0: 3}}
EXAMPLES = {"section3": "section3.toml", "asphalt": "asphalt.toml", "captif": "captif_road.toml"}


def _merge(base: dict, over: dict) -> dict:
    out = dict(base)
    for k, v in over.items():
        out[k] = _merge(out.get(k, {}), v) if isinstance(v, dict) else v
    return out


def case_config(case: str, level: str, workers: int, cache: Path, outdir: Path,
                realizations: int | None = None):
    """The bundled example of ``case`` at ``level`` (quick: with :data:`QUICK`), run by
    ``workers`` into ``cache``, writing to ``outdir/case``."""
    cfg = load_config(ROOT / "examples" / EXAMPLES[case])
    data = cfg.model_dump(mode="json", exclude_none=True)
    if level == "quick":
        data = _merge(data, QUICK[case])
    if realizations is not None:
        data["realizations"] = realizations
    data = _merge(data, {"execution": {"workers": workers, "cache": str(cache)},
                         "output": {"directory": str(outdir / case), "overwrite": True}})
    return rc.config.parse_config(data, source=f"{case} ({level})")


def run_case(case, cfg, outdir: Path, used_keys: set[str] | None = None):
    """Run ``cfg``; with ``used_keys`` add the key of every task the run asked for."""
    runner = make_runner(cfg, progress="log")

    def recording_runner(tasks, description="sweep"):
        if used_keys is not None:
            used_keys.update(t.key() for t in tasks)
        return runner(tasks, description)

    t0 = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        # as `rubbercontact run`: Dask's local cluster leaves sockets to the garbage
        # collector, which is not a finding of the validation
        warnings.simplefilter("ignore", ResourceWarning)
        ds = rc.pipeline.run(cfg, runner=recording_runner)
    wall = time.perf_counter() - t0
    path = outdir / case / "results.nc"
    write_results(ds, path, overwrite=True)
    figs = plot_all(ds, outdir / case)
    # the models' validity notes (where a model left its validated class, e.g. a law
    # read beyond its FEM points) are results, not warnings: listed beside them
    notes = [line for k, v in sorted(ds.attrs.items()) if k.startswith("validity_")
             for line in str(v).splitlines() if line]
    msgs = sorted({str(w.message) for w in caught}) + notes
    return ds, wall, figs, msgs


def _assemble(header: list[str], outdir: Path, report: Path) -> None:
    """VALIDATION.md = header + 'What changed' + every case report (or a line saying it is
    missing) + the mean-field study's summary."""
    parts = [(outdir / c / "report.md").read_text() if (outdir / c / "report.md").exists()
             else render("validation", "missing_case", case=c) + "\n" for c in EXAMPLES]
    changed = []
    if TRANSIENT_SECTION3.exists() and (outdir / "section3" / "report.md").exists():
        changed = what_changed(TRANSIENT_SECTION3.read_text(), parts[list(EXAMPLES).index(
            "section3")])
    report.write_text("\n".join(header + changed) + "\n" + "\n".join(parts)
                      + meanfield_summary(outdir / "meanfield.md"))


def meanfield_summary(path: Path) -> str:
    """The mean-field study's headline section (its own report, ``python -m studies
    meanfield``, against the VHS BEM: the strips, ``meanfield-strips``), as a VALIDATION.md
    section; empty without it."""
    if not path.exists():
        return ""
    text = path.read_text()
    head = "## Validation of the strips (meanfield-strips)"
    if head not in text:
        return ""
    body = text.split(head, 1)[1].split("\n## ", 1)[0].strip()
    return ("\n## Mean-field strips (meanfield-strips) against the VHS BEM\n\n"
            "From the mean-field study (`python -m studies meanfield`, "
            "docs/validation/meanfield.md, which has the "
            "self-affine, 2D and meanfield-hybrid cases and the cost).\n\n" + body + "\n")


def _header(args, commit: str) -> list[str]:
    level = f"- level: `{args.level}`"
    if args.level == "quick":
        level += " " + render("validation", "header_reduced")
    return [*render("validation", "header").split("\n"), "",
            f"- date: {datetime.now(UTC).strftime('%Y-%m-%d %H:%M UTC')}",
            f"- commit: {commit}, rubbercontact {rc.__version__}",
            f"- machine: {platform.machine()}, {platform.processor() or 'cpu'}, "
            f"Python {platform.python_version()}, {args.workers} Dask worker(s)", level, ""]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--level", choices=["quick", "paper"], default="quick")
    ap.add_argument("--only", default="asphalt,captif,section3")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--cache", type=Path, default=ROOT / ".validation-cache")
    ap.add_argument("--output", type=Path, default=ROOT / "docs" / "validation")
    ap.add_argument("--report", type=Path, default=ROOT / "VALIDATION.md")
    ap.add_argument("--realizations", type=int, default=None,
                    help="override the number of random-phase realizations of every case")
    ap.add_argument("--reference-cache", type=Path, default=REFERENCE_CACHE,
                    help="tracked FEM results copied into --cache before the run")
    ap.add_argument("--phase-realizations", type=int, default=QUICK_PHASE_REALIZATIONS,
                    help="realizations of the VHS and the hybrids behind section 3's "
                         "phase-averaged eq. 28 (0: skip it)")
    ap.add_argument("--no-extended", dest="extended", action="store_false",
                    help="skip section 3's extra loads over the paper's area range")
    ap.add_argument("--export-reference", action="store_true",
                    help="copy the FEM solves this run used into --reference-cache")
    ap.add_argument("--prune-reference", action="store_true",
                    help="delete the FEM solves of --reference-cache that no case of this run "
                         "used (every case must run; other studies re-render from some: "
                         "see its README)")
    ap.add_argument("--accept-reference", metavar="WHY", default=None,
                    help="recompute the cheapest FEM solves of --reference-cache computed by "
                         "other code and, where they agree within --accept-rtol, record that "
                         "code as equivalent (with WHY) in its equivalence.json; then stop")
    ap.add_argument("--accept-rtol", type=float, default=1e-6,
                    help="relative tolerance of --accept-reference (the steady FEM's "
                         "stopping tolerance, not round-off)")
    ap.add_argument("--accept-samples", type=int, default=3)
    args = ap.parse_args(argv)
    if args.accept_reference is not None:
        return accept_reference(args.reference_cache, args.accept_reference,
                                args.accept_rtol, args.accept_samples)
    seed_cache(args.reference_cache, args.cache)
    used: set[str] = set()
    cases = [c.strip() for c in args.only.split(",") if c.strip()]
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True).stdout.strip() or "unknown"
    lines = _header(args, commit)
    for case in cases:
        cfg = case_config(case, args.level, args.workers, args.cache, args.output,
                          args.realizations)
        print(f"== {case}", flush=True)
        case_used: set[str] = set()
        ds, wall, figs, msgs = run_case(case, cfg, args.output, case_used)
        if case == "section3":
            phase = (phase_average_data(ds, cfg, args.phase_realizations)
                     if args.phase_realizations else {})
            extended = (extended_phase_data(cfg, phase, case_used, QUICK_EXTENDED_LOADS)
                        if phase and args.level == "quick" and args.extended else {})
            if phase and args.level == "quick":
                write_headline(headline_table(ds, phase, commit))
            part = section3_report(ds, wall, figs, msgs, args.level, phase, extended,
                                   fem_solves(args.cache, case_used),
                                   steady_vs_transient(args.cache, case_used,
                                                       args.reference_cache))
        elif case == "asphalt":
            part = asphalt_report(ds, wall, figs, msgs, args.level, short_wave_share(ds, cfg),
                                  fem_solves(args.cache, case_used))
        else:
            part = captif_report(ds, wall, figs, msgs, fem_solves(args.cache, case_used))
        used |= case_used
        # one report per case, so cases can be run (and rerun) separately
        when = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
        stamp = render("validation", "case_stamp", when=when, commit=commit)
        (args.output / case / "report.md").write_text("\n".join([*part, stamp, ""]))
        _assemble(lines, args.output, args.report)
    print(f"wrote {args.report}")
    if args.export_reference:
        report = ResultCache(args.cache).copy_to(ResultCache(args.reference_cache),
                                                 FEM_FUNCTIONS, keys=used)
        print(f"FEM solves into {args.reference_cache}: {report}")
    if args.prune_reference:
        if set(cases) != set(EXAMPLES):
            print("not pruning the reference cache: not every case ran")
        else:
            removed = prune_reference(args.reference_cache, used)
            print(f"removed {removed} FEM solve(s) no case of this run used from "
                  f"{args.reference_cache}")
    return 0


def prune_reference(reference: Path, keep: set[str]) -> int:
    """Delete the FEM solves of ``reference`` whose key is not in ``keep`` (the stale ones
    of an earlier validation: a run that uses none of them cannot re-render from them)."""
    import xarray as xr

    removed = 0
    for path in sorted(reference.glob("sweep-v1/*/*.nc")):
        if path.stem in keep:
            continue
        with xr.open_dataset(path) as ds:
            task = str(ds.attrs.get("rc_cache_task", ""))
        if any(f in task for f in FEM_FUNCTIONS):
            path.unlink()
            removed += 1
    return removed


def seed_cache(reference: Path, cache: Path) -> None:
    """Copy the tracked FEM results ``cache`` lacks: those of the current code, and those
    of a code the reference's ``equivalence.json`` accepts for it (re-keyed); corrupt ones
    and those of any other code are skipped."""
    if reference.is_dir():
        report = equivalence.seed(reference, cache, FEM_FUNCTIONS)
        print(f"reference FEM solves {reference} -> {cache}: {report}", flush=True)


def accept_reference(reference: Path, why: str, rtol: float, n: int) -> int:
    """Check the reference's FEM solves of each code other than the current one on the
    ``n`` cheapest of them, and record the equivalence where they agree within ``rtol``."""
    from rubbercontact.sweep.codehash import code_digest

    groups = {(fn, code) for _, fn, code in
              equivalence.entries(ResultCache(reference), FEM_FUNCTIONS)}
    known = {(a.function, a.stored, a.current) for a in equivalence.load_equivalence(reference)}
    status = 0
    for fn, code in sorted(groups):
        now = code_digest(fn)
        if code == now or (fn, code, now) in known:
            continue
        check = equivalence.check_sample(reference, fn, code, n)
        try:
            row = equivalence.accept(reference, check, why, rtol)
            print(f"accepted: {row.checked}")
        except rc.InputError as exc:
            print(exc)
            status = 1
    return status


if __name__ == "__main__":
    sys.exit(main())
