"""Synthetic 1D surfaces: line scans of a sine series (the built-in default data set), a
random octave ladder of sines and a random-phase self-affine profile (test surfaces of the
mean-field and half-space checks and of their studies).

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


def random_ladder(waves: int, seed: int, longest: float = 8.0) -> SineSeries:
    """An octave ladder of sine waves with random slopes.

    Wavelengths ``λ_i = longest / 2^i`` [mm] (``i = 0 … waves − 1``), each wave's rms slope
    ``m2_i ~ U(0.1, 0.6)`` (drawn in order from ``numpy.random.default_rng(seed)``), so its
    amplitude is ``Δ_i = m2_i √2 λ_i / (2π)`` [mm]; phases zero.

    Parameters
    ----------
    waves
        Number of waves, >= 1.
    seed
        Seed of the slopes.
    longest
        Longest wavelength [mm] (the period).
    """
    if isinstance(waves, bool) or int(waves) != waves or waves < 1:
        raise InputError(f"waves: must be a positive integer, got {waves!r}")
    longest = positive_scalar("longest", longest, unit="mm")
    rng = np.random.default_rng(seed)
    lam = longest / 2.0 ** np.arange(int(waves))
    m2 = rng.uniform(0.1, 0.6, int(waves))
    return SineSeries(lam, m2 * np.sqrt(2) * lam / (2 * np.pi))


def self_affine_profile(*, n: int, length: float, lam_min: float, hurst: float,
                        rolloff: int, slope: float, seed: int | None):
    """A random-phase periodic profile with a self-affine spectrum, and its exact spectrum.

    Harmonics ``k = 1 … K``, ``K = round(length/lam_min)``, of the period; the variance of
    harmonic ``k`` is ∝ 1 below the roll-off harmonic and ∝ ``(k/rolloff)^−(1+2H)`` from it
    on (the 1D ``C1`` of :mod:`rubbercontact.meanfield.psd`), scaled to the rms slope
    exactly; uniform random phases. The spectrum is the same for every seed.

    Parameters
    ----------
    n
        Points of the profile over one period, >= 4 per shortest wavelength (``4K``).
    length
        Period [mm].
    lam_min
        Shortest wavelength [mm].
    hurst
        Hurst exponent ``H`` [-], > 0.
    rolloff
        Harmonic of the roll-off, >= 1.
    slope
        Rms slope ``sqrt(<z'²>)`` [-].
    seed
        Seed of the phases (``None``: fresh entropy).

    Returns
    -------
    z : ndarray of shape ``(n,)``
        Heights [mm] at ``x = i·length/n``, zero mean.
    psd : rubbercontact.meanfield.PSD
        The exact 1D spectrum: nodes ``q_k = 2πk/length`` [rad/mm] with the variances
        ``v_k`` [mm²], ``Σ q_k² v_k = slope²``.
    """
    from ..meanfield.psd import PSD

    length = positive_scalar("length", length, unit="mm")
    lam_min = positive_scalar("lam_min", lam_min, unit="mm")
    hurst = positive_scalar("hurst", hurst)
    slope = positive_scalar("slope", slope)
    kmax = int(round(length / lam_min))
    if kmax < 1:
        raise InputError(f"lam_min: {lam_min} mm is longer than the period {length} mm")
    if isinstance(rolloff, bool) or int(rolloff) != rolloff or rolloff < 1:
        raise InputError(f"rolloff: must be a positive integer harmonic, got {rolloff!r}")
    if isinstance(n, bool) or int(n) != n or n < 4 * kmax:
        raise InputError(f"n: {n!r} points give fewer than 4 per shortest wavelength "
                         f"(need n >= {4 * kmax})")
    n = int(n)
    k = np.arange(1, kmax + 1)
    q = 2 * np.pi * k / length
    c = np.where(k < rolloff, 1.0, (k / rolloff) ** (-(1 + 2 * hurst)))
    var = c * slope**2 / np.sum(q**2 * c)
    phases = np.random.default_rng(seed).uniform(0.0, 2 * np.pi, kmax)
    # one-sided FFT coefficients of amplitude sqrt(2 var) per harmonic (irfft's 1/n undone)
    spec = np.zeros(n // 2 + 1, complex)
    spec[1:kmax + 1] = np.sqrt(var / 2) * np.exp(1j * phases) * n
    z = np.fft.irfft(spec, n)
    return z, PSD(q, var, 1, source=f"self-affine profile H={hurst:g}, {kmax} harmonics")
