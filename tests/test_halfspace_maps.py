"""The 2D half-space speed-ups against the previous path (issue 42, item 5).

On maps the solver starts from coarser grids (every 2nd point per axis), solves the
contact-set systems with single-precision FFTs refined in double precision, leaves the
multi-shift preconditioner off, ends a wall + soft law with the mixed Newton,
preconditions the systems of a soft law by the variable-coefficient stiffness
``1/(M(q) + c(x))``, does not solve a Newton step's system further than ``tol`` asks and
solves the hard wall + soft law steps' systems to 1e-2. ``PREVIOUS`` switches all seven
back: the solver as it was before, the reference here (``ROUND_BEFORE`` only the last
three).
Both stop at the same tolerance (``tol`` on the Newton residual ``|r|/|σ|``, 1e-8 relative
linear residuals for the hard wall), so two converged answers
differ by the tolerance times the conditioning of the contact problem; the bounds below are
those of the 1D/2D comparisons of ``tests/test_maps_models.py`` (1e-6), measured differences
in the comments.
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
from rubbercontact.halfspace.contact_set import contact_solve, step_displacement
from rubbercontact.halfspace.krylov import gmres
from rubbercontact.halfspace.laws import InteractionLaw
from rubbercontact.halfspace.newton import _newton_rtol
from rubbercontact.halfspace.precond import scaled_kernel
from rubbercontact.halfspace.problem import Problem
from rubbercontact.materials import GeneralizedMaxwell, sbr
from rubbercontact.roughness import SineSeries
from rubbercontact.roughness.mapsynth import self_affine_map

PREVIOUS = SolverOptions(coarse_min_side_2d=None, single_precision_2d=False, multi_shift_2d=True,
                          wall_soft_mixed_newton_2d=False, soft_law_preconditioner_2d=False,
                          newton_forcing_target_2d=False, wall_soft_linear_rtol_2d=1e-3)
#: the defaults before the soft-law preconditioner, the Newton forcing floor and the
#: active-set GMRES tolerance 1e-2 on maps
ROUND_BEFORE = SolverOptions(soft_law_preconditioner_2d=False, newton_forcing_target_2d=False,
                             wall_soft_linear_rtol_2d=1e-3)
#: the defaults of commit 2de76b6: the hard wall + soft law steps on three shifts and to
#: 1e-2 throughout, the coarser grids of that stage to ``tol``, the final Newton's first
#: step on the geometric-mean tangent
ROUND_2DE76B6 = SolverOptions(wall_soft_shifts_2d=3, wall_soft_coarse_tol_2d=None,
                              wall_soft_moving_rtol_2d=None, wall_soft_first_tangent_2d=False,
                              soft_law_scaled_2d=False)
MAT = sbr()
#: relative agreement of μ, contact fraction and ū with the previous path
RTOL = 1e-6
#: relative L2 difference of the pressure fields
PTOL = 1e-5


@pytest.fixture(scope="module")
def rough():
    """A 256² self-affine map (coarsens once to 128²: the default smallest side)."""
    return self_affine_map((256, 256), 2.0, 0.8, rms_gradient=0.5, seed=1)


def _fem_like():
    return TabulatedLaw(separation=[0.004, 0.008, 0.012, 0.016, 0.01867],
                        pressure=[8, 3, 1, 0.3, 0], contact_fraction=[0.6, 0.4, 0.25, 0.1, 0],
                        shear_stress=[2.5, 1.2, 0.4, 0.08, 0])


def _cell_like():
    """A soft law steep on the scale of the map (decays over 2.5 µm; the hybrid's linear law
    of a high-slope cell has this shape): the wall + soft path's hard case."""
    u = np.linspace(0.0, 0.0025, 26)
    sig = 1.8 * np.exp(-u / 0.0005)
    sig[-1] = 0.0
    return TabulatedLaw(u, sig, contact_fraction=np.minimum(1.0, sig), shear_stress=0.07 * sig)


def _assert_same(new, old):
    # μ also absolutely: the elastic map's μ is ~1e-5 (no dissipation, discretisation only)
    assert new.friction == pytest.approx(old.friction, rel=RTOL, abs=1e-8)
    for k in ("contact_fraction", "mean_separation"):
        assert getattr(new, k) == pytest.approx(getattr(old, k), rel=RTOL), k
    dp = np.linalg.norm(new.pressure - old.pressure) / np.linalg.norm(old.pressure)
    assert dp < PTOL


@pytest.mark.parametrize("case", ["hard wall", "elastic", "LJ", "LJ + FEM-like", "LJ + steep"])
def test_fast_map_paths_equal_the_previous_path(rough, case):
    # measured at 256²: μ, A, ū within 2e-10 (the elastic μ ≈ −1e-5: 6e-11 absolute), pressure
    # within 3e-8 (hard wall; the laws within 2e-11)
    mat, law = MAT, None
    if case == "elastic":
        mat = GeneralizedMaxwell.elastic(10.0)
    elif case == "LJ":
        law = LennardJonesRepulsion()
    elif case == "LJ + FEM-like":
        law = LennardJonesRepulsion() + _fem_like()
    elif case == "LJ + steep":
        law = LennardJonesRepulsion() + _cell_like()
    args = (rough.heights, rough.lengths, mat, 10.0, 0.3)
    new = solve_sliding(*args, law=law)
    old = solve_sliding(*args, law=law, options=PREVIOUS)
    _assert_same(new, old)
    if case in ("hard wall", "elastic"):
        assert new.info["coarse_levels"] == 1   # the coarse-grid start did run
        assert np.array_equal(new.pressure > 0, old.pressure > 0)


def test_coarse_map_problem_has_the_fine_kernel_on_its_wavenumbers():
    # the coarse problem's M(q) is the response kernel of the coarse grid: the same modes
    shape, lengths = (16, 32), (1.0, 2.0)
    comp = kn.response_kernel(MAT, shape, lengths, 10.0)
    z = np.random.default_rng(0).standard_normal(shape).ravel()
    prob = Problem(shape, lengths, z - z.mean(), np.zeros(z.size), comp, 0.1, SolverOptions())
    coarse = prob.coarse()
    assert coarse.shape == (8, 16)
    np.testing.assert_array_equal(coarse.compliance,
                                  kn.response_kernel(MAT, (8, 16), lengths, 10.0))
    np.testing.assert_allclose(coarse.z.reshape(8, 16),
                                  (z.reshape(shape)[::2, ::2] - z.reshape(shape)[::2, ::2]
                                   .mean()), rtol=0, atol=1e-15)


def test_refine_is_bilinear_periodic_and_keeps_the_load():
    shape = (8, 12)
    prob = Problem(shape, (1.0, 1.5), np.zeros(96), np.zeros(96),
                   kn.response_kernel(MAT, shape, (1.0, 1.5), 1.0), 0.3, SolverOptions())
    iy, ix = np.meshgrid(np.arange(4), np.arange(6), indexing="ij")
    coarse = (1.0 + ix + 10.0 * iy).astype(float)     # linear inside, wraps at the seams
    fine = prob.refine(coarse.ravel()).reshape(shape)
    assert fine.mean() == pytest.approx(0.3)          # <σ> = σ0 restored by a factor
    r = fine * (coarse[0, 0] / fine[0, 0])
    np.testing.assert_allclose(r[::2, ::2], coarse)
    assert r[0, 1] == pytest.approx(1.5)
    assert r[0, 11] == pytest.approx(0.5 * (6.0 + 1.0))     # periodic along x
    assert r[7, 0] == pytest.approx(0.5 * (31.0 + 1.0))     # periodic along y
    assert r[1, 1] == pytest.approx(0.25 * (1.0 + 2.0 + 11.0 + 12.0))


def test_single_precision_contact_solve_meets_the_double_tolerance(rough):
    # the refined single-precision solve stops on the double-precision residual, with its
    # Krylov basis in float32 (options.single_krylov_2d) or float64
    n = rough.heights.size
    comp = kn.response_kernel(MAT, rough.heights.shape, rough.lengths, 10.0)
    z = rough.heights.ravel()
    idx = np.flatnonzero(z > np.quantile(z, 0.9))
    results = {}
    for single, krylov32 in ((True, True), (True, False), (False, False)):
        prob = Problem(rough.heights.shape, rough.lengths, z - z.mean(), np.zeros(n), comp, 0.3,
                       SolverOptions(single_precision_2d=single, single_krylov_2d=krylov32))
        results[single, krylov32] = contact_solve(prob, idx, z[idx], 0.3 * n,
                                                  prob.preconditioner(), rtol=1e-10)
    ref = results[False, False]
    for fast in (results[True, True], results[True, False]):
        assert fast.residual <= 1e-10
        assert np.linalg.norm(fast.x - ref.x) / np.linalg.norm(ref.x) < 1e-8
        assert fast.multiplier == pytest.approx(ref.multiplier, rel=1e-8)


def test_single_precision_is_off_on_small_maps():
    # below 256² the double-precision path runs unchanged (bitwise)
    hm = self_affine_map((64, 64), 1.0, 0.8, rms_gradient=0.3, seed=2)
    a = solve_sliding(hm.heights, hm.lengths, MAT, 10.0, 0.2)
    b = solve_sliding(hm.heights, hm.lengths, MAT, 10.0, 0.2, options=PREVIOUS)
    np.testing.assert_array_equal(a.pressure, b.pressure)


@pytest.mark.parametrize("law", [None, LennardJonesRepulsion(),
                                 LennardJonesRepulsion() + _fem_like(),
                                 LennardJonesRepulsion() + _cell_like()])
def test_map_uniform_in_y_on_the_fast_path_is_the_1d_solve(law, soft_preconditioner_calls):
    # 256² coarsens once and runs in single precision; the 1D twin (256 points) does neither.
    # Both laws run the soft-law preconditioner in some of their map solves (measured: μ, A,
    # ū within 3e-11 of 1D, the pressure within 4e-10 of its peak)
    surf = SineSeries([1.0, 0.25], [0.02, 0.006], [0.3, 1.1])
    z = surf.heights(np.arange(256) / 256)
    one = solve_sliding(surf, 1.0, MAT, 10.0, 0.3, law=law, n=256)
    two = solve_sliding(np.tile(z, (256, 1)), 1.0, MAT, 10.0, 0.3, law=law)
    if law is None:
        assert two.info["coarse_levels"] == 1
    elif len(law.members) == 2:
        assert any(soft_preconditioner_calls)
    for k in ("friction", "contact_fraction", "mean_separation"):
        assert getattr(two, k) == pytest.approx(getattr(one, k), rel=RTOL), k
    # pointwise at the contact edges: measured 1.1e-6 of the peak pressure for the hard wall
    # (the previous 2D path 1.9e-7), round-off for the laws; bound PTOL as above
    np.testing.assert_allclose(two.pressure, np.tile(one.pressure, (256, 1)), rtol=0,
                               atol=PTOL * one.pressure.max())


class _LinearLaw(InteractionLaw):
    """``σ = a − k u``: a soft law, linear wherever it is evaluated (no clipping)."""

    def __init__(self, a: float, k: float) -> None:
        self.a, self.k = a, k

    def pressure(self, u):
        return self.a - self.k * np.asarray(u)

    def stiffness(self, u):
        return np.full(np.shape(u), self.k)


@pytest.fixture
def soft_preconditioner_calls(monkeypatch):
    """Counts the contact-set solves that used the soft-law preconditioner."""
    calls = []
    original = contact_set.soft_law_kernels

    def counted(*args):
        out = original(*args)
        calls.append(out is not None)
        return out

    monkeypatch.setattr(contact_set, "soft_law_kernels", counted)
    return calls


@pytest.mark.parametrize("material", ["sbr", "elastic"])
def test_soft_law_on_an_oblique_sine_is_the_closed_form(material, soft_preconditioner_calls):
    # σ = a − k u everywhere in contact: σ(q) = k z(q)/(1 + k M(q)) for the one mode, so
    # μ = Δ² q_x Im G/(2σ0), G = k/(1 + k M), M = 2/(|q| E_r(q_x v)); k → ∞ gives the hard
    # wall's |q| q_x Δ² Im E_r/(4σ0). 256²: coarse start and single precision both run
    mat = MAT if material == "sbr" else GeneralizedMaxwell.elastic(10.0)
    n, length, amp, v, sigma0 = 256, 1.0, 2e-4, 10.0, 0.3
    mx, my = 3, 2
    y, x = np.meshgrid(np.arange(n) / n * length, np.arange(n) / n * length, indexing="ij")
    qx, qy = 2 * np.pi * mx / length, 2 * np.pi * my / length
    z = amp * np.sin(qx * x + qy * y)
    m_d = Problem((n, n), (length, length), z.ravel(), np.zeros(z.size),
                  kn.response_kernel(mat, (n, n), (length, length), v), sigma0,
                  SolverOptions()).compliance_diagonal
    k = 0.2 / m_d                                    # c = 1/k = 5 m_d on every row
    assert k * amp < 0.5 * sigma0                    # σ > 0 everywhere
    out = solve_sliding(z, length, mat, v, sigma0, law=_LinearLaw(sigma0, k))
    er = complex(np.asarray(mat.complex_modulus(np.array([qx * v])))[0]) / 0.75
    g = k / (1.0 + k * 2.0 / (np.hypot(qx, qy) * er))
    expected = amp**2 * qx * g.imag / (2 * sigma0)
    # tol (1e-8) bounds |σ − f(u)|/|σ| with σ ≈ σ0, while μ is carried by the fluctuation
    # k Δ|1/(1 + kM)| (a few % of σ0): measured 3.8e-8 (single precision), 3e-16 (double)
    assert out.friction == pytest.approx(expected, rel=3e-7, abs=1e-12)
    assert any(soft_preconditioner_calls)
    if material == "elastic":
        assert abs(out.friction) < 1e-12


def test_soft_law_preconditioner_keeps_the_answer(rough, soft_preconditioner_calls):
    # a wall + soft law whose soft rows have c > m_d: the new defaults against the defaults
    # before (ROUND_BEFORE) and the previous path; measured at 256²: μ, A, ū within 1e-12
    law = LennardJonesRepulsion() + _cell_like()
    args = (rough.heights, rough.lengths, MAT, 10.0, 0.3)
    new = solve_sliding(*args, law=law)
    assert any(soft_preconditioner_calls)
    _assert_same(new, solve_sliding(*args, law=law, options=ROUND_BEFORE))
    _assert_same(new, solve_sliding(*args, law=law, options=PREVIOUS))


def test_wall_soft_map_switches_keep_the_answer(rough, monkeypatch):
    # the hard wall + soft law steps on two shifts (the Newton steps too) and to 5e-2
    # while the set moves, its coarser grid to 1e-6, the final Newton's first step on the
    # tangent at the pressure, against the defaults of 2de76b6; measured at 256²: μ, A, ū
    # within 9e-13, pressure 2e-11, 1028 instead of 1141 FFT pairs (963 against 1079 with
    # the soft-law preconditioner's lowest shift at 0.3 m_d and two Newton shifts)
    shifts = []
    original = contact_set.soft_law_kernels

    def counted(*args):
        out = original(*args)
        if out is not None:
            shifts.append(len(out[0]))
        return out

    monkeypatch.setattr(contact_set, "soft_law_kernels", counted)
    law = LennardJonesRepulsion() + _cell_like()
    args = (rough.heights, rough.lengths, MAT, 10.0, 0.3)
    new = solve_sliding(*args, law=law, options=SolverOptions(soft_law_scaled_2d=False))
    assert set(shifts) == {2}   # both stages on two shifts since soft_law_shifts_2d
    old = solve_sliding(*args, law=law, options=ROUND_2DE76B6)
    _assert_same(new, old)
    assert new.matvecs < old.matvecs


def test_scaled_kernel_is_the_shifted_stiffness_and_the_row_scaling(rough):
    # kernel 1/(M + s); row i scaled by (β m_d + s)/(β m_d + c_i): 1 at c = s
    prob = Problem((64, 64), (1.0, 1.0), np.zeros(64 * 64), np.zeros(64 * 64),
                   kn.response_kernel(MAT, (64, 64), (1.0, 1.0), 10.0), 0.3, SolverOptions())
    m_d = prob.compliance_diagonal
    s = 0.3 * m_d
    c = np.array([0.0, s, 10.0 * m_d])
    kernels, weights, scale = scaled_kernel(prob, c, s, complex_kernel=True)
    assert weights is None and len(kernels) == 1
    np.testing.assert_array_equal(kernels[0], kn.stiffness_kernel(prob.compliance, s,
                                                                  hermitian=False))
    b = prob.options.soft_law_scale_beta_2d * m_d
    np.testing.assert_allclose(scale, [(b + s) / b, 1.0, (b + s) / (b + 10.0 * m_d)],
                               rtol=1e-15)


def test_newton_forcing_floor_is_relative_to_the_tolerance():
    # maps: a step from res near tol solves its system to 0.01 tol/res, not to tol
    assert _newton_rtol(1e-8, 3e-8, mixed=True, target=True) == pytest.approx(1e-2 / 3)
    assert _newton_rtol(1e-8, 3e-8, mixed=True) == pytest.approx(1e-8)
    assert _newton_rtol(1e-8, 1e-2, mixed=True, target=True) == pytest.approx(3e-3)
    assert _newton_rtol(1e-8, 1e-4, loose=True, target=True) == pytest.approx(1e-3)


@pytest.mark.parametrize("law", [LennardJonesRepulsion() + _cell_like(),
                                 LennardJonesRepulsion() + _fem_like()])
def test_map_only_switches_leave_1d_bitwise(law):
    # the soft-law preconditioner and the Newton forcing floor are for maps: a profile
    # (GMRES contact-set solves run in both: 12 and 3) gives bitwise the answer of ROUND_BEFORE
    surf = SineSeries([1.0, 0.25, 0.0625], [0.02, 0.006, 0.002], [0.3, 1.1, 2.0])
    new = solve_sliding(surf, 1.0, MAT, 10.0, 0.3, law=law, n=8192)
    old = solve_sliding(surf, 1.0, MAT, 10.0, 0.3, law=law, n=8192, options=ROUND_BEFORE)
    np.testing.assert_array_equal(new.pressure, old.pressure)
    assert new.matvecs == old.matvecs


@pytest.mark.parametrize("shape", [(16, 16), (8, 32), (17, 16), (6, 10)])
@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_split_inverse_fft_is_the_inverse_transform(shape, dtype):
    # options.split_inverse_fft_2d: the two-pass inverse against scipy's irfftn (bitwise
    # when ny is a power of two, within rounding otherwise) and against the random
    # field it came from (the round trip)
    rng = np.random.default_rng(3)
    field = rng.standard_normal(shape).astype(dtype)
    spec = kn.forward(field)
    got = kn.inverse(spec.copy(), shape, split=True, scratch=True)
    ref = kn.inverse(spec, shape)
    assert got.dtype == ref.dtype == dtype
    if shape[0] & (shape[0] - 1) == 0:
        np.testing.assert_array_equal(got, ref)
    eps = np.finfo(dtype).eps
    np.testing.assert_allclose(got, ref, rtol=0, atol=20 * eps * np.abs(ref).max())
    np.testing.assert_allclose(got, field, rtol=0, atol=20 * eps * np.abs(field).max())
    kept = spec.copy()
    kn.inverse(spec, shape, split=True)
    np.testing.assert_array_equal(spec, kept)   # not scratch: the input is left alone


def test_split_inverse_fft_switch_keeps_the_map_answer(rough):
    # the solver's maps with and without the two-pass inverse: the same transform, so
    # the same answer (bitwise: the test map's sides are powers of two)
    args = (rough.heights, rough.lengths, MAT, 10.0, 0.3)
    law = LennardJonesRepulsion() + _cell_like()
    new = solve_sliding(*args, law=law)
    old = solve_sliding(*args, law=law, options=SolverOptions(split_inverse_fft_2d=False))
    np.testing.assert_array_equal(new.pressure, old.pressure)
    assert new.matvecs == old.matvecs


def test_soft_law_lowest_shift_and_float32_basis_keep_the_answer(rough):
    # the soft-law preconditioner's lowest shift at least 0.3 m_d, two shifts in the
    # Newton steps and the float32 Krylov basis, against 1e-3 m_d, three shifts and the
    # float64 basis (the defaults of e729684); measured at 256²: μ, A, ū within 2e-14,
    # pressure 4e-13, 963 against 1028 FFT pairs
    args = (rough.heights, rough.lengths, MAT, 10.0, 0.3)
    law = LennardJonesRepulsion() + _cell_like()
    new = solve_sliding(*args, law=law, options=SolverOptions(soft_law_scaled_2d=False))
    old = solve_sliding(*args, law=law, options=SolverOptions(
        soft_law_lowest_shift_2d=1e-3, soft_law_shifts_2d=3, single_krylov_2d=False,
        split_inverse_fft_2d=False, soft_law_scaled_2d=False))
    _assert_same(new, old)


def test_scaled_soft_law_preconditioner_keeps_the_answer(rough, monkeypatch):
    # one kernel at the lowest shift and a row scaling against two shifts interpolated in
    # log c (both stages); measured at 256²: μ, A, ū within 7e-15, pressure 3e-13, 857
    # against 963 FFT pairs
    got = []
    original = contact_set.soft_law_kernels

    def recorded(*args):
        out = original(*args)
        if out is not None:
            got.append(out)
        return out

    monkeypatch.setattr(contact_set, "soft_law_kernels", recorded)
    args = (rough.heights, rough.lengths, MAT, 10.0, 0.3)
    law = LennardJonesRepulsion() + _cell_like()
    new = solve_sliding(*args, law=law)
    assert got and all(len(k) == 1 and w is None and s is not None for k, w, s in got)
    old = solve_sliding(*args, law=law, options=SolverOptions(soft_law_scaled_2d=False))
    _assert_same(new, old)
    assert new.matvecs < old.matvecs


@pytest.mark.slow
def test_float32_krylov_basis_keeps_the_lennard_jones_wall_converging():
    # the 512² map of benchmarks/maps.md, Lennard-Jones wall alone: with float32 bases in
    # the tight cycles too its last Newton steps once stalled at 1.76e-8 (tol 1e-8); the
    # defaults (float32 in the tight cycles as well, guarded by the float64 residual:
    # options.tight_krylov32_2d) converge, to the float64 basis's answer
    hm = self_affine_map((512, 512), 2.0, 0.8, rms_gradient=0.5, seed=1)
    args = (hm.heights, hm.lengths, MAT, 10.0, 0.3)
    new = solve_sliding(*args, law=LennardJonesRepulsion())
    old = solve_sliding(*args, law=LennardJonesRepulsion(),
                        options=SolverOptions(single_krylov_2d=False))
    assert new.converged
    _assert_same(new, old)


def test_step_displacement_is_the_transform_of_the_step(rough):
    # linearity: M(δσ_free + E x) = M δσ_free + M E x; the solve's response is M E x
    prob = Problem(rough.heights.shape, rough.lengths, np.zeros(rough.heights.size),
                   np.zeros(rough.heights.size),
                   kn.response_kernel(MAT, rough.heights.shape, rough.lengths, 10.0), 0.3,
                   SolverOptions())
    rng = np.random.default_rng(2)
    idx = np.flatnonzero(rng.random(prob.size) < 0.2)
    dsig = np.zeros(prob.size)
    free = np.ones(prob.size, bool)
    free[idx] = False
    dsig[free] = 1e-3 * rng.standard_normal(free.sum())
    w_free = prob.displacement(dsig)
    rhs = rng.standard_normal(idx.size) * 1e-4
    lin = contact_solve(prob, idx, rhs, 0.3 * idx.size, prob.preconditioner(), rtol=1e-8)
    dsig[idx] = lin.x
    got = step_displacement(prob, dsig, w_free, lin)
    want = prob.displacement(dsig)
    assert np.linalg.norm(got - want) <= 1e-14 * np.linalg.norm(want)
    off = Problem(prob.shape, prob.lengths, prob.z, prob.slope, prob.compliance, 0.3,
                  SolverOptions(reuse_response_2d=False))
    np.testing.assert_array_equal(step_displacement(off, dsig, w_free, lin), want)


def test_response_reuse_and_the_coarser_wall_soft_start_keep_the_answer(rough):
    # the steps' displacements from the solves' responses, the hard wall + soft law stage
    # started from 64² (256 -> 128 -> 64) instead of 128², against both off; measured at
    # 256²: μ, A, ū within 3e-16, pressure 7e-15, 729 against 839 FFT pairs (every level
    # run: wall_soft_skip_level_2d off, tested in test_halfspace_maps_krylov)
    args = (rough.heights, rough.lengths, MAT, 10.0, 0.3)
    law = LennardJonesRepulsion() + _cell_like()
    new = solve_sliding(*args, law=law, options=SolverOptions(wall_soft_skip_level_2d=False))
    old = solve_sliding(*args, law=law, options=SolverOptions(
        reuse_response_2d=False, wall_soft_coarse_min_side_2d=None))
    assert new.info["coarse_levels"] == 2 and old.info["coarse_levels"] == 1
    _assert_same(new, old)
    assert new.matvecs < old.matvecs


def test_gmres_without_the_closing_residual_returns_the_same_iterate():
    # a cycle that ends by its estimate: the same x, one operator application less, and
    # the estimate is the true residual in exact arithmetic (a well-conditioned system)
    rng = np.random.default_rng(3)
    a = np.eye(60) + 0.1 * rng.standard_normal((60, 60))
    b = rng.standard_normal(60)
    calls = []

    def matvec(v):
        calls.append(1)
        return a @ v

    one = gmres(matvec, lambda v: v, b, rtol=1e-10)
    n_true = len(calls)
    calls.clear()
    two = gmres(matvec, lambda v: v, b, rtol=1e-10, true_residual=False)
    np.testing.assert_array_equal(one.x, two.x)
    assert len(calls) == n_true - 1
    true = np.linalg.norm(b - a @ two.x) / np.linalg.norm(b)
    assert two.residual == pytest.approx(true, rel=1e-4)
