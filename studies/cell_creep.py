"""How the section 3 full FEM settles at high load: period by period, for several cell heights.

Companion of ``studies/cell_height.py`` on a coarse mesh (96 columns, 16-28 rows graded
toward the face, 96 steps per period), cheap enough to slide 17 periods of the 0.25 mm cell
(85 ms at 50 mm/s, 5.2 of SBR's longest retardation times). Each test records per period
the mean friction and contact fraction and, at the period's end, the cell's bulk shear
(mean face lag / H). The validation's full FEM slides 3 periods.

The question: at 2 MPa the friction stress exceeds the relaxed shear modulus E∞/3 and the
cell shears as a whole by more than 1. Does a 3-period test stand for the steady state, and
does the steady state depend on the cell height? While the bulk creeps, the face slides
slower than the driven top by ``H dγ/dt``, so a taller cell lags more.

Resumable: one JSON line per finished test in the ``.jsonl`` next to the report. Run
single-threaded::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies cell_creep \\
        --report docs/validation/cell_creep.md
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact.pipeline.setup import translated_to_zero_phase

from ._rows import append_row, publish, read_rows
from ._templates import render

DESCRIPTION = ("How the section 3 full FEM settles at high "
               "load: period by period, for several cell heights.")

COLUMNS = 96
#: H/L0 -> (rows, grading): the face row stays 2.9-3.4 um
CELLS = {0.75: (16, 8.0), 1.5: (22, 16.0), 3.0: (28, 32.0)}
#: (p̄ [MPa], H/L0, periods): long runs on the paper's and a doubled cell, 3 periods on a
#: quadrupled one (costlier per period)
CASES = [(2.0, 0.75, 17), (0.8, 0.75, 17), (2.0, 1.5, 17), (0.8, 1.5, 17),
         (2.0, 3.0, 3), (0.8, 3.0, 3)]
VELOCITY = 50.0
SEED = 2021


def run_case(p: float, ratio: float, periods: int, realization: int = 0) -> dict:
    """One coarse sliding test of section 3 (seed 2021), per-period averages."""
    mat = rc.materials.sbr()
    surf = translated_to_zero_phase(
        rc.roughness.section3().realizations(realization + 1, seed=SEED)[realization])
    rows, grading = CELLS[ratio]
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")     # unsteady / sheared: that is what is measured
        out = rc.fem.sliding_test(surf, mat, p, VELOCITY, mesh=(COLUMNS, rows),
                                  height_ratio=ratio, periods=periods, min_periods=periods,
                                  steps_per_period=COLUMNS, grading=grading, solver="transient")
    h = out.history
    slide = h["phase"] == 2
    per = out.stats.periods

    def by_period(x):
        return np.asarray(x)[slide].reshape(per, COLUMNS)

    return {"p": p, "ratio": ratio, "periods": per, "realization": realization,
            "friction": by_period(h["friction"]).mean(axis=1).tolist(),
            "contact_fraction": by_period(h["contact_fraction"]).mean(axis=1).tolist(),
            "bulk_shear": (-by_period(h["face_shift"])[:, -1] / out.height).tolist(),
            "period_ms": 1e3 * surf.period / VELOCITY,
            "g_inf": mat.equilibrium_modulus / 3, "wall_time": time.perf_counter() - t0}


def report(rows: list[dict]) -> str:
    heights = [render("cell_creep", "height_first" if k == 0 else "height", ratio=f"{r:g}",
                      rows=n, grading=f"{g:g}")
               for k, (r, (n, g)) in enumerate(CELLS.items())]
    cell = rc.roughness.section3().period
    lines = [
        render("cell_creep", "title"),
        "",
        render("cell_creep", "intro", seed=SEED, velocity=f"{VELOCITY:g}", columns=COLUMNS,
               heights=", ".join(heights), cell=f"{cell:g}",
               period=f"{1e3 * cell / VELOCITY:g}"),
        "",
        "| p̄ [MPa] | H/L0 | μ (A) after 3 periods | μ (A) at the end | periods | γ at the end |",
        "|---|---|---|---|---|---|",
    ]
    ordered = sorted(rows, key=lambda r: (-r["p"], r["ratio"]))
    for r in ordered:
        mu, a, g = (r[k] for k in ("friction", "contact_fraction", "bulk_shear"))
        lines.append(f"| {r['p']:g} | {r['ratio']:g} | {mu[2]:.3f} ({a[2]:.4f}) | "
                     f"{mu[-1]:.3f} ({a[-1]:.4f}) | {r['periods']} | {g[-1]:.2f} |")
    lines.append("")
    for r in ordered:
        mu, a, g = (np.asarray(r[k]) for k in ("friction", "contact_fraction", "bulk_shear"))
        tau = mu[-1] * r["p"]
        shear = dict(tau=f"{tau:.2f}", shear=f"{tau / r['g_inf']:.2f}")
        lines += [render("cell_creep", "case_title", pressure=f"{r['p']:g}",
                         ratio=f"{r['ratio']:g}", periods=r["periods"],
                         minutes=f"{r['wall_time'] / 60:.1f}"), "",
                  render("cell_creep", "settled", **shear,
                         mu_change=f"{100 * (mu[-1] / mu[2] - 1):+.1f}",
                         area_change=f"{100 * (a[-1] / a[2] - 1):+.1f}")
                  if r["periods"] > 3 else render("cell_creep", "period3", **shear), "",
                  "| period | t [ms] | μ | A | γ |", "|---|---|---|---|---|"]
        for k in range(r["periods"]):
            lines.append(f"| {k + 1} | {(k + 1) * r['period_ms']:.0f} | {mu[k]:.3f} | "
                         f"{a[k]:.4f} | {g[k]:.3f} |")
        lines.append("")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--report", type=Path, required=True,
                    help="Markdown report; finished tests go to the .jsonl beside it")
    args = ap.parse_args(argv)
    store = args.report.with_suffix(".jsonl")
    done = {(r["p"], r["ratio"], r["periods"]) for r in read_rows(store)}
    for p, ratio, periods in CASES:
        if (p, ratio, periods) not in done:
            append_row(store, run_case(p, ratio, periods))
    return publish(report(read_rows(store)), args.report)


if __name__ == "__main__":
    sys.exit(main())
