"""The hybrids' flash with each scale at its own temperature against one temperature for both.

The run of ``benchmarks/bench_flash_run.py`` (``examples/speed_sweep.toml`` made small:
the CAPTIF profiles' sine series, 3 realizations, N = 16384, filled SBR with its WLF
shift, 0.2 MPa, 8 speeds 1e-3 – 1e4 mm/s at 20 °C, the linear law of the high-slope
waves given instead of the FEM, in-process, from an empty cache) with the models
``hybrid``, ``hybrid-windowed`` and ``meanfield-hybrid``: per pass the isothermal run,
the flash with one temperature for both scales (``FlashPlan.per_scale = False``, the
previous code) and the flash with the high-slope law at its spots' own temperature
(:mod:`rubbercontact.pipeline.flash_scales`, the runs' default); the faster (CPU) of the
passes counted. Prints a Markdown section: the costs, and μ and the rises at each speed.

Run single-threaded: ``OMP_NUM_THREADS=1 python benchmarks/bench_flash_scales.py
[--output FILE]``.
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import tempfile
import time
import warnings
from dataclasses import replace
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

import rubbercontact as rc
import rubbercontact.pipeline.execute as execute
import rubbercontact.pipeline.lawstage as lawstage

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
import bench_flash_run as base  # noqa: E402 - its configuration, law and CPU tallies
from bench_meanfield import _cpu  # noqa: E402

MODELS = ["hybrid", "hybrid-windowed", "meanfield-hybrid"]
RUNS = {"isothermal": (False, True), "flash, one temperature": (True, False),
        "flash, each scale its own": (True, True)}


def timed_run(cfg: dict, law, per_scale: bool) -> dict:
    """One run: its dataset, wall and CPU [s], and the flash's CPU [s]."""
    def plan(setup):
        out = base.PLAN_FLASH(setup)
        return None if out is None else replace(out, per_scale=per_scale)

    execute.plan_flash = plan
    base.CPU.clear()
    t0, c0 = time.perf_counter(), time.process_time()
    ds = rc.pipeline.run(cfg, law=law, progress=False)
    return {"ds": ds, "wall": time.perf_counter() - t0, "cpu": time.process_time() - c0,
            "flash_cpu": base.CPU.get("flash", 0.0)}


def _config(path: Path, flash: bool) -> dict:
    cfg = base.config(path, flash)
    cfg["models"] = MODELS
    return cfg


def _rows(one, own, iso) -> list[str]:
    rows = []
    for m in MODELS:
        a, b, c = (r.sel(model=m).isel(pressure=0) for r in (one, own, iso))
        for i, v in enumerate(b["velocity"].values):
            mu0, mu1 = float(a["friction_flash"][i]), float(b["friction_flash"][i])
            rows.append(f"| {m} | {v:.3g} | {float(c['friction_mean'][i]):.4f} | {mu0:.4f} | "
                        f"{mu1:.4f} | {100 * (mu1 / mu0 - 1):+.1f} % | "
                        f"{float(a['flash_temperature'][i]):.2f} | "
                        f"{float(b['flash_temperature'][i]):.2f} / "
                        f"{float(b['flash_temperature_hs'][i]):.2f} |")
    return rows


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", type=Path)
    ap.add_argument("--passes", type=int, default=2)
    args = ap.parse_args(argv)
    lawstage.continue_with_linear_shape = lambda table, *a, **k: table
    warnings.simplefilter("ignore", rc.hybrid.LawWarning)
    load0 = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        law = base.linear_law(_config(Path(tmp), False))
        timed_run(_config(Path(tmp) / "warm-up", True), law, True)
        passes = [{name: timed_run(_config(Path(tmp) / f"{k}-{i}", flash), law, per_scale)
                   for i, (name, (flash, per_scale)) in enumerate(RUNS.items())}
                  for k in range(args.passes)]
    best = {n: min((p[n] for p in passes), key=lambda r: r["cpu"]) for n in RUNS}
    iso, one, own = (best[n] for n in RUNS)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    text = "\n".join([
        "# The hybrids' flash: each scale at its own temperature against one for both "
        "(`benchmarks/bench_flash_scales.py`)", "",
        f"Run {datetime.now(UTC):%Y-%m-%d %H:%M} UTC, commit {commit}, {_cpu()}, "
        f"{os.cpu_count()} cores, OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}"
        f", numpy {np.__version__}, Python {platform.python_version()}; load average "
        f"{load0:.1f} at the start, {os.getloadavg()[0]:.1f} at the end (shared machine: "
        f"compare CPU times). The run of bench_flash_run.py (speed_sweep.toml made small, "
        f"linear law, SBR, 0.2 MPa, 8 speeds 1e-3 – 1e4 mm/s, 20 °C) with "
        f"{', '.join(MODELS)}; the faster (CPU) of {args.passes} passes.", "",
        "| run | wall [s] | CPU [s] | CPU / isothermal | flash CPU [s] | half-space solves |",
        "|---|---|---|---|---|---|",
        *(f"| {n} | {r['wall']:.1f} | {r['cpu']:.1f} | {r['cpu'] / iso['cpu']:.2f} | "
          f"{r['flash_cpu']:.1f} | {r['ds'].attrs.get('flash_halfspace_solves', 0)} |"
          for n, r in best.items()), "",
        f"Flash note (each scale its own): {own['ds'].attrs['flash_note'] or '(none)'}; "
        f"largest residual {own['ds'].attrs['flash_residual_K']:.3g} K.", "",
        "| model | v [mm/s] | μ isothermal | μ one temperature | μ each scale | change | "
        "T_c [K] one | T_c / T_hs [K] each |",
        "|---|---|---|---|---|---|---|---|", *_rows(one["ds"], own["ds"], iso["ds"]), ""])
    print(text)
    if args.output:
        args.output.write_text(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
