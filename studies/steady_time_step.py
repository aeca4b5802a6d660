"""The steady FEM's time step: one column of travel per history step, against finer steps.

The steady solver integrates each quadrature point's history from its upstream neighbour,
one column of travel per step (``dt = h/v``): exactly the transient test at
``steps_per_period = nx``. Its time-discretization error is measured against the transient
test at 2 and 4 steps per column, each started from the steady state (the internal
variables of the steady solution, ``streamline.branch_histories``), so only the small
difference between the discrete problems has to settle, and slid a few periods. At k > 1
steps per column the transient's period average also averages over k sub-column surface
offsets, which moves the contact area on contacts a few columns wide; the friction is the
cleaner measure of the time step.

Resumable: one JSON line per (case, k) in ``docs/validation/steady_time_step.jsonl``. About
an hour single-threaded::

    OMP_NUM_THREADS=1 .venv/bin/python -m studies steady_time_step
"""

from __future__ import annotations

import argparse
import time
import warnings
from pathlib import Path

import numpy as np

import rubbercontact as rc
from rubbercontact.fem.constitutive import ViscousState, isochoric_stress, kinematics
from rubbercontact.fem.element import deformation_gradient
from rubbercontact.fem.setup import build_cell
from rubbercontact.fem.streamline import branch_histories
from rubbercontact.fem.transient import TransientTest, _State

from ._rows import append_row, publish, read_rows
from ._templates import render

DESCRIPTION = "The steady FEM's one-column history step against 2 and 4 steps per column."

ROOT = Path(__file__).resolve().parents[1]
ROWS = ROOT / "docs" / "validation" / "steady_time_step.jsonl"
REPORT = ROOT / "docs" / "validation" / "steady_time_step.md"
PERIODS = 3
STEPS = (1, 2, 4)


def cases() -> dict[str, dict]:
    hs = rc.roughness.high_slope_wave()
    s3 = rc.roughness.section3().realizations(1, seed=2021)[0]
    return {"law cell": {"surface": hs, "p": 1.0, "v": 10.0, "mesh": (120, 23), "grading": 8.0},
            "section 3 cell": {"surface": s3, "p": 0.8, "v": 50.0, "mesh": (240, 45),
                               "grading": 8.0}}


def transient_from_steady(case: dict, steady, k: int) -> TransientTest:
    """A transient test at ``k`` steps per column whose state is the steady solution."""
    surf, mat, mesh = case["surface"], rc.materials.sbr(), case["mesh"]
    opts = rc.fem.FemOptions(mesh=mesh, grading=case["grading"])
    hx = surf.period / mesh[0]
    offset = float(np.mod(steady.sliding_distance, hx))
    tr_opts = opts.with_(solver="transient", transient={
        "steps_per_period": k * mesh[0], "periods": PERIODS, "min_periods": PERIODS,
        "steady_tol": 1e-12, "surface_offset": offset})
    test = TransientTest(surf, mat, case["p"], case["v"], tr_opts)
    sm = build_cell(surf, mat, case["p"], case["v"], opts, sliding_plate=True).model
    face = steady.state.U
    u_full = sm.asm.full_displacement(face)
    u_full[0::2] -= face[sm.plate_x]          # the plate at x = 0: the surface at shift T
    ncol = int(round((steady.sliding_distance - offset) / hx))
    uf = np.roll(u_full.reshape(mesh[1] + 1, mesh[0], 2), ncol, axis=1).reshape(-1)
    m = test.model
    U = np.zeros(m.n)
    free = m.dof_map >= 0
    U[m.dof_map[free]] = uf[free]
    F = deformation_gradient(m.asm.dNdX, uf[m.asm.edofs].reshape(-1, 4, 2))
    J, Cinv, I1 = kinematics(F)
    s_iso, _ = isochoric_stress(test.setup.params.mu, J, Cinv, I1, tangent=False)
    q = branch_histories(test.setup.params, hx / case["v"],
                         s_iso.reshape(mesh[1], mesh[0], 4, 3))
    test.state = _State(U, ViscousState(s_iso, q.reshape((-1,) + s_iso.shape)), 0.0, offset,
                        test.setup.load)
    return test


def run_case(name: str, case: dict, k: int, steady) -> dict:
    t0 = time.process_time()
    test = transient_from_steady(case, steady, k)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        test.slide()
    h = test.result().history
    spp = k * case["mesh"][0]
    n = len(h["friction"]) // spp
    return {"case": name, "steps_per_column": k,
            "friction": [float(np.mean(h["friction"][j * spp:(j + 1) * spp])) for j in range(n)],
            "contact_fraction": [float(np.mean(h["contact_fraction"][j * spp:(j + 1) * spp]))
                                 for j in range(n)],
            "steady_friction": steady.friction,
            "steady_contact_fraction": steady.contact_fraction,
            "cpu_s": time.process_time() - t0}


def report(rows: list[dict]) -> str:
    lines = [render("steady_time_step", "header", periods=PERIODS), "",
             "| cell | steps per column | μ (last period) | μ / steady − 1 | A (last period) | "
             "A / steady − 1 |", "|---|---|---|---|---|---|"]
    for r in rows:
        mu, a = r["friction"][-1], r["contact_fraction"][-1]
        lines.append(f"| {r['case']} | {r['steps_per_column']} | {mu:.5f} | "
                     f"{100 * (mu / r['steady_friction'] - 1):+.2f} % | {a:.5f} | "
                     f"{100 * (a / r['steady_contact_fraction'] - 1):+.2f} % |")
    lines += ["", render("steady_time_step", "footer")]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=DESCRIPTION)
    ap.add_argument("--rows", type=Path, default=ROWS)
    ap.add_argument("--report", type=Path, default=REPORT)
    ap.add_argument("--report-only", action="store_true")
    args = ap.parse_args(argv)
    done = {(r["case"], r["steps_per_column"]) for r in read_rows(args.rows)}
    if not args.report_only:
        for name, case in cases().items():
            if all((name, k) in done for k in STEPS):
                continue
            steady = rc.fem.steady_sliding(case["surface"], rc.materials.sbr(), case["p"],
                                           case["v"], mesh=case["mesh"],
                                           grading=case["grading"])
            for k in STEPS:
                if (name, k) not in done:
                    append_row(args.rows, run_case(name, case, k, steady))
    return publish(report(read_rows(args.rows)), args.report)
