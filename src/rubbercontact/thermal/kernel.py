r"""The steady surface temperature of a half-space under a moving heat flux, by FFT.

In the frame of the heat sources (the contact spots, fixed on the road) the rubber moves
at ``+v`` along ``x``; its temperature rise obeys ``v ∂T/∂x = D ∇²T`` in ``z > 0`` with the
flux ``Q(x) = −K ∂T/∂z`` into the surface. A surface mode ``e^{i k·x}`` decays into the
rubber as ``e^{−λz}``, ``λ² = k² + i k_x v/D`` (``Re λ > 0``), so

.. math:: \hat T(k) = \hat Q(k) / (K λ(k)),\qquad λ = \sqrt{k^2 + i k_x v / D},

(Carslaw & Jaeger, *Conduction of Heat in Solids*, 2nd ed. 1959, §10.7, in Fourier form).
The mean mode ``k = 0`` has no steady state (a uniform flux heats a half-space without
bound, ``∝ √t``): it is removed, the mean surface temperature being the run's
(background) temperature. The FFT conventions and the wavevector grid are those of the
elastic kernel (:mod:`rubbercontact.halfspace.kernels`): periodic fields, the last axis is
the sliding direction ``x``.

Units: flux [mW/mm² = MPa·mm/s], conductivity [mW/(mm·K)], diffusivity [mm²/s], speed
[mm/s], temperature rise [K].
"""

from __future__ import annotations

import numpy as np

from .._validation import finite_array, positive_scalar
from ..errors import InputError
from ..halfspace.kernels import forward, inverse, wavevectors
from .properties import ThermalProperties

__all__ = ["thermal_admittance", "temperature_kernel", "surface_temperature",
           "subsurface_temperature", "rise_bound"]


def thermal_admittance(k, k_x, velocity: float, diffusivity: float) -> np.ndarray:
    """``λ = √(k² + i k_x v/D)`` [1/mm], the principal root (``Re λ ≥ 0``).

    ``k`` is the wavevector's magnitude and ``k_x`` its sliding component [1/mm];
    ``velocity`` [mm/s] the rubber's speed past the sources, ``diffusivity`` [mm²/s].
    """
    k = np.asarray(k, float)
    return np.sqrt(k**2 + 1j * np.asarray(k_x, float) * (velocity / diffusivity))


def temperature_kernel(shape: tuple[int, ...], lengths: tuple[float, ...], velocity: float,
                       thermal: ThermalProperties) -> np.ndarray:
    """``1/(K λ(k))`` [K·mm²/mW] on the rfft half-grid of :func:`wavevectors`, 0 at ``k = 0``."""
    qabs, qx = wavevectors(shape, lengths)
    lam = thermal_admittance(qabs, qx, velocity, thermal.diffusivity)
    out = np.zeros(qabs.shape, complex)
    nz = qabs > 0
    out[nz] = 1.0 / (thermal.conductivity_package * lam[nz])
    return out


def _lengths(q: np.ndarray, lengths) -> tuple[float, ...]:
    if np.ndim(lengths) == 0:
        side = positive_scalar("lengths", lengths, unit="mm")
        return (side,) if q.ndim == 1 else (side * q.shape[0] / q.shape[1], side)
    lens = tuple(positive_scalar("lengths", x, unit="mm") for x in lengths)
    if len(lens) != q.ndim:
        raise InputError(f"lengths: expected {q.ndim} period(s), got {len(lens)}")
    return lens


def _inputs(flux, lengths, velocity, thermal):
    q = finite_array("flux", flux, ndim=(1, 2), min_size=2)
    if isinstance(velocity, bool) or not np.isfinite(velocity):
        raise InputError(f"velocity: expected a finite number in mm/s, got {velocity!r}")
    return q, _lengths(q, lengths), float(velocity), thermal or ThermalProperties()


def subsurface_temperature(flux, lengths, velocity: float, depth: float,
                           thermal: ThermalProperties | None = None) -> np.ndarray:
    """Steady temperature rise [K] at ``depth`` [mm] ≥ 0 under the surface: each mode of
    :func:`surface_temperature` decays as ``e^{−λ z}`` (module docstring). The rubber a
    surface mode of wavenumber ``q`` deforms lies within ``~1/q`` of the surface; this is
    the temperature it has there. Other arguments as :func:`surface_temperature`."""
    q, lens, v, thermal = _inputs(flux, lengths, velocity, thermal)
    z = positive_scalar("depth", depth, allow_zero=True, unit="mm")
    qabs, qx = wavevectors(q.shape, lens)
    decay = np.exp(-thermal_admittance(qabs, qx, v, thermal.diffusivity) * z)
    kern = temperature_kernel(q.shape, lens, v, thermal) * decay
    return inverse(kern * forward(q), q.shape)


def surface_temperature(flux, lengths, velocity: float,
                        thermal: ThermalProperties | None = None) -> np.ndarray:
    """Steady surface temperature rise [K] of a periodic heat flux into the rubber.

    Parameters
    ----------
    flux
        Heat flux into the rubber ``Q`` [mW/mm²] on a periodic grid, shape ``(n,)`` or
        ``(ny, nx)``; ``x`` (the last axis) is the sliding direction.
    lengths
        Periods [mm]: one number (1D, or a square grid's side in 2D) or one per axis.
    velocity
        Speed [mm/s] of the rubber past the flux pattern (``+x``: the warm wake lies at
        larger ``x``); 0 is the stationary source.
    thermal
        :class:`ThermalProperties` (default: the filled-SBR compound).

    Returns
    -------
    numpy.ndarray
        ``T − T_background`` [K] on the grid; its mean over the period is 0 (module
        docstring: the mean flux heats the background, not the pattern).
    """
    q, lens, v, thermal = _inputs(flux, lengths, velocity, thermal)
    return inverse(temperature_kernel(q.shape, lens, v, thermal) * forward(q), q.shape)


def rise_bound(mean_flux: float, period: float, thermal: ThermalProperties | None = None,
               points: int = 2**24) -> float:
    """Upper bound [K] on the surface temperature rise, anywhere and at any speed, of a
    non-negative heat flux of mean ``mean_flux`` [mW/mm²] on a 1D periodic grid of
    ``period`` [mm] and at most ``points`` points.

    Each mode is ``Q̂_k/(K λ_k)`` with ``|λ_k| ≥ |k|`` (:func:`thermal_admittance`) and,
    for ``Q ≥ 0``, ``|Q̂_k| ≤ <Q>``; so ``|T| ≤ Σ_{k≠0} <Q>/(K|k|) = <Q> (L/πK) H_{N/2}
    ≤ <Q> (L/πK)(ln(N/2) + 1)`` (``H`` the harmonic number). A flash search whose bound is
    below its tolerance has its answer without a solve: no rise, the isothermal contact.
    """
    thermal = thermal or ThermalProperties()
    q = abs(float(mean_flux))
    length = positive_scalar("period", period, unit="mm")
    harmonic = np.log(max(int(points), 2) / 2.0) + 1.0
    return q * length / (np.pi * thermal.conductivity_package) * harmonic
