"""Benchmark: the steady FEM solver against the time-stepped (transient) test, side by side.

Cases (issue 26's performance list), each run by both solvers in one process:

1. ``law``: the validation's law cell, 120 x 23 rows graded x8, 50 mm/s, 2 MPa. Transient
   creep-settled (``min_creep_times = 5``: 82 ms of sliding) with the validation's time step
   (60 steps per period) and with one column per step (120, the steady solver's discrete
   problem, so the answers must agree), against the steady solve.
2. ``default``: the default test, 120 x 90, 1 MPa, 10 mm/s (``rubbercontact fem``): the
   transient with its defaults (6 periods) against the steady solve.
3. ``full``: the section 3 full FEM (240 x 45 graded x8, realization 0 of seed 2021) at 0.35
   and 2 MPa, 50 mm/s: steady; ``--transient-full`` adds the creep-settled transient (17
   periods of 240 steps, tens of minutes). ``--baseline REV`` runs the same cases first with
   the library of commit ``REV`` (its ``src`` exported to a temporary directory, run in a
   child process), so old and new stand side by side in one run.
4. ``sweep``: 13 speeds over 1e-3 ... 1e3 mm/s at 1 MPa on the law cell by continuation,
   against one fresh point.

Each steady row gives the per-iteration split (assembly / factorization / Krylov). Run
single-threaded::

    OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_steady.py --output benchmarks/steady.md

Times are CPU seconds of this process (``time.process_time``) beside wall seconds, with the
1-minute load average at the end of each solve: on the shared 2-core machine the CPU
seconds of one solve rise with the load too (measured: 75 s quiet, 131 s at load 7.7). The
markdown table (``--output``) goes into BENCHMARKS.md (``collect.py``).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

import rubbercontact as rc

LAW = {"mesh": (120, 23), "grading": 8.0}
FULL = {"mesh": (240, 45), "grading": 8.0}


def _row(label: str, res, cpu: float) -> dict:
    s = res.stats
    fact = getattr(s, "factorization_time", None)   # not in results of older commits
    row = {"case": label, "solver": s.solver, "friction": res.friction,
           "contact_fraction": res.contact_fraction, "mean_separation_mm": res.mean_separation,
           "bulk_shear": s.bulk_shear, "cpu_s": cpu, "wall_s": s.wall_time,
           "load": os.getloadavg()[0], "newton": s.newton_iterations,
           "factorizations": s.factorizations, "assembly_s": s.assembly_time,
           "solve_s": s.solve_time,
           "factorization_s": fact if fact is not None and np.isfinite(fact) else None}
    if s.solver == "steady":
        row.update(krylov=s.krylov_iterations, surface_offset=s.surface_offset,
                   tried="; ".join(s.tried))
    else:
        row.update(steps=s.steps, periods=s.periods, steady=s.steady)
    print(json.dumps(row), flush=True)
    return row


def _timed(fn):
    t0 = time.process_time()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        out = fn()
    return out, time.process_time() - t0


def law_case(rows: list) -> None:
    surf, mat = rc.roughness.high_slope_wave(), rc.materials.sbr()
    st, cpu = _timed(lambda: rc.fem.steady_sliding(surf, mat, 2.0, 50.0, **LAW))
    rows.append(_row("law 120x23x8 50mm/s 2MPa", st, cpu))
    creep = 5 * float(mat.retardation_times().max())
    for spp in (60, 120):
        kw = {"solver": "transient", "steps_per_period": spp, "min_sliding_time": creep,
              "periods": 200, "surface_offset": st.stats.surface_offset if spp == 120 else 0.0}
        tr, cpu = _timed(lambda kw=kw: rc.fem.sliding_test(surf, mat, 2.0, 50.0, **LAW, **kw))
        rows.append(_row(f"law 120x23x8 50mm/s 2MPa, {spp} steps/period", tr, cpu))


def default_case(rows: list) -> None:
    surf, mat = rc.roughness.high_slope_wave(), rc.materials.sbr()
    st, cpu = _timed(lambda: rc.fem.steady_sliding(surf, mat, 1.0, 10.0, mesh=(120, 90)))
    rows.append(_row("default 120x90 10mm/s 1MPa", st, cpu))
    tr, cpu = _timed(lambda: rc.fem.sliding_test(surf, mat, 1.0, 10.0, mesh=(120, 90),
                                                 solver="transient"))
    rows.append(_row("default 120x90 10mm/s 1MPa", tr, cpu))


def full_case(rows: list, transient: bool) -> None:
    surf = rc.roughness.section3().realizations(1, seed=2021)[0]
    mat = rc.materials.sbr()
    for p in (0.35, 2.0):
        st, cpu = _timed(lambda p=p: rc.fem.steady_sliding(surf, mat, p, 50.0, **FULL))
        rows.append(_row(f"full 240x45x8 50mm/s {p}MPa", st, cpu))
        if transient:
            creep = 5 * float(mat.retardation_times().max())
            tr, cpu = _timed(lambda p=p, creep=creep: rc.fem.sliding_test(
                surf, mat, p, 50.0, **FULL, solver="transient", steps_per_period=240,
                min_sliding_time=creep, periods=100))
            rows.append(_row(f"full 240x45x8 50mm/s {p}MPa", tr, cpu))


def sweep_case(rows: list) -> None:
    surf, mat = rc.roughness.high_slope_wave(), rc.materials.sbr()
    v = np.geomspace(1e-3, 1e3, 13)
    one, cpu1 = _timed(lambda: rc.fem.steady_sliding(surf, mat, 1.0, 1.0, **LAW))
    rows.append(_row("one point 120x23x8 1mm/s 1MPa", one, cpu1))
    sweep, cpu = _timed(lambda: rc.fem.steady_sweep(surf, mat, 1.0, v, **LAW))
    fresh = []
    for vi in v:       # every speed of the sweep solved on its own: the mean cost of a point
        _, cpu_i = _timed(lambda vi=vi: rc.fem.steady_sliding(surf, mat, 1.0, float(vi), **LAW))
        fresh.append(cpu_i)
    row = {"case": "sweep 13 speeds 1e-3..1e3 mm/s, 1 MPa, 120x23x8", "cpu_s": cpu,
           "ratio_to_one_point": cpu / cpu1, "fresh_cpu_s": fresh,
           "ratio_to_mean_fresh_point": cpu / float(np.mean(fresh)),
           "friction": [r.friction for r in sweep],
           "newton": [r.stats.newton_iterations for r in sweep],
           "solver": [r.stats.solver for r in sweep]}
    print(json.dumps(row), flush=True)
    rows.append(row)


def baseline(rev: str, cases: str) -> list:
    """The rows of ``cases`` run with the library of commit ``rev`` (in a child process)."""
    root = Path(__file__).resolve().parents[1]
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run(f"git -C {root} archive {rev} src | tar -x -C {tmp}", shell=True,
                       check=True)
        out = Path(tmp) / "rows.json"
        env = {**os.environ, "PYTHONPATH": str(Path(tmp) / "src"), "OMP_NUM_THREADS": "1"}
        subprocess.run([sys.executable, __file__, "--cases", cases, "--json", str(out)],
                       env=env, check=True)
        rows = json.loads(out.read_text())["rows"]
    for r in rows:
        r["case"] += f" [{rev}]"
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", default="law,default,full,sweep")
    ap.add_argument("--transient-full", action="store_true")
    ap.add_argument("--baseline", default=None, metavar="REV",
                    help="run the cases with commit REV's library first")
    ap.add_argument("--json", default=None)
    ap.add_argument("--output", default=None, help="markdown table for BENCHMARKS.md")
    args = ap.parse_args()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, check=False).stdout.strip() or "?"
    report = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "commit": commit,
              "machine": f"{platform.processor() or platform.machine()}, python "
                         f"{platform.python_version()}, numpy {np.__version__}", "rows": []}
    if args.baseline:
        report["baseline"] = args.baseline
        report["rows"] += baseline(args.baseline, args.cases)
    for case in args.cases.split(","):
        if case == "full":
            full_case(report["rows"], args.transient_full)
        else:
            {"law": law_case, "default": default_case, "sweep": sweep_case}[case](
                report["rows"])
        if args.json:
            with open(args.json, "w") as f:
                json.dump(report, f, indent=1)
        if args.output:
            with open(args.output, "w") as f:
                f.write(markdown(report))


def _fmt(x, spec: str) -> str:
    return "–" if x is None else format(x, spec)


def markdown(report: dict) -> str:
    """The steady-vs-transient section of BENCHMARKS.md: one row per solve, in run order."""
    lines = ["# Steady FEM against the time-stepped test (`benchmarks/bench_steady.py`)", "",
             f"{report['date']}, commit {report['commit']}, {report['machine']}, one thread; "
             "CPU seconds of the process. Steady and transient rows of a case ran one after "
             "the other in this run. The transient law rows slide 5 retardation times "
             "(creep-settled); the default transient row uses `rubbercontact fem`'s defaults.",
             "", "| case | solver | CPU [s] | wall [s] | load | μ | A | ū [mm] | Newton | "
             "factorizations | assembly [s, wall] | factorization [s, wall] | "
             "GMRES (split) or all linear solves [s, wall] |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in report["rows"]:
        if isinstance(r.get("friction"), list):
            continue
        fact = r.get("factorization_s")
        krylov = None if fact is None else r["solve_s"] - fact
        lines.append(f"| {r['case']} | {r['solver']} | {r['cpu_s']:.1f} | "
                     f"{_fmt(r.get('wall_s'), '.1f')} | {_fmt(r.get('load'), '.1f')} | "
                     f"{r['friction']:.5f} | "
                     f"{r['contact_fraction']:.5f} | {r['mean_separation_mm']:.6f} | "
                     f"{r['newton']} | {_fmt(r.get('factorizations'), 'd')} | "
                     f"{_fmt(r.get('assembly_s'), '.2f')} | {_fmt(fact, '.2f')} | "
                     + (f"{_fmt(r.get('solve_s'), '.2f')} |" if krylov is None
                        else f"{krylov:.2f} (GMRES) |"))
    by_case: dict = {}
    for r in report["rows"]:
        if not isinstance(r.get("friction"), list):
            by_case.setdefault(r["case"].split(",")[0], []).append(r)
    ratios = []
    for rows in by_case.values():
        st = [r for r in rows if r["solver"] == "steady"]
        for r in rows:
            if st and r["solver"] != "steady":
                ratios.append(f"- {r['case']}: transient / steady CPU = "
                              f"{r['cpu_s'] / st[0]['cpu_s']:.0f}×, μ differs by "
                              f"{abs(r['friction'] / st[0]['friction'] - 1):.1e} (relative)")
    rev = report.get("baseline")
    for r in report["rows"]:
        old = next((o for o in report["rows"] if rev and o["case"] == f"{r['case']} [{rev}]"),
                   None)
        if old is not None and not isinstance(r.get("friction"), list):
            ratios.append(f"- {r['case']}: this commit {r['cpu_s']:.1f} s CPU "
                          f"({r['newton']} Newton) against {old['cpu_s']:.1f} s "
                          f"({old['newton']} Newton) at {rev}; μ differs by "
                          f"{abs(r['friction'] / old['friction'] - 1):.1e} (relative)")
    sweeps = [r for r in report["rows"] if isinstance(r.get("friction"), list)]
    for r in sweeps:
        ratios.append(f"- {r['case']}: {r['cpu_s']:.1f} s, {r['ratio_to_one_point']:.2f}× the "
                      f"1 mm/s point"
                      + (f", {r['ratio_to_mean_fresh_point']:.2f}× the mean of the 13 speeds "
                         f"solved one by one ({sum(r['fresh_cpu_s']):.0f} s in all)"
                         if "fresh_cpu_s" in r else "")
                      + f"; solvers {sorted(set(r['solver']))}")
    return "\n".join([*lines, "", *ratios, ""]) + "\n"


if __name__ == "__main__":
    main()
