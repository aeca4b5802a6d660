"""Eq. 28 against the phase-averaged full FEM, with the VHS as a control variate.

The hybrid predicts the friction of a random-phase surface *on average over the phases*;
the validation compares it with the mean of the full FEM over 10 realizations. On the
section 3 surface the FEM varies by 20-40 % between realizations at one load (the phase
of the high-slope wave against the low-slope crests), so a 10-realization mean carries a
sampling error of several per cent, and eq. 28's 90 % interval at 10 mm/s spans 1.9-16.2 %
(VALIDATION.md). More FEM realizations cost about 400 s each per load.

The VHS solves the same surface exactly in the linear theory, costs 0.05 s, and tracks the
FEM realization by realization (both see the same crests). So the FEM's phase average is
estimated with the VHS as a control variate: for each load,

    E[X_FEM] ≈ mean_N(X_VHS) + mean_R(X_FEM − X_VHS),      X = μ or A,

with the VHS over N realizations (the first R of which are the FEM's, same seed) and the
difference over the R realizations that have a full FEM. The estimate is unbiased for any
N ≥ R; its variance is var(X_FEM − X_VHS)/R + var(X_VHS)/N instead of var(X_FEM)/R. The
hybrids are averaged over the same N realizations. Eq. 28 is then evaluated exactly as in
VALIDATION.md (mean curves interpolated at 4 areas log-spaced over the range every model
covers). The 90 % interval is a two-sample bootstrap: the R FEM realizations and the N
cheap ones are resampled independently (2000 resamples).

``make validate`` puts the phase-averaged row into VALIDATION.md's eq. 28 table
(``compare.phase_average_data``, ``eq28_phase_averaged``); this study adds the mean curves,
the spreads that make the estimate work, and its convergence in N. Every solve goes
through the validation's cache (``--cache``; the FEM and the law come
from there or from ``docs/validation/reference-cache``, the cheap models are computed and
cached), so a rerun or a killed run resumes. Run (about 6 min per velocity on 2 cores with
N = 1000, once the FEM is in the cache; 9000 cached half-space solves)::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies phase_average --velocities 10 50 \\
        --report docs/validation/phase_average.md

``--extended`` adds eq. 28 over the validation's extended loads (the paper's area range);
``--law-min-creep-times 5`` makes the hybrids read a law whose FEM points each slid 5
longest retardation times (built through the cache; at 10 mm/s the full FEM's 3 periods
already slide 4.6 of them, so law and FEM are then both settled; at 50 mm/s see
``studies/settled_loads.py``)::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies phase_average --velocities 10 \\
        --extended --law-min-creep-times 5 --report docs/validation/phase_average_settled_10mms.md
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from datetime import UTC, datetime
from pathlib import Path
from types import SimpleNamespace

import numpy as np

import rubbercontact as rc
from rubbercontact.pipeline import make_runner

from . import _compare as compare
from . import _validation_report as vreport
from . import validate
from ._rows import publish
from .fem_reference_mesh import _mesh
from .sampling_study import creep_settled_law

DESCRIPTION = "Eq. 28 against the phase-averaged full FEM, with the VHS as a control variate."

ROOT = Path(__file__).resolve().parents[1]
SHOWN = ("hybrid-windowed", "hybrid", "vhs")


def run(velocities, n: int, workers: int, cache: Path, law: Path | None = None):
    """The validation's section 3 run at ``velocities`` (from the cache; the hybrids read
    ``law`` if given), its phase data and its config."""
    cfg = validate.case_config("section3", "quick", workers, cache,
                               ROOT / "results" / "phase_average")
    data = cfg.model_dump(mode="json", exclude_none=True)
    data.update(velocities=[float(v) for v in velocities])
    if law is not None:
        data["law"] = {"file": str(law)}
    cfg = rc.config.parse_config(data, source="section3 (quick)")
    ds = rc.pipeline.run(cfg, runner=make_runner(cfg, progress="log"))
    return ds, compare.phase_average_data(ds, cfg, n), cfg


def extended_lines(extended: dict, resamples: int) -> list[str]:
    """Eq. 28 over the validation's extended loads (``compare.EXTENDED_LOADS``)."""
    out = ["## Over the paper's area range (the validation's extended loads)", "",
           "| v [mm/s] | loads | areas | " + " | ".join(SHOWN) + " |",
           "|---|---|---|" + "---|" * len(SHOWN)]
    for v, data in extended.items():
        top = float(data["pressures"].max())
        for label, d in (("all", data), (f"below {top:g} MPa", compare.below_load(data, top))):
            e, ci = compare.eq28_phase_averaged({v: d}, resamples)[v]
            lo, hi = compare.phase_area_range(d)
            out.append(f"| {v:g} | {label} | {lo:.3f}-{hi:.3f} | " + " | ".join(
                f"{100 * e[m]:.1f} % ({vreport.interval_text(*ci[m], resamples)})"
                if m in ci else "-" for m in SHOWN) + " |")
    return out + [""]


def _spread(data: dict) -> list[str]:
    """Per load: the FEM's spread, the FEM − VHS difference's, and each estimate's error."""
    fem_a, fem_mu = data["fem"]
    vhs_a, vhs_mu = data["paired"]["vhs"]
    win_mu = data["paired"]["hybrid-windowed"][1]
    r, n = fem_a.shape[0], data["all"]["vhs"][0].shape[0]
    lines = ["| σ0 [MPa] | s.d. μ_FEM | s.d. (μ_FEM − μ_VHS) | corr(μ_FEM, μ_VHS) | "
             "corr(μ_FEM, μ_windowed) | s.e. of mean μ_FEM: plain | phase-averaged | "
             "s.d. A_FEM | s.d. (A_FEM − A_VHS) |", "|---|---|---|---|---|---|---|---|---|"]
    for k, p in enumerate(data["pressures"]):
        mu, d = fem_mu[:, k], fem_mu[:, k] - vhs_mu[:, k]
        # the estimate's variance, the covariance of the paired R inside the N included
        c_all = data["all"]["vhs"][1][:, k]
        se_cv = np.sqrt(d.var(ddof=1) / r + c_all.var(ddof=1) / n
                        + 2 * np.cov(d, vhs_mu[:, k])[0, 1] / n)
        lines.append(f"| {p:g} | {mu.std(ddof=1):.4f} | {d.std(ddof=1):.4f} | "
                     f"{np.corrcoef(mu, vhs_mu[:, k])[0, 1]:.3f} | "
                     f"{np.corrcoef(mu, win_mu[:, k])[0, 1]:.2f} | "
                     f"{mu.std(ddof=1) / np.sqrt(r):.4f} | {se_cv:.4f} | "
                     f"{fem_a[:, k].std(ddof=1):.4f} | "
                     f"{(fem_a[:, k] - vhs_a[:, k]).std(ddof=1):.4f} |")
    return lines


def _subset(data: dict, n: int) -> dict:
    return {**data, "all": {m: tuple(x[:n] for x in xs) for m, xs in data["all"].items()}}


def report(ds, phase_data: dict, resamples: int, law_note: str = "") -> str:
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True).stdout.strip()
    plain = compare.eq28_first(ds)
    phase = compare.eq28_phase_averaged(phase_data, resamples)
    n = next(iter(phase_data.values()))["all"]["vhs"][0].shape[0]
    out = ["# Eq. 28 against the phase-averaged full FEM (VHS as control variate)", "",
           f"Generated by `studies/phase_average.py` "
           f"({datetime.now(UTC).strftime('%Y-%m-%d %H:%M UTC')}, commit {commit}). "
           "Section 3, quick level (the validation's meshes, law and loads 0.15 / 0.35 / "
           "0.8 MPa). *Plain*: every model averaged over the R realizations that have a full "
           "FEM, as in VALIDATION.md (90 % interval: paired bootstrap over the R). "
           f"*Phase-averaged*: the hybrids and the VHS over N = {n} realizations (the "
           "first R the same), the FEM as mean_N(VHS) + mean_R(FEM − VHS) (see the "
           "script's docstring; 90 % interval: the R and the N resampled independently, "
           f"{resamples} resamples). The paper's 2.9 % / 7.1 % are for its hybrid (here "
           "`hybrid`; `hybrid-windowed` is this package's reading of the same law) over 5 "
           "realizations and 10 target areas 0.01-0.1." + law_note, ""]
    for v, data in phase_data.items():
        r = data["fem"][0].shape[0]
        fem_time = float(np.nansum(ds["wall_time"].sel(model="fem", velocity=v).values))
        _, e_plain, ci_plain = plain[v]
        e_phase, ci_phase = phase[v]
        out += [f"## {v:g} mm/s (R = {r} full-FEM realizations, {fem_time:.0f} s of FEM)", "",
                f"| model | eq. 28, plain (R = {r}) | 90 % interval | eq. 28, phase-averaged "
                f"(N = {n}) | 90 % interval | paper |", "|---|---|---|---|---|---|"]
        for m in SHOWN:
            paper = (f"{100 * compare.PAPER_E[v]:.1f} %" if m == "hybrid"
                     and v in compare.PAPER_E else "")
            out.append(f"| {m} | {100 * e_plain[m]:.1f} % | "
                       f"{vreport.interval_text(*ci_plain[m])} % | "
                       f"**{100 * e_phase[m]:.1f} %** | "
                       f"{vreport.interval_text(*ci_phase[m], resamples)} % | {paper} |")
        conv = [(k, compare.eq28_of_curves(
            compare.phase_mean_curves(_subset(data, k))["phase"], SHOWN))
            for k in (r, 25, 50, 100, 200, 500, n) if r <= k <= n]
        curves = compare.phase_mean_curves(data)
        fem_a, fem_mu = curves["phase"]["fem"]
        out += ["", "At equal load (phase-averaged, per load "
                + " / ".join(f"{p:g}" for p in data["pressures"]) + " MPa): " + "; ".join(
                    f"{m} μ " + " / ".join(f"{100 * (x / y - 1):+.1f}" for x, y in
                                           zip(curves["phase"][m][1], fem_mu, strict=True))
                    + " %, A " + " / ".join(f"{100 * (x / y - 1):+.1f}" for x, y in
                                            zip(curves["phase"][m][0], fem_a, strict=True))
                    + " %" for m in SHOWN) + " against the FEM."]
        out += ["", "Convergence in N (the phase-averaged error with the first N cheap "
                "realizations): " + "; ".join(
                    f"N = {k}: " + " / ".join(f"{100 * e[m]:.1f}" for m in SHOWN) + " %"
                    for k, e in dict(conv).items()) + " (" + " / ".join(SHOWN) + ").", "",
                "Mean curves, μ (A) per load:", "",
                "| σ0 [MPa] | FEM plain | FEM phase-averaged | VHS plain | VHS N | "
                "windowed plain | windowed N | hybrid plain | hybrid N |",
                "|---|---|---|---|---|---|---|---|---|"]
        for k, p in enumerate(data["pressures"]):
            cells = [f"{curves[kind][m][1][k]:.3f} ({curves[kind][m][0][k]:.4f})"
                     for m in ("fem", "vhs", "hybrid-windowed", "hybrid")
                     for kind in ("plain", "phase")]
            out.append(f"| {p:g} | " + " | ".join(cells) + " |")
        out += ["", "Why the control variate works: per load, the spread over the R "
                "realizations.", "", *_spread(data), ""]
    return "\n".join(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--velocities", type=float, nargs="+", default=[10.0, 50.0])
    ap.add_argument("--realizations", type=int, default=compare.PHASE_REALIZATIONS,
                    help="N: realizations of the cheap models (the VHS and the hybrids)")
    ap.add_argument("--resamples", type=int, default=2000)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--cache", type=Path, default=ROOT / ".validation-cache")
    ap.add_argument("--reference-cache", type=Path, default=validate.REFERENCE_CACHE)
    ap.add_argument("--report", type=Path, default=None)
    ap.add_argument("--law-min-creep-times", type=float, default=None,
                    help="the hybrids read a law whose FEM points slide this many longest "
                         "retardation times (built through the cache, as "
                         "sampling_study.py --law-min-creep-times does)")
    ap.add_argument("--extended", action="store_true",
                    help="add eq. 28 over the validation's extended loads (its full FEM "
                         "there comes from the reference cache)")
    args = ap.parse_args(argv)
    validate.seed_cache(args.reference_cache, args.cache)
    law = None
    if args.law_min_creep_times is not None:
        law = creep_settled_law(SimpleNamespace(
            velocities=args.velocities, workers=args.workers, cache=args.cache,
            outdir=ROOT / "results" / "phase_average" / "law",
            law_min_creep_times=args.law_min_creep_times), *_mesh("240x45:g8", 4.0))
    ds, phase_data, cfg = run(args.velocities, args.realizations, args.workers, args.cache,
                              law)
    text = report(ds, phase_data, args.resamples, "" if law is None else (
        f" Here the hybrids read a creep-settled law: every FEM point slid "
        f"{args.law_min_creep_times:g} longest retardation times."))
    if args.extended:
        text += "\n" + "\n".join(extended_lines(
            compare.extended_phase_data(cfg, phase_data), args.resamples))
    return publish(text, args.report)


if __name__ == "__main__":
    sys.exit(main())
