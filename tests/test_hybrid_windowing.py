"""The windowed hybrid: the high-slope law read at the λ_hs-averaged low-slope pressure.

References: closed forms of the box average and of a hand-made law table; the VHS on the
whole two-wave surface (the linear peer, no FEM) for the scale-split limit.
"""

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.hybrid.law import linear_law
from rubbercontact.hybrid.tasks import halfspace_task
from rubbercontact.hybrid.windowing import window_average, windowed_hs_terms
from rubbercontact.roughness import SineSeries


def test_window_average_closed_forms():
    n, L = 400, 1.0
    rng = np.random.default_rng(0)
    f = rng.random(n)
    g = window_average(f, L, 0.1)            # 0.1 * 400 = 40 cells -> 41 (centred, odd)
    assert g.mean() == pytest.approx(f.mean(), rel=1e-12)   # mass is conserved
    i = 123
    assert g[i] == pytest.approx(f[i - 20:i + 21].mean(), rel=1e-12)
    np.testing.assert_allclose(window_average(np.full(n, 2.5), L, 0.3), 2.5, rtol=1e-12)
    spike = np.zeros(n)
    spike[0] = 41.0
    h = window_average(spike, L, 0.1)        # wraps around the period
    assert np.count_nonzero(h > 1e-12) == 41 and h.max() == pytest.approx(1.0)
    np.testing.assert_array_equal(window_average(f, L, 1e-4), f)   # below one cell
    np.testing.assert_allclose(window_average(f, L, L), f.mean())
    for bad in (0.0, -0.1, 1.5):
        with pytest.raises(rc.errors.InputError, match="window"):
            window_average(f, L, bad)
    with pytest.raises(rc.errors.InputError):
        window_average(np.r_[f[:-1], np.nan], L, 0.1)


def _table(c=0.3):
    """Hand-made law, as law_at_velocity orders it (u rising, σ falling to 0):
    σ = 20 (1 − u), Δτ = c σ², α = σ/(1 + σ), on 0..10 MPa."""
    sig = np.linspace(10.0, 0.0, 2001)
    return {"separation": list(1.0 - sig / 20), "pressure": list(sig),
            "contact_fraction": list(sig / (1 + sig)), "shear_stress": list(c * sig**2)}


def test_windowed_terms_of_an_isolated_patch_and_of_uniform_pressure():
    n, L, lam = 2000, 1.0, 0.1
    sigma0 = 0.2
    # A one-cell patch carrying all the load: the window spreads its force evenly over
    # one high-slope period (201 cells), so μ_hs = λ Δτ(σ0 L/λ)/(σ0 L) with Δτ = 0.3 σ².
    p = np.zeros(n)
    p[7] = sigma0 * n
    mu, area = windowed_hs_terms(p, L, lam, _table(), sigma0)
    w = 201 / n * L
    pbar = sigma0 * L / w
    # 2001-point table, read through the hybrid's PCHIP interpolant and resampled at 4096
    # points: the interpolation error is far below 1e-4
    assert mu == pytest.approx(w * 0.3 * pbar**2 / (sigma0 * L), rel=1e-4)
    assert area == pytest.approx(w * pbar / (1 + pbar) / L, rel=1e-4)
    # Uniform pressure: the window changes nothing.
    mu_u, area_u = windowed_hs_terms(np.full(n, 1.3), L, lam, _table(), 1.3)
    assert mu_u == pytest.approx(0.3 * 1.3, rel=1e-5)
    assert area_u == pytest.approx(1.3 / 2.3, rel=1e-5)
    with pytest.raises(rc.errors.InputError, match="1-D"):
        windowed_hs_terms(np.ones((4, 4)), L, lam, _table(), 1.0)


HS = SineSeries([0.0625], [0.01867])    # the paper's high-slope wave, m2 = 1.33


@pytest.fixture(scope="module")
def hs_linear_law():
    return linear_law(HS, rc.materials.sbr(), 10.0)


def _three(lam, m2, phases, p, table):
    """(VHS, hybrid, windowed hybrid) friction on high-slope wave + one low-slope wave."""
    mat = rc.materials.sbr()
    amp = m2 * np.sqrt(2) * lam / (2 * np.pi)
    ls = SineSeries([lam], [amp], [phases[1]])
    full = SineSeries([0.0625, lam], [0.01867, amp], list(phases))
    vhs = rc.halfspace.solve_sliding(full, lam, mat, 10.0, p, n=4096).friction
    kw = dict(n=4096, interface_law=table)
    hyb = float(halfspace_task(ls.as_dict(), lam, mat.as_dict(), 10.0, p, **kw)["friction"])
    win = float(halfspace_task(ls.as_dict(), lam, mat.as_dict(), 10.0, p, hs_window=0.0625,
                               **kw)["friction"])
    return vhs, hyb, win


def test_windowed_hybrid_holds_where_the_scales_are_not_separated(hs_linear_law):
    # Linear law (the VHS of the high-slope wave alone): every difference from the VHS on
    # the two-wave surface is the scale split. At λ_ls/λ_hs = 2 with a steep low-slope
    # wave (section 3's 0.125 mm wave, m2 = 0.94) the low-slope patches are a few µm,
    # far narrower than λ_hs: the paper's pointwise reading over-counts by ~50 % (measured
    # +52 %, docs/validation/scale_separation.md); read at the λ_hs-averaged pressure the
    # hybrid is within 15 % (measured +5 %; the window is a physical approximation, and
    # over the study's ratio-2 and ratio-4 cases it stays within ±11 %).
    vals = np.array([_three(0.125, 0.94, ph, 0.15, hs_linear_law)
                     for ph in ((0.3, 2.0), (4.0, 1.1))])
    vhs, hyb, win = vals.mean(axis=0)
    assert hyb / vhs - 1 > 0.3
    assert abs(win / vhs - 1) < 0.15


def test_windowed_and_pointwise_agree_when_the_scales_are_separated(hs_linear_law):
    # λ_ls/λ_hs = 16: the low-slope pressure varies slowly on λ_hs and the window changes
    # little (measured: windowed 0.596-0.707 vs pointwise 0.621-0.721, VHS 0.614-0.706);
    # both within 5 % of the VHS.
    vhs, hyb, win = _three(1.0, 0.94, (0.3, 2.0), 0.35, hs_linear_law)
    assert abs(hyb / vhs - 1) < 0.05
    assert abs(win / vhs - 1) < 0.05
