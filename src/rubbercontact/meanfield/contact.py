r"""Persson's contact mechanics in 1D (plane strain) and 2D (isotropic), written for our BEM.

Full contact of one mode (the exact limit every constant below comes from)
---------------------------------------------------------------------------
The half-space of :mod:`rubbercontact.halfspace.solver` answers a pressure mode
``σ_k e^{ikx}`` with the displacement ``w_k = M(k) σ_k``, ``M(k) = 2/(|k| E_r(k_x v))``,
``E_r = E/(1 − ν²)``. In full contact the rubber follows the surface, ``w = z − const``, so a
height mode ``z_k`` carries the pressure ``σ_k = T(k) z_k`` with the transfer ``T = 1/M``
(``T = 1/(M + c)`` when an interface of compliance ``c`` [mm/MPa] sits between the two, see
:mod:`.enriched`). With ``v_i`` the height variance of node ``i`` (:mod:`.psd`) the mode adds

* the pressure variance ``s_i = v_i <|T|²>``: in 1D ``q² |E_r(qv)|² v_i / 4``,
* the dissipation (friction stress) ``f_i = v_i <|T|² (−q cos φ Im M)>``: in 1D
  ``q² v_i Im E_r(qv) / 2``,

where ``<·>`` averages over the direction ``φ`` of the wave vector to the sliding direction
(2D; one direction ``φ = 0`` in 1D). One sine ``Δ sin qx`` (``v = Δ²/2``) in full contact thus
has ``μ = f/σ0 = q²Δ² Im E_r(qv)/(4σ0)`` — the exact full-contact limit — and the pressure
amplitude ``qΔ|E_r|/2`` (Westergaard's ``p* = πE_rΔ/λ`` for an elastic sine). The 2D sums are
Persson's ``(1/8)∫q³C∫dφ|E_r|²`` and ``(1/2)∫q³C∫dφ cos φ Im E_r`` in our normalisation; the
1D ones are derived here, not transcribed.

Diffusion of the pressure with magnification
--------------------------------------------
Let ``P(σ, ζ)`` be the distribution of the contact pressure when the roughness up to the node
``ζ`` is resolved. Adding a node in full contact adds an independent pressure field of variance
``s_i``; Persson's closure keeps that step inside the contact and lets pressure that reaches 0
leave it (the rubber separates and does not come back), so

.. math:: ∂P/∂G = σ_0² ∂²P/∂σ²,\qquad G(ζ) = Σ_{i ≤ ζ} s_i / (2σ_0²),
          \qquad P(σ, 0) = δ(σ − σ_0),\qquad P(0, ζ) = 0.

Its solution is the image pair
``P(σ) = [φ(σ − σ0) − φ(σ + σ0)]`` with ``φ`` the normal density of variance ``2Gσ0²``: it
vanishes at ``σ = 0`` (the boundary condition), keeps the mean load ``∫σP dσ = σ0`` and
carries the contact fraction ``A(ζ) = ∫P dσ = erf(1/(2√G))``. Its pressure variance grows by
``A(ζ) s_i`` per node: the pressure power of mode ``i`` is its full-contact value times the
contact fraction at its magnification. At small loads
``A → √(8/π) σ0/(E_r m2)`` for an elastic half-space (``G → E_r² m2²/(8σ0²)``; ``m2`` the rms
gradient), the theory's small-load slope. It is exact in full contact only; in 1D the BEM
puts the area above it at small loads (docs/validation/meanfield.md).

A discrete node (a sine wave) raises ``G`` in one step; its friction is weighted by the mean of
the contact fraction over that step (:func:`cell_average`, Gauss–Legendre in ``G``), the limit
of a narrow band of roughness.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import erf

from ..materials.protocol import Material

#: Gauss–Legendre points per node for the cell averages in ``G``.
CELL_POINTS = 8
#: Gauss–Legendre points over ``φ ∈ [0, π/2]`` for the 2D angular averages.
ANGLES_2D = 48


@dataclass(frozen=True)
class ModalResponse:
    """Full-contact response of every node at every speed (leading axes = speeds).

    Attributes
    ----------
    wavenumbers
        ``q_i`` [rad/mm].
    pressure_variance
        ``s_i`` [MPa²], shape ``(..., n_q)``.
    friction_stress
        ``f_i`` [MPa], shape ``(..., n_q)``: the full-contact friction stress of node ``i``.
    """

    wavenumbers: np.ndarray
    pressure_variance: np.ndarray
    friction_stress: np.ndarray


@dataclass(frozen=True)
class Compliance:
    """Half-space compliance ``M(q_i, φ_j)`` [mm/MPa] at the speeds, with angle weights."""

    values: np.ndarray           # (..., n_q, n_phi), complex
    cos_phi: np.ndarray          # (n_phi,)
    weights: np.ndarray          # (n_phi,), sum 1
    wavenumbers: np.ndarray
    variances: np.ndarray


def half_space_compliance(wavenumbers: np.ndarray, variances: np.ndarray, dimension: int,
                          material: Material, velocity, nu: float,
                          angles: int = ANGLES_2D) -> Compliance:
    """``M = 2/(q E_r(q v cos φ))`` on the nodes for each speed in ``velocity`` [mm/s]."""
    q = np.asarray(wavenumbers, float)
    if dimension == 1:
        cos_phi, weights = np.ones(1), np.ones(1)
    else:
        x, w = np.polynomial.legendre.leggauss(int(angles))
        cos_phi, weights = np.cos(np.pi / 4 * (x + 1)), w / 2
    v = np.asarray(velocity, float)[..., None, None]
    omega = q[:, None] * cos_phi * np.abs(v)
    e_r = material.complex_modulus(omega) / (1.0 - nu**2)
    if np.any(np.asarray(velocity) < 0):   # E(−ω) = conj E(ω): friction changes sign
        e_r = np.where(v < 0, np.conj(e_r), e_r)
    return Compliance(2.0 / (q[:, None] * e_r), cos_phi, weights, q,
                      np.asarray(variances, float))


def modal_response(comp: Compliance, interface=0.0, nodes=slice(None)) -> ModalResponse:
    """``s_i`` and ``f_i`` with the pressure transfer ``T = 1/(M + c)`` (module docstring).

    ``interface``: the compliance ``c`` [mm/MPa] in series with the half-space (0: the
    rubber touches the rigid surface), broadcastable to ``(..., n_q)`` of ``nodes``.
    """
    m = comp.values[..., nodes, :]
    q = comp.wavenumbers[nodes]
    c = np.asarray(interface, float)[..., None]
    t2 = 1.0 / np.abs(m + c) ** 2
    loss = -(q[:, None] * comp.cos_phi) * np.imag(m)
    s = comp.variances[nodes] * np.sum(t2 * comp.weights, axis=-1)
    f = comp.variances[nodes] * np.sum(t2 * loss * comp.weights, axis=-1)
    return ModalResponse(q, s, f)


def g_cumulative(pressure_variance: np.ndarray, mean_pressure) -> np.ndarray:
    """``G`` after each node: ``Σ_{j<=i} s_j / (2σ0²)`` [-] (along the last axis)."""
    sigma0 = np.asarray(mean_pressure, float)[..., None]
    return np.cumsum(pressure_variance, axis=-1) / (2.0 * sigma0**2)


def contact_fraction(g) -> np.ndarray:
    """``A = erf(1/(2√G))`` [-] (1 at ``G = 0``)."""
    g = np.asarray(g, float)
    with np.errstate(divide="ignore"):
        return np.where(g > 0, erf(0.5 / np.sqrt(np.maximum(g, 1e-300))), 1.0)


def cell_average(func, g_before: np.ndarray, g_after: np.ndarray,
                 points: int = CELL_POINTS) -> np.ndarray:
    """Mean of ``func(G)`` over ``[g_before, g_after]`` (Gauss–Legendre in ``G``)."""
    x, w = np.polynomial.legendre.leggauss(int(points))
    t = (x + 1) / 2
    g = g_before[..., None] + (g_after - g_before)[..., None] * t
    return np.sum(func(g) * w / 2, axis=-1)


def pressure_density(sigma, g: float, mean_pressure: float) -> np.ndarray:
    """``P(σ)`` [1/MPa] of the diffusion with the vanishing-at-zero boundary (image pair)."""
    s = np.asarray(sigma, float)
    var = 2.0 * g * mean_pressure**2
    norm = 1.0 / np.sqrt(2 * np.pi * var)
    dens = norm * (np.exp(-(s - mean_pressure) ** 2 / (2 * var))
                   - np.exp(-(s + mean_pressure) ** 2 / (2 * var)))
    return np.where(s >= 0, np.maximum(dens, 0.0), 0.0)


@dataclass(frozen=True)
class AreaCurve:
    """Contact fraction against magnification: after each node of the spectrum.

    Attributes
    ----------
    wavenumber
        ``q_i`` [rad/mm].
    magnification
        ``ζ_i = q_i/q_0`` [-].
    contact_fraction
        ``A(ζ_i)`` [-].
    g
        ``G(ζ_i)`` [-].
    """

    wavenumber: np.ndarray
    magnification: np.ndarray
    contact_fraction: np.ndarray
    g: np.ndarray


@dataclass(frozen=True)
class PressureDistribution:
    """``P(σ)`` at one magnification: ``∫P dσ`` = contact fraction, ``∫σP dσ = σ0``.

    Attributes
    ----------
    sigma
        Pressure grid [MPa] (ascending, from 0 or from where ``P`` is negligible).
    density
        ``P(σ)`` [1/MPa].
    wavenumber, magnification
        Resolution ``q`` [rad/mm] and ``ζ = q/q0`` [-].
    g
        ``G`` [-] at that magnification.
    mean_pressure
        ``σ0`` [MPa].
    fraction
        The contact fraction when the density is not the diffusion's (the strip cascade of
        :mod:`.strips`, a histogram), else ``None``.
    """

    sigma: np.ndarray
    density: np.ndarray
    wavenumber: float
    magnification: float
    g: float
    mean_pressure: float
    fraction: float | None = None

    @property
    def contact_fraction(self) -> float:
        """``erf(1/(2√G))`` [-] (the exact integral of :attr:`density`), or :attr:`fraction`."""
        if self.fraction is not None:
            return float(self.fraction)
        return float(contact_fraction(self.g))

    def expect(self, values) -> float:
        """``∫ P(σ) f(σ) dσ`` for ``f`` sampled on :attr:`sigma` (Simpson's rule)."""
        from scipy.integrate import simpson

        return float(simpson(self.density * np.asarray(values, float), x=self.sigma))


def pressure_distribution(g: float, mean_pressure: float, wavenumber: float,
                          magnification: float, points: int = 801) -> PressureDistribution:
    """Sample ``P(σ)`` on ``points`` pressures covering ``σ0 ± 9`` standard deviations."""
    sd = np.sqrt(2.0 * g) * mean_pressure
    lo = max(0.0, mean_pressure - 9.0 * sd)
    sigma = np.linspace(lo, mean_pressure + 9.0 * sd, int(points))
    return PressureDistribution(sigma, pressure_density(sigma, g, mean_pressure),
                                float(wavenumber), float(magnification), float(g),
                                float(mean_pressure))
