r"""Statistics of a height map: its 2D spectrum, slopes, anisotropy, and the mean-field PSD.

Spectrum convention (the mean-field theory's, :mod:`rubbercontact.meanfield.psd`): the map
is one period; with ``ẑ_k = FFT(z − <z>)/N`` (``N = nx·ny``) the mode ``k`` carries the
variance ``P_k = |ẑ_k|²`` [mm²] (two-sided: ``Σ_k P_k = <z²>``, Parseval) and the density is
``C(q_k) = P_k/(Δq_x Δq_y)`` [mm⁴] with ``Δq = 2π/L`` (the paper's eq. 11 on the lattice).

Slopes: ``<(∂z/∂x)²> = Σ q_x² P_k`` (rms slope along the sliding direction),
``<|∇z|²> = Σ |q|² P_k`` (rms gradient); for an isotropic surface the line-scan rms slope
is ``rms_gradient/√2``. The slope tensor ``<∇z ∇zᵀ>`` measures anisotropy: the ratio of its
eigenvalues' roots, ``sqrt(λ_max/λ_min)``, is 1 for an isotropic surface and grows with the
lay (infinite for a map uniform in one direction).

On a periodic map these are spectral (exact for a trigonometric polynomial, what the
half-space solver sees); on a non-periodic (measured) map the slopes are first differences
on the 2×2 blocks of measured points, centred in the block (the line-scan convention of
:func:`rubbercontact.roughness.rms_slope` along each axis; filled dropouts excluded, no
seam).
"""

from __future__ import annotations

import warnings
from typing import Literal

import numpy as np

from ..errors import InputError
from .fit import RoughnessWarning
from .maps import HeightMap

#: Anisotropy ``sqrt(λ_max/λ_min)`` of the slope tensor above which the isotropic
#: mean-field theory is warned about (a 1.5:1 slope ratio: the lay is clearly visible).
ANISOTROPY_WARN = 1.5
#: Off-axis spectral power (relative) under which a map counts as uniform in y (round-off).
_UNIFORM_RTOL = 1e-12


def _check(hmap) -> HeightMap:
    if not isinstance(hmap, HeightMap):
        raise InputError(f"map: expected a HeightMap, got {type(hmap).__name__}")
    return hmap


def mode_power(hmap: HeightMap) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(q_x, q_y, P)`` on the full FFT grid (numpy order), ``P_k = |ẑ_k|²`` [mm²]."""
    hmap = _check(hmap)
    ny, nx = hmap.shape
    z = hmap.heights
    zk = np.fft.fft2(z - z.mean()) / z.size
    qx = 2 * np.pi * np.fft.fftfreq(nx, hmap.dx)
    qy = 2 * np.pi * np.fft.fftfreq(ny, hmap.dy)
    qyy, qxx = np.meshgrid(qy, qx, indexing="ij")
    return qxx, qyy, np.abs(zk) ** 2


def spectrum_2d(hmap: HeightMap, window: Literal["none", "hann"] = "none"):
    """The 2D periodogram as an :class:`xarray.Dataset` (dims ``qy``, ``qx``, centred).

    Variables ``power`` ``P_k`` [mm²] and ``density`` ``C(q)`` [mm⁴] (module docstring).
    ``window="hann"``: the mean-removed map is multiplied by a 2D Hann window, rescaled to
    keep the variance (a spectrum estimate for a non-periodic map; the window's own slope
    at the edges leaks only into the lowest modes).
    """
    import xarray as xr

    hmap = _check(hmap)
    if window not in ("none", "hann"):
        raise InputError(f"window: expected 'none' or 'hann', got {window!r}")
    if window == "hann":
        z = hmap.heights - hmap.heights.mean()
        w = np.outer(np.hanning(hmap.shape[0] + 2)[1:-1], np.hanning(hmap.shape[1] + 2)[1:-1])
        z = z * w / np.sqrt(np.mean(w**2))
        hmap = hmap.replace(z, {"window": "hann"})
    qx, qy, p = mode_power(hmap)
    dq = (2 * np.pi / hmap.lengths[1]) * (2 * np.pi / hmap.lengths[0])
    p = np.fft.fftshift(p)
    return xr.Dataset(
        {"power": (("qy", "qx"), p, {"units": "mm^2", "long_name": "mode variance"}),
         "density": (("qy", "qx"), p / dq, {"units": "mm^4", "long_name": "PSD C(q)"})},
        coords={"qx": ("qx", np.fft.fftshift(qx[0]), {"units": "rad/mm"}),
                "qy": ("qy", np.fft.fftshift(qy[:, 0]), {"units": "rad/mm"})},
        attrs={"window": window, "periodic": int(hmap.periodic)})


def slope_tensor(hmap: HeightMap) -> np.ndarray:
    """``[[<z_x²>, <z_x z_y>], [<z_x z_y>, <z_y²>]]`` [-] (module docstring for how)."""
    hmap = _check(hmap)
    if hmap.periodic:
        qx, qy, p = mode_power(hmap)
        return np.array([[np.sum(qx * qx * p), np.sum(qx * qy * p)],
                         [np.sum(qx * qy * p), np.sum(qy * qy * p)]])
    z, m = hmap.heights, hmap.measured
    # forward differences at the cell centres of each 2x2 block whose corners are measured
    ok = m[:-1, :-1] & m[1:, :-1] & m[:-1, 1:] & m[1:, 1:]
    if not ok.any():
        raise InputError("map: no 2x2 block of measured points to take slopes on")
    zx = 0.5 * (z[:-1, 1:] - z[:-1, :-1] + z[1:, 1:] - z[1:, :-1])[ok] / hmap.dx
    zy = 0.5 * (z[1:, :-1] - z[:-1, :-1] + z[1:, 1:] - z[:-1, 1:])[ok] / hmap.dy
    return np.array([[np.mean(zx * zx), np.mean(zx * zy)], [np.mean(zx * zy), np.mean(zy * zy)]])


def rms_slope_x(hmap: HeightMap) -> float:
    """rms slope along the sliding direction ``sqrt(<(∂z/∂x)²>)`` [-]."""
    return float(np.sqrt(slope_tensor(hmap)[0, 0]))


def rms_gradient(hmap: HeightMap) -> float:
    """rms gradient ``sqrt(<|∇z|²>)`` [-]."""
    return float(np.sqrt(np.trace(slope_tensor(hmap))))


def rms_height(hmap: HeightMap) -> float:
    """rms height about the mean of the measured points [mm]."""
    z = _check(hmap).heights[hmap.measured]
    return float(np.sqrt(np.mean((z - z.mean()) ** 2)))


def anisotropy(hmap: HeightMap) -> tuple[float, float]:
    """``(ratio, angle)``: ``sqrt(λ_max/λ_min)`` of the slope tensor [-] (inf when one
    direction is flat) and the direction of steepest rms slope from the x axis [rad]."""
    lam, vec = np.linalg.eigh(slope_tensor(hmap))
    ratio = float(np.sqrt(lam[1] / lam[0])) if lam[0] > 1e-14 * lam[1] else float("inf")
    angle = float(np.arctan2(vec[1, 1], vec[0, 1]))
    return ratio, float(np.mod(angle + np.pi / 2, np.pi) - np.pi / 2)


def map_psd(hmap: HeightMap, nodes_per_decade: int | None = 32):
    """The spectrum the mean-field theory reads (:class:`rubbercontact.meanfield.PSD`).

    A map uniform in ``y`` (all its power on ``q_y = 0``) is a profile extruded along y:
    its plane-strain (1D) spectrum, from its rows, so that the mean-field answer per unit
    width is the profile's. Any other map: the radially pooled 2D periodogram
    (:meth:`PSD.from_map`), which assumes isotropy — a :class:`RoughnessWarning` says so when
    the slope anisotropy exceeds :data:`ANISOTROPY_WARN`. The map should be periodic
    (:meth:`HeightMap.periodized`), else its seams leak into the spectrum.
    ``nodes_per_decade``: pooling of the harmonics (32, the PSD's default; ``None`` keeps
    every harmonic).
    """
    from ..meanfield.psd import PSD

    hmap = _check(hmap)
    qx, qy, p = mode_power(hmap)
    if np.sum(p[qy != 0]) <= _UNIFORM_RTOL * np.sum(p):
        one = PSD.from_profiles(hmap.heights, hmap.dx, nodes_per_decade=nodes_per_decade)
        keep = one.variances > 1e-15 * one.variances.sum()   # round-off harmonics dropped
        return PSD(one.wavenumbers[keep], one.variances[keep], 1,
                   source=f"{one.source}, a map uniform in y")
    ratio, angle = anisotropy(hmap)
    if ratio > ANISOTROPY_WARN:
        warnings.warn(f"map: slope anisotropy {ratio:.3g} (steepest at {np.degrees(angle):.0f}° "
                      f"from x); the mean-field theory averages it as isotropic",
                      RoughnessWarning, stacklevel=2)
    return PSD.from_map(hmap.heights, hmap.lengths, nodes_per_decade=nodes_per_decade)
