"""Figures of a map run (plotting/maps) and the fields they draw from the results."""

from __future__ import annotations

import numpy as np
import pytest

from rubbercontact.pipeline import run
from rubbercontact.plotting.maps import plot_map_run, results_map
from rubbercontact.roughness import self_affine_map

SYN = {"size": 1.0, "points": 64, "hurst": 0.8, "rms_gradient": 0.5, "seed": 5}


@pytest.fixture(scope="module")
def ds():
    return run({"surface": {"map": {"synthetic": SYN}}, "loads": {"pressures": [0.1, 0.2, 0.4]},
                "velocities": [1.0, 10.0, 100.0]})


def test_the_results_hold_the_map_and_a_balanced_contact_map(ds):
    hm = self_affine_map((64, 64), 1.0, 0.8, rms_gradient=0.5, seed=5)
    assert np.array_equal(results_map(ds).heights, hm.heights)
    p = ds["contact_pressure"]
    # the kept solution is the middle speed and load; its pressure balances σ0 (force
    # balance, to the solver's tolerance 1e-8)
    assert p.attrs["velocity"] == 10.0 and p.attrs["mean_pressure"] == 0.2
    assert float(p.mean()) == pytest.approx(0.2, rel=1e-6)
    assert p.attrs["friction"] == float(ds["friction"].sel(model="vhs", velocity=10.0,
                                                           pressure=0.2))


def test_every_map_figure_is_written(ds, tmp_path):
    paths = plot_map_run(ds, tmp_path)
    assert [p.name for p in paths] == ["map.png", "map_spectrum.png", "contact_map.png",
                                       "map_friction.png", "map_speed.png"]
    assert all(p.stat().st_size > 10_000 for p in paths)
