"""The steady FEM on the steepest CAPTIF cell with its crests rounded to the profiles'
sampling (docs/validation/steep_cells.md, parts 'rounded', 'qs'): the station 1 band
(0.25 / 0.5 / 1 mm, m2 up to 2.8), whose sharp crests (9-14 µm) stopped the steady solve at
most law points, converges on the automatic mesh, unimpaled, and its quasi-static friction
vanishes there."""

import pytest

import rubbercontact as rc

#: The high-slope part of examples/captif_road.toml fitted to station 1 alone, translated
#: to zero phase (studies/steep_cells.py, cells()).
STATION_1 = rc.roughness.SineSeries([0.25, 0.5, 1.0],
                                    [0.15847269, 0.15212879, 0.23474476])
#: The CAPTIF profiles' sampling interval [mm] (data/real_surfaces/README.md).
SAMPLING = 0.0375


def _rounded(p: float, v: float) -> rc.fem.SlidingTestResult:
    return rc.fem.steady_sliding(STATION_1, rc.materials.sbr(), p, v, mesh="auto",
                                 crest_radius=SAMPLING, fallback=False)


def _sound(out, penetration: float = 1e-3 * STATION_1.period) -> None:
    assert out.stats.solver == "steady" and not out.stats.impaled
    # nothing of the face below the surface beyond a hair of the load's penetration
    assert out.stats.max_penetration < penetration
    assert 0.0 < out.contact_fraction < 1.0


def test_the_rounded_station_1_cell_converges_steady_at_a_law_point():
    out = _rounded(0.3, 10.0)
    _sound(out)
    assert out.friction > 0.0


@pytest.mark.slow
@pytest.mark.parametrize("p, v", [(1.0, 1.0), (3.0, 10.0)])
def test_the_rounded_station_1_cell_converges_at_the_hard_points(p, v):
    # as fitted, 1 MPa / 1 mm/s stopped after 816 s of penalty and barrier attempts
    _sound(_rounded(p, v))


@pytest.mark.slow
def test_the_quasi_static_friction_vanishes_on_the_rounded_cells_mesh():
    # at 1e-3 mm/s the SBR's loss tangent on these waves is about 1e-4: the friction must
    # vanish; a lattice force of an under-resolved mesh would not (tolerance 0.005, the
    # mesh study's, docs/validation/mesh_resolution.md)
    out = _rounded(0.3, 1e-3)
    _sound(out)
    assert abs(out.friction) <= 0.005


@pytest.mark.slow
def test_the_station_1_law_grid_converges_or_is_refused_with_its_reason():
    # Issue 41: the law grid {0.1, 0.3, 1, 3, 10} MPa x {1, 3, 10, 30, 100} mm/s, one speed
    # path per pressure as a run's law computes it (benchmarks/bench_steep_grid.py times
    # it). Each point converges steady and unimpaled on the automatic mesh, or -- only
    # above the relaxed modulus E∞ (fem/loadrange.py) -- is refused before any work with
    # the reason; never an impaled or a silently failed point.
    import numpy as np

    from rubbercontact.errors import InputError, RubberContactError
    from rubbercontact.fem import make_options
    from rubbercontact.fem.sweep import sweep_points

    mat = rc.materials.sbr()
    opts = make_options(mesh="auto", crest_radius=SAMPLING, fallback=False)
    speeds = np.array([1.0, 3.0, 10.0, 30.0, 100.0])
    for p in (0.1, 0.3, 1.0, 3.0, 10.0):
        points = list(sweep_points(STATION_1, mat, np.full(speeds.size, p), speeds, opts,
                                   errors=(RubberContactError,)))
        assert len(points) == speeds.size
        for pt in points:
            if p > mat.equilibrium_modulus:
                assert isinstance(pt.error, InputError), (p, speeds[pt.index])
                assert "outside the cell's range" in str(pt.error)
                continue
            assert pt.error is None, (p, speeds[pt.index], pt.error)
            # the penalty's penetration grows with the local pressure (1.02 µm at 3 MPa /
            # 1 mm/s): below 1 % of the smallest wave's amplitude it moves the contact by
            # less than 1 % of that wave
            _sound(pt.result, penetration=0.01 * STATION_1.amplitudes.min())
            assert pt.result.friction > 0.0
