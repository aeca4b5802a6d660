"""FFT surface response of a linear (visco)elastic half-space: plain functions on arrays.

Conventions (shared with :mod:`rubbercontact.halfspace.solver`): a periodic field ``f`` sampled on
``n`` points per axis is expanded as ``f(x) = Σ_q f(q) exp(+i q·x)`` (numpy/scipy ``irfftn``), the
last axis is the sliding direction ``x``. The half-space surface response is

``w(q) = M(q) σ(q)``, ``M(q) = 2 / (|q| E_r(q_x v))``, ``E_r = E(ω)/(1 − ν²)``,

and the ``q = 0`` entry of every kernel is 0 (the mean separation carries the mean). All arrays
live on the ``rfftn`` half-grid, where ``q_x >= 0``.
"""

from __future__ import annotations

import numpy as np
import scipy.fft as sfft

from ..materials.protocol import Material

__all__ = ["wavevectors", "response_kernel", "stiffness_kernel", "apply_kernel", "forward",
           "inverse", "derivative_x", "single"]


def forward(field: np.ndarray) -> np.ndarray:
    """Real-to-complex FFT over all axes (``rfftn``, one thread)."""
    if field.ndim == 1:  # the 1D transform skips rfftn's axes bookkeeping (~20 % at N = 1024)
        return sfft.rfft(field, workers=1)
    return sfft.rfftn(field, workers=1)


def inverse(spectrum: np.ndarray, shape: tuple[int, ...], split: bool = False,
            scratch: bool = False) -> np.ndarray:
    """Inverse of :func:`forward` back to a real field of ``shape``.

    Parameters
    ----------
    spectrum
        rfft half-grid spectrum (complex64 or complex128).
    shape
        Real grid shape ``(n,)`` or ``(ny, nx)``.
    split
        Maps: the complex inverse along ``y``, then the real inverse along ``x``, as two
        scipy calls instead of ``irfftn``. The same pocketfft passes (bitwise the same
        result when ``ny`` is a power of two; otherwise within an ulp), but ``irfftn``
        spends as long again around them: at 1024² 14–16 ms against 7–7.5 ms in float64,
        5.1 against 3.7–3.9 ms in float32 (``scratch``; one core, measured for
        ``benchmarks/maps.md``).
    scratch
        ``spectrum`` is a temporary the transform may overwrite (with ``split``).
    """
    if len(shape) == 1:
        return sfft.irfft(spectrum, n=shape[0], workers=1)
    if split and len(shape) == 2:
        rows = sfft.ifft(spectrum, axis=0, workers=1, overwrite_x=scratch)
        return sfft.irfft(rows, n=shape[1], axis=1, workers=1, overwrite_x=True)
    return sfft.irfftn(spectrum, s=shape, workers=1)


def wavevectors(shape: tuple[int, ...], lengths: tuple[float, ...]) -> tuple[np.ndarray,
                                                                              np.ndarray]:
    """Wavevector magnitude ``|q|`` and sliding component ``q_x`` [1/mm] on the rfft half-grid.

    Parameters
    ----------
    shape
        Grid shape ``(n,)`` or ``(ny, nx)``; ``x`` is the last axis.
    lengths
        Periodic lengths [mm], one per axis.
    """
    qs = []
    for i, (n, length) in enumerate(zip(shape, lengths, strict=True)):
        d = length / n
        if i == len(shape) - 1:
            qs.append(2 * np.pi * sfft.rfftfreq(n, d))
        else:
            qs.append(2 * np.pi * sfft.fftfreq(n, d))
    grids = np.meshgrid(*qs, indexing="ij")
    qabs = np.sqrt(sum(g**2 for g in grids))
    return qabs, grids[-1]


def response_kernel(material: Material, shape: tuple[int, ...],
                    lengths: tuple[float, ...], velocity: float, nu: float = 0.5) -> np.ndarray:
    """Surface compliance ``M(q) = 2/(|q| E_r(q_x v))`` [mm/MPa] on the rfft half-grid.

    ``ω = +q_x v`` follows from steady sliding: a rubber material point moving with ``+v``
    relative to the rigid surface sees the mode ``exp(i q x)`` as ``exp(i q v t)``, and the
    material convention is ``σ(t) = E(ω) ε`` for ``ε ∝ exp(iωt)``. With ``v > 0`` the pressure
    then leads on the flanks with ``dz/dx > 0`` and the hysteretic friction is positive.
    Returned array is complex (real for an elastic material); entry ``q = 0`` is 0.
    """
    qabs, qx = wavevectors(shape, lengths)
    # E depends on q_x alone: on a map it is evaluated once per column and broadcast (the
    # same numbers; a branch sum per grid point took 0.5 s of a 1024² solve)
    er = np.broadcast_to(np.asarray(material.complex_modulus(qx[(0,) * (qx.ndim - 1)]
                                                             * velocity), dtype=complex),
                         qx.shape) / (1.0 - nu**2)
    kernel = np.zeros(qabs.shape, dtype=complex)
    nz = qabs > 0
    kernel[nz] = 2.0 / (qabs[nz] * er[nz])
    if material.is_elastic or velocity == 0.0:
        return kernel.real.copy()
    return kernel


def stiffness_kernel(compliance: np.ndarray, shift: float = 0.0,
                     hermitian: bool = True) -> np.ndarray:
    """``1/(Re M(q) + shift)`` (or ``1/(M + shift)``) with the ``q = 0`` entry 0 [MPa/mm].

    With ``shift = 0`` and an elastic material this is the exact inverse ``|q| E_r/2`` of the
    response on zero-mean fields; a positive ``shift`` (a uniform local compliance) regularises
    it. ``hermitian=True`` inverts only the Hermitian part ``Re M`` (symmetric positive
    definite): used as a preconditioner for the non-symmetric viscoelastic operator it keeps
    the preconditioned spectrum in the right half-plane (sector of the loss angle), which
    GMRES needs; inverting the full complex ``M`` (``hermitian=False``) does not guarantee that
    on a contact set, but needs fewer GMRES iterations in practice (measured in
    ``benchmarks/halfspace.md``): the solver uses it and falls back to the Hermitian inverse
    when GMRES stalls.
    """
    if hermitian:
        compliance = np.real(compliance)
    out = np.zeros_like(compliance)
    nz = np.abs(compliance) > 0
    out[nz] = 1.0 / (compliance[nz] + shift)
    return out


def single(kernel: np.ndarray) -> np.ndarray:
    """``kernel`` in single precision (complex64 or float32): with a float32 field
    :func:`apply_kernel` then runs single-precision FFTs (2–4× faster on maps, measured in
    ``benchmarks/maps.md``; relative rounding ~1e-7)."""
    return kernel.astype(np.complex64 if np.iscomplexobj(kernel) else np.float32)


def apply_kernel(kernel: np.ndarray, field: np.ndarray, split: bool = False) -> np.ndarray:
    """Real-space convolution ``irfftn(kernel · rfftn(field))``; ``split``: see
    :func:`inverse`."""
    return inverse(kernel * forward(field), field.shape, split=split, scratch=True)


def derivative_x(field: np.ndarray, length: float) -> np.ndarray:
    """Exact spectral derivative along the last axis of a periodic field [per mm]."""
    shape = field.shape
    nx = shape[-1]
    qx = 2 * np.pi * sfft.rfftfreq(nx, length / nx)
    spec = forward(field)
    factor = 1j * qx
    if nx % 2 == 0:
        factor[-1] = 0.0  # the Nyquist mode has no well-defined derivative of a real field
    return inverse(spec * factor, shape)
