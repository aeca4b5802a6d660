"""Pure task functions of the pipeline: plain-data keyword arguments in, ``xarray.Dataset`` out.

They are what the sweep executor ships to workers and what the result cache keys on,
so they take only serialisable inputs (dicts of numbers) and rebuild the objects here.
"""

from __future__ import annotations

import time
import warnings
from contextlib import contextmanager
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from ..errors import InputError
from ..materials import GeneralizedMaxwell
from ..roughness import SineSeries

_UNITS = {
    "friction": "1", "friction_ls": "1", "friction_hs": "1", "contact_fraction": "1",
    "mean_separation": "mm", "mean_pressure": "MPa", "velocity": "mm/s", "shear_stress": "MPa",
    "max_local_pressure": "MPa", "wall_time": "s",
}


def _material(material: dict) -> GeneralizedMaxwell:
    return GeneralizedMaxwell(**material)


def _surface(surface: dict) -> SineSeries:
    return SineSeries(surface["wavelengths"], surface["amplitudes"], surface.get("phases"))


def _scalars(values: dict, attrs: dict) -> xr.Dataset:
    ds = xr.Dataset({k: ((), float(v)) for k, v in values.items()}, attrs=attrs)
    for k in ds.data_vars:
        ds[k].attrs["units"] = _UNITS.get(k, "1")
    return ds


def halfspace_law(kind: str, interface_law: dict | None = None, velocity: float | None = None):
    """The interaction law of a half-space solve.

    ``kind`` is ``"hard-wall"`` (exact complementarity) or ``"lennard-jones"``;
    ``interface_law`` (a law table as plain data, see :func:`..law.law_table_to_dict`)
    adds the high-slope law σ_hs(u) with its α_hs(u) and Δτ_hs(u).
    """
    from .. import halfspace

    base = None if kind == "hard-wall" else halfspace.LennardJonesRepulsion()
    if interface_law is None:
        return base
    from .law import tabulated_law_from_dict

    table = tabulated_law_from_dict(interface_law)
    return table if base is None else base + table


def halfspace_task(surface: dict, period: float, material: dict, velocity: float,
                   mean_pressure: float, n: int = 4096, nu: float = 0.5,
                   law: str = "lennard-jones", interface_law: dict | None = None,
                   keep_profile: bool = False, hs_window: float | None = None,
                   tol: float = 1e-8) -> xr.Dataset:
    """One steady-sliding half-space solve (VHS model, or the low-slope part of the hybrid).

    With ``hs_window`` (the high-slope period [mm]) the hybrid's ``μ_hs`` and ``A_c`` read
    the law at the pressure averaged over that window (see :mod:`.windowing`); ``tol`` is
    the solver's relative tolerance (:func:`rubbercontact.halfspace.solve_sliding`).
    """
    t0 = time.perf_counter()
    point = _halfspace_point(_surface(surface), period, _material(material), velocity,
                             mean_pressure, n, nu, law, interface_law, hs_window, t0, tol)
    ds = _scalars(point.values, point.attrs)
    if keep_profile and point.profiles:
        ds["x"] = ("x", point.x, {"units": "mm"})
        for k, arr in point.profiles.items():
            ds[k] = ("x", arr, {"units": _PROFILE_UNITS[k]})
    return ds


def halfspace_loads_task(surface: dict, period: float, material: dict, velocity: float,
                         mean_pressures: list, n: int = 4096, nu: float = 0.5,
                         law: str = "lennard-jones", interface_law: dict | None = None,
                         keep_profile: bool = False, hs_window: float | None = None,
                         tol: float = 1e-8) -> xr.Dataset:
    """:func:`halfspace_task` at each of several mean pressures, as one task.

    One task per (speed, realization) instead of one per load: the pipeline's result cache
    writes one file per task, and for the half-space solves of a speed sweep (tens of
    milliseconds each) writing the files cost about a quarter of the run. A load that fails
    is recorded in ``status`` and the others are kept.

    Parameters
    ----------
    mean_pressures
        Mean pressures σ0 [MPa]; the other arguments as for :func:`halfspace_task`.

    Returns
    -------
    xarray.Dataset
        The scalars of :func:`halfspace_task` on a ``pressure`` dimension, ``status`` per
        load (``"ok"`` or the failure) and, with ``keep_profile``, the profiles on
        ``(pressure, x)``.
    """
    from ..errors import ConvergenceError

    surf, mat = _surface(surface), _material(material)
    p = np.asarray(mean_pressures, float)
    points: list[_HalfspacePoint | None] = []
    status = []
    # the interaction law is the same at every load (its Lennard-Jones member is resolved
    # per load by the solver): the tabulated law's interpolants are built once
    built = None if surf.size == 0 else halfspace_law(law, interface_law, velocity)
    for sigma0 in p:
        try:
            points.append(_halfspace_point(surf, period, mat, velocity, float(sigma0), n, nu,
                                           law, interface_law, hs_window, time.perf_counter(),
                                           tol, built))
            status.append("ok")
        except (ConvergenceError, InputError, FloatingPointError,
                np.linalg.LinAlgError) as err:
            points.append(None)
            status.append(f"{type(err).__name__}: {err}")
    done = [pt for pt in points if pt is not None]
    names = list(done[0].values) if done else ["friction", "wall_time"]
    data = {k: ("pressure", [np.nan if pt is None else pt.values[k] for pt in points],
                {"units": _UNITS.get(k, "1")}) for k in names if k != "mean_pressure"}
    ds = xr.Dataset(data, coords={"pressure": ("pressure", p, {"units": "MPa"})},
                    attrs=done[0].attrs if done else {"model": "halfspace", "law": law})
    ds["status"] = ("pressure", np.array(status, dtype=str))
    if keep_profile and done and done[0].profiles:
        ds["x"] = ("x", done[0].x, {"units": "mm"})
        # the heights are the same at every load
        ds["heights_profile"] = ("x", done[0].profiles["heights_profile"], {"units": "mm"})
        for k in ("pressure_profile", "separation_profile"):
            rows = [np.full(done[0].x.size, np.nan) if pt is None else pt.profiles[k]
                    for pt in points]
            ds[k] = (("pressure", "x"), np.array(rows), {"units": _PROFILE_UNITS[k]})
    return ds


_PROFILE_UNITS = {"pressure_profile": "MPa", "heights_profile": "mm",
                  "separation_profile": "mm"}


@dataclass(frozen=True)
class _HalfspacePoint:
    """One half-space solve reduced to what the tasks report."""

    values: dict
    attrs: dict
    x: np.ndarray | None = None
    profiles: dict = field(default_factory=dict)


def _halfspace_point(surf: SineSeries, period: float, material: GeneralizedMaxwell,
                     velocity: float, mean_pressure: float, n: int, nu: float, law: str,
                     interface_law: dict | None, hs_window: float | None,
                     t0: float, tol: float = 1e-8,
                     built_law=None) -> _HalfspacePoint:
    """Solve one load; the flat low-slope surface by its scalar equation. ``built_law``:
    :func:`halfspace_law` of ``law`` and ``interface_law``, if already built."""
    from .. import halfspace

    if surf.size == 0:
        if interface_law is None:
            raise InputError("surface: empty (flat) surface without an interface law")
        return _flat_interface_solve(interface_law, mean_pressure, velocity, law, t0)
    res = halfspace.solve_sliding(surf, period, material, velocity,
                                  mean_pressure,
                                  law=(built_law if built_law is not None
                                       else halfspace_law(law, interface_law, velocity)),
                                  n=n, nu=nu, tol=tol)
    values = {
        "friction": res.friction, "friction_ls": res.friction_ls,
        "friction_hs": res.friction_hs, "contact_fraction": res.contact_fraction,
        "mean_separation": res.mean_separation, "mean_pressure": mean_pressure,
        "velocity": velocity, "max_local_pressure": float(np.max(res.pressure)),
        "iterations": res.iterations,
    }
    if hs_window is not None and interface_law is not None:
        from .windowing import windowed_hs_terms

        mu_hs, area = windowed_hs_terms(res.pressure, period, float(hs_window), interface_law,
                                        mean_pressure)
        values.update(friction=res.friction_ls + mu_hs, friction_hs=mu_hs,
                      contact_fraction=area)
    values["wall_time"] = time.perf_counter() - t0
    attrs = {"model": "halfspace", "law": law, "hybrid": int(interface_law is not None),
             "hs_window_mm": float(hs_window or 0.0)}
    profiles = {"pressure_profile": np.asarray(res.pressure),
                "heights_profile": np.asarray(res.heights),
                "separation_profile": np.asarray(res.separation)}
    return _HalfspacePoint(values, attrs, np.asarray(res.x), profiles)


def _flat_interface_solve(interface_law: dict, mean_pressure: float, velocity: float,
                          law: str, t0: float) -> _HalfspacePoint:
    """Exact half-space solution for a flat low-slope surface (every wave is high-slope).

    With ``z_ls = 0`` the pressure is uniform, ``w = 0`` and ``u = ū`` everywhere, so the
    solve reduces to the scalar equation ``σ_hs(ū) = σ0``; then ``μ = Δτ_hs(ū)/σ0`` and
    ``A_c/A_0 = α_hs(ū)`` (eqs. 6–8 with constant fields). The Lennard-Jones wall acts at
    separations far below the law's and is left out.
    """
    from scipy.optimize import brentq

    from .law import tabulated_law_from_dict

    table = tabulated_law_from_dict(interface_law)
    u_tab = np.asarray(interface_law["separation"])
    hi = float(u_tab.max())
    lo = float(u_tab.min())
    for _ in range(60):   # walk into the stiff continuation until it exceeds sigma0
        if float(table.pressure(np.array([lo]))[0]) > mean_pressure:
            break
        lo -= (hi - lo) if lo > 0 else max(abs(lo), hi)
    else:
        raise InputError(f"mean_pressure: {mean_pressure} MPa is beyond the interface law")
    u = brentq(lambda x: float(table.pressure(np.array([x]))[0]) - mean_pressure, lo, hi,
               xtol=1e-15, rtol=1e-12)
    ua = np.array([u])
    tau = float(table.shear_stress(ua)[0])
    values = {"friction": tau / mean_pressure, "friction_ls": 0.0,
              "friction_hs": tau / mean_pressure,
              "contact_fraction": float(table.contact_fraction(ua)[0]),
              "mean_separation": u, "mean_pressure": mean_pressure, "velocity": velocity,
              "max_local_pressure": mean_pressure, "iterations": 0,
              "wall_time": time.perf_counter() - t0}
    return _HalfspacePoint(values, {"model": "halfspace", "law": law, "hybrid": 1, "flat": 1})


#: Warnings of a FEM test whose facts its result records (the cell's bulk shear, an impaled
#: face, the narrowest contact patch, the transient's steadiness): a run's law and its full
#: FEM say each once for all their tests (:func:`~.law.assemble_law`,
#: :func:`rubbercontact.pipeline.assemble.assemble`), so the tasks keep them out of the log,
#: where a speed sweep printed one per point.
RECORDED_WARNINGS = (r".*sheared as a whole", r".*the face is impaled",
                     r".*narrowest contact patch .* under-resolved",
                     r".*period averages still change")


@contextmanager
def recorded_diagnostics():
    """Silence the FEM warnings of :data:`RECORDED_WARNINGS` inside a task."""
    with warnings.catch_warnings():
        for pattern in RECORDED_WARNINGS:
            warnings.filterwarnings("ignore", message=pattern, category=RuntimeWarning)
        yield


def fem_task(surface: dict, material: dict, velocity: float, mean_pressure: float,
             options: dict | None = None) -> xr.Dataset:
    """One FEM micromechanical sliding test (paper §2.4), reduced to its scalars.

    ``options`` is a :class:`~rubbercontact.fem.FemOptions` as plain data
    (:meth:`~rubbercontact.fem.FemOptions.to_dict`); every field is in the cache key.
    """
    from .. import fem

    t0 = time.perf_counter()
    opts = fem.FemOptions.from_dict(options or {})
    surf = _surface(surface)
    with recorded_diagnostics():
        out = fem.sliding_test(surf, _material(material), mean_pressure, velocity,
                               options=opts)
    values = _fem_scalars(out, surf, velocity, mean_pressure, time.perf_counter() - t0)
    ds = _scalars(values, {"model": "fem", "solver": out.stats.solver,
                           "status": out.stats.status})
    for k, unit in _FEM_UNITS.items():
        ds[k].attrs["units"] = unit
    prof = out.pressure_profile
    ds["x_fem"] = ("x_fem", np.asarray(prof.x), {"units": "mm"})
    ds["pressure_profile"] = ("x_fem", np.asarray(prof.pressure), {"units": "MPa"})
    return ds


def fem_speed_path_task(surface: dict, material: dict, velocities: list, mean_pressure: float,
                        options: dict | None = None) -> xr.Dataset:
    """FEM sliding tests at one load along a path of speeds, each started from the last.

    The steady solver's continuation (:func:`rubbercontact.fem.steady_sliding` with
    ``start``) in speed, in the order of :func:`rubbercontact.fem.sweep.continuation_order`:
    the middle speed from the press, the others outwards from their neighbour's steady
    state. A point that fails is recorded as failed (its ``status``) and passes the last
    converged state on (the solver presses afresh when the continuation from it fails),
    so one bad point does not sink the path.

    Parameters
    ----------
    surface, material, mean_pressure, options
        As for :func:`fem_task` (``options`` must select the steady solver).
    velocities
        Speeds [mm/s], neighbours in the sequence start each other (give them ascending).

    Returns
    -------
    xarray.Dataset
        The scalars of :func:`fem_task` (without the pressure profile) on a ``velocity``
        dimension, and ``status`` per speed (``"ok"`` or the failure).
    """
    from .. import fem
    from ..errors import ConvergenceError
    from ..fem.sweep import sweep_points

    opts = fem.FemOptions.from_dict(options or {})
    if opts.solver != "steady":
        raise InputError("fem_speed_path_task: continuation in speed needs solver = 'steady'")
    surf, mat = _surface(surface), _material(material)
    v = np.asarray(velocities, float)
    rows: list = [None] * v.size
    status = ["not run"] * v.size
    errors = (ConvergenceError, InputError, FloatingPointError, np.linalg.LinAlgError)
    with recorded_diagnostics():
        points = list(sweep_points(surf, mat, np.full(v.size, mean_pressure), v, opts,
                                   errors=errors))
    for pt in points:
        if pt.result is None:
            status[pt.index] = f"{type(pt.error).__name__}: {pt.error}"
            continue
        rows[pt.index] = _fem_scalars(pt.result, surf, float(v[pt.index]), mean_pressure,
                                      pt.wall)
        status[pt.index] = "ok"
    names = [k for k in next((r for r in rows if r is not None), {"friction": 0.0})
             if k != "velocity"]             # the speed is the coordinate
    data = {k: ("velocity", [np.nan if r is None else r[k] for r in rows],
                {"units": _FEM_UNITS.get(k, _UNITS.get(k, "1"))}) for k in names}
    ds = xr.Dataset(data, coords={"velocity": ("velocity", v,
                                               {"units": "mm/s"})},
                    attrs={"model": "fem", "solver": "steady", "path": "continuation in speed"})
    ds["status"] = ("velocity", np.array(status, dtype=str))
    return ds


_FEM_UNITS = {"sliding_time": "s", "max_penetration": "mm", "max_segment_penetration": "mm",
              "surface_offset": "mm"}


def _fem_scalars(out, surf: SineSeries, velocity: float, mean_pressure: float,
                 wall: float) -> dict:
    """The scalars :func:`fem_task` reports, of one sliding-test result."""
    st = out.stats
    sliding_time = (np.inf if st.solver == "steady"
                    else st.periods * surf.period / velocity if velocity > 0 else 0.0)
    return {
        "friction": out.friction, "shear_stress": out.shear_stress,
        "contact_fraction": out.contact_fraction, "mean_separation": out.mean_separation,
        "mean_pressure": mean_pressure, "velocity": velocity, "wall_time": wall,
        "steps": st.steps, "newton_iterations": st.newton_iterations, "cutbacks": st.cutbacks,
        "krylov_iterations": st.krylov_iterations, "max_penetration": st.max_penetration,
        "steady": int(st.steady), "period_change": st.period_change,
        "period_area_change": st.period_area_change,
        "max_segment_penetration": st.max_segment_penetration,
        "bulk_shear": st.bulk_shear, "surface_offset": st.surface_offset,
        "sliding_time": sliding_time, "impaled": int(st.impaled),
        "patch_columns": st.patch_columns, "under_resolved": int(st.under_resolved),
        "refined": int(st.refined),
    }
