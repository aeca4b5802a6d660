r"""Contact-set linear systems: the one linear solve behind every half-space algorithm.

Every algorithm (hard wall, Newton on a law, wall + soft law) reduces to systems on a contact
set ``B``: ``(M x)_B + c x + λ = b``, ``Σ x = S`` (``c >= 0`` a diagonal local compliance,
``λ`` the mean-separation increment). They are solved by right-preconditioned GMRES
(:mod:`~rubbercontact.halfspace.krylov`) in the subspace ``Σ x = 0`` after removing the mean.

Preconditioner: the *stiffness* operator ``K = 1/(M + c̄)``
(:func:`~rubbercontact.halfspace.kernels.stiffness_kernel`) applied to the zero-extended vector
and restricted back to ``B`` (operator preconditioning: on a contact interval the restricted
``1/|q|`` and ``|q|`` operators are spectrally inverse up to compact terms), so the iteration
count does not grow with the grid. For a viscoelastic material ``M`` is not symmetric (it is
normal, with a positive-definite Hermitian part ``Re M``), hence GMRES. ``K`` inverts the full
complex ``M``, which needs fewer iterations than the inverse of the Hermitian part
``1/(Re M + c̄)``; only the latter is guaranteed to keep the preconditioned operator positive
definite (the sector of the loss angle), so when GMRES with the complex ``K`` has not converged
within ``options.complex_preconditioner_maxiter`` iterations it continues with the Hermitian one
(a safety net, forced in a test).

Steep laws add a ``c`` that varies over orders of magnitude across a contact edge
(``c = 1/k``): where ``c > m_d`` (the diagonal of ``M``) the point is preconditioned by
``1/(c + m_d)``, and when at least ``options.multi_shift_min_points`` points have
``c > 10 c̄`` (resolved edges) the kernel becomes the variable-coefficient
``1/(M(q) + c(x))``, interpolated in ``log c`` between the shifts ``c̄, √(c̄ m_d), m_d`` (one
forward and three inverse FFTs per application); the Newton iteration counts then stay flat
in N. On maps of at least 256² points a soft law (at least a tenth of the rows with
``c > m_d``) is preconditioned over all rows by one stiffness kernel and a row scaling, or by
that variable-coefficient stiffness (:func:`~.precond.soft_law_kernels`), instead of leaving
those rows to the diagonal. In 1D, a contact set of at most ``options.dense_max_set`` points
(or any set on a grid of at most ``options.dense_max_points`` points) is solved directly: the
set's block of the circulant ``M`` is gathered from one column and the bordered system
factorised (in single precision, refined to double: :func:`mixed_precision_solve`). That is
exact and, for the few percent of contact of a rubber on a road, cheaper than GMRES, each of
whose iterations costs two FFTs of the whole grid. On maps of at least 256² points
(``options.single_precision_2d``) the GMRES iterations run with single-precision FFTs and
double-precision residuals refine the solution to the same tolerance
(:func:`_refined_solve_single`; float32 transforms cost 0.2–0.45 of float64 ones there).
Iteration counts and timings are measured in ``benchmarks/halfspace.md`` and
``benchmarks/maps.md``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.linalg import lapack

from . import kernels as kn
from .krylov import gmres
from .options import SINGLE_MIN_POINTS_2D
from .precond import shift_weights, shifted_preconditioner, soft_law_kernels
from .problem import Problem
from .twolevel import coarse_correction

__all__ = ["LinearSolve", "contact_solve", "mixed_precision_solve", "refined_solve",
           "shifted_preconditioner", "step_displacement"]


@dataclass(frozen=True, eq=False)
class LinearSolve:
    """Solution of one contact-set system.

    Attributes
    ----------
    x
        Values on the contact set ``B``.
    multiplier
        ``λ``, the increment of the mean separation [mm].
    iterations
        GMRES iterations (1 for a dense solve).
    residual
        Relative residual of GMRES (0 for a dense solve).
    response
        ``M x`` on the whole grid (flat, ``x`` zero-extended) [mm], from the last
        double-precision residual; ``None`` for a dense solve.
    """

    x: np.ndarray
    multiplier: float
    iterations: int
    residual: float
    response: np.ndarray | None = None


def _solve_dense(prob: Problem, idx: np.ndarray, rhs: np.ndarray, total: float,
                 c: np.ndarray | None) -> LinearSolve:
    """Direct solve of the contact-set system in 1D (bordered dense system on the set).

    With ``options.reuse_dense_factorization``, a solve on the same set as the last one on
    this problem (consecutive Newton steps once the set has settled: only ``c`` changed)
    starts the refinement from that solve's LU factor.
    """
    nb = idx.size
    a = np.empty((nb + 1, nb + 1))
    a[:nb, :nb] = prob.restricted(idx)
    if c is not None:
        a[np.arange(nb), np.arange(nb)] += c
    a[:nb, nb] = 1.0
    a[nb, :nb] = 1.0
    a[nb, nb] = 0.0
    reuse = prob.options.reuse_dense_factorization
    key = idx.tobytes() if reuse else None
    last = prob._dense_lu
    stale = last[1] if reuse and last is not None and last[0] == key else None
    sol, factor = refined_solve(a, np.append(rhs, total), stale)
    prob._dense_lu = (key, factor) if reuse and factor is not None else None
    prob.matvecs += 1
    return LinearSolve(sol[:nb], float(sol[nb]), 1, 0.0)


#: Refinement steps of :func:`mixed_precision_solve` before it falls back to float64.
_REFINE_STEPS = 10
#: Refinement steps allowed from another matrix's factor (:func:`refined_solve`) before a
#: fresh one; each must shrink the residual at least this many times.
_STALE_STEPS = 12
_STALE_CONTRACTION = 4.0


def mixed_precision_solve(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a⁻¹ b`` to float64 accuracy from a float32 LU and iterative refinement.

    The scheme of LAPACK's ``dsgesv`` (not exposed by SciPy): factorise in single precision
    (half the memory traffic of ``dgetrf``), refine ``x += LU⁻¹ (b − a x)`` with the residual
    in double precision until the backward error test
    ``|r|∞ <= |x|∞ |a|_F ε √n`` holds (``ε`` float64's). Where that fails (a matrix too
    ill-conditioned for single precision: the refinement contracts by ``cond(a) ε₃₂`` per
    step) the float64 LU solves it.
    """
    return refined_solve(a, b)[0]


def refined_solve(a: np.ndarray, b: np.ndarray, stale: tuple | None = None
                  ) -> tuple[np.ndarray, tuple | None]:
    """:func:`mixed_precision_solve`, optionally from the LU factor of a nearby matrix.

    Parameters
    ----------
    a, b
        The system (float64).
    stale
        ``(lu, piv)`` of LAPACK's ``sgetrf`` for another matrix of the same size (the same
        contact set with another local compliance ``c``): the refinement is first run with
        it (``x += LU_old⁻¹ (b − a x)``, each step at least ``_STALE_CONTRACTION`` times
        smaller in residual, at most ``_STALE_STEPS``) to the same backward-error test;
        only when it does not contract is ``a`` factorised.

    Returns
    -------
    x, factor
        The solution, and the float32 factor it was refined with (``None`` if the float64
        fallback solved it).
    """
    n = b.size
    bound = float(np.linalg.norm(a)) * np.finfo(float).eps * np.sqrt(n)
    if stale is not None and stale[0].shape[0] == n:
        lu, piv = stale
        x = lapack.sgetrs(lu, piv, b.astype(np.float32))[0].astype(float)
        prev = np.inf
        for _ in range(_STALE_STEPS):
            r = b - a @ x
            rn = float(np.abs(r).max())
            if not np.isfinite(rn) or rn * _STALE_CONTRACTION > prev:
                break
            if rn <= float(np.abs(x).max()) * bound:
                return x, stale
            prev = rn
            x += lapack.sgetrs(lu, piv, r.astype(np.float32))[0]
    lu, piv, info = lapack.sgetrf(a.astype(np.float32))
    if info == 0:
        x = lapack.sgetrs(lu, piv, b.astype(np.float32))[0].astype(float)
        for _ in range(_REFINE_STEPS):
            r = b - a @ x
            if not np.all(np.isfinite(r)):
                break
            if float(np.abs(r).max()) <= float(np.abs(x).max()) * bound:
                return x, (lu, piv)
            x += lapack.sgetrs(lu, piv, r.astype(np.float32))[0]
    return np.linalg.solve(a, b), None


def _to_hermitian(kernels: list[np.ndarray]) -> None:
    """Replace each stiffness kernel ``1/(M + s)`` by ``1/Re(M + s)`` in place."""
    for i, kern in enumerate(kernels):
        nz = kern != 0
        safe = np.zeros(kern.shape)
        safe[nz] = 1.0 / np.real(1.0 / kern[nz])
        kernels[i] = safe


def contact_solve(prob: Problem, idx: np.ndarray, rhs: np.ndarray, total: float,
                  precond: np.ndarray | Callable[[], np.ndarray],
                  c: np.ndarray | None = None,
                  x0: np.ndarray | None = None, rtol: float = 1e-10,
                  extra_diag: np.ndarray | None = None,
                  multi_shift: bool = False, soft_shifts: int | None = None) -> LinearSolve:
    """Solve ``(M x)_B + c x + λ = rhs``, ``Σ x = total`` on the flat indices ``idx``.

    ``precond`` is the stiffness kernel used as preconditioner, or a function returning it
    (called only if it is used: not when the soft-law preconditioner replaces it, whose
    kernels are complex as it would be); ``extra_diag`` (optional, bool
    on B) marks points preconditioned by the diagonal ``1/(c + m_diag)`` instead.
    ``multi_shift``: when many points have ``c`` well above the kernel's shift ``c̄`` (the
    median of ``c``; a steep law's contact edges), the preconditioner becomes the
    variable-coefficient stiffness ``1/(M(q) + c(x))``, interpolated in ``log c`` between
    the kernels for the shifts ``c̄, √(c̄ m_d), m_d`` (one forward and three inverse FFTs).
    ``soft_shifts``: the number of shifts of the soft-law preconditioner on maps
    (:func:`~.precond.soft_law_kernels`; ``None``: ``options.soft_law_shifts_2d``).
    """
    nb = idx.size
    opts = prob.options
    if len(prob.shape) == 1 and (prob.size <= opts.dense_max_points
                                 or nb <= opts.dense_max_set):
        return _solve_dense(prob, idx, rhs, total, c)
    single = (opts.single_precision_2d and len(prob.shape) == 2
              and prob.size >= SINGLE_MIN_POINTS_2D)
    buf = np.zeros(prob.size)
    # single precision: the iterations scatter into a float32 work grid (the transforms'
    # input; the same rounding as converting a float64 grid, without the copy)
    work = np.zeros(prob.size, np.float32) if single else buf
    m_diag = prob.compliance_diagonal
    op = _restricted_operator(prob, idx, c, buf, single=False)

    if callable(precond):
        complex_kernel = np.iscomplexobj(prob.compliance) and opts.complex_preconditioner
    else:
        complex_kernel = np.iscomplexobj(precond)
    soft = soft_law_kernels(prob, c, complex_kernel, soft_shifts)
    if soft is None and callable(precond):
        precond = precond()
    if soft is not None:
        extra_diag = None   # every row on the variable-coefficient kernel
    # the coarse space (maps): for the soft-law preconditioner and the hard wall's kernel
    two_level = coarse_correction(prob, idx, c) if soft is not None or c is None else None
    if extra_diag is not None and extra_diag.any():
        cont = ~extra_diag
        dinv = 1.0 / (c[extra_diag] + m_diag)
        idc = idx[cont]
    else:
        cont = None
        idc = idx
    kernels = [precond]
    weights = scale = None
    if soft is not None:
        kernels, weights, scale = soft
    elif multi_shift and c is not None:
        cc = c if cont is None else c[cont]
        cbar = float(np.median(cc)) if cc.size else m_diag
        if cbar < 0.01 * m_diag and \
                np.count_nonzero(cc > 10.0 * cbar) >= opts.multi_shift_min_points:
            shifts = np.geomspace(cbar, m_diag, 3)
            herm = not complex_kernel
            kernels = [kn.stiffness_kernel(prob.compliance, sh, hermitian=herm)
                       for sh in shifts]
            weights = shift_weights(cc, shifts)
    if single:
        kernels = [kn.single(k) for k in kernels]

    def pre(v):
        v = v - v.mean()
        _scatter(work, idc, v if cont is None else v[cont])
        if weights is None:
            apply = prob.apply_single if single else prob.apply
            pc = apply(kernels[0], work).take(idc).astype(float, copy=False)
        else:
            prob.matvecs += len(kernels)
            spec = kn.forward(work.reshape(prob.shape))
            split = opts.split_inverse_fft_2d
            pc = weights[0] * kn.inverse(spec * kernels[0], prob.shape, split=split,
                                         scratch=True).ravel()[idc]
            for kern, wgt in zip(kernels[1:], weights[1:], strict=True):
                pc += wgt * kn.inverse(spec * kern, prob.shape, split=split,
                                       scratch=True).ravel()[idc]
        _clear(work, idc)
        if scale is not None:
            pc = pc * scale
        if two_level is not None:
            pc = two_level.apply(v, pc)
        if cont is None:
            out = pc
        else:
            out = np.empty_like(v)
            out[cont] = pc
            out[extra_diag] = dinv * v[extra_diag]
        return out - out.mean()

    base = np.full(nb, total / nb)
    if single:
        return _refined_solve_single(prob, idx, rhs, c, base, x0, rtol, pre, kernels, buf,
                                     work)
    b = rhs - (op(base) + 0.0)  # op already removes the mean; rhs mean is irrelevant (λ)
    b = b - b.mean()
    if np.linalg.norm(b) <= 1e-14 * np.linalg.norm(rhs):
        # the uniform pressure solves it (e.g. a contact set of whole columns of a map
        # uniform in y): what is left is a round-off constant, which the zero-mean
        # preconditioner annihilates and GMRES would break down on
        b[:] = 0.0
    y0 = None if x0 is None else (x0 - x0.mean())
    if complex_kernel:
        sol = gmres(op, pre, b, x0=y0, rtol=rtol, maxiter=opts.complex_preconditioner_maxiter)
        its = sol.iterations
        if sol.residual > rtol:
            # the inverse of the full complex M is not guaranteed to keep the preconditioned
            # restricted operator positive definite: fall back to the Hermitian part's inverse
            _to_hermitian(kernels)
            sol = gmres(op, pre, b, x0=sol.x, rtol=rtol)
            its += sol.iterations
    else:
        sol = gmres(op, pre, b, x0=y0, rtol=rtol)
        its = sol.iterations
    x = base + sol.x
    res, mx = _set_residual(prob, idx, rhs, c, x, buf)
    return LinearSolve(x, float(res.mean()), its, sol.residual, mx)


def _restricted_operator(prob: Problem, idx: np.ndarray, c: np.ndarray | None,
                         buf: np.ndarray, single: bool) -> Callable[[np.ndarray], np.ndarray]:
    """``v ↦ (M v)_B + c v`` with its mean removed (the subspace ``Σ x = 0``); ``buf`` a zero
    grid-sized work array (float32 for ``single``: single-precision FFTs)."""
    kernel = prob.compliance_single() if single else prob.compliance
    apply = prob.apply_single if single else prob.apply

    def op(v):
        _scatter(buf, idx, v)
        out = apply(kernel, buf).take(idx).astype(float, copy=False)  # float64 Krylov vectors
        _clear(buf, idx)
        if c is not None:
            out = out + c * v
        return out - out.mean()

    return op


def _scatter(grid: np.ndarray, idx: np.ndarray, values: np.ndarray) -> None:
    """``grid[idx] = values``, ``values`` converted to the grid's dtype first: the same
    rounding, but a scatter that converts as it goes (a float64 vector into a float32
    grid) costs more than the conversion and a plain scatter (``benchmarks/maps.md``)."""
    grid[idx] = values.astype(grid.dtype, copy=False)


def _clear(grid: np.ndarray, idx: np.ndarray) -> None:
    """``grid[idx] = 0`` for a grid that is zero off ``idx``: a whole-grid fill where the
    set is more than a sixteenth of the grid (a contiguous write, faster than the scatter
    there: ``benchmarks/maps.md``)."""
    if idx.size * 16 > grid.size:
        grid.fill(0.0)
    else:
        grid[idx] = 0.0


def step_displacement(prob: Problem, dsig: np.ndarray, w_free: np.ndarray,
                      lin: LinearSolve | None) -> np.ndarray:
    """``M δσ`` [mm] of a step whose ``δσ`` is ``lin.x`` on the set and a fixed part of
    displacement ``w_free`` off it (flat arrays).

    On maps (``options.reuse_response_2d``) the sum of ``w_free`` and the solve's last
    double-precision response ``lin.response``: one FFT pair less per step, the same field
    to round-off; otherwise one transform of ``δσ``.
    """
    if lin is not None and lin.response is not None and len(prob.shape) == 2 \
            and prob.options.reuse_response_2d:
        return w_free + lin.response
    return prob.displacement(dsig)


def _set_residual(prob: Problem, idx: np.ndarray, rhs: np.ndarray, c: np.ndarray | None,
                  x: np.ndarray, buf: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``rhs − (M x)_B − c x`` in double precision (its mean is ``λ``), and ``M x`` on the
    whole grid."""
    _scatter(buf, idx, x)
    mx = prob.apply(prob.compliance, buf)
    _clear(buf, idx)
    return rhs - mx[idx] - (0.0 if c is None else c * x), mx


#: Single-precision GMRES cycles of :func:`_refined_solve_single` reduce the residual by
#: at most this factor each (float32 FFTs round at ~1e-7 relative).
_SINGLE_FLOOR = 1e-5
#: Single-precision cycles to at least this tolerance keep a float32 Krylov basis
#: (``options.single_krylov_2d``; the tighter ones too with ``options.tight_krylov32_2d``).
_KRYLOV32_MIN_RTOL = 1e-3
#: ``options.tight_krylov32_2d``: a cycle tighter than ``_KRYLOV32_MIN_RTOL`` whose
#: double-precision residual ends above this many times its target leaves the solve's
#: further cycles to a float64 basis.
_KRYLOV32_SHORTFALL = 10.0
#: Refinement cycles allowed (each a GMRES solve of the current residual).
_SINGLE_CYCLES = 8


def _refined_solve_single(prob: Problem, idx: np.ndarray, rhs: np.ndarray,
                          c: np.ndarray | None, base: np.ndarray, x0: np.ndarray | None,
                          rtol: float, pre: Callable[[np.ndarray], np.ndarray],
                          kernels: list[np.ndarray], buf: np.ndarray,
                          work: np.ndarray) -> LinearSolve:
    """Mixed-precision iterative refinement (maps, ``options.single_precision_2d``).

    Each cycle: the double-precision residual ``r`` of the set's system (one float64 FFT
    pair), then GMRES on the correction with the operator and preconditioner in single
    precision to ``max(rtol |b|/|r|, _SINGLE_FLOOR)``. Stops when ``|r| <= rtol |b|`` in
    double precision (``b`` the residual of the uniform start), i.e. the test of the
    double-precision path; the last residual gives ``λ``. Each float32 FFT pair costs
    0.3–0.45 of a float64 one on 512²–1024² (measured). ``buf``: a zero float64 grid for
    the residuals, ``work``: a zero float32 grid for the iterations.
    """
    op32 = _restricted_operator(prob, idx, c, work, single=True)
    res, mx = _set_residual(prob, idx, rhs, c, base, buf)
    b = res - res.mean()
    bnorm = float(np.linalg.norm(b))
    if bnorm <= 1e-14 * float(np.linalg.norm(rhs)):
        return LinearSolve(base, float(res.mean()), 0, 0.0, mx)  # the uniform pressure (above)
    x, r, exact = base, b, True
    if x0 is not None:
        # warm start: its residual in single precision; the double-precision test follows
        # the first cycle
        y0 = x0 - x0.mean()
        x, r, exact = base + y0, b - op32(y0), False
    its = 0
    budget = [prob.options.complex_preconditioner_maxiter if np.iscomplexobj(kernels[0]) else 0]
    opts = prob.options
    # the float32 basis down to this cycle tolerance (tight cycles only while they deliver)
    basis_floor = _SINGLE_FLOOR if opts.single_krylov_2d and opts.tight_krylov32_2d \
        else _KRYLOV32_MIN_RTOL
    for _ in range(_SINGLE_CYCLES):
        rnorm = float(np.linalg.norm(r))
        if exact and rnorm <= rtol * bnorm:
            break
        cycle_rtol = max(rtol * bnorm / rnorm, _SINGLE_FLOOR)
        sol = _single_cycle(op32, pre, r, cycle_rtol, kernels, budget, opts.single_krylov_2d,
                            basis_floor, prob.krylov_workspace())
        its += sol.iterations
        dx = sol.x
        if prob.options.single_krylov_2d:
            # the correction lives in Σ x = 0, but a float32 basis rounds its mean to ~1e-7
            # of its size, which would move the load Σ x: a change the zero-mean residual
            # below cannot see (measured: λ off by 1e-8 at any tolerance)
            dx = dx - dx.mean()
        x = x + dx
        res, mx = _set_residual(prob, idx, rhs, c, x, buf)
        r, exact = res - res.mean(), True
        if cycle_rtol < _KRYLOV32_MIN_RTOL and \
                float(np.linalg.norm(r)) > _KRYLOV32_SHORTFALL * cycle_rtol * rnorm:
            basis_floor = _KRYLOV32_MIN_RTOL   # a tight float32 cycle fell short: float64
    return LinearSolve(x, float(res.mean()), its, float(np.linalg.norm(r)) / bnorm, mx)


def _single_cycle(op32, pre, r: np.ndarray, rtol: float, kernels: list[np.ndarray],
                  budget: list[int], krylov32: bool = False,
                  basis_floor: float = _KRYLOV32_MIN_RTOL, workspace: dict | None = None):
    """One GMRES solve of the correction; with the complex preconditioner while
    ``budget[0]`` iterations remain, then (as the double-precision path) the Hermitian
    part's inverse, converted in place in ``kernels``. ``krylov32``: the Krylov basis in
    single precision (``options.single_krylov_2d``) for cycles to at least
    ``basis_floor``; ``workspace``: :func:`~.krylov.gmres`'s."""
    # by default only for loose cycles: on the Lennard-Jones wall alone (c over orders of
    # magnitude) float32 cycles to the last Newton steps' 1e-5 stalled, and the Newton with
    # them (512² map of benchmarks/maps.md: 1.76e-8 after 21 steps, tol 1e-8); tighter ones
    # with options.tight_krylov32_2d, guarded by the caller
    basis = np.float32 if krylov32 and rtol >= basis_floor else np.float64
    # the refinement computes the residual in double precision after every cycle: GMRES
    # need not apply the single-precision operator once more for its own
    if budget[0] <= 0:
        return gmres(op32, pre, r, rtol=rtol, basis_dtype=basis, true_residual=False,
                     workspace=workspace)
    sol = gmres(op32, pre, r, rtol=rtol, maxiter=budget[0], basis_dtype=basis,
                true_residual=False, workspace=workspace)
    budget[0] -= sol.iterations
    if sol.residual > rtol:
        _to_hermitian(kernels)
        kernels[:] = [kn.single(k) for k in kernels]
        budget[0] = 0
    return sol
