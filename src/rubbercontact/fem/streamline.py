"""The viscous history of steady sliding: the exponential integrator along streamlines.

In the frame of the surface, steady sliding at speed ``v`` is a travelling wave: the
material flows through the periodic cell in ``+x`` and every field is a function of
position only. The transient sliding test with one element of travel per step
(``dt = h/v``) has as its steady state the field that, after one step, is the same
field shifted by one column. For the history of Simo's model this means that every
quadrature point carries the history its *upstream neighbour* (same point of the
element one column to the left, ``h`` upstream) had, advanced by one step of the
exponential integrator of :mod:`.constitutive`::

    Q_b(i) = e^{−ξ_b} Q_b(i−1) + β_b [w₁ ΔS(i) + w₂ ΔS(i−1)],  ΔS(i) = S_iso(i) − S_iso(i−1)

with ``ξ_b = dt/τ_b``, ``w₁ = γ_b``, ``w₂ = 0`` for the linear history update and
``w₁ = γ_b + c_b/2``, ``w₂ = −c_b/2`` for the quadratic one at equal steps. Closing the
recurrence periodically around the row (the streamline is a circle of ``nx``
columns) makes it a circulant operator on each row of quadrature points,
diagonalised by the discrete Fourier transform along the row::

    Q̂(k) = Ĥ(k) Ŝ_iso(k),
    Ĥ(k) = Σ_b β_b [w₁ (1 − z) + w₂ (z − z²)] / (1 − e^{−ξ_b} z),   z = e^{−2πik/nx}.

``Ĥ(0) = 0``: the row mean of ``S_iso`` is constant along the streamline, so the
branches carry none of it; the mean shear and mean compression of the cell are held
by the relaxed modulus, which is why the steady solution is creep-settled by
construction. Only the sum over branches enters the stress, so one spectrum serves
all of them.

The fixed point is exactly the one the transient test reaches at one element of
travel per step, with the same integrator and hence the same time-discretization
error ``O((q v dt)²)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .constitutive import MaterialParameters


@dataclass(frozen=True)
class StreamlineKernel:
    """The circulant history operator of one row of quadrature points.

    Attributes
    ----------
    spectrum
        ``Ĥ(k)`` on the ``rfft`` grid of the row, summed over branches ``(nx//2 + 1,)``.
    nx
        Points per row.
    weight
        ``h₀`` of the sparse part ``h₀ (1 − z)`` that the solver's preconditioner carries
        (default: the circulant's diagonal, see :meth:`upwind_weight`).

    Notes
    -----
    The impulse response ``h_j`` (the weight of the point ``j`` columns upstream) of the
    steady history is dominated by ``h₀`` and ``h₁ ≈ −h₀``: the fast branches act on the
    first upstream difference of the stress, like a viscous damper. Its two-point part
    ``h₀ (1 − z)`` keeps the exact zero at ``k = 0`` (relaxed row means) and is sparse,
    so the preconditioner holds it; the rest is applied through the FFT.
    """

    spectrum: np.ndarray
    nx: int
    weight: float | None = None

    def __post_init__(self) -> None:
        if self.weight is None:
            object.__setattr__(self, "weight", self.upwind_weight())

    def upwind_weight(self) -> float:
        """The circulant's diagonal ``h₀`` (the mean of its two-sided spectrum)."""
        nx, spec = self.nx, self.spectrum
        full = np.concatenate([spec, np.conj(spec[1:(nx + 1) // 2][::-1])])
        return float(full.real.mean())

    @property
    def phase(self) -> np.ndarray:
        """``z = e^{−2πik/nx}`` on the ``rfft`` grid (the upstream shift)."""
        return np.exp(-2j * np.pi * np.arange(self.spectrum.size) / self.nx)

    def upwind(self) -> StreamlineKernel:
        """The sparse part ``h₀ (1 − z)`` alone, as a kernel."""
        return StreamlineKernel(self.weight * (1.0 - self.phase), self.nx, self.weight)

    def blended(self, other: StreamlineKernel, lam: float) -> StreamlineKernel:
        """``(1 − λ) self + λ other``, with ``other``'s preconditioner weight."""
        return StreamlineKernel((1.0 - lam) * self.spectrum + lam * other.spectrum, self.nx,
                                other.weight)

    def apply(self, s: np.ndarray, axis: int = 1) -> np.ndarray:
        """``Σ_b Q_b`` for the isochoric stresses ``s`` (rows of ``nx`` points along ``axis``)."""
        return self._convolve(self.spectrum, s, axis)

    def apply_remainder(self, s: np.ndarray, axis: int = 1) -> np.ndarray:
        """The part of :meth:`apply` beyond ``h₀ (1 − z)``."""
        return self._convolve(self.spectrum - self.weight * (1.0 - self.phase), s, axis)

    def _convolve(self, spec: np.ndarray, s: np.ndarray, axis: int) -> np.ndarray:
        if not np.any(spec):
            return np.zeros_like(s)
        shape = [1] * s.ndim
        shape[axis] = spec.size
        return np.fft.irfft(spec.reshape(shape) * np.fft.rfft(s, axis=axis), n=self.nx,
                            axis=axis)


def streamline_kernel(params: MaterialParameters, dt: float, nx: int) -> StreamlineKernel:
    """The steady history operator for steps of ``dt`` [s] along rows of ``nx`` points.

    ``dt = inf`` (no sliding) gives the relaxed solid (no history); an elastic material
    has none either.
    """
    z = np.exp(-2j * np.pi * np.arange(nx // 2 + 1) / nx)
    spec = np.zeros(z.size, complex)
    if params.n_branches and np.isfinite(dt):
        decay, gamma = params.step_factors(dt)
        if params.history_order == 2:
            c = params.curvature_factors(dt)
            w1, w2 = gamma + 0.5 * c, -0.5 * c
        else:
            w1, w2 = gamma, np.zeros_like(gamma)
        for b in range(params.n_branches):
            spec += params.beta[b] * (w1[b] * (1 - z) + w2[b] * (z - z * z)) / (1 - decay[b] * z)
    return StreamlineKernel(spec, nx)


def branch_histories(params: MaterialParameters, dt: float, s_iso_rows: np.ndarray
                     ) -> np.ndarray:
    """Each branch's steady history ``Q_b`` ``(n_branches, *s_iso_rows.shape)`` for the
    isochoric stresses ``s_iso_rows`` (rows of ``nx`` points along axis 1): the internal
    variables a transient test needs to continue from a steady state."""
    nx = s_iso_rows.shape[1]
    out = np.zeros((params.n_branches,) + s_iso_rows.shape)
    for b in range(params.n_branches):
        one = MaterialParameters(params.mu, params.kappa, params.beta[b:b + 1],
                                 params.tau[b:b + 1], params.history_order,
                                 params.viscous_model)
        out[b] = streamline_kernel(one, dt, nx).apply(s_iso_rows, axis=1)
    return out
