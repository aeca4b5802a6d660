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
``F(T) − T``, bracketed from the isothermal estimate ``F(0)`` (secant steps beyond it
while ``F(T) > T``), then false position (Illinois) until ``|F(T) − T|`` is below the
tolerance: 1–10 solves per speed on a three-wave profile (0.01–10 m/s), the first being
the isothermal one. A hybrid run passes a ``solve`` that evaluates its high-slope law
at the same reduced speed. What this leaves out: the temperature varies over the contact
and with depth, and each scale of a rough surface sees its own
(:mod:`rubbercontact.meanfield.flash` resolves that per magnification); in full contact
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
        Mean rise over the contact (``p > 0``) [K].
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
    touching = p > 0
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
class ContactFlash:
    """A sliding contact at its own flash temperature.

    Attributes
    ----------
    result
        The solve at the converged reduced speed ``a_T(T0 + T_c) v``.
    isothermal
        The solve at the background temperature.
    heating
        :class:`ContactHeating` of ``result`` at the true speed.
    contact_temperature
        ``T0 + T_c`` [°C].
    background_temperature
        ``T0`` [°C].
    shift_factor
        ``a_T(T0 + T_c)`` relative to the shift law's reference [-].
    residual
        ``|F(T_c) − T_c|`` [K] at the end: below the tolerance, unless the bracket
        closed first (the grid's contact set can jump between two temperatures closer
        than the tolerance).
    evaluations
        ``(T, F(T))`` of every solve, in order [K].
    inputs
        The thermal properties, the shift law, the speed and the tolerance (provenance).
    """

    result: object
    isothermal: object
    heating: ContactHeating
    contact_temperature: float
    background_temperature: float
    shift_factor: float
    residual: float
    evaluations: tuple = field(default_factory=tuple)
    inputs: dict = field(default_factory=dict)


def flash_contact(solve: Callable[[float], object], velocity: float, shift: ShiftLaw | dict,
                  thermal: ThermalProperties | None = None, temperature: float | None = None,
                  tolerance: float = 1e-2, max_solves: int = 30) -> ContactFlash:
    """The contact temperature and friction of a sliding contact, self-consistent.

    Parameters
    ----------
    solve
        ``solve(reduced_speed) -> SlidingResult``: the contact of the rubber *at the shift
        law's reference temperature* sliding at ``reduced_speed`` [mm/s], e.g.
        ``lambda u: rc.halfspace.solve_sliding(z, L, material, u, sigma0)``.
    velocity
        The true sliding speed ``v`` [mm/s], > 0.
    shift
        The material's time–temperature shift law.
    thermal
        The compound (default: filled SBR).
    temperature
        Background ``T0`` [°C] (default: the shift law's reference).
    tolerance
        On ``T_c`` [K] (1e-2 K moves a WLF shift by ~1e-3 decades).
    max_solves
        Solves allowed before :class:`~rubbercontact.errors.ConvergenceError`.
    """
    v = positive_scalar("velocity", velocity, unit="mm/s")
    law = shift_law_from_dict(shift)
    if temperature is not None and (isinstance(temperature, bool)
                                    or not isinstance(temperature, int | float)):
        raise InputError(f"temperature: expected a number in °C, got {temperature!r}")
    t0 = law.t_ref if temperature is None else float(temperature)
    law.log10_shift(t0)                                     # validity at T0
    tol = positive_scalar("tolerance", tolerance, unit="K")
    thermal = thermal or FILLED_SBR
    if not callable(solve):
        raise InputError(f"solve: expected a function of the reduced speed, got {solve!r}")
    seen: dict[float, tuple] = {}

    def evaluate(rise: float) -> float:
        if rise not in seen:
            if len(seen) >= max_solves:
                raise ConvergenceError(
                    f"flash temperature: no self-consistent contact temperature in "
                    f"{max_solves} solves at {v:g} mm/s; raise max_solves",
                    diagnostics={"evaluations": [(t, s[2]) for t, s in seen.items()]})
            a_t = float(law.shift(t0 + rise))
            res = solve(a_t * v)
            heat = contact_heating(res, v, thermal)
            seen[rise] = (res, heat, heat.contact_rise, a_t)
        return seen[rise][2] - rise

    g0 = evaluate(0.0)
    if g0 > tol:
        lo, g_lo = 0.0, g0
        hi = max(g0, tol)
        g_hi = evaluate(hi)
        while g_hi > 0:                         # F is bounded: a root lies beyond
            # secant extrapolation through the last two points, at most 4× further
            step = g_hi * (hi - lo) / (g_lo - g_hi) if g_lo > g_hi else np.inf
            lo, g_lo, hi = hi, g_hi, hi + min(step, 3.0 * hi)
            g_hi = evaluate(hi)
        rise = _false_position(evaluate, lo, g_lo, hi, g_hi, tol)
    else:
        rise = 0.0
    res, heat, f_rise, a_t = seen[rise]
    inputs = {"velocity": v, "thermal": thermal.as_dict(), "shift": law.as_dict(),
              "tolerance_K": tol}
    return ContactFlash(res, seen[0.0][0], heat, t0 + rise, t0, a_t, abs(f_rise - rise),
                        tuple((t, s[2]) for t, s in seen.items()), inputs)
