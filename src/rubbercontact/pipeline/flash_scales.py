r"""Each scale of a hybrid at its own temperature: the high-slope spots flash on top of the
low-slope contact.

What is computed
----------------
The hybrids (``hybrid``, ``hybrid-windowed``: :mod:`.flash_hybrid`; ``meanfield-hybrid``:
:mod:`.flash_meanfield`) solve the low-slope scale at the temperature of its contact,
``T_ls = T0 + T_c``. The high-slope scale's friction, the law's share ``μ_hs`` (its
``Δτ_hs``), is dissipated in the high-slope scale's own contact spots: the fraction
``A_hs`` of the nominal area (the hybrid's real contact, ``<α_hs>``) inside the low-slope
contact ``A_ls``, spots of half-width ``R = spot_radius/q_hs`` (``q_hs = 2π/λ_hs``, the law
cell's period; ``spot_radius = π/2``: half a wavelength across, the mean-field flash's
convention). Concentrating the heat ``w_hs = μ_hs σ0 v`` from ``A_ls`` into ``A_hs`` is one
more step of the mean-field flash's cascade (:func:`~rubbercontact.meanfield.flash.cascade_rise`):

.. math:: ΔT_{hs} = \Big(\frac{1}{A_{hs}} − \frac{1}{A_{ls}}\Big)\, Γ(R, v)\, μ_{hs} σ_0 v,

``Γ`` the centre temperature of a uniform unit-flux band of half-width ``R`` sliding at
``v`` (:func:`~rubbercontact.thermal.band_centre_temperature`; the law is a plane-strain
cell, its spots are ridges across the sliding direction). The Péclet number ``vR/(2D)``
decides: above 1 the heat enters only a layer ``√(D R/v)`` thin, ``Γ → (2/K)√(RD/πv)``;
below, ``Γ ≈ (2R/πK)(ln(4D/vR) − γ + 1)``, ``γ`` Euler's constant. The high-slope scale's
friction and real contact are read from the law at ``a_T(T_ls + ΔT_hs) v``, at the
low-slope pressure the solve gave, as the model reads the law (pointwise, windowed, or
weighted by ``P(σ)``); ``μ_hs`` depends on ``ΔT_hs`` and ``ΔT_hs`` on ``μ_hs``: the scalar
root of ``ΔT = G(ΔT)`` by Brent's method (:func:`scale_flash`), inside each step of the
low-slope search. The heat of both scales, ``(μ_ls + μ_hs) σ0 v``, heats the low-slope
contact as before; the high-slope step redistributes ``w_hs`` inside it, adding none.

Which variant, and where it holds
---------------------------------
Persson's (J. Phys.: Condens. Matter 18, 7789, 2006) per-magnification cascade, each scale
at its own temperature, the heat of the finer scales released in the spots of the
coarser, in the form of :mod:`rubbercontact.meanfield.flash` (the exact moving source for
the diffusion step; the background that of the low-slope step: the run's temperature,
with ``meanfield-hybrid``'s ``contact_time`` heating in the simplest form of Fortunato et
al., J. Phys.: Condens. Matter 27, 175008, 2015): the low-slope step is the Fourier
solution of the solved contact (hybrids) or the cascade of the low-slope nodes
(``meanfield-hybrid``), the high-slope scale one level more. Left out:

* the law's load–separation ``σ_hs(ū)``, the low-slope solve's interface, stays at
  ``T_ls``: the low-slope pressure is held while the high-slope friction and contact follow
  ``T_hs``. A hotter cell is softer; this holds where the low-slope pressure is set by the
  low-slope scale, the interface's compliance small against the half-space's;
* the high-slope waves share one level, the spots of the cell's period: for the same end
  areas a cascade through finer spots (smaller ``Γ``, less heat at each level) gives less,
  so this is the upper end of the high-slope rise;
* the mean-field closure (the heat spread uniformly over the spots) and the spots' surface
  temperature taken for the dissipating rubber's, as in :mod:`rubbercontact.meanfield.flash`.

The limits are exact: an infinitely conducting rubber (``Γ = 0``), a law without friction
(``Δτ_hs ≡ 0``) or a rubber whose shift is 1 keep the solve's own high-slope terms, bit for
bit: a reading is the solve's own terms moved by the change of the law's reading from the
solve's speed to ``a_T(T_hs) v`` (:func:`shifted_reader`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from .._validation import positive_scalar
from ..errors import ConvergenceError, InputError
from ..hybrid.lawspeed import blend_values
from ..materials.shift import ShiftLaw
from ..meanfield.flash import HOTTEST, cascade_rise
from ..thermal.properties import ThermalProperties
from ..thermal.spots import band_centre_temperature


@dataclass(frozen=True)
class HighSlopeTerms:
    """The high-slope law's share of a hybrid's answer.

    Attributes
    ----------
    friction
        ``μ_hs`` [-].
    contact_fraction
        ``A_hs`` [-], the real contact (the law's ``α_hs`` over the low-slope contact).
    """

    friction: float
    contact_fraction: float


@dataclass(frozen=True)
class ScaleSpots:
    """The high-slope scale's contact spots.

    Attributes
    ----------
    half_width
        ``R`` [mm] of a spot (module docstring).
    thermal
        The compound.
    tolerance
        On ``|G(ΔT) − ΔT|`` [K] (the flash's).
    """

    half_width: float
    thermal: ThermalProperties
    tolerance: float = 1e-2

    def __post_init__(self) -> None:
        positive_scalar("half_width", self.half_width, unit="mm")
        positive_scalar("tolerance", self.tolerance, unit="K")
        if not isinstance(self.thermal, ThermalProperties):
            raise InputError(f"thermal: expected ThermalProperties, got "
                             f"{type(self.thermal).__name__}")

    @classmethod
    def of_cell(cls, period: float, spot_radius: float, thermal: ThermalProperties,
                tolerance: float) -> ScaleSpots:
        """The spots of a law cell of ``period`` [mm] (``λ_hs``): ``R = spot_radius/q_hs``."""
        return cls(spot_radius * float(period) / (2.0 * np.pi), thermal, tolerance)

    def spot_rise(self, velocity: float) -> float:
        """``Γ`` [K per mW/mm²] at the true ``velocity`` [mm/s]."""
        return float(band_centre_temperature(self.half_width, velocity, self.thermal))


@dataclass(frozen=True)
class ScaleFlash:
    """The high-slope scale at its own temperature, at one speed.

    Attributes
    ----------
    low_temperature
        ``T_ls`` [°C], the low-slope contact's.
    rise
        ``ΔT_hs`` [K] of the high-slope spots above ``T_ls``.
    terms
        ``μ_hs``, ``A_hs`` at ``T_ls + ΔT_hs``.
    low_area
        ``A_ls`` [-].
    spot_rise
        ``Γ`` [K per mW/mm²].
    heat_flux
        ``w_hs = |μ_hs| σ0 v`` [mW/mm²].
    residual
        ``|G(ΔT_hs) − ΔT_hs|`` [K].
    """

    low_temperature: float
    rise: float
    terms: HighSlopeTerms
    low_area: float
    spot_rise: float
    heat_flux: float
    residual: float

    @property
    def temperature(self) -> float:
        """``T_hs = T_ls + ΔT_hs`` [°C]."""
        return self.low_temperature + self.rise


def scale_rise(terms: HighSlopeTerms, low_area: float, spot_rise: float,
               mean_pressure: float, velocity: float) -> float:
    """``ΔT_hs`` [K] of the module docstring: the cascade's step from ``low_area``
    (``A_ls``) into ``terms.contact_fraction`` with the heat ``|μ_hs| σ0 v`` [mW/mm²] on
    spots of ``spot_rise`` ``Γ`` [K per mW/mm²] (the coarser levels' part, 0 here: the
    caller's ``T_c``)."""
    heat = abs(float(terms.friction)) * float(mean_pressure) * float(velocity)
    return float(cascade_rise(np.array([0.0, heat]),
                              np.array([float(low_area), float(terms.contact_fraction)]),
                              np.array([0.0, float(spot_rise)]))[-1])


def rise_root(excess: Callable[[float], float], tolerance: float) -> float:
    """The root ``ΔT ≥ 0`` of ``excess(ΔT) = G(ΔT) − ΔT`` for a heat ``G ≥ 0``: 0 if
    ``excess(0) ≤ tolerance`` [K]; else bracketed in ``[0, G(0)]``, widened by doubling up
    to :data:`~rubbercontact.meanfield.flash.HOTTEST` K, and found by Brent's method to
    ``tolerance``.

    Raises
    ------
    ConvergenceError
        No root below ``HOTTEST`` K.
    """
    top = excess(0.0)
    if top <= tolerance:
        return 0.0
    hi = top
    while excess(hi) > 0:
        if hi > HOTTEST:
            raise ConvergenceError(f"no contact temperature below {HOTTEST:g} K above the "
                                   f"run's balances the heat")
        hi *= 2
    return float(brentq(excess, 0.0, hi, xtol=tolerance))


def shifted_reader(read: Callable[[float], HighSlopeTerms], low: HighSlopeTerms,
                   low_speed: float) -> Callable[[float], HighSlopeTerms]:
    """``reader(speed)``: ``low`` (the solve's own terms, read at ``low_speed`` [mm/s])
    moved by ``read(speed) − read(low_speed)`` — the change of the law's reading at the
    solve's pressure (:meth:`LawInPressure.reader`) — so that a law the same at both
    speeds gives ``low`` bit for bit (module docstring); the contact fraction is kept in
    [0, 1]."""
    base: list[HighSlopeTerms] = []

    def reader(speed: float) -> HighSlopeTerms:
        if not base:
            base.append(read(low_speed))
        now = read(speed)
        area = low.contact_fraction + (now.contact_fraction - base[0].contact_fraction)
        return HighSlopeTerms(low.friction + (now.friction - base[0].friction),
                              float(np.clip(area, 0.0, 1.0)))

    return reader


class LawInPressure:
    """The high-slope law's ``α_hs``, ``Δτ_hs`` at given local pressures, at any speed.

    Each tabulated table is read once as a function of the pressure through its own
    interpolant (:func:`~rubbercontact.hybrid.windowing.law_in_pressure`, as the windowed
    hybrid and ``meanfield-hybrid`` read it); between two tabulated speeds, at fixed
    pressure, ``α`` and ``Δτ`` are blended as the law is
    (:func:`rubbercontact.hybrid.lawspeed.blend_values`, in ``w = ln(v/v_a)/ln(v_b/v_a)``),
    here at the solve's own pressures rather than at the tables' pressures, without a table
    rebuilt per speed. Outside the tabulated speeds
    the nearest end is read; every read is counted in ``reads``
    (:class:`~.flash_hybrid.LawReads`, for the run's note).

    Parameters
    ----------
    laws
        The law at its tabulated speeds (:class:`~rubbercontact.hybrid.lawspeed.LawSpeeds`).
    reads
        The run's :class:`~.flash_hybrid.LawReads`.
    """

    def __init__(self, laws, reads) -> None:
        self._laws, self._reads = laws, reads
        self._curves: dict[float, tuple[np.ndarray, ...]] = {}

    def _curve(self, speed: float) -> tuple[np.ndarray, ...]:
        """``(σ, α, Δτ)`` of the table at a tabulated ``speed``, ascending in ``σ``."""
        from ..hybrid.windowing import law_in_pressure

        if speed not in self._curves:
            self._curves[speed] = law_in_pressure(self._laws.table(speed))
        return self._curves[speed]

    def reader(self, sigma: np.ndarray, mean: Callable[[np.ndarray], float],
               mean_pressure: float) -> Callable[[float], HighSlopeTerms]:
        """``read(speed)``: ``μ_hs = mean(Δτ(σ))/σ0`` and ``A_hs = mean(α(σ))`` with the
        law at ``speed`` [mm/s], at the local pressures ``sigma`` [MPa] (``mean``: the
        model's average over them, e.g. ``np.mean`` over a grid)."""
        at: dict[float, tuple[np.ndarray, np.ndarray]] = {}

        def values(speed: float) -> tuple[np.ndarray, np.ndarray]:
            if speed not in at:
                sig, alpha, tau = self._curve(speed)
                at[speed] = (np.interp(sigma, sig, alpha), np.interp(sigma, sig, tau))
            return at[speed]

        def read(speed: float) -> HighSlopeTerms:
            where = self._reads.where(self._laws, speed)
            alpha, tau = values(where.lower)
            if where.upper != where.lower:
                hi = values(where.upper)
                alpha, tau = (blend_values(alpha, hi[0], where.weight),
                              blend_values(tau, hi[1], where.weight))
            return HighSlopeTerms(float(mean(tau)) / mean_pressure, float(mean(alpha)))

        return read


def scale_flash(reader: Callable[[float], HighSlopeTerms], low: HighSlopeTerms,
                low_temperature: float, velocity: float, mean_pressure: float,
                low_area: float, shift: ShiftLaw, spots: ScaleSpots) -> ScaleFlash:
    """The high-slope scale at its own temperature, self-consistent (module docstring).

    Parameters
    ----------
    reader
        ``reader(reduced_speed)``: the high-slope terms with the law read at that speed
        [mm/s] (:func:`shifted_reader`).
    low
        The terms of the solve at ``T_ls`` (the answer when the spots do not heat).
    low_temperature
        ``T_ls`` [°C].
    velocity
        The true sliding speed ``v`` [mm/s].
    mean_pressure
        ``σ0`` [MPa].
    low_area
        ``A_ls`` [-].
    shift
        The material's shift law.
    spots
        :class:`ScaleSpots`.
    """
    gamma = spots.spot_rise(velocity)
    seen: dict[float, tuple[HighSlopeTerms, float]] = {}

    def excess(rise: float) -> float:
        if rise not in seen:
            terms = low if rise == 0.0 else reader(
                float(shift.shift(low_temperature + rise)) * velocity)
            seen[rise] = (terms, scale_rise(terms, low_area, gamma, mean_pressure, velocity)
                          - rise)
        return seen[rise][1]

    root = rise_root(excess, spots.tolerance)
    terms, resid = seen[root]
    return ScaleFlash(low_temperature, root, terms, float(low_area), gamma,
                      abs(terms.friction) * mean_pressure * velocity, abs(resid))


def spots_bound(mean_flux: float, contact_fraction: float, velocity: float,
                spots: ScaleSpots) -> float:
    """Upper bound [K] of ``ΔT_hs`` without feedback: the whole heat ``mean_flux``
    [mW/mm²] on the real contact ``contact_fraction`` (``A_ls ≤ 1``, ``w_hs ≤ μσ0v``)."""
    if not contact_fraction > 0:
        return np.inf
    return abs(float(mean_flux)) / float(contact_fraction) * spots.spot_rise(velocity)
