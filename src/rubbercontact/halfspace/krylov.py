"""Right-preconditioned restarted GMRES on real vectors (small, allocation-light).

Used for the contact-set systems of the half-space solver, whose operator (the restriction of the
surface compliance ``M`` to the contact set plus a diagonal) is non-symmetric for a viscoelastic
material. With the stiffness-kernel preconditioner the iteration count stays at a handful and does
not grow with the grid size, so orthogonalisation cost is negligible next to the FFTs.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["GmresResult", "gmres"]


@dataclass(frozen=True, eq=False)
class GmresResult:
    """Solution ``x``, iterations (matrix–vector products), relative residual ``|b − A x|/|b|``."""

    x: np.ndarray
    iterations: int
    residual: float


def gmres(matvec: Callable[[np.ndarray], np.ndarray], psolve: Callable[[np.ndarray], np.ndarray],
          b: np.ndarray, x0: np.ndarray | None = None, rtol: float = 1e-10, restart: int = 40,
          maxiter: int = 400, basis_dtype: type = np.float64,
          true_residual: bool = True, workspace: dict | None = None) -> GmresResult:
    """Solve ``A x = b`` with right preconditioning ``A P y = b``, ``x = P y``.

    ``basis_dtype``: the precision of the Krylov vectors and their orthogonalisation
    (``np.float32`` when the operator itself rounds to single precision: half the memory
    traffic of the Gram-Schmidt passes, which move the whole basis twice per iteration);
    the Hessenberg matrix, the rotations and ``x`` stay float64.
    ``true_residual=False``: a cycle that ends by the recurrence's residual estimate (or at
    ``maxiter``) returns that estimate instead of applying ``A`` once more for ``b − A x``
    (for a caller that computes the residual itself, e.g. in higher precision); a cycle
    that ends at the restart length still restarts from the true residual.
    ``workspace``: a dict in which the Krylov bases are kept between calls (grown as
    needed, one per dtype) instead of allocated per cycle: the bases of a 1024² map's
    contact set are tens of MB, and the pages of a fresh array are new to the process at
    every allocation (their faults cost ~5 % of a map solve, ``benchmarks/maps.md``).
    """
    bnorm = float(np.linalg.norm(b))
    x = np.zeros_like(b) if x0 is None else x0.copy()
    if bnorm == 0.0:
        return GmresResult(np.zeros_like(b), 0, 0.0)
    r = b - matvec(x) if x0 is not None else b.copy()
    beta = float(np.linalg.norm(r))
    its = 0
    while beta > rtol * bnorm and its < maxiter:
        m = min(restart, maxiter - its)
        v, z = _bases(workspace, m, b.size, basis_dtype)
        h = np.zeros((m + 1, m))
        cs = np.zeros(m)
        sn = np.zeros(m)
        g = np.zeros(m + 1)
        g[0] = beta
        v[0] = r / beta
        k = 0
        for k in range(m):
            z[k] = psolve(v[k])
            w = matvec(z[k]).astype(basis_dtype, copy=False)
            its += 1
            # classical Gram-Schmidt with one reorthogonalisation (CGS2): as stable as
            # modified Gram-Schmidt, but two matrix-vector products instead of 2(k+1)
            # vector operations (measured: the Python loop dominated at small N)
            basis = v[:k + 1]
            hk = basis @ w
            w -= hk @ basis
            h2 = basis @ w
            w -= h2 @ basis
            h[:k + 1, k] = hk + h2
            h[k + 1, k] = np.linalg.norm(w)
            if h[k + 1, k] > 0:
                v[k + 1] = w / h[k + 1, k]
            for i in range(k):  # apply previous Givens rotations
                t = cs[i] * h[i, k] + sn[i] * h[i + 1, k]
                h[i + 1, k] = -sn[i] * h[i, k] + cs[i] * h[i + 1, k]
                h[i, k] = t
            d = np.hypot(h[k, k], h[k + 1, k])
            cs[k], sn[k] = (1.0, 0.0) if d == 0 else (h[k, k] / d, h[k + 1, k] / d)
            h[k, k] = d
            h[k + 1, k] = 0.0
            g[k + 1] = -sn[k] * g[k]
            g[k] = cs[k] * g[k]
            if abs(g[k + 1]) <= rtol * bnorm or h[k + 1, k] == 0 and d == 0:
                break
        kk = k + 1
        y = np.linalg.solve(np.triu(h[:kk, :kk]), g[:kk]) if kk else np.zeros(0)
        _add_combination(x, y, z[:kk])
        if not true_residual and (abs(g[kk]) <= rtol * bnorm or its >= maxiter):
            return GmresResult(x, its, abs(g[kk]) / bnorm)
        r = b - matvec(x)
        beta = float(np.linalg.norm(r))
        if abs(g[kk]) <= rtol * bnorm and beta > 10 * rtol * bnorm and its >= maxiter:
            break
    return GmresResult(x, its, beta / bnorm)


#: Columns of a single-precision basis converted to double precision at a time.
_BLOCK = 16384


def _add_combination(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> None:
    """``x += y @ z`` (``x``, ``y`` float64). A float32 ``z`` is converted a block of
    columns at a time: ``y @ z`` would convert all of it, a fresh array the size of the
    basis per restart cycle (on a map's contact set its page faults and copy cost more
    than the product; ``benchmarks/maps.md``). The same products, block by block."""
    if z.dtype == x.dtype or x.size <= _BLOCK:
        x += y @ z
        return
    for start in range(0, x.size, _BLOCK):
        x[start:start + _BLOCK] += y @ z[:, start:start + _BLOCK]


def _bases(workspace: dict | None, m: int, n: int, dtype: type) -> tuple[np.ndarray, np.ndarray]:
    """Arrays ``(m + 1) × n`` and ``m × n`` of ``dtype`` for the Krylov vectors, views of
    ``workspace``'s buffers (grown when too small) or fresh ones without a workspace."""
    if workspace is None:
        return np.empty((m + 1, n), dtype), np.empty((m, n), dtype)
    key = np.dtype(dtype).str
    bufs = workspace.get(key)
    if bufs is None or bufs[0].size < (m + 1) * n:
        bufs = (np.empty((m + 1) * n, dtype), np.empty(m * n, dtype))
        workspace[key] = bufs
    return bufs[0][:(m + 1) * n].reshape(m + 1, n), bufs[1][:m * n].reshape(m, n)
