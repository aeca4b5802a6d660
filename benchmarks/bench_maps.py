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
(issue 42's target: ≤ 10 min for the three models on the 2-core machine); the VHS with the
hard wall and with the Lennard-Jones wall, the law of a run's ``[halfspace]`` by default.
``--bem``: the 2D half-space solver against its previous path (``PREVIOUS`` options,
bitwise the code before the 2D speed-ups) and against the defaults of commit 1fba2c7
(``ROUND_BEFORE``) in one run, interleaved: viscoelastic solves with tabulated laws on 1024²,
the hard wall and the Lennard-Jones wall on 512², and the elastic hard wall on 512² against
Tamaas at equal accuracy (√10 tolerance ladders, then medians of 7 interleaved solves); it
replaces that section of ``--output`` and leaves the rest of the file.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import subprocess
import time
from pathlib import Path

import numpy as np

from rubbercontact import meanfield
from rubbercontact.halfspace import LennardJonesRepulsion, SolverOptions
from rubbercontact.hybrid.maps import linear_law_map, solve_map, solve_map_hybrid
from rubbercontact.hybrid.tasks import halfspace_law
from rubbercontact.materials import sbr
from rubbercontact.roughness.mapsplit import split_map
from rubbercontact.roughness.mapstats import map_psd, rms_slope_x
from rubbercontact.roughness.mapsynth import self_affine_map

SIDE, HURST, GRADIENT, VELOCITY, PRESSURE = 2.0, 0.8, 0.5, 10.0, 0.3


def timed(fn, repeat: int) -> tuple[tuple[float, float], object]:
    """Median wall and CPU time [s] of ``repeat`` calls, and the last result."""
    times, out = [], None
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        times.append((time.perf_counter() - t0, time.process_time() - c0))
    return (float(np.median([t[0] for t in times])),
            float(np.median([t[1] for t in times]))), out


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
    """μ(v) on the ``n²`` map by each model (the VHS with the hard wall and with the
    Lennard-Jones wall); a Markdown table and the (wall, CPU) time [s] per model."""
    mat = sbr()
    hm = self_affine_map((n, n), SIDE, HURST, rms_gradient=GRADIENT, seed=1)
    v = np.geomspace(1e-4, 1e3, speeds)
    t_vhs, (split, vhs) = timed(lambda: (split_map(hm, 0.9 * _steepest(hm), cell_points=32),
                                         [solve_map(hm, mat, vi, PRESSURE).friction
                                          for vi in v]), 1)
    t_lj, lj = timed(lambda: [solve_map(hm, mat, vi, PRESSURE, law=LennardJonesRepulsion())
                              .friction for vi in v], 1)
    t_hyb, hyb = timed(lambda: [solve_map_hybrid(
        split, linear_law_map(split.cell, mat, vi, points=40), mat, vi, PRESSURE).friction
        for vi in v], 1)
    t_mf, mf = timed(lambda: meanfield.friction_curve(map_psd(hm), mat, v,
                                                      PRESSURE).friction, 1)
    lines = ["| v [mm/s] | VHS μ (hard wall) | VHS μ (LJ wall) | hybrid μ | mean-field μ |",
             "|---|---|---|---|---|"]
    lines += [f"| {a:.3g} | {b:.3f} | {e:.3f} | {c:.3f} | {d:.3f} |"
              for a, b, e, c, d in zip(v, vhs, lj, hyb, mf, strict=True)]
    return "\n".join(lines), {"vhs": t_vhs, "vhs_lj": t_lj, "hybrid": t_hyb, "meanfield": t_mf}


def table(rows: list[dict]) -> str:
    """Wall time with the CPU time in brackets, per model and grid size."""
    keys = ("vhs_hard", "vhs_lj", "lj_table", "split", "law", "hybrid", "meanfield")
    head = ("| grid | VHS hard wall | VHS LJ | LJ + table | split | law of the cell (40 "
            "loads) | hybrid (low-slope solve) | mean-field |")
    lines = [head, "|" + "---|" * 8]
    for r in rows:
        cells = " | ".join(f"{r[k][0]:.3g} s ({r[k][1]:.3g})" for k in keys)
        lines.append(f"| {r['n']}² | {cells} |")
    return "\n".join(lines)


# -- the 2D BEM: previous path against the current one (issue 42, item 5) -------------------
#: The solver as before the 2D speed-ups (no coarse-grid start on maps, double-precision
#: GMRES, the multi-shift preconditioner on maps, the plain Newton at the end of a wall +
#: soft law): bitwise the results of the code before commit 9a375d4.
PREVIOUS = SolverOptions(coarse_min_side_2d=None, single_precision_2d=False, multi_shift_2d=True,
                          split_inverse_fft_2d=False,
                          wall_soft_mixed_newton_2d=False, soft_law_preconditioner_2d=False,
                          newton_forcing_target_2d=False, wall_soft_linear_rtol_2d=1e-3)
#: The defaults of commit 1fba2c7 (the start of the 2026-12-06 09:00 UTC round): the
#: single-precision cycles tighter than 1e-3 on a float64 Krylov basis, the GMRES bases
#: allocated per restart cycle, the finest hard wall + soft law started from the next
#: grid, the one-level soft-law preconditioner with its row scaling at β = 4 (the round's
#: change without a switch, a law's pressure and stiffness in one pass, runs in both
#: columns: bitwise the same answers).
ROUND_BEFORE = SolverOptions(tight_krylov32_2d=False, krylov_workspace_2d=False,
                             wall_soft_skip_level_2d=False, coarse_space_2d=None,
                             soft_law_scale_beta_2d=4.0)
#: The three solvers of ``--bem``, interleaved in one run.
BEM_VARIANTS = {"previous": PREVIOUS, "before": ROUND_BEFORE, "current": None}
BEM_HEADING = "## 2D BEM: the previous solver against the current one"
SPEEDS_HEADING = "## μ(v) at 15 speeds on the 512² map"


def _solve_timed(fn) -> tuple[float, float, object]:
    """Wall and CPU time [s] of one call, and its result."""
    t0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    return time.perf_counter() - t0, time.process_time() - c0, out


def _interleaved(fns: dict, repeat: int, once: tuple = ()) -> dict:
    """Each of ``fns`` called ``repeat`` times in turn (those named in ``once`` in the first
    round only); median wall and CPU time, last result."""
    runs = {k: [] for k in fns}
    for i in range(repeat):
        for k, fn in fns.items():
            if i == 0 or k not in once:
                runs[k].append(_solve_timed(fn))
    return {k: (float(np.median([r[0] for r in v])), float(np.median([r[1] for r in v])),
                v[-1][2]) for k, v in runs.items()}


def _rel(a: float, b: float) -> float:
    return abs(a - b) / max(abs(b), 1e-300)


def bem_viscoelastic(repeat: int, quick: bool) -> list[dict]:
    """Previous and current solver on the map of :func:`bench` (SBR, 10 mm/s, 0.3 MPa)."""
    from bench_halfspace import _fem_like_law

    mat = sbr()
    big, small = (256, 128) if quick else (1024, 512)
    rows = []
    for n in sorted({big, small}, reverse=True):
        hm = self_affine_map((n, n), SIDE, HURST, rms_gradient=GRADIENT, seed=1)
        split = split_map(hm, 0.9 * _steepest(hm), cell_points=32)
        cell_law = halfspace_law("lennard-jones", linear_law_map(split.cell, mat, VELOCITY,
                                                                 points=40))
        cases = ([("LJ + FEM-like table", LennardJonesRepulsion() + _fem_like_law()),
                  ("LJ + the cell's linear law", cell_law)] if n == big else
                 [("hard wall", None), ("LJ wall", LennardJonesRepulsion()),
                  ("LJ + the cell's linear law", cell_law)])
        for name, law in cases:
            # the previous path takes minutes on the 1024² linear law: once there
            once = ("previous",) if (n == big and law is cell_law and not quick) else ()
            got = _interleaved({o: (lambda o=o, law=law, hm=hm: solve_map(
                hm, mat, VELOCITY, PRESSURE, law=law, options=BEM_VARIANTS[o]))
                for o in BEM_VARIANTS}, repeat, once)
            rows.append(_bem_row(n, name, f"{1 if once else repeat}, {repeat}", got))
            print(rows[-1], flush=True)
    return rows


def _bem_row(n: int, name: str, reps: str, got: dict) -> dict:
    """One table row: times, FFT pairs and answers of each variant, differences to current."""
    new = got["current"][2]
    row = {"n": n, "case": name, "repeat": reps, "mu": new.friction}
    for key, (wall, cpu, out) in got.items():
        row[key] = {"wall": wall, "cpu": cpu, "fft": out.matvecs,
                    "dmu": _rel(new.friction, out.friction),
                    "darea": _rel(new.contact_fraction, out.contact_fraction),
                    "dubar": _rel(new.mean_separation, out.mean_separation),
                    "dp": float(np.linalg.norm(new.pressure - out.pressure)
                                / np.linalg.norm(out.pressure))}
    return row


def bem_elastic(n: int, repeat: int = 7, target: float = 1e-6) -> dict:
    """Elastic hard wall on the ``n²`` map of bench_halfspace (10 % contact) against Tamaas:
    each solver at the first rung of its √10 ladder within ``target`` (relative L2 pressure
    error against our active set at 1e-12), then ``repeat`` interleaved solves."""
    import bench_halfspace as bh

    from rubbercontact.halfspace import solve_sliding
    from rubbercontact.materials import GeneralizedMaxwell

    z = bh.hurst_map(n)
    p0 = bh.pressure_for_fraction(z, 1.0, 0.10)
    ref = solve_sliding(z, 1.0, GeneralizedMaxwell.elastic(bh.E), 0.0, p0, tol=1e-12,
                        max_iter=100000, options=PREVIOUS)
    solvers = {
        "ours": (lambda t: bh.run_ours(z, 1.0, p0, t, "active-set"), bh.ladder(1e-4, 1e-10)),
        "ours (previous)": (lambda t: bh.run_ours(z, 1.0, p0, t, "active-set", PREVIOUS),
                            bh.ladder(1e-4, 1e-10)),
        "Tamaas": (lambda t: bh.run_tamaas(z, 1.0, p0, t), bh.ladder(1e-6, 1e-12)),
    }
    chosen = {}
    for name, (fn, rungs) in solvers.items():
        for tol in rungs:
            p, dt, its, _ = fn(tol)
            err = float(np.linalg.norm(p - ref.pressure) / np.linalg.norm(ref.pressure))
            chosen[name] = (tol, err, its)
            if err <= target:
                break
    times = {k: [] for k in solvers}
    for _ in range(repeat):
        for name, (fn, _) in solvers.items():
            times[name].append(fn(chosen[name][0])[1])
    return {"n": n, "target": target, "repeat": repeat, "chosen": chosen,
            "median": {k: float(np.median(v)) for k, v in times.items()},
            "contact": ref.contact_fraction}


def _commit() -> str:
    out = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                         text=True, check=False, cwd=Path(__file__).parent)
    dirty = subprocess.run(["git", "status", "--porcelain", "--", "src/rubbercontact/halfspace"],
                           capture_output=True, text=True, check=False,
                           cwd=Path(__file__).parent.parent).stdout.strip()
    return out.stdout.strip() + (" + uncommitted halfspace/ changes" if dirty else "")


def bem_markdown(visco: list[dict], elastic: dict | None, info: str) -> str:
    lines = [BEM_HEADING, "", info, "",
             "Viscoelastic (SBR, 10 mm/s, 0.3 MPa, the map of the table above), three solvers "
             "interleaved in one process, medians of `runs` (previous; before and current): "
             "`previous` the solver before the "
             "2D speed-ups (`PREVIOUS` options), `before` the defaults "
             "of commit 1fba2c7 (`ROUND_BEFORE`: the single-precision cycles tighter than "
             "1e-3 on a float64 Krylov basis, the GMRES bases allocated per restart cycle, "
             "the finest hard wall + soft law started from the next grid, the one-level "
             "soft-law preconditioner at β = 4; the round's "
             "change without a switch, a law's pressure and stiffness in one pass, in both), "
             "`current` the defaults. CPU time "
             "of the process (the machine is shared: the steadier figure), wall time in "
             "brackets; FFT pairs of any precision on all grids (a multi-shift "
             "preconditioner application counts as its number of shifts); Δ the largest "
             "relative difference of μ, A, ū between current and either other, Δσ the "
             "largest relative L2 difference of the pressure maps.", "",
             "| grid | law | runs | previous CPU [s] | before CPU [s] | current CPU [s] | "
             "speed-up prev/cur | speed-up before/cur | FFT pairs (prev, before, cur) | μ | "
             "Δ(μ, A, ū) | Δσ |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in visco:
        p, b, c = r["previous"], r["before"], r["current"]
        dscal = max(max(x["dmu"], x["darea"], x["dubar"]) for x in (p, b))
        lines.append(
            f"| {r['n']}² | {r['case']} | {r['repeat']} | {p['cpu']:.2f} ({p['wall']:.1f}) | "
            f"{b['cpu']:.2f} ({b['wall']:.1f}) | {c['cpu']:.2f} ({c['wall']:.1f}) | "
            f"{p['cpu'] / c['cpu']:.1f}× | {b['cpu'] / c['cpu']:.2f}× | "
            f"{p['fft']}, {b['fft']}, {c['fft']} | {r['mu']:.5f} | {dscal:.1e} | "
            f"{max(p['dp'], b['dp']):.1e} |")
    if elastic:
        e = elastic
        lines += ["", f"Elastic hard wall, {e['n']}² self-affine map (H = 0.8) at "
                  f"{100 * e['contact']:.0f} % contact, E = 10 MPa, ν = 0.5 "
                  "(`bench_halfspace.hurst_map`): each solver at the first rung of its √10 "
                  f"tolerance ladder whose pressure is within {e['target']:g} (relative L2) of "
                  "our active set at tol 1e-12, then medians of "
                  f"{e['repeat']} interleaved solves (wall time).", "",
                  "| solver | tol | error | its | median [s] | Tamaas / this |",
                  "|---|---|---|---|---|---|"]
        tam = e["median"]["Tamaas"]
        for name, (tol, err, its) in e["chosen"].items():
            med = e["median"][name]
            lines.append(f"| {name} | {tol:.2g} | {err:.1e} | {its} | {med:.3f} | "
                         f"{tam / med:.2f} |")
    return "\n".join(lines) + "\n"


def bem_info() -> str:
    load = os.getloadavg()
    stamp = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M")
    return (f"Generated by `benchmarks/bench_maps.py --bem` ({stamp} UTC, commit {_commit()}, "
            f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores shared with "
            f"other jobs: load average {load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f} at the "
            f"start, OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}).")


def splice(path: str, heading: str, section: str) -> None:
    """Replace the section starting at ``heading`` (to the next ``## `` heading) in ``path``,
    or append it."""
    text = Path(path).read_text() if Path(path).exists() else ""
    if heading in text:
        head, rest = text.split(heading, 1)
        nxt = rest.find("\n## ")
        tail = rest[nxt + 1:] if nxt >= 0 else ""
        text = head + section + ("\n" + tail if tail else "")
    else:
        text = text.rstrip("\n") + "\n\n" + section
    Path(path).write_text(text)


def run_bem(args) -> int:
    info = bem_info()
    print(info, flush=True)
    visco = bem_viscoelastic(args.repeat, args.quick)
    elastic = bem_elastic(128 if args.quick else 512, repeat=3 if args.quick else 7)
    print(elastic, flush=True)
    load = os.getloadavg()
    info = info[:-2] + (f"; {load[0]:.1f} / {load[1]:.1f} / {load[2]:.1f} at the end, "
                        f"{datetime.datetime.now(datetime.UTC):%H:%M} UTC).")
    text = bem_markdown(visco, elastic, info)
    print(text)
    if args.output:
        splice(args.output, BEM_HEADING, text)
    return 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="128² and 256² only, one run each")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--speeds", action="store_true", help="add mu(v) at 15 speeds on 512²")
    ap.add_argument("--output", default=None,
                    help="write the tables into this Markdown file (its other sections kept)")
    ap.add_argument("--bem", action="store_true",
                    help="only the 2D BEM section: previous solver against the current one")
    args = ap.parse_args(argv)
    if args.bem:
        return run_bem(args)
    sizes = (128, 256) if args.quick else (128, 256, 512)
    repeat = 1 if args.quick else args.repeat
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    stamp = datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d %H:%M")
    rows = [bench(n, repeat) for n in sizes]
    text = "\n\n".join([
        "# Height maps: cost of each model by grid size",
        f"Generated by `benchmarks/bench_maps.py` ({stamp} UTC, commit {_commit()}, "
        f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores shared with "
        f"other jobs, load {load:.1f} at the start, "
        f"OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}). Self-affine map "
        f"H = {HURST}, rms gradient {GRADIENT}, side {SIDE} mm; SBR, {VELOCITY:g} mm/s, "
        f"{PRESSURE} MPa; medians of {repeat} runs, wall time with the process's CPU time in "
        "brackets (the machine is shared: CPU time is the steadier figure); the law's cell "
        "32², 40 loads.",
        table(rows)])
    if args.speeds:
        curve, t = speed_curve()
        end = datetime.datetime.now(datetime.UTC).strftime("%H:%M")
        wall = sum(x[0] for x in t.values())
        cpu = sum(x[1] for x in t.values())
        text += (f"\n\n{SPEEDS_HEADING}\n\n"
                 f"Run by `bench_maps.py --speeds` after the table above (ended {end} UTC), "
                 "one process on one core; the split's threshold 0.9 × the steepest octave's "
                 "rms slope along x, the cell one period (32²), 40 loads per law. Wall time "
                 f"(CPU): VHS {t['vhs'][0]:.0f} s ({t['vhs'][1]:.0f}), VHS with the "
                 f"Lennard-Jones wall {t['vhs_lj'][0]:.0f} s ({t['vhs_lj'][1]:.0f}), hybrid "
                 f"(the cell's law at every speed and the low-slope solve) {t['hybrid'][0]:.0f} s "
                 f"({t['hybrid'][1]:.0f}), mean-field {t['meanfield'][0]:.2g} s; total "
                 f"{wall / 60:.1f} min ({cpu / 60:.1f} min CPU).\n\n" + curve)
    text += "\n"
    print(text)
    if args.output:
        _write_tables(args.output, text, args.speeds)
    return 0


def _write_tables(path: str, text: str, speeds: bool) -> None:
    """Write the grid-size table (and the μ(v) section with ``--speeds``) into ``path``,
    keeping its other sections (the ``--bem`` section and the notes by hand)."""
    old = Path(path).read_text() if Path(path).exists() else ""
    keep = old.find("\n## ")
    rest = old[keep + 1:] if keep >= 0 else ""
    if speeds and SPEEDS_HEADING in rest:
        # the new μ(v) section replaces the old one
        head, tail = rest.split(SPEEDS_HEADING, 1)
        nxt = tail.find("\n## ")
        rest = head + (tail[nxt + 1:] if nxt >= 0 else "")
    Path(path).write_text(text + ("\n" + rest if rest else ""))


if __name__ == "__main__":
    raise SystemExit(main())
