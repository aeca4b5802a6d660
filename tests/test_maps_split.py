"""The paper's scale split on maps: octave bands, z = z_ls + z_hs, the high-slope cell."""

import numpy as np
import pytest

from rubbercontact.errors import InputError
from rubbercontact.roughness import SineSeries
from rubbercontact.roughness import mapstats as ms
from rubbercontact.roughness.maps import HeightMap
from rubbercontact.roughness.mapsplit import octave_bands, split_map
from rubbercontact.roughness.mapsynth import self_affine_map


def extruded(series: SineSeries, nx: int = 256, ny: int = 16) -> HeightMap:
    """The profile ``series`` (period Lx) extruded along y, square pixels."""
    lx = series.period
    return HeightMap(np.tile(series.heights(np.arange(nx) * lx / nx), (ny, 1)),
                     (lx * ny / nx, lx), periodic=True)


LADDER = SineSeries.ladder(1.0, [0.05, 0.05, 0.06], [0.3, 1.0, 2.0])   # m2 0.22, 0.44, 1.07


def test_bands_of_an_extruded_ladder_are_its_waves():
    bands = octave_bands(extruded(LADDER))
    # a wave of wavelength Lx/2^k is alone in band k: its rms slope along x is its m2
    np.testing.assert_allclose(bands["rms_slope_x"].values[:3], LADDER.rms_slopes()[::-1],
                               rtol=1e-12)
    assert np.all(bands["rms_slope_y"].values < 1e-12)
    assert bands["high_slope"].values.tolist()[:3] == [0, 0, 1]
    assert bands["variance"].sum() == pytest.approx(LADDER.rms_height**2, rel=1e-12)


def test_split_is_exact_and_matches_the_1d_partition():
    hm = extruded(LADDER)
    sp = split_map(hm, 1.0)
    np.testing.assert_allclose(sp.low.heights + sp.high.heights, hm.heights, rtol=0,
                               atol=1e-15)
    hs, ls = LADDER.partition(1.0)
    x = hm.x
    np.testing.assert_allclose(sp.high.heights, np.broadcast_to(hs.heights(x), hm.shape),
                               atol=1e-15)
    np.testing.assert_allclose(sp.low.heights, np.broadcast_to(ls.heights(x), hm.shape),
                               atol=1e-15)
    # the cell is one period of the high-slope wave, uniform in y: the 1D cell
    assert sp.cell_period == pytest.approx(hs.period)
    assert ms.rms_slope_x(sp.cell) == pytest.approx(hs.rms_slope, rel=1e-12)
    assert ms.rms_height(sp.cell) == pytest.approx(hs.rms_height, rel=1e-12)
    assert sp.cell.profile() is not None
    assert sp.cell_modes.sizes["mode"] == 1


def test_split_of_a_random_map_and_its_cell():
    hm = self_affine_map((128, 128), 2.0, 0.8, rms_gradient=1.0, seed=3)
    sp = split_map(hm, 0.3)
    high = np.flatnonzero(sp.bands["high_slope"].values)
    assert high.size >= 1
    np.testing.assert_allclose(sp.low.heights + sp.high.heights, hm.heights, atol=1e-15)
    # z_hs carries exactly the high-slope bands' variance and slope along x
    assert ms.rms_height(sp.high) ** 2 == pytest.approx(
        float(sp.bands["variance"][high].sum()), rel=1e-10)
    assert ms.rms_slope_x(sp.high) ** 2 == pytest.approx(
        float((sp.bands["rms_slope_x"][high] ** 2).sum()), rel=1e-10)
    # the cell keeps the band's variance exactly; its slope up to the lattice shift: each
    # map mode moves by at most half a cell-lattice step to the nearest cell mode, and the
    # shifts of a band's many modes cancel to first order (5 %; 1 % measured here)
    assert ms.rms_height(sp.cell) == pytest.approx(ms.rms_height(sp.high), rel=1e-10)
    assert ms.rms_slope_x(sp.cell) == pytest.approx(ms.rms_slope_x(sp.high), rel=0.05)
    assert sp.cell_period == pytest.approx(float(sp.bands["wavelength"][high.min()]))


def test_no_high_slope_band_and_bad_input():
    sp = split_map(extruded(LADDER), 5.0)
    assert sp.cell is None and sp.cell_period == 0.0
    assert np.abs(sp.high.heights).max() == 0.0
    with pytest.raises(InputError, match="periodic"):
        split_map(HeightMap(extruded(LADDER).heights, (1 / 16, 1.0)))
    with pytest.raises(InputError, match="cell_points"):
        split_map(extruded(LADDER), 1.0, cell_points=7)


def test_a_high_slope_part_periodic_on_the_cell_is_the_cell():
    # an egg crate of the 0.125 mm band plus a longer wave: the map's z_hs repeats on the
    # cell, which then keeps the map's own amplitudes and phases (no random phases)
    n, lx = 128, 1.0
    x = np.arange(n) * lx / n
    # m2 along x: 1.42 (band of 0.125 mm) and 1.07 (the diagonal, next band): both high
    crate = (0.04 * (np.sin(16 * np.pi * x[None, :] + 0.4) + np.sin(16 * np.pi * x[:, None] + 1.1))
             + 0.03 * np.sin(16 * np.pi * (x[None, :] + x[:, None]) + 0.2))
    hm = HeightMap(crate + 0.01 * np.sin(2 * np.pi * x[None, :]), (lx, lx), periodic=True)
    for periods in (1, 2):
        sp = split_map(hm, 1.0, cell_points=16 * periods, cell_periods=periods)
        assert sp.cell_period == pytest.approx(0.125)
        assert sp.cell_side == pytest.approx(0.125 * periods)
        assert sp.cell.source["phases"] == "the map's"
        np.testing.assert_allclose(sp.cell.heights, sp.high.heights[:16 * periods, :16 * periods],
                                   atol=1e-15)
    with pytest.raises(InputError, match="power of 2"):
        split_map(hm, 1.0, cell_periods=3)
