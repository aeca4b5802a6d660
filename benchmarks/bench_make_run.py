"""Benchmark: ``make run`` from a fresh clone with an empty result cache, install included.

Clones the repository at HEAD into a temporary directory, points ``RUBBERCONTACT_CACHE``
at a new, empty directory (the default cache lives in the user's cache directory, where a
warm cache would hide the real cost), and times ``make .venv/.installed`` (virtual
environment + install) and then ``make run`` (the built-in default run)::

    .venv/bin/python benchmarks/bench_make_run.py --output benchmarks/make_run.md
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _timed(cmd: list[str], cwd: Path, env: dict) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, cwd=cwd, env=env, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", type=Path)
    args = ap.parse_args()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True, check=True).stdout.strip()
    load0 = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        clone, cache = Path(tmp) / "clone", Path(tmp) / "cache"
        subprocess.run(["git", "clone", "--quiet", str(ROOT), str(clone)], check=True)
        env = {k: v for k, v in os.environ.items() if k not in ("VIRTUAL_ENV",)}
        env["RUBBERCONTACT_CACHE"] = str(cache)
        install = _timed(["make", ".venv/.installed"], clone, env)
        run = _timed(["make", "run"], clone, env)
        outputs = sorted(p.name for p in (clone / "results").iterdir())
    text = "\n".join([
        "# make run from an empty cache (`benchmarks/bench_make_run.py`)", "",
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, commit {commit}, "
        f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores; load average "
        f"{load0:.1f} at the start, {os.getloadavg()[0]:.1f} at the end. A fresh `git clone`, "
        "`RUBBERCONTACT_CACHE` set to a new empty directory.", "",
        "| step | wall |", "|---|---:|",
        f"| `make .venv/.installed` (venv + pip install) | {install:.0f} s |",
        f"| `make run` (the built-in default) | {run:.0f} s |",
        f"| total | {install + run:.0f} s |", "",
        f"Written to `results/`: {', '.join(outputs)}.", ""])
    print(text)
    if args.output:
        args.output.write_text(text)


if __name__ == "__main__":
    main()
