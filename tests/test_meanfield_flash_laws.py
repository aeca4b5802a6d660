r"""The mean-field flash temperature against closed forms of its own theory
(rubbercontact.meanfield.flash, "One scale, in closed form" in its docstring).

A spectrum of one node and a power-law rubber ``E(ω) = E1 (iωτ)^n`` make the
self-consistency a scalar equation: a shift ``a`` multiplies the modulus by the real
``a^n``, and Persson's theory depends on ``(E, σ0)`` only through ``σ0/E`` (ratios of
``|E|²/σ0²`` and ``Im E/σ0``), so the node at ``T`` has the isothermal theory's friction
and area at the load ``σ0 a_T(T)^{−n}``; its rise is
``ΔT = (1/A − 1) Γ(R) μ σ0 v`` with ``Γ`` the centre temperature of a spot of radius
``R = (π/2)/q`` (:mod:`rubbercontact.thermal.spots`). Checked here against the
isothermal theory (:func:`rubbercontact.meanfield.friction_curve`, which has no modulus
tables and no fixed point) and the Lambert-W solution of the small-load, exponential
-shift case.

The published trend (the peak's drop and shift in Persson 2006's model compound) is not
reproduced: the paper's master curve and surface are not available to this project in
numbers (issue 40). The speeds its abstract states are checked on a typical case in
tests/test_meanfield_flash_published.py (docs/validation/flash_temperature.md).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.special import lambertw

import rubbercontact as rc
from rubbercontact import meanfield as mf
from rubbercontact.meanfield.flash import FlashOptions, flash_friction_curve
from rubbercontact.thermal import band_centre_temperature, disc_centre_temperature

#: One wave of 1 mm wavelength and 50 µm amplitude: ``q = 2π`` rad/mm, spot radius 0.25 mm.
Q, VARIANCE = 2 * np.pi, 0.05**2 / 2
#: Exponent of the power-law modulus [-].
N_POWER = 0.3
#: Decades the shift moves per kelvin [1/K]: an exponential shift, by a WLF law whose
#: ``C2`` (1e8 K) makes it linear to ``ΔT/C2`` < 1e-5 relative over the rises here.
SLOPE = 0.03
LINEAR = rc.materials.WLF(SLOPE * 1e8, 1e8, 20.0)
CLASSIC = rc.materials.WLF(8.86, 101.6, 20.0)
THERMAL = FlashOptions().thermal
#: The fixed point's tolerance [K] used here.
TOL_K = 1e-7


class PowerLaw:
    """``E(ω) = E1 (i|ω|τ)^n`` [MPa] (conjugate for ω < 0): shifting its frequency by
    ``a`` multiplies it by the real ``a^n``, its loss angle staying ``nπ/2``."""

    name = "power-law rubber"
    is_elastic = False

    def __init__(self, e1: float = 10.0, n: float = N_POWER, tau: float = 1e-3) -> None:
        self.e1, self.n, self.tau = e1, n, tau

    def complex_modulus(self, omega):
        w = np.asarray(omega, float)
        e = self.e1 * (1j * np.abs(w) * self.tau) ** self.n
        return np.where(w < 0, np.conj(e), e)


def _psd(dimension: int) -> mf.PSD:
    return mf.PSD(np.array([Q]), np.array([VARIANCE]), dimension, source="one node")


def _gamma(dimension: int, v: float) -> float:
    """Centre temperature [K per mW/mm²] of the node's spot of radius (π/2)/q at v."""
    spot = disc_centre_temperature if dimension == 2 else band_centre_temperature
    return float(spot(np.pi / 2 / Q, v, THERMAL))


def _isothermal_rise(psd: mf.PSD, v: float, sigma0: float, load: float) -> float:
    """``(1/A − 1) Γ μ σ0 v`` [K] with the isothermal theory's μ, A at ``load`` [MPa]
    (the heat is the true load's ``σ0``'s: ``μ σ0 v``)."""
    c = mf.friction_curve(psd, PowerLaw(), [v], load)
    return ((1 / c.contact_fraction[0] - 1) * _gamma(psd.dimension, v) * c.friction[0]
            * sigma0 * v)


@pytest.mark.parametrize("law", [LINEAR, CLASSIC], ids=["exponential", "WLF"])
@pytest.mark.parametrize("dimension", [1, 2])
def test_one_node_is_the_scalar_equation(dimension, law):
    """At 0.1 MPa (A = 3–9 %, not small) and 1e2–1e6 mm/s the flash's rise is the root
    of ``ΔT = (1/A − 1) Γ μ σ0 v`` with μ, A the isothermal theory's at ``σ0 a_T^{−n}``:
    to 2e-7 relative (the fixed point stops within 1e-7 K of its root and the rises are
    ≥ 0.8 K; the modulus tables are cubic to < 1e-9; measured ≤ 1.3e-9), and μ is that
    theory's at the root to 1e-6 (its tables against its direct sums, < 1e-8 elsewhere)."""
    psd, sigma0 = _psd(dimension), 0.1
    speeds = np.array([1e2, 1e4, 1e6])
    out = flash_friction_curve(psd, PowerLaw(), speeds, sigma0,
                               flash=FlashOptions(shift=law, tolerance=TOL_K))
    for v, rise, mu in zip(speeds, out.flash_temperature, out.friction, strict=True):
        def excess(dt, v=v):
            load = sigma0 * 10.0 ** (-N_POWER * float(law.log10_shift(20.0 + dt)))
            return _isothermal_rise(psd, v, sigma0, load) - dt

        top = _isothermal_rise(psd, v, sigma0, sigma0)   # heating softens: a root below
        root = brentq(excess, 0.0, top, xtol=1e-10, rtol=1e-13)
        assert rise == pytest.approx(root, rel=2e-7)
        load = sigma0 * 10.0 ** (-N_POWER * float(law.log10_shift(20.0 + root)))
        iso = mf.friction_curve(psd, PowerLaw(), [v], load)
        assert mu == pytest.approx(iso.friction[0], rel=1e-6)


@pytest.mark.parametrize("dimension", [1, 2])
def test_high_speed_flash_is_self_limited_as_lambert_w(dimension):
    """Small load, exponential shift ``log10 a_T = −s ΔT``, high speed (``uR`` = 1e4–1e6).

    Without feedback the rise is ``ΔT0 = Γ μ σ0 v / A``, and at ``uR ≫ 1``
    ``Γ → (2/K)√(RD/πv)`` while ``A ∝ σ0/|E(qv)| ∝ v^{−n}`` (μ fixed by the loss angle):
    ``ΔT0 ∝ v^{1/2+n}``. With the feedback the modulus falls by ``a^n = 10^{−n s ΔT}``, the
    area grows by its inverse, so ``ΔT = ΔT0 e^{−kΔT}``, ``k = n s ln 10``:
    ``ΔT = W(kΔT0)/k`` (Lambert's W), which grows only as ``(1/k) ln v`` once
    ``kΔT0 ≫ 1``: the flash limits itself.

    Tolerances: ΔT0's power law to 3e-4 between 1e4 and 1e6 mm/s (Γ's asymptote is off by
    O(1/(uR)) < 1e-4; the area's departure from ``A ∝ σ0/|E|`` is O(A) < 2e-4 at 1e-3
    MPa; measured 1.2e-5); the flash against Lambert's W to 1e-3 (the neglected −1 and the
    area's curvature, both O(A) < 2e-4: measured 1.4–2.0e-4)."""
    psd, sigma0 = _psd(dimension), 1e-3
    speeds = np.array([1e4, 1e5, 1e6])
    out = flash_friction_curve(psd, PowerLaw(), speeds, sigma0,
                               flash=FlashOptions(shift=LINEAR, tolerance=TOL_K))
    assert np.all(out.contact_fraction_isothermal < 2e-4)
    d = THERMAL.diffusivity
    u_r = speeds / (2 * d) * np.pi / 2 / Q
    assert u_r.min() > 1e4
    asymptote = 2 / THERMAL.conductivity_package * np.sqrt(np.pi / 2 / Q * d / (np.pi * speeds))
    gamma = np.array([_gamma(dimension, v) for v in speeds])
    np.testing.assert_allclose(gamma, asymptote, rtol=1e-4)
    rise0 = gamma * out.friction_isothermal * sigma0 * speeds / out.contact_fraction_isothermal
    np.testing.assert_allclose(rise0 / rise0[0], (speeds / speeds[0]) ** (0.5 + N_POWER),
                               rtol=3e-4)
    k = N_POWER * SLOPE * np.log(10)
    expected = lambertw(k * rise0).real / k
    np.testing.assert_allclose(out.flash_temperature, expected, rtol=1e-3)
    assert k * rise0[-1] > 10               # in the logarithmic regime at the top speed
    # a decade of speed adds about (1/k) ln(10^{1/2+n}) less the log-log correction
    step = np.diff(out.flash_temperature)
    assert np.all(step < (0.5 + N_POWER) * np.log(10) / k)
    assert out.flash_temperature[-1] < rise0[-1] / 5
