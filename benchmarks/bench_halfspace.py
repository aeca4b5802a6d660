"""Half-space solver benchmarks: elastic hard wall vs Tamaas and ContactMechanics; viscoelastic.

Run: ``python benchmarks/bench_halfspace.py [--quick] [--output benchmarks/halfspace.md]``.
Single-threaded (set ``OMP_NUM_THREADS=1``). Accuracy is made equal by running every solver on a
ladder of its own tolerances and keeping the first (cheapest) run whose pressure field is within
``--target`` (relative L2) of a tightly converged reference (our active-set solver at tol 1e-12).
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy.fft as sfft

import rubbercontact as rc
from rubbercontact.halfspace import (
    LennardJonesRepulsion,
    SolverOptions,
    TabulatedLaw,
    solve_sliding,
)

E, NU = 10.0, 0.5
_OB = ("OPENBLAS_CORETYPE", "OPENBLAS_L2_SIZE")
ER = E / (1 - NU**2)


# -- surfaces ------------------------------------------------------------------------------------
def sinusoid(n: int, frac: float = 0.3):
    lam, delta = 1.0, 0.01
    x = np.arange(n) * lam / n
    z = delta * np.sin(2 * np.pi * x / lam)
    p0 = np.pi * ER * delta / lam * np.sin(np.pi * frac / 2) ** 2  # Westergaard
    return z, lam, p0


def hurst_map(n: int, hurst: float = 0.8, seed: int = 1) -> np.ndarray:
    """Periodic self-affine map (isotropic PSD ∝ q^-(2+2H)), rms height 0.01 mm, L = 1 mm."""
    rng = np.random.default_rng(seed)
    q = np.sqrt(sfft.fftfreq(n)[:, None] ** 2 + sfft.rfftfreq(n)[None, :] ** 2) * n
    amp = np.zeros_like(q)
    ok = (q > 0) & (q <= n / 2)
    amp[ok] = q[ok] ** (-(1 + hurst))
    spec = amp * (rng.standard_normal(q.shape) + 1j * rng.standard_normal(q.shape))
    z = sfft.irfftn(spec, s=(n, n))
    return 0.01 * z / z.std()


def pressure_for_fraction(z, period, frac):
    """Mean pressure giving the target contact fraction (bisection on a coarse tolerance)."""
    mat = rc.materials.GeneralizedMaxwell.elastic(E)
    lo, hi = 1e-4, 10.0
    for _ in range(30):
        mid = np.sqrt(lo * hi)
        a = solve_sliding(z, period, mat, 0.0, mid, tol=1e-6).contact_fraction
        if a < frac:
            lo = mid
        else:
            hi = mid
        if hi / lo < 1.02:
            break
    return np.sqrt(lo * hi)


# -- helpers -------------------------------------------------------------------------------------
def fft_pair_time(shape, repeat=50) -> float:
    a = np.random.default_rng(0).standard_normal(shape)
    k = np.ones(sfft.rfftn(a).shape)
    best = np.inf
    for _ in range(3):
        t = time.perf_counter()
        for _ in range(repeat):
            sfft.irfftn(k * sfft.rfftn(a, workers=1), s=shape, workers=1)
        best = min(best, (time.perf_counter() - t) / repeat)
    return best


def capture_output(fn):
    """Run fn with C-level stdout/stderr captured (Tamaas logs from C++)."""
    sys.stdout.flush()
    sys.stderr.flush()
    tmp = tempfile.TemporaryFile(mode="w+b")
    saved = [os.dup(1), os.dup(2)]
    os.dup2(tmp.fileno(), 1)
    os.dup2(tmp.fileno(), 2)
    try:
        out = fn()
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for s in saved:
            os.close(s)
    tmp.seek(0)
    return out, tmp.read().decode(errors="replace")


def run_ours(z, period, p0, tol, method, options=None):
    mat = rc.materials.GeneralizedMaxwell.elastic(E)
    t = time.perf_counter()
    r = solve_sliding(z, period, mat, 0.0, p0, tol=tol, method=method, max_iter=100000,
                      options=options)
    dt = time.perf_counter() - t
    its = r.iterations if method == "pk" else r.info.get("linear_iterations", r.iterations)
    return r.pressure, dt, its, r.matvecs


def run_tamaas(z, period, p0, tol):
    import tamaas as tm

    tm.set_log_level(tm.LogLevel.info)
    if z.ndim == 1:
        model = tm.ModelFactory.createModel(tm.model_type.basic_1d, [period], [z.size])
    else:
        model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [period, period],
                                            list(z.shape))
    model.E = E
    model.nu = NU
    solver = tm.PolonskyKeerRey(model, z, tol)
    solver.max_iter = 100000
    solver.dump_freq = 10**9
    t = time.perf_counter()
    _, log = capture_output(lambda: solver.solve(p0))
    dt = time.perf_counter() - t
    its = None
    for line in reversed(log.splitlines()):
        parts = line.split()
        if parts and parts[0].isdigit():
            its = int(parts[0])
            break
    return np.array(model.traction).reshape(z.shape), dt, its, None


def run_cm(z, period, p0, pentol_rel):
    from ContactMechanics import PeriodicFFTElasticHalfSpace
    from ContactMechanics.Optimization import constrained_conjugate_gradients
    from SurfaceTopography import Topography, UniformLineScan

    if z.ndim == 1:
        sub = PeriodicFFTElasticHalfSpace((z.size,), E, physical_sizes=(period,), poisson=NU)
        topo = UniformLineScan(z, period, periodic=True)
        area_px = period / z.size
        area = period
    else:
        sub = PeriodicFFTElasticHalfSpace(z.shape, E, physical_sizes=(period, period),
                                          poisson=NU)
        topo = Topography(z, (period, period), periodic=True)
        area_px = period**2 / z.size
        area = period**2
    rms = float(np.sqrt(np.mean(z**2)))
    t = time.perf_counter()
    # tolerances passed explicitly (the defaults are absolute and loose): penetration relative
    # to the rms height, force outside contact relative to the mean force per pixel
    res = constrained_conjugate_gradients(
        sub, topo, external_force=p0 * area, pentol=pentol_rel * rms,
        forcetol=pentol_rel * p0 * area_px, thermotol=pentol_rel, maxiter=100000)
    dt = time.perf_counter() - t
    return np.asarray(res.jac).reshape(z.shape) / area_px, dt, int(res.nit), None


def ladder(loosest: float, tightest: float) -> list[float]:
    """Tolerances from ``loosest`` to ``tightest`` in steps of √10: fine enough that the first
    rung within the target is not pushed far past it (with steps of ×100 a solver just short
    of the target at one rung was timed at a hundred times tighter tolerance: issue 42)."""
    steps = int(round(2 * np.log10(loosest / tightest)))
    return [float(loosest * 10.0 ** (-0.5 * k)) for k in range(steps + 1)]


LADDERS = {
    "ours (active set)": (lambda z, L, p, t: run_ours(z, L, p, t, "active-set"),
                          ladder(1e-4, 1e-10)),
    "ours (Polonsky-Keer)": (lambda z, L, p, t: run_ours(z, L, p, t, "pk"),
                             ladder(1e-6, 1e-12)),
    "Tamaas PolonskyKeerRey": (run_tamaas, ladder(1e-6, 1e-12)),
    "ContactMechanics CCG": (run_cm, ladder(1e-6, 1e-12)),
}


def elastic_case(label, z, period, p0, target, skip=(), fft=None):
    mat = rc.materials.GeneralizedMaxwell.elastic(E)
    ref = solve_sliding(z, period, mat, 0.0, p0, tol=1e-12, max_iter=100000)
    rows = []
    for name, (fn, ladder) in LADDERS.items():
        if name in skip:
            continue
        got = None
        for tol in ladder:
            try:
                p, dt, its, mv = fn(z, period, p0, tol)
            except ImportError as exc:
                got = (name, None, None, None, None, None, f"not installed ({exc.name})")
                break
            err = float(np.linalg.norm(p - ref.pressure) / np.linalg.norm(ref.pressure))
            got = (name, tol, dt, its, mv, err, "")
            if err <= target:
                break
        rows.append(got)
        print(label, got, flush=True)
    return {"label": label, "rows": rows, "fft": fft, "contact": ref.contact_fraction}


def viscoelastic_cases(ns, fracs, velocity=10.0, repeat=5):
    """SBR on the section-3 surface, steep Lennard-Jones law and hard wall (best of ``repeat``)."""
    surf = rc.roughness.section3(phases=[0.3, 1.2, 2.5])
    mat = rc.materials.sbr()
    out = []
    # mean pressures for the target contact fractions (hard wall, N = 2^12; not timed)
    pressures = {}
    for frac in fracs:
        lo, hi = 1e-3, 100.0
        for _ in range(40):
            mid = np.sqrt(lo * hi)
            a = solve_sliding(surf, None, mat, velocity, mid, n=4096, tol=1e-6).contact_fraction
            lo, hi = (mid, hi) if a < frac else (lo, mid)
            if hi / lo < 1.03:
                break
        pressures[frac] = np.sqrt(lo * hi)
    for frac in fracs:
        for n in ns:
            for law_name, law in (("LJ law", LennardJonesRepulsion()), ("hard wall", None)):
                dt = np.inf
                for _ in range(repeat):
                    t = time.perf_counter()
                    r = solve_sliding(surf, None, mat, velocity, pressures[frac], n=n, law=law)
                    dt = min(dt, time.perf_counter() - t)
                row = dict(frac=frac, n=n, law=law_name, time=dt, iterations=r.iterations,
                           gmres=r.info.get("linear_iterations", ""),
                           matvecs=r.matvecs, contact=r.contact_fraction, friction=r.friction,
                           ubar=r.mean_separation, sigma0=pressures[frac],
                           fft=fft_pair_time((n,)), load=os.getloadavg()[0])
                print(row, flush=True)
                out.append(row)
    return out


def _fem_like_law():
    """The shape of the FEM high-slope law σ_hs(ū) (mm, MPa): the hybrid pipeline's case."""
    return TabulatedLaw(separation=[0.004, 0.008, 0.012, 0.016, 0.01867],
                        pressure=[8, 3, 1, 0.3, 0], contact_fraction=[0.6, 0.4, 0.25, 0.1, 0],
                        shear_stress=[2.5, 1.2, 0.4, 0.08, 0])


def _shared_law():
    """A soft exponential law that leaves a large share of the load to the wall."""
    u = np.linspace(0.0, 0.04, 21)
    sig = 2.0 * np.exp(-u / 0.002)
    sig[-1] = 0.0
    return TabulatedLaw(u, sig, contact_fraction=np.exp(-u / 0.002), shear_stress=0.3 * sig)


def wall_soft_cases(n=2048, reference=True):
    """LJ wall + tabulated soft law on the section-3 low-slope part (SBR): the active-set path
    timed against the previous continuation path (same answer expected)."""
    continuation = SolverOptions(wall_soft_active_set=False)  # the previous path
    mat = rc.materials.sbr()
    ls = rc.roughness.section3(phases=[2.0, 0.4, 5.1]).partition(1.0)[1]
    ls_shared = rc.roughness.section3(phases=[0.3, 1.2, 2.5]).partition(1.0)[1]
    cases = [("FEM-like", ls, _fem_like_law(), v, s0) for v in (10.0, 50.0)
             for s0 in (0.1, 0.5, 1.0, 2.0)]
    cases += [("shared", ls_shared, _shared_law(), 10.0, s0) for s0 in (0.3, 1.0, 3.0)]
    out = []
    for name, surf, tab, v, s0 in cases:
        law = LennardJonesRepulsion() + tab
        best, r = np.inf, None
        for _ in range(2):
            t = time.perf_counter()
            r = solve_sliding(surf, None, mat, v, s0, law=law, n=n)
            best = min(best, time.perf_counter() - t)
        row = dict(case=name, v=v, sigma0=s0, n=n, time=best, matvecs=r.matvecs,
                   friction=r.friction, contact=r.contact_fraction, ubar=r.mean_separation,
                   path=r.info.get("wall_soft_method", "continuation"),
                   wall=float(np.mean(law.laws[0].resolve(float(np.std(r.heights)), s0)
                                      .pressure(r.separation))) / s0)
        if reference:
            t = time.perf_counter()
            ref = solve_sliding(surf, None, mat, v, s0, law=law, n=n, options=continuation)
            row["ref_time"] = time.perf_counter() - t
            row["ref_stages"] = len(ref.info.get("continuation", []))
            row["dmu"] = abs(r.friction - ref.friction) / ref.friction
            row["darea"] = abs(r.contact_fraction - ref.contact_fraction) / ref.contact_fraction
            row["dubar"] = abs(r.mean_separation - ref.mean_separation) / ref.mean_separation
        print(row, flush=True)
        out.append(row)
    return out


def machine_info() -> str:
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, check=False).stdout.strip()
    except OSError:
        commit = "?"
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    load = os.getloadavg() if hasattr(os, "getloadavg") else ("?",)
    now = datetime.datetime.now(datetime.timezone.utc)  # noqa: UP017 - Python 3.10 support
    return (f"- date: {now:%Y-%m-%d %H:%M} UTC\n"
            f"- machine: {cpu}, {os.cpu_count()} cores, Python {platform.python_version()}, "
            f"numpy {np.__version__}\n- commit: {commit}\n"
            f"- load average at start: {load[0]:.2f} (other jobs share the 2 cores)\n"
            f"- OPENBLAS_CORETYPE/OPENBLAS_L2_SIZE: "
            f"{'set' if any(k in os.environ for k in _OB) else 'unset'} for this run; "
            f"OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}\n")


def wall_soft_markdown(rows) -> list[str]:
    if not rows:
        return []
    lines = ["", f"Wall + soft law (hybrid pipeline's case; SBR, section-3 low-slope part, "
             f"N = {rows[0]['n']}, tol 1e-8): `LennardJonesRepulsion() + TabulatedLaw(...)`. "
             "FEM-like: the tabulated law of the shape of the FEM high-slope law (wall idle or "
             "nearly); shared: an exponential soft law with the wall carrying a large share "
             "(`wall` = <σ_wall>/σ0). `time` the active-set path (best of 2), `previous` the "
             "continuation path it replaces (stages in brackets); Δ = relative differences of "
             "μ, contact fraction and ū between the two.", "",
             "| law | v [mm/s] | σ0 [MPa] | wall | time [s] | FFT pairs | previous [s] | "
             "speed-up | μ | Δμ | ΔA | Δū |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        prev = (f"{r['ref_time']:.3f} ({r['ref_stages']})" if "ref_time" in r else "")
        sp = f"{r['ref_time'] / r['time']:.0f}×" if "ref_time" in r else ""
        d = (f"{r['dmu']:.1e} | {r['darea']:.1e} | {r['dubar']:.1e}" if "dmu" in r
             else " | | ")
        lines.append(f"| {r['case']} | {r['v']:g} | {r['sigma0']:g} | {r['wall']:.2f} | "
                     f"{r['time']:.3f} | {r['matvecs']} | {prev} | {sp} | "
                     f"{r['friction']:.6f} | {d} |")
    return lines


def to_markdown(elastic, visco, target, info, wall_soft=()) -> str:
    lines = ["# Half-space solver benchmarks", "", info,
             f"Elastic hard wall: every solver run on a ladder of its own tolerances; the row is "
             f"the first run whose pressure is within {target:g} (relative L2) of a reference "
             f"(our active set at tol 1e-12). Sinusoid (λ = 1 mm, Δ = 0.01 mm, 30 % contact) "
             f"in 1D; self-affine H = 0.8 map at 10 % contact in 2D. E = {E} MPa, ν = {NU}. "
             "`its` are CG/PK iterations (Tamaas, ContactMechanics, ours PK) or GMRES "
             "iterations summed over active-set updates (ours); `ms/it` the time per iteration; "
             "`/FFT` the time per iteration divided by one rfft+irfft pair.", "",
             "| case | solver | tol | time [s] | its | ms/it | /FFT | error | ratio Tamaas/ours |",
             "|---|---|---|---|---|---|---|---|---|"]
    for case in elastic:
        tam = next((r for r in case["rows"] if r and r[0].startswith("Tamaas") and r[2]), None)
        ours = next((r for r in case["rows"] if r and r[0] == "ours (active set)"), None)
        for r in case["rows"]:
            name, tol, dt, its, _mv, err, note = r
            if dt is None:
                lines.append(f"| {case['label']} | {name} | | | | | | | {note} |")
                continue
            per = dt / its * 1e3 if its else float("nan")
            ratio = f"{tam[2] / dt:.2f}" if tam and r is ours else ""
            lines.append(f"| {case['label']} | {name} | {tol:.2g} | {dt:.3f} | {its} | "
                         f"{per:.2f} | {per / (case['fft'] * 1e3):.1f} | {err:.1e} | {ratio} |")
        lines.append(f"| {case['label']} | rfft+irfft pair | | {case['fft'] * 1e3:.3f} ms | | | "
                     f"| | |")
    lines += ["", "Viscoelastic (SBR, v = 10 mm/s, section-3 surface, tol 1e-8): steep "
              "Lennard-Jones law (default ℓ = 1e-5 h_rms) and exact hard wall; time best of "
              "5; `iterations` Newton steps (law) or active-set updates on all grids (hard "
              "wall), `GMRES` the Newton steps' GMRES iterations; `FFT pairs` counts "
              "operator applications on all grids (a multi-shift preconditioner application "
              "as 3); `load` the 1-min load average after the row.", "",
              "| contact | N | law | time [s] | iterations | GMRES | FFT pairs | "
              "time / FFT pair | μ | load |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for r in visco:
        lines.append(f"| {r['contact']:.3f} | {r['n']} | {r['law']} | {r['time']:.3f} | "
                     f"{r['iterations']} | {r.get('gmres', '')} | {r['matvecs']} | "
                     f"{r['time'] / r['fft']:.0f} | {r['friction']:.4f} | "
                     f"{r.get('load', float('nan')):.1f} |")
    lines += wall_soft_markdown(list(wall_soft))
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="small sizes only (smoke test)")
    ap.add_argument("--target", type=float, default=1e-6, help="relative L2 pressure error")
    ap.add_argument("--output", default=None, help="write the markdown table here")
    ap.add_argument("--skip-elastic", action="store_true")
    ap.add_argument("--skip-visco", action="store_true")
    ap.add_argument("--skip-wall-soft", action="store_true")
    args = ap.parse_args(argv)
    info = machine_info()
    print(info)
    elastic = []
    if not args.skip_elastic:
        ns = [2**10, 2**12] if args.quick else [2**12, 2**14, 2**16]
        for n in ns:
            z, lam, p0 = sinusoid(n)
            elastic.append(elastic_case(f"1D N=2^{int(np.log2(n))}", z, lam, p0, args.target,
                                        fft=fft_pair_time((n,))))
        for n in ([64] if args.quick else [256, 512]):
            z = hurst_map(n)
            p0 = pressure_for_fraction(z, 1.0, 0.10)
            elastic.append(elastic_case(f"2D {n}²", z, 1.0, p0, args.target,
                                        fft=fft_pair_time((n, n))))
    visco = []
    if not args.skip_visco:
        ns = [2**10, 2**12] if args.quick else [2**12, 2**14, 2**16]
        visco = viscoelastic_cases(ns, [0.05, 0.30])
    wall_soft = []
    if not args.skip_wall_soft:
        wall_soft = wall_soft_cases(n=1024 if args.quick else 2048)
    md = to_markdown(elastic, visco, args.target, info, wall_soft)
    print(md)
    if args.output:
        write_keeping_notes(args.output, md)
    return 0


#: Everything after this line of the output file is written by hand and kept.
NOTES_MARKER = "<!-- written by hand below: kept when the tables above are regenerated -->"


def write_keeping_notes(path: str, md: str) -> None:
    """Write the generated tables to ``path``, keeping the hand-written part after
    :data:`NOTES_MARKER` (the before/after tables, observations and moved facts)."""
    old = open(path).read() if os.path.exists(path) else ""
    notes = old[old.index(NOTES_MARKER):] if NOTES_MARKER in old else NOTES_MARKER + "\n"
    with open(path, "w") as fh:
        fh.write(md + "\n" + notes)


if __name__ == "__main__":
    sys.exit(main())
