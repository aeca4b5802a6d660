"""The result of an FEM sliding test, shared by the steady and the transient solvers.

Definitions
-----------
* ``v > 0``: the rubber moves in +x relative to the surface (the surface moves in −x
  under the rubber at rest). Friction ``μ = −F_x/(p̄ L0)`` with ``F_x`` the horizontal
  contact force on the rubber; it is ``> 0``.
* Contact fraction: share of the period ``L0`` over which the face is in contact, each
  abscissa counted once (so at most 1 also where the face folds over itself).
* Mean separation ``ū = (1/L0) ∮ y dx`` under the deformed face, from the mean plane of
  ``z`` (``<z> = 0``).
* Bulk shear: the face's mean horizontal lag behind the plate over the cell height.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any

import numpy as np

#: Mean shear strain of the cell above which a test warns (see :func:`bulk_shear_message`).
BULK_SHEAR_LIMIT = 1.0
#: The study behind the bulk-shear warning.
BULK_SHEAR_STUDY = "docs/validation/cell_creep.md"


def bulk_shear_message(bulk_shear: float, mean_pressure: float, velocity: float,
                       solver: str) -> str:
    """The warning of a test whose cell sheared as a whole by more than the limit."""
    tail = ("its result depends on the sliding distance until the creep has settled "
            "(fem.min_creep_times, or the steady solver)" if solver == "transient" else
            "the contact area may stop growing with the load there")
    return (f"FEM sliding test (p̄ = {mean_pressure:g} MPa, v = {velocity:g} mm/s): the cell "
            f"sheared as a whole by {bulk_shear:.2f} > {BULK_SHEAR_LIMIT:g} under a friction "
            f"stress above E∞/3; {tail} ({BULK_SHEAR_STUDY})")


#: Penetration of the surface between face nodes, in element widths, beyond which a test
#: reports an impaled face (see :func:`.contact.segment_penetration`).
SEGMENT_PENETRATION_LIMIT = 0.5


def impaled_message(penetration: float, width: float, mean_pressure: float,
                    velocity: float) -> str:
    """The warning of a face that an asperity passed through between two nodes."""
    return (f"FEM sliding test (p̄ = {mean_pressure:g} MPa, v = {velocity:g} mm/s): the face "
            f"is impaled, the surface passes through it between nodes by {penetration:.3g} mm "
            f"({penetration / width:.1f} element widths); the friction and the contact "
            f"fraction are not meaningful: refine the mesh")


@dataclass(frozen=True)
class PressureProfile:
    """Contact-face state at the end of the test (arrays along the face nodes).

    Attributes
    ----------
    x
        Current abscissa of the face nodes in the surface frame, ``(x + s) mod L0``,
        sorted [mm].
    pressure
        Contact pressure (normal force / current tributary length) [MPa].
    y
        Current height of the face nodes [mm].
    surface_height
        ``z(x)`` [mm].
    """

    x: np.ndarray
    pressure: np.ndarray
    y: np.ndarray
    surface_height: np.ndarray


@dataclass(frozen=True)
class SolverStats:
    """Work done and quality indicators of one test.

    Attributes
    ----------
    solver
        ``"steady"``, ``"transient"``, or ``"transient (fallback)"``.
    status
        ``"ok"``, or what went wrong on the way (e.g. why the steady solve fell back).
    steady
        The result is a steady state (steady solver: converged; transient: successive
        period averages agreed).
    bulk_shear
        ``|mean face x-displacement − plate| / H`` at the end.
    impaled
        The surface passed through the face between two nodes by more than
        :data:`SEGMENT_PENETRATION_LIMIT` element widths (while sliding, for the
        transient test; the warning :func:`impaled_message`): friction and contact
        fraction are not meaningful.
    patch_columns
        Steady solver: the narrowest contact patch in columns (``inf`` without patch
        edges; NaN: not measured, transient).
    under_resolved
        ``patch_columns`` is below ``FemOptions.patch_columns`` (:mod:`.resolution`).
    refined
        The automatic mesh was refined (1.5x or 2x the columns) after the first solve's check.

    Notes
    -----
    The attributes above are shared by both solvers. Steady solver:
    ``krylov_iterations``, ``continuation_steps``, ``tried`` (one line per stage),
    ``surface_offset`` (the surface's shift under the cell, mod one column [mm]),
    ``factorization_time`` (the part of ``solve_time`` that formed and factorized the
    preconditioner; the rest is GMRES with its matrix-free products).
    Transient: ``steps``, ``cutbacks``, ``line_search_cuts``, ``periods``,
    ``period_change`` / ``period_area_change`` (relative change of μ / A over the last
    period), ``bulk_shear_change`` (over the last period).
    """

    solver: str
    newton_iterations: int
    factorizations: int
    wall_time: float            # [s]
    assembly_time: float        # [s]
    solve_time: float           # [s] factorizations and linear solves
    n_unknowns: int
    steady: bool
    max_penetration: float      # [mm], at the face's contact points
    max_segment_penetration: float  # [mm], between nodes (see contact.segment_penetration)
    bulk_shear: float = np.nan
    status: str = "ok"
    impaled: bool = False
    krylov_iterations: int = 0
    continuation_steps: int = 0
    tried: tuple[str, ...] = ()
    surface_offset: float = 0.0
    factorization_time: float = np.nan   # [s] steady: tangent formed and factorized
    steps: int = 0
    cutbacks: int = 0
    line_search_cuts: int = 0
    periods: int = 0
    period_change: float = np.nan
    period_area_change: float = np.nan
    bulk_shear_change: float = np.nan
    patch_columns: float = np.nan
    under_resolved: bool = False
    refined: bool = False

    def as_dict(self) -> dict[str, Any]:
        """Plain values; an undefined float (NaN) is None so the dict is valid JSON."""
        out = {k: getattr(self, k) for k in self.__dataclass_fields__}
        out["tried"] = list(self.tried)
        return {k: None if isinstance(v, float) and not np.isfinite(v) else v
                for k, v in out.items()}


@dataclass(frozen=True)
class SlidingTestResult:
    """Result of an FEM sliding test (steady state, or the last steady period's averages).

    Attributes
    ----------
    friction
        ``μ`` [-].
    shear_stress
        ``Δτ = μ p̄`` [MPa].
    contact_fraction
        ``α`` [-].
    mean_separation
        ``ū`` [mm].
    mean_pressure, velocity
        Inputs ``p̄`` [MPa], ``v`` [mm/s].
    pressure_profile
        Face state at the end.
    history
        Transient: per step ``time`` [s], ``sliding_distance`` [mm], ``phase`` (0 press,
        1 settle, 2 slide), ``friction``, ``friction_top`` (from the top-edge reaction),
        ``contact_fraction``, ``mean_separation`` [mm], ``plate_displacement`` [mm],
        ``load`` [MPa], ``max_penetration`` [mm], ``newton_iterations``, ``face_shift``
        [mm]. Steady: empty (its stages are in ``stats.tried``).
    stats
        Solver statistics.
    state
        Steady solver: the solution that can start a neighbouring solve (see
        :func:`rubbercontact.fem.steady_sliding`'s ``start``); None otherwise.
    """

    friction: float
    shear_stress: float
    contact_fraction: float
    mean_separation: float
    mean_pressure: float
    velocity: float
    pressure_profile: PressureProfile
    history: dict[str, np.ndarray]
    stats: SolverStats
    width: float
    height: float
    mesh: tuple[int, int]
    material: dict = field(default_factory=dict)
    surface: dict = field(default_factory=dict)
    element_coordinates: np.ndarray | None = None   # (n_el, 4, 2) deformed, final [mm]
    element_stress: np.ndarray | None = None        # (n_el, 3) Cauchy [σxx, σyy, σxy] [MPa]
    sliding_distance: float = 0.0                   # final s [mm]
    state: Any = None

    def to_dataset(self):
        """The result as an :class:`xarray.Dataset` (units in ``attrs``)."""
        import xarray as xr

        h = self.history
        units = {"time": "s", "sliding_distance": "mm", "phase": "", "friction": "1",
                 "friction_top": "1", "contact_fraction": "1", "mean_separation": "mm",
                 "plate_displacement": "mm", "load": "MPa", "max_penetration": "mm",
                 "segment_penetration": "mm", "newton_iterations": "", "face_shift": "mm"}
        data_vars = {f"history_{k}": ("step", np.asarray(v), {"units": units.get(k, "")})
                     for k, v in h.items() if k != "time"}
        p = self.pressure_profile
        data_vars["profile_pressure"] = ("face_node", p.pressure, {"units": "MPa"})
        data_vars["profile_y"] = ("face_node", p.y, {"units": "mm"})
        data_vars["profile_surface_height"] = ("face_node", p.surface_height, {"units": "mm"})
        for name, val, unit in (("friction", self.friction, "1"),
                                ("shear_stress", self.shear_stress, "MPa"),
                                ("contact_fraction", self.contact_fraction, "1"),
                                ("mean_separation", self.mean_separation, "mm"),
                                ("mean_pressure", self.mean_pressure, "MPa"),
                                ("velocity", self.velocity, "mm/s")):
            data_vars[name] = ((), float(val), {"units": unit})
        coords = {"face_x": ("face_node", p.x, {"units": "mm"})}
        if "time" in h:
            coords["step"] = np.arange(len(h["time"]))
            coords["time"] = ("step", h["time"], {"units": "s"})
        attrs = {"model": "rubbercontact.fem", "solver": self.stats.solver,
                 "width_mm": self.width, "height_mm": self.height, "mesh": list(self.mesh),
                 "material": json.dumps(self.material), "surface": json.dumps(self.surface),
                 "stats": json.dumps(self.stats.as_dict())}
        return xr.Dataset(data_vars, coords=coords, attrs=attrs)


def face_profile(model, ev_contact, u_full: np.ndarray, shift: float) -> PressureProfile:
    """The face state of a converged evaluation, in the surface frame."""
    L0 = model.cell.width
    pos = model.face_positions(u_full)
    xn = np.append(pos[:, 0], pos[0, 0] + L0)
    yn = np.append(pos[:, 1], pos[0, 1])
    seg = np.hypot(np.diff(xn), np.diff(yn))
    trib = 0.5 * (seg + np.roll(seg, 1))
    pres = np.hypot(ev_contact.force[:, 0], ev_contact.force[:, 1]) / trib
    xs = np.mod(pos[:, 0] + shift, L0)
    order = np.argsort(xs)
    return PressureProfile(xs[order], pres[order], pos[order, 1],
                           model.surface.heights(xs[order]))
