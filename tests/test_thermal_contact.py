"""The heat and the flash temperature of a solved half-space contact (thermal/contact.py)."""

from __future__ import annotations

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.thermal import (
    FILLED_SBR,
    ThermalProperties,
    contact_heating,
    flash_contact,
    thermal_admittance,
)

SBR = rc.materials.sbr()
WLF = rc.materials.WLF(8.86, 101.6, 20.0)
SINES = rc.roughness.SineSeries([1.0, 0.1, 0.01], [0.02, 0.002, 0.0002])


def _solve(pressure: float = 0.1, n: int = 2048):
    return lambda u: rc.halfspace.solve_sliding(SINES, None, SBR, u, pressure, n=n)


def test_the_heat_is_the_frictional_power():
    """Energy balance: the heat flux into the rubber averages to μ σ0 v, μ the solver's
    friction (to the solver's load balance, tol 1e-8), and it is released in the contact."""
    v = 300.0
    res = _solve()(v)
    heat = contact_heating(res)
    assert heat.mean_heat_flux == pytest.approx(res.friction * 0.1 * v, rel=1e-7)
    assert np.all(heat.heat_flux[res.pressure == 0] == 0)
    assert heat.contact_rise > 0 and heat.peak_rise >= heat.contact_rise


def test_full_contact_has_no_flash_and_the_mode_is_the_kernels():
    """One sine pressed into full contact: the pressure is σ0 + p̂ cos(kx + φ), the heat
    μ v p: its uniform part is the background's, so the contact (everywhere) is at the
    background on average, and the rise is the single mode μ v |p̂| / (K |λ(k)|)."""
    sine = rc.roughness.SineSeries([1.0], [0.001])
    v = 50.0
    res = rc.halfspace.solve_sliding(sine, None, SBR, v, 5.0, n=256)
    assert res.contact_fraction == 1.0
    heat = contact_heating(res, thermal=FILLED_SBR)
    assert abs(heat.contact_rise) < 1e-12 * heat.peak_rise
    p_hat = 2 * np.abs(np.fft.rfft(res.pressure)[1]) / res.pressure.size
    k = 2 * np.pi
    lam = thermal_admittance(k, k, v, FILLED_SBR.diffusivity)
    expected = res.friction * v * p_hat / (FILLED_SBR.conductivity_package * np.abs(lam))
    amplitude = 2 * np.abs(np.fft.rfft(heat.temperature)[1]) / heat.temperature.size
    assert amplitude == pytest.approx(expected, rel=1e-12)
    assert heat.peak_rise == pytest.approx(expected, rel=1e-4)   # the grid samples the crest


def test_an_infinitely_conducting_rubber_slides_isothermally():
    """K = 1e20 W/(m·K): the contact stays at the background (rise < tolerance) and the
    answer is the isothermal solve itself."""
    out = flash_contact(_solve(), 1e4, WLF, thermal=ThermalProperties(conductivity=1e20))
    assert out.contact_temperature == 20.0
    assert out.result.friction == out.isothermal.friction
    assert len(out.evaluations) == 1


def test_a_temperature_independent_rubber_heats_but_keeps_its_friction():
    """E_a = 1e-6 J/mol: a_T = 1 to 1e-9, so every solve is the isothermal one; the contact
    still heats by kelvins."""
    law = rc.materials.Arrhenius(1e-6, 20.0)
    out = flash_contact(_solve(), 1e4, law)
    assert out.contact_temperature > 21.0
    assert out.result.friction == pytest.approx(out.isothermal.friction, rel=1e-8)


def test_self_consistent_and_warmer_when_faster():
    """T_c is the rise of its own friction (to the tolerance, and within the jumps of the
    grid's contact set: 0.5 K), and a faster slide runs hotter."""
    slow = flash_contact(_solve(), 300.0, WLF)
    fast = flash_contact(_solve(), 1e4, WLF)
    for out in (slow, fast):
        rise = out.contact_temperature - 20.0
        assert out.heating.contact_rise == pytest.approx(rise, abs=0.5)
        assert out.shift_factor == pytest.approx(WLF.shift(out.contact_temperature), rel=1e-12)
    assert fast.contact_temperature > slow.contact_temperature > 20.0


def test_bad_input():
    with pytest.raises(InputError, match="velocity"):
        flash_contact(_solve(), 0.0, WLF)
    with pytest.raises(InputError, match="solve"):
        flash_contact("solve", 1.0, WLF)
    with pytest.raises(InputError, match="law"):
        flash_contact(_solve(), 1.0, {"law": "VFT"})
    with pytest.raises(InputError, match="temperature"):
        flash_contact(_solve(), 1.0, WLF, temperature="warm")
    with pytest.raises(InputError, match="singularity"):
        flash_contact(_solve(), 1.0, WLF, temperature=-90.0)


def test_the_background_shifts_the_isothermal_solve():
    """At T0 = 40 °C the isothermal solve runs at a_T(40 °C) v (the rubber at 40 °C is the
    reference rubber at that speed), and the contact is at T0 + its rise."""
    v = 1e3
    out = flash_contact(_solve(), v, WLF, temperature=40.0)
    ref = _solve()(WLF.shift(40.0) * v)
    assert out.isothermal.friction == pytest.approx(ref.friction, rel=1e-12)
    assert out.background_temperature == 40.0
    assert out.contact_temperature > 40.0
