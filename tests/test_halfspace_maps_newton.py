"""Map solves: a Newton step's load correction at the load's round-off.

A Newton step of the half-space solver corrects the load by ``σ0 n − Σσ − Σ δσ_free``,
spread uniformly over the contact set before GMRES, whose tolerance is relative to the
residual of that start. Near ``tol`` the correction is an ulp of ``σ0 n``; on the rows of
the Lennard-Jones wall's tail (local compliance ``c`` up to 1e8 ``m_d``) it became a
residual hundreds of times the Newton residual, the step's loose tolerance
(``options.newton_forcing_target_2d``) then asked for nothing, and the Newton stalled just
above ``tol``. ``options.exact_load_2d`` drops a correction of at most 1e-13 of the load.
Checked against the previous solver path and the imposed load, not printed numbers.
"""

from __future__ import annotations

import numpy as np
import pytest

from rubbercontact.errors import ConvergenceError, InputError
from rubbercontact.halfspace import LennardJonesRepulsion, SolverOptions, solve_sliding
from rubbercontact.materials import sbr
from rubbercontact.roughness.mapsynth import self_affine_map

MAT = sbr()
#: the solver before the 2D speed-ups (as ``tests/test_halfspace_maps.py``)
PREVIOUS = SolverOptions(coarse_min_side_2d=None, single_precision_2d=False, multi_shift_2d=True,
                          wall_soft_mixed_newton_2d=False, soft_law_preconditioner_2d=False,
                          newton_forcing_target_2d=False, wall_soft_linear_rtol_2d=1e-3)
#: the defaults before ``exact_load_2d``
BEFORE = SolverOptions(exact_load_2d=False)
#: relative agreement of μ, contact fraction and ū with the previous path
RTOL = 1e-6


@pytest.fixture(scope="module")
def stalling():
    """The cheapest map found on which the Lennard-Jones wall alone stalled (256², seed 8,
    10 mm/s: 400 steps to 1.62e-8 with ``tol`` 1e-8, the mixed and the plain Newton)."""
    return self_affine_map((256, 256), 2.0, 0.8, rms_gradient=0.5, seed=8)


def _lj(hm, options, max_iter=200):
    return solve_sliding(hm, None, MAT, 10.0, 0.3, law=LennardJonesRepulsion(),
                         options=options, max_iter=max_iter)


def test_lj_wall_converges_where_the_load_roundoff_stalled_it(stalling):
    new = _lj(stalling, None)
    old = _lj(stalling, PREVIOUS)
    assert new.iterations <= 10     # the mixed Newton's steps (6 measured; 5 on PREVIOUS)
    for a, b in ((new.friction, old.friction), (new.contact_fraction, old.contact_fraction),
                 (new.mean_separation, old.mean_separation)):
        assert abs(a - b) <= RTOL * abs(b)
    # the load is still imposed: the dropped correction is below 1e-13 of it
    assert abs(float(np.mean(new.pressure)) - 0.3) <= 1e-12 * 0.3


def test_the_map_reproduces_the_stall_without_the_switch(stalling):
    # the regression's witness: the same solve with the correction kept does not converge
    # in 30 steps (each of the mixed and the plain Newton), which the default does in 6
    with pytest.raises(ConvergenceError, match="did not converge"):
        _lj(stalling, BEFORE, max_iter=30)


def test_dropping_the_roundoff_leaves_a_converging_solve_alone():
    # a map on which both converge (256², seed 4, 10 mm/s: 10 steps before, 5 now): the
    # same answer to the tolerance's conditioning
    hm = self_affine_map((256, 256), 2.0, 0.8, rms_gradient=0.5, seed=4)
    new, old = _lj(hm, None), _lj(hm, BEFORE)
    for a, b in ((new.friction, old.friction), (new.contact_fraction, old.contact_fraction),
                 (new.mean_separation, old.mean_separation)):
        assert abs(a - b) <= RTOL * abs(b)


def test_exact_load_is_a_switch():
    assert SolverOptions().exact_load_2d is True
    with pytest.raises(InputError, match="exact_load_2d"):
        SolverOptions(exact_load_2d=1)
