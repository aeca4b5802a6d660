"""Benchmark: the station 1 law grid (issue 41's performance bar), as a run computes it.

The CAPTIF station 1 high-slope cell (0.25 / 0.5 / 1 mm waves at zero phase, crests rounded
to the profiles' sampling, the automatic mesh, no transient fallback) at the law grid
{0.1, 0.3, 1, 3, 10} MPa × {1, 3, 10, 30, 100} mm/s:

- ``paths`` (new, what a run's law does with three speeds or more: ``law.speed_path``):
  one continuation path per pressure, the middle speed pressed and the others started
  from their neighbour (:func:`rubbercontact.fem.sweep.sweep_points`);
- ``fresh`` (old: every point pressed afresh, as the study's grid and a run with
  ``speed_path = "points"``), for the pressures of ``--fresh`` (default 0.3 and 1 MPa, to
  bound the benchmark's time), in the same process.

CPU seconds per point (``time.process_time``) and the 1-minute load at the end of each.
``--baseline REV`` runs each pressure's path with the library of commit ``REV`` first (its
``src`` exported to a temporary directory, in a child process), so old and new stand side
by side in one run, interleaved pressure by pressure (``--baseline-pressures``: only at
those). Run single-threaded::

    OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_steep_grid.py \\
        --output benchmarks/steep_grid.md
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
from rubbercontact.errors import RubberContactError
from rubbercontact.fem import make_options
from rubbercontact.fem.sweep import sweep_points

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from studies._rows import publish  # noqa: E402
from studies.steep_cells import PRESSURES, ROUNDED, VELOCITIES, cells  # noqa: E402

#: The issue's bar: the 25 points within 10 minutes on one core, median point 20 s.
BAR_TOTAL, BAR_MEDIAN = 600.0, 20.0


def run_path(surface, options, p: float) -> list[dict]:
    """One pressure's speeds by continuation; a row per point."""
    v = np.asarray(VELOCITIES, float)
    rows, gen = [], sweep_points(surface, rc.materials.sbr(), np.full(v.size, p), v, options,
                                 errors=(RubberContactError,))
    while True:
        t0 = time.process_time()
        try:
            pt = next(gen)
        except StopIteration:
            return rows
        rows.append(_row("paths", p, float(v[pt.index]), pt.result, pt.error,
                         time.process_time() - t0))


def run_fresh(surface, options, p: float) -> list[dict]:
    """One pressure's speeds, each pressed afresh."""
    rows = []
    for v in VELOCITIES:
        t0 = time.process_time()
        res, err = None, None
        try:
            res = rc.fem.steady_sliding(surface, rc.materials.sbr(), p, v, options=options)
        except RubberContactError as exc:
            err = exc
        rows.append(_row("fresh", p, v, res, err, time.process_time() - t0))
    return rows


def _row(mode: str, p: float, v: float, res, err, cpu: float) -> dict:
    row = {"mode": mode, "pressure": p, "velocity": v, "cpu_s": cpu,
           "load": os.getloadavg()[0]}
    if res is None:
        why = str(err).split("): ", 1)[-1] if str(err).startswith("FEM sliding test") else err
        return {**row, "status": str(why).split(";")[0][:110]}
    return {**row, "status": "ok", "friction": res.friction,
            "contact_fraction": res.contact_fraction, "newton": res.stats.newton_iterations,
            "shear": res.stats.bulk_shear, "mesh": "x".join(map(str, res.mesh)),
            "neighbour": "neighbour" in " ".join(res.stats.tried[:1])}


def baseline_path(src: Path, rev: str, p: float) -> list[dict]:
    """The ``paths`` rows of pressure ``p`` with the library exported to ``src`` (commit
    ``rev``), run in a child process."""
    out = src.parent / "rows.json"
    env = {**os.environ, "PYTHONPATH": str(src), "OMP_NUM_THREADS": "1"}
    subprocess.run([sys.executable, __file__, "--pressures", str(p), "--fresh",
                    "--json", str(out)], env=env, check=True, stdout=subprocess.DEVNULL)
    rows = json.loads(out.read_text())
    return [{**r, "mode": f"paths [{rev}]"} for r in rows]


def table(rows: list[dict]) -> list[str]:
    out = ["| mode | p̄ [MPa] | v [mm/s] | CPU [s] | Newton | μ | A | shear | mesh | status "
           "| load |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        mu = f"{r['friction']:.4f}" if "friction" in r else ""
        area = f"{r['contact_fraction']:.4f}" if "friction" in r else ""
        shear = f"{r['shear']:.2f}" if "shear" in r else ""
        out.append(f"| {r['mode']} | {r['pressure']:g} | {r['velocity']:g} | "
                   f"{r['cpu_s']:.1f} | {r.get('newton', '')} | {mu} | {area} | {shear} | "
                   f"{r.get('mesh', '')} | {r['status']} | {r['load']:.1f} |")
    return out


def summary(rows: list[dict]) -> list[str]:
    lines = []
    for mode in dict.fromkeys(r["mode"] for r in rows):
        sel = [r for r in rows if r["mode"] == mode]
        if not sel:
            continue
        cpu = np.array([r["cpu_s"] for r in sel])
        ok = sum(r["status"] == "ok" for r in sel)
        out = sum(r["status"].startswith("outside") for r in sel)
        refused = f", {out} refused as outside the cell's range" if out else ""
        lines.append(f"- {mode}: {len(sel)} points, {ok} steady{refused}; CPU total "
                     f"{cpu.sum():.0f} s, "
                     f"median point {np.median(cpu):.1f} s (bar: {BAR_TOTAL:.0f} s for the "
                     f"25 points, median {BAR_MEDIAN:.0f} s)")
        both = sorted({r["pressure"] for r in rows if r["mode"] == "fresh"})
        if mode.startswith("paths") and both:
            same = cpu[[r["pressure"] in both for r in sel]].sum()
            lines.append(f"  - the paths' CPU at {', '.join(f'{p:g}' for p in both)} MPa: "
                         f"{same:.0f} s")
    return lines


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pressures", type=float, nargs="*", default=list(PRESSURES))
    ap.add_argument("--fresh", type=float, nargs="*", default=[0.3, 1.0])
    ap.add_argument("--output", type=Path, default=None)
    ap.add_argument("--baseline", default=None, metavar="REV",
                    help="run each path with the library of commit REV first")
    ap.add_argument("--baseline-pressures", type=float, nargs="*", default=None,
                    help="the pressures --baseline runs (default: all of --pressures)")
    ap.add_argument("--json", type=Path, default=None, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    surface = cells()["station 1"]
    options = make_options(**ROUNDED, fallback=False)
    rows: list[dict] = []
    warnings.simplefilter("ignore")
    with tempfile.TemporaryDirectory() as tmp:
        if args.baseline:
            subprocess.run(f"git -C {ROOT} archive {args.baseline} src | tar -x -C {tmp}",
                           shell=True, check=True)
        old = args.pressures if args.baseline_pressures is None else args.baseline_pressures
        for p in args.pressures:
            if args.baseline and p in old:
                rows += baseline_path(Path(tmp) / "src", args.baseline, p)
            rows += run_path(surface, options, p)
            print("\n".join(table(rows)[-2 * len(VELOCITIES):]), flush=True)
    for p in args.fresh:
        rows += run_fresh(surface, options, p)
        print("\n".join(table(rows)[-len(VELOCITIES):]), flush=True)
    if args.json:               # a baseline child: its rows only
        args.json.write_text(json.dumps(rows))
        return 0
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    head = [f"Machine: {platform.node()} ({platform.processor() or platform.machine()}, "
            f"{os.cpu_count()} cores), {time.strftime('%Y-%m-%d')}, commit {commit}, "
            f"mesh {options.resolved(surface).mesh} (auto, crests rounded to "
            f"{ROUNDED['crest_radius']} mm).", ""]
    return publish("\n".join(head + summary(rows) + [""] + table(rows)) + "\n", args.output)


if __name__ == "__main__":
    raise SystemExit(main())
