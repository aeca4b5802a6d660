"""The test cell of one FEM sliding test: mesh, material, contact penalty and load.

Shared by the steady and the transient solvers, so that both solve the same discrete
problem: the same face height, the same penalty (sized on the modulus one step of the
sliding sees) and the same convergence tolerance.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..materials.maxwell import GeneralizedMaxwell
from ..roughness.sines import SineSeries
from .barrier import barrier_law
from .cell import CellModel
from .constitutive import MaterialParameters
from .contact import penalty_parameter
from .mesh import periodic_cell
from .options import FemOptions


@dataclass(frozen=True, eq=False)
class CellSetup:
    """A discretized test cell and what sizes its numerics.

    Attributes
    ----------
    model
        Residual and tangent of the cell.
    params
        Material parameters of the finite-strain model.
    load
        Plate force per unit depth ``p̄ L0`` [N/mm].
    atol
        Newton tolerance on ``‖r‖`` [N/mm].
    dt
        Step of the viscous history [s]: one column of travel for the steady solver, one
        step of the transient's sliding (``inf`` without sliding).
    h_min
        Smallest element size [mm].
    """

    model: CellModel
    params: MaterialParameters
    load: float
    atol: float
    dt: float
    h_min: float

    @property
    def cell(self):
        return self.model.cell


def build_cell(surface: SineSeries, material: GeneralizedMaxwell, mean_pressure: float,
               velocity: float, options: FemOptions, *, mesh: tuple[int, int] | None = None,
               steps_per_period: int | None = None, sliding_plate: bool = False) -> CellSetup:
    """The cell of ``options`` (or of ``mesh``) for one test.

    ``steps_per_period`` sets the history step ``dt = L0/(steps · v)`` (default ``nx``:
    one column of travel). The face starts with its highest node 0.1 % of an element in
    the surface, so that the plate is supported from the first iteration.
    """
    nx, ny = mesh or options.mesh
    params = MaterialParameters.from_material(material, options.bulk_modulus,
                                              options.history_order, options.viscous_model)
    L0 = surface.period
    hx = L0 / nx
    barrier = None
    if options.contact == "barrier":
        # The reach is small against the face's own resolution (the smallest element,
        # and the chord sag of a segment on the most curved crest, below which gaps
        # already count as contact): points within it count as contact.
        rows = periodic_cell(L0, options.height_ratio * L0, nx, ny, grading=options.grading)
        sag = hx**2 * float(np.sum(surface.wavenumbers**2 * surface.amplitudes)) / 8.0
        scale = min(hx, float(np.diff(rows.y_nodes).min()), sag)
        barrier = barrier_law(scale, mean_pressure, options.barrier_distance,
                              options.barrier_stiffness)
        # the straight face must start above the whole surface, within the barrier's reach
        # of its crest so that it carries the plate from the first iteration
        y0 = _surface_top(surface) + 0.5 * barrier.dhat
    else:
        y0 = float(surface.heights(np.arange(nx) * hx).max()) - 1e-3 * hx
    cell = periodic_cell(L0, options.height_ratio * L0, nx, ny, grading=options.grading, y0=y0)
    spp = steps_per_period or nx
    dt = L0 / (spp * velocity) if velocity > 0 else np.inf
    # Penalty on the modulus one step sees; a test without sliding ends fully relaxed.
    mu_alg = params.algorithmic_shear_modulus(dt) if velocity > 0 else params.mu
    h_min = min(hx, float(np.diff(cell.y_nodes).min()))
    penalty = penalty_parameter(mu_alg, h_min, options.penalty_factor)
    # the rounding is sized on the penetration under the mean pressure, p̄/ε
    model = CellModel(cell, surface, params, penalty,
                      smoothing=options.contact_smoothing * mean_pressure / penalty,
                      contact_points=options.contact_points, sliding_plate=sliding_plate,
                      barrier=barrier)
    load = mean_pressure * L0
    return CellSetup(model, params, load, options.newton_tol * load, dt, h_min)


def _surface_top(surface: SineSeries) -> float:
    """The surface's highest point [mm]: every sampled local maximum (64 samples per
    shortest wave) polished by Newton on ``z' = 0``, the highest kept."""
    n = 64 * int(np.ceil(surface.period / float(np.min(surface.wavelengths))))
    x = np.arange(n) * surface.period / n
    z = surface.heights(x)
    peak = np.flatnonzero((z >= np.roll(z, 1)) & (z >= np.roll(z, -1)))
    xp = x[peak]
    for _ in range(20):
        curv = surface.curvatures(xp)
        step = np.where(curv < 0, surface.slopes(xp) / np.where(curv < 0, curv, -1.0), 0.0)
        xp = xp - np.clip(step, -surface.period / n, surface.period / n)
    return float(max(surface.heights(xp).max(), z.max()))
