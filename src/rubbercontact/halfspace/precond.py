"""Preconditioner kernels of the contact-set systems (:mod:`~.contact_set`).

Each is a stiffness kernel ``1/(M(q) + s)`` on the rfft half-grid
(:func:`~rubbercontact.halfspace.kernels.stiffness_kernel`), applied to the zero-extended
vector and restricted back to the set; a local compliance ``c`` that varies over the set
(a law's ``c = 1/k``) is met by several kernels interpolated per row, or by one kernel and
a row scaling. Iteration counts are measured in ``benchmarks/halfspace.md`` and
``benchmarks/maps.md``.
"""

from __future__ import annotations

import numpy as np

from . import kernels as kn
from .options import SINGLE_MIN_POINTS_2D
from .problem import Problem

__all__ = ["shift_weights", "shifted_preconditioner", "soft_law_kernels"]

#: Maps: the soft-law preconditioner is used when at least this fraction of the set's rows
#: has a local compliance ``c`` above the diagonal ``m_d`` of ``M`` (a soft law's rows).
SOFT_MIN_FRACTION = 0.1


def shifted_preconditioner(prob: Problem, c: np.ndarray, contact: np.ndarray) -> np.ndarray:
    """Stiffness kernel ``1/(M + c̄)`` with ``c̄`` the median of ``c`` on the ``contact`` points
    (all points when none is), Hermitian part only unless the options say otherwise."""
    cbar = float(np.median(c[contact])) if contact.any() else float(np.median(c))
    return kn.stiffness_kernel(prob.compliance, cbar,
                               hermitian=not prob.options.complex_preconditioner)


def shift_weights(c: np.ndarray, shifts: np.ndarray) -> np.ndarray:
    """Weights (``len(shifts)`` × ``c.size``) interpolating linearly in ``log c`` between shifts."""
    lc = np.log(np.clip(c, shifts[0], shifts[-1]))
    ls = np.log(shifts)
    j = np.clip(np.searchsorted(ls, lc) - 1, 0, shifts.size - 2)
    t = (lc - ls[j]) / (ls[j + 1] - ls[j])
    weights = np.zeros((shifts.size, c.size))
    cols = np.arange(c.size)
    weights[j, cols] = 1.0 - t
    weights[j + 1, cols] += t
    return weights


def soft_law_kernels(prob: Problem, c: np.ndarray | None, complex_kernel: bool,
                     count: int | None = None
                     ) -> tuple[list[np.ndarray], np.ndarray | None, np.ndarray | None] | None:
    """Kernels, weights and row scaling of the soft-law preconditioner on a map, or ``None``.

    A soft law (``c = 1/k`` above ``m_d`` on at least ``SOFT_MIN_FRACTION`` of the rows,
    e.g. the hybrid's linear law applied to a whole map) would leave those rows to the
    diagonal ``1/(c + m_d)`` in the default preconditioner, which misses their long-range
    elastic coupling: at low ``q`` the restricted ``M`` dominates ``c``, at high ``q``
    ``c`` does. The variable-coefficient stiffness ``1/(M(q) + c(x))`` treats both
    (``options.soft_law_preconditioner_2d``, maps of at least 256² points: at 128² its extra
    FFTs cost more than they save; 1D grids never use it). Its shifts span ``c`` from the
    quantile ``options.soft_law_low_quantile_2d`` of the positive ``c``, at least
    ``options.soft_law_lowest_shift_2d × m_d``, to the largest.

    With ``options.soft_law_scaled_2d`` (the default) it is one kernel at the lowest shift
    and a row scaling (:func:`scaled_kernel`; the weights are ``None``); otherwise ``count``
    kernels (``None``: ``options.soft_law_shifts_2d``; the hard wall + soft law steps pass
    ``options.wall_soft_shifts_2d``) interpolated in ``log c`` (the rows below the lowest
    shift, e.g. hard-wall rows with ``c = 0``, on the lowest; the scaling is ``None``).
    """
    opts = prob.options
    if c is None or len(prob.shape) != 2 or not opts.soft_law_preconditioner_2d \
            or prob.size < SINGLE_MIN_POINTS_2D:
        return None
    m_diag = prob.compliance_diagonal
    if np.count_nonzero(c > m_diag) < SOFT_MIN_FRACTION * c.size:
        return None
    positive = c[c > 0]
    lo = max(float(np.quantile(positive, opts.soft_law_low_quantile_2d)),
             opts.soft_law_lowest_shift_2d * m_diag)
    hi = float(c.max())
    if hi <= 1.01 * lo:   # one local compliance: its kernel alone (no interpolation)
        return [kn.stiffness_kernel(prob.compliance, hi, hermitian=not complex_kernel)], \
            None, None
    if opts.soft_law_scaled_2d:
        return scaled_kernel(prob, c, lo, complex_kernel)
    shifts = np.geomspace(lo, hi, opts.soft_law_shifts_2d if count is None else count)
    kernels = [kn.stiffness_kernel(prob.compliance, float(sh),
                                   hermitian=not complex_kernel) for sh in shifts]
    return kernels, shift_weights(c, shifts), None


def scaled_kernel(prob: Problem, c: np.ndarray, shift: float, complex_kernel: bool
                  ) -> tuple[list[np.ndarray], None, np.ndarray]:
    """The soft-law preconditioner as one stiffness kernel and a row scaling.

    ``1/(M(q) + s)`` at the lowest shift ``s``, its output on row ``i`` multiplied by
    ``(β m_d + s)/(β m_d + c_i)`` (``β = options.soft_law_scale_beta_2d``): where ``c_i``
    exceeds ``s`` the row's local stiffness is lowered towards ``1/(m_d + c_i)`` (the
    high-``q`` end, where ``M`` is near its diagonal ``m_d``) while the long-range coupling
    of ``M`` stays in the kernel. One inverse FFT per application instead of one per
    interpolated shift, and no more GMRES iterations than two shifts on the maps of
    ``benchmarks/maps.md`` (measured there, with the ``β`` and ``s`` tried).

    Parameters
    ----------
    prob
        The problem (its compliance ``M`` [mm/MPa] and diagonal ``m_d``).
    c
        Local compliance of each row of the set [mm/MPa].
    shift
        ``s`` [mm/MPa].
    complex_kernel
        Invert the full complex ``M`` (else its Hermitian part).

    Returns
    -------
    kernels, weights, scale
        ``[1/(M + s)]``, ``None`` and the row scaling (dimensionless, one per row).
    """
    m_diag = prob.compliance_diagonal
    kernel = kn.stiffness_kernel(prob.compliance, shift, hermitian=not complex_kernel)
    beta = prob.options.soft_law_scale_beta_2d * m_diag
    return [kernel], None, (beta + shift) / (beta + c)
