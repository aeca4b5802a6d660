"""Models on maps: the VHS, the mean-field and the hybrid with the linear law.

Against closed forms (an oblique sine in full contact) and against the 1D models: a map
uniform in y is a profile extruded along y, and every model must give the profile's answer
per unit width (the 2D kernel on q_y = 0 is the 1D one; the solvers run to tol 1e-8).
"""

from dataclasses import replace

import numpy as np
import pytest

from rubbercontact import meanfield
from rubbercontact.errors import InputError
from rubbercontact.halfspace import LennardJonesRepulsion, solve_sliding
from rubbercontact.hybrid.linearlaw import linear_law
from rubbercontact.hybrid.maps import (
    MapHybridOptions,
    lateral_friction,
    linear_law_map,
    solve_map,
    solve_map_hybrid,
)
from rubbercontact.hybrid.tasks import halfspace_task
from rubbercontact.hybrid.windowing import window_average
from rubbercontact.hybrid.windowing2d import window_average_2d
from rubbercontact.materials import GeneralizedMaxwell, sbr
from rubbercontact.meanfield import PSD
from rubbercontact.roughness import SineSeries
from rubbercontact.roughness.maps import HeightMap
from rubbercontact.roughness.mapsplit import split_map
from rubbercontact.roughness.mapstats import map_psd

MAT = sbr()
V = 10.0
#: two waves: 0.125 mm high-slope (m2 1.07), 1 mm low-slope (m2 0.22)
SURF = SineSeries([1.0, 0.125], [0.05, 0.03], [0.3, 1.0])
#: relative agreement of a 2D solve with its 1D twin: solver tolerance 1e-8 on the
#: residual, amplified by the conditioning of the contact problem (measured 1e-10)
RTOL_1D = 1e-6


def extruded(series: SineSeries, nx: int, ny: int = 8) -> HeightMap:
    lx = series.period
    return HeightMap(np.tile(series.heights(np.arange(nx) * lx / nx), (ny, 1)),
                     (lx * ny / nx, lx), periodic=True)


def oblique(m=2, n=1, nx=32, amp=0.002):
    lx = 1.0
    x = np.arange(nx) * lx / nx
    qx, qy = 2 * np.pi * m / lx, 2 * np.pi * n / lx
    z = amp * np.sin(qx * x[None, :] + qy * x[:, None])
    return HeightMap(z, (lx, lx), periodic=True), qx, qy


@pytest.mark.parametrize("law", [None, LennardJonesRepulsion()])
def test_vhs_on_a_map_uniform_in_y_is_the_1d_vhs(law):
    res2 = solve_map(extruded(SURF, 256), MAT, V, 0.2, law=law)
    res1 = solve_sliding(SURF, 1.0, MAT, V, 0.2, law=law, n=256)
    for k in ("friction", "contact_fraction", "mean_separation"):
        assert getattr(res2, k) == pytest.approx(getattr(res1, k), rel=RTOL_1D), k


def test_oblique_sine_in_full_contact_is_the_closed_form():
    # full contact: σ = σ0 + Re[Δ|q|E_r/2 ...]: μ = |q| q_x Δ² Im E_r(q_x v)/(4σ0), and the
    # force on the rigid surface points along q: μ_y = |q| q_y Δ² Im E_r/(4σ0)
    hm, qx, qy = oblique()
    q = np.hypot(qx, qy)
    er = complex(MAT.reduced_modulus(qx * V, 0.5))
    sigma0 = 2.0 * 0.002 * q * abs(er) / 2       # twice the pressure amplitude
    res = solve_map(hm, MAT, V, sigma0)
    assert res.contact_fraction == 1.0
    # spectral slopes and one mode: exact up to the solver tolerance
    assert res.friction == pytest.approx(q * qx * 0.002**2 * er.imag / (4 * sigma0), rel=1e-8)
    assert lateral_friction(res) == pytest.approx(q * qy * 0.002**2 * er.imag / (4 * sigma0),
                                                  rel=1e-8)


def test_elastic_map_has_no_friction():
    hm, _, _ = oblique()
    for mat, v in ((GeneralizedMaxwell.elastic(5.0), V), (MAT, 0.0)):
        res = solve_map(hm, mat, v, 0.05)
        assert abs(res.friction) < 1e-12 and abs(lateral_friction(res)) < 1e-12


def test_meanfield_on_a_map_uniform_in_y_is_the_1d_meanfield():
    psd_map = map_psd(extruded(SURF, 256), nodes_per_decade=None)
    psd_1d = PSD(SURF.wavenumbers[::-1], SURF.amplitudes[::-1] ** 2 / 2, 1)   # closed form
    opts = meanfield.MeanFieldOptions()
    a = meanfield.solve(psd_map, MAT, V, 0.2, options=opts)
    b = meanfield.solve(psd_1d, MAT, V, 0.2, options=opts)
    # the periodogram's nodes equal the waves' to round-off (1e-12)
    assert a.friction == pytest.approx(b.friction, rel=1e-9)
    assert a.contact_fraction == pytest.approx(b.contact_fraction, rel=1e-9)


@pytest.fixture(scope="module")
def laws():
    hs, _ = SURF.partition(1.0)
    n = 64
    cell = HeightMap(np.tile(hs.heights(np.arange(n) * hs.period / n), (8, 1)),
                     (hs.period * 8 / n, hs.period), periodic=True)
    return linear_law_map(cell, MAT, V, points=30), linear_law(hs, MAT, V, n=n, points=30)


def test_linear_law_of_a_cell_uniform_in_y_is_the_1d_linear_law(laws):
    law2, law1 = laws
    assert law2["dimension"] == 2 and len(law2["pressure"]) == len(law1["pressure"])
    for k in ("separation", "contact_fraction", "shear_stress"):
        np.testing.assert_allclose(law2[k], law1[k], rtol=RTOL_1D, atol=1e-14, err_msg=k)
    np.testing.assert_allclose(law2["shear_stress_y"], 0.0, atol=1e-14)   # no lateral force


def test_law_of_a_cell_of_two_periods_is_the_law_of_one():
    # a periodic surface's law is a mean over its period: two copies give the same table
    split1 = split_map(extruded(SURF, 256), 1.0, cell_points=32)
    split2 = split_map(extruded(SURF, 256), 1.0, cell_points=64, cell_periods=2)
    law1 = linear_law_map(split1.cell, MAT, V, points=12)
    law2 = linear_law_map(split2.cell, MAT, V, points=12)
    for k in ("separation", "contact_fraction", "shear_stress"):
        np.testing.assert_allclose(law2[k], law1[k], rtol=RTOL_1D, atol=1e-14, err_msg=k)


@pytest.mark.parametrize("window", [True, False])
def test_hybrid_on_a_map_uniform_in_y_is_the_1d_hybrid(laws, window):
    law2, law1 = laws
    hs, ls = SURF.partition(1.0)
    split = split_map(extruded(SURF, 256), 1.0)
    res2 = solve_map_hybrid(split, law2, MAT, V, 0.2, MapHybridOptions(window=window))
    res1 = halfspace_task(ls.as_dict(), 1.0, MAT.as_dict(), V, 0.2, n=256, law="hard-wall",
                          interface_law=law1, hs_window=hs.period if window else None)
    assert res2.friction == pytest.approx(float(res1.friction), rel=RTOL_1D)
    assert res2.friction_ls == pytest.approx(float(res1.friction_ls), rel=RTOL_1D)
    assert res2.contact_fraction == pytest.approx(float(res1.contact_fraction), rel=RTOL_1D)
    assert abs(res2.friction_y) < 1e-12
    assert res2.window == (hs.period if window else 0.0)


def test_plane_strain_law_on_a_map_is_refused(laws):
    split = split_map(extruded(SURF, 128), 1.0)
    with pytest.raises(InputError, match="plane-strain") as exc:
        solve_map_hybrid(split, laws[1], MAT, V, 0.2)
    assert "\n" not in str(exc.value)


def test_hybrid_without_a_high_slope_band_is_refused(laws):
    split = split_map(extruded(SURF, 128), 5.0)      # no band reaches m2 = 5
    with pytest.raises(InputError, match="no high-slope band"):
        solve_map_hybrid(split, laws[0], MAT, V, 0.2)


def test_map_solve_needs_a_periodic_map():
    with pytest.raises(InputError, match="periodized"):
        solve_map(HeightMap(extruded(SURF, 64).heights, (1 / 8, 1.0)), MAT, V, 0.2)


def test_box_average_of_a_field_uniform_in_y_is_the_1d_window():
    rng = np.random.default_rng(2)
    row = rng.random(128)
    box = window_average_2d(np.tile(row, (16, 1)), (0.5, 4.0), 0.3)
    np.testing.assert_allclose(box, np.tile(window_average(row, 4.0, 0.3), (16, 1)),
                               rtol=1e-13)
    # a box of a whole period (or more) is the mean
    field = rng.random((16, 32))
    np.testing.assert_allclose(window_average_2d(field, (1.0, 1.0), 1.5), field.mean(),
                               rtol=1e-13)


@pytest.mark.parametrize("window", [True, False])
def test_the_lateral_force_of_waves_in_one_direction_points_along_them(window):
    """Two waves along one direction q ∝ (2, 1), 1 mm and 1/8 mm apart along x (low and
    high slope): the map is a function of 2x + y, the problem is one-dimensional along q, so
    every force points along q — each row of the cell's law has Δτ_y = Δτ/2, the low-slope
    pressure gives <σ ∂z/∂y> = <σ ∂z/∂x>/2 exactly (one mode each), and the hybrid's
    lateral ratio is μ/2, pointwise or windowed, to the solves' tolerance."""
    n, lx = 128, 1.0
    x = np.arange(n) * lx / n
    phase = 2 * np.pi * (2 * x[None, :] + x[:, None])             # (q_x, q_y) ∝ (2, 1)
    hm = HeightMap(0.01 * np.sin(phase) + 0.003 * np.sin(8 * phase), (lx, lx), periodic=True)
    split = split_map(hm, 0.15, cell_points=32, cell_periods=2)  # slopes x 0.089 and 0.21
    law = linear_law_map(split.cell, MAT, V, points=12)
    tau = np.asarray(law["shear_stress"])
    assert np.all(tau[:-1] > 0)
    np.testing.assert_allclose(law["shear_stress_y"], tau / 2, rtol=1e-6, atol=1e-14)
    res = solve_map_hybrid(split, law, MAT, V, 0.2, MapHybridOptions(window=window))
    assert res.friction_hs > 0.1 * res.friction
    assert res.friction_y == pytest.approx(res.friction / 2, rel=1e-6)
    # the high-slope wave alone: a flat low-slope map, the law at uniform pressure
    flat = replace(split, low=split.low.replace(np.zeros((n, n)), {}))
    res = solve_map_hybrid(flat, law, MAT, V, 0.2, MapHybridOptions(window=window))
    assert res.low is None and res.friction_hs == res.friction > 0
    assert res.friction_y == pytest.approx(res.friction / 2, rel=1e-6)
