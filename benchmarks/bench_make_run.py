"""Benchmark: ``make run`` from a fresh clone with an empty result cache, install included.

Clones the repository at HEAD into a temporary directory, points ``RUBBERCONTACT_CACHE``
at a new, empty directory (the default cache lives in the user's cache directory, where a
warm cache would hide the real cost), and times ``make .venv/.installed`` (virtual
environment + install) and then ``make run`` (the built-in default run). ``--compare
COMMIT`` times that commit the same way first, in the same run (old and new side by
side)::

    .venv/bin/python benchmarks/bench_make_run.py --output benchmarks/make_run.md
    .venv/bin/python benchmarks/bench_make_run.py --compare 1fba2c7 --output ...
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


@dataclass(frozen=True)
class Timing:
    """One commit's ``make`` steps from a fresh clone [s] and what its run wrote."""

    commit: str
    install: float
    run: float
    outputs: list[str]


def _timed(cmd: list[str], cwd: Path, env: dict) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, cwd=cwd, env=env, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def _short(rev: str) -> str:
    return subprocess.run(["git", "rev-parse", "--short", rev], cwd=ROOT,
                          capture_output=True, text=True, check=True).stdout.strip()


def time_commit(rev: str) -> Timing:
    """``make .venv/.installed`` and ``make run`` in a fresh clone at ``rev``, empty cache."""
    with tempfile.TemporaryDirectory() as tmp:
        clone, cache = Path(tmp) / "clone", Path(tmp) / "cache"
        subprocess.run(["git", "clone", "--quiet", str(ROOT), str(clone)], check=True)
        subprocess.run(["git", "checkout", "--quiet", rev], cwd=clone, check=True)
        env = {k: v for k, v in os.environ.items() if k not in ("VIRTUAL_ENV",)}
        env["RUBBERCONTACT_CACHE"] = str(cache)
        install = _timed(["make", ".venv/.installed"], clone, env)
        run = _timed(["make", "run"], clone, env)
        outputs = sorted(p.name for p in (clone / "results").iterdir())
    return Timing(_short(rev), install, run, outputs)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", type=Path)
    ap.add_argument("--compare", help="an older commit timed first, in the same run")
    args = ap.parse_args()
    load0 = os.getloadavg()[0]
    revs = ([args.compare] if args.compare else []) + ["HEAD"]
    timings = [time_commit(rev) for rev in revs]
    new = timings[-1]
    head = ["step"] + [f"wall at {t.commit}" for t in timings]
    rows = [("`make .venv/.installed` (venv + pip install)", [t.install for t in timings]),
            ("`make run` (the built-in default)", [t.run for t in timings]),
            ("total", [t.install + t.run for t in timings])]
    text = "\n".join([
        "# make run from an empty cache (`benchmarks/bench_make_run.py`)", "",
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, commit {new.commit}, "
        f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores; load average "
        f"{load0:.1f} at the start, {os.getloadavg()[0]:.1f} at the end. A fresh `git clone`"
        " per commit, `RUBBERCONTACT_CACHE` set to a new empty directory"
        + (", the commits one after the other." if len(timings) > 1 else "."), "",
        "| " + " | ".join(head) + " |", "|---" + "|---:" * len(timings) + "|",
        *[f"| {name} | " + " | ".join(f"{x:.0f} s" for x in xs) + " |" for name, xs in rows],
        "", f"Written to `results/`: {', '.join(new.outputs)}.", ""])
    print(text)
    if args.output:
        args.output.write_text(text)


if __name__ == "__main__":
    main()
