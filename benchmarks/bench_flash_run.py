"""A run's cost with the flash temperature against the same run isothermal, side by side.

``examples/speed_sweep.toml`` made small: its surface (the two CAPTIF profiles' sine
series, 3 realizations, N = 16384, the runs' Lennard-Jones wall), rubber and load
(0.2 MPa), at 8 speeds 1e-3 – 1e4 mm/s and the reference temperature only, models
``vhs``, ``hybrid`` and ``hybrid-windowed``. The high-slope law is the linear (VHS) law of
the high-slope waves at the run's speeds instead of the FEM (minutes per point on this
machine, and the same for both runs: the flash repeats the half-space solves, not the
law), given to both runs, and the run's continuation of the law past its highest point
(VHS solves near full contact, the same for both runs) is left out. Each run from an
empty result cache, in-process (one worker), after an untimed warm-up run (the result
cache's code digests, imports); per pass the isothermal run, the flash run with each
realization's search started from its own lower speeds (``FlashPlan.guided = False``, the
previous code) and the flash run as runs do it (started from the previous realization's
roots); the faster (CPU) of the passes counted. Wall and CPU time (``time.process_time``:
the machine is shared, wall times are contended) of the whole run and of its parts
(``attrs["timings_s"]``: ``models`` the isothermal model tasks, ``flash`` the flash).

Prints a Markdown section (machine, date, commit).
Run single-threaded: ``OMP_NUM_THREADS=1 python benchmarks/bench_flash_run.py [--output FILE]``.
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
from dataclasses import replace
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
import xarray as xr

import rubbercontact as rc
import rubbercontact.pipeline.execute as execute
import rubbercontact.pipeline.lawstage as lawstage
from rubbercontact.hybrid.linearlaw import linear_law_table
from rubbercontact.materials import GeneralizedMaxwell
from rubbercontact.pipeline.setup import resolve, task_material

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))
from bench_meanfield import _cpu  # noqa: E402 - one CPU-name reader for the benchmarks

MODELS = ["vhs", "hybrid", "hybrid-windowed"]
SPEEDS = {"from": 1e-3, "to": 1e4, "points": 8}
LAW_PRESSURES = np.geomspace(0.01, 100.0, 13)


def config(cache: Path, flash: bool) -> dict:
    """``examples/speed_sweep.toml`` made small (module docstring)."""
    cfg = rc.config.load_config(ROOT / "examples" / "speed_sweep.toml").model_dump(
        mode="json", exclude_none=True)
    cfg.pop("temperatures", None)
    cfg.update(velocities=SPEEDS, models=MODELS,
               execution={"workers": 1, "cache": str(cache)},
               output={"directory": str(cache / "out")})
    if flash:
        cfg.setdefault("friction", {})["flash_temperature"] = {"enabled": True}
    return cfg


def linear_law(cfg: dict) -> xr.Dataset:
    """The VHS law of the run's high-slope waves at its computed speeds, as a law table
    (the points in (near) full contact excluded)."""
    setup = resolve(rc.config.parse_config(cfg))
    mat = GeneralizedMaxwell(**task_material(setup.material))
    return linear_law_table(setup.hs0, mat, setup.speeds.computed, LAW_PRESSURES, n=1024)


PLAN_FLASH = execute.plan_flash
CPU: dict[str, float] = {}


def _cpu_timed(name: str, fn):
    """``fn`` with its CPU time [s] added to ``CPU[name]``."""
    def timed(*args, **kwargs):
        c0 = time.process_time()
        try:
            return fn(*args, **kwargs)
        finally:
            CPU[name] = CPU.get(name, 0.0) + time.process_time() - c0
    return timed


execute.run_models = _cpu_timed("models", execute.run_models)
execute.add_flash = _cpu_timed("flash", execute.add_flash)


def timed_run(cfg: dict, law: xr.Dataset, guided: bool = True,
              relative_tolerance: float | None = None) -> dict:
    """One run: its dataset, wall and CPU time [s] and its parts' walls; ``guided``: the
    flash's searches started from the previous realization's roots; ``relative_tolerance``
    of the search (None: the runs')."""
    def plan(setup):
        out = PLAN_FLASH(setup)
        if out is None:
            return None
        search = (out.search if relative_tolerance is None
                  else replace(out.search, relative_tolerance=relative_tolerance))
        return replace(out, guided=guided, search=search)

    execute.plan_flash = plan
    CPU.clear()
    t0, c0 = time.perf_counter(), time.process_time()
    ds = rc.pipeline.run(cfg, law=law, progress=False)
    return {"ds": ds, "wall": time.perf_counter() - t0, "cpu": time.process_time() - c0,
            "parts": json.loads(ds.attrs["timings_s"]), "parts_cpu": dict(CPU)}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", type=Path)
    ap.add_argument("--passes", type=int, default=2)
    args = ap.parse_args(argv)
    lawstage.continue_with_linear_shape = lambda table, *a, **k: table
    warnings.simplefilter("ignore", rc.hybrid.LawWarning)
    load0 = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        law = linear_law(config(Path(tmp), False))
        timed_run(config(Path(tmp) / "warm-up", False), law)
        passes = []
        runs = {"isothermal": (False, True, None), "flash, from own speeds": (True, False, None),
                "flash, guided": (True, True, None),
                "flash, guided, rtol 3e-3": (True, True, 3e-3)}
        for k in range(args.passes):
            passes.append({name: timed_run(config(Path(tmp) / f"{k}-{i}", flash), law,
                                           guided, rtol)
                           for i, (name, (flash, guided, rtol)) in enumerate(runs.items())})
    best = {n: min((p[n] for p in passes), key=lambda r: r["cpu"]) for n in runs}
    iso, old, fl, loose = (best[n] for n in runs)
    ds = fl["ds"]
    rows = []
    for m in MODELS:
        h, h0 = ds.sel(model=m).isel(pressure=0), old["ds"].sel(model=m).isel(pressure=0)
        for i, v in enumerate(ds["velocity"].values):
            rows.append(f"| {m} | {v:.3g} | {float(h['friction_mean'][i]):.4f} | "
                        f"{float(h0['friction_flash'][i]):.4f} | "
                        f"{float(h['friction_flash'][i]):.4f} | "
                        f"{float(h0['flash_temperature'][i]):.3f} / "
                        f"{float(h['flash_temperature'][i]):.3f} |")
    mu0, mu1 = old["ds"]["friction_flash"].values, ds["friction_flash"].values
    dmu = float(np.nanmax(np.abs(mu1 / mu0 - 1)[mu0 > 1e-3]))
    mu2 = loose["ds"]["friction_flash"].values
    dmu_loose = float(np.nanmax(np.abs(mu2 / mu0 - 1)[mu0 > 1e-3]))
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    hs_iso = iso["parts"]["models"]
    text = "\n".join([
        "# Flash temperature in a run: isothermal and with the flash, side by side "
        "(`benchmarks/bench_flash_run.py`)", "",
        f"Run {datetime.now(UTC):%Y-%m-%d %H:%M} UTC, commit {commit}, {_cpu()}, "
        f"{os.cpu_count()} cores, OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}"
        f", numpy {np.__version__}, Python {platform.python_version()}; load average "
        f"{load0:.1f} at the start, {os.getloadavg()[0]:.1f} at the end (the machine is "
        f"shared: CPU times are the figures to compare). examples/speed_sweep.toml made "
        f"small: {', '.join(MODELS)}, 3 realizations, N = 16384, 0.2 MPa, 8 speeds 1e-3 – "
        f"1e4 mm/s at 20 °C, the linear law of the high-slope waves given (no FEM); each run "
        f"from an empty cache, in-process; the faster (CPU) of {args.passes} passes.", "",
        "| run | wall [s] | CPU [s] | CPU / isothermal | model tasks wall / CPU [s] | "
        "flash wall / CPU [s] | half-space part CPU / isothermal | half-space solves |",
        "|---|---|---|---|---|---|---|---|",
        f"| isothermal | {iso['wall']:.1f} | {iso['cpu']:.1f} | 1 | {hs_iso:.1f} / "
        f"{iso['parts_cpu']['models']:.1f} | | 1 | {len(MODELS) * 3 * 8} |",
        *(f"| {name} | {r['wall']:.1f} | {r['cpu']:.1f} | {r['cpu'] / iso['cpu']:.2f} | "
          f"{r['parts']['models']:.1f} / {r['parts_cpu']['models']:.1f} | "
          f"{r['parts']['flash']:.1f} / {r['parts_cpu']['flash']:.1f} | "
          f"{(r['parts_cpu']['models'] + r['parts_cpu']['flash']) / iso['parts_cpu']['models']:.2f}"
          f" | {len(MODELS) * 3 * 8} + {r['ds'].attrs['flash_halfspace_solves']} |"
          for name, r in (("flash, from own speeds", old), ("flash, guided", fl),
                          ("flash, guided, relative tolerance 3e-3", loose))), "",
        f"Largest |Δμ/μ| of the flash, guided against from own speeds (μ > 1e-3): "
        f"{dmu:.1e} (the search's tolerance, 0.01 K + 0.1 % of T_c); with the relative "
        f"tolerance 3e-3 against from own speeds: {dmu_loose:.1e}. Flash note: "
        f"{ds.attrs['flash_note'] or '(none)'}", "",
        "| model | v [mm/s] | μ isothermal | μ flash, own speeds | μ flash, guided | "
        "T_c − T0 [K] own / guided |",
        "|---|---|---|---|---|---|", *rows, ""])
    print(text)
    if args.output:
        args.output.write_text(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
