"""The steady sliding test: press with the viscous memory on, refine, report in the
plate's gauge.

Protocol (each stage a homotopy or a Newton solve of :mod:`.newton_krylov`):

1. *Press* on the coarsest mesh of the nested iteration (:mod:`.multilevel`): the load
   from 0 to ``p̄ L0`` in adaptive steps, with the full upstream memory of steady
   sliding at ``v``: friction, the shifted contact and the bulk shear grow with the
   load. The face is held (``"face"`` gauge, see :mod:`.steady`), so the bulk shear
   moves the plate, not the contact. Where the load path stops (a flat or folding
   load-height curve on steep cells), the press goes on by the plate's height
   (:mod:`.press`). If that fails too, the cell is pressed frictionless (the history
   reduced to its local part) and the memory is switched on afterwards by a second
   homotopy.
2. *Refine*: the solution interpolated onto the finer mesh and solved there; where the
   plain Newton fails, a Newton homotopy from the interpolated state.
3. *Gauge*: the solution translated so that the plate is at ``x = 0``: exactly the
   ``"top"``-gauge steady state on the surface shifted by the plate's lead ``T``, which
   the transient test reaches at one element of travel per step when started at that
   surface offset (``stats.surface_offset``).

A solve can start from a neighbouring one instead (:class:`SteadyState`, e.g. the
previous speed or load of a sweep): the homotopy then runs from that problem to this
one on the finest mesh, and only if it fails from the press.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..materials.maxwell import GeneralizedMaxwell
from ..roughness.sines import SineSeries
from .deformation import measure_deformation
from .multilevel import coarse_meshes, prolong
from .newton_krylov import BudgetSpent, Counters, Endpoint, PathResult, follow
from .options import FemOptions
from .press import HeightPress, PressOutcome
from .setup import CellSetup, build_cell
from .steady import SteadyCell, SteadyEvaluation
from .streamline import StreamlineKernel, streamline_kernel

#: Smallest step of the repair homotopy of a refinement (:func:`_refine`): a prolonged
#: state that needs shorter steps is far from the fine solution, and the coarse-to-fine
#: path then presses the fine mesh from the start instead. Measured on
#: examples/captif_road.toml's 1 MPa / 10 mm/s cell, 128 x 19 -> 256 x 19: the repair takes
#: 4 steps to λ = 1, none shorter than 1/4.
REPAIR_MIN_STEP = 1.0 / 64


@dataclass(frozen=True, eq=False)
class SteadyState:
    """A converged steady solution that can start a neighbouring solve.

    Attributes
    ----------
    mesh
        Its mesh ``(nx, ny)``.
    U
        Unknowns in the ``"face"`` gauge on the surface at shift 0.
    kernel
        Its history kernel.
    load
        Its plate load [N/mm].
    """

    mesh: tuple[int, int]
    U: np.ndarray
    kernel: StreamlineKernel
    load: float


@dataclass
class SteadySolution:
    """The converged steady state in the ``"top"`` gauge, and how it was reached."""

    setup: CellSetup
    U: np.ndarray
    ev: SteadyEvaluation
    shift: float                  # the surface's shift under the cell [mm] (see _to_top_gauge)
    state: SteadyState            # the "face" gauge solution, for the next solve
    counters: Counters
    path: list[str] = field(default_factory=list)


class SteadyFailure(Exception):
    """The steady solver did not converge; ``tried`` says what it did."""

    def __init__(self, reason: str, tried: list[str], counters: Counters) -> None:
        super().__init__(reason)
        self.reason, self.tried, self.counters = reason, tried, counters


def local_kernel(kernel: StreamlineKernel) -> StreamlineKernel:
    """The history reduced to a point's own stress (weight ``h₀``), with the row means
    relaxed: a static, frictionless problem pressed as in steady sliding."""
    spec = np.full_like(kernel.spectrum, kernel.weight)
    spec[0] = 0.0
    return StreamlineKernel(spec, kernel.nx, kernel.weight)


def _kernel(setup: CellSetup) -> StreamlineKernel:
    return streamline_kernel(setup.params, setup.dt, setup.cell.nx)


def _press(setup: CellSetup, kernel: StreamlineKernel, options: FemOptions,
           counters: Counters) -> np.ndarray:
    """The steady state at the full load, from the undeformed cell, on ``setup``'s mesh.

    The load is raised with the full viscous memory in place; where that path stops, the
    press goes on from its last state with the plate's height as the parameter
    (:mod:`.press`); if that fails too, the cell is pressed frictionless
    (:func:`local_kernel`) and the memory switched on after.
    """
    name = f"{setup.cell.nx}x{setup.cell.ny}"
    cell = SteadyCell(setup.model, kernel)
    U0 = np.zeros(setup.model.n)
    load = setup.load
    press = follow(cell, U0, Endpoint(kernel, 0.0), Endpoint(kernel, load), 0.0, "face",
                   setup.atol, options.steady, counters, f"press {name}")
    if press.converged:
        return press.U
    by_height = _press_by_height(setup, cell, press, options, counters)
    if by_height.converged:
        return by_height.U
    local = local_kernel(kernel)
    plain = follow(cell, U0, Endpoint(local, 0.0), Endpoint(local, load), 0.0, "face",
                   setup.atol, options.steady, counters, f"frictionless press {name}")
    if not plain.converged:
        raise SteadyFailure(_with_strain(plain, setup), counters.tried, counters)
    memory = follow(cell, plain.U, Endpoint(local, load), Endpoint(kernel, load), 0.0, "face",
                    setup.atol, options.steady, counters, f"memory {name}")
    if not memory.converged:
        raise SteadyFailure(_with_strain(memory, setup), counters.tried, counters)
    return memory.U


def _with_strain(path: PathResult, setup: CellSetup) -> str:
    """The stop of ``path`` and the strain of the last state it reached: on steep cells
    above E∞ the stop is the strain of wrapping the crests (:mod:`.deformation`)."""
    return (f"{path.reason}; at λ = {path.reached:.3g}: "
            f"{measure_deformation(setup.model, path.U).describe()}")


def _press_by_height(setup: CellSetup, cell: SteadyCell, press: PathResult,
                     options: FemOptions, counters: Counters) -> PressOutcome:
    """The press continued from where the load path stopped, by the plate's height.

    The first height step is a quarter of the travel the load path's secant stiffness
    predicts for the rest of the load (2 % of the surface's peak-to-valley height if the
    load path did not start); the smallest is 1e-6 of that height.
    """
    m = setup.model
    pv = float(np.ptp(m.surface.heights(m.X_face[:, 0])))
    travel = -float(press.U[m.plate])
    first = 0.02 * pv
    if press.reached > 0 and travel > 0:
        first = min(first, 0.25 * travel * (1.0 - press.reached) / press.reached)
    hp = HeightPress(cell, setup.load, setup.atol, options.steady, counters)
    label = f"height press {m.cell.nx}x{m.cell.ny} from λ = {press.reached:.4g}"
    try:
        out = hp.run(press.U, max(first, 1e-4 * pv), 1e-6 * pv)
    except BudgetSpent as spent:
        counters.tried.append(f"{label} ({spent})")
        raise
    counters.tried.append(f"{label}: {out.steps} heights"
                          + (", converged" if out.converged else f" ({out.reason})"))
    return out


def _refine(coarse: CellSetup, U: np.ndarray, fine: CellSetup, options: FemOptions,
            counters: Counters) -> np.ndarray | None:
    """The coarse solution carried to the finer mesh and solved there (None: failed)."""
    m = fine.model
    kern = _kernel(fine)
    cell = SteadyCell(m, kern)
    V = prolong(coarse.model, U, m, 0.0)
    # The interpolated Q1/P0 field is not incompressible element by element (pointwise
    # J varies inside a coarse element): relax the interior with the face and the plate
    # held, then release them. The relaxation is a Newton homotopy from the interpolated
    # state, like the release below: its first step (λ = 1) is the plain Newton, and where
    # that fails (on a steep cell its line search stalls: the long steps invert elements,
    # the short ones do not lower the merit) it walks the residual down in steps instead
    # of releasing from an unrepaired state. Measured on examples/captif_road.toml's 1 MPa
    # / 10 mm/s cell, 128 x 19 -> 256 x 19: the plain repair and the release failed after
    # 187 Newton iterations and the fine mesh was pressed from the start, 719 in the whole
    # test; the homotopy repairs in 4 steps and releases in 2, 104 Newton, 301 in all.
    held = np.concatenate([m.bx, m.by, [m.plate, m.plate_x]])
    holding = cell.holding(held)
    start = holding.evaluate(V, 0.0, fine.load, "top").r
    repair = follow(holding, V, Endpoint(kern, fine.load, start), Endpoint(kern, fine.load),
                    0.0, "top", fine.atol,
                    replace(options.steady, min_step=max(options.steady.min_step,
                                                         REPAIR_MIN_STEP)),
                    counters, f"repair {m.cell.nx}x{m.cell.ny}", first_step=1.0)
    # Releasing the face moves the contact set; a plain Newton from the repaired state
    # can fail to find its way (the line search stalls at the contact edges). The Newton
    # homotopy r(U) = (1 − λ) r(U₀) starts exactly at the repaired state and walks the
    # residual down in steps; its first step (λ = 1) is that plain Newton.
    bias = cell.evaluate(repair.U, 0.0, fine.load, "face").r
    path = follow(cell, repair.U, Endpoint(kern, fine.load, bias), Endpoint(kern, fine.load),
                  0.0, "face", fine.atol, options.steady, counters,
                  f"release {m.cell.nx}x{m.cell.ny}", first_step=1.0)
    return path.U if path.converged else None


def _coarse_to_fine(surface, material, p, v, options: FemOptions, counters: Counters
                    ) -> tuple[CellSetup, np.ndarray]:
    """The press on the coarsest mesh, refined mesh by mesh; the finest's solution."""
    nx, ny = options.mesh
    per = options.steady.coarse_elements
    min_nx = (max(int(np.ceil(per * surface.period / surface.wavelengths[0])),
                  options.steady.coarse_columns) if per else nx)
    levels = coarse_meshes(nx, ny, min_nx, levels=8)
    setup = build_cell(surface, material, p, v, options, mesh=levels[0], sliding_plate=True)
    U = _press(setup, _kernel(setup), options, counters)
    for mesh in levels[1:]:
        fine = build_cell(surface, material, p, v, options, mesh=mesh, sliding_plate=True)
        V = _refine(setup, U, fine, options, counters)
        # the coarse start was not close enough: press on this mesh
        U = V if V is not None else _press(fine, _kernel(fine), options, counters)
        setup = fine
    return setup, U


def _to_top_gauge(setup: CellSetup, kernel: StreamlineKernel, U: np.ndarray
                  ) -> tuple[np.ndarray, SteadyEvaluation, float]:
    """The ``"face"`` solution ``U`` as the ``"top"`` solution it is, exactly: with the
    plate at ``T``, ``U`` translated by ``−T`` is the steady state of the cell whose top is
    held at ``x = 0``, on the surface shifted by ``T`` (the transient test's steady state at
    the sliding distances ``T + k h``)."""
    model = setup.model
    T = float(U[model.plate_x])
    xdofs = model.dof_map[0::2]
    xdofs = np.unique(xdofs[xdofs >= 0])
    V = U.copy()
    V[xdofs] -= T
    ev = SteadyCell(model, kernel).evaluate(V, T, setup.load, "top")
    return V, ev, T


def solve_steady(surface: SineSeries, material: GeneralizedMaxwell, mean_pressure: float,
                 velocity: float, options: FemOptions, start: SteadyState | None = None
                 ) -> SteadySolution:
    """Solve one steady sliding test (inputs checked by the caller).

    Raises
    ------
    SteadyFailure
        No converged state (every stage stopped, or the Newton budget was spent); its
        ``tried`` lists every stage.
    """
    counters = Counters()
    try:
        setup, U = _solve(surface, material, mean_pressure, velocity, options, start, counters)
    except BudgetSpent as spent:
        # the stage that spent it is the last one tried (each records itself on the way out)
        reason = counters.tried[-1] if counters.tried else str(spent)
        raise SteadyFailure(reason, counters.tried, counters) from None
    kern = _kernel(setup)
    UA, ev, shift = _to_top_gauge(setup, kern, U)
    state = SteadyState(tuple(options.mesh), U, kern, setup.load)
    return SteadySolution(setup, UA, ev, shift, state, counters, list(counters.tried))


def _solve(surface, material, mean_pressure: float, velocity: float, options: FemOptions,
           start: SteadyState | None, counters: Counters) -> tuple[CellSetup, np.ndarray]:
    """The converged ``"face"``-gauge unknowns on the finest mesh: from the neighbour
    ``start`` if it is on this mesh and its path converges, else pressed coarse to fine."""
    setup, U = None, None
    if start is not None and tuple(start.mesh) == tuple(options.mesh):
        setup = build_cell(surface, material, mean_pressure, velocity, options,
                           sliding_plate=True)
        kern = _kernel(setup)
        path = follow(SteadyCell(setup.model, kern), start.U,
                      Endpoint(start.kernel, start.load), Endpoint(kern, setup.load), 0.0,
                      "face", setup.atol, options.steady, counters, "from the neighbour",
                      first_step=1.0)
        U = path.U if path.converged else None
    if U is None:
        setup, U = _coarse_to_fine(surface, material, mean_pressure, velocity, options,
                                   counters)
    return setup, U
