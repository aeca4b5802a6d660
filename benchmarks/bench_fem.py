"""Benchmark of the FEM sliding test (issue 4).

1. Cost of one Newton iteration at a given mesh, split into assembly (residual +
   tangent, and residual only), sparse factorization and triangular solve.
2. The whole test on the paper's high-slope wave (λ = 0.0625 mm, Δ = 0.01867 mm),
   SBR, p̄ = 1 MPa, v = 10 mm/s, for a sequence of meshes (mesh convergence and cost
   vs mesh size): friction, contact fraction, mean separation, steps, Newton
   iterations, factorizations, cut-backs, wall time.

Run single-threaded::

    OMP_NUM_THREADS=1 .venv/bin/python benchmarks/bench_fem.py --meshes 30x23 60x45 120x90 \
        --json /tmp/bench_fem.json
"""

from __future__ import annotations

import argparse
import json
import platform
import subprocess
import time

import numpy as np

import rubbercontact as rc
from rubbercontact.fem.cell import CellModel
from rubbercontact.fem.constitutive import MaterialParameters
from rubbercontact.fem.contact import penalty_parameter
from rubbercontact.fem.mesh import periodic_cell
from rubbercontact.fem.solver import factorize


def iteration_cost(nx: int, ny: int, reps: int = 5, viscous_model: str = "simo") -> dict:
    surf = rc.roughness.high_slope_wave()
    par = MaterialParameters.from_material(rc.materials.sbr(), viscous_model=viscous_model)
    L0 = surf.period
    # face 2 µm below the peak: about a tenth of the face in contact
    cell = periodic_cell(L0, 0.75 * L0, nx, ny, y0=float(surf.amplitudes[0]) - 0.002)
    dt = L0 / nx / 10.0
    model = CellModel(cell, surf, par,
                      penalty_parameter(par.algorithmic_shear_modulus(dt), L0 / nx))
    st = model.new_state()
    U = np.zeros(model.n)
    # uniform compression: face fixed, top edge down by 2 % of the height
    ydof = model.dof_map[1::2]
    free = ydof >= 0
    U[ydof[free]] = -0.02 * (cell.X[free, 1] - cell.y0)
    t = {"assembly_tangent": [], "assembly_residual": [], "factorization": [], "solve": []}
    for _ in range(reps):
        t0 = time.perf_counter()
        r, K, _ = model.evaluate(U, st, dt, 0.0, L0)
        t1 = time.perf_counter()
        model.evaluate(U, st, dt, 0.0, L0, tangent=False)
        t2 = time.perf_counter()
        lu = factorize(K)
        t3 = time.perf_counter()
        lu.solve(r)
        t4 = time.perf_counter()
        for k, v in zip(t, (t1 - t0, t2 - t1, t3 - t2, t4 - t3), strict=True):
            t[k].append(v)
    out = {k: float(np.median(v)) for k, v in t.items()}
    out.update(mesh=f"{nx}x{ny}", unknowns=model.n, nnz_K=int(K.nnz),
               nnz_LU=int(lu.lu.L.nnz + lu.lu.U.nnz))
    return out


def full_test(nx: int, ny: int, periods: int, viscous_model: str = "simo",
              steps_per_period: int | None = None) -> dict:
    t0 = time.perf_counter()
    res = rc.fem.sliding_test(rc.roughness.high_slope_wave(), rc.materials.sbr(), 1.0, 10.0,
                              mesh=(nx, ny), periods=periods, viscous_model=viscous_model,
                              steps_per_period=steps_per_period)
    spp = steps_per_period or nx
    wall = time.perf_counter() - t0
    h = res.history
    fr = h["friction"][h["phase"] == 2]
    al = h["contact_fraction"][h["phase"] == 2]
    s = res.stats
    return {"mesh": f"{nx}x{ny}", "friction": res.friction,
            "contact_fraction": res.contact_fraction,
            "mean_separation_mm": res.mean_separation, "steps": s.steps,
            "newton_iterations": s.newton_iterations,
            "iterations_per_step": s.newton_iterations / s.steps,
            "factorizations": s.factorizations, "cutbacks": s.cutbacks,
            "line_search_cuts": s.line_search_cuts, "periods": s.periods,
            "steady": s.steady, "max_penetration_mm": s.max_penetration,
            "assembly_time_s": s.assembly_time, "solve_time_s": s.solve_time,
            "wall_time_s": wall, "unknowns": s.n_unknowns,
            "viscous_model": viscous_model, "steps_per_period": spp,
            "period_means": [float(np.mean(fr[i * spp:(i + 1) * spp]))
                             for i in range(len(fr) // spp)],
            "period_means_contact_fraction": [float(np.mean(al[i * spp:(i + 1) * spp]))
                                              for i in range(len(al) // spp)]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--meshes", nargs="*", default=["30x23", "60x45", "120x90"])
    ap.add_argument("--iteration-mesh", default="120x90")
    ap.add_argument("--periods", type=int, default=6)
    ap.add_argument("--json", default=None)
    ap.add_argument("--viscous-model", default="simo", choices=["simo", "reese-govindjee"])
    ap.add_argument("--steps-per-period", type=int, default=None,
                    help="default nx (one element of travel per step)")
    args = ap.parse_args()
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, check=False).stdout.strip()
    except OSError:
        commit = "?"
    report = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "commit": commit,
              "machine": f"{platform.processor() or platform.machine()}, "
                         f"python {platform.python_version()}, numpy {np.__version__}"}
    nx, ny = (int(v) for v in args.iteration_mesh.split("x"))
    report["iteration"] = iteration_cost(nx, ny, viscous_model=args.viscous_model)
    print(json.dumps(report["iteration"]), flush=True)
    report["tests"] = []
    for m in args.meshes:
        nx, ny = (int(v) for v in m.split("x"))
        r = full_test(nx, ny, args.periods, args.viscous_model, args.steps_per_period)
        report["tests"].append(r)
        print(json.dumps(r), flush=True)
        if args.json:
            with open(args.json, "w") as f:
                json.dump(report, f, indent=1)


if __name__ == "__main__":
    main()
