"""``make bench``: run every benchmark script that exists (half-space, steady and
transient FEM, mean-field); ``bench_speed_sweep.py``, ``bench_halfspace_sweep.py`` (which
reads the former's ``--save`` file) and ``bench_make_run.py`` take minutes and run on their
own."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent


def main() -> int:
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    status = 0
    for script, args in (("bench_halfspace.py", ["--output", str(HERE / "halfspace.md")]),
                         ("bench_steady.py", ["--output", str(HERE / "steady.md")]),
                         ("bench_fem.py", []),
                         ("bench_steep_grid.py", ["--output", str(HERE / "steep_grid.md")]),
                         ("bench_meanfield.py", ["--output", str(HERE / "meanfield.md")]),
                         ("bench_strips.py", ["--output", str(HERE / "strips.md")])):
        path = HERE / script
        if not path.exists():
            print(f"skip {script} (not present)")
            continue
        print(f"== {script}", flush=True)
        status |= subprocess.call([sys.executable, str(path), *args], env=env)
    return status


if __name__ == "__main__":
    sys.exit(main())
