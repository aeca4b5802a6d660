"""Time–temperature superposition: shift laws by hand, the TTS identity, and friction
against speed on the half-space (TTS, the two speed limits, the loss peak)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.halfspace import LennardJonesRepulsion, solve_sliding
from rubbercontact.materials import WLF, Arrhenius, GeneralizedMaxwell
from rubbercontact.roughness import SineSeries

SBR = rc.materials.sbr()
LAW = WLF(c1=8.86, c2=101.6, t_ref=20.0)


# --- shift laws against hand computation --------------------------------------------------------
def test_wlf_by_hand():
    # log10 a_T = -C1 (T - Tr)/(C2 + T - Tr)
    # T = 50 °C: -8.86 * 30 / (101.6 + 30) = -265.8 / 131.6 = -2.019756838905775
    assert LAW.log10_shift(50.0) == pytest.approx(-2.019756838905775, rel=1e-14)
    # T = 0 °C: -8.86 * (-20) / (101.6 - 20) = 177.2 / 81.6 = 2.171568627450980
    assert LAW.log10_shift(0.0) == pytest.approx(2.171568627450980, rel=1e-14)
    assert LAW.shift(0.0) == pytest.approx(10**2.171568627450980, rel=1e-13)
    assert LAW.shift(20.0) == 1.0
    np.testing.assert_allclose(LAW.log10_shift([0.0, 50.0]),
                               [2.171568627450980, -2.019756838905775], rtol=1e-14)


def test_arrhenius_by_hand():
    law = Arrhenius(activation_energy=100e3, t_ref=20.0)
    # ln a_T = Ea/R (1/T - 1/Tr) in kelvin; T = 50 °C = 323.15 K, Tr = 293.15 K, R = 8.314462618
    # 1/323.15 - 1/293.15 = (293.15 - 323.15)/(323.15 * 293.15) = -30/94731.4225
    #                     = -3.1668478e-4
    # Ea/R = 100000/8.314462618 = 12027.2355 K;  ln a = -3.8088425
    ln_a = 100000 / 8.314462618 * (-30 / 94731.4225)
    assert ln_a == pytest.approx(-3.8088425, rel=1e-7)
    assert law.shift(50.0) == pytest.approx(np.exp(ln_a), rel=1e-13)
    assert law.log10_shift(50.0) == pytest.approx(ln_a / np.log(10), rel=1e-13)
    assert law.shift(20.0) == 1.0


def test_wlf_singularity_and_bad_parameters():
    # singular at T_ref - C2 = -81.6 °C; at and below it the law has no meaning
    for t in (-81.6, -90.0):
        with pytest.raises(InputError, match="singularity"):
            LAW.shift(t)
    # -70 °C: log10 a = 8.86 * 90 / 11.6 = 68.74: finite, but a_T overflows a double near
    # the singularity (log10 a > 308 within 2.6 K of it): a clear error, not inf
    assert LAW.log10_shift(-70.0) == pytest.approx(8.86 * 90 / 11.6, rel=1e-14)
    with pytest.raises(InputError, match="overflows"):
        LAW.shift(-81.0)
    with pytest.raises(InputError, match="c2"):
        WLF(8.86, -5.0, 20.0)
    with pytest.raises(InputError, match="activation_energy"):
        Arrhenius(-1.0, 20.0)
    with pytest.raises(InputError, match="absolute zero"):
        Arrhenius(1e5, 20.0).shift(-300.0)
    with pytest.raises(InputError, match="no shift law"):
        SBR.at_temperature(40.0)


@pytest.mark.parametrize("law", [LAW, Arrhenius(80e3, 20.0)])
def test_rereferenced_law_is_the_ratio_of_shifts(law):
    t = np.array([-10.0, 5.0, 37.0, 80.0])
    moved = law.rereferenced(40.0)
    assert moved.t_ref == 40.0
    np.testing.assert_allclose(moved.shift(t), law.shift(t) / law.shift(40.0), rtol=1e-12)


# --- the TTS identity on the material -----------------------------------------------------------
@pytest.mark.parametrize("law", [LAW, Arrhenius(80e3, 20.0)])
@pytest.mark.parametrize("temperature", [-15.0, 20.0, 65.0])
def test_at_temperature_is_the_reference_at_shifted_frequency(law, temperature):
    w = np.logspace(-4, 12, 60)
    a_t = law.shift(temperature)
    hot = SBR.at_temperature(temperature, shift=law)
    # only the rounding of (ω a_T) τ against ω (a_T τ) separates the two: a few ulp
    np.testing.assert_allclose(hot.complex_modulus(w), SBR.complex_modulus(a_t * w),
                               rtol=1e-14)
    assert hot.equilibrium_modulus == SBR.equilibrium_modulus
    np.testing.assert_array_equal(hot.moduli, SBR.moduli)       # no vertical shift


def test_carried_shift_law_composes():
    mat = GeneralizedMaxwell(4.17, SBR.moduli, SBR.relaxation_times, shift=LAW)
    direct = mat.at_temperature(60.0)
    via = mat.at_temperature(0.0).at_temperature(60.0)     # the law re-referred to 0 °C
    np.testing.assert_allclose(via.relaxation_times, direct.relaxation_times, rtol=1e-13)
    assert direct.shift.t_ref == 60.0
    back = direct.at_temperature(20.0)
    np.testing.assert_allclose(back.relaxation_times, SBR.relaxation_times, rtol=1e-13)


def test_vertical_factor():
    hot = SBR.at_temperature(60.0, LAW, vertical=True)
    factor = (60.0 + 273.15) / (20.0 + 273.15)
    assert hot.equilibrium_modulus == pytest.approx(4.17 * factor, rel=1e-15)
    np.testing.assert_allclose(hot.moduli, SBR.moduli * factor, rtol=1e-15)


# --- friction against speed on the half-space ---------------------------------------------------
LAM, DELTA = 0.125, 0.002
SINE = SineSeries([LAM], [DELTA])
Q = 2 * np.pi / LAM


@pytest.mark.parametrize("temperature", [-10.0, 50.0])
@pytest.mark.parametrize("velocity", [1.0, 100.0])
@pytest.mark.parametrize("law", [None, LennardJonesRepulsion()])
def test_halfspace_tts(temperature, velocity, law):
    # the kernel depends on E(q v) only, so a material at T sliding at v is the reference
    # material at a_T v: same operator up to the rounding of (q v) (a_T τ) and the same
    # iterations, so the answers agree to round-off (measured: μ 1.2e-15, pressure 6e-13
    # relative to its peak)
    hot = SBR.at_temperature(temperature, LAW)
    a_t = LAW.shift(temperature)
    at_t = solve_sliding(SINE, None, hot, velocity, 0.1, n=512, law=law)
    reduced = solve_sliding(SINE, None, SBR, a_t * velocity, 0.1, n=512, law=law)
    assert at_t.friction > 0
    assert at_t.friction == pytest.approx(reduced.friction, rel=1e-12)
    assert at_t.contact_fraction == reduced.contact_fraction
    np.testing.assert_allclose(at_t.pressure, reduced.pressure, rtol=0,
                               atol=1e-11 * reduced.pressure.max())


def test_hysteretic_friction_vanishes_at_both_speed_limits():
    # E(ω) is real at both ends: Im E ≈ ω Σ E_i τ_i as ω → 0 and ≈ Σ E_i/(ω τ_i) as ω → ∞,
    # and E' tends to E_∞ and E_glassy. The contact tends to the elastic one and μ, first
    # order in Im E, falls like v at low speed and like 1/v at high speed. Relative
    # corrections are (ω τ_max)² ~ 1e-6 at v = 2e-3 mm/s and 1/(ω τ_min)² ~ 6e-6 at 2e10 mm/s
    # (ω = q v, q = 50/mm), below the solver's 1e-8-level residual effects: 1e-4 holds.
    sigma0 = 0.1    # partial contact on the rubbery and on the glassy side
    low = [solve_sliding(SINE, None, SBR, v, sigma0, n=512) for v in (2e-5, 2e-4, 2e-3)]
    high = [solve_sliding(SINE, None, SBR, v, sigma0, n=512) for v in (2e10, 2e11, 2e12)]
    peak = solve_sliding(SINE, None, SBR, 100.0, sigma0, n=512)
    assert all(r.contact_fraction < 1 for r in low + high)
    mu_low = np.array([r.friction for r in low])
    mu_high = np.array([r.friction for r in high])
    np.testing.assert_allclose(mu_low[1:] / mu_low[:-1], 10.0, rtol=1e-4)
    np.testing.assert_allclose(mu_high[1:] / mu_high[:-1], 0.1, rtol=1e-4)
    assert mu_low[0] < 1e-4 * peak.friction and mu_high[-1] < 1e-5 * peak.friction


def test_single_sine_full_contact_peaks_where_im_er_peaks():
    # full contact: μ = q²Δ² Im E_r(qv)/(4σ0) (closed form), so μ(v) peaks at the maximum
    # of Im E_r(ω), ω = q v. Full contact at every speed needs σ0 > |E_r| qΔ/2 with the
    # glassy |E_r| = 2901/0.75 MPa: Δ = 1e-4 mm and σ0 = 15 MPa (> 9.7 MPa).
    delta, sigma0 = 1e-4, 15.0
    sine = SineSeries([LAM], [delta])
    # Im E_r of Table 1 has several local maxima (one per branch, merged): the global one
    # from a 0.001-decade scan, refined by a bounded search
    x = np.linspace(3.0, 12.0, 9001)
    x0 = x[np.argmax(SBR.reduced_modulus(10.0**x).imag)]
    opt = minimize_scalar(lambda x: -SBR.reduced_modulus(10.0**x).imag,
                          bounds=(x0 - 0.002, x0 + 0.002), method="bounded",
                          options={"xatol": 1e-8})
    grid = np.logspace(4, 11, 29)     # ω, 4 per decade
    v_peak = 10.0**opt.x / Q

    def mu(v):
        res = solve_sliding(sine, None, SBR, v, sigma0, n=256)
        assert res.contact_fraction == 1.0
        er = complex(SBR.reduced_modulus(Q * v))
        # the full-contact solution is linear: the solver's answer is the closed form
        assert res.friction == pytest.approx(Q**2 * delta**2 * er.imag / (4 * sigma0),
                                             rel=1e-6)
        return res.friction

    at_peak = mu(v_peak)
    for step in (-0.1, 0.1):       # ±0.1 decade around the closed-form peak: both lower
        assert mu(v_peak * 10**step) < at_peak
    on_grid = [mu(w / Q) for w in grid]
    assert grid[int(np.argmax(on_grid))] == grid[np.argmax(SBR.reduced_modulus(grid).imag)]
