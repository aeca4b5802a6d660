"""The mean-field (Persson) model against the project's VHS BEM (issue 28).

The BEM solves the same linear problem exactly; the mean-field theory replaces it by a
statistical closure. On the same surfaces, speeds and loads this study measures the
theory's error in friction and contact area, for the modelling choices of
:mod:`rubbercontact.meanfield` (the friction's ``S(q)`` and how a discrete wave is weighted)
and for the defaults:

0. One sine, the exact 1D limit: Westergaard's contact area and the patch spectrum's
   friction (:mod:`rubbercontact.meanfield.patches`) against the BEM, five loads and speeds.
1. 1D multi-wave surfaces: the three-wave section 3 surface, the Table 2 asphalt, the CAPTIF
   fit (octaves 0.25–8 mm of the measured profiles, as examples/captif_road.toml), and four
   random octave ladders with m2 ≤ 0.6 per wave; SBR at 1, 10, 50 and 500 mm/s; four loads
   chosen so that the theory's contact fraction is 2, 6, 20 and 45 %; the BEM averaged over
   8 random-phase realizations, 32 on the random ladders (the theory sees only the spectrum).
2. A self-affine 1D profile spanning 4 decades (1 µm – 10 mm), the BEM at N = 2^18 on two
   realizations and at N = 2^20 on one (the grid convergence).
3. ``meanfield-hybrid`` against the windowed hybrid (``hybrid.windowing``) with the same
   stand-in law, the VHS linear law of the high-slope wave (no FEM), on section 3, Table 2
   and a surface whose high-slope wave is 16 times shorter than the low-slope ones.
4. A 2D isotropic self-affine map against the 2D BEM.
5. Where the strips' friction is off at 500 mm/s: the BEM's and the strips' dissipation and
   pressure variance by wavenumber band on one ladder, and on its three longest waves by
   pairs and together (:mod:`._meanfield_bands`).

Each case appends one JSON line to ``--rows`` (BEM results, the loads and the surfaces);
finished cases are skipped on a rerun. The report is rendered from the rows with the
current theory (cheap), so ``--report-only`` re-renders it. Run (about 1.5 h on one core:
45 min for the one 2^20 solve, 40 min for the multi-wave cases)::

    OMP_NUM_THREADS=1 python -m studies meanfield \
        --captif /work/shared/data/real_surfaces
"""

from __future__ import annotations

import argparse
import subprocess
import time
import warnings
from datetime import UTC, datetime
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact import meanfield as mf
from rubbercontact.roughness import SineSeries

from ._meanfield_bands import run_bands, run_layer, run_patches, run_triplets, run_truncated
from ._meanfield_cases import (
    AREAS,
    HYBRID_AREAS,
    SEPARATION,
    SINE_LOADS,
    SINE_SPEEDS,
    SPEEDS,
    VARIANTS,
    load_for_area,
    make_map,
    one_sine,
    random_ladder,
    self_affine_profile,
    separated_hybrid,
    separation_series,
    westergaard_p_star,
)
from ._meanfield_report import report
from ._rows import append_row, publish, read_rows

DESCRIPTION = "The mean-field (Persson) model against the VHS BEM: friction and area errors."

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "docs" / "validation"
SBR = rc.materials.sbr()
REALIZATIONS, SEED = 8, 1
#: Realizations of the random ladders in all (part ``more``: the ones after the first
#: REALIZATIONS, at the same loads, so the BEM means are known to a third of the first
#: eight's standard error, below the 15 % target's scale).
LADDER_REALIZATIONS = 32
RANDOM = ((6, 11), (8, 3), (8, 21), (10, 5))      # (waves, seed) of the random ladders
SELF_AFFINE = {"length": 10.0, "lam_min": 1e-3, "hurst": 0.8, "rolloff": 4, "slope": 0.7}
SA_POINTS = ((10.0, 0.05), (50.0, 0.05))           # (speed, theory's area)
#: Smaller broadband profiles at every target speed: (name, parameters, grid points).
BROADBAND = (("H = 0.5, 2 decades", {"length": 10.0, "lam_min": 0.1, "hurst": 0.5,
                                     "rolloff": 4, "slope": 0.5}, 2**13),
             ("H = 0.8, 3 decades", {"length": 10.0, "lam_min": 0.01, "hurst": 0.8,
                                     "rolloff": 4, "slope": 0.5}, 2**15))
MAP = {"n": 512, "length": 4.0, "hurst": 0.8, "rolloff": 4, "kmax": 64, "slope": 0.5}
MAP_SEEDS = (1, 2)
SPEED_CURVE = (0.1, 1.0, 10.0, 50.0, 500.0, 5000.0)  # mm/s, Table 2 at one load
SPEED_LOAD = 0.4                                     # MPa


def _key(row: dict) -> tuple:
    return (row["kind"], row["case"], row["v"], row.get("target"), row.get("n"),
            row.get("seed"))


def _bem_average(reals, period, v, p, n) -> dict:
    t0 = time.perf_counter()
    out = [rc.halfspace.solve_sliding(r, period, SBR, v, p, n=n) for r in reals]
    return {"bem_mu": [o.friction for o in out], "bem_A": [o.contact_fraction for o in out],
            "bem_time": (time.perf_counter() - t0) / len(out)}


def captif_series(directory: Path) -> SineSeries:
    """The CAPTIF fit of examples/captif_road.toml: octaves 0.15–8 mm of 16 mm windows."""
    files = sorted(Path(directory).glob("captif_*.dat"))
    if not files:
        raise SystemExit(f"--captif {directory}: no captif_*.dat profiles there")
    prof = rc.io.read_profiles(files, format="captif", window=16.0, despike=True)
    lam = rc.roughness.octave_wavelengths(0.15, 8.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", rc.roughness.RoughnessWarning)
        return rc.roughness.fit_hdc(prof, wavelengths=lam)


def surfaces_1d(captif: Path | None) -> dict[str, tuple[SineSeries, int]]:
    """``{name: (series, n)}`` of the multi-wave 1D cases."""
    out = {"section 3": (rc.roughness.section3(), 4096),
           "Table 2": (rc.roughness.asphalt_ac8(), 16384)}
    if captif is not None:
        out["CAPTIF fit"] = (captif_series(captif), 16384)
    for m, seed in RANDOM:
        out[f"random {m} waves (seed {seed})"] = (random_ladder(m, seed),
                                                   16384 if m <= 8 else 65536)
    return out


def run_1d(rows_path: Path, done: set, captif: Path | None) -> None:
    for name, (surf, n) in surfaces_1d(captif).items():
        reals = surf.realizations(REALIZATIONS, SEED)
        for v in SPEEDS:
            for target in AREAS:
                row = {"kind": "1d", "case": name, "v": v, "target": target, "n": n}
                if _key(row) in done:
                    continue
                p = load_for_area(mf.PSD.from_sines(surf), SBR, v, target)
                row.update(p=p, R=REALIZATIONS, surface=surf.as_dict(),
                           **_bem_average(reals, surf.period, v, p, n))
                append_row(rows_path, row)


def run_sine(rows_path: Path, done: set) -> None:
    """One sine (the exact 1D limit) at loads given as fractions of Westergaard's ``p*``."""
    surf = one_sine()
    lam = float(surf.wavelengths[0])
    for v in SINE_SPEEDS:
        for x in SINE_LOADS:
            row = {"kind": "sine", "case": "one sine", "v": v, "target": x, "n": 8192}
            if _key(row) in done:
                continue
            p = x * westergaard_p_star(surf, SBR, v)
            t0 = time.perf_counter()
            res = rc.halfspace.solve_sliding(surf, lam, SBR, v, p, n=8192)
            row.update(p=p, surface=surf.as_dict(), bem_mu=[res.friction],
                       bem_A=[res.contact_fraction], bem_time=time.perf_counter() - t0)
            append_row(rows_path, row)


def run_separation(rows_path: Path, done: set) -> None:
    """Elastic (v = 0) two- and four-wave profiles at the theory's areas, 8 realizations."""
    for name, lams, n in SEPARATION:
        surf = separation_series(lams)
        for target in AREAS:
            row = {"kind": "separation", "case": name, "v": 0.0, "target": target, "n": n}
            if _key(row) in done:
                continue
            p = load_for_area(mf.PSD.from_sines(surf), SBR, 0.0, target)
            row.update(p=p, R=REALIZATIONS, surface=surf.as_dict(),
                       **_bem_average(surf.realizations(REALIZATIONS, SEED), surf.period, 0.0,
                                      p, n))
            append_row(rows_path, row)


def run_hybrid(rows_path: Path, done: set) -> None:
    from rubbercontact.hybrid.law import linear_law
    from rubbercontact.hybrid.tasks import halfspace_task

    for name, surf, n in (("Table 2", rc.roughness.asphalt_ac8(), 16384),
                          ("section 3", rc.roughness.section3(), 4096),
                          ("separated ×16", separated_hybrid(), 4096)):
        hs, ls = surf.partition(1.0)
        for v in (10.0, 50.0):
            todo = [t for t in HYBRID_AREAS if _key({"kind": "hybrid", "case": name, "v": v,
                                                     "target": t, "n": n}) not in done]
            if not todo:
                continue
            table = linear_law(hs, SBR, v)
            for target in todo:
                p = load_for_area(mf.PSD.from_sines(surf), SBR, v, target)
                win, t0 = [], time.perf_counter()
                for r in surf.realizations(REALIZATIONS, SEED):
                    d = halfspace_task(r.partition(1.0)[1].as_dict(), surf.period,
                                       SBR.as_dict(), v, p, n=n, interface_law=table,
                                       hs_window=float(hs.period))
                    win.append((float(d["friction"]), float(d["contact_fraction"])))
                row = {"kind": "hybrid", "case": name, "v": v, "target": target, "n": n,
                       "p": p, "R": REALIZATIONS, "surface": surf.as_dict(), "law": table,
                       "win_mu": [w[0] for w in win], "win_A": [w[1] for w in win],
                       "win_time": (time.perf_counter() - t0) / len(win),
                       **_bem_average(surf.realizations(REALIZATIONS, SEED), surf.period, v,
                                      p, n)}
                append_row(rows_path, row)


def run_2d(rows_path: Path, done: set) -> None:
    for v in (10.0, 50.0):
        for target in AREAS[:3]:
            for seed in MAP_SEEDS:
                row = {"kind": "2d", "case": "self-affine map", "v": v, "target": target,
                       "n": MAP["n"], "seed": seed}
                if _key(row) in done:
                    continue
                z = make_map(seed=seed, **MAP)
                psd = mf.PSD.from_map(z, MAP["length"])
                p = load_for_area(psd, SBR, v, target)
                t0 = time.perf_counter()
                res = rc.halfspace.solve_sliding(z, MAP["length"], SBR, v, p)
                row.update(p=p, map=MAP, bem_mu=[res.friction], bem_A=[res.contact_fraction],
                           bem_time=time.perf_counter() - t0)
                append_row(rows_path, row)


def run_more(rows_path: Path, done: set) -> None:
    """The random ladders' realizations ``REALIZATIONS + 1 … LADDER_REALIZATIONS`` (the same
    seeded stream, so together with the ``1d`` rows the first ``LADDER_REALIZATIONS``), at
    the loads of their ``1d`` rows; the report pools the two (:func:`pool_realizations`)."""
    first = {_key(r): r for r in read_rows(rows_path) if r["kind"] == "1d"}
    for m, seed in RANDOM:
        surf = random_ladder(m, seed)
        name, n = f"random {m} waves (seed {seed})", 16384 if m <= 8 else 65536
        reals = surf.realizations(LADDER_REALIZATIONS, SEED)[REALIZATIONS:]
        for v in SPEEDS:
            for target in AREAS:
                row = {"kind": "1d-more", "case": name, "v": v, "target": target, "n": n}
                base = first.get(_key({**row, "kind": "1d"}))
                if _key(row) in done or base is None:
                    continue
                row.update(p=base["p"], R=len(reals),
                           **_bem_average(reals, surf.period, v, base["p"], n))
                append_row(rows_path, row)


def pool_realizations(rows: list[dict]) -> list[dict]:
    """``rows`` with each ``1d-more`` row's realizations appended to its ``1d`` row (same
    case, speed, load and grid) and the ``1d-more`` rows dropped."""
    more = {_key({**r, "kind": "1d"}): r for r in rows if r["kind"] == "1d-more"}
    out = []
    for r in rows:
        if r["kind"] == "1d-more":
            continue
        extra = more.get(_key(r)) if r["kind"] == "1d" else None
        if extra is not None and np.isclose(extra["p"], r["p"]):
            r = {**r, "R": r["R"] + extra["R"], "bem_mu": r["bem_mu"] + extra["bem_mu"],
                 "bem_A": r["bem_A"] + extra["bem_A"]}
        out.append(r)
    return out


def _self_affine_row(row: dict, params: dict) -> dict:
    """``row`` (its ``n``, ``seed``, ``v``, ``target``) with the BEM solved on the
    self-affine profile of ``params`` at the load where the theory's area is ``target``."""
    z, psd = self_affine_profile(n=row["n"], seed=row["seed"], **params)
    p = load_for_area(psd, SBR, row["v"], row["target"])
    t0 = time.perf_counter()
    res = rc.halfspace.solve_sliding(z, params["length"], SBR, row["v"], p)
    return {**row, "p": p, "params": params, "bem_mu": [res.friction],
            "bem_A": [res.contact_fraction], "bem_time": time.perf_counter() - t0}


def run_self_affine(rows_path: Path, done: set, sizes: tuple[int, ...]) -> None:
    """Both speeds at N = 2^18 on two realizations; the reference ``sizes`` (2^20: 45 min
    per solve here) on the first realization at the first speed only."""
    for i, (v, target) in enumerate(SA_POINTS):
        for n, seed in ((2**18, 1), (2**18, 2), *((s, 1) for s in sizes if i == 0)):
            row = {"kind": "selfaffine", "case": "self-affine 4 decades", "v": v,
                   "target": target, "n": n, "seed": seed}
            if _key(row) not in done:
                append_row(rows_path, _self_affine_row(row, SELF_AFFINE))


def run_broadband(rows_path: Path, done: set) -> None:
    """Self-affine profiles over 2 and 3 decades at the four speeds, 2 realizations each."""
    for name, params, n in BROADBAND:
        for v in SPEEDS:
            for target in AREAS[:3]:
                for seed in (1, 2):
                    row = {"kind": "broadband", "case": name, "v": v, "target": target,
                           "n": n, "seed": seed}
                    if _key(row) not in done:
                        append_row(rows_path, _self_affine_row(row, params))


def run_pressure_histogram(rows_path: Path, done: set) -> None:
    """The BEM pressure distribution pooled over realizations, for P(σ) of the theory."""
    m, seed = RANDOM[1]
    row = {"kind": "pressure", "case": f"random {m} waves (seed {seed})", "v": 10.0,
           "target": 0.2, "n": 16384}
    if _key(row) in done:
        return
    surf = random_ladder(m, seed)
    p = load_for_area(mf.PSD.from_sines(surf), SBR, 10.0, 0.2)
    sig = np.concatenate([rc.halfspace.solve_sliding(r, surf.period, SBR, 10.0, p,
                                                     n=16384).pressure
                          for r in surf.realizations(REALIZATIONS, SEED)])
    edges = np.linspace(0.0, np.quantile(sig[sig > 0], 0.995), 61)
    hist, _ = np.histogram(sig[sig > 0], bins=edges)
    row.update(p=p, surface=surf.as_dict(), edges=edges.tolist(),
               density=(hist / (sig.size * np.diff(edges))).tolist())
    append_row(rows_path, row)


def run_spectrum(rows_path: Path, done: set) -> None:
    """Where the BEM dissipates: ``μσ0 = Σ_k var σ_k (−k Im M)`` pooled in octave bands
    centred on the waves, and above the roughness's cut-off."""
    m, seed = RANDOM[3]
    surf = random_ladder(m, seed)
    q = np.sort(surf.wavenumbers)
    edges = np.concatenate([[0.0], q * 2**-0.5, [q[-1] * 2**0.5, np.inf]])
    for v in (1.0, 500.0):
        row = {"kind": "spectrum", "case": f"random {m} waves (seed {seed})", "v": v,
               "target": 0.06, "n": 65536}
        if _key(row) in done:
            continue
        p = load_for_area(mf.PSD.from_sines(surf), SBR, v, 0.06)
        bands, mus, areas = np.zeros(edges.size - 1), [], []
        for r in surf.realizations(4, SEED):
            res = rc.halfspace.solve_sliding(r, surf.period, SBR, v, p, n=65536)
            mus.append(res.friction)
            areas.append(res.contact_fraction)
            sk = np.fft.rfft(res.pressure) / res.pressure.size
            k = 2 * np.pi * np.arange(sk.size) / surf.period
            m_k = 2.0 / (np.maximum(k, 1e-300) * SBR.complex_modulus(k * v) / 0.75)
            diss = np.where(k > 0, 2 * np.abs(sk) ** 2 * (-k * m_k.imag), 0.0) / p
            diss[-1] /= 2                                   # Nyquist has no twin
            idx = np.digitize(k, edges) - 1
            bands += np.bincount(idx, weights=diss, minlength=bands.size)[:bands.size] / 4
        row.update(p=p, surface=surf.as_dict(), band_edges=edges[1:-1].tolist(),
                   bem_bands=bands.tolist(), bem_mu=mus, bem_A=areas)
        append_row(rows_path, row)


def run_speed(rows_path: Path, done: set) -> None:
    """μ(v) at one load on Table 2: the BEM at six speeds over 5 decades."""
    surf = rc.roughness.asphalt_ac8()
    for v in SPEED_CURVE:
        row = {"kind": "speed", "case": "Table 2", "v": v, "target": None, "n": 16384,
               "p": SPEED_LOAD}
        if _key(row) in done:
            continue
        row.update(R=REALIZATIONS, surface=surf.as_dict(),
                   **_bem_average(surf.realizations(REALIZATIONS, SEED), surf.period, v,
                                  SPEED_LOAD, 16384))
        append_row(rows_path, row)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--captif", type=Path, default=None,
                    help="directory of the CAPTIF profiles (captif_*.dat); omitted: no "
                         "CAPTIF case")
    ap.add_argument("--rows", type=Path, default=OUT / "meanfield.jsonl")
    ap.add_argument("--report", type=Path, default=OUT / "meanfield.md")
    ap.add_argument("--parts",
                    default="sine,separation,1d,hybrid,2d,pressure,spectrum,speed,"
                            "broadband,selfaffine,bands,more")
    ap.add_argument("--selfaffine-sizes", default=str(2**20),
                    help="grid sizes of the 4-decade profile's reference solves (comma list)")
    ap.add_argument("--report-only", action="store_true")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    if not args.report_only:
        args.rows.parent.mkdir(parents=True, exist_ok=True)
        done = {_key(r) for r in read_rows(args.rows)}
        parts = set(args.parts.split(","))
        if "sine" in parts:
            run_sine(args.rows, done)
        if "separation" in parts:
            run_separation(args.rows, done)
        if "1d" in parts:
            run_1d(args.rows, done, args.captif)
        if "more" in parts:
            run_more(args.rows, done)
        if "hybrid" in parts:
            run_hybrid(args.rows, done)
        if "2d" in parts:
            run_2d(args.rows, done)
        if "pressure" in parts:
            run_pressure_histogram(args.rows, done)
        if "spectrum" in parts:
            run_spectrum(args.rows, done)
        if "speed" in parts:
            run_speed(args.rows, done)
        if "broadband" in parts:
            run_broadband(args.rows, done)
        if "bands" in parts:
            run_bands(args.rows, done, _key)
            run_truncated(args.rows, done, _key)
            run_layer(args.rows, done, _key)
            run_patches(args.rows, done, _key)
            run_triplets(args.rows, done, _key)
        if "selfaffine" in parts:
            sizes = tuple(int(s) for s in args.selfaffine_sizes.split(",") if s)
            run_self_affine(args.rows, done, sizes)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    text = report(pool_realizations(read_rows(args.rows)), figures=args.report.parent,
                  date=f"{datetime.now(UTC):%Y-%m-%d %H:%M}", commit=commit,
                  wall=time.perf_counter() - t0, variants=VARIANTS)
    return publish(text, args.report)
