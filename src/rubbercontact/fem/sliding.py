"""The FEM micromechanical sliding test (paper §2.4): the public entry points.

:func:`steady_sliding` solves the steady state of the periodic cell sliding at constant
speed directly (:mod:`.steady_solver`); :func:`sliding_test` runs either solver
(``solver="steady"``, the default, or ``"transient"``, the time-stepped press / settle /
slide protocol of :mod:`.transient`). Both return a :class:`~.result.SlidingTestResult`.

The steady solution is the state the transient test tends to at one element of travel
per step, with the same integrator, once its creep has settled.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import fields, replace

import numpy as np

from .._validation import positive_scalar
from ..errors import ConvergenceError, InputError
from ..materials.maxwell import GeneralizedMaxwell
from ..materials.protocol import check_prony
from ..roughness.crests import round_crests
from ..roughness.protocol import check_waves
from ..roughness.sines import SineSeries
from .constitutive import cauchy_from_pk2
from .contact import face_contact_fraction, mean_separation, segment_penetration
from .loadrange import outside_range
from .options import RESCUE_NEWTON, FemOptions, SteadyOptions, TransientOptions
from .resolution import (
    REFINE_FACTORS,
    narrowest_patch,
    refine_factor,
    refined_mesh,
    under_resolved_message,
)
from .result import (
    BULK_SHEAR_LIMIT,
    SEGMENT_PENETRATION_LIMIT,
    SlidingTestResult,
    SolverStats,
    bulk_shear_message,
    face_profile,
    impaled_message,
)
from .steady_solver import SteadyFailure, SteadySolution, SteadyState, solve_steady
from .transient import TransientTest

#: Minimum number of elements per shortest wavelength accepted.
MIN_ELEMENTS_PER_WAVELENGTH = 8

_FEM_FIELDS = {f.name for f in fields(FemOptions)} - {"steady", "transient"}
_TRANSIENT_FIELDS = {f.name for f in fields(TransientOptions)}
_STEADY_FIELDS = {f.name for f in fields(SteadyOptions)}


def make_options(options: FemOptions | None = None, **changes) -> FemOptions:
    """``options`` (default :class:`FemOptions`) with ``changes`` by field name, whether the
    field is the cell's (``mesh``, ``grading``, ...), the transient's (``periods``, ...) or
    the steady solver's (``coarse_elements``, ...)."""
    base = options or FemOptions()
    if not isinstance(base, FemOptions):
        raise InputError(f"options: expected a FemOptions, got {type(base).__name__}")
    top, tr, st = {}, {}, {}
    for key, value in changes.items():
        if key in _FEM_FIELDS:
            top[key] = value
        elif key in _TRANSIENT_FIELDS:
            tr[key] = value
        elif key in _STEADY_FIELDS:
            st[key] = value
        else:
            raise InputError(f"unknown FEM option {key!r}")
    out = base.with_(**top, transient=tr, steady=st)
    if tr and out.solver != "transient":
        raise InputError(f"{', '.join(sorted(tr))}: option(s) of the transient solver; pass "
                         f"solver='transient'")
    return out


def check_test(surface, material, mean_pressure, velocity, options: FemOptions
               ) -> tuple[float, float]:
    """Check the inputs of one test; ``(p̄, v)`` as floats."""
    # the cell is meshed by the shortest wavelength and its contact search bounds the
    # surface's slope and curvature by the waves: what it needs is a profile of sine waves
    check_waves(surface, analytic=True, needs="the FEM cell")
    if surface.period <= 0:
        raise InputError(f"surface: period must be > 0 mm, got {surface.period} "
                         f"(empty SineSeries)")
    check_prony(material)
    p = positive_scalar("mean_pressure", mean_pressure, unit="MPa")
    v = positive_scalar("velocity", velocity, allow_zero=True, unit="mm/s")
    nx = options.resolved(surface).mesh[0]
    per_wave = nx * surface.wavelengths[0] / surface.period
    if per_wave < MIN_ELEMENTS_PER_WAVELENGTH - 1e-9:
        nx_min = int(np.ceil(MIN_ELEMENTS_PER_WAVELENGTH * surface.period
                             / surface.wavelengths[0]))
        raise InputError(f"mesh: nx = {nx} gives {per_wave:.3g} elements per shortest "
                         f"wavelength ({surface.wavelengths[0]} mm); need at least "
                         f"{MIN_ELEMENTS_PER_WAVELENGTH} (nx >= {nx_min})")
    if options.viscous_model != "simo" and options.solver == "steady":
        raise InputError(f"viscous_model: the steady solver integrates Simo's model only; "
                         f"{options.viscous_model!r} needs solver='transient'")
    if options.transient.steps_per_period is not None and options.solver == "steady":
        raise InputError("steps_per_period: the steady solver steps one column of travel; "
                         "refine the mesh instead, or pass solver='transient'")
    outside = outside_range(p, material.equilibrium_modulus)
    if outside and options.auto:
        raise InputError(f"FEM sliding test (p̄ = {p:g} MPa, v = {v:g} mm/s): outside the "
                         f"cell's range, not tried on mesh = 'auto': {outside}")
    if outside:
        warnings.warn(f"mean_pressure: {outside}: slow or failing convergence",
                      RuntimeWarning, stacklevel=3)
    return p, v


def sliding_test(surface: SineSeries, material: GeneralizedMaxwell, mean_pressure: float,
                 velocity: float, mesh: tuple[int, int] | None = None, *,
                 solver: str | None = None, options: FemOptions | None = None,
                 start: SteadyState | None = None, progress=None,
                 **changes) -> SlidingTestResult:
    """Press a periodic rubber cell onto ``surface`` and slide it at constant speed.

    Parameters
    ----------
    surface
        Rigid surface (cell width ``L0`` = its longest wavelength).
    material
        Prony series (Young's moduli, incompressible); shear moduli are ``E/3``.
    mean_pressure
        ``p̄`` [MPa] > 0.
    velocity
        ``v`` [mm/s] >= 0; ``v > 0``: the rubber moves in +x relative to the surface;
        ``v = 0`` gives the fully relaxed static indentation.
    mesh
        ``(nx, ny)`` elements (default ``options.mesh``, 120 × 90); ``nx`` must give >= 8
        elements per shortest wavelength.
    solver
        ``"steady"`` (default: the steady state directly) or ``"transient"`` (time-stepped).
    options
        All options of the test (:class:`~.options.FemOptions`).
    start
        Steady solver: a neighbouring solution (``result.state``) to continue from.
    progress
        Transient solver: optional callable ``progress(phase, step, time, friction)``.
    **changes
        Any field of :class:`~.options.FemOptions`, :class:`~.options.TransientOptions`
        (e.g. ``periods``, ``steps_per_period``; these need ``solver="transient"``) or
        :class:`~.options.SteadyOptions`, by name.

    Raises
    ------
    InputError
        Bad input (the message names the field), or on ``mesh = "auto"`` a mean pressure
        outside the cell's range (above the relaxed modulus, :mod:`.loadrange`).
    ConvergenceError
        The solver failed (the steady solver first falls back to the transient one unless
        ``fallback=False``); ``diagnostics`` says what was tried.
    """
    if mesh is not None:
        changes["mesh"] = mesh
    if solver is not None:
        changes["solver"] = solver
    opts = make_options(options, **changes)
    p, v = check_test(surface, material, mean_pressure, velocity, opts)
    if opts.crest_radius is not None:
        surface = round_crests(surface, opts.crest_radius)
    refine, opts = opts.auto, opts.resolved(surface)
    if opts.solver == "transient":
        return TransientTest(surface, material, p, v, opts, progress).run()
    if not refine:
        return _steady(surface, material, p, v, opts, start)
    return _resolved_steady(surface, material, p, v, opts, start)


def _refined(surface, opts: FemOptions, factor: float) -> FemOptions:
    """The resolved automatic ``opts`` on the rule's mesh for ``factor`` times the columns
    per wave (rows and grading the rule's for it: the face rows keep their aspect); the
    nested iteration starts at the old ``nx`` where the new one halves onto it."""
    m = refined_mesh(surface, opts.height_ratio, opts.columns_per_wave, factor)
    return opts.with_(mesh=(m.nx, m.ny), grading=m.grading)


def _resolved_steady(surface, material, p, v, opts: FemOptions, start) -> SlidingTestResult:
    """The steady test on an automatic mesh: solved, its narrowest contact patch checked,
    and where that is below ``opts.patch_columns`` re-solved on a finer mesh: the smallest
    of :data:`~.resolution.REFINE_FACTORS` that widens the patch enough, then the larger
    ones while the patch stays too narrow (not after a refinement that fails, nor for a
    cell sheared as a whole beyond ``BULK_SHEAR_LIMIT``). A neighbour that was refined
    starts this test on the refined mesh directly."""
    for factor in REFINE_FACTORS:
        fine = _refined(surface, opts, factor)
        if start is not None and tuple(start.mesh) == fine.mesh:
            res = _steady(surface, material, p, v, fine, start)
            return _say_resolution(_mark_refined(res, "on the neighbour's refined mesh"),
                                   opts)
    res = _steady(surface, material, p, v, opts, start)
    first = res.stats.patch_columns
    tried: tuple[str, ...] = ()
    factors = [f for f in REFINE_FACTORS if f >= refine_factor(first, opts.patch_columns)]
    if res.stats.under_resolved and res.stats.bulk_shear > BULK_SHEAR_LIMIT:
        # sheared as a whole, its contact area is flagged whatever the mesh (the area may
        # stop growing with the load: bulk_shear_message) and a law's extension stops short
        # of such loads: refining it costs minutes for an answer outside the cell's range
        # (benchmarks/steep_grid.md)
        tried, factors = (f"not refined: the cell sheared as a whole by "
                          f"{res.stats.bulk_shear:.2f} > {BULK_SHEAR_LIMIT:g}",), []
    for factor in factors if res.stats.under_resolved else ():
        fine = _refined(surface, opts, factor)
        try:
            # afresh, nested from the first mesh's columns: carrying the first solution over
            # onto the finer rows cost more on the steep CAPTIF cells (mesh_resolution.md,
            # steep_grid.md)
            again = _steady(surface, material, p, v, fine.with_(steady={"fallback": False}),
                            None)
        except ConvergenceError as exc:
            # a finer mesh would not fare better: the press only gets harder with columns
            tried += (f"refine {fine.mesh[0]}x{fine.mesh[1]} (narrowest patch {first:.1f} "
                      f"columns) failed: {exc}",)
            break
        res = _mark_refined(again, f"narrowest patch {first:.1f} columns on "
                                   f"{opts.mesh[0]}x{opts.mesh[1]}")
        if not res.stats.under_resolved:
            break
    res = replace(res, stats=replace(res.stats, tried=res.stats.tried + tried))
    return _say_resolution(res, opts)


def _say_resolution(res: SlidingTestResult, opts: FemOptions) -> SlidingTestResult:
    """Warn (one line) if the automatic mesh's test is still under-resolved."""
    if res.stats.under_resolved:
        warnings.warn(under_resolved_message(res.stats.patch_columns, opts.patch_columns,
                                             res.mesh, res.mean_pressure, res.velocity),
                      RuntimeWarning, stacklevel=4)
    return res


def _mark_refined(res: SlidingTestResult, why: str) -> SlidingTestResult:
    """``res`` flagged as refined, with why in its stages."""
    note = f"refined to {res.mesh[0]}x{res.mesh[1]} ({why})"
    return replace(res, stats=replace(res.stats, refined=True,
                                      tried=(note,) + tuple(res.stats.tried)))


def steady_sliding(surface: SineSeries, material: GeneralizedMaxwell, mean_pressure: float,
                   velocity: float, mesh: tuple[int, int] | None = None, *,
                   options: FemOptions | None = None, start: SteadyState | None = None,
                   **changes) -> SlidingTestResult:
    """The steady state of the sliding test, solved directly (see :func:`sliding_test`).

    In the frame of the surface the cell is steady: every quadrature point carries the
    history of its upstream neighbour (:mod:`.streamline`), and one non-linear problem
    gives friction, contact fraction, mean separation and the settled bulk shear. A
    speed or load sweep passes each ``result.state`` on as the next ``start``.
    """
    return sliding_test(surface, material, mean_pressure, velocity, mesh, solver="steady",
                        options=options, start=start, **changes)


def _steady(surface, material, p, v, opts: FemOptions, start) -> SlidingTestResult:
    wall0 = time.perf_counter()
    rescue = _rescue_options(opts)
    try:
        sol = solve_steady(surface, material, p, v, opts, start)
    except SteadyFailure as fail:
        failures = [fail]
        rescue = _with_budget_left(rescue, fail.counters.newton_iterations)
        if rescue is not None:
            try:
                return _barrier_rescue(surface, material, p, v, rescue,
                                       f"penalty contact failed: {fail.reason}")
            except SteadyFailure as again:
                failures.append(again)
        return _after_failure(surface, material, p, v, opts, failures)
    res = steady_result(sol, surface, material, p, v, opts, time.perf_counter() - wall0,
                        warn_impaled=rescue is None)
    rescue = _with_budget_left(rescue, sol.counters.newton_iterations)
    if not (res.stats.impaled and rescue is not None):
        return res
    # The penalty converged with a crest through the face between two nodes: μ and A
    # are meaningless there, and the barrier cannot impale by construction.
    why = f"penalty contact impaled the face ({res.stats.max_segment_penetration:.3g} mm)"
    try:
        return _barrier_rescue(surface, material, p, v, rescue, why)
    except SteadyFailure as again:
        warnings.warn(impaled_message(res.stats.max_segment_penetration,
                                      res.width / res.mesh[0], p, v),
                      RuntimeWarning, stacklevel=3)
        note = f"{why}; barrier rescue: {again.reason}"
        return replace(res, stats=replace(res.stats, tried=tuple(res.stats.tried) + (note,)))


def _barrier_rescue(surface, material, p, v, rescue: FemOptions, why: str
                    ) -> SlidingTestResult:
    """The steady solve again with the barrier contact (raises :class:`SteadyFailure`)."""
    wall0 = time.perf_counter()
    try:
        # afresh: a penalty state penetrates the surface, where the barrier is infinite
        sol = solve_steady(surface, material, p, v, rescue, None)
    except SteadyFailure as fail:
        # its budget is what the penalty solve left of steady.newton_budget: say so
        left = rescue.steady.newton_budget
        raise SteadyFailure(f"with the {left} Newton iterations left, {fail.reason}",
                            fail.tried, fail.counters) from None
    res = steady_result(sol, surface, material, p, v, rescue, time.perf_counter() - wall0)
    return replace(res, stats=replace(res.stats, solver="steady (barrier rescue)",
                                      tried=(f"{why}; barrier rescue",)
                                      + tuple(res.stats.tried)))


def _rescue_options(opts: FemOptions) -> FemOptions | None:
    """The options of the barrier rescue of a failed penalty solve (None: no rescue)."""
    if opts.contact != "penalty" or opts.steady.rescue != "barrier":
        return None
    return opts.with_(contact="barrier", steady={
        "newton_per_step": max(RESCUE_NEWTON, opts.steady.newton_per_step),
        "rescue": "none", "fallback": False})


def _with_budget_left(rescue: FemOptions | None, spent: int) -> FemOptions | None:
    """The rescue's options with the Newton budget the penalty solve left (None: no rescue,
    or nothing left: the budget bounds the whole steady solve on a mesh)."""
    if rescue is None or spent >= rescue.steady.newton_budget:
        return None
    return rescue.with_(steady={"newton_budget": rescue.steady.newton_budget - spent})


def _after_failure(surface, material, p, v, opts: FemOptions,
                   failures: list[SteadyFailure]) -> SlidingTestResult:
    """The steady solve (and its rescue) failed: the transient test, or the error."""
    names = ("", "; barrier rescue: ")
    reason = "".join(f"{n}{f.reason}" for n, f in zip(names, failures, strict=False))
    tried = [t for f in failures for t in f.tried]
    if not opts.steady.fallback:
        raise ConvergenceError(f"steady FEM solve failed: {reason}",
                               diagnostics={"tried": tried, "reason": reason}) from None
    warnings.warn(f"steady FEM solve failed (p̄ = {p:g} MPa, v = {v:g} mm/s: "
                  f"{reason}); running the transient test instead"
                  + ("" if opts.steady.fallback_budget is None else
                     f" (at most {opts.steady.fallback_budget} Newton iterations)"),
                  RuntimeWarning, stacklevel=4)
    try:
        res = TransientTest(surface, material, p, v, opts.with_(solver="transient"),
                            newton_budget=opts.steady.fallback_budget).run()
    except ConvergenceError as exc:
        raise ConvergenceError(f"steady FEM solve failed: {reason}; transient fallback "
                               f"(steady.fallback_budget): {exc}",
                               diagnostics={"tried": tried, "reason": reason,
                                            "fallback": exc.diagnostics},
                               last_state=exc.last_state) from None
    stats = replace(res.stats, solver="transient (fallback)",
                    status=f"steady failed: {reason} (tried: {'; '.join(tried)})")
    return replace(res, stats=stats)


def steady_result(sol: SteadySolution, surface, material, p: float, v: float,
                  opts: FemOptions, wall: float, *, warn_impaled: bool = True
                  ) -> SlidingTestResult:
    """The :class:`~.result.SlidingTestResult` of a converged steady solution.

    ``warn_impaled=False``: an impaled face is flagged but not warned about (the caller
    tries the barrier rescue first, and warns if that fails).
    """
    setup, ev = sol.setup, sol.ev
    model, L0, H = setup.model, surface.period, setup.cell.height
    cs = ev.contact
    pos = model.face_positions(ev.u_full)
    mu = -float(cs.force[:, 0].sum()) / setup.load
    bulk_shear = float(abs(np.mean(pos[:, 0] - model.X_face[:, 0])) / H)
    if bulk_shear > BULK_SHEAR_LIMIT:
        warnings.warn(bulk_shear_message(bulk_shear, p, v, "steady"), RuntimeWarning,
                      stacklevel=4)
    seg_pen = segment_penetration(surface, sol.shift, pos, L0)
    impaled = seg_pen > SEGMENT_PENETRATION_LIMIT * setup.cell.hx
    if impaled and warn_impaled:
        warnings.warn(impaled_message(seg_pen, setup.cell.hx, p, v), RuntimeWarning,
                      stacklevel=4)
    patch = narrowest_patch(surface, sol.shift, cs, L0, setup.cell.hx)
    c = sol.counters
    stats = SolverStats(
        solver="steady", newton_iterations=c.newton_iterations,
        factorizations=c.factorizations, wall_time=wall, assembly_time=c.assembly_time,
        solve_time=c.factorization_time + c.krylov_time, n_unknowns=model.n, steady=True,
        max_penetration=float(np.max(-cs.gap[cs.active], initial=0.0)),
        max_segment_penetration=seg_pen, impaled=bool(impaled),
        bulk_shear=bulk_shear, krylov_iterations=c.krylov_iterations,
        continuation_steps=c.continuation_steps, tried=tuple(sol.path),
        surface_offset=float(np.mod(sol.shift, setup.cell.hx)),
        factorization_time=c.factorization_time, patch_columns=patch,
        under_resolved=bool(patch < opts.patch_columns))
    ue = ev.u_full[model.asm.edofs].reshape(-1, 4, 2)
    return SlidingTestResult(
        friction=mu, shear_stress=mu * p,
        contact_fraction=face_contact_fraction(surface, sol.shift, cs, L0),
        mean_separation=mean_separation(pos[:, 0], pos[:, 1], L0), mean_pressure=p,
        velocity=v, pressure_profile=face_profile(model, cs, ev.u_full, sol.shift),
        history={}, stats=stats, width=L0, height=H, mesh=tuple(opts.mesh),
        material=material.as_dict(), surface=surface.as_dict(),
        element_coordinates=setup.cell.Xe + ue,
        element_stress=cauchy_from_pk2(ev.F, ev.S).mean(axis=1), sliding_distance=sol.shift,
        state=sol.state)
