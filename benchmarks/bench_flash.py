"""Mean-field μ(v) with the flash temperature against the isothermal curve, same run.

``meanfield.friction_curve`` (isothermal) and ``meanfield.flash_friction_curve`` at 201
speeds over 10 decades (1e-4 – 1e6 mm/s), the self-affine spectrum of
benchmarks/bench_meanfield.py (5 decades, 1D and 2D), the paper's SBR with the WLF
"universal" constants C1 = 8.86, C2 = 101.6 K referred to 20 °C (an assumption: the paper
gives no shift law) and the default filled-SBR thermal properties; best of 3. Then the
half-space (BEM) at its own flash temperature (``thermal.flash_contact``) against the
isothermal solves, on a 2-decade self-affine profile (10 mm – 0.1 mm, H = 0.8, rms slope
0.5, N = 2^14 as in examples/speed_sweep.toml) at 0.2 MPa and 11 speeds 1e-3 – 1e4 mm/s.
Prints a Markdown section (machine, date, commit) with the timings and the curves side
by side.

Run single-threaded: ``OMP_NUM_THREADS=1 python benchmarks/bench_flash.py [--output FILE]``.
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import time
import warnings
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact import meanfield as mf
from rubbercontact.thermal import flash_contact

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
from bench_meanfield import _cpu  # noqa: E402 - one CPU-name reader for the benchmarks

from studies._meanfield_cases import self_affine_profile  # noqa: E402

SBR = rc.materials.sbr()
MATERIAL = rc.materials.GeneralizedMaxwell(SBR.equilibrium_modulus, SBR.moduli,
                                           SBR.relaxation_times, name="SBR (Table 1), WLF",
                                           shift=rc.materials.WLF(8.86, 101.6, 20.0))
SPEEDS = np.logspace(-4, 6, 201)
SHOWN = (1e-2, 1.0, 1e2, 1e3, 1e4, 1e5, 1e6)
PRESSURE = 0.3


def _best(fn, repeat: int = 3) -> tuple[float, object]:
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def _halfspace() -> tuple[list[str], float, float]:
    """Isothermal and flash half-space solves per speed: table rows, total walls."""
    z, _ = self_affine_profile(n=2**14, length=10.0, lam_min=0.1, hurst=0.8, rolloff=4,
                               slope=0.5, seed=1)

    def solve(u: float):
        return rc.halfspace.solve_sliding(z, 10.0, MATERIAL, u, 0.2)

    rows, wall_iso, wall_flash = [], 0.0, 0.0
    for v in np.logspace(-3, 4, 11):
        t0 = time.perf_counter()
        iso = solve(v)
        t1 = time.perf_counter()
        out = flash_contact(solve, v, MATERIAL.shift)
        t2 = time.perf_counter()
        wall_iso, wall_flash = wall_iso + t1 - t0, wall_flash + t2 - t1
        rows.append(f"| {v:.3g} | {iso.friction:.3f} | {out.result.friction:.3f} | "
                    f"{out.contact_temperature - 20.0:.2f} | {len(out.evaluations)} | "
                    f"{out.residual:.2g} | {t1 - t0:.2f} s | {t2 - t1:.2f} s |")
    return rows, wall_iso, wall_flash


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", type=Path)
    args = ap.parse_args(argv)
    load0 = os.getloadavg()[0]
    timing, curves = [], []
    for dim in (1, 2):
        psd = mf.PSD.self_affine(hurst=0.8, qr=2 * np.pi / 10, q1=2 * np.pi / 1e-4,
                                 rms_slope=0.7, dimension=dim)
        t_iso, _ = _best(lambda psd=psd: mf.friction_curve(psd, MATERIAL, SPEEDS, PRESSURE))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", mf.FlashWarning)   # 1 km/s: hundreds of °C
            t_fl, out = _best(lambda psd=psd: mf.flash_friction_curve(psd, MATERIAL, SPEEDS,
                                                                     PRESSURE))
        timing.append(f"| {dim}D, {psd.size} nodes | {t_iso:.3f} s | {t_fl:.3f} s | "
                      f"{t_fl / t_iso:.1f} | {out.iterations.mean():.1f} / "
                      f"{out.iterations.max()} | {out.residual.max():.1e} K |")
        for v in SHOWN:
            i = int(np.argmin(np.abs(np.log(SPEEDS / v))))
            curves.append(f"| {dim}D | {SPEEDS[i]:.3g} | {out.friction_isothermal[i]:.3f} | "
                          f"{out.friction[i]:.3f} | {out.flash_temperature[i]:.1f} | "
                          f"{out.contact_fraction_isothermal[i]:.4f} / "
                          f"{out.contact_fraction[i]:.4f} |")
        k_iso, k_fl = np.argmax(out.friction_isothermal), np.argmax(out.friction)
        curves.append(f"| {dim}D | peak | {out.friction_isothermal[k_iso]:.3f} at "
                      f"{SPEEDS[k_iso]:.3g} mm/s | {out.friction[k_fl]:.3f} at "
                      f"{SPEEDS[k_fl]:.3g} mm/s | {out.flash_temperature[k_fl]:.1f} | |")
    hs_rows, hs_iso, hs_flash = _halfspace()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    text = "\n".join([
        "# Mean-field flash temperature (`benchmarks/bench_flash.py`)", "",
        f"Run {datetime.now(UTC):%Y-%m-%d %H:%M} UTC, commit {commit}, {_cpu()}, "
        f"{os.cpu_count()} cores, one thread (OMP_NUM_THREADS="
        f"{os.environ.get('OMP_NUM_THREADS', 'unset')}), numpy {np.__version__}, Python "
        f"{platform.python_version()}; load average {load0:.1f} at the start, "
        f"{os.getloadavg()[0]:.1f} at the end (the machine is shared). 201 speeds "
        f"1e-4 – 1e6 mm/s, σ0 = {PRESSURE} MPa, self-affine H = 0.8 from 10 mm to 0.1 µm, "
        "rms slope 0.7; SBR of Table 1 with WLF C1 = 8.86, C2 = 101.6 K at 20 °C (assumed), "
        "filled-SBR thermal defaults; best of 3.", "",
        "| spectrum | isothermal `friction_curve` | `flash_friction_curve` | ratio | "
        "fixed-point steps mean / max | largest residual |", "|---|---|---|---|---|---|",
        *timing, "",
        "`flash_friction_curve` returns the isothermal curve (at the background 20 °C) "
        "beside the flash one:", "",
        "| spectrum | v [mm/s] | μ isothermal | μ flash | ΔT finest spots [K] | "
        "A isothermal / flash |", "|---|---|---|---|---|---|", *curves, "",
        "Half-space at its own contact temperature (`thermal.flash_contact`: the solve "
        "repeated at a_T(T0 + T_c) v until T_c is the contact's mean rise; the first "
        "solve is the isothermal one, solved again here for the timing), 2-decade "
        f"self-affine profile, N = 2^14, 0.2 MPa: {hs_flash:.1f} s against "
        f"{hs_iso:.1f} s isothermal ({hs_flash / hs_iso:.1f}×).", "",
        "| v [mm/s] | μ isothermal | μ flash | T_c − T0 [K] | solves | residual [K] | "
        "isothermal | flash |", "|---|---|---|---|---|---|---|---|", *hs_rows])
    print(text)
    if args.output:
        args.output.write_text(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
