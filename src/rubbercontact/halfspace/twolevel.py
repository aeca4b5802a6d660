r"""Two-level correction of the contact-set preconditioner on maps (``options.coarse_space_2d``).

The contact-set systems ``(M x)_B + c x + λ = b``, ``Σ x = S`` on a map
(:mod:`~rubbercontact.halfspace.contact_set`) are preconditioned by one stiffness kernel
applied to the zero-extended vector (for a soft law with a row scaling,
:func:`~rubbercontact.halfspace.precond.scaled_kernel`; for the hard wall, ``c = 0``, the
kernel ``1/M``). That one-level operator leaves the smoothest modes of the set badly
scaled: the set is a perforated fraction of the grid, and its long-range coupling through
``M(q) ~ 1/|q|`` is not what the kernel applied to the zero-extended vector restores. The
correction adds a coarse space of piecewise-constant vectors on aggregates (the set's
points in each of ``k × k`` blocks of the grid):

.. math:: P_2 v = R^T A_c^{-1} R v + (I - R^T D^{-1} R)\,P v

with ``R`` the aggregate sums, ``D`` the aggregates' point counts (so ``R^T D^{-1} R`` replaces
each aggregate's values by their mean: the one-level output keeps only its part of zero
aggregate mean) and ``A_c`` the coarse operator, bordered by the load constraint
``Σ x = 0``. ``A_c ≈ R A R^T`` is assembled without a fine transform: between aggregates
``j ≠ k`` the fine sum ``Σ_{i∈j, l∈k} M(i − l)`` is taken as ``n_j n_k M̄(j − k)``, ``M̄`` the
kernel averaged over pairs of points of two whole blocks (one fine inverse FFT per problem,
cached); within an aggregate the diagonal ``M(0)`` of its ``n_j`` points and the block's mean
off-diagonal coupling for the ``n_j (n_j − 1)`` pairs; plus the aggregate's ``Σ c``. The dense
system has at most ``k² + 1`` rows (``k = 16``: 257), factorised once per solve. GMRES's
iteration counts and the cost are measured in ``benchmarks/maps.md``.
"""

from __future__ import annotations

import numpy as np
import scipy.fft as sfft

from .problem import Problem

__all__ = ["CoarseCorrection", "block_kernel", "coarse_correction"]


def block_kernel(prob: Problem, blocks: int) -> tuple[np.ndarray, float, float]:
    """The compliance averaged over blocks of a map (cached on ``prob``).

    Parameters
    ----------
    prob
        A map problem whose sides are divisible by ``blocks``.
    blocks
        Blocks per side ``k``.

    Returns
    -------
    mbar, m0, moff
        ``M̄(J)`` [mm/MPa] on the ``k × k`` block grid: the mean of ``M(i − l)`` over ``i`` in
        block ``J`` and ``l`` in block 0; the diagonal ``M(0)`` of the fine operator; and the
        mean of ``M(i − l)`` over the pairs ``i ≠ l`` within one block.
    """
    key = ("block_kernel", blocks)
    cache = prob.cache()
    if key in cache:
        return cache[key]
    ny, nx = prob.shape
    fy, fx = ny // blocks, nx // blocks
    # the box sum over a block in each axis, squared (a pair of points, one in each
    # block): |Σ_a e^{-i q a}|² on the rfft half-grid
    qy = np.fft.fftfreq(ny)[:, None]
    qx = np.fft.rfftfreq(nx)[None, :]
    box_y = _box2(qy, fy)
    box_x = _box2(qx, fx)
    comp = prob.compliance
    summed = sfft.irfft2(comp * (box_y * box_x), s=prob.shape, workers=1)
    mbar = summed[::fy, ::fx] / float(fy * fx) ** 2
    # M(0): the inverse transform at the origin, the half-grid's columns counted twice
    # except x = 0 and, for an even nx, x = nx/2
    weight = np.full(comp.shape[1], 2.0)
    weight[0] = 1.0
    if nx % 2 == 0:
        weight[-1] = 1.0
    m0 = float((np.real(comp) * weight).sum() / prob.size)
    pts = fy * fx
    moff = (pts * pts * float(mbar[0, 0]) - pts * m0) / (pts * pts - pts)
    cache[key] = (mbar, m0, moff)
    return cache[key]


def _box2(q: np.ndarray, width: int) -> np.ndarray:
    """``|Σ_{a<width} e^{-2πi q a}|²`` (``q`` in cycles per point): ``sin²(π q w)/sin²(π q)``,
    ``w²`` at ``q = 0``."""
    s = np.sin(np.pi * q)
    out = np.full(q.shape, float(width * width))
    nz = np.abs(s) > 1e-12
    out[nz] = (np.sin(np.pi * q[nz] * width) / s[nz]) ** 2
    return out


class CoarseCorrection:
    """The coarse space of one contact-set system (see the module docstring).

    Parameters
    ----------
    prob
        The map problem.
    idx
        Flat grid indices of the set ``B``.
    c
        Local compliance of each row [mm/MPa] (``None``: 0).
    blocks
        Blocks per side ``k``; the sides must be divisible by it.
    """

    def __init__(self, prob: Problem, idx: np.ndarray, c: np.ndarray | None,
                 blocks: int) -> None:
        ny, nx = prob.shape
        fy, fx = ny // blocks, nx // blocks
        mbar, m0, moff = block_kernel(prob, blocks)
        iy, ix = np.divmod(idx, nx)
        agg = (iy // fy) * blocks + ix // fx
        counts = np.bincount(agg, minlength=blocks * blocks)
        used = np.flatnonzero(counts)
        remap = np.full(blocks * blocks, -1, dtype=np.intp)
        remap[used] = np.arange(used.size)
        self.agg = remap[agg]
        self.m = m = used.size
        # the set (flat indices ascending) runs through each block row by row: its points in
        # one grid row and one block are consecutive. Sums over aggregates as sums over these
        # runs, then over the runs of each aggregate (fewer passes than a bincount of the set)
        run = iy * blocks + ix // fx
        self._starts = np.flatnonzero(np.r_[True, run[1:] != run[:-1]])
        self._run_agg = self.agg[self._starts]
        self._run_len = np.diff(np.r_[self._starts, idx.size])
        n = counts[used].astype(float)
        self.counts = n
        # between aggregates: n_j n_k M̄(J − K) on the block grid (periodic differences)
        jy, jx = np.divmod(used, blocks)
        dy = (jy[:, None] - jy[None, :]) % blocks
        dx = (jx[:, None] - jx[None, :]) % blocks
        a_c = mbar[dy, dx] * np.outer(n, n)
        # within one: the n_j diagonal terms and the n_j (n_j − 1) pairs at the block's
        # mean off-diagonal coupling, instead of n_j² M̄(0); and the set's local compliance
        csum = np.zeros(m) if c is None else np.bincount(self.agg, c, m)
        a_c[np.arange(m), np.arange(m)] += n * m0 + n * (n - 1) * moff - n * n * mbar[0, 0] \
            + csum
        self.matrix = a_c       # A_c ≈ R A R^T [mm/MPa], unbordered (kept for the tests)
        # bordered by Σ x = 0 (the mean-separation multiplier λ takes the constant)
        bordered = np.zeros((m + 1, m + 1))
        bordered[:m, :m] = a_c
        bordered[:m, m] = n
        bordered[m, :m] = n
        self.inverse = np.linalg.inv(bordered)[:m, :m]

    def apply(self, v: np.ndarray, pv: np.ndarray) -> np.ndarray:
        """``R^T A_c⁻¹ R v + pv − R^T D⁻¹ R pv``: the one-level output ``pv = P v`` with its
        aggregate means replaced by the coarse solve's values (float64, on the set)."""
        coarse = self.inverse @ self._sums(v) - self._sums(pv) / self.counts
        return pv + np.repeat(coarse.take(self._run_agg), self._run_len)

    def _sums(self, v: np.ndarray) -> np.ndarray:
        """``R v``: the sums of ``v`` (on the set) over each aggregate, in float64."""
        runs = np.add.reduceat(v, self._starts, dtype=np.float64)
        return np.bincount(self._run_agg, runs, self.m)


def coarse_correction(prob: Problem, idx: np.ndarray,
                      c: np.ndarray | None) -> CoarseCorrection | None:
    """The correction of a map's soft-law system, or ``None`` when
    ``options.coarse_space_2d`` is ``None`` or does not divide both sides into blocks of at
    least two points."""
    opts = prob.options
    blocks = opts.coarse_space_2d
    if blocks is None or len(prob.shape) != 2 \
            or min(prob.shape) < opts.coarse_space_min_side_2d:
        return None
    if any(n % blocks or n // blocks < 2 for n in prob.shape):
        return None
    try:
        corr = CoarseCorrection(prob, idx, c, blocks)
    except np.linalg.LinAlgError:
        return None     # a singular coarse system: the one-level preconditioner
    return corr if np.all(np.isfinite(corr.inverse)) else None
