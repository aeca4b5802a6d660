"""SineSeries: exact geometry of the paper's sine-wave roughness."""

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.errors import InputError


def test_slopes_are_derivative_of_heights():
    s = rc.roughness.section3(phases=[0.3, 1.1, 4.0])
    x = np.linspace(0, s.period, 1001)
    h = 1e-6
    # central difference error ~ h^2 z''' / 6 ~ 1e-12 * q^3 Delta ~ 1e-6 relative; tolerance 1e-5.
    fd = (s.heights(x + h) - s.heights(x - h)) / (2 * h)
    np.testing.assert_allclose(s.slopes(x), fd, rtol=0, atol=1e-5 * np.abs(s.slopes(x)).max())


def test_rms_height_and_slope_match_sampled_values():
    s = rc.roughness.asphalt_ac8().realizations(1, seed=3)[0]
    x, z = s.grid(2**14)
    # Over one full period the discrete mean of sin^2 is exactly 1/2 for every resolved wave.
    assert np.sqrt(np.mean(z**2)) == pytest.approx(s.rms_height, rel=1e-12)
    assert np.sqrt(np.mean(s.slopes(x) ** 2)) == pytest.approx(s.rms_slope, rel=1e-12)


def test_partition_paper_table2():
    hs, ls = rc.roughness.asphalt_ac8().partition(1.0)
    np.testing.assert_array_equal(hs.wavelengths, [0.0625])
    assert ls.size == 7 and np.all(ls.rms_slopes() < 1)
    # Partition keeps phases with their waves.
    s = rc.roughness.section3(phases=[0.1, 0.2, 0.3])
    hs, ls = s.partition()
    np.testing.assert_allclose(hs.phases, [0.1])
    np.testing.assert_allclose(ls.phases, [0.2, 0.3])
    assert (hs + ls) == s


def test_ladder_and_realizations():
    s = rc.roughness.SineSeries.ladder(8.0, [1.0, 0.5, 0.25])
    np.testing.assert_allclose(s.wavelengths, [2.0, 4.0, 8.0])
    np.testing.assert_allclose(s.amplitudes, [0.25, 0.5, 1.0])
    r1 = s.realizations(5, seed=42)
    r2 = s.realizations(5, seed=42)
    assert r1 == r2
    ph = np.array([r.phases for r in s.realizations(2000, seed=1)])
    assert ph.min() >= 0 and ph.max() < 2 * np.pi
    # Uniform phases: mean pi within 4 standard errors (sd of U(0,2pi) = 2pi/sqrt(12)).
    assert abs(ph.mean() - np.pi) < 4 * (2 * np.pi / np.sqrt(12)) / np.sqrt(ph.size)


def test_exact_hdc_of_sampled_series():
    s = rc.roughness.section3(phases=[0.5, 2.0, 3.0])
    n = 4096
    x, z = s.grid(n)
    for k in (1, 17, 300, 1024):
        lag = k * s.period / n
        measured = np.mean((np.roll(z, -k) - z) ** 2)
        assert measured == pytest.approx(s.hdc(lag), rel=1e-10)


@pytest.mark.parametrize("args, field", [
    (([0.1, 0.2], [0.01]), "lengths differ"),
    (([0.1, -0.2], [0.01, 0.01]), r"wavelengths\[1\]"),
    (([0.1, 0.2], [0.01, -0.01]), r"amplitudes\[1\]"),
    (([0.1, np.nan], [0.01, 0.01]), "wavelengths"),
    (([0.1, 0.25], [0.01, 0.01]), "integer"),
    (([0.1, 0.1], [0.01, 0.01]), "duplicate"),
])
def test_bad_sine_series(args, field):
    with pytest.raises(InputError, match=field):
        rc.roughness.SineSeries(*args)


def test_sampled_grid_is_the_series_on_uniform_points_and_kept():
    s = rc.roughness.SineSeries([0.25, 1.0], [0.01, 0.03], [0.3, 1.1])
    z, dz = s.sampled(1.0, 64)
    x = np.arange(64) / 64
    np.testing.assert_array_equal(z, s.heights(x))
    np.testing.assert_array_equal(dz, s.slopes(x))
    assert not z.flags.writeable and s.sampled(1.0, 64)[0] is z
    assert s.sampled(1.0, 128)[0].size == 128
