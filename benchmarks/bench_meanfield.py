"""Mean-field model benchmark: μ(v) over 10 decades in one pass, against the BEM per point.

1. ``meanfield.friction_curve`` at 201 speeds (1e-4 – 1e6 mm/s) for a self-affine spectrum
   over 5 decades of wavelength (1D and 2D isotropic), best of 5;
2. ``meanfield.solve`` and ``friction_curve`` on the exact spectrum of the 4-decade profile of
   studies/meanfield.py (10^4 harmonics);
3. the BEM (``halfspace.solve_sliding``, hard wall) on that profile at N = 2^18 (``--sizes``
   adds 2^20: 45 min per solve on the reference machine), one
   solve per point at 10 and 50 mm/s, at the loads where the theory's area is 5 %.

Run single-threaded: ``OMP_NUM_THREADS=1 python benchmarks/bench_meanfield.py
[--sizes 262144,1048576] [--output FILE]``; prints a Markdown section (machine, date, commit).
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import time
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact import meanfield as mf

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from rubbercontact.meanfield.patches import harmonic_table  # noqa: E402
from studies._meanfield_cases import load_for_area, self_affine_profile  # noqa: E402
from studies.meanfield import SELF_AFFINE  # noqa: E402

SBR = rc.materials.sbr()
SPEEDS = np.logspace(-4, 6, 201)


def _best(fn, repeat: int = 5) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def _cpu() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default=f"{2**18}",
                    help="BEM grid sizes for the 4-decade profile (comma list)")
    ap.add_argument("--output", type=Path)
    args = ap.parse_args(argv)
    load0 = os.getloadavg()[0]
    rows = []
    harmonic_table.cache_clear()
    psd = mf.PSD.self_affine(hurst=0.8, qr=2 * np.pi / 10, q1=2 * np.pi / 1e-4, rms_slope=0.7)
    t0 = time.perf_counter()
    mf.friction_curve(psd, SBR, SPEEDS, 0.3)
    cold = time.perf_counter() - t0
    for dim in (1, 2):
        psd = mf.PSD.self_affine(hurst=0.8, qr=2 * np.pi / 10, q1=2 * np.pi / 1e-4,
                                 rms_slope=0.7, dimension=dim)
        t = _best(lambda psd=psd: mf.friction_curve(psd, SBR, SPEEDS, 0.3))
        rows.append(f"| μ(v), 201 speeds over 10 decades, {dim}D self-affine spectrum over 5 "
                    f"decades ({psd.size} nodes) | {t:.3f} s | {1e3 * t / SPEEDS.size:.2f} ms |")
    rows.insert(1, f"| the same 1D curve as the first call of a process (builds the patch "
                   f"spectrum's harmonic table) | {cold:.3f} s | |")
    z, exact = self_affine_profile(n=4 * 10**4, seed=1, **SELF_AFFINE)
    t = _best(lambda: mf.friction_curve(exact, SBR, SPEEDS, 0.3))
    rows.append(f"| μ(v), 201 speeds, exact spectrum of the 4-decade profile ({exact.size} "
                f"nodes) | {t:.3f} s | {1e3 * t / SPEEDS.size:.2f} ms |")
    bem = []
    for v in (10.0, 50.0):
        p = load_for_area(exact, SBR, v, 0.05)
        t = _best(lambda v=v, p=p: mf.solve(exact, SBR, v, p))
        res = mf.solve(exact, SBR, v, p)
        rows.append(f"| one `solve`, 4-decade profile, {v:g} mm/s, σ0 = {p:.3g} MPa | "
                    f"{1e3 * t:.1f} ms | |")
        for n in (int(s) for s in args.sizes.split(",") if s):
            z, _ = self_affine_profile(n=n, seed=1, **SELF_AFFINE)
            t0 = time.perf_counter()
            b = rc.halfspace.solve_sliding(z, SELF_AFFINE["length"], SBR, v, p)
            dt = time.perf_counter() - t0
            bem.append(f"| {v:g} | {p:.3g} | 2^{int(np.log2(n))} | {dt:.1f} s | {b.matvecs} "
                       f"| {b.friction:.4f} / {b.contact_fraction:.4f} | "
                       f"{res.friction:.4f} / {res.contact_fraction:.4f} |")
            print(bem[-1], flush=True)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    text = "\n".join([
        f"Run {datetime.now(UTC):%Y-%m-%d %H:%M} UTC, commit {commit}, {_cpu()}, "
        f"{os.cpu_count()} cores, one thread (OMP_NUM_THREADS="
        f"{os.environ.get('OMP_NUM_THREADS', 'unset')}), numpy {np.__version__}, Python "
        f"{platform.python_version()}; load average {load0:.1f} at the start, "
        f"{os.getloadavg()[0]:.1f} at the end (the machine is shared). "
        "`python benchmarks/bench_meanfield.py`.", "",
        "| mean-field | wall (best of 5) | per speed |", "|---|---|---|", *rows, "",
        "BEM on the same 4-decade profile (harmonics 10 mm – 1 µm, H = 0.8, rms slope 0.7), "
        "one solve per point:", "",
        "| v [mm/s] | σ0 [MPa] | N | BEM wall | FFT pairs | BEM μ / A | mean-field μ / A |",
        "|---|---|---|---|---|---|---|", *bem])
    print(text)
    if args.output:
        args.output.write_text(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
