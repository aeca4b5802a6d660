"""Benchmark: the 1024² map with the cell's linear law (``bench_maps.py --bem``'s case),
the one-level contact-set preconditioner against the current two-level one (issue 42,
item 5: ≤ 5 s on one core).

The one-level solver is the current code with ``coarse_space_2d=None,
soft_law_scale_beta_2d=4.0``: bitwise the solver before commit bac6dcb. The two run
interleaved in one process, six rounds; the medians are of rounds 2-6 (the first pays
~1 s of first-touch page faults), CPU time of the process::

    OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_map_coarse_space.py
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_maps import GRADIENT, HURST, PRESSURE, SIDE, VELOCITY, _steepest  # noqa: E402

from rubbercontact.halfspace import SolverOptions  # noqa: E402
from rubbercontact.hybrid.maps import linear_law_map, solve_map  # noqa: E402
from rubbercontact.hybrid.tasks import halfspace_law  # noqa: E402
from rubbercontact.materials import sbr  # noqa: E402
from rubbercontact.roughness.mapsplit import split_map  # noqa: E402
from rubbercontact.roughness.mapsynth import self_affine_map  # noqa: E402

VARIANTS = {"one-level": SolverOptions(coarse_space_2d=None, soft_law_scale_beta_2d=4.0),
            "current": None}


def main(n: int = 1024, rounds: int = 6) -> None:
    mat = sbr()
    hm = self_affine_map((n, n), SIDE, HURST, rms_gradient=GRADIENT, seed=1)
    split = split_map(hm, 0.9 * _steepest(hm), cell_points=32)
    law = halfspace_law("lennard-jones", linear_law_map(split.cell, mat, VELOCITY, points=40))
    print(f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {os.cpu_count()} cores, "
          f"load {os.getloadavg()[0]:.1f}, OMP_NUM_THREADS="
          f"{os.environ.get('OMP_NUM_THREADS', 'unset')}", flush=True)
    cpu = {k: [] for k in VARIANTS}
    out = {}
    for i in range(rounds):
        for k, opts in VARIANTS.items():
            c0 = time.process_time()
            out[k] = solve_map(hm, mat, VELOCITY, PRESSURE, law=law, options=opts)
            cpu[k].append(time.process_time() - c0)
            print(f"round {i + 1} {k}: {cpu[k][-1]:.2f} s CPU, {out[k].matvecs} FFT pairs",
                  flush=True)
    for k, t in cpu.items():
        print(f"{k}: median {np.median(t[1:]):.2f} s CPU (rounds 2-{rounds}: "
              f"{', '.join(f'{x:.2f}' for x in t[1:])})")
    a, b = out["current"], out["one-level"]
    dmu = abs(a.friction - b.friction) / abs(b.friction)
    da = abs(a.contact_fraction - b.contact_fraction) / b.contact_fraction
    print(f"μ {a.friction:.6g}; relative differences: μ {dmu:.1e}, A {da:.1e}; "
          f"load {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
