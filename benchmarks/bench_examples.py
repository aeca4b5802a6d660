"""Benchmark: the shipped examples from an empty cache, beside what ``--check`` estimated.

Issue 39 ("runs say what they cost"): for each example, ``rubbercontact run EXAMPLE
--check`` prints its plan and an estimate ("cost: about … on N worker(s)", per-point costs
measured on one core, stated to a factor of 2); the example is then run for real with the
same workers and a new, empty result cache (``--cache``), and the wall time and the CPU
time of the run and its workers (``RUSAGE_CHILDREN``: the processes it waited for) are
written beside the estimate::

    .venv/bin/python benchmarks/bench_examples.py asphalt dma_compound --workers 2 \\
        --output benchmarks/examples.md

``examples/section3.toml`` (about 70 core-hours of full FEM, docs/scaling.md) is not run
unless named.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import re
import resource
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CLI = [sys.executable, "-m", "rubbercontact.cli"]
DEFAULT = ("captif_road", "asphalt", "dma_compound", "speed_sweep")


@dataclass(frozen=True)
class Timing:
    """One example: the estimate ``--check`` printed and the run's measured cost."""

    example: str
    estimate: str       # as printed, e.g. "about 5 min on 2 worker(s); 9 min of CPU"
    wall: float         # [s]
    cpu: float          # [s], the run and the worker processes it waited for
    warnings: int       # lines of the run's output that say "warning"
    said: tuple[str, ...] = ()   # the first few of them
    solves: str = ""    # the solves' own clocks (results.nc), :func:`solve_times`
    failed: str = ""    # the run's "error: N solve(s) failed" line (exit code 1), if any


def estimate(example: Path, workers: int) -> str:
    """The ``cost: about …`` line of ``--check``: wall time on ``workers``, CPU time."""
    out = subprocess.run(CLI + ["run", str(example), "--check", "--workers", str(workers)],
                         cwd=ROOT, capture_output=True, text=True, check=True).stdout
    found = re.search(r"cost: (about .+?) \(to a factor", out)
    return (found[1].replace(" from an empty cache,", ";") if found
            else "(no estimate printed)")


def solve_times(results_nc: Path) -> str:
    """What the solves of a run took by their own clocks (``results.nc``: each point's
    ``wall_time``, so under load it counts the waiting too): the law's FEM points (how many,
    their sum, the slowest, how many were re-solved on a finer mesh) and the models'
    points (how many, their sum); and the run's own stage timings (``timings_s``)."""
    if not results_nc.exists():
        return "no results.nc"
    import numpy as np
    import xarray as xr

    parts = []
    with xr.open_dataset(results_nc) as res:
        if "law_wall_time" in res:
            wall = res["law_wall_time"].values
            done = np.isfinite(wall)
            refined = (int(np.nansum(res["law_refined"].values[done]))
                       if "law_refined" in res else 0)
            parts.append(f"law FEM {int(done.sum())} points, {np.nansum(wall):.0f} s "
                         f"(slowest {np.nanmax(wall) if done.any() else 0:.0f} s, "
                         f"{refined} refined)")
        if "wall_time" in res:
            wall = res["wall_time"].values
            parts.append(f"models {int(np.isfinite(wall).sum())} points, "
                         f"{np.nansum(wall):.0f} s")
        if "timings_s" in res.attrs:          # the run's own stages (wall)
            stages = json.loads(res.attrs["timings_s"])
            parts.append("run: " + ", ".join(f"{k} {v:.0f} s" for k, v in stages.items()))
    return "; ".join(parts)


def cached_task_times(cache: Path) -> str:
    """The law cell's quasi-static points and the law tables by their own clocks, read
    from the run's cache entries (results.nc keeps the check's friction, not its time, and
    nothing of the tables): how many, their sum, the slowest."""
    import xarray as xr

    from rubbercontact.pipeline.lawcheck import QS_LABEL

    kinds = {QS_LABEL: "law quasi-static check", "law table": "law tables"}
    wall: dict[str, list[float]] = {k: [] for k in kinds}
    for entry in cache.rglob("*.nc"):
        with xr.open_dataset(entry) as ds:
            label = str(ds.attrs.get("rc_cache_label", ""))
            for prefix, times in wall.items():
                if label.startswith(prefix):
                    times.append(float(ds.attrs.get("rc_cache_wall_time_s", float("nan"))))
    return "; ".join(f"{kinds[k]} {len(w)} points, {sum(w):.0f} s (slowest {max(w):.0f} s)"
                     for k, w in wall.items() if w)


def run(example: Path, workers: int) -> Timing:
    """Run ``example`` from an empty cache into a temporary directory."""
    guess = estimate(example, workers)
    with tempfile.TemporaryDirectory() as tmp:
        cpu0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        proc = subprocess.run(CLI + ["run", str(example), "--workers", str(workers),
                                     "--output", str(Path(tmp) / "out"), "--cache",
                                     str(Path(tmp) / "cache"), "--quiet"],
                              cwd=ROOT, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        cpu1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        solves = "; ".join(x for x in (solve_times(Path(tmp) / "out" / "results.nc"),
                                       cached_task_times(Path(tmp) / "cache")) if x)
        finished = (Path(tmp) / "out" / "results.nc").exists()
    last = proc.stderr.strip().splitlines()[-1:]
    # exit code 1 after writing the results: the run ended, some solves failed (it says
    # which); that is a measured run, not a crash
    failed = last[0][:300] if proc.returncode == 1 and finished and last else ""
    if proc.returncode != 0 and not failed:
        raise SystemExit(f"{example.name}: run failed ({proc.returncode}): {last}")
    cpu = (cpu1.ru_utime - cpu0.ru_utime) + (cpu1.ru_stime - cpu0.ru_stime)
    lines = [ln.strip() for ln in (proc.stdout + proc.stderr).splitlines()
             if "warning" in ln.lower()]
    return Timing(example.stem, guess, wall, cpu, len(lines), tuple(dict.fromkeys(lines))[:4],
                  solves, failed)


def _minutes(seconds: float) -> str:
    return f"{seconds / 60:.1f} min"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("examples", nargs="*", default=list(DEFAULT),
                    help="example names (files in examples/, without .toml)")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--output", type=Path)
    args = ap.parse_args()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True, check=True).stdout.strip()
    load0, start = os.getloadavg()[0], time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    rows, said = [], []
    for name in args.examples:
        t = run(ROOT / "examples" / f"{name}.toml", args.workers)
        print(f"{t.example}: estimate {t.estimate}; wall {t.wall:.0f} s, CPU {t.cpu:.0f} s; "
              f"{t.solves}; load {os.getloadavg()[0]:.1f}", flush=True)
        rows.append(f"| `{t.example}` | {t.estimate} | {_minutes(t.wall)} | "
                    f"{_minutes(t.cpu)} | {os.getloadavg()[0]:.1f} | {t.solves} | {t.warnings} |")
        said += [f"- `{t.example}`: {line[:200]}" for line in t.said]
        said += [f"- `{t.example}` ended with exit code 1: {t.failed}"] if t.failed else []
    text = "\n".join([
        "# The examples from an empty cache against their estimate "
        "(`benchmarks/bench_examples.py`)", "",
        f"{start}, commit {commit}, {platform.processor() or platform.machine()}, "
        f"{os.cpu_count()} cores, `--workers {args.workers}`; load average {load0:.1f} at the "
        f"start, {os.getloadavg()[0]:.1f} at the end (other jobs share the machine when it is "
        "above the workers: wall times are then high, CPU times less so). The estimate is "
        "`rubbercontact run EXAMPLE --check` (to a factor of 2); CPU is the run's and its "
        "workers'.", "",
        "| example | `--check` estimate | wall | CPU | load at the end | the solves' own "
        "clocks (results.nc) | warning lines |",
        "|---|---|---:|---:|---:|---|---:|", *rows, "",
        *(["Warning lines (first few per example, 200 characters) and failed solves:", "",
           *said, ""]
          if said else [])])
    print(text)
    if args.output:
        args.output.write_text(text)


if __name__ == "__main__":
    main()
