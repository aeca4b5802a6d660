r"""A 1D contact by wavenumber band: the BEM's pressure and the strip cascade's.

In 1D steady sliding the friction stress is exactly

.. math:: μσ_0 = \sum_k \operatorname{var}σ_k \, (−2\,\mathrm{Im}[1/E_r(kv)]),

the pressure variance of each Fourier mode ``k`` of the periodic pressure times the loss at
its frequency ``kv``. :func:`pressure_power` and :func:`band_power` split a half-space
(BEM) pressure that way, :func:`strip_bands` the strip cascade's
(:func:`~rubbercontact.meanfield.strips.strip_contact`) friction or pressure variance, band
by band, so the two can be compared where the cascade's friction goes wrong
(docs/validation/meanfield.md, ``studies/meanfield.py`` part ``bands``);
:func:`contact_patches` gives the widths of the BEM's contact intervals.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from .._validation import positive_scalar
from ..errors import InputError
from ..materials.protocol import Material
from ..roughness.protocol import WaveProfile, check_waves
from .strips import strip_contact

__all__ = ["band_power", "contact_patches", "pressure_power", "strip_bands"]


def pressure_power(pressure: np.ndarray, period: float) -> tuple[np.ndarray, np.ndarray]:
    """Each one-sided Fourier mode of a periodic 1D pressure and its variance.

    Parameters
    ----------
    pressure
        Pressure [MPa] on ``n`` equal steps of one period.
    period
        The period [mm].

    Returns
    -------
    k : ndarray
        Wavenumbers ``2πj/period`` [rad/mm], ``j = 0 … n//2``.
    power : ndarray
        The variance [MPa²] each mode carries (``2|p̂_j|²``, once at the Nyquist mode of an
        even ``n``); the mean (``k = 0``) carries none, so ``power.sum()`` is the
        pressure's variance.
    """
    pressure = np.asarray(pressure, float)
    period = positive_scalar("period", period, unit="mm")
    n = pressure.size
    sk = np.fft.rfft(pressure) / n
    k = 2 * np.pi * np.arange(sk.size) / period
    power = np.where(k > 0, 2 * np.abs(sk) ** 2, 0.0)
    if n % 2 == 0:
        power[-1] /= 2                                       # Nyquist has no twin
    return k, power


def band_power(solves: Sequence, period: float, edges: np.ndarray,
               weight: Callable[[np.ndarray], np.ndarray] | None = None) -> np.ndarray:
    """The pressure variance [MPa²] in each band of ``edges``, averaged over the solves.

    Parameters
    ----------
    solves
        Pressures [MPa] of one period each: arrays, or results with a ``pressure`` array
        (:func:`rubbercontact.halfspace.solve_sliding`'s).
    period
        The period [mm].
    edges
        Band edges [rad/mm], ascending (``0`` and ``inf`` allowed); band ``b`` holds
        ``edges[b] <= k < edges[b + 1]``.
    weight
        Optional ``weight(k)`` multiplying each mode's variance (the loss
        ``−2 Im[1/E_r(kv)]`` [1/MPa] gives each band's friction stress [MPa]).

    Returns
    -------
    ndarray of shape ``(len(edges) − 1,)``.
    """
    edges = np.asarray(edges, float)
    if edges.ndim != 1 or edges.size < 2 or np.any(np.diff(edges) <= 0):
        raise InputError("edges: need at least 2 ascending band edges [rad/mm]")
    if len(solves) == 0:
        raise InputError("solves: no pressure to split")
    out = np.zeros(edges.size - 1)
    for res in solves:
        k, power = pressure_power(getattr(res, "pressure", res), period)
        w = power if weight is None else power * weight(k)
        out += np.bincount(np.digitize(k, edges) - 1, w, edges.size - 1) / len(solves)
    return out


def contact_patches(pressure: np.ndarray, period: float) -> np.ndarray:
    """Widths [mm] of the contact intervals (``pressure > 0``) of a periodic 1D pressure on
    ``n`` equal steps of ``period`` [mm]; an interval across the period's edge is one."""
    c = np.asarray(pressure) > 0
    if c.all() or not c.any():
        return np.array([period]) if c.all() else np.array([])
    c = np.roll(c, -int(np.argmin(c)))                  # start in a gap: no wrapped patch
    edges = np.flatnonzero(np.diff(np.append(c, False).astype(int)))
    return (edges[1::2] - edges[::2]) * period / c.size


def strip_bands(surface: WaveProfile, material: Material, velocity: float,
                mean_pressure: float, edges: np.ndarray, *, unit: bool = False,
                nu: float = 0.5) -> np.ndarray:
    """The strip cascade's friction, or its pressure variance, in each wavenumber band.

    The cascade is solved once per band with the loss kept only at the frequencies
    ``ω = kv`` of the band's wavenumbers ``edges[b] <= k < edges[b + 1]`` (and set to 1
    there with ``unit``). Its geometry reads ``|E_r|`` only and is the same in every
    solve, and its friction is linear in the loss, so the bands add up to the cascade's
    friction (to its pressure variance with ``unit``) up to the log interpolation of its
    width-loss table, which a band's edge cuts (+0.1 % at 1 mm/s, +0.7 % at 500 mm/s on
    ``random_ladder(8, 3)`` at 0.4 MPa).

    Parameters
    ----------
    surface
        A sine series, or any profile declaring its waves
        (:class:`~rubbercontact.roughness.WaveProfile`: the cascade's waves; phases play no
        part).
    material
        The rubber (:class:`~rubbercontact.materials.Material`).
    velocity
        Sliding speed [mm/s], != 0.
    mean_pressure
        ``σ0`` [MPa].
    edges
        Band edges [rad/mm], ascending.
    unit
        False: friction coefficient per band [-]; True: pressure variance per band [MPa²].
    nu
        Poisson's ratio.

    Returns
    -------
    ndarray of shape ``(len(edges) − 1,)``.
    """
    check_waves(surface, needs="the strip bands")
    p = positive_scalar("mean_pressure", mean_pressure, unit="MPa")
    speed = abs(float(velocity))
    if not speed > 0:
        raise InputError(f"velocity: the bands are frequencies kv, need v != 0, got {velocity}")
    edges = np.asarray(edges, float)
    if edges.ndim != 1 or edges.size < 2 or np.any(np.diff(edges) <= 0):
        raise InputError("edges: need at least 2 ascending band edges [rad/mm]")
    out = []
    for lo, hi in zip(edges[:-1], edges[1:], strict=True):
        def inside(omega, loss, lo=lo, hi=hi):
            band = (omega >= lo * speed) & (omega < hi * speed)
            return (1.0 if unit else loss) * band

        res = strip_contact(surface.wavenumbers, surface.amplitudes, material, velocity, p,
                            nu=nu, loss_filter=inside)
        out.append(float(res.friction_stress.sum()) / (1.0 if unit else p))
    return np.array(out)
