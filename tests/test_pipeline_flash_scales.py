"""Each scale of a hybrid at its own temperature (rubbercontact.pipeline.flash_scales).

Checked against what the code did not produce: the closed forms of a band source at low
and high Péclet number (asymptotic expansions of Jaeger's band, written here), the
Lambert-W root of the scalar equation with an exponential shift and a power-law friction,
the energy balance of a solved hybrid (the heat of both scales is ``μ σ0 v``, the solver's
load balance), the run's own one-temperature answer where the high-slope law has no
friction, and the isothermal answer where the rubber conducts perfectly or does not
shift. The runs reuse tests/test_pipeline_flash_hybrid.py's configuration and linear law.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from scipy.special import lambertw
from test_pipeline_flash_hybrid import HYBRIDS, WLF, _config, _linear_law

import rubbercontact as rc
from rubbercontact.hybrid.lawspeed import LawSpeeds
from rubbercontact.hybrid.lawtable import law_at_velocity
from rubbercontact.hybrid.windowing import windowed_hs_terms
from rubbercontact.pipeline import flash as pipeline_flash
from rubbercontact.pipeline.flash_halfspace import hybrid_solver
from rubbercontact.pipeline.flash_hybrid import SCALE_FLASH, LawReads, hybrid_scale
from rubbercontact.pipeline.flash_scales import (
    HighSlopeTerms,
    LawInPressure,
    ScaleSpots,
    scale_flash,
    scale_rise,
    shifted_reader,
)
from rubbercontact.pipeline.setup import resolve
from rubbercontact.thermal import FILLED_SBR, FlashSearch, flash_contact

SBR = FILLED_SBR
MODELS = (*HYBRIDS, "meanfield-hybrid")


@pytest.fixture(autouse=True)
def _no_continuation(monkeypatch):
    monkeypatch.setattr("rubbercontact.hybrid.lawtask.continue_with_linear_shape",
                        lambda table, *args, **kwargs: table)


def _band_fast(half_width, v, th) -> float:
    """Band centre per unit flux at high Péclet number: (2/K)√(RD/πv)."""
    return 2.0 / th.conductivity_package * np.sqrt(half_width * th.diffusivity / (np.pi * v))


def _band_slow(half_width, v, th) -> float:
    """Band centre at low Péclet number x = vR/2D: (2R/πK)(ln(2/x) − γ + 1) (K0's and
    sinh·K1's small-argument series)."""
    x = v * half_width / (2.0 * th.diffusivity)
    return 2 * half_width / (np.pi * th.conductivity_package) * (np.log(2 / x) - np.euler_gamma
                                                                  + 1)


@pytest.mark.parametrize("speed, closed, rtol", [
    (1e5, _band_fast, 1e-4),     # x = vR/2D ~ 1e4: next term 1/(8x) ~ 1e-5
    (1e-3, _band_slow, 1e-5),    # x ~ 1e-4: next term ~ x² ln x
])
def test_the_high_slope_rise_is_the_band_source_of_its_spots(speed, closed, rtol):
    """Without feedback (a law the same at every speed) the rise is one cascade step:
    (1/A_hs − 1/A_ls) Γ(R, v) μ_hs σ0 v, Γ the band's centre at the spot size λ_hs/4."""
    spots = ScaleSpots.of_cell(0.125, np.pi / 2, SBR, 1e-12)
    assert spots.half_width == pytest.approx(0.125 / 4, rel=1e-15)
    low = HighSlopeTerms(0.2, 0.02)
    out = scale_flash(lambda u: low, low, 20.0, speed, 0.3, 0.25, rc.materials.WLF(
        8.86, 101.6, 20.0), spots)
    expected = (1 / 0.02 - 1 / 0.25) * closed(0.125 / 4, speed, SBR) * 0.2 * 0.3 * speed
    assert out.rise == pytest.approx(expected, rel=rtol)
    assert out.terms == low and out.heat_flux == pytest.approx(0.2 * 0.3 * speed)
    # no concentration (the high-slope spots cover the low-slope contact): no rise
    assert scale_rise(HighSlopeTerms(0.2, 0.25), 0.25, out.spot_rise, 0.3, speed) == 0.0


def test_bad_spots_are_one_line():
    for kw, word in (({"half_width": -1.0}, "half_width"), ({"tolerance": 0.0}, "tolerance"),
                     ({"thermal": {"conductivity": 0.25}}, "thermal")):
        with pytest.raises(rc.errors.InputError, match=word) as err:
            ScaleSpots(**{"half_width": 0.03, "thermal": SBR, **kw})
        assert "\n" not in str(err.value)


def test_the_self_consistent_rise_is_lambert_w():
    """μ_hs = μ0 (u/v)^m (the law's friction a power of the reduced speed), A fixed, the
    exponential shift log10 a_T = −sΔT (WLF with C2 = 1e10 K: exponential to kΔT²/C2 <
    1e-7 at the 100 K reached): ΔT = ΔT0 e^{−kΔT}, k = m s ln 10, so ΔT = W(kΔT0)/k.
    Brent's root to 1e-9 K: 1e-6."""
    mu0, m, s, sigma0, a_ls, a_hs = 0.3, 0.4, 0.02, 0.3, 0.3, 0.03
    shift = rc.materials.WLF(s * 1e10, 1e10, 20.0)
    spots = ScaleSpots.of_cell(0.125, np.pi / 2, SBR, 1e-9)
    for v in (1e2, 1e4, 1e6):
        low = HighSlopeTerms(mu0, a_hs)
        out = scale_flash(lambda u, v=v: HighSlopeTerms(mu0 * (u / v) ** m, a_hs), low,
                          20.0, v, sigma0, a_ls, shift, spots)
        rise0 = (1 / a_hs - 1 / a_ls) * spots.spot_rise(v) * mu0 * sigma0 * v
        k = m * s * np.log(10)
        assert out.rise == pytest.approx(lambertw(k * rise0).real / k, rel=1e-6)
        assert out.residual < 1e-8 and out.temperature == 20.0 + out.rise
        assert out.terms.friction == pytest.approx(mu0 * np.exp(-k * out.rise), rel=1e-6)


def test_limits_keep_the_solves_own_terms_bit_for_bit():
    """Infinite conductivity (Γ → 0), no high-slope friction (no heat), a shift of 1 (the
    same law at every temperature): the solve's own terms, exactly, whatever the law's
    reading gives at the solve's speed."""
    low = HighSlopeTerms(0.123456789, 0.0456789)
    law = rc.materials.WLF(8.86, 101.6, 20.0)
    cold = replace(SBR, conductivity=1e300)
    out = scale_flash(lambda u: HighSlopeTerms(9.0, 0.5), low, 20.0, 1e4, 0.3, 0.3, law,
                      ScaleSpots(0.03, cold))
    assert out.rise == 0.0 and out.terms is low
    idle = HighSlopeTerms(0.0, 0.0456789)
    out = scale_flash(lambda u: idle, idle, 20.0, 1e4, 0.3, 0.3, law, ScaleSpots(0.03, SBR))
    assert out.rise == 0.0 and out.terms is idle
    # shifted_reader: a law the same at both speeds moves nothing, its reading aside
    reader = shifted_reader(lambda u: HighSlopeTerms(0.7, 0.3), low, 1.0)
    assert reader(10.0) == low


def test_the_law_in_pressure_is_blended_at_fixed_pressure(hand_made_law):
    """At a tabulated speed the reading is the table's through its own interpolant (the
    windowed hybrid's, exactly); Δτ doubled at the faster speed: √2 Δτ halfway in ln v at
    every pressure (1e-12), the contact fraction unchanged; below the slowest speed the
    slowest table, the read counted as clamped."""
    a = hand_made_law(41)
    b = {**a, "shear_stress": [2.0 * t for t in a["shear_stress"]]}
    reads = LawReads()
    law = LawInPressure(LawSpeeds({1.0: a, 100.0: b}), reads)
    p = np.linspace(0.0, 12.0, 257)             # beyond the table's 10 MPa: held
    read = law.reader(p, np.mean, 2.0)
    at_a, mid = read(1.0), read(10.0)
    assert at_a.friction == windowed_hs_terms(p, 1.0, 1.0 / 257, a, 2.0)[0]
    assert mid.friction == pytest.approx(np.sqrt(2.0) * at_a.friction, rel=1e-12)
    assert mid.contact_fraction == pytest.approx(at_a.contact_fraction, rel=1e-12)
    assert read(0.1) == at_a and reads.clamped == 1 and reads.reads == 3


def _hot_solve(tmp_path, speed: float):
    """One realization of ``hybrid`` at 0.3 MPa searched at ``speed`` with its high-slope
    scale at its own temperature."""
    cfg = _config(tmp_path)
    setup = resolve(rc.config.parse_config(cfg))
    law = _linear_law(cfg)
    laws = LawSpeeds({float(v): law_at_velocity(law, float(v))
                      for v in law["velocity"].values})
    reads = LawReads()
    spots = ScaleSpots.of_cell(setup.hs0.period, np.pi / 2, SBR, 1e-2)
    shift = rc.materials.WLF(**{k: WLF[k] for k in ("c1", "c2")}, t_ref=20.0)
    hook = hybrid_scale(0.3, laws, reads, None, spots, shift)
    solve = hybrid_solver(setup, "hybrid", 0, 0.3, laws, reads)
    return flash_contact(solve, speed, shift, SBR, search=FlashSearch(warm_start=True),
                         scale=hook), spots


def test_both_scales_heat_with_mu_sigma0_v_and_the_spots_are_hotter(tmp_path):
    """The heat into the rubber is μ σ0 v and it is the two scales' heats together
    (μ_ls σ0 v on the low-slope contact, μ_hs σ0 v concentrated in the high-slope spots);
    tolerance 1e-7, the solver's load balance (tol 1e-8 on 256 points). The high-slope
    spots are hotter than the contact they sit in, by their band source at the Péclet
    number of 1e4 mm/s (x ~ 1e3: the fast closed form to 1e-3)."""
    f, spots = _hot_solve(tmp_path, 1e4)
    hs = f.result.info[SCALE_FLASH]
    v, sigma0 = 1e4, 0.3
    assert f.heating.mean_heat_flux == pytest.approx(f.result.friction * sigma0 * v, rel=1e-7)
    both = f.result.friction_ls * sigma0 * v + hs.heat_flux
    assert both == pytest.approx(f.heating.mean_heat_flux, rel=1e-7)
    assert f.result.friction == pytest.approx(f.result.friction_ls + hs.terms.friction,
                                              rel=1e-12)
    assert hs.low_temperature == pytest.approx(f.contact_temperature, abs=0.1)
    assert hs.rise > 1.0 and hs.residual < 1e-2
    gamma = _band_fast(spots.half_width, v, SBR)
    expected = (1 / hs.terms.contact_fraction - 1 / hs.low_area) * gamma * hs.heat_flux
    assert hs.rise == pytest.approx(expected, rel=1e-3)


def _runs(tmp_path, monkeypatch, law_edit=None, **cfg_over):
    """The run with each scale at its own temperature and with one for both."""
    cfg = _config(tmp_path, models=list(MODELS), **cfg_over)
    law = _linear_law(cfg)
    if law_edit is not None:
        law = law_edit(law)
    out = {}
    plan = pipeline_flash.plan_flash
    for per_scale in (True, False):
        monkeypatch.setattr("rubbercontact.pipeline.execute.plan_flash",
                            lambda s, p=per_scale: replace(plan(s), per_scale=p))
        c = {**cfg, "output": {"directory": str(tmp_path / f"out{per_scale}")}}
        out[per_scale] = rc.pipeline.run(c, law=law, progress=False)
    return out


@pytest.mark.filterwarnings("ignore::rubbercontact.hybrid.lawtable.LawWarning")
def test_a_law_without_friction_is_the_one_temperature_answer(tmp_path, monkeypatch):
    """Δτ_hs ≡ 0: no heat in the high-slope spots, T_hs = T_ls, and every hybrid's answer
    is the one-temperature answer bit for bit."""
    runs = _runs(tmp_path, monkeypatch,
                 lambda law: law.assign(shear_stress=0.0 * law["shear_stress"]))
    new, old = runs[True], runs[False]
    for m in MODELS:
        for k in ("friction_flash", "contact_fraction_flash", "flash_temperature"):
            np.testing.assert_array_equal(new[k].sel(model=m), old[k].sel(model=m))
        np.testing.assert_array_equal(new["flash_temperature_hs"].sel(model=m),
                                      new["flash_temperature"].sel(model=m))
        assert np.all(np.isnan(old["flash_temperature_hs"].sel(model=m)))
    assert new["flash_temperature"].sel(model="hybrid").values[-1, 0] > 1.0


@pytest.mark.filterwarnings("ignore::rubbercontact.hybrid.lawtable.LawWarning")
def test_the_high_slope_spots_are_hotter_and_heat_more_with_the_speed(tmp_path,
                                                                       monkeypatch):
    """T_hs ≥ T_ls at every speed, both growing with the speed; where the spots heat the
    answer moves off the one-temperature answer; the heat is μ σ0 v."""
    runs = _runs(tmp_path, monkeypatch)
    new, old = runs[True], runs[False]
    v = new["velocity"].values
    for m in MODELS:
        h = new.sel(model=m, pressure=0.3)
        t_ls, t_hs = h["flash_temperature"].values, h["flash_temperature_hs"].values
        assert np.all(t_hs >= t_ls) and np.all(np.diff(t_hs) > 0)
        assert t_hs[-1] - t_ls[-1] > 1.0
        mu, mu_old = h["friction_flash"].values, old.sel(model=m, pressure=0.3)[
            "friction_flash"].values
        assert mu[-1] != mu_old[-1]
        np.testing.assert_allclose(h["flash_heat_flux"], mu * 0.3 * v, rtol=1e-7)
