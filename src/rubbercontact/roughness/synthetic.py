"""Synthetic line scans of a sine-series surface: the built-in default data set.

The paper (section 4.1) measured 30 line scans of 16 mm at 0.05 mm resolution on
an AC-8 asphalt and fitted the 8 waves of Table 2 to their mean HDC. Its scans are
not published; :func:`synthetic_line_scans` makes their stand-in from Table 2
itself, finer sampled (0.005 mm, so that the 0.0625 mm wave has 12.5 points per
wavelength), each scan with its own random phases and additive white noise.
"""

from __future__ import annotations

import numpy as np

from .._validation import positive_scalar
from ..errors import InputError
from .sines import SineSeries

#: Default white-noise standard deviation [mm] (0.5 µm, a confocal profilometer's level).
DEFAULT_NOISE = 0.0005


def synthetic_line_scans(series: SineSeries | None = None, n_scans: int = 30,
                         length: float = 16.0, dx: float = 0.005,
                         noise: float = DEFAULT_NOISE, seed: int | None = 0) -> np.ndarray:
    """Line scans of ``series`` with random phases and noise, one scan per row [mm].

    Parameters
    ----------
    series
        The surface; default Table 2 (:func:`~rubbercontact.roughness.asphalt_ac8`).
    n_scans
        Number of scans; each gets independent phases ``φ_i ~ U(0, 2π)``.
    length, dx
        Scan length and sampling step [mm]; each scan has ``round(length/dx)`` points at
        ``x = 0, dx, …`` (with the defaults 3200 points spanning exactly two periods of
        the 8 mm wave).
    noise
        Standard deviation [mm] of independent Gaussian noise added to every height
        (0 for exact samples). White noise adds ``2·noise²`` to the HDC at every lag.
    seed
        Seed of the random generator (phases, then noise); ``None`` for fresh entropy.

    Returns
    -------
    ndarray of shape ``(n_scans, round(length/dx))``.
    """
    if series is None:
        from .presets import asphalt_ac8

        series = asphalt_ac8()
    if not isinstance(series, SineSeries):
        raise InputError(f"series: expected a SineSeries, got {type(series).__name__}")
    if isinstance(n_scans, bool) or int(n_scans) != n_scans or n_scans < 1:
        raise InputError(f"n_scans: must be a positive integer, got {n_scans!r}")
    length = positive_scalar("length", length, unit="mm")
    dx = positive_scalar("dx", dx, unit="mm")
    noise = positive_scalar("noise", noise, allow_zero=True, unit="mm")
    n = int(round(length / dx))
    if n < 2:
        raise InputError(f"length: {length} mm holds fewer than 2 samples at dx = {dx} mm")
    rng = np.random.default_rng(seed)
    x = np.arange(n) * dx
    phases = rng.uniform(0.0, 2 * np.pi, size=(int(n_scans), series.size))
    arg = x[None, :, None] * series.wavenumbers + phases[:, None, :]
    z = np.einsum("snw,w->sn", np.sin(arg), series.amplitudes)
    if noise > 0:
        z += rng.normal(0.0, noise, size=z.shape)
    return z
