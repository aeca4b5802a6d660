"""Mean-field μ(v) with the flash temperature against the isothermal curve, same run.

``meanfield.friction_curve`` (isothermal) and ``meanfield.flash_friction_curve`` at 201
speeds over 10 decades (1e-4 – 1e6 mm/s), the self-affine spectrum of
benchmarks/bench_meanfield.py (5 decades, 1D and 2D), the paper's SBR with the WLF
"universal" constants C1 = 8.86, C2 = 101.6 K referred to 20 °C (an assumption: the paper
gives no shift law) and the default filled-SBR thermal properties; best of 3. Then the
half-space (BEM) at its own flash temperature against the isothermal solves, on a
2-decade self-affine profile (10 mm – 0.1 mm, H = 0.8, rms slope 0.5, N = 2^14 as in
examples/speed_sweep.toml) at 0.2 MPa and the 15 speeds of examples/speed_sweep.toml
(1e-3 – 1e4 mm/s), hard wall and the runs' Lennard-Jones wall: per speed, interleaved, the
isothermal solve, the plain search (``FlashSearch(method="bracket")``, the previous
default, cold solves) and the secant search started from the lower speeds, each heated
solve from the nearest one solved (``warm_start``: what runs do); the faster of 2 passes
per column.
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
from rubbercontact.thermal import FlashSearch, flash_contact
from rubbercontact.thermal.contact import start_pressure
from rubbercontact.thermal.sweep import predicted_start

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


HS_SPEEDS = np.logspace(-3, 4, 15)
PLAIN = FlashSearch(method="bracket")


def _hs_pass(solve) -> list[dict]:
    """One interleaved pass over the speeds: isothermal, plain, secant from neighbours."""
    rows, done = [], []
    for v in HS_SPEEDS:
        t0 = time.perf_counter()
        iso = solve(v)
        t1 = time.perf_counter()
        old = flash_contact(lambda u: solve(u), v, MATERIAL.shift, search=PLAIN)
        t2 = time.perf_counter()
        start = predicted_start(done, float(v), FlashSearch().tolerance)
        new = flash_contact(solve, v, MATERIAL.shift,
                            search=FlashSearch(start=start, warm_start=True))
        t3 = time.perf_counter()
        done.append((float(v), new))
        rows.append({"v": v, "iso": iso, "old": old, "new": new,
                     "t": (t1 - t0, t2 - t1, t3 - t2)})
    return rows


def _halfspace(law) -> tuple[list[str], np.ndarray]:
    """Table rows of the faster of 2 passes per column, and the walls (iso, old, new)."""
    z, _ = self_affine_profile(n=2**14, length=10.0, lam_min=0.1, hurst=0.8, rolloff=4,
                               slope=0.5, seed=1)

    def solve(u: float, start=None):
        return rc.halfspace.solve_sliding(
            z, 10.0, MATERIAL, u, 0.2, law=law,
            start=None if start is None else start_pressure(start))

    passes = [_hs_pass(solve) for _ in range(2)]
    walls = np.min([[sum(r["t"][k] for r in p) for k in range(3)] for p in passes], axis=0)
    rows = []
    for r in passes[-1]:
        old, new = r["old"], r["new"]
        rise_old, rise_new = (f.contact_temperature - 20.0 for f in (old, new))
        rows.append(f"| {r['v']:.3g} | {r['iso'].friction:.4f} | {old.result.friction:.4f} "
                    f"| {new.result.friction:.4f} | {rise_old:.3f} / {rise_new:.3f} | "
                    f"{old.residual:.1g} / {new.residual:.1g} | {len(old.evaluations)} / "
                    f"{len(new.evaluations)} | {r['t'][0]:.2f} / {r['t'][1]:.2f} / "
                    f"{r['t'][2]:.2f} s |")
    dmu = max(abs(r["new"].result.friction / r["old"].result.friction - 1)
              for r in passes[-1] if r["old"].result.friction > 0)
    dt = max(abs(r["new"].contact_temperature - r["old"].contact_temperature)
             for r in passes[-1])
    rows.append(f"| all | | | | largest ΔT {dt:.3f} K | | "
                f"{sum(len(r['old'].evaluations) for r in passes[-1])} / "
                f"{sum(len(r['new'].evaluations) for r in passes[-1])} | largest Δμ/μ "
                f"{dmu:.1e} |")
    return rows, walls


def _hs_section(name: str, rows: list[str], walls: np.ndarray) -> list[str]:
    iso, old, new = walls
    return [f"**{name}**: isothermal {iso:.2f} s; plain flash {old:.2f} s ({old / iso:.1f}×); "
            f"flash started from the lower speeds {new:.2f} s ({new / iso:.1f}×); a run "
            f"computes both, so its half-space cost is (isothermal + flash)/isothermal = "
            f"{1 + old / iso:.1f}× before, {1 + new / iso:.1f}× now.", "",
            "| v [mm/s] | μ isothermal | μ flash plain | μ flash new | T_c − T0 [K] plain / "
            "new | residual [K] plain / new | solves plain / new | isothermal / plain / new |",
            "|---|---|---|---|---|---|---|---|", *rows, ""]


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
    hard = _halfspace(None)
    lj = _halfspace(rc.halfspace.LennardJonesRepulsion())
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    text = "\n".join([
        "# Flash temperature: mean field and half-space (`benchmarks/bench_flash.py`)", "",
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
        "## Half-space at its own contact temperature", "",
        "`thermal.flash_contact`: the solve repeated at a_T(T0 + T_c) v until T_c is the "
        "contact's mean rise, |F(T_c) − T_c| ≤ 1e-2 K (plain) or ≤ 1e-2 K + 1e-3 T_c "
        "(new: the secant search on ln F − ln T, started at the rise extrapolated from the "
        "lower speeds with the last root's slope, each solve at T > 0 polished from the "
        "nearest one solved within a factor 1.25 in reduced speed, as runs do). "
        "2-decade self-affine profile, N = 2^14, 0.2 MPa, the 15 speeds of "
        "examples/speed_sweep.toml; per speed interleaved isothermal, plain, new (the "
        "plain search's first solve is the isothermal one, solved again); walls the "
        "faster of 2 passes per column.", "",
        *_hs_section("Hard wall", *hard),
        *_hs_section("Lennard-Jones wall (the runs' default `[halfspace] law`)", *lj)])
    print(text)
    if args.output:
        args.output.write_text(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
