"""Part ``strain`` of :mod:`studies.steep_cells`: what stops the press above E∞.

The frictionless press of the stations 0+1 cell to 10 MPa (the history reduced to its
local part, :func:`rubbercontact.fem.steady_solver.local_kernel`: a static hyperelastic
contact problem, no memory, no friction) on meshes of increasing resolution, with the
barrier contact and 60 Newton iterations per step. Where it stops, the last converged
state's deformation: the stretch of the face segments, the principal stretches and the
smallest Jacobian at the quadrature points, the steepest face segment and the sharpest
turn between two segments, and the surface's radius of curvature beside the most
compressed element. If the stop came from contact switching or the line search it would
move up the load as the mesh is refined; if it came from the strain of wrapping the
crests it moves down.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

import rubbercontact as rc

from ._rows import append_row
from ._templates import render

#: (columns, rows, grading) of the meshes, coarse to fine.
STRAIN_MESHES = ((40, 30, 1.0), (80, 30, 1.0), (80, 30, 4.0), (160, 30, 4.0))
STRAIN_POINT = ("stations 0+1", 10.0)


def deformation(model, U: np.ndarray, surface) -> dict:
    """The row's figures of the state ``U`` of ``model``: the library's
    :class:`~rubbercontact.fem.deformation.Deformation` and the surface's radius of
    curvature beside the most compressed element, against the column width."""
    from dataclasses import asdict

    from rubbercontact.fem.deformation import measure_deformation

    d = measure_deformation(model, U)
    radius = 1.0 / abs(float(surface.curvatures(np.array([d.worst_x]))[0]))
    return {**asdict(d), "worst_row": d.worst_element // model.cell.nx,
            "crest_radius_mm": radius, "hx_mm": surface.period / model.cell.nx}


def run_strain(path: Path, surfaces: dict, done: set) -> None:
    """Part ``strain`` (resumable, one row per mesh)."""
    from rubbercontact.fem.newton_krylov import Counters, Endpoint, follow
    from rubbercontact.fem.options import FemOptions
    from rubbercontact.fem.setup import build_cell
    from rubbercontact.fem.steady import SteadyCell
    from rubbercontact.fem.steady_solver import _kernel, local_kernel

    name, p = STRAIN_POINT
    surf = surfaces[name]
    for nx, ny, grading in STRAIN_MESHES:
        if (nx, ny, grading) in done:
            continue
        opts = FemOptions(mesh=(nx, ny), contact="barrier", grading=grading).with_(
            steady={"newton_per_step": 60})
        setup = build_cell(surf, rc.materials.sbr(), p, 1.0, opts, sliding_plate=True)
        kern = local_kernel(_kernel(setup))
        t0 = time.process_time()
        out = follow(SteadyCell(setup.model, kern), np.zeros(setup.model.n),
                     Endpoint(kern, 0.0), Endpoint(kern, setup.load), 0.0, "face", setup.atol,
                     opts.steady, Counters(), "frictionless press")
        append_row(path, {"part": "strain", "cell": name, "pressure": p, "nx": nx, "ny": ny,
                          "grading": grading, "reached": out.reached,
                          "converged": out.converged, "reason": out.reason[:200],
                          "cpu_s": time.process_time() - t0,
                          **deformation(setup.model, out.U, surf)})


def strain_report(rows: list[dict]) -> list[str]:
    """Part ``strain``: the stop and the deformation there, mesh by mesh."""
    if not rows:
        return []
    lines = [render("steep_cells", "strain"), "",
             "| mesh | stopped at λ (p̄) | face stretch | face slope / turn | principal "
             "stretches | J min | surface radius there / hx | CPU |",
             "|---|---|---|---|---|---|---|---|"]
    for r in sorted(rows, key=lambda r: (r["nx"], r["grading"])):
        mesh = f"{r['nx']} × {r['ny']}" + (f" ×{r['grading']:g}" if r["grading"] != 1 else "")
        stop = ("converged" if r["converged"]
                else f"{r['reached']:.3g} ({r['reached'] * r['pressure']:.2g} MPa)")
        lines.append(
            f"| {mesh} | {stop} | {r['face_stretch_min']:.2f}–{r['face_stretch_max']:.2f} | "
            f"{r['face_slope_deg']:.0f}° / {r['face_turn_deg']:.0f}° | "
            f"{r['stretch_min']:.2f}–{r['stretch_max']:.2f} | {r['J_min']:.2f} | "
            f"{1e3 * r['crest_radius_mm']:.0f} µm / {1e3 * r['hx_mm']:.1f} µm | "
            f"{r['cpu_s']:.0f} s |")
    return lines + ["", render("steep_cells", "strain_footer"), ""]
