"""A sine profile with its crests rounded to a radius: the law cell of a measured road.

A steep band of sines has crests far sharper than its waves: a sine of wavelength ``λ``
and peak slope ``S = qΔ`` has the crest radius ``λ/(2π S)``, on a measured road's steep
band often below the profile's sampling interval. Nothing measured says the road is that
sharp there: below its sampling interval (and the
instrument's spot or stylus tip) a profile does not resolve a crest. The FEM cell, on the
other hand, follows such a crest, and pressed above a fraction of ``E∞`` the rubber
wrapping it is crushed until Newton stops (docs/validation/steep_cells.md).

:func:`round_crests` gives the surface a stylus of tip radius ``r`` would trace: the
morphological opening of the solid below the profile by a disk of radius ``r`` (the
union of all such disks that fit under it). Crests sharper than ``r`` become arcs of
radius ``r``; flanks and valleys, and crests already blunter than ``r``, are unchanged,
and the surface is only ever lowered. The opening leaves a jump of curvature where an
arc meets the profile; the lowering is smoothed over ``r/8`` (a Gaussian, which keeps it
<= 0) so that the surface is smooth for the FEM's closest-point Newton and is held
exactly by a short Fourier series on the cell.

The result keeps the band's waves as its own (``wavelengths``, ``amplitudes``): they
set the FEM mesh (columns per shortest wave) and bound its slope ``Σ q_i Δ_i`` and
curvature ``Σ q_i² Δ_i`` — the rounding lowers crests and lessens their curvature, so
the bounds still hold (the slope's to the smoothing's few parts in a thousand).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.ndimage import gaussian_filter1d, grey_opening

from .._validation import positive_scalar
from .sines import SineSeries

__all__ = ["RoundedCrests", "round_crests", "opening_lowering"]

#: Grid points per crest radius of the opening (its height error is below
#: ``(1 + S²)^(3/2) dx² / (2 r)``, with ``S`` the steepest slope: 1e-3 r at S = 3).
POINTS_PER_RADIUS = 128
#: Width of the Gaussian that smooths the lowering, as a fraction of the radius.
SMOOTHING = 0.125
#: Round-off of the opening's ``z - cap + cap``, relative to the profile's range.
ROUND_OFF = 1e-12
#: Harmonics of the lowering are kept down to this fraction of its largest one.
HARMONIC_TOL = 1e-7


@dataclass(frozen=True, eq=False)
class RoundedCrests:
    """A :class:`SineSeries` band with crests rounded to ``radius`` (:func:`round_crests`).

    Attributes
    ----------
    band
        The sine band as fitted [mm].
    radius
        Smallest crest radius ``r`` [mm] (the opening disk's).
    lowering
        What the rounding takes off the band, less its mean: a series of the cell's
        harmonics.
    offset
        The lowering's mean [mm] (``≤ 0``): the band's mean plane stays the reference of
        heights and separations, as the hybrid's ``z = z_ls + z_hs`` has it.
    """

    band: SineSeries
    radius: float
    lowering: SineSeries
    offset: float = 0.0

    dimension = 1

    # -- the band's waves: the mesh rules and the slope/curvature bounds -------------------
    @property
    def wavelengths(self) -> np.ndarray:
        return self.band.wavelengths

    @property
    def amplitudes(self) -> np.ndarray:
        return self.band.amplitudes

    @property
    def wavenumbers(self) -> np.ndarray:
        return self.band.wavenumbers

    @property
    def period(self) -> float:
        return self.band.period

    # -- the rounded profile ------------------------------------------------------------------
    def heights(self, x) -> np.ndarray:
        """``z(x)`` [mm]."""
        return self.band.heights(x) + self.lowering.heights(x) + self.offset

    def slopes(self, x) -> np.ndarray:
        """``dz/dx`` [-]."""
        return self.band.slopes(x) + self.lowering.slopes(x)

    def curvatures(self, x) -> np.ndarray:
        """``d²z/dx²`` [1/mm]."""
        return self.band.curvatures(x) + self.lowering.curvatures(x)

    def as_dict(self) -> dict:
        """The band and the radius (the lowering follows from them)."""
        return {**self.band.as_dict(), "crest_radius": self.radius}

    def __repr__(self) -> str:
        return f"RoundedCrests({self.band!r}, radius={self.radius:g} mm)"


def opening_lowering(z: np.ndarray, dx: float, radius: float) -> np.ndarray:
    """The morphological opening of a periodic profile's subgraph by a disk, minus the
    profile (``≤ 0``: what the opening takes off).

    Parameters
    ----------
    z
        Heights [mm] on a periodic grid of step ``dx`` [mm].
    radius
        The disk's radius [mm].
    """
    m = int(np.ceil(radius / dx))
    t = np.arange(-m, m + 1) * dx
    cap = np.sqrt(np.maximum(radius * radius - t * t, 0.0))
    # erosion by the disk's upper cap, then dilation by it: only disks that fit under
    # the profile survive, and their union's top is the opened profile
    opened = grey_opening(z, structure=cap, mode="wrap")
    low = np.minimum(opened - z, 0.0)
    # where the disk rolled on the profile what is left is the grid's error of a disk
    # sampled every dx, up to (1 + S²)^(3/2) dx² / (2r) on a flank of slope S, and round-off
    steepest = float(np.max(np.abs(np.diff(z)))) / dx
    resolved = max((1 + steepest**2) ** 1.5 * dx**2 / (2 * radius),
                   ROUND_OFF * float(np.ptp(z)))
    low[low > -resolved] = 0.0
    return low


def round_crests(band: SineSeries, radius: float) -> RoundedCrests:
    """``band`` with every crest sharper than ``radius`` rounded to it.

    Parameters
    ----------
    band
        A periodic sine profile (the cell's high-slope band) [mm].
    radius
        Crest radius ``r`` [mm] > 0, e.g. the sampling interval of the measured profile.
    """
    radius = positive_scalar("crest_radius", radius, unit="mm")
    period = band.period
    n = 2 ** int(np.ceil(np.log2(max(POINTS_PER_RADIUS * period / radius, 1024))))
    dx = period / n
    z = band.heights(np.arange(n) * dx)
    low = gaussian_filter1d(opening_lowering(z, dx, radius), SMOOTHING * radius / dx,
                            mode="wrap")
    return RoundedCrests(band, float(radius), _harmonics(low, period), float(np.mean(low)))


def _harmonics(low: np.ndarray, period: float) -> SineSeries:
    """``low`` (periodic) less its mean as a sine series of the period's harmonics."""
    c = np.fft.rfft(low) / low.size
    amp = 2.0 * np.abs(c[1:])
    if not amp.size or amp.max() == 0.0:
        return SineSeries(np.array([]), np.array([]))
    h = np.flatnonzero(amp > HARMONIC_TOL * amp.max()) + 1
    # c_h e^{iqx} + c.c. = 2|c_h| cos(qx + arg c_h) = 2|c_h| sin(qx + arg c_h + π/2)
    return SineSeries(period / h, amp[h - 1], np.angle(c[h]) + np.pi / 2)
