"""Benchmark: a 15-speed friction curve on the Table 2 asphalt from an empty result cache.

Issue 27's performance case: μ(v) at 15 log-spaced speeds (1e-3 … 1e4 mm/s), 5 loads and
8 random-phase realizations, models ``vhs`` and ``hybrid`` with the hybrid's law computed by
the steady FEM (the validation's law cell, 120 × 23 graded ×8, by continuation in speed),
run by the pipeline with 2 Dask workers into a new, empty cache. Reports the wall time, the
law's share, and the half-space part (the VHS and hybrid solves) in CPU seconds::

    OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_speed_sweep.py \\
        --output benchmarks/speed_sweep.md
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

import rubbercontact as rc

CONFIG = {
    "surface": {"preset": "asphalt_ac8"},
    "material": {"preset": "sbr"},
    "loads": {"pressures": [0.05, 0.1, 0.2, 0.3, 0.4]},
    "velocities": {"from": 1e-3, "to": 1e4, "points": 15},
    "realizations": 8,
    "seed": 2021,
    "models": ["vhs", "hybrid"],
    "halfspace": {"n": 8192},
    "fem": {"mesh": [120, 23], "grading": 8.0},
    "law": {"pressures": [0.1, 0.2, 0.5, 1.0, 2.0, 4.0, 6.0]},
}


def run(workers: int, save: Path | None = None) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        cfg = {**CONFIG, "execution": {"workers": workers, "cache": str(Path(tmp) / "cache")},
               "output": {"directory": str(Path(tmp) / "out")}}
        t0 = time.perf_counter()
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            ds = rc.pipeline.run(cfg, progress="log")
        wall = time.perf_counter() - t0
    if save is not None:
        # the results with their law table: bench_halfspace_sweep.py reruns the half-space
        # part from it without the FEM
        from rubbercontact.io.results import write_results

        write_results(ds, save, overwrite=True)
    timings = json.loads(ds.attrs["timings_s"])
    cpu = json.loads(ds.attrs["model_cpu_time_s"])
    law_ok = int(np.isfinite(ds["law_friction"]).sum())
    peak = {}
    for p in ds["pressure"].values:
        pk = rc.pipeline.friction_peak(ds["velocity"].values, ds.rc.mean("friction")
                                       .sel(model="hybrid", pressure=p).values)
        peak[float(p)] = None if pk is None else (pk.velocity, pk.friction)
    return {"wall_s": wall, "timings_s": timings, "model_cpu_s": cpu,
            "law_points": int(ds["law_friction"].size), "law_points_ok": law_ok,
            "warnings": sorted({str(w.message)[:160] for w in caught}),
            "hybrid_peak": peak}


def markdown(res: dict, head: str) -> str:
    t, cpu = res["timings_s"], res["model_cpu_s"]
    law = t.get("law", 0.0)
    hs = cpu.get("vhs", 0.0) + cpu.get("hybrid", 0.0)
    lines = ["# Speed sweeps: friction against speed from an empty cache "
             "(`benchmarks/bench_speed_sweep.py`)", "", head, "",
             "Table 2 asphalt, 15 speeds 1e-3 … 1e4 mm/s, 5 loads 0.05 … 0.4 MPa, "
             "8 realizations, models vhs + hybrid, law by the steady FEM on the 120 × 23 ×8 "
             "cell (7 pressures × 15 speeds, by continuation in speed), half-space n = 8192.",
             "", "| part | time |", "|---|---:|",
             f"| whole run (wall, empty cache) | {res['wall_s']:.0f} s |",
             f"| law: FEM sweep (wall) | {law:.0f} s ({law / res['wall_s']:.0%} of the run) |",
             f"| half-space part: VHS + hybrid solves, 2 × 600 (CPU) | {hs:.1f} s |",
             f"| law points converged | {res['law_points_ok']} of {res['law_points']} |", ""]
    for p, pk in res["hybrid_peak"].items():
        if pk is not None:
            lines.append(f"- hybrid μ peaks at {pk[0]:.3g} mm/s (μ = {pk[1]:.3f}) at "
                         f"σ0 = {p:g} MPa")
    if res["warnings"]:
        lines += ["", "Warnings of the run (first 160 characters):", ""]
        lines += [f"- {w}" for w in res["warnings"]]
    return "\n".join(lines) + "\n"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--output", type=Path)
    ap.add_argument("--save", type=Path, help="write the results (with the law) to NetCDF")
    args = ap.parse_args()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, check=False).stdout.strip() or "?"
    load0 = os.getloadavg()[0]
    res = run(args.workers, args.save)
    head = (f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, commit {commit}, "
            f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
            f"{args.workers} workers, one thread each; load average {load0:.1f} at the start, "
            f"{os.getloadavg()[0]:.1f} at the end.")
    text = markdown(res, head)
    print(text)
    if args.output:
        args.output.write_text(text)


if __name__ == "__main__":
    main()
