"""FEM against the VHS on one sine as its slope grows: where does the non-linearity start?

Linear theory scales: multiplying the amplitude and the mean pressure by the same factor
leaves the contact fraction unchanged and multiplies the friction by it. So along the
family ``Δ ∝ m2``, ``p̄ = p_ref m2 / 1.33`` (the paper's high-slope wave at ``m2 = 1.33``)
the VHS gives one contact fraction and ``μ/m2`` = const, and any change of the FEM's
``μ_FEM/μ_VHS`` and ``A_FEM/A_VHS`` with ``m2`` is the finite-slope (kinematic and
finite-strain) non-linearity of the FEM alone. At small ``m2`` both ratios must tend to 1
(the FEM's peer test in ``tests/test_fem_sliding.py``); the paper reports the FEM slightly
*above* the VHS at small pressures on its ``m2 = 1.33`` wave (its Fig. 7A).

Wave λ = 0.0625 mm, SBR, 10 mm/s, the default (Simo) material model. Each case appends one
JSON line to ``--out`` after it finishes, and finished cases are skipped on a rerun, so the
study resumes after a kill. Run (about 10 min on one core at 60 x 45)::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies slope_nonlinearity \
        --out docs/validation/slope_nonlinearity.jsonl \
        --report docs/validation/slope_nonlinearity.md
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

from ._rows import append_row, read_rows
from ._templates import render

DESCRIPTION = ("FEM against the VHS on one sine as its "
               "slope grows: where does the non-linearity start?")

LAM = 0.0625
SLOPES = (0.1, 0.25, 0.5, 0.75, 1.0, 1.33)
M2_REF = 1.33              # the paper's high-slope wave
P_REF = (0.5, 2.0)          # mean pressure at m2 = 1.33 [MPa]; scaled with m2
VELOCITY = 10.0


def run_case(m2: float, p_ref: float, mesh: tuple[int, int]) -> dict:
    amp = m2 * np.sqrt(2) * LAM / (2 * np.pi)
    surf = rc.roughness.SineSeries([LAM], [amp])
    p = p_ref * m2 / M2_REF
    mat = rc.materials.sbr()
    vhs = rc.halfspace.solve_sliding(surf, None, mat, VELOCITY, p, n=4096)
    t0 = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        fem = rc.fem.sliding_test(surf, mat, p, VELOCITY, mesh=mesh, periods=4, solver="transient")
    return {"m2": m2, "p_ref": p_ref, "pressure": p, "mesh": list(mesh),
            "fem_friction": fem.friction, "fem_contact_fraction": fem.contact_fraction,
            "vhs_friction": vhs.friction, "vhs_contact_fraction": vhs.contact_fraction,
            "steady": fem.stats.steady, "wall_s": time.perf_counter() - t0,
            "warnings": sorted({str(w.message)[:120] for w in caught})}


def report(rows: list[dict]) -> str:
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    out = [render("slope_nonlinearity", "title"), "",
           render("slope_nonlinearity", "intro", date=f"{datetime.now(UTC):%Y-%m-%d %H:%M}",
                  commit=commit, wavelength=LAM, velocity=f"{VELOCITY:g}",
                  m2_ref=f"{M2_REF:g}"), "",
           "| p_ref [MPa] | mesh | m2 | p̄ [MPa] | VHS μ (A) | FEM μ (A) | μ FEM/VHS "
           "| A FEM/VHS | FEM wall [s] |", "|---|---|---|---|---|---|---|---|---|"]
    for r in sorted(rows, key=lambda r: (r["p_ref"], r["mesh"], r["m2"])):
        out.append(f"| {r['p_ref']:g} | {r['mesh'][0]}x{r['mesh'][1]} | {r['m2']:g} | "
                   f"{r['pressure']:.4g} | {r['vhs_friction']:.4f} "
                   f"({r['vhs_contact_fraction']:.4f}) | {r['fem_friction']:.4f} "
                   f"({r['fem_contact_fraction']:.4f}) | "
                   f"{r['fem_friction'] / r['vhs_friction']:.3f} | "
                   f"{r['fem_contact_fraction'] / r['vhs_contact_fraction']:.3f} | "
                   f"{r['wall_s']:.0f} |" + (" not steady" if not r["steady"] else ""))
    return "\n".join(out) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--out", type=Path, default=Path("slope_nonlinearity.jsonl"))
    ap.add_argument("--report", type=Path)
    ap.add_argument("--mesh", default="60x45")
    ap.add_argument("--slopes", type=float, nargs="*", default=list(SLOPES))
    ap.add_argument("--p-ref", type=float, nargs="*", default=list(P_REF))
    args = ap.parse_args(argv)
    mesh = tuple(int(v) for v in args.mesh.lower().split("x"))
    rows = read_rows(args.out)
    done = {(r["m2"], r["p_ref"], tuple(r["mesh"])) for r in rows}
    for p_ref in args.p_ref:
        for m2 in args.slopes:
            if (m2, p_ref, mesh) in done:
                continue
            row = run_case(m2, p_ref, mesh)
            append_row(args.out, row)
            rows.append(row)
    if args.report:
        args.report.write_text(report(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
