"""How far from steady sliding are the FEM tests the validation stops after 3 periods?

The FEM sliding test runs until two successive period averages agree (friction within
1 %, contact fraction within 1 % or a quarter of one element's share of the cell), or until
``periods``. The quick validation allows 3 periods. At 50 mm/s a period of the 0.25 mm
full cell lasts 5 ms and one of the 0.0625 mm law cell 1.25 ms, while the slowest Maxwell
branch of the SBR relaxes in 11 ms: many of those tests end unsteady (the pipeline says
which; ``fem_steady`` in results.nc, ``steady`` in the law). This study reruns chosen tests
of the validation for many periods and lists every period's average, so the 3-period value
can be set against the later ones.

Cases ``KIND:V:P[:R[:NXxNY[:G]]]``: ``full`` (the three-wave cell of realization R, rows
graded x4 unless G is given, 240 steps per period) or ``law`` (the high-slope wave of
realization 0 alone, 120 x 45 graded x4 by default, 60 steps per period), speed V [mm/s],
mean pressure P [MPa]. Each case
appends one JSON line to ``--out`` when it finishes (resumable; finished cases are skipped).
Run single-threaded, e.g.::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies fem_steadiness --periods 10 \\
        law:50:0.5 full:50:0.15:0:120x90 \\
        --out docs/validation/fem_steadiness.jsonl --report docs/validation/fem_steadiness.md
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
from rubbercontact.pipeline.setup import translated_to_zero_phase

from ._rows import append_row, publish, read_rows
from ._templates import render

DESCRIPTION = "How far from steady sliding are the FEM tests the validation stops after 3 periods?"

ROOT = Path(__file__).resolve().parents[1]
SEED, REALIZATIONS = 2021, 5          # the section 3 validation's realizations
VALIDATION_PERIODS = 3                # what the quick validation allows
FULL_CELL, LAW_CELL = 0.25, 0.0625    # cell widths [mm]: section 3's period, its λ_hs


def _case(spec: str) -> dict:
    parts = spec.split(":")
    kind, v, p = parts[0], float(parts[1]), float(parts[2])
    if kind not in ("full", "law"):
        raise SystemExit(f"case {spec!r}: kind must be 'full' or 'law'")
    r = int(parts[3]) if len(parts) > 3 else 0
    mesh = parts[4] if len(parts) > 4 else ("240x90" if kind == "full" else "120x45")
    grading = float(parts[5]) if len(parts) > 5 else 4.0
    return {"kind": kind, "velocity": v, "pressure": p, "realization": r, "mesh": mesh,
            "grading": grading}


def _key(case: dict, periods: int) -> tuple:
    return (case["kind"], case["velocity"], case["pressure"], case["realization"],
            case["mesh"], case.get("grading", 4.0), case.get("viscous_model", "simo"),
            periods)


def run_case(case: dict, periods: int) -> dict:
    """Every sliding period's mean friction and contact fraction of one test."""
    real = rc.roughness.section3().realizations(REALIZATIONS, seed=SEED)[case["realization"]]
    surface = real if case["kind"] == "full" else real.partition(1.0)[0]
    spp = 240 if case["kind"] == "full" else 60
    nx, ny = (int(x) for x in case["mesh"].split("x"))
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")      # unsteadiness is what is measured here
        out = rc.fem.sliding_test(translated_to_zero_phase(surface), rc.materials.sbr(),
                                  case["pressure"], case["velocity"], mesh=(nx, ny),
                                  grading=case["grading"], periods=periods,
                                  min_periods=periods,
                                  viscous_model=case.get("viscous_model", "simo"),
                                  steps_per_period=spp, height_ratio=0.75, solver="transient")
    h = out.history
    sliding = h["phase"] == 2
    mu = h["friction"][sliding].reshape(-1, spp).mean(axis=1)
    area = h["contact_fraction"][sliding].reshape(-1, spp).mean(axis=1)
    ubar = h["mean_separation"][sliding].reshape(-1, spp).mean(axis=1)
    return {**case, "periods": periods, "friction": mu.tolist(), "contact_fraction":
            area.tolist(), "mean_separation": ubar.tolist(),
            "wall_time": time.perf_counter() - t0}


def _mesh_label(row: dict) -> str:
    grading, model = row.get("grading", 4.0), row.get("viscous_model", "simo")
    return (row["mesh"] + ("" if grading == 4.0 else f" g{grading:g}")
            + ("" if model == "simo" else f" ({model})"))


def _summary(row: dict) -> str:
    mu, area = np.array(row["friction"]), np.array(row["contact_fraction"])
    k = VALIDATION_PERIODS - 1
    late_mu, late_a = mu[k:].mean(), area[k:].mean()
    return (f"| {row['kind']} | {_mesh_label(row)} | {row['velocity']:g} | {row['pressure']:g} | "
            f"{row['realization']} | {mu[k]:.4f} ({area[k]:.4f}) | "
            f"{mu[k:].min():.4f}-{mu[k:].max():.4f} | {area[k:].min():.4f}-{area[k:].max():.4f}"
            f" | {late_mu:.4f} ({late_a:.4f}) | {100 * (mu[k] / late_mu - 1):+.1f} % / "
            f"{100 * (area[k] / late_a - 1):+.1f} % |")


def _period_s(row: dict) -> float:
    """Duration of one sliding period [s]: cell width over speed."""
    width = FULL_CELL if row["kind"] == "full" else LAW_CELL
    return width / row["velocity"]


def _drift_time(row: dict) -> float:
    """e-folding time [s] of the mean separation's approach to its final value, from the
    ratio of its period-to-period changes over the second half of the run (NaN when the
    changes do not shrink)."""
    u = np.asarray(row["mean_separation"])
    d = np.abs(np.diff(u))
    half = d.size // 2
    if half < 2 or not (d[half:] > 0).all():
        return np.nan
    slope = np.polyfit(np.arange(half, d.size), np.log(d[half:]), 1)[0]
    return -_period_s(row) / slope if slope < 0 else np.nan


def _r(block: str, **fields) -> str:
    return render("fem_steadiness", block, **fields)


def _time_scales(rows: list[dict]) -> str:
    """Why the tests settle slowly: the cell creeps under the mean friction stress."""
    mat = rc.materials.sbr()
    tau, lam = mat.relaxation_times.max(), mat.retardation_times().max()
    j_inf = 1.0 / mat.equilibrium_modulus
    ends = {v: VALIDATION_PERIODS * _period_s({"kind": "full", "velocity": v})
            for v in (10.0, 50.0)}
    creep = " and ".join(
        _r("creep_at", percent=f"{100 * float(mat.creep_compliance(t)) / j_inf:.0f}",
           velocity=f"{v:g}", time=f"{1e3 * t:.1f}") for v, t in ends.items())
    text = _r("time_scales", relaxation=f"{1e3 * tau:.1f}", retardation=f"{1e3 * lam:.1f}",
              distance=f"{VALIDATION_PERIODS * FULL_CELL:g}", creep=creep)
    drifts = [(r, _drift_time(r)) for r in rows if "mean_separation" in r]
    drifts = [(r, t) for r, t in drifts if np.isfinite(t)]
    if drifts:
        text += " " + _r("drift", runs=", ".join(
            _r("drift_run", time=f"{1e3 * t:.1f}", mesh=_mesh_label(r),
               velocity=f"{r['velocity']:g}", pressure=f"{r['pressure']:g}",
               u_first=f"{1e3 * r['mean_separation'][0]:.2f}",
               u_last=f"{1e3 * r['mean_separation'][-1]:.2f}",
               a_first=f"{r['contact_fraction'][0]:.3f}",
               a_last=f"{r['contact_fraction'][-1]:.3f}",
               shear=f"{3 * r['friction'][-1] * r['pressure'] * j_inf:.2f}")
            for r, t in drifts))
    finals: dict = {}
    for r in rows:
        if "mean_separation" in r and r["kind"] == "law":
            finals.setdefault((r.get("viscous_model", "simo"), _mesh_label(r), r["velocity"]),
                              {})[r["pressure"]] = r["mean_separation"][-1]
    pairs = [(k, u) for k, u in finals.items() if len(u) > 1]
    if pairs:
        text += " " + _r("finals", runs="; ".join(
            _r("finals_run", mesh=label, velocity=f"{v:g}",
               separations=" / ".join(f"{1e3 * u[p]:.2f}" for p in sorted(u)),
               pressures=" / ".join(f"{p:g}" for p in sorted(u)),
               trend="falls" if all(np.diff([u[p] for p in sorted(u)]) < 0) else "rises")
            for (_model, label, v), u in pairs))
    return text


def report(rows: list[dict]) -> str:
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    lines = [_r("title"), "",
             _r("intro", date=f"{datetime.now(UTC):%Y-%m-%d}", commit=commit,
                periods=VALIDATION_PERIODS), "",
             "| cell | mesh | v [mm/s] | σ0 [MPa] | r | period 3 μ (A) | μ range | A range | "
             "mean from period 3 μ (A) | period 3 vs mean |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    lines += [_summary(r) for r in rows]
    lines += ["", _time_scales(rows)]
    lines += ["", _r("every_period"), ""]
    for r in rows:
        cells = ", ".join(f"{m:.4f} ({a:.4f})" for m, a in zip(r["friction"],
                                                              r["contact_fraction"],
                                                              strict=True))
        lines.append(f"- {r['kind']} {_mesh_label(r)}, {r['velocity']:g} mm/s, "
                     f"{r['pressure']:g} MPa, realization {r['realization']} "
                     f"({r['wall_time']:.0f} s): {cells}")
        if "mean_separation" in r:
            lines.append("  - " + _r("separation_label") + " " + ", ".join(
                f"{1e3 * u:.3f}" for u in r["mean_separation"]))
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("cases", nargs="+", help="KIND:V:P[:R[:NXxNY[:G]]]")
    ap.add_argument("--periods", type=int, default=10)
    ap.add_argument("--viscous-model", choices=["simo", "reese-govindjee"], default="simo",
                    help="finite-strain viscoelastic model of the cases given")
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "validation" /
                    "fem_steadiness.jsonl")
    ap.add_argument("--report", type=Path)
    args = ap.parse_args(argv)
    if args.periods < VALIDATION_PERIODS + 1:
        raise SystemExit(f"--periods must exceed {VALIDATION_PERIODS}")
    done = {_key(r, r["periods"]) for r in read_rows(args.out)}
    for case in map(_case, args.cases):
        case["viscous_model"] = args.viscous_model
        if _key(case, args.periods) not in done:
            append_row(args.out, run_case(case, args.periods))
    text = report(read_rows(args.out))
    return publish(text, args.report)


if __name__ == "__main__":
    raise SystemExit(main())
