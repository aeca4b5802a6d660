"""Map solves: the kept Krylov workspace, the float32 basis in tight cycles, the finest
grid's hard wall + soft law started two levels down.

``options.krylov_workspace_2d`` keeps the GMRES bases between the contact-set solves of a
problem (bitwise the same iterates: only where the vectors live changes);
``options.tight_krylov32_2d`` extends the float32 Krylov basis of the single-precision
cycles to the tight ones, guarded by the double-precision residual. Both are checked
against the paths they replace with stated tolerances, not against earlier printed
numbers.
"""

from __future__ import annotations

import numpy as np
import pytest

from rubbercontact.halfspace import (
    LennardJonesRepulsion,
    SolverOptions,
    TabulatedLaw,
    contact_set,
    solve_sliding,
)
from rubbercontact.halfspace import kernels as kn
from rubbercontact.halfspace.contact_set import contact_solve
from rubbercontact.halfspace.krylov import gmres
from rubbercontact.halfspace.problem import Problem
from rubbercontact.materials import sbr
from rubbercontact.roughness.mapsynth import self_affine_map

MAT = sbr()
#: both switches off: the code before them
BEFORE = SolverOptions(tight_krylov32_2d=False, krylov_workspace_2d=False)


@pytest.fixture(scope="module")
def rough():
    """A 256² self-affine map: the smallest on which the single-precision cycles run."""
    return self_affine_map((256, 256), 2.0, 0.8, rms_gradient=0.5, seed=1)


def _cell_like():
    """A soft law steep on the scale of the map (as in ``test_halfspace_maps``)."""
    u = np.linspace(0.0, 0.0025, 26)
    sig = 1.8 * np.exp(-u / 0.0005)
    sig[-1] = 0.0
    return TabulatedLaw(u, sig, contact_fraction=np.minimum(1.0, sig), shear_stress=0.07 * sig)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_gmres_workspace_gives_the_same_iterates(dtype):
    # a non-symmetric system, solved twice into one workspace (the second larger, so the
    # buffers grow) and once without: bitwise the same solutions and iteration counts
    rng = np.random.default_rng(3)
    ws: dict = {}
    for n in (120, 300):
        a = np.eye(n) * 2.0 + rng.standard_normal((n, n)) / np.sqrt(n)
        b = rng.standard_normal(n)
        kw = {"rtol": 1e-9, "restart": 8, "basis_dtype": dtype}
        ref = gmres(lambda v, a=a: a @ v, lambda v: v, b, **kw)
        got = gmres(lambda v, a=a: a @ v, lambda v: v, b, workspace=ws, **kw)
        np.testing.assert_array_equal(got.x, ref.x)
        assert got.iterations == ref.iterations > 8     # restarted at least once
    assert set(ws) == {np.dtype(dtype).str}


def test_tight_float32_cycles_meet_the_double_tolerance(rough):
    # a contact-set system to rtol 1e-10: every refinement cycle is tighter than 1e-3, so
    # with the switch on they run on a float32 basis; the solve still ends on its
    # double-precision residual, within 1e-8 of the double-precision path
    n = rough.heights.size
    comp = kn.response_kernel(MAT, rough.heights.shape, rough.lengths, 10.0)
    z = rough.heights.ravel()
    idx = np.flatnonzero(z > np.quantile(z, 0.9))
    out = {}
    for key, opts in (("tight", SolverOptions()), ("before", BEFORE),
                      ("double", SolverOptions(single_precision_2d=False))):
        prob = Problem(rough.heights.shape, rough.lengths, z - z.mean(), np.zeros(n), comp,
                       0.3, opts)
        out[key] = contact_solve(prob, idx, z[idx], 0.3 * n, prob.preconditioner(), rtol=1e-10)
    ref = out["double"]
    for key in ("tight", "before"):
        assert out[key].residual <= 1e-10
        assert np.linalg.norm(out[key].x - ref.x) / np.linalg.norm(ref.x) < 1e-8
        assert out[key].multiplier == pytest.approx(ref.multiplier, rel=1e-8)


def test_a_tight_float32_cycle_that_falls_short_leaves_the_rest_to_float64(rough, monkeypatch):
    # with a shortfall factor of 0 every tight float32 cycle "falls short": only the first
    # cycle of each solve may use the float32 basis, and the answer is unchanged
    seen = []
    original = contact_set.gmres

    def recorded(*args, **kw):
        seen.append((kw["rtol"], np.dtype(kw.get("basis_dtype", np.float64))))
        return original(*args, **kw)

    monkeypatch.setattr(contact_set, "gmres", recorded)
    monkeypatch.setattr(contact_set, "_KRYLOV32_SHORTFALL", 0.0)
    n = rough.heights.size
    comp = kn.response_kernel(MAT, rough.heights.shape, rough.lengths, 10.0)
    z = rough.heights.ravel()
    idx = np.flatnonzero(z > np.quantile(z, 0.9))
    prob = Problem(rough.heights.shape, rough.lengths, z - z.mean(), np.zeros(n), comp, 0.3,
                   SolverOptions())
    got = contact_solve(prob, idx, z[idx], 0.3 * n, prob.preconditioner(), rtol=1e-10)
    assert got.residual <= 1e-10
    assert len(seen) >= 2
    assert seen[0][1] == np.float32
    assert all(dt == np.float64 for _, dt in seen[1:])


@pytest.mark.parametrize("law", [LennardJonesRepulsion(),
                                 LennardJonesRepulsion() + _cell_like()])
def test_map_solve_with_both_switches_keeps_the_answer(rough, law):
    # the Lennard-Jones wall alone (whose tight float32 cycles once stalled its Newton) and
    # with a steep soft law, against both switches off: μ, A, ū within 1e-9, pressure
    # within 1e-7 relative L2 (measured at 256²: μ, A, ū equal, pressure 8e-15 and 3e-16;
    # the wall alone 1605 against 2097 FFT pairs, the path changed by the basis' rounding)
    args = (rough.heights, rough.lengths, MAT, 10.0, 0.3)
    new = solve_sliding(*args, law=law)
    old = solve_sliding(*args, law=law, options=BEFORE)
    assert new.converged and old.converged
    for k in ("friction", "contact_fraction", "mean_separation"):
        assert getattr(new, k) == pytest.approx(getattr(old, k), rel=1e-9), k
    dp = np.linalg.norm(new.pressure - old.pressure) / np.linalg.norm(old.pressure)
    assert dp < 1e-7


def test_finest_grid_starting_two_levels_down_keeps_the_answer(rough):
    # options.wall_soft_skip_level_2d: the 256² grid's hard wall + soft law starts from 64²
    # instead of 128²: one coarse level less, the same answer (measured at 256²: μ, A, ū
    # within 1e-15, pressure 1e-13)
    args = (rough.heights, rough.lengths, MAT, 10.0, 0.3)
    law = LennardJonesRepulsion() + _cell_like()
    new = solve_sliding(*args, law=law)
    old = solve_sliding(*args, law=law, options=SolverOptions(wall_soft_skip_level_2d=False))
    assert new.converged and old.converged
    assert new.info["coarse_levels"] == old.info["coarse_levels"] - 1
    for k in ("friction", "contact_fraction", "mean_separation"):
        assert getattr(new, k) == pytest.approx(getattr(old, k), rel=1e-9), k
    dp = np.linalg.norm(new.pressure - old.pressure) / np.linalg.norm(old.pressure)
    assert dp < 1e-7
