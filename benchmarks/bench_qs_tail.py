"""Benchmark: the law cell's quasi-static point as a fresh press against the tail of a
speed path (issue 39: asphalt's quasi-static check took 554 s of its 5.9 min).

For each law pressure of an example, in this process, one after the other:

- **fresh**: the check's task as :mod:`rubbercontact.pipeline.lawcheck` runs it, a steady
  point pressed at the quasi-static speed (no transient fallback);
- **tail**: a path by continuation (:func:`rubbercontact.hybrid.tasks.fem_speed_path_task`)
  over the slowest law speed and the quasi-static speed, on the same options: the law
  speed pressed, then the quasi-static speed continued from its steady state.

Written per pressure: Newton iterations and CPU of each, and μ_hs at the quasi-static
speed by each (the check passes within ``QS_TOL``)::

    .venv/bin/python benchmarks/bench_qs_tail.py asphalt --output benchmarks/qs_tail.md
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    from rubbercontact.config.parse import load_config
    from rubbercontact.hybrid.tasks import fem_speed_path_task, fem_task
    from rubbercontact.pipeline.lawcheck import QS_TOL, quasi_static_speed
    from rubbercontact.pipeline.lawstage import _fem_options, law_pressures
    from rubbercontact.pipeline.setup import resolve, task_material

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("example", help="a file in examples/, without .toml")
    ap.add_argument("--pressures", type=float, nargs="*",
                    help="law pressures [MPa] (default: the example's)")
    ap.add_argument("--start", type=float,
                    help="the path's law speed [mm/s] (default: the slowest the run computes)")
    ap.add_argument("--output", type=Path)
    args = ap.parse_args()
    setup = resolve(load_config(ROOT / "examples" / f"{args.example}.toml"))
    cfg, hs0, mat = setup.config, setup.hs0, setup.material
    pressures = (args.pressures if args.pressures
                 else np.sort(law_pressures(cfg, np.ones(1))).tolist())
    qs = quasi_static_speed(mat, float(hs0.wavelengths.min()))
    slowest = args.start or float(setup.speeds.computed.min())
    opts = _fem_options(cfg, mat).with_(steady={"fallback": False}).to_dict()
    common = {"surface": hs0.as_dict(), "material": task_material(mat), "options": opts}
    rows = []
    for p in pressures:
        t0 = time.process_time()
        fresh = fem_task(velocity=qs, mean_pressure=float(p), **common)
        c_fresh = time.process_time() - t0
        t0 = time.process_time()
        path = fem_speed_path_task(velocities=sorted([qs, slowest]), mean_pressure=float(p),
                                   **common)
        c_path = time.process_time() - t0
        at_qs = path.sel(velocity=qs)
        at_law = path.sel(velocity=slowest)
        mu_f, mu_t = float(fresh["friction"]), float(at_qs["friction"])
        row = (f"| {p:g} | {int(fresh['newton_iterations'])} | {c_fresh:.1f} | "
               f"{int(at_law['newton_iterations'])} + {int(at_qs['newton_iterations'])} | "
               f"{c_path:.1f} | {mu_f:.3g} | {mu_t:.3g} ({at_qs['status'].values}) | "
               f"{abs(mu_t - mu_f):.2g} | {os.getloadavg()[0]:.1f} |")
        print(row, flush=True)
        rows.append(row)
    text = "\n".join([
        "# The quasi-static point: fresh press against the tail of a path "
        "(`benchmarks/bench_qs_tail.py`)", "",
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, examples/{args.example}.toml's "
        f"law cell, quasi-static speed {qs:g} mm/s, the path from {slowest:g} mm/s; CPU of "
        f"this process (one thread per BLAS: {os.environ.get('OMP_NUM_THREADS', 'unset')}). "
        f"The check passes within {QS_TOL:g}.", "",
        "| p [MPa] | fresh: Newton | fresh: CPU [s] | path: Newton (law point + tail) | "
        "path: CPU [s] | μ_hs fresh | μ_hs tail | difference | load |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|", *rows, ""])
    print(text)
    if args.output:
        args.output.write_text(text)


if __name__ == "__main__":
    main()
