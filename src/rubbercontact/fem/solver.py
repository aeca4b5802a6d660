"""Newton–Raphson with the consistent tangent, sparse direct solves and line search.

The tangent of the mean-dilatation element plus the penalty contact is symmetric;
it is factorized with SuperLU in symmetric mode using the ``MMD_AT_PLUS_A``
ordering (minimum degree on ``A + Aᵀ``) and diagonal pivots, with a residual check
and a pivoting fallback. The CSR arrays of the symmetric
matrix are handed to SuperLU directly as a CSC matrix (the transpose of a
symmetric matrix is itself), so no format conversion is paid.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu


@dataclass
class SolverCounters:
    """Work counters accumulated over a whole test."""

    newton_iterations: int = 0
    factorizations: int = 0
    residual_evaluations: int = 0
    line_search_cuts: int = 0
    assembly_time: float = 0.0
    solve_time: float = 0.0
    residual_ratios: list = field(default_factory=list)
    loose_convergences: int = 0


class NewtonFailure(Exception):
    """One Newton solve failed (the caller cuts the step back)."""

    def __init__(self, reason: str, history: list[float]) -> None:
        super().__init__(reason)
        self.reason = reason
        self.history = history


class _Factor:
    """A factorization with a residual check and a pivoting fallback."""

    def __init__(self, K: sp.csr_matrix) -> None:
        self.Kc = sp.csc_matrix((K.data, K.indices, K.indptr), shape=K.shape)
        # Symmetric mode (diagonal pivots, ordering on A + Aᵀ) keeps the fill of the
        # minimum-degree ordering: 2.9 M non-zeros and 0.14 s at 120 × 90 against 36 M and
        # 8 s with SuperLU's default threshold pivoting, which destroys the ordering.
        try:
            self.lu = splu(self.Kc, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                           options={"SymmetricMode": True})
            self.pivoted = False
        except RuntimeError:  # zero diagonal pivot: fall back to threshold pivoting
            self.lu = splu(self.Kc, permc_spec="MMD_AT_PLUS_A")
            self.pivoted = True

    def solve(self, r: np.ndarray) -> np.ndarray:
        x = self.lu.solve(r)
        bad = not np.all(np.isfinite(x))
        if not bad:
            res = np.linalg.norm(self.Kc @ x - r)
            bad = res > 1e-6 * max(np.linalg.norm(r), 1e-300)
        if bad and not self.pivoted:
            # An indefinite tangent mid-iteration can need pivoting: refactorize safely.
            self.lu = splu(self.Kc, permc_spec="MMD_AT_PLUS_A")
            self.pivoted = True
            x = self.lu.solve(r)
        return x


class _GeneralFactor:
    """LU of a structurally symmetric, non-symmetric matrix (the steady preconditioner).

    Diagonal pivots on the minimum-degree ordering of ``A + Aᵀ`` keep the fill of the
    symmetric case; a residual check falls back to threshold pivoting.

    With ``single=True`` the factors are computed and applied in single precision (the
    right-hand side and the solution stay double). That suits a preconditioner: GMRES
    only needs ``K⁻¹`` approximately, and a single-precision SuperLU factorization and
    solve move half the bytes. The check then accepts a relative residual up to
    :data:`SINGLE_RESIDUAL` and otherwise refactorizes in double precision.
    """

    def __init__(self, K: sp.csr_matrix, single: bool = False) -> None:
        self.Kc = K.tocsc()
        self.single = single
        self.checked = False
        if single:
            try:
                self.lu, self.pivoted = self._symmetric_mode(self.Kc.astype(np.float32))
                return
            except RuntimeError:   # singular in single precision (underflow): use double
                self.single = False
        self.lu, self.pivoted = self._symmetric_mode(self.Kc)

    @staticmethod
    def _symmetric_mode(A: sp.csc_matrix):
        try:
            return splu(A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                        options={"SymmetricMode": True}), False
        except RuntimeError:
            return splu(A, permc_spec="MMD_AT_PLUS_A"), True

    def _apply(self, r: np.ndarray) -> np.ndarray:
        if self.single:
            return self.lu.solve(r.astype(np.float32)).astype(np.float64)
        return self.lu.solve(r)

    def solve(self, r: np.ndarray) -> np.ndarray:
        x = self._apply(r)
        if not self.checked:   # once: the factor is either accurate or not
            self.checked = True
            limit = SINGLE_RESIDUAL if self.single else 1e-6
            bad = not np.all(np.isfinite(x)) or (
                np.linalg.norm(self.Kc @ x - r) > limit * max(np.linalg.norm(r), 1e-300))
            if bad and self.single:
                self.single = False
                self.lu, self.pivoted = self._symmetric_mode(self.Kc)
                self.checked = False
                return self.solve(r)
            if bad and not self.pivoted:
                self.lu = splu(self.Kc, permc_spec="MMD_AT_PLUS_A")
                self.pivoted = True
                x = self.lu.solve(r)
        return x


#: Largest relative residual ``‖K x − r‖/‖r‖`` accepted from a single-precision
#: factorization before it is redone in double precision: a preconditioner within a few
#: per cent leaves GMRES's iteration count unchanged (BENCHMARKS.md, steady FEM).
SINGLE_RESIDUAL = 0.05


def factorize_general(K: sp.csr_matrix, single: bool = False) -> _GeneralFactor:
    """Factorization of the non-symmetric ``K`` (CSR), see :class:`_GeneralFactor`;
    ``single``: in single precision, for use as a preconditioner."""
    return _GeneralFactor(K, single)


def factorize(K: sp.csr_matrix) -> _Factor:
    """Factorization of the symmetric matrix ``K`` (given as CSR), see :class:`_Factor`."""
    return _Factor(K)


def newton(residual: Callable, U0: np.ndarray, *, atol: float, max_iter: int = 25,
           counters: SolverCounters | None = None, max_line_search: int = 5,
           max_step: float | None = None):
    """Solve ``r(U) = 0``.

    Parameters
    ----------
    residual
        ``residual(U, tangent) -> (r, K or None, aux)``; ``r`` contains NaN if the
        state is inadmissible (inverted element).
    U0
        Predictor.
    atol
        Convergence when ``‖r‖₂ <= atol``.
    max_iter
        Newton iterations before giving up.
    counters
        Accumulates work statistics.
    max_step
        Largest change of any unknown per iteration [mm] (``None``: no limit).
    max_line_search
        Maximum line-search trials per iteration.

    Returns
    -------
    U, aux, history
        Converged unknowns, the ``aux`` of the converged evaluation and ``‖r‖`` per iteration.

    Raises
    ------
    NewtonFailure
        On non-convergence or an inadmissible predictor.
    """
    c = counters if counters is not None else SolverCounters()
    U = U0.copy()
    t0 = time.perf_counter()
    r, K, aux = residual(U, True)
    c.assembly_time += time.perf_counter() - t0
    c.residual_evaluations += 1
    norm = float(np.linalg.norm(r))
    hist = [norm]
    if not np.isfinite(norm):
        raise NewtonFailure("inadmissible predictor (inverted element)", hist)
    for _ in range(max_iter):
        if norm <= atol:
            return U, aux, hist
        t0 = time.perf_counter()
        try:
            lu = factorize(K)
            dU = -lu.solve(r)
        except RuntimeError as exc:  # singular matrix
            raise NewtonFailure(f"linear solve failed: {exc}", hist) from None
        c.solve_time += time.perf_counter() - t0
        c.factorizations += 1
        c.newton_iterations += 1
        if max_step is not None:
            # Trust region: no node moves more than max_step in one iteration, which keeps
            # elements from inverting and face nodes from being driven deep into the
            # surface (where the penalty force would dwarf the load).
            big = float(np.max(np.abs(dU)))
            if big > max_step:
                dU *= max_step / big
        # Line search on the incremental energy along dU: G(α) = dU·r(U + α dU) is its
        # derivative (the step has an incremental potential: the history stress is
        # constant within a step). Accept α = 1 unless it overshoots the minimum badly
        # (G(1) > η|G(0)|) or inverts elements; then Illinois/secant steps on G.
        g0 = float(dU @ r)
        lo, g_lo = 0.0, g0
        alpha, hi, g_hi = 1.0, None, None
        for k in range(max_line_search + 1):
            t0 = time.perf_counter()
            r_new, K_new, aux_new = residual(U + alpha * dU, True)
            c.assembly_time += time.perf_counter() - t0
            c.residual_evaluations += 1
            n_new = float(np.linalg.norm(r_new))
            if k == max_line_search:
                break
            if not np.isfinite(n_new):
                hi, g_hi = alpha, None
                alpha = 0.5 * (lo + alpha)
                c.line_search_cuts += 1
                continue
            g = float(dU @ r_new)
            if g0 >= 0 or g <= 0.5 * abs(g0) or n_new < norm:
                break  # not a descent direction (accept), or acceptable decrease
            hi, g_hi = alpha, g
            # Secant root of G between lo (G < 0) and hi (G > 0), kept inside the bracket.
            a_new = lo + (hi - lo) * g_lo / (g_lo - g_hi)
            alpha = float(np.clip(a_new, lo + 0.1 * (hi - lo), lo + 0.9 * (hi - lo)))
            c.line_search_cuts += 1
        if not np.isfinite(n_new):
            raise NewtonFailure("line search could not avoid inverted elements", hist)
        if norm > 0:
            c.residual_ratios.append(n_new / norm)
        U = U + alpha * dU
        r, K, aux, norm = r_new, K_new, aux_new, n_new
        hist.append(norm)
    if norm <= 30 * atol:
        # Stagnation just above the tolerance (active-set flicker of one face node at
        # round-off level): accept, the force error is still <= 30 × atol.
        c.loose_convergences += 1
        return U, aux, hist
    raise NewtonFailure(f"no convergence in {max_iter} iterations (‖r‖ = {norm:.3e}, "
                        f"tolerance {atol:.3e})", hist)
