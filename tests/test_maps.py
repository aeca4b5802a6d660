"""Height maps: the object, dropouts, periodization, statistics, synthesis (closed forms)."""

import warnings

import numpy as np
import pytest
from scipy.special import gamma

from rubbercontact.errors import InputError
from rubbercontact.meanfield import PSD
from rubbercontact.roughness import SineSeries
from rubbercontact.roughness import mapstats as ms
from rubbercontact.roughness.fit import RoughnessWarning
from rubbercontact.roughness.maps import HeightMap, harmonic_fill
from rubbercontact.roughness.mapsynth import (
    isotropic_from_line_psd,
    self_affine_map,
    synthetic_map,
)


def oblique(nx=64, ny=32, lx=2.0, m=3, n=2, amp=0.01):
    """``Δ sin(q·x)`` with ``q = 2π(m/Lx, n/Ly)`` on the lattice (square pixels)."""
    ly = lx * ny / nx
    x, y = np.arange(nx) * lx / nx, np.arange(ny) * ly / ny
    qx, qy = 2 * np.pi * m / lx, 2 * np.pi * n / ly
    z = amp * np.sin(qx * x[None, :] + qy * y[:, None])
    return HeightMap(z, (ly, lx), periodic=True), qx, qy


def test_map_geometry_and_dataset():
    hm, _, _ = oblique()
    assert hm.shape == (32, 64) and hm.dx == pytest.approx(2.0 / 64)
    ds = hm.to_dataset()
    assert ds["heights"].dims == ("y", "x") and ds["heights"].attrs["units"] == "mm"
    assert ds["x"].size == 64 and ds.attrs["periodic"] == 1


def test_bad_input_is_one_clear_error():
    with pytest.raises(InputError, match="NaN"):
        HeightMap.from_array(np.full((8, 8), np.nan), 0.1, nan="error")
    with pytest.raises(InputError, match="2D map"):
        HeightMap.from_array(np.zeros(8), 0.1)
    with pytest.raises(InputError, match="dx"):
        HeightMap.from_array(np.zeros((8, 8)), -1.0)
    with pytest.raises(InputError, match="at least"):
        HeightMap(np.zeros((2, 8)), (1.0, 1.0))


def test_slope_statistics_of_an_oblique_sine_are_exact():
    # one mode: <z_x²> = qx²Δ²/2, <|∇z|²> = |q|²Δ²/2, slope tensor rank 1 (anisotropy inf)
    hm, qx, qy = oblique(amp=0.02)
    assert ms.rms_slope_x(hm) == pytest.approx(qx * 0.02 / np.sqrt(2), rel=1e-12)
    assert ms.rms_gradient(hm) == pytest.approx(np.hypot(qx, qy) * 0.02 / np.sqrt(2), rel=1e-12)
    ratio, angle = ms.anisotropy(hm)
    assert ratio == np.inf and np.tan(angle) == pytest.approx(qy / qx, rel=1e-9)
    spec = ms.spectrum_2d(hm)
    assert float(spec["power"].sum()) == pytest.approx(0.02**2 / 2, rel=1e-12)  # Parseval


def test_nonperiodic_slopes_are_first_differences_over_measured_points():
    # a plane of tilt a along x: every difference is exact; filled points are excluded
    z = 0.3 * np.arange(16)[None, :] * 0.1 * np.ones((12, 1))
    z[5, 5] = np.nan
    hm = HeightMap.from_array(z, 0.1, nan="fill")
    assert hm.filled.sum() == 1 and hm.source["nan"]["points"] == 1
    assert ms.rms_slope_x(hm) == pytest.approx(0.3, rel=1e-12)


def test_harmonic_fill_is_exact_on_harmonic_functions():
    # a plane solves the 5-point Laplace equation: an inner gap is filled by the plane
    y, x = np.mgrid[0:20, 0:30]
    plane = 0.2 * x - 0.1 * y + 1.0
    z = plane.astype(float)
    z[4:9, 10:17] = np.nan
    np.testing.assert_allclose(harmonic_fill(z), plane, atol=1e-10)
    # on the free edge a plane is harmonic only with no slope across that edge
    ramp = (0.1 * y).astype(float)
    z = ramp.copy()
    z[12:15, 0:3] = np.nan
    np.testing.assert_allclose(harmonic_fill(z), ramp, atol=1e-10)


def test_mirror_periodization_invents_no_slope():
    rng = np.random.default_rng(1)
    z = np.cumsum(rng.standard_normal((10, 14)), axis=1) * 1e-3
    hm = HeightMap.from_array(z, 0.05).detrended("plane")
    per = hm.periodized("mirror")
    assert per.periodic and per.shape == (18, 26)
    assert per.lengths == pytest.approx((18 * 0.05, 26 * 0.05))
    zp = per.heights
    # every x-difference of the periodic map (seams included) is ± an original one
    dp = np.abs(np.diff(np.concatenate([zp, zp[:, :1]], axis=1), axis=1))
    d0 = np.abs(np.diff(hm.heights, axis=1))
    assert np.all(np.isin(np.round(dp, 15), np.round(d0, 15)))
    assert np.array_equal(zp[:10, :14], hm.heights)


def test_detrend_plane_removes_a_tilt():
    y, x = np.mgrid[0:16, 0:16] * 0.1
    hm = HeightMap.from_array(0.5 * x + 0.2 * y + 3.0, 0.1)
    flat = hm.detrended("plane")
    assert np.abs(flat.heights).max() < 1e-12
    assert flat.source["tilt_x"] == pytest.approx(0.5)
    with pytest.raises(InputError, match="periodic"):
        oblique()[0].detrended("plane")


def test_self_affine_map_is_isotropic_with_the_exact_gradient():
    hm = self_affine_map((64, 64), 2.0, 0.8, rms_gradient=0.5, seed=3)
    assert ms.rms_gradient(hm) == pytest.approx(0.5, rel=1e-12)
    # square lattice, power depending on |q| only: the slope tensor is isotropic
    assert ms.anisotropy(hm)[0] == pytest.approx(1.0, abs=1e-9)
    assert ms.rms_slope_x(hm) == pytest.approx(0.5 / np.sqrt(2), rel=1e-9)


def test_isotropic_spectrum_of_a_power_law_line_scan_is_the_closed_form():
    # C1 ∝ q^-(1+2H) (one-sided line scan) ↔ C ∝ q^-2(1+H) with
    # C1(q) = 2 q C(q) √π Γ(H+½)/Γ(H+1); 32 nodes per decade: 0.5 % in the interior
    # (the cells' discretization), away from the lowest and highest decade (cut-offs)
    h = 0.8
    p1 = PSD.self_affine(hurst=h, q0=1.0, q1=1e4, rms_height=1.0, dimension=1)
    p2 = isotropic_from_line_psd(p1)
    q = p1.wavenumbers
    with np.errstate(divide="ignore"):          # the lowest ring may be 0 (cut-off)
        ratio = p1.density / (2 * q * p2.density * np.sqrt(np.pi) * gamma(h + 0.5) / gamma(h + 1))
        inner = (q > 10) & (q < 1e3)
    np.testing.assert_allclose(ratio[inner], 1.0, atol=5e-3)


def test_synthetic_map_from_a_spectrum_keeps_the_variance_on_the_lattice():
    p2 = PSD.self_affine(hurst=0.7, q0=4.0, q1=120.0, rms_height=0.01, dimension=2)
    hm = synthetic_map(p2, (128, 128), 2 * np.pi / 2.0, seed=0)   # fundamental 2 rad/mm
    # every node lies within the lattice's wavenumbers (2 … 181 rad/mm): variance exact
    assert hm.source["variance_on_lattice"] == pytest.approx(1.0)
    assert ms.rms_height(hm) == pytest.approx(0.01, rel=1e-9)
    # a line-scan spectrum goes through the isotropy assumption, stated in the source
    p1 = PSD.self_affine(hurst=0.7, q0=4.0, q1=200.0, rms_height=0.01, dimension=1)
    assert "isotropy" in synthetic_map(p1, (64, 64), 3.0).source


def test_map_psd_uniform_in_y_is_the_profile_spectrum_and_anisotropy_warns():
    s = SineSeries.ladder(1.0, [0.02, 0.01], [0.1, 0.4])
    x = np.arange(128) / 128
    hm = HeightMap(np.tile(s.heights(x), (16, 1)), (0.125, 1.0), periodic=True)
    psd = ms.map_psd(hm, nodes_per_decade=None)
    assert psd.dimension == 1
    np.testing.assert_allclose(psd.wavenumbers, s.wavenumbers[::-1], rtol=1e-12)
    np.testing.assert_allclose(psd.variances, s.amplitudes[::-1] ** 2 / 2, rtol=1e-10)
    ob, _, _ = oblique()
    with pytest.warns(RoughnessWarning, match="anisotropy"):
        assert ms.map_psd(ob).dimension == 2
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert ms.map_psd(self_affine_map((32, 32), 1.0, 0.8, rms_gradient=0.3)).dimension == 2


def test_resampling_a_periodic_map_is_exact_for_its_modes():
    hm, qx, qy = oblique(nx=32, ny=16, amp=0.02)
    fine = hm.resampled((48, 96))
    x, y = np.arange(96) * 2.0 / 96, np.arange(48) * 1.0 / 48
    np.testing.assert_allclose(fine.heights, 0.02 * np.sin(qx * x[None, :] + qy * y[:, None]),
                               atol=1e-15)
    with pytest.raises(InputError, match="periodic"):
        HeightMap(hm.heights, hm.lengths).resampled((8, 8))


def test_a_hann_window_stops_the_seam_leaking_into_the_short_waves():
    """A measured map holds 4.3 periods of a wave along x: taken as one period, the seam's
    jump is a step whose power falls only as q⁻² into the short waves; the Hann window takes
    the jump away (power ∝ q⁻⁶ beyond its main lobe) and keeps the variance up to the
    window's edge effect (within 5 %; 0.2 % here)."""
    n, lx = 128, 1.0
    x = np.arange(n) * lx / n
    z = 0.01 * np.sin(2 * np.pi * 4.3 * x)
    hm = HeightMap(np.tile(z, (32, 1)), (lx / 4, lx))
    plain, hann = ms.spectrum_2d(hm), ms.spectrum_2d(hm, window="hann")
    assert hann.attrs["window"] == "hann" and plain.attrs["window"] == "none"
    qx = plain["qx"].values
    short = np.abs(qx) > 2 * np.pi * 16                     # waves 4× shorter and more
    peak = float(plain["power"].max())
    assert float(plain["power"].sel(qy=0.0)[short].max()) > 1e-4 * peak     # 7e-4: leakage
    assert float(hann["power"].sel(qy=0.0)[short].max()) < 1e-7 * peak      # 5e-9
    var = np.var(z)
    assert float(plain["power"].sum()) == pytest.approx(var, rel=1e-12)     # Parseval
    assert float(hann["power"].sum()) == pytest.approx(var, rel=0.05)
    with pytest.raises(InputError, match="window"):
        ms.spectrum_2d(hm, window="bartlett")
