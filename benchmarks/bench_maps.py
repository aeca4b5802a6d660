"""Height-map benchmarks: the cost of every model on a map, by grid size.

Run: ``OMP_NUM_THREADS=1 python benchmarks/bench_maps.py [--quick] [--speeds] [--output
benchmarks/maps.md]``.

On an isotropic self-affine map (H = 0.8, rms gradient 0.5, side 2 mm, SBR, 10 mm/s,
0.3 MPa), per grid size: the 2D half-space (VHS) with the hard wall and with the
Lennard-Jones wall plus a tabulated law (the hybrid's low-slope solve), the split into
octave bands, the linear law of the high-slope cell, the hybrid's low-slope solve, and the
mean-field theory on the map's spectrum. Medians of ``--repeat`` runs (interleaved), wall
time on one core; the machine's load is printed with the figures. ``--speeds``: μ(v) at 15
speeds (1e-4 … 1e3 mm/s) on the 512² map, each model in turn, with the total wall time
(issue 42's target: ≤ 10 min for the three models on the 2-core machine).
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import time

import numpy as np

from rubbercontact import meanfield
from rubbercontact.halfspace import LennardJonesRepulsion
from rubbercontact.hybrid.maps import linear_law_map, solve_map, solve_map_hybrid
from rubbercontact.hybrid.tasks import halfspace_law
from rubbercontact.materials import sbr
from rubbercontact.roughness.mapsplit import split_map
from rubbercontact.roughness.mapstats import map_psd, rms_slope_x
from rubbercontact.roughness.mapsynth import self_affine_map

SIDE, HURST, GRADIENT, VELOCITY, PRESSURE = 2.0, 0.8, 0.5, 10.0, 0.3


def timed(fn, repeat: int) -> tuple[float, object]:
    """Median wall time [s] of ``repeat`` calls and the last result."""
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), out


def bench(n: int, repeat: int) -> dict:
    """Every timing of one grid size ``n²``."""
    mat = sbr()
    hm = self_affine_map((n, n), SIDE, HURST, rms_gradient=GRADIENT, seed=1)
    # the split threshold: the rms slope along x of the steepest octave (a high band exists)
    t_split, split = timed(lambda: split_map(hm, 0.9 * _steepest(hm), cell_points=32), repeat)
    t_law, law = timed(lambda: linear_law_map(split.cell, mat, VELOCITY, points=40), 1)
    tab = halfspace_law("lennard-jones", law)
    out = {"n": n, "split": t_split, "law": t_law}
    out["vhs_hard"], r = timed(lambda: solve_map(hm, mat, VELOCITY, PRESSURE), repeat)
    out["vhs_hard_area"] = r.contact_fraction
    out["vhs_lj"], _ = timed(lambda: solve_map(hm, mat, VELOCITY, PRESSURE,
                                               law=LennardJonesRepulsion()), repeat)
    out["lj_table"], _ = timed(lambda: solve_map(hm, mat, VELOCITY, PRESSURE, law=tab), repeat)
    out["hybrid"], _ = timed(lambda: solve_map_hybrid(split, law, mat, VELOCITY, PRESSURE),
                             repeat)
    out["meanfield"], _ = timed(lambda: meanfield.solve(map_psd(hm), mat, VELOCITY, PRESSURE),
                                repeat)
    return out


def _steepest(hm) -> float:
    from rubbercontact.roughness.mapsplit import octave_bands

    slopes = octave_bands(hm)["rms_slope_x"].values
    return float(slopes.max()) if slopes.max() > 0 else rms_slope_x(hm)


def speed_curve(n: int = 512, speeds: int = 15) -> tuple[str, dict]:
    """μ(v) on the ``n²`` map by each model; a Markdown table and the wall time per model."""
    mat = sbr()
    hm = self_affine_map((n, n), SIDE, HURST, rms_gradient=GRADIENT, seed=1)
    v = np.geomspace(1e-4, 1e3, speeds)
    t0 = time.perf_counter()
    split = split_map(hm, 0.9 * _steepest(hm), cell_points=32)
    vhs = [solve_map(hm, mat, vi, PRESSURE).friction for vi in v]
    t_vhs = time.perf_counter() - t0
    t0 = time.perf_counter()
    hyb = [solve_map_hybrid(split, linear_law_map(split.cell, mat, vi, points=40), mat, vi,
                            PRESSURE).friction for vi in v]
    t_hyb = time.perf_counter() - t0
    t0 = time.perf_counter()
    mf = meanfield.friction_curve(map_psd(hm), mat, v, PRESSURE).friction
    t_mf = time.perf_counter() - t0
    lines = ["| v [mm/s] | VHS μ | hybrid μ | mean-field μ |", "|---|---|---|---|"]
    lines += [f"| {a:.3g} | {b:.3f} | {c:.3f} | {d:.3f} |" for a, b, c, d in zip(v, vhs, hyb, mf,
                                                                                strict=True)]
    return "\n".join(lines), {"vhs": t_vhs, "hybrid": t_hyb, "meanfield": t_mf}


def table(rows: list[dict]) -> str:
    head = ("| grid | VHS hard wall | VHS LJ | LJ + table | split | law of the cell (40 "
            "loads) | hybrid (low-slope solve) | mean-field |")
    lines = [head, "|" + "---|" * 8]
    for r in rows:
        lines.append(f"| {r['n']}² | {r['vhs_hard']:.3g} s | {r['vhs_lj']:.3g} s | "
                     f"{r['lj_table']:.3g} s | {r['split']:.3g} s | {r['law']:.3g} s | "
                     f"{r['hybrid']:.3g} s | {r['meanfield']:.3g} s |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="128² and 256² only, one run each")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--speeds", action="store_true", help="add mu(v) at 15 speeds on 512²")
    ap.add_argument("--output", default=None, help="write the Markdown table here")
    args = ap.parse_args(argv)
    sizes = (128, 256) if args.quick else (128, 256, 512)
    repeat = 1 if args.quick else args.repeat
    rows = [bench(n, repeat) for n in sizes]
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    stamp = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M")
    text = "\n\n".join([
        "# Height maps: cost of each model by grid size",
        f"Generated by `benchmarks/bench_maps.py` ({stamp} UTC, "
        f"{platform.processor() or platform.machine()}, load {load:.1f}, "
        f"OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}). Self-affine map "
        f"H = {HURST}, rms gradient {GRADIENT}, side {SIDE} mm; SBR, {VELOCITY:g} mm/s, "
        f"{PRESSURE} MPa; medians of {repeat} runs; the law's cell 32², 40 loads.",
        table(rows)])
    if args.speeds:
        curve, t = speed_curve()
        text += ("\n\n## μ(v) at 15 speeds on the 512² map\n\n"
                 f"Wall time: VHS {t['vhs']:.0f} s, hybrid (the cell's law at every speed and "
                 f"the low-slope solve) {t['hybrid']:.0f} s, mean-field {t['meanfield']:.2g} s; "
                 f"total {sum(t.values()) / 60:.1f} min.\n\n" + curve)
    text += "\n"
    print(text)
    if args.output:
        with open(args.output, "w") as fh:
            fh.write(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
