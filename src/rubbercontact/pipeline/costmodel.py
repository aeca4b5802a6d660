"""What one solve of each kind costs: the measured per-point prices of ``run --check``.

:mod:`.cost` counts a run's solves and adds these up. The constants below are CPU seconds
of one process on one thread of the 2-core development machine, or factors against such a
point; ``benchmarks/cost_model.md`` records where each was measured, and
``benchmarks/examples.md`` compares the whole estimate with measured runs. The model:

- a steady FEM point costs ``FEM_POINT_S`` on the reference law cell, times the elements
  to the power ``FEM_ELEMENT_EXPONENT``, times ``1 + FEM_PRESSURE_SLOPE p / E∞`` (more
  Newton iterations as the load approaches the rubber's relaxed modulus); the
  time-stepped solver ``TRANSIENT_FACTOR`` times that; a full FEM test
  ``FULL_FEM_FACTOR`` times a point of its mesh and load; along a path of speeds by
  continuation ``CONTINUATION_FACTOR`` of a fresh point per speed; on an automatic mesh a
  point whose narrowest contact patch is too narrow is re-solved on twice the columns
  (:mod:`rubbercontact.fem`), budgeted as ``AUTO_REFINED_SHARE`` of the points;
- a half-space solve ``HALFSPACE_SOLVE_S`` at ``HALFSPACE_POINTS``, as ``n log n``;
- the law's tables, continued past the top FEM pressure with the linear law's shape,
  ``LAW_TABLE_SPEED_S`` per computed speed;
- mean-field points per model, ``MEANFIELD_POINT_S``;
- the law cell's quasi-static check ``QS_POINT_FACTOR`` times a law point,
  ``QS_GRADED_FACTOR`` on an explicit mesh graded toward its face;
- the flash temperature ``FLASH_SOLVE_FACTOR`` times a half-space model's isothermal
  solves, and ``MEANFIELD_FLASH_CURVE_S`` per mean-field μ(v);
- ``OVERHEAD_S`` of set-up per run.
"""

from __future__ import annotations

import math

# --- Measured costs: the one place (benchmarks/cost_model.md: where each was measured) ---
#: Steady FEM point on the reference mesh, load far below E∞, 10-50 mm/s [s].
FEM_POINT_S = 1.3
#: A law cell's quasi-static point (:mod:`.lawcheck`) against a law point at the same
#: pressure (the relaxed rubber indents deeper, in more continuation steps).
QS_POINT_FACTOR = 3.0
#: The same on an explicit mesh graded toward the face by more than ``QS_GRADING``: the
#: grading, not the cell's size, multiplies the relaxed press's iterations.
QS_GRADED_FACTOR = 8.5
QS_GRADING = 2.0
#: The reference mesh (nx, ny): the law cell of examples/asphalt.toml and section3.toml.
FEM_REFERENCE_MESH = (120, 23)
#: Cost against the elements ``nx ny``, as ``(nx ny / reference)^FEM_ELEMENT_EXPONENT``.
FEM_ELEMENT_EXPONENT = 1.75
#: Cost against load: ``1 + FEM_PRESSURE_SLOPE p / E∞``.
FEM_PRESSURE_SLOPE = 3.7
#: Time-stepped against steady solver.
TRANSIENT_FACTOR = 50.0
#: One speed of a path by continuation against a fresh point at 10-50 mm/s.
CONTINUATION_FACTOR = 0.5
#: Share of an automatic mesh's points re-solved on twice the columns; the re-solve is
#: priced as a fresh point on the refined mesh.
AUTO_REFINED_SHARE = 0.28
#: A full FEM test (the whole surface's cell) against a law point of its mesh and load.
FULL_FEM_FACTOR = 3.0
#: One half-space solve (one load) [s] on ``HALFSPACE_POINTS`` points, scaled as n log n.
HALFSPACE_SOLVE_S = 0.03
HALFSPACE_POINTS = 16384
#: The law's table at one computed speed [s], one task on the workers.
LAW_TABLE_SPEED_S = 1.0
#: One mean-field point per model [s]; a model not listed is priced as the strips.
MEANFIELD_POINT_S = {"meanfield": 0.001, "meanfield-hybrid": 0.004, "meanfield-strips": 0.17}
#: A half-space model's flash against its isothermal solves.
FLASH_SOLVE_FACTOR = 1.8
#: One mean-field flash μ(v) per model, run temperature and load [s].
MEANFIELD_FLASH_CURVE_S = 0.5
#: Set-up outside the solves (Python and the Dask workers' start, the surface, the
#: figures) [s].
OVERHEAD_S = 15.0
# ------------------------------------------------------------------------------------------


def fem_point_seconds(mesh: tuple[int, int], solver: str = "steady",
                      pressure: float = 0.0, modulus: float = math.inf) -> float:
    """Expected cost of one FEM sliding test [s].

    Parameters
    ----------
    mesh
        Elements (nx, ny) of the cell.
    solver
        ``"steady"`` or ``"transient"`` (``fem.solver``).
    pressure
        Mean pressure of the test [MPa]; 0 (the default) prices a light load.
    modulus
        The rubber's relaxed modulus E∞ [MPa] that ``pressure`` is measured against.

    Returns
    -------
    float
        ``FEM_POINT_S (elements / reference elements)^FEM_ELEMENT_EXPONENT
        (1 + FEM_PRESSURE_SLOPE pressure / modulus)``, times ``TRANSIENT_FACTOR`` for the
        time-stepped solver.
    """
    elements = mesh[0] * mesh[1] / (FEM_REFERENCE_MESH[0] * FEM_REFERENCE_MESH[1])
    t = FEM_POINT_S * elements ** FEM_ELEMENT_EXPONENT
    t *= 1.0 + FEM_PRESSURE_SLOPE * pressure / modulus
    return t * (TRANSIENT_FACTOR if solver == "transient" else 1.0)


def halfspace_solve_seconds(n: int) -> float:
    """Expected cost of one half-space solve (one load) on ``n`` points [s]."""
    ref = HALFSPACE_POINTS * math.log(HALFSPACE_POINTS)
    return HALFSPACE_SOLVE_S * n * math.log(n) / ref


def law_point_seconds_on(options, surface, pressure: float, modulus: float) -> float:
    """Expected cost of one fresh law FEM point [s], from the law cell's own terms: its
    :class:`~rubbercontact.fem.FemOptions`, its surface (the high-slope waves), the
    point's pressure [MPa] and the rubber's E∞ [MPa]; on an automatic mesh with the share
    of points re-solved on the refined mesh. Zero for a pressure the automatic mesh does
    not try (:mod:`rubbercontact.fem.loadrange`)."""
    from ..fem.loadrange import outside_range
    from ..fem.resolution import refined_mesh

    if options.auto and outside_range(pressure, modulus):
        return 0.0
    mesh = tuple(options.resolved(surface).mesh)
    t = fem_point_seconds(mesh, options.solver, pressure, modulus)
    if options.auto:
        m = refined_mesh(surface, options.height_ratio, options.columns_per_wave)
        t += AUTO_REFINED_SHARE * fem_point_seconds((m.nx, m.ny), options.solver, pressure,
                                                    modulus)
    return t


def law_task_seconds(options, surface, pressure: float, modulus: float, speeds: int = 1,
                     continuation: bool = False) -> float:
    """Expected cost of one law FEM task [s]: a fresh point, or a path of ``speeds`` by
    continuation (``CONTINUATION_FACTOR`` of a fresh point per speed)."""
    fresh = law_point_seconds_on(options, surface, pressure, modulus)
    return fresh * CONTINUATION_FACTOR * speeds if continuation else fresh


def quasi_static_seconds(options, surface, pressure: float, modulus: float) -> float:
    """Expected cost of the law cell's quasi-static point at ``pressure`` [s]:
    ``QS_POINT_FACTOR`` times a law point, ``QS_GRADED_FACTOR`` on an explicit mesh graded
    by more than ``QS_GRADING``."""
    graded = not options.auto and options.grading > QS_GRADING
    factor = QS_GRADED_FACTOR if graded else QS_POINT_FACTOR
    return factor * law_point_seconds_on(options, surface, pressure, modulus)


def meanfield_point_seconds(model: str) -> float:
    """Expected cost of one mean-field point of ``model`` [s] (``MEANFIELD_POINT_S``; a
    model not listed priced as the strips)."""
    return MEANFIELD_POINT_S.get(model, MEANFIELD_POINT_S["meanfield-strips"])
