"""The wave's crests outside a strip (rubbercontact.meanfield.outer).

References: Westergaard's separation against the elastic BEM on one sine, its limits, the
line contacts' compatibility solved by the crest load, and the 1D BEM at 500 mm/s on the
ladder's three longest waves and on the whole 8-wave ladder (seed 3), where the strips'
friction was 14 % and 37 % high while the contact stayed inside the longer waves' strips.
"""

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact import meanfield as mf
from rubbercontact.meanfield.outer import (
    crest_load,
    outer_load,
    penetration,
    westergaard_separation,
)
from rubbercontact.roughness import SineSeries, random_ladder

SBR = rc.materials.sbr()


def test_separation_limits():
    theta = np.linspace(-np.pi, np.pi, 401)
    # no contact: the undeformed gap Δ(1 − cos θ); full contact: none
    assert westergaard_separation(theta, 0.0) == pytest.approx(1 - np.cos(theta), abs=1e-12)
    assert np.all(westergaard_separation(theta, 1.0) == 0.0)
    r = 0.3
    s = westergaard_separation(theta, r)
    assert np.all(s[np.abs(theta) <= np.pi * r] == 0.0)
    # grows away from the edge, where it leaves with zero slope (s ∝ (θ − α)^{3/2})
    out = theta > np.pi * r
    assert np.all(np.diff(s[out]) > 0)
    edge = np.pi * r
    assert float(westergaard_separation(edge + 1e-4, r)) < 1e-5


@pytest.mark.parametrize("x", [0.1, 0.3, 0.6])
def test_separation_is_the_elastic_bems(x):
    # one sine (λ = 1 mm, m2 = 0.3) at σ0 = x p*, relaxed SBR: the BEM's separation on the
    # grid against Δ·s(qx, r), r = (2/π) arcsin √x. Measured: 2e-6 Δ at N = 4096, 1e-7 at
    # N = 16384 (the contact edges fall between grid points)
    lam, m2 = 1.0, 0.3
    q = 2 * np.pi / lam
    amp = m2 * np.sqrt(2) / q
    p_star = q * amp * abs(SBR.complex_modulus(0.0)) / 0.75 / 2
    res = rc.halfspace.solve_sliding(SineSeries([lam], [amp]), lam, SBR, 0.0, x * p_star,
                                     n=4096)
    theta = q * (res.x - res.x[np.argmax(res.heights)])
    model = amp * westergaard_separation(theta, 2 / np.pi * np.arcsin(np.sqrt(x)))
    assert np.max(np.abs(res.separation - model)) < 1e-5 * amp


def test_penetration_is_the_amplitude_less_the_mean_gap():
    # Westergaard's mean gap Δ(1 − x + x ln x) and the crest tops' height above the rubber
    # add up to the amplitude; full contact: the crest tops stand Δ above the mean surface
    x = np.geomspace(1e-9, 1.0, 50)
    assert penetration(x) + (1 - x + x * np.log(x)) == pytest.approx(np.ones_like(x))
    assert float(penetration(1.0)) == 1.0


def test_crest_load_is_the_line_contact_compatibility():
    # W = πEκa²/4 sinks by (2W/πE)(ln(2d/a) + ½) relative to the strip d away
    kappa, e, d = 2.2, 12.0, 1.3
    for interference in (1e-6, 1e-3, 0.05):
        w = float(crest_load(interference, d, kappa, e))
        a = np.sqrt(4 * w / (np.pi * e * kappa))
        assert 2 * w / (np.pi * e) * (np.log(2 * d / a) + 0.5) == pytest.approx(interference,
                                                                                  rel=1e-3)
    assert float(crest_load(-0.01, d, kappa, e)) == 0.0


def _against_bem(surf: SineSeries, v: float, p0: float, n: int):
    bem = [rc.halfspace.solve_sliding(r, surf.period, SBR, v, p0, n=n)
           for r in surf.realizations(8, 1)]
    res = mf.solve(mf.PSD.from_sines(surf), SBR, v, p0, options=mf.StripOptions())
    mu, area = (np.array([getattr(b, k) for b in bem]) for k in ("friction",
                                                                 "contact_fraction"))
    return res, mu, area


def test_three_octave_waves_at_500_mm_s_against_the_bem():
    # 8, 4 and 2 mm (the 8-wave ladder's longest, seed 3) at 0.4 MPa: the BEM's contact
    # leaves the 4 mm wave's strips for the 2 mm wave's crests just outside them. Strips kept
    # inside the longer strips put the friction 14 % high; with the outer crests, within
    # 8 % in friction (measured +2 %) and 10 % in area plus twice the BEM mean's standard
    # error (measured +5 %)
    surf = SineSeries([8.0, 4.0, 2.0], [0.2572, 0.1966, 0.2254])
    res, mu, area = _against_bem(surf, 500.0, 0.4, 16384)
    se = area.std(ddof=1) / np.sqrt(area.size)
    assert res.friction == pytest.approx(mu.mean(), rel=0.08)
    assert res.contact_fraction == pytest.approx(area.mean(), rel=0.10 + 2 * se / area.mean())
    nested = mf.solve(mf.PSD.from_sines(surf), SBR, 500.0, 0.4,
                      options=mf.StripOptions(outer_crests=False))
    assert nested.friction > 1.1 * mu.mean()
    assert nested.inputs["outer_crests"] is False


def test_one_wave_has_no_outer_crests():
    # a single sine is Westergaard's exactly: nothing outside its strips, the two geometries
    # agree to rounding
    surf = SineSeries([1.0], [0.06])
    for v in (1.0, 500.0):
        a, b = (mf.solve(mf.PSD.from_sines(surf), SBR, v, 0.05,
                         options=mf.StripOptions(outer_crests=g))
                for g in (True, False))
        assert a.friction == pytest.approx(b.friction, rel=1e-12)
        assert a.contact_fraction == pytest.approx(b.contact_fraction, rel=1e-12)


def test_octave_ladder_at_500_mm_s_and_a_small_load_against_the_bem():
    # the random 8-wave ladder (seed 3) at 500 mm/s and its 2 % load (the BEM's A ≈ 2.4 %),
    # the ladder point furthest off before the outer crests (friction +37 %): within the
    # issue's 15 % in friction and in area (measured +14 % and −5 %; against 32 realizations
    # the same)
    res, mu, area = _against_bem(random_ladder(8, 3), 500.0, 0.4004, 16384)
    assert res.friction == pytest.approx(mu.mean(), rel=0.15)
    assert res.contact_fraction == pytest.approx(area.mean(), rel=0.15)


def test_outer_load_limits():
    # a 4 mm strip (fraction 0.3 of its 8 mm wave) under a 2 mm wave of p* = 1 MPa
    kw = dict(strip_wavenumber=np.pi / 4, strip_amplitude=0.25, contact_pressure=0.5,
              wavenumber=np.pi, amplitude=0.1, p_star=1.0)
    touching = outer_load(np.array([1.2]), residual=np.array([1.0]), **kw)
    assert 0 < touching.share[0] < 1 and 0 < touching.ratio[0] <= 1
    # a strip filling its period has no outside; a wave that only bends the strip lifts
    # nothing; a wave of negligible amplitude reaches no crest outside
    assert outer_load(np.array([4.0]), residual=np.array([1.0]), **kw).share[0] == 0
    assert outer_load(np.array([1.2]), residual=np.array([0.0]), **kw).share[0] == 0
    assert outer_load(np.array([1.2]), residual=np.array([1.0]),
                      **{**kw, "amplitude": 1e-6}).share[0] == 0
