"""The hybrid's low-slope grid: the equal-points-per-wave rule and its accuracy."""

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.config import parse_config
from rubbercontact.errors import InputError
from rubbercontact.hybrid.grid import low_slope_points
from rubbercontact.pipeline.plan import model_tasks
from rubbercontact.pipeline.setup import resolve, task_material


def _waves(lams):
    lams = np.asarray(lams, float)
    return rc.roughness.SineSeries(lams, 0.01 * lams)


@pytest.mark.parametrize("n, full, low, expected", [
    (8192, [0.0625, 0.125, 8.0], [0.125, 8.0], 4096),     # asphalt: one octave removed
    (2048, [0.0625, 0.125, 0.25], [0.25], 512),           # two octaves
    (1000, [0.1, 0.25, 1.0], [0.25, 1.0], 500),           # ratio 2.5: 400 needed, 500 kept
    (4097, [0.1, 0.4], [0.4], 4097),                      # odd n is not halved
    (8192, [0.0625, 8.0], [8.0], 64),                     # floor n_min = 64
    (4096, [0.125, 0.25], [0.125, 0.25], 4096),           # same shortest wave
    (4096, [0.125, 0.25], [], 4096),                      # flat low-slope surface
])
def test_grid_rule_keeps_the_points_per_shortest_wave(n, full, low, expected):
    surf = _waves(full)
    ls = _waves(low) if low else rc.roughness.SineSeries([], [])
    m = low_slope_points(n, surf, ls)
    assert m == expected
    if low and m < n:
        # at least the VHS grid's points per wave, and half of it would have fewer (or
        # fall below the floor)
        assert m * ls.wavelengths[0] >= n * surf.wavelengths[0]
        assert (m // 2) * ls.wavelengths[0] < n * surf.wavelengths[0] or m // 2 < 64


def test_grid_rule_rejects_a_low_part_with_a_shorter_wave():
    with pytest.raises(InputError, match="shortest wave"):
        low_slope_points(1024, _waves([0.25, 0.5]), _waves([0.125]))


def _asphalt_run(**halfspace):
    return parse_config({"surface": {"preset": "asphalt_ac8"}, "velocities": [10.0],
                         "loads": {"pressures": [0.1]}, "realizations": 2,
                         "models": ["vhs", "hybrid", "hybrid-windowed"],
                         "halfspace": {"n": 8192, **halfspace}})


@pytest.mark.parametrize("halfspace, n_hybrid", [({}, 4096), ({"hybrid_n": 8192}, 8192),
                                                  ({"hybrid_n": 2048}, 2048)])
def test_the_pipeline_gives_the_hybrid_its_grid(halfspace, n_hybrid):
    # the rule by default, halfspace.hybrid_n when given; the VHS keeps halfspace.n
    setup = resolve(_asphalt_run(**halfspace))
    tables = {10.0: {"separation": [0.01, 0.02], "pressure": [1.0, 0.0],
                     "contact_fraction": [0.5, 0.0], "shear_stress": [0.3, 0.0]}}
    slots, tasks = model_tasks(setup, setup.material, np.array([0.1]), tables)
    for slot, task in zip(slots, tasks, strict=True):
        assert task.kwargs["n"] == (8192 if slot.model == "vhs" else n_hybrid)


def test_hybrid_on_its_grid_matches_finer_grids_on_the_asphalt():
    # Table 2 asphalt (one realization), the shortest wave alone high-slope, its linear law
    # (the VHS law of that wave: no FEM). The hybrid on the derived grid (4096 = 64 points
    # per 0.125 mm wave) against the VHS grid (8192) and a 4x finer peer (32768): measured
    # within 0.07 % in mu and 0.17 % in A at 10 and 1000 mm/s (0.7 % in mu at 0.01 mm/s,
    # where mu ~ 0.009); 1 % is the accuracy the rule claims at 64 points per wave.
    from rubbercontact.hybrid.law import linear_law
    from rubbercontact.hybrid.tasks import halfspace_loads_task

    mat = rc.materials.sbr()
    full = rc.roughness.asphalt_ac8(np.random.default_rng(5).uniform(0, 2 * np.pi, 8))
    high, low = full.partition(1.0)
    n_ls = low_slope_points(8192, full, low)
    assert n_ls == 4096
    for v in (10.0, 1000.0):
        table = linear_law(high, mat, v, points=30)

        def solve(n, v=v, table=table):
            ds = halfspace_loads_task(low.as_dict(), full.period, task_material(mat), v,
                                      [0.05, 0.4], n=n, interface_law=table)
            return ds["friction"].values, ds["contact_fraction"].values

        mu, area = solve(n_ls)
        for n in (8192, 32768):
            mu_n, area_n = solve(n)
            np.testing.assert_allclose(mu, mu_n, rtol=0.01)
            np.testing.assert_allclose(area, area_n, rtol=0.01)
