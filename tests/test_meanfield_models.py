"""The mean-field models by name (issue 38, item 5): Persson's theory with ``S(q)``
(``meanfield``), the strip cascade (``meanfield-strips``), their options as small strategy
objects, and an option that does not apply refused in one line.

Expectations from outside the code: the closed form of full contact, ``S`` as published
(``S = γ + (1 − γ)A²``: γ = 1 is the uncorrected theory, the friction linear in γ), and
Persson's integral over a node's cell done by adaptive quadrature.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import erf

import rubbercontact as rc
from rubbercontact import meanfield as mf
from rubbercontact.errors import InputError
from rubbercontact.roughness import SineSeries

SBR = rc.materials.sbr()
T2 = rc.roughness.asphalt_ac8()
BASE = {"surface": {"preset": "section3"}, "velocities": [10.0], "loads": {"pressures": [0.2]}}


def _er(omega, nu=0.5):
    return SBR.complex_modulus(omega) / (1 - nu**2)


@pytest.mark.parametrize("gamma", [0.2, mf.DEFAULT_GAMMA, 1.0])
@pytest.mark.parametrize("weighting", ["cell", "after"])
def test_full_contact_s_is_irrelevant_and_the_friction_is_the_closed_form(gamma, weighting):
    # A → 1: S = γ + (1 − γ) = 1 for every γ, and μ = Σ q²Δ² Im E_r(qv)/(4σ0)
    q, d = T2.wavenumbers, T2.amplitudes
    opts = mf.MeanFieldOptions(correction=gamma, weighting=weighting)
    for v in (1.0, 50.0):
        sigma0 = 1e4 * float(np.max(q * d * np.abs(_er(q * v))))
        exact = float(np.sum(q**2 * d**2 * _er(q * v).imag) / (4 * sigma0))
        res = mf.solve(mf.PSD.from_sines(T2), SBR, v, sigma0, options=opts)
        assert res.contact_fraction == 1.0
        assert res.friction == pytest.approx(exact, rel=1e-12)


def test_gamma_one_is_the_uncorrected_theory_by_quadrature():
    # Persson 2001 (S = 1): μ = Σ f_i <A>_i/σ0, <A>_i the mean of erf(1/(2√G)) over the
    # node's step in G, here by adaptive quadrature from f_i and G_i of the closed forms
    # s_i = q²|E_r|²v_i/4, f_i = q² v_i Im E_r/2 (one sine: Δ²/2 = v_i).
    psd = mf.PSD.from_sines(T2)
    v, sigma0 = 10.0, 0.3
    q, var = psd.wavenumbers, psd.variances
    e = _er(q * v)
    g = np.cumsum(q**2 * np.abs(e) ** 2 * var / 4) / (2 * sigma0**2)
    f = q**2 * var * e.imag / 2
    g0 = np.concatenate([[0.0], g[:-1]])
    mean_a = [quad(lambda x: erf(1 / (2 * np.sqrt(x))) if x > 0 else 1.0, a, b,
                   epsrel=1e-12, epsabs=0)[0] / (b - a) for a, b in zip(g0, g, strict=True)]
    expected = float(np.sum(f * np.array(mean_a)) / sigma0)
    res = mf.solve(psd, SBR, v, sigma0, options=mf.MeanFieldOptions(correction=1.0))
    assert res.friction == pytest.approx(expected, rel=1e-6)
    after = mf.solve(psd, SBR, v, sigma0,
                     options=mf.MeanFieldOptions(correction=1.0, weighting="after"))
    assert after.friction == pytest.approx(
        float(np.sum(f * erf(1 / (2 * np.sqrt(g)))) / sigma0), rel=1e-12)


def test_s_as_published_one_sine_and_linear_in_gamma():
    # one sine weighed after the wave: μ(γ)/μ(1) = γ + (1 − γ)A² exactly, A the theory's
    psd = mf.PSD.from_sines(SineSeries([1.0], [0.02]))
    after = {g: mf.solve(psd, SBR, 10.0, 0.05, options=mf.MeanFieldOptions(
        correction=g, weighting="after")) for g in (0.3, 0.5, 1.0)}
    a = after[1.0].contact_fraction
    assert 0.01 < a < 0.5
    for g in (0.3, 0.5):
        assert after[g].friction / after[1.0].friction == pytest.approx(g + (1 - g) * a**2,
                                                                        rel=1e-12)
    # S is linear in γ at every A, so μ is: μ(½) is the mean of μ(0.2) and μ(0.8)
    spectrum = mf.PSD.self_affine(hurst=0.8, qr=2.0, q1=2e3, rms_slope=0.3)
    mu = {g: mf.solve(spectrum, SBR, 10.0, 0.3, options=mf.MeanFieldOptions(
        correction=g)).friction for g in (0.2, 0.5, 0.8)}
    assert mu[0.5] == pytest.approx((mu[0.2] + mu[0.8]) / 2, rel=1e-12)
    assert mf.MeanFieldOptions().correction.describe() == "S = 0.8 + 0.2 A²"
    assert mf.MeanFieldOptions(correction=1.0).correction.describe() == "S = 1"


def _one_line(make, match: str, error=InputError) -> None:
    with pytest.raises(error, match=match) as err:
        make()
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("make, match", [
    (lambda: mf.solve(mf.PSD.from_sines(T2), SBR, 10.0, 0.3,
                      options=mf.MeanFieldOptions(interface="rigid")), "with a law"),
    (lambda: mf.solve(mf.PSD.self_affine(hurst=0.8, qr=2.0, q1=50.0, rms_slope=0.3), SBR,
                      10.0, 0.3, options=mf.StripOptions()), "sine series"),
    (lambda: mf.solve(mf.PSD.self_affine(hurst=0.8, qr=2.0, q1=50.0, rms_slope=0.3,
                                         dimension=2), SBR, 10.0, 0.3,
                      options=mf.MeanFieldOptions(dissipation="patch")), "2D"),
    (lambda: mf.options_from_dict({"model": "strips", "gamma": 0.5}), "do not apply"),
    (lambda: mf.options_from_dict({"model": "diffusion"}), "model must be"),
    (lambda: rc.models.MeanField(mf.StripOptions()), "MeanFieldOptions"),
    (lambda: rc.models.MeanFieldStrips(mf.MeanFieldOptions()), "StripOptions"),
])
def test_an_option_that_does_not_apply_is_refused_in_one_line(make, match):
    _one_line(make, match)


@pytest.mark.parametrize("table, models, match", [
    ({"outer_crests": False}, ["vhs", "meanfield"], "meanfield-strips"),
    ({"interface": "rigid"}, ["meanfield"], "meanfield-hybrid"),
    ({"gamma": 0.5}, ["vhs", "meanfield-strips"], "meanfield or meanfield-hybrid"),
    ({"dissipation": "patch"}, ["meanfield-strips"], "dissipation"),
    ({"spectrum": "sines"}, ["meanfield-strips"], "spectrum"),
    ({"geometry": "strips"}, ["meanfield"], "model 'meanfield-strips'"),
    ({"correction": "none"}, ["meanfield"], "gamma = 1 is S = 1"),
])
def test_a_config_key_for_a_model_not_run_is_refused_in_one_line(table, models, match):
    _one_line(lambda: rc.config.parse_config({**BASE, "models": models, "meanfield": table}),
              match)


def test_config_options_are_the_option_objects():
    cfg = rc.config.parse_config({**BASE, "models": ["meanfield", "meanfield-strips"]})
    assert cfg.meanfield.options("meanfield") == mf.MeanFieldOptions()
    assert cfg.meanfield.options("meanfield-strips") == mf.StripOptions()
    cfg = rc.config.parse_config({**BASE, "models": ["meanfield-hybrid", "meanfield-strips"],
                                  "meanfield": {"gamma": 1.0, "weighting": "after",
                                                "interface": "rigid", "outer_crests": False}})
    assert cfg.meanfield.options("meanfield-hybrid") == mf.MeanFieldOptions(
        correction=1.0, weighting="after", interface="rigid")
    assert cfg.meanfield.options("meanfield-strips") == mf.StripOptions(outer_crests=False)
    for opts in (mf.MeanFieldOptions(correction=0.4, dissipation="cascade"),
                 mf.StripOptions(outer_crests=False)):
        assert mf.options_from_dict(opts.to_dict()) == opts


def test_strips_are_a_registered_model_sharing_the_runs_cache_entries(tmp_path):
    from rubbercontact.pipeline.plan import meanfield_call

    assert {"meanfield", "meanfield-strips"} <= set(rc.models.available())
    strips = rc.models.create("meanfield-strips")
    assert isinstance(strips, rc.models.MeanFieldStrips)
    p = np.array([0.2, 0.35])
    res = strips.solve(T2, SBR, 10.0, p)
    direct = [mf.solve(mf.PSD.from_sines(T2), SBR, 10.0, float(pi),
                       options=mf.StripOptions()) for pi in p]
    np.testing.assert_allclose(res.friction, [d.friction for d in direct], rtol=1e-12)
    cfg = rc.config.parse_config({**BASE, "models": ["meanfield-strips", "meanfield"]})
    for name, model in (("meanfield-strips", strips), ("meanfield", rc.models.MeanField())):
        fn, kw = meanfield_call(cfg, name, T2.as_dict(), SBR, 10.0, 0.2, None, T2.period)
        (task,) = model.tasks(T2, SBR, 10.0, [0.2])
        assert task.function == fn and task.kwargs == kw
