"""Statistics of line scans: HDC, PSD, rms height and slope against closed forms."""

import numpy as np
import pytest

from rubbercontact.errors import InputError
from rubbercontact.roughness import TABLE2, SineSeries, asphalt_ac8
from rubbercontact.roughness.statistics import (
    detrend,
    hdc,
    log_lags,
    psd,
    rms_height,
    rms_slope,
)


# -- Table 2 ---------------------------------------------------------------------------------
def test_table2_m2_column_from_wavelengths_and_amplitudes():
    lam, amp, m2_printed = TABLE2.T
    m2 = (2 * np.pi / lam) * amp / np.sqrt(2)  # m2 = qΔ/√2, paper eq. 16 for one sine
    np.testing.assert_allclose(SineSeries(lam, amp).rms_slopes(), m2, rtol=1e-14)
    # Waves 3–8 agree to the 4 significant digits printed.
    for mine, printed in zip(m2[2:], m2_printed[2:], strict=True):
        assert float(f"{mine:.4g}") == pytest.approx(printed, abs=1e-12)
    # Waves 1–2: qΔ/√2 of the printed amplitudes gives 1.3272 and 0.9412 against the
    # printed 1.3275 and 0.9403. Wave 1 is within the rounding of the 4-digit amplitude
    # (0.01867 ± 0.000005 gives 1.3269…1.3276); wave 2 is off by 0.1 %, apparently a typo
    # in the paper. Hence rtol 1e-3 for these two.
    np.testing.assert_allclose(m2[:2], m2_printed[:2], rtol=1e-3)
    assert 2 * np.pi / 0.0625 * 0.018665 / np.sqrt(2) <= 1.3275 <= \
        2 * np.pi / 0.0625 * 0.018675 / np.sqrt(2)


# -- HDC of a single sine ---------------------------------------------------------------------
DELTA, LAM = 0.02, 0.25  # mm


def test_hdc_single_sine_periodic_is_exact():
    n = 200  # 0.25 mm sampled at 1.25 µm, exactly one period
    dx = LAM / n
    z = DELTA * np.sin(2 * np.pi * np.arange(n) * dx / LAM + 0.7)
    lags, r = hdc(z, dx, periodic=True)
    exact = 2 * DELTA**2 * np.sin(np.pi * lags / LAM) ** 2  # paper eq. 14
    np.testing.assert_allclose(r, exact, rtol=0, atol=1e-15)
    # the plateau of eq. 15: 2Δ² at λ/2 …
    assert hdc(z, dx, LAM / 2, periodic=True)[1] == pytest.approx(2 * DELTA**2, rel=1e-12)
    # … and averaged over a whole wavelength of lags, R_zz = 2 z_rms² = Δ² (eq. 9).
    all_lags, all_r = hdc(z, dx, np.arange(n) * dx, periodic=True)
    assert all_r.mean() == pytest.approx(DELTA**2, rel=1e-12)
    assert all_r.mean() == pytest.approx(2 * rms_height(z) ** 2, rel=1e-12)


def test_hdc_single_sine_nonperiodic_within_sampling_bound():
    # 10.3 periods, not a whole number: the non-periodic estimator's error is the mean of
    # a cosine over the N−k pairs, |ε| <= 1/((N−k)|sin(q dx)|) relative (sum of a
    # geometric series), so "sampling accuracy" is that bound at every lag.
    dx = 0.005
    n = int(10.3 * LAM / dx)
    q = 2 * np.pi / LAM
    z = DELTA * np.sin(q * np.arange(n) * dx + 1.1)
    lags, r = hdc(z, dx, max_lag=2 * LAM)
    k = np.rint(lags / dx)
    exact = 2 * DELTA**2 * np.sin(q * lags / 2) ** 2
    bound = exact / ((n - k) * abs(np.sin(q * dx)))
    assert np.all(np.abs(r - exact) <= bound * (1 + 1e-9) + 1e-16)
    # the plateau value at λ/2 and the mean over one wavelength of lags
    assert r[k == LAM / 2 / dx][0] == pytest.approx(2 * DELTA**2, rel=0.02)
    assert r[k <= LAM / dx].mean() == pytest.approx(DELTA**2, rel=0.02)


def test_hdc_of_sampled_sine_series_equals_its_closed_form():
    s = asphalt_ac8(phases=np.linspace(0, 5, 8))
    x, z = s.grid(1600)  # 8 mm period at 5 µm
    lags, r = hdc(z, x[1], log_lags(x[1], 4.0), periodic=True)
    np.testing.assert_allclose(r, s.hdc(lags), rtol=1e-9)


def test_hdc_fft_matches_direct_sums_pooled_over_scans():
    rng = np.random.default_rng(3)
    scans = [np.cumsum(rng.normal(size=n)) for n in (50, 64, 64, 31)]
    ks = np.arange(1, 49)
    lags, r = hdc(scans, 1.0, ks)
    num = np.array([sum(np.sum((s[k:] - s[:-k]) ** 2) for s in scans if s.size > k)
                    for k in ks])
    den = np.array([sum(s.size - k for s in scans if s.size > k) for k in ks])
    np.testing.assert_allclose(r, num / den, rtol=1e-10)
    lags, rp = hdc(scans, 1.0, np.arange(1, 15), periodic=True)
    num = np.array([sum(np.sum((np.roll(s, -k) - s) ** 2) for s in scans) for k in range(1, 15)])
    np.testing.assert_allclose(rp, num / sum(s.size for s in scans), rtol=1e-10)
    # linear detrending is the same as removing the least-squares line first
    lin = [s - np.polyval(np.polyfit(np.arange(s.size), s, 1), np.arange(s.size)) for s in scans]
    np.testing.assert_allclose(hdc(scans, 1.0, ks, detrend="linear")[1], hdc(lin, 1.0, ks)[1],
                               rtol=1e-9)


def test_hdc_masked_counts_only_finite_pairs():
    rng = np.random.default_rng(4)
    z = np.cumsum(rng.normal(size=300))
    z[rng.random(300) < 0.1] = np.nan
    ks = np.arange(1, 120)
    _, r = hdc(z, 0.5, ks * 0.5, nan="omit")
    direct = [np.nanmean((z[k:] - z[:-k]) ** 2) for k in ks]
    np.testing.assert_allclose(r, direct, rtol=1e-10)
    with pytest.raises(InputError, match="profiles: contains NaN"):
        hdc(z, 0.5)


def test_lags_are_rounded_to_the_grid_and_log_lags_are_distinct():
    z = np.sin(np.arange(100) * 0.3)
    lags, _ = hdc(z, 0.1, [0.26, 1.0])
    np.testing.assert_allclose(lags, [0.3, 1.0])
    g = log_lags(0.005, 4.0)
    k = g / 0.005
    assert np.allclose(k, np.rint(k)) and np.all(np.diff(k) > 0)
    assert k[0] == 1 and k[-1] == 800


# -- PSD -------------------------------------------------------------------------------------
@pytest.mark.parametrize("n", [256, 255])
@pytest.mark.parametrize("mode", ["none", "mean", "linear"])
def test_psd_parseval(n, mode):
    rng = np.random.default_rng(n)
    scans = np.cumsum(rng.normal(size=(5, n)), axis=1) * 1e-3 + 0.3
    dx = 0.01
    q, c = psd(scans, dx, detrend=mode)
    dq = 2 * np.pi / (n * dx)
    np.testing.assert_allclose(np.diff(q), dq)
    zd = detrend(scans, mode)
    variance = np.mean(np.var(zd, axis=1))  # variance about each scan's mean
    assert np.sum(c) * dq == pytest.approx(variance, rel=1e-12)


def test_psd_of_a_sine_puts_its_variance_at_its_wavenumber():
    n, dx = 512, 0.01
    lam = n * dx / 8
    z = 0.03 * np.sin(2 * np.pi * np.arange(n) * dx / lam)
    q, c = psd(z, dx)
    i = int(np.argmax(c))
    assert q[i] == pytest.approx(2 * np.pi / lam)
    assert c[i] * (q[1] - q[0]) == pytest.approx(0.03**2 / 2, rel=1e-12)


# -- rms height and slope --------------------------------------------------------------------
def test_rms_slope_of_sampled_series_matches_sqrt_sum_m2():
    s = asphalt_ac8(phases=np.arange(8.0))
    n = 1600
    x, z = s.grid(n)
    dx = x[1]
    numeric = rms_slope(z, dx, periodic=True)
    # Over a whole period the cross terms vanish and first differences give exactly
    # sqrt(Σ 2Δ² sin²(q dx/2))/dx: each wave's m2 times sin(u)/u, u = q dx/2, whose
    # relative deficit is at most u²/6 = (q dx)²/24 — 1.05 % for the 0.0625 mm wave here.
    closed = np.sqrt(np.sum(2 * s.amplitudes**2 * np.sin(s.wavenumbers * dx / 2) ** 2)) / dx
    assert numeric == pytest.approx(closed, rel=1e-12)
    tol = (s.wavenumbers.max() * dx) ** 2 / 24
    assert s.rms_slope * (1 - tol) <= numeric <= s.rms_slope
    assert numeric == pytest.approx(np.sqrt(np.sum(TABLE2[:, 2] ** 2)), rel=tol + 1e-3)
    # halving dx shrinks the error four-fold (second order)
    _, z2 = s.grid(2 * n)
    err1 = 1 - numeric / s.rms_slope
    err2 = 1 - rms_slope(z2, dx / 2, periodic=True) / s.rms_slope
    assert err2 == pytest.approx(err1 / 4, rel=0.01)


def test_rms_height_of_sampled_series():
    s = asphalt_ac8(phases=np.arange(8.0))
    _, z = s.grid(1600)
    assert rms_height(z) == pytest.approx(s.rms_height, rel=1e-12)
    assert rms_height(z + 5.0) == pytest.approx(s.rms_height, rel=1e-12)


# -- bad inputs ------------------------------------------------------------------------------
def test_empty_profile_is_refused():
    with pytest.raises(InputError, match=r"profiles\[1\]: empty profile"):
        hdc([np.ones(10), np.array([])], 0.1)
    with pytest.raises(InputError, match="profiles: no profile given"):
        rms_height([])


def test_nan_heights_are_refused_with_the_scan_named():
    z = np.ones((3, 20))
    z[2, 7] = np.nan
    with pytest.raises(InputError, match=r"profiles\[2\]: contains NaN.*index 7"):
        rms_slope(z, 0.1)


@pytest.mark.parametrize("dx", [-0.1, 0.0, float("nan")])
def test_bad_dx_is_refused(dx):
    with pytest.raises(InputError, match="dx"):
        hdc(np.ones(10), dx)


def test_mismatched_lengths_refused_by_psd():
    with pytest.raises(InputError, match=r"profiles\[1\]: length 9 differs"):
        psd([np.ones(10), np.ones(9)], 0.1)


def test_bad_detrend_and_lags():
    with pytest.raises(InputError, match="detrend"):
        hdc(np.ones(10), 0.1, detrend="quadratic")
    with pytest.raises(InputError, match="lags"):
        hdc(np.ones(10), 0.1, [5.0])
    with pytest.raises(InputError, match="lags"):
        hdc(np.ones(10), 0.1, [-0.1])
