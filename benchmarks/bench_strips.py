"""Benchmark: the mean-field strip cascade (the default on sine series), this code against a
baseline commit, side by side.

``meanfield.strips.strip_contact`` on the Table 2 asphalt (8 waves) and the random 8-wave
ladder (seed 3) of studies/meanfield.py, at 1, 10, 50 and 500 mm/s and the loads of the
diffusion's 2 and 20 % contact: wall time per point (best of 3, one thread) and μ, A. With
``--baseline REV`` the same points run first with the library of commit ``REV`` (``git
archive`` into a temporary folder, a child process), so both columns come from one run.

``OMP_NUM_THREADS=1 python benchmarks/bench_strips.py --baseline ac1db64
--output benchmarks/strips.md``
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
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact.meanfield.strips import strip_contact

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from studies._meanfield_cases import load_for_area, random_ladder  # noqa: E402

SBR = rc.materials.sbr()
SPEEDS, TARGETS = (1.0, 10.0, 50.0, 500.0), (0.02, 0.2)


def measure() -> list[dict]:
    """Every point: surface, speed, load, best wall of 3 [s], μ and A."""
    rows = []
    for name, surf in (("Table 2", rc.roughness.asphalt_ac8()),
                       ("random 8 waves (seed 3)", random_ladder(8, 3))):
        psd = rc.meanfield.PSD.from_sines(surf)
        for v in SPEEDS:
            for target in TARGETS:
                p = load_for_area(psd, SBR, v, target)
                walls = []
                for _ in range(3):
                    t0 = time.perf_counter()
                    res = strip_contact(surf.wavenumbers, surf.amplitudes, SBR, v, p)
                    walls.append(time.perf_counter() - t0)
                rows.append({"surface": name, "v": v, "p": p, "wall": min(walls),
                             "mu": float(res.friction_stress.sum()) / p,
                             "A": float(res.samples.weight.sum())})
                print(json.dumps(rows[-1]), flush=True)
    return rows


def baseline(rev: str) -> list[dict]:
    """:func:`measure` with the library, the studies' cases and this benchmark of commit
    ``rev``, in a child process (the current studies may need the current library)."""
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run(f"git -C {ROOT} archive {rev} src studies benchmarks | tar -x -C {tmp}",
                       shell=True, check=True)
        out = Path(tmp) / "rows.json"
        env = {**os.environ, "PYTHONPATH": str(Path(tmp) / "src"), "OMP_NUM_THREADS": "1"}
        subprocess.run([sys.executable, str(Path(tmp) / "benchmarks" / Path(__file__).name),
                        "--json", str(out)], env=env, check=True)
        return json.loads(out.read_text())


def markdown(new: list[dict], old: list[dict] | None, rev: str | None, load: tuple) -> str:
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    head = (f"Run {datetime.now(UTC):%Y-%m-%d %H:%M} UTC, commit {commit}, "
            f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores, one thread; "
            f"load average {load[0]:.1f} at the start, {load[1]:.1f} at the end. "
            "`python benchmarks/bench_strips.py"
            + (f" --baseline {rev}`." if rev else "`."))
    cols = "| surface | v [mm/s] | σ0 [MPa] | wall [s] | μ / A |"
    sep = "|---|---|---|---|---|"
    if old:
        cols = (f"| surface | v [mm/s] | σ0 [MPa] | wall [s], {rev} | wall [s], this tree | "
                f"μ / A, {rev} | μ / A, this tree |")
        sep = "|---|---|---|---|---|---|---|"
    lines = [head, "", cols, sep]
    for i, r in enumerate(new):
        cells = [r["surface"], f"{r['v']:g}", f"{r['p']:.4g}"]
        if old:
            o = old[i]
            cells += [f"{o['wall']:.3f}", f"{r['wall']:.3f}", f"{o['mu']:.3f} / {o['A']:.4f}"]
        else:
            cells += [f"{r['wall']:.3f}"]
        cells.append(f"{r['mu']:.3f} / {r['A']:.4f}")
        lines.append("| " + " | ".join(cells) + " |")
    mean_new = np.mean([r["wall"] for r in new])
    tail = f"Mean wall per point: {mean_new:.3f} s"
    if old:
        tail += f" (baseline {np.mean([r['wall'] for r in old]):.3f} s)"
    return "\n".join(lines + ["", tail + "."])


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", metavar="REV", help="commit to measure side by side")
    ap.add_argument("--json", type=Path, help=argparse.SUPPRESS)
    ap.add_argument("--output", type=Path)
    args = ap.parse_args(argv)
    if args.json:
        args.json.write_text(json.dumps(measure()))
        return 0
    load0 = os.getloadavg()[0]
    old = baseline(args.baseline) if args.baseline else None
    new = measure()
    text = markdown(new, old, args.baseline, (load0, os.getloadavg()[0]))
    print(text)
    if args.output:
        args.output.write_text(text + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
