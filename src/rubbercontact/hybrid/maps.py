"""The hybrid method on height maps, with the linear law of the high-slope cell.

The map is split (:func:`rubbercontact.roughness.mapsplit.split_map`) into ``z_ls`` and the
high-slope band, realized on a cell of one high-slope period in x and y. The law of the
high-slope band is the 2D half-space (VHS) solution of the cell alone
(:func:`linear_law_map`, the 2D form of :func:`~rubbercontact.hybrid.linearlaw.linear_law`):
with it the hybrid's error against the VHS on the whole map is its scale split alone; the 3D
FEM cell will fill the same slot with a table of the same keys and ``dimension = 2``.

The low-slope map is solved by the 2D BEM with the law ``σ_hs(ū)`` (plus the Lennard-Jones
wall if asked) and the law's ``Δτ_hs``, ``α_hs`` read at the pressure averaged over a box of
one high-slope period ``λ_c`` (:mod:`.windowing2d`), or pointwise (the paper's eqs. 6, 8)
with ``window=False``.

Laws carry their dimension: a table without ``dimension = 2`` is a plane-strain (1D) law,
whose ``σ_hs(ū)`` is per unit width of a line contact, and is refused on a map.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from .._validation import positive_scalar
from ..errors import InputError
from ..halfspace import SlidingResult, SolverOptions
from ..halfspace.kernels import derivative_x
from ..materials import GeneralizedMaxwell
from ..roughness.maps import HeightMap, max_height
from ..roughness.mapsplit import MapSplit
from ..roughness.protocol import SurfaceMap, check_surface

LAW_KINDS = ("hard-wall", "lennard-jones")


@dataclass(frozen=True)
class MapHybridOptions:
    """Settings of :func:`solve_map_hybrid`.

    Attributes
    ----------
    law : {"hard-wall", "lennard-jones"}
        The low-slope solve's law besides the high-slope table: the table alone, or the
        integrated Lennard-Jones wall plus the table (the 1D hybrid's default).
    window : bool
        Read ``Δτ_hs``, ``α_hs`` at the pressure averaged over a box of one high-slope period
        (default) or pointwise.
    nu : float
        Poisson's ratio.
    tol : float
        Relative tolerance of the half-space solve.
    solver : SolverOptions or None
        Switches of the half-space solver.
    """

    law: str = "hard-wall"
    window: bool = True
    nu: float = 0.5
    tol: float = 1e-8
    solver: SolverOptions | None = None

    def __post_init__(self) -> None:
        if self.law not in LAW_KINDS:
            raise InputError(f"options.law: expected one of {LAW_KINDS}, got {self.law!r}")
        if not isinstance(self.window, bool):
            raise InputError(f"options.window: expected True or False, got {self.window!r}")


@dataclass(frozen=True, eq=False)
class MapHybridResult:
    """The hybrid on a map at one speed and load (units: MPa, mm).

    Attributes
    ----------
    friction, friction_ls, friction_hs
        Total ``μ``, ``<σ_ls ∂z_ls/∂x>/σ0`` and the law's ``<Δτ_hs>/σ0`` [-].
    friction_y
        Lateral force ratio ``(<σ_ls ∂z_ls/∂y> + <Δτ_hs,y>)/σ0`` [-] (0 for a map symmetric
        about the sliding direction).
    contact_fraction
        ``<α_hs>`` [-].
    mean_separation
        ``ū`` of the low-slope solve [mm].
    window
        The averaging cell's side [mm] (0: pointwise).
    low
        The low-slope half-space solution (pressure map, separation, iterations); ``None``
        when the low-slope map is flat (every band high-slope: the law alone, exactly).
    elapsed
        Wall time [s].
    """

    friction: float
    friction_ls: float
    friction_hs: float
    friction_y: float
    contact_fraction: float
    mean_separation: float
    window: float
    low: SlidingResult | None
    elapsed: float


def lateral_friction(result: SlidingResult) -> float:
    """``<σ ∂z/∂y>/σ0`` [-] of a half-space solution on a map (0 for a profile)."""
    if result.y is None:
        return 0.0
    ly = float(result.y[1] - result.y[0]) * result.y.size
    zy = derivative_x(np.ascontiguousarray(np.asarray(result.heights).T), ly).T
    return float(np.mean(result.pressure * zy)) / result.mean_pressure


def solve_map(hmap: SurfaceMap, material: GeneralizedMaxwell, velocity: float,
              mean_pressure: float, law=None, *, nu: float = 0.5, tol: float = 1e-8,
              options: SolverOptions | None = None) -> SlidingResult:
    """The VHS on a periodic map: :func:`rubbercontact.halfspace.solve_sliding` on its
    heights and lengths (sliding along x). Arguments as there; ``hmap`` a periodic
    :class:`~rubbercontact.roughness.HeightMap` or any
    :class:`~rubbercontact.roughness.SurfaceMap`."""
    from ..halfspace import solve_sliding

    check_surface(hmap, what="map", dimensions=(2,), needs="solve_map")
    if getattr(hmap, "periodic", True) is False:
        raise InputError("map: the half-space solve takes the map as one period; use "
                         "map.periodized() first")
    return solve_sliding(hmap, None, material, velocity, mean_pressure,
                         law=law, nu=nu, tol=tol, options=options)


def linear_law_map(cell: HeightMap, material: GeneralizedMaxwell, velocity: float, *,
                   nu: float = 0.5, points: int = 80) -> dict:
    """The linear (VHS) law of a high-slope cell, as a table with ``dimension = 2``.

    Hard-wall 2D half-space solves of the cell at ``points`` pressures from 1e-3 to 50 MPa
    (geometric) up to full contact, plus the zero-load anchor at the cell's highest point,
    as :func:`~rubbercontact.hybrid.linearlaw.linear_law` does in 1D. Keys: ``separation``
    [mm], ``pressure`` [MPa], ``contact_fraction`` [-], ``shear_stress`` and
    ``shear_stress_y`` (the lateral ``<σ ∂z/∂y>``) [MPa], ``dimension`` (2).
    """
    if int(points) != points or points < 2:
        raise InputError(f"points: expected an integer >= 2, got {points!r}")
    rows = []
    for p in np.geomspace(1e-3, 50.0, int(points)):
        r = solve_map(cell, material, velocity, float(p), nu=nu)
        if r.contact_fraction >= 0.999:   # full contact: u stops changing
            break
        rows.append((r.mean_separation, p, r.contact_fraction, r.friction * p,
                     lateral_friction(r) * p))
    if not rows:
        raise InputError("cell: in full contact already at 1e-3 MPa; no law to tabulate")
    u, sig, alpha, tau, tau_y = (np.array(c) for c in zip(*sorted(rows), strict=True))
    return {"separation": [*u, max_height(cell)], "pressure": [*sig, 0.0],
            "contact_fraction": [*alpha, 0.0], "shear_stress": [*tau, 0.0],
            "shear_stress_y": [*tau_y, 0.0], "dimension": 2}


def check_map_law(table: dict) -> dict:
    """``table`` if it is a law for maps (``dimension == 2``), else one clear error."""
    if not isinstance(table, dict):
        raise InputError(f"law: expected a law table (dict), got {type(table).__name__}")
    dim = table.get("dimension", 1)
    if dim != 2:
        raise InputError(f"law: a plane-strain ({dim}D) law cannot be applied to a map (its "
                         f"pressure is per unit width of a line contact); compute the law on "
                         f"the map's high-slope cell (linear_law_map)")
    return table


def solve_map_hybrid(split: MapSplit, law: dict, material: GeneralizedMaxwell,
                     velocity: float, mean_pressure: float,
                     options: MapHybridOptions | None = None) -> MapHybridResult:
    """The hybrid on a map (module docstring) at one speed [mm/s] and mean pressure [MPa].

    Parameters
    ----------
    split
        The map's split (its low-slope map and cell).
    law
        The high-slope law at ``velocity`` with ``dimension = 2`` (:func:`linear_law_map`).
    material, velocity, mean_pressure
        Rubber, speed [mm/s], ``σ0`` [MPa].
    options
        :class:`MapHybridOptions`.
    """
    from .law import tabulated_law_from_dict
    from .tasks import _flat_interface_solve, halfspace_law
    from .windowing2d import lateral_table

    t0 = time.perf_counter()
    opts = options or MapHybridOptions()
    if not isinstance(opts, MapHybridOptions):
        raise InputError(f"options: expected a MapHybridOptions, got {opts!r}")
    if not isinstance(split, MapSplit):
        raise InputError(f"split: expected a MapSplit, got {type(split).__name__}")
    if split.cell is None:
        raise InputError("split: the map has no high-slope band (no law to apply); solve it "
                         "whole with solve_map (the VHS)")
    table = check_map_law(law)
    sigma0 = positive_scalar("mean_pressure", mean_pressure, unit="MPa")
    low = split.low
    if np.ptp(low.heights) <= 1e-14 * max(np.ptp(split.high.heights), 1e-300):
        # every band high-slope: uniform pressure, the law alone (the 1D flat solve)
        v = _flat_interface_solve(table, sigma0, velocity, opts.law, t0).values
        tau_y = (_flat_interface_solve(lateral_table(table), sigma0, velocity, opts.law,
                                       t0).values["friction_hs"]
                 if "shear_stress_y" in table else 0.0)
        return MapHybridResult(v["friction"], 0.0, v["friction_hs"], tau_y,
                               v["contact_fraction"], v["mean_separation"], 0.0, None,
                               time.perf_counter() - t0)
    res = solve_map(low, material, velocity, sigma0, halfspace_law(opts.law, table),
                    nu=opts.nu, tol=opts.tol, options=opts.solver)
    mu_y = lateral_friction(res)
    if opts.window:
        terms = _windowed(res, low, split.cell_period, table, sigma0)
        mu_hs, area, mu_y = (terms["friction_hs"], terms["contact_fraction"],
                             mu_y + terms["friction_hs_y"])
        window = split.cell_period
    else:
        mu_hs, area, window = res.friction_hs, res.contact_fraction, 0.0
        if "shear_stress_y" in table:      # Δτ_hs,y(u), read as the solve reads Δτ_hs(u)
            lateral = tabulated_law_from_dict(lateral_table(table))
            mu_y += float(np.mean(lateral.shear_stress(res.separation))) / sigma0
    return MapHybridResult(res.friction_ls + mu_hs, res.friction_ls, mu_hs, mu_y, area,
                           res.mean_separation, window, res, time.perf_counter() - t0)


def _windowed(res: SlidingResult, low: HeightMap, window: float, table: dict,
              sigma0: float) -> dict:
    from .windowing2d import windowed_hs_terms_2d

    return windowed_hs_terms_2d(res.pressure, low.lengths, window, table, sigma0)
