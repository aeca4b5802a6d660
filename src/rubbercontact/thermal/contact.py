r"""Flash temperature of a half-space (or hybrid) sliding contact, iterated with its friction.

Heat
----
The friction stress is spread over the contact as the pressure, ``τ(x) = μ p(x)``, so the
heat flux into the rubber is ``Q(x) = μ p(x) v`` [mW/mm²]: its mean is ``μ σ0 v``, the
frictional power per unit nominal area (the energy balance), and it is released where
the rubber touches. (The hysteretic dissipation is released in the rubber's bulk within
about a wavelength of the surface, ahead of and under the contact; spreading it as the
pressure is the classical flash-temperature assumption of Jaeger, Archard and Greenwood.)
All of it enters the rubber. Its steady temperature is :func:`.kernel.surface_temperature`
(mean removed: the background is the run's temperature).

Coupling
--------
The linear half-space has one modulus, so the contact has one temperature: the mean rise
over the contact, ``T_c`` (:attr:`ContactHeating.contact_rise`). The solve is repeated at
the reduced speed ``a_T(T0 + T_c) v`` (by time–temperature superposition the rubber at
``T0 + T_c`` sliding at ``v`` is the reference rubber at ``a_T v``), the heat at the true
``v``, until ``T_c`` is the rise its own friction gives: the scalar root of
``F(T) − T``. Two searches (:class:`FlashSearch`):

* ``"bracket"`` (the plain one): bracketed from the isothermal estimate ``F(0)`` (secant
  steps beyond it while ``F(T) > T``), then false position (Illinois) until
  ``|F(T) − T|`` is below the tolerance: 1–10 solves per speed, the first the isothermal.
* ``"secant"`` (the default): secant steps on ``h(ln T) = ln F − ln T``, which is nearly
  linear (``F`` follows the shift ``ln a_T``, about linear in ``T``, and ``μ`` and the
  contact's size change smoothly with the reduced speed), kept inside the sign bracket
  once there is one. It starts at a guess (:class:`FlashStart`; a sweep's neighbouring
  speed, :mod:`.sweep`) with the previous root's slope, and without one at ``F(0)``;
  a guess below the tolerance starts at 0 (the isothermal solve, final if ``F(0)`` is
  below the tolerance). The same roots to the tolerance (tested), in 2–4 solves instead
  of 4–10 where the contact heats (``benchmarks/flash.md``).

A hybrid run passes a ``solve`` of its low-slope scale at that reduced speed and a
``scale`` that reads its high-slope law at the high-slope spots' own, hotter, temperature
(:mod:`rubbercontact.pipeline.flash_scales`) before the heat is taken. What this leaves
out: the temperature varies over the contact and with depth, and each scale of a rough
surface sees its own (:mod:`rubbercontact.meanfield.flash` resolves that per
magnification; the hybrids' ``scale`` one level of it); in full contact
the rise averages to zero over the contact and the contact is at the background
temperature.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .._validation import positive_scalar
from ..errors import ConvergenceError, InputError
from ..materials.shift import ShiftLaw, shift_law_from_dict
from .kernel import surface_temperature
from .properties import FILLED_SBR, ThermalProperties


@dataclass(frozen=True)
class ContactHeating:
    """The frictional heat of a sliding contact and its steady temperature rise.

    Attributes
    ----------
    heat_flux
        ``Q = μ p v`` [mW/mm²] on the solver's grid.
    temperature
        Surface temperature rise above the background [K] on the grid (zero mean).
    contact_rise
        Mean rise over the contact [K] (:func:`contact_mask`).
    peak_rise
        Largest rise [K].
    mean_heat_flux
        ``<Q>`` [mW/mm²] (= ``μ σ0 v``).
    velocity
        The true sliding speed [mm/s] the heat was computed at.
    """

    heat_flux: np.ndarray
    temperature: np.ndarray
    contact_rise: float
    peak_rise: float
    mean_heat_flux: float
    velocity: float


def _lengths(result) -> tuple[float, ...]:
    def period(c: np.ndarray) -> float:
        return float((c[1] - c[0]) * c.size)

    return (period(result.x),) if result.y is None else (period(result.y), period(result.x))


#: Key of ``SlidingResult.info`` giving the separation [mm] below which the rubber is in
#: contact (a hybrid's low-slope solve: where its high-slope law carries load).
CONTACT_SEPARATION = "contact_separation"


def contact_mask(result) -> np.ndarray:
    """The contact of a solved sliding contact on its grid: ``p > 0`` for the hard wall;
    with an interaction law (``result.method == "newton"``), whose pressure is positive
    everywhere, the points of smallest separation, as many as its contact fraction (the
    law's contact range, e.g. ``u < 2ℓ`` for the Lennard-Jones wall, ties aside); where
    ``result.info`` has :data:`CONTACT_SEPARATION` (a hybrid's low-slope solve, whose
    contact fraction is the high-slope scale's real contact, a part of the loaded zone),
    the points below that separation."""
    info = getattr(result, "info", None)
    if isinstance(info, dict) and info.get(CONTACT_SEPARATION) is not None:
        return np.asarray(result.separation, float) < float(info[CONTACT_SEPARATION])
    p = np.asarray(result.pressure, float)
    if result.method != "newton":
        return p > 0
    u = np.asarray(result.separation, float).ravel()
    k = int(round(float(result.contact_fraction) * u.size))
    mask = np.zeros(u.size, bool)
    mask[np.argsort(u, kind="stable")[:k]] = True
    return mask.reshape(p.shape)


def start_pressure(result) -> np.ndarray:
    """The pressure of a solved contact on its contact (:func:`contact_mask`), zero
    elsewhere [MPa]: a start for a nearby solve (``solve_sliding(..., start=...)``; an
    interaction law's pressure is positive everywhere, a hard wall's start must not be)."""
    return np.where(contact_mask(result), np.asarray(result.pressure, float), 0.0)


def contact_heating(result, velocity: float | None = None,
                    thermal: ThermalProperties | None = None) -> ContactHeating:
    """Heat and temperature of a solved sliding contact (module docstring).

    Parameters
    ----------
    result
        A :class:`~rubbercontact.halfspace.SlidingResult` (``pressure``, ``x``, ``y``,
        ``friction``).
    velocity
        The true sliding speed [mm/s], > 0 (default ``result.velocity``; give it when the
        solve ran at a reduced speed ``a_T v``).
    thermal
        The compound (default: filled SBR).
    """
    thermal = thermal or FILLED_SBR
    v = positive_scalar("velocity", result.velocity if velocity is None else velocity,
                        unit="mm/s")
    p = np.asarray(result.pressure, float)
    flux = abs(float(result.friction)) * p * v
    temp = surface_temperature(flux, _lengths(result), v, thermal)
    touching = contact_mask(result)
    rise = float(temp[touching].mean()) if touching.any() else 0.0
    return ContactHeating(flux, temp, rise, float(temp.max()), float(flux.mean()), v)


def _false_position(g, lo: float, g_lo: float, hi: float, g_hi: float, tol: float) -> float:
    """A root of ``g`` in ``[lo, hi]`` (``g_lo > 0 ≥ g_hi``) by the Illinois variant of
    false position, stopped when ``|g| ≤ tol`` or the bracket is narrower than ``tol``:
    the contact set of a grid jumps, so ``g`` need not be continuous below that."""
    side = 0
    while abs(g_hi) > tol and hi - lo > tol:
        x = hi - g_hi * (hi - lo) / (g_hi - g_lo)
        gx = g(x)
        if gx > 0:
            lo, g_lo = x, gx
            g_hi, side = (g_hi / 2, -1) if side == -1 else (g_hi, -1)
        else:
            hi, g_hi = x, gx
            g_lo, side = (g_lo / 2, 1) if side == 1 else (g_lo, 1)
    return hi if abs(g_hi) <= tol or hi - lo <= tol else lo


@dataclass(frozen=True)
class FlashStart:
    """Where the secant search of ``T_c`` starts (e.g. from a sweep's neighbouring speed).

    Attributes
    ----------
    rise
        Guess of ``T_c`` [K] (≥ 0; below the tolerance: start at the isothermal solve).
    log_slope
        Estimate of ``d ln F / d ln T`` at the root [-] (None: a damped first step).
    result
        A solve to start the first solve from (:attr:`FlashSearch.warm_start`), e.g. the
        neighbouring speed's final one.
    """

    rise: float
    log_slope: float | None = None
    result: object | None = None


@dataclass(frozen=True)
class FlashSearch:
    """How :func:`flash_contact` looks for the contact temperature (module docstring).

    Attributes
    ----------
    tolerance
        On ``|F(T_c) − T_c|`` [K] (1e-2 K moves a WLF shift by ~1e-3 decades).
    relative_tolerance
        Added to ``tolerance`` times ``T_c`` [-] (``"secant"`` only): the grid's contact set
        jumps make ``F`` uneven at ~1e-3 of ``T_c`` (benchmarks/flash.md), and 1e-3 of a
        30 K rise moves a WLF shift by ~2e-3 decades.
    max_solves
        Solves allowed before :class:`~rubbercontact.errors.ConvergenceError`.
    method
        ``"secant"`` (default) or ``"bracket"`` (the plain search).
    start
        A guess for ``"secant"`` (None: from ``F(0)``).
    warm_start
        ``solve`` takes a second argument, the solve to start from (None: none): a solve
        at ``T > 0`` is started from the evaluated one (or ``start.result``) nearest in
        reduced speed if within a factor 1.25; a solve at ``T = 0`` never is, so it is
        the isothermal solve bit for bit.
    """

    tolerance: float = 1e-2
    relative_tolerance: float = 1e-3
    max_solves: int = 30
    method: str = "secant"
    start: FlashStart | None = None
    warm_start: bool = False

    def __post_init__(self) -> None:
        positive_scalar("tolerance", self.tolerance, unit="K")
        if not 0.0 <= self.relative_tolerance < 1.0:
            raise InputError(f"relative_tolerance: expected a number in [0, 1), got "
                             f"{self.relative_tolerance!r}")
        if isinstance(self.max_solves, bool) or not isinstance(self.max_solves, int) \
                or self.max_solves < 1:
            raise InputError(f"max_solves: expected an integer >= 1, got {self.max_solves!r}")
        if self.method not in ("secant", "bracket"):
            raise InputError(f"method: expected 'secant' or 'bracket', got {self.method!r}")
        if self.start is not None and not (np.isfinite(self.start.rise)
                                           and self.start.rise >= 0):
            raise InputError(f"start.rise: expected a finite rise >= 0 K, got "
                             f"{self.start.rise!r}")


@dataclass(frozen=True)
class ContactFlash:
    """A sliding contact at its own flash temperature.

    Attributes
    ----------
    result
        The solve at the converged reduced speed ``a_T(T0 + T_c) v``.
    isothermal
        The solve at the background temperature (None when the secant search started
        from a guess and never solved there).
    heating
        :class:`ContactHeating` of ``result`` at the true speed.
    contact_temperature
        ``T0 + T_c`` [°C].
    background_temperature
        ``T0`` [°C].
    shift_factor
        ``a_T(T0 + T_c)`` relative to the shift law's reference [-].
    residual
        ``|F(T_c) − T_c|`` [K] at the end: below the tolerance (the secant search's:
        ``tolerance + relative_tolerance·T_c``), unless the bracket
        closed first (the grid's contact set can jump between two temperatures closer
        than the tolerance).
    evaluations
        ``(T, F(T))`` of every solve, in order [K].
    inputs
        The thermal properties, the shift law, the speed and the search (provenance).
    """

    result: object
    isothermal: object | None
    heating: ContactHeating
    contact_temperature: float
    background_temperature: float
    shift_factor: float
    residual: float
    evaluations: tuple = field(default_factory=tuple)
    inputs: dict = field(default_factory=dict)

    @property
    def log_slope(self) -> float | None:
        """``d ln F / d ln T`` between the two evaluations with ``T, F > 0`` closest to the
        root [-] (None with fewer than two): the next speed's :class:`FlashStart`."""
        pts = sorted(((abs(np.log(t / f)), t, f) for t, f in self.evaluations
                      if t > 0 and f > 0), key=lambda e: e[0])
        pts = [(t, f) for _, t, f in pts]
        for t2, f2 in pts[1:]:
            (t1, f1) = pts[0]
            if abs(np.log(t2 / t1)) > 1e-9:
                return float(np.log(f2 / f1) / np.log(t2 / t1))
        return None


def flash_contact(solve: Callable[[float], object], velocity: float, shift: ShiftLaw | dict,
                  thermal: ThermalProperties | None = None, temperature: float | None = None,
                  tolerance: float = 1e-2, max_solves: int = 30,
                  search: FlashSearch | None = None,
                  scale: Callable[[object, float, float], object] | None = None
                  ) -> ContactFlash:
    """The contact temperature and friction of a sliding contact, self-consistent.

    Parameters
    ----------
    solve
        ``solve(reduced_speed) -> SlidingResult``: the contact of the rubber *at the shift
        law's reference temperature* sliding at ``reduced_speed`` [mm/s], e.g.
        ``lambda u: rc.halfspace.solve_sliding(z, L, material, u, sigma0)``; with
        ``search.warm_start`` ``solve(reduced_speed, start)``, ``start`` a previous
        result or None, e.g. ``lambda u, s: solve_sliding(..., start=s and
        start_pressure(s))``.
    velocity
        The true sliding speed ``v`` [mm/s], > 0.
    shift
        The material's time–temperature shift law.
    thermal
        The compound (default: filled SBR).
    temperature
        Background ``T0`` [°C] (default: the shift law's reference).
    tolerance, max_solves
        :class:`FlashSearch`'s, when ``search`` is None.
    search
        The search (default: the secant search with ``tolerance`` and ``max_solves``).
    scale
        ``scale(result, temperature, velocity) -> result``: a hybrid's finer scale at its
        own temperature (:mod:`rubbercontact.pipeline.flash_scales`), applied to each
        solve at the contact temperature ``temperature`` [°C] and the true ``velocity``
        [mm/s] before its heat is taken (None: one temperature for the contact).
    """
    v = positive_scalar("velocity", velocity, unit="mm/s")
    law = shift_law_from_dict(shift)
    if temperature is not None and (isinstance(temperature, bool)
                                    or not isinstance(temperature, int | float)):
        raise InputError(f"temperature: expected a number in °C, got {temperature!r}")
    t0 = law.t_ref if temperature is None else float(temperature)
    law.log10_shift(t0)                                     # validity at T0
    search = search or FlashSearch(tolerance=tolerance, max_solves=max_solves)
    tol = search.tolerance
    thermal = thermal or FILLED_SBR
    if not callable(solve):
        raise InputError(f"solve: expected a function of the reduced speed, got {solve!r}")
    seen: dict[float, tuple] = {}

    def evaluate(rise: float) -> float:
        if rise not in seen:
            if len(seen) >= search.max_solves:
                raise ConvergenceError(
                    f"flash temperature: no self-consistent contact temperature in "
                    f"{search.max_solves} solves at {v:g} mm/s; raise max_solves",
                    diagnostics={"evaluations": [(t, s[2]) for t, s in seen.items()]})
            a_t = float(law.shift(t0 + rise))
            res = (solve(a_t * v, _nearest(seen, rise, a_t * v, search.start))
                   if search.warm_start else solve(a_t * v))
            if scale is not None:
                res = scale(res, t0 + rise, v)
            heat = contact_heating(res, v, thermal)
            seen[rise] = (res, heat, heat.contact_rise, a_t)
        return seen[rise][2] - rise

    if search.method == "secant":
        rise = _secant(evaluate, tol, search.relative_tolerance, search.start)
    else:
        rise = _bracket(evaluate, tol)
    res, heat, f_rise, a_t = seen[rise]
    inputs = {"velocity": v, "thermal": thermal.as_dict(), "shift": law.as_dict(),
              "tolerance_K": tol, "relative_tolerance": search.relative_tolerance,
              "method": search.method, "warm_start": search.warm_start}
    iso = seen[0.0][0] if 0.0 in seen else None
    return ContactFlash(res, iso, heat, t0 + rise, t0, a_t, abs(f_rise - rise),
                        tuple((t, s[2]) for t, s in seen.items()), inputs)


#: A solve starts from another only if their reduced speeds differ by at most this factor:
#: the polish from a 1.5–3× slower or faster solve failed half the time on the profile
#: of benchmarks/bench_flash.py and then cost about one solve more.
_WARM_RATIO = 1.25


def _nearest(seen: dict, rise: float, speed: float, start: FlashStart | None):
    """The solve to start the one at ``rise`` [K] and reduced ``speed`` [mm/s] from: the
    evaluated one (or ``start.result``) nearest in reduced speed, within
    :data:`_WARM_RATIO`; None at 0 K (the isothermal solve, bit for bit) or beyond."""
    if rise == 0.0:
        return None
    known = [s[0] for s in seen.values()]
    if start is not None and start.result is not None:
        known.append(start.result)
    if not known:
        return None
    near = min(known, key=lambda r: abs(np.log(speed / r.velocity)))
    return near if abs(np.log(speed / near.velocity)) <= np.log(_WARM_RATIO) else None


def _bracket(evaluate: Callable[[float], float], tol: float) -> float:
    """The plain search: from ``F(0)``, bracket, then false position (module docstring)."""
    g0 = evaluate(0.0)
    if g0 <= tol:
        return 0.0
    lo, g_lo = 0.0, g0
    hi = max(g0, tol)
    g_hi = evaluate(hi)
    while g_hi > 0:                         # F is bounded: a root lies beyond
        # secant extrapolation through the last two points, at most 4× further
        step = g_hi * (hi - lo) / (g_lo - g_hi) if g_lo > g_hi else np.inf
        lo, g_lo, hi = hi, g_hi, hi + min(step, 3.0 * hi)
        g_hi = evaluate(hi)
    return _false_position(evaluate, lo, g_lo, hi, g_hi, tol)


#: Largest step of the secant search in ``ln T`` (a factor 4 in ``T``).
_MAX_LOG_STEP = np.log(4.0)


def _secant(evaluate: Callable[[float], float], tol: float, rtol: float,
            start: FlashStart | None) -> float:
    """Secant steps on ``h(x) = ln F(e^x) − x``, ``x = ln T`` (module docstring); a step
    leaving the sign bracket bisects it, one whose ``F`` is not positive falls back to the
    plain search (no heat: the contact left)."""
    if start is None or start.rise <= tol:
        g0 = evaluate(0.0)
        if g0 <= tol:
            return 0.0
        t_a = g0                                     # F(0): the first fixed-point step
    else:
        t_a = float(start.rise)
    slope = None if start is None else start.log_slope
    g_a = evaluate(t_a)
    if abs(g_a) <= tol + rtol * t_a:
        return t_a
    if g_a + t_a <= 0:
        return _bracket(evaluate, tol)
    x_a, h_a = np.log(t_a), np.log((g_a + t_a) / t_a)
    # the sign bracket in x (h > 0 below the root): (x, g, T) at its ends
    inf = np.inf
    lo, hi = (((x_a, g_a, t_a), (inf, inf, inf)) if h_a > 0
              else ((-inf, inf, inf), (x_a, g_a, t_a)))
    # second point: Newton with the previous root's slope, else half the fixed-point step
    d = 0.5 * h_a if slope is None else -h_a / (min(slope, 0.5) - 1.0)
    x_b = x_a + float(np.clip(d, -_MAX_LOG_STEP, _MAX_LOG_STEP))
    while True:
        t_b = float(np.exp(x_b))
        g_b = evaluate(t_b)
        if abs(g_b) <= tol + rtol * t_b:
            return t_b
        if g_b + t_b <= 0:
            return _bracket(evaluate, tol)
        h_b = np.log((g_b + t_b) / t_b)
        if h_b > 0:
            lo = max(lo, (x_b, g_b, t_b))
        else:
            hi = min(hi, (x_b, g_b, t_b))
        if np.exp(hi[0]) - np.exp(lo[0]) <= tol + rtol * t_b:
            # F jumps here (the grid's contact set): the end closer to a fixed point
            return min(lo, hi, key=lambda e: abs(e[1]))[2]
        x_c = x_b - h_b * (x_b - x_a) / (h_b - h_a) if h_b != h_a else np.inf
        x_c = x_b + float(np.clip(x_c - x_b, -_MAX_LOG_STEP, _MAX_LOG_STEP))
        if not lo[0] < x_c < hi[0]:
            x_c = (0.5 * (lo[0] + hi[0]) if np.isfinite(lo[0] + hi[0])
                   else x_b + np.copysign(_MAX_LOG_STEP, h_b))   # toward the root
        x_a, h_a, x_b = x_b, h_b, x_c
