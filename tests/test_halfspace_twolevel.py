"""The two-level correction of the soft-law preconditioner on maps (``coarse_space_2d``).

Its coarse operator against the Galerkin product ``R A R^T`` computed point by point, its
block kernel against the fine kernel averaged by hand, and the solves with it against the
one-level path (the same answers to the solver's tolerance) and in 1D (untouched).
"""

from __future__ import annotations

import numpy as np
import pytest

from rubbercontact.errors import InputError
from rubbercontact.halfspace import (
    LennardJonesRepulsion,
    SolverOptions,
    TabulatedLaw,
    solve_sliding,
)
from rubbercontact.halfspace import kernels as kn
from rubbercontact.halfspace.problem import Problem
from rubbercontact.halfspace.twolevel import CoarseCorrection, block_kernel, coarse_correction
from rubbercontact.materials import GeneralizedMaxwell, sbr
from rubbercontact.roughness import SineSeries
from rubbercontact.roughness.mapsynth import self_affine_map

MAT = sbr()
#: the one-level soft-law preconditioner as before the coarse space
ONE_LEVEL = SolverOptions(coarse_space_2d=None, soft_law_scale_beta_2d=4.0)


#: the coarse space on every map size (the default only from 512² on)
ANY_SIZE = SolverOptions(coarse_space_min_side_2d=1)


def _problem(shape=(32, 24), lengths=(0.4, 0.3), options=None) -> Problem:
    n = shape[0] * shape[1]
    return Problem(shape, lengths, np.zeros(n), np.zeros(n),
                   kn.response_kernel(MAT, shape, lengths, 10.0), 0.3, options or ANY_SIZE)


def _fine_kernel(prob: Problem) -> np.ndarray:
    """The real-space kernel: ``(M σ)_i = Σ_l K[i − l] σ_l`` (periodic)."""
    return np.fft.irfft2(prob.compliance, s=prob.shape)


def test_block_kernel_is_the_fine_kernel_averaged_over_block_pairs():
    # M̄(J) = mean of M(i − l), i in block J, l in block 0; the FFT form against the sum by
    # hand: both sum the same float64 terms in another order (round-off, 1e-12 of max |M|)
    prob = _problem()
    blocks = 4
    fy, fx = 8, 6
    kern = _fine_kernel(prob)
    mbar, m0, moff = block_kernel(prob, blocks)
    ny, nx = prob.shape
    want = np.zeros((blocks, blocks))
    for jy in range(blocks):
        for jx in range(blocks):
            tot = 0.0
            for iy in range(jy * fy, (jy + 1) * fy):
                for ix in range(jx * fx, (jx + 1) * fx):
                    for ly in range(fy):
                        tot += kern[(iy - ly) % ny, (ix - np.arange(fx)) % nx].sum()
            want[jy, jx] = tot / (fy * fx) ** 2
    scale = np.abs(kern).max()
    np.testing.assert_allclose(mbar, want, rtol=0, atol=1e-12 * scale)
    assert m0 == pytest.approx(kern[0, 0], rel=1e-12)
    pairs = [(a, b) for a in np.ndindex(fy, fx) for b in np.ndindex(fy, fx) if a != b]
    off = np.mean([kern[(a[0] - b[0]) % ny, (a[1] - b[1]) % nx] for a, b in pairs])
    assert moff == pytest.approx(off, rel=1e-11)


def _galerkin(prob: Problem, idx: np.ndarray, c: np.ndarray, agg: np.ndarray, m: int):
    """``R A R^T`` with ``A = M_BB + diag c`` by one transform per aggregate."""
    out = np.zeros((m, m))
    for j in range(m):
        x = np.zeros(prob.size)
        x[idx[agg == j]] = 1.0
        col = prob.displacement(x)[idx] + c * (agg == j)
        out[:, j] = np.bincount(agg, col, m)
    return out


def test_coarse_operator_is_the_galerkin_operator_on_whole_blocks():
    # the whole grid as the set: every aggregate a whole block, where the block kernel is
    # exact (between blocks and within one); against R A R^T point by point (round-off:
    # measured 4e-16 of the largest entry)
    prob = _problem()
    idx = np.arange(prob.size)
    c = np.random.default_rng(3).uniform(0.0, 5.0, idx.size) * prob.compliance_diagonal
    cc = CoarseCorrection(prob, idx, c, 4)
    want = _galerkin(prob, idx, c, cc.agg, cc.m)
    np.testing.assert_allclose(cc.matrix, want, rtol=0, atol=1e-11 * np.abs(want).max())


def test_coarse_operator_on_a_sparse_set_is_near_the_galerkin_operator():
    # on a partial set the pairs within a block and between neighbours are averaged: the
    # coarse operator is an approximation there. Bound: 10 % of its largest entry, the
    # block-to-block coupling at one block apart being what the average misplaces (measured
    # 2.1 % on this random fifth of a 64² grid)
    prob = _problem((64, 64), (0.5, 0.5))
    rng = np.random.default_rng(5)
    idx = np.flatnonzero(rng.random(prob.size) < 0.2)
    c = rng.uniform(0.0, 30.0, idx.size) * prob.compliance_diagonal
    cc = CoarseCorrection(prob, idx, c, 8)
    want = _galerkin(prob, idx, c, cc.agg, cc.m)
    assert np.abs(cc.matrix - want).max() < 0.1 * np.abs(want).max()


def test_correction_solves_the_coarse_space_exactly():
    # for a vector of the coarse space (constant per aggregate) and its image under the
    # Galerkin operator, the coarse part of the correction returns it (the one-level part
    # zero here): R^T A_c⁻¹ R (A R^T y) = R^T y up to the load border's constant
    prob = _problem()
    idx = np.arange(prob.size)
    c = np.full(idx.size, 2.0 * prob.compliance_diagonal)
    cc = CoarseCorrection(prob, idx, c, 4)
    y = np.random.default_rng(1).standard_normal(cc.m)
    y -= np.average(y, weights=cc.counts)         # Σ x = 0
    x = y[cc.agg]
    ax = prob.displacement(x) + c * x
    got = cc.apply(ax - ax.mean(), np.zeros(idx.size))
    np.testing.assert_allclose(got - got.mean(), x - x.mean(), rtol=0, atol=1e-10)


def test_coarse_correction_needs_divisible_sides_and_the_option():
    # the default 16 blocks per side: 64 × 32 divides (blocks of 4 × 2), 64 × 40 does not,
    # 64 × 16 leaves blocks of one point along x
    assert coarse_correction(_problem((64, 32)), np.arange(10), None) is not None
    default = SolverOptions()
    assert coarse_correction(_problem((512, 512), options=default), np.arange(10), None) \
        is not None
    assert coarse_correction(_problem((256, 512), options=default), np.arange(10), None) is None
    assert coarse_correction(_problem((64, 40)), np.arange(10), None) is None
    assert coarse_correction(_problem((64, 16)), np.arange(10), None) is None
    assert coarse_correction(_problem((64, 32), options=ONE_LEVEL), np.arange(10), None) is None


def test_a_singular_coarse_system_leaves_the_one_level_preconditioner(monkeypatch):
    def singular(a):
        raise np.linalg.LinAlgError("singular matrix")

    monkeypatch.setattr(np.linalg, "inv", singular)
    assert coarse_correction(_problem((64, 32)), np.arange(10), None) is None


@pytest.mark.parametrize("bad", [0, -1, True, float("inf")])
def test_beta_option_is_a_positive_number(bad):
    assert SolverOptions(soft_law_scale_beta_2d=4.0).soft_law_scale_beta_2d == 4.0
    with pytest.raises(InputError, match="soft_law_scale_beta_2d"):
        SolverOptions(soft_law_scale_beta_2d=bad)


def _cell_like():
    """The wall + soft path's hard case (as ``test_halfspace_maps``): a soft law decaying
    over 2.5 µm, the shape of the hybrid's linear law of a high-slope cell."""
    u = np.linspace(0.0, 0.0025, 26)
    sig = 1.8 * np.exp(-u / 0.0005)
    sig[-1] = 0.0
    return TabulatedLaw(u, sig, contact_fraction=np.minimum(1.0, sig), shear_stress=0.07 * sig)


def test_two_level_keeps_the_map_answer():
    # 256² with the coarse space forced on (its systems use the soft-law preconditioner,
    # 16² blocks of 16²): both stop at tol 1e-8 on |σ − f(u)|/|σ|, so μ, A, ū agree to
    # ~1e-8 times the problem's conditioning; bound 1e-6 as the other map switches
    # (tests/test_halfspace_maps.py). Measured: within 3e-14, pressure 1.3e-12
    hm = self_affine_map((256, 256), 2.0, 0.8, rms_gradient=0.5, seed=1)
    args = (hm.heights, hm.lengths, MAT, 10.0, 0.3)
    law = LennardJonesRepulsion() + _cell_like()
    new = solve_sliding(*args, law=law, options=ANY_SIZE)
    old = solve_sliding(*args, law=law, options=ONE_LEVEL)
    for k in ("friction", "contact_fraction", "mean_separation"):
        assert getattr(new, k) == pytest.approx(getattr(old, k), rel=1e-6), k
    assert np.linalg.norm(new.pressure - old.pressure) < 1e-5 * np.linalg.norm(old.pressure)


def test_two_level_leaves_1d_bitwise():
    # a profile's systems never use the soft-law preconditioner: bitwise the one-level answer
    surf = SineSeries([1.0, 0.25, 0.0625], [0.02, 0.006, 0.002], [0.3, 1.1, 2.0])
    law = LennardJonesRepulsion() + _cell_like()
    new = solve_sliding(surf, 1.0, MAT, 10.0, 0.3, law=law, n=8192)
    old = solve_sliding(surf, 1.0, MAT, 10.0, 0.3, law=law, n=8192, options=ONE_LEVEL)
    np.testing.assert_array_equal(new.pressure, old.pressure)
    assert new.matvecs == old.matvecs


@pytest.mark.parametrize("elastic", [False, True])
def test_two_level_keeps_the_hard_wall_answer(elastic):
    # the hard wall's systems (c = 0, kernel 1/M) with the coarse space forced on at 256²:
    # both solve each active-set system to 1e-8 and stop when the set stops changing, so
    # the same set and the pressure within ~1e-8 times the conditioning; bounds as the map
    # switches of tests/test_halfspace_maps.py (1e-6, pressure 1e-5; μ also 1e-8 absolute: the
    # elastic μ is ~1e-5, discretisation only). Measured: the same set, μ, A, ū within 5e-10
    # (elastic μ 3e-11 absolute), pressure 2.4e-8
    hm = self_affine_map((256, 256), 2.0, 0.8, rms_gradient=0.5, seed=1)
    mat = GeneralizedMaxwell.elastic(10.0) if elastic else MAT
    args = (hm.heights, hm.lengths, mat, 10.0, 0.3)
    new = solve_sliding(*args, options=ANY_SIZE)
    old = solve_sliding(*args, options=ONE_LEVEL)
    assert new.friction == pytest.approx(old.friction, rel=1e-6, abs=1e-8)
    for k in ("contact_fraction", "mean_separation"):
        assert getattr(new, k) == pytest.approx(getattr(old, k), rel=1e-6), k
    assert np.linalg.norm(new.pressure - old.pressure) < 1e-5 * np.linalg.norm(old.pressure)
