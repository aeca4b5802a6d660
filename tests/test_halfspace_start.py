"""``solve_sliding(..., start=...)``: a solve started from a nearby speed's pressure is the
cold solve's exact complementarity solution (same contact set; μ, ū to the linear
tolerance), hard wall and the Lennard-Jones wall (whose hard-wall guess is started)."""

from __future__ import annotations

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.thermal.contact import start_pressure

SBR = rc.materials.sbr()
SINES = rc.roughness.SineSeries([1.0, 0.1, 0.01], [0.02, 0.002, 0.0002])


@pytest.mark.parametrize("law", [None, rc.halfspace.LennardJonesRepulsion()])
@pytest.mark.parametrize("u0, u1", [(100.0, 110.0), (3.0, 3.3)])
def test_a_started_solve_is_the_cold_solve(law, u0, u1):
    def solve(u, start=None):
        return rc.halfspace.solve_sliding(SINES, None, SBR, u, 0.1, law=law, n=2048,
                                          start=start)

    near = solve(u0)
    cold, warm = solve(u1), solve(u1, start_pressure(near))
    if law is None:
        assert warm.info.get("warm_start") is True
        np.testing.assert_array_equal(warm.pressure > 0, cold.pressure > 0)
    assert warm.friction == pytest.approx(cold.friction, rel=1e-6)
    assert warm.mean_separation == pytest.approx(cold.mean_separation, rel=1e-6)
    assert warm.contact_fraction == cold.contact_fraction


def test_a_start_far_off_falls_back_to_the_cold_path():
    cold = rc.halfspace.solve_sliding(SINES, None, SBR, 30.0, 0.1, n=2048)
    flat = np.full(2048, 0.1)                      # full contact: nothing like the answer
    warm = rc.halfspace.solve_sliding(SINES, None, SBR, 30.0, 0.1, n=2048, start=flat)
    assert warm.friction == pytest.approx(cold.friction, rel=1e-6)


def test_a_start_of_the_wrong_size_is_one_line():
    with pytest.raises(InputError, match="start"):
        rc.halfspace.solve_sliding(SINES, None, SBR, 30.0, 0.1, n=2048, start=np.ones(7))
