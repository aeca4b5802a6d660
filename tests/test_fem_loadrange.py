"""The loads the FEM cell holds (issue 41, item 1: a point outside the model's range is
reported with the reason): one rule, a mean pressure at or below the rubber's relaxed
modulus, for the automatic mesh's test and for the law's extension."""

from __future__ import annotations

import time

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.fem.loadrange import outside_range
from rubbercontact.pipeline.lawcover import Coverage, plan_extension

#: An elastic rubber and a gentle sine: pressed at 1.5 E (flat full contact) the cell
#: converges in a few Newton iterations, so only the rule can stop it.
E = 4.0
SURF = rc.roughness.SineSeries([1.0], [0.01], [np.pi / 2])


def test_the_rule_is_the_relaxed_modulus():
    assert outside_range(E, E) is None and outside_range(0.5 * E, E) is None
    why = outside_range(1.5 * E, E)
    assert "6 MPa is above the relaxed modulus E∞ = 4 MPa" in why


def test_the_automatic_mesh_refuses_a_load_above_the_relaxed_modulus_before_any_work():
    mat = rc.materials.GeneralizedMaxwell.elastic(E)
    t0 = time.process_time()
    with pytest.raises(InputError, match=r"outside the cell's range.*relaxed modulus"):
        rc.fem.steady_sliding(SURF, mat, 1.5 * E, 1.0, mesh="auto", columns_per_wave=8)
    assert time.process_time() - t0 < 1.0
    # at E∞ itself, and on an explicit mesh above it (with the warning), the test runs
    ok = rc.fem.steady_sliding(SURF, mat, E, 1.0, mesh="auto", columns_per_wave=8)
    assert ok.contact_fraction == pytest.approx(1.0)
    with pytest.warns(RuntimeWarning, match="relaxed modulus"):
        tried = rc.fem.steady_sliding(SURF, mat, 1.5 * E, 1.0, mesh=(8, 8))
    assert tried.contact_fraction == pytest.approx(1.0)


def test_a_speed_path_reports_the_refused_point_and_goes_on():
    from rubbercontact.fem.sweep import sweep_points

    mat = rc.materials.GeneralizedMaxwell.elastic(E)
    opts = rc.fem.make_options(mesh="auto", columns_per_wave=8)
    p = np.array([0.5 * E, 1.5 * E, 0.6 * E])
    pts = sorted(sweep_points(SURF, mat, p, np.ones(3), opts, first=0,
                              errors=(InputError,)), key=lambda pt: pt.index)
    assert pts[0].result is not None and pts[2].result is not None
    assert pts[1].result is None and "relaxed modulus" in str(pts[1].error)


def test_the_law_extension_stops_on_the_same_rule():
    import xarray as xr

    law = xr.Dataset({"status": (("velocity", "pressure"), [["ok"]])},
                     coords={"velocity": [10.0], "pressure": [3.5]})
    # the first rung above 3.5 MPa is 10 MPa, above E∞ = 4 MPa
    cov = Coverage(np.array([10.0]), np.array([20.0]), np.array([3.5]))
    ext = plan_extension(cov, law, max_pressure=np.inf, relaxed_modulus=E)
    assert not ext.points and ext.stopped[10.0] == outside_range(10.0, E)
