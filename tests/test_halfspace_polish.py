"""Coarse-grid start of the viscoelastic hard wall across an unresolved leading edge.

The profile and load of ``benchmarks/bench_flash.py`` (seed 1, N = 2^14, 0.2 MPa): between
about 14.5 and 14.9 mm/s the active-set polish of the interpolated coarse solution moves one
leading contact edge by two grid points per update (odd–even pressure at the unresolved
glassy edge) and needs 23 updates, more than ``options.coarse_polish_updates``.
"""

from __future__ import annotations

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.halfspace import SolverOptions, solve_sliding
from rubbercontact.roughness import self_affine_profile

SBR = rc.materials.sbr()


@pytest.fixture(scope="module")
def profile() -> np.ndarray:
    z, _ = self_affine_profile(n=2**14, length=10.0, lam_min=0.1, hurst=0.8, rolloff=4,
                               slope=0.5, seed=1)
    return z


def _solve(z, velocity, **kw):
    return solve_sliding(z, 10.0, SBR, velocity, 0.2, **kw)


def test_marching_edge_polish_gives_the_single_grid_answer(profile):
    """At 14.552 mm/s the coarse-grid start (polish extended while the edge advances) is the
    same exact complementarity solution as the projection method on the fine grid alone."""
    fast = _solve(profile, 14.552)
    ref = _solve(profile, 14.552, options=SolverOptions(coarse_min_points=None))
    assert fast.info["coarse_levels"] == 3   # the coarse start was kept, not abandoned
    np.testing.assert_array_equal(fast.pressure > 0, ref.pressure > 0)
    # GMRES stops at 1e-8; μ, A and ū then agree to ~1e-8 (as in test_halfspace.py's
    # test_coarse_grid_start_gives_the_single_grid_answer)
    assert fast.friction == pytest.approx(ref.friction, rel=1e-7)
    assert fast.contact_fraction == pytest.approx(ref.contact_fraction, rel=1e-12)
    assert fast.mean_separation == pytest.approx(ref.mean_separation, rel=1e-7)
    # complementarity: σ >= 0 and no interpenetration beyond the linear tolerance
    assert fast.pressure.min() >= 0.0
    assert fast.separation.min() > -1e-7 * np.abs(profile).max()


def test_marching_edge_speed_lies_between_its_neighbours(profile):
    """μ and ū at 14.552 mm/s lie between those at 14.49 and 15 mm/s (both rise with speed
    here, below the friction peak), and the contact area is between theirs."""
    lo, mid, hi = (_solve(profile, v) for v in (14.49, 14.552, 15.0))
    assert lo.friction < mid.friction < hi.friction
    assert lo.mean_separation < mid.mean_separation < hi.mean_separation
    assert hi.contact_fraction <= mid.contact_fraction <= lo.contact_fraction
