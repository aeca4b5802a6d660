"""Sine-series fits of the HDC (paper eqs. 29–30) on data of known answer."""

import warnings

import numpy as np
import pytest

from rubbercontact.errors import InputError
from rubbercontact.roughness import (
    TABLE2,
    RoughnessWarning,
    SineSeries,
    asphalt_ac8,
    fit_hdc,
    fit_hdc_curve,
    fit_hdc_details,
    octave_wavelengths,
    synthetic_line_scans,
    wave_hdc,
)
from rubbercontact.roughness.statistics import hdc, log_lags

DX = 0.005  # 12.5 points per wavelength for the shortest (0.0625 mm) wave


@pytest.fixture(scope="module")
def table2_scans():
    """30 random-phase scans of 16 mm of Table 2's surface, 0.5 µm noise (the default)."""
    return synthetic_line_scans(asphalt_ac8(), n_scans=30, length=16.0, dx=DX, seed=11)


def test_octave_ladder_is_table2():
    np.testing.assert_allclose(octave_wavelengths(0.0625, 8.0), TABLE2[:, 0])
    np.testing.assert_allclose(octave_wavelengths(upper_cutoff=8.0, n_waves=8), TABLE2[:, 0])
    np.testing.assert_allclose(octave_wavelengths(lower_cutoff=0.0625, n_waves=8),
                               TABLE2[:, 0])
    # M from the cut-offs: the shortest octave not below the lower cut-off
    np.testing.assert_allclose(octave_wavelengths(0.15, 8.0), [0.25, 0.5, 1, 2, 4, 8])
    with pytest.raises(InputError, match="lower_cutoff"):
        octave_wavelengths(10.0, 8.0)
    with pytest.raises(InputError, match="n_waves"):
        octave_wavelengths(upper_cutoff=8.0, n_waves=0)


def test_wellconditioned_recovers_table2(table2_scans):
    fit = fit_hdc_details(table2_scans, DX, TABLE2[:, 0])
    ratio = fit.series.amplitudes / TABLE2[:, 1]
    up_to_2mm = TABLE2[:, 0] <= 2.0
    # the requirement: every wave up to 2 mm within 10 % (we see < 2 %)
    np.testing.assert_allclose(ratio[up_to_2mm], 1.0, atol=0.10)
    # 4 and 8 mm: only 4 and 2 periods per scan; still within 10 % here (we see < 2.5 %)
    np.testing.assert_allclose(ratio[~up_to_2mm], 1.0, atol=0.10)
    hs, ls = fit.series.partition(1.0)
    np.testing.assert_allclose(hs.wavelengths, [0.0625])
    assert ls.size == 7
    # the model HDC is the exact HDC of the returned series and follows the data:
    np.testing.assert_allclose(fit.fitted, fit.series.hdc(fit.lags), rtol=1e-12)
    assert fit.log10_rms_error < 0.005  # measured 0.0006 (a 0.15 % typical misfit)


@pytest.mark.parametrize("seed", [1, 2])
def test_wellconditioned_recovery_other_phase_draws(seed):
    scans = synthetic_line_scans(asphalt_ac8(), seed=seed)
    series = fit_hdc(scans, DX, TABLE2[:, 0])
    keep = TABLE2[:, 0] <= 2.0
    np.testing.assert_allclose(series.amplitudes[keep] / TABLE2[keep, 1], 1.0, atol=0.10)


def test_paper_method_follows_hdc_and_minimises_eqs_29_30(table2_scans):
    fit = fit_hdc_details(table2_scans, DX, TABLE2[:, 0], method="paper")
    # fitted (clipped eq. 15) HDC follows the measured one: we measure 0.021 (≈5 %)
    assert fit.log10_rms_error < 0.05
    np.testing.assert_allclose(fit.series.partition()[0].wavelengths, [0.0625])

    def objective(amplitudes):  # eqs. 29–30 as a sum of squares of log10 misfits
        g = wave_hdc(fit.lags, TABLE2[:, 0], clipped=True) @ amplitudes**2
        return np.sum((np.log10(g) - np.log10(fit.measured)) ** 2)

    # it is a minimum of the paper's objective: not worse than the true amplitudes …
    assert objective(fit.series.amplitudes) <= objective(TABLE2[:, 1])
    # … which is exactly why it is ill-conditioned: the minimum is far from the truth
    # (the clipped curve is not the HDC of the series); documented in fit.py.
    ratio = fit.series.amplitudes / TABLE2[:, 1]
    assert np.max(np.abs(ratio - 1)) > 0.3


def test_exact_curve_is_recovered_exactly():
    s = asphalt_ac8()
    lags = log_lags(DX, 4.0)
    fit = fit_hdc_curve(lags, s.hdc(lags), s.wavelengths)
    np.testing.assert_allclose(fit.series.amplitudes, s.amplitudes, rtol=1e-6)
    assert fit.log10_rms_error < 1e-8


def test_single_wave_fit_from_a_profile():
    s = SineSeries([0.5], [0.1], [0.3])
    x = np.arange(4000) * 0.002
    series = fit_hdc(s.heights(x), 0.002, [0.5])
    assert series.amplitudes[0] == pytest.approx(0.1, rel=0.01)


def test_warns_when_sampling_cannot_resolve_a_wavelength():
    # the paper's own 0.05 mm scans alias its 0.0625 mm wave (1.25 points per wavelength)
    scans = synthetic_line_scans(asphalt_ac8(), n_scans=4, dx=0.05, seed=0)
    with pytest.warns(RoughnessWarning, match=r"0\.0625 mm \(1\.2 points\)"):
        fit_hdc(scans, 0.05, TABLE2[:, 0])
    fine = synthetic_line_scans(asphalt_ac8(), n_scans=2, seed=0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RoughnessWarning)
        fit_hdc(fine, DX, TABLE2[:, 0])


def test_table_rows_and_dict(table2_scans):
    fit = fit_hdc_details(table2_scans, DX, TABLE2[:, 0])
    rows = fit.table(m2_threshold=1.0)
    assert [r["high_slope"] for r in rows] == [True] + [False] * 7
    d = fit.as_dict()
    assert d["method"] == "wellconditioned" and len(d["waves"]) == 8
    assert d["log10_rms_error"] == pytest.approx(fit.log10_rms_error)


def test_default_wavelengths_and_lags(table2_scans):
    # ladder: 8 mm (half the scan) down to the last octave >= 4·dx = 0.02 mm
    fit = fit_hdc_details(table2_scans, DX)
    np.testing.assert_allclose(fit.series.wavelengths, np.r_[0.03125, TABLE2[:, 0]])
    # the surface has no 0.03125 mm wave: only the 0.5 µm white noise is put there
    assert fit.series.amplitudes[0] < 0.1 * TABLE2[0, 1]
    np.testing.assert_allclose(fit.series.amplitudes[1:] / TABLE2[:, 1], 1.0, atol=0.1)
    assert fit.lags.max() == pytest.approx(4.0)  # half the longest wavelength
    lags, r = hdc(table2_scans, DX, fit.lags)
    np.testing.assert_allclose(fit.measured, r)


def test_bad_fit_inputs():
    z = np.sin(np.arange(200) * 0.1)
    with pytest.raises(InputError, match="method"):
        fit_hdc(z, 0.01, [0.5], method="magic")
    with pytest.raises(InputError, match="max_lag"), pytest.warns(RoughnessWarning):
        fit_hdc(z, 0.01, [8.0])  # needs lags up to 4 mm from a 2 mm scan
    with pytest.raises(InputError, match="wavelengths"):
        fit_hdc_curve([0.1, 0.2], [1.0, 2.0], [-1.0])
    with pytest.raises(InputError, match="lags and measured"):
        fit_hdc_curve([0.1, 0.2], [1.0], [1.0])
    with pytest.raises(InputError, match="dx"):
        fit_hdc(z, -0.01, [0.5])
