"""Statistics of measured line scans: HDC, PSD, rms height and rms slope.

Every function takes *profiles* in one of these forms:

- one 1D array of heights [mm];
- a 2D array, one line scan per row;
- a sequence of 1D arrays (line scans of possibly different lengths);
- a :class:`rubbercontact.io.Profiles` (its ``dx`` is used when ``dx`` is not given).

All scans share one sampling step ``dx`` [mm]. Scans must be free of NaN: cut
them into gap-free windows or interpolate the gaps when reading (see
:func:`rubbercontact.io.read_profiles`).

Averaging over many scans pools the *pairs of points* (or the points) of all scans,
so that a long scan weighs more than a short one; for scans of equal length this is
the plain average of the scans' statistics.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Literal

import numpy as np

from .._validation import positive_scalar
from ..errors import InputError

Detrend = Literal["none", "mean", "linear"]
_DETREND_MODES = ("none", "mean", "linear")


# -- input handling -------------------------------------------------------------------------
def as_profile_list(profiles, *, name: str = "profiles", min_points: int = 2,
                    allow_nan: bool = False) -> list[np.ndarray]:
    """Return ``profiles`` as a list of finite 1D float arrays, or raise :class:`InputError`.

    The error names the offending scan (``profiles[3]``) and what is wrong with it.
    ``allow_nan`` lets NaN (dropouts) through; infinities are always refused.
    """
    if hasattr(profiles, "profiles") and hasattr(profiles, "dx"):  # io.Profiles
        profiles = profiles.profiles
    single = False
    if isinstance(profiles, np.ndarray) or (
            isinstance(profiles, Sequence) and len(profiles) and np.isscalar(profiles[0])):
        try:
            arr = np.asarray(profiles, dtype=float)
        except (TypeError, ValueError) as exc:
            raise InputError(f"{name}: cannot be read as numbers ({exc})") from None
        if arr.ndim == 1:
            items, single = [arr], True
        elif arr.ndim == 2:
            items = list(arr)
        else:
            raise InputError(f"{name}: expected a 1D profile or a 2D array (one scan per row), "
                             f"got shape {arr.shape}")
    elif isinstance(profiles, Sequence):
        items = list(profiles)
    else:
        raise InputError(f"{name}: expected an array of heights or a list of arrays, "
                         f"got {type(profiles).__name__}")
    if not items:
        raise InputError(f"{name}: no profile given (empty list)")
    out = []
    for i, item in enumerate(items):
        label = name if single else f"{name}[{i}]"
        try:
            z = np.asarray(item, dtype=float)
        except (TypeError, ValueError) as exc:
            raise InputError(f"{label}: cannot be read as numbers ({exc})") from None
        if z.ndim != 1:
            raise InputError(f"{label}: expected a 1D profile, got shape {z.shape}")
        if z.size == 0:
            raise InputError(f"{label}: empty profile (no height values)")
        if z.size < min_points:
            raise InputError(f"{label}: needs at least {min_points} points, got {z.size}")
        bad = np.isinf(z) if allow_nan else ~np.isfinite(z)
        if allow_nan and np.isnan(z).all():
            raise InputError(f"{label}: empty profile (every height is NaN)")
        if bad.any():
            raise InputError(
                f"{label}: contains NaN or infinite heights ({int(bad.sum())} of {z.size}, "
                f"first at index {int(np.argmax(bad))}); cut the scan into gap-free windows "
                f"or interpolate the gaps (rubbercontact.io.read_profiles(nan=...))")
        out.append(z)
    return out


def _unpack(profiles, dx, *, min_points: int = 2, allow_nan: bool = False
            ) -> tuple[list[np.ndarray], float]:
    if dx is None:
        if hasattr(profiles, "profiles") and hasattr(profiles, "dx"):
            dx = profiles.dx
        else:
            raise InputError("dx: the sampling step [mm] is required for plain arrays")
    dx = positive_scalar("dx", dx, unit="mm")
    return as_profile_list(profiles, min_points=min_points, allow_nan=allow_nan), dx


def _check_detrend(mode: str) -> str:
    if mode not in _DETREND_MODES:
        raise InputError(f"detrend: expected one of {', '.join(_DETREND_MODES)}, got {mode!r}")
    return mode


def detrend(z, mode: Detrend = "mean") -> np.ndarray:
    """Remove nothing (``"none"``), the mean (``"mean"``) or a least-squares line
    (``"linear"``) from each row of ``z`` (1D or 2D array)."""
    _check_detrend(mode)
    z = np.asarray(z, dtype=float)
    if mode == "none":
        return z.copy()
    # NaN (dropouts) are ignored by the fits and stay NaN.
    ok = np.isfinite(z)
    cnt = np.maximum(ok.sum(axis=-1, keepdims=True), 1)
    zf = np.where(ok, z, 0.0)
    mean = zf.sum(axis=-1, keepdims=True) / cnt
    if mode == "mean":
        return z - mean
    t = np.broadcast_to(np.arange(z.shape[-1], dtype=float), z.shape)
    tm = np.where(ok, t, 0.0).sum(axis=-1, keepdims=True) / cnt
    tc = np.where(ok, t - tm, 0.0)  # centred abscissa: slope and mean decouple
    denom = (tc * tc).sum(axis=-1, keepdims=True)
    slope = (tc * (zf - mean)).sum(axis=-1, keepdims=True) / np.where(denom > 0, denom, 1)
    return z - mean - slope * (t - tm)


def _groups(profiles: list[np.ndarray], mode: str) -> list[np.ndarray]:
    """Detrended scans stacked into 2D arrays, one per distinct length (for batch FFTs)."""
    lengths = sorted({z.size for z in profiles})
    return [detrend(np.stack([z for z in profiles if z.size == n]), mode) for n in lengths]


# -- height-difference correlation ----------------------------------------------------------
def _hdc_sums(block: np.ndarray, kmax: int, periodic: bool) -> tuple[np.ndarray, np.ndarray]:
    """Sum over the scans (rows) of ``Σ_n (z[n+k] − z[n])²`` and the number of pairs, k ≤ kmax.

    Autocorrelation sums by FFT: ``A(k) = Σ_n z[n] z[n+k]``, zero-padded to 2N for the
    non-periodic (linear) case, so the cost is O(N log N) per scan for all lags at once.
    """
    n_scans, n = block.shape
    k = np.arange(kmax + 1)
    # Differences do not depend on the mean: removing it keeps the sums below well scaled.
    z = detrend(block, "mean")
    if np.isnan(z).any():
        return _masked_hdc_sums(z, kmax)
    if periodic:
        spec = np.fft.rfft(z, axis=1)
        acf = np.fft.irfft(np.abs(spec) ** 2, n=n, axis=1).sum(axis=0)
        sq = float(np.sum(z * z))
        num = 2 * (sq - acf[np.mod(k, n)])
        pairs = np.full(k.shape, float(n_scans * n))
        return num, pairs
    nfft = 1 << int(np.ceil(np.log2(2 * n)))
    spec = np.fft.rfft(z, n=nfft, axis=1)
    acf = np.fft.irfft(np.abs(spec) ** 2, n=nfft, axis=1)[:, : n].sum(axis=0)
    csum = np.concatenate([[0.0], np.cumsum(np.sum(z * z, axis=0))])  # csum[m] = Σ_{n<m} z²
    num = np.zeros(kmax + 1)
    pairs = np.zeros(kmax + 1)
    valid = k < n
    kv = k[valid]
    head = csum[n - kv]                 # Σ_{n < N−k} z[n]²
    tail = csum[n] - csum[kv]           # Σ_{n ≥ k} z[n]²
    num[valid] = head + tail - 2 * acf[kv]
    pairs[valid] = n_scans * (n - kv)
    return num, pairs


def _masked_hdc_sums(z: np.ndarray, kmax: int) -> tuple[np.ndarray, np.ndarray]:
    """Non-periodic sums over the pairs whose both ends are finite (NaN = dropout).

    ``Σ m_n m_{n+k} (z_{n+k} − z_n)²`` with the mask ``m`` is a sum of three
    cross-correlations, each one FFT product: O(N log N) as without gaps.
    """
    n = z.shape[1]
    m = np.isfinite(z).astype(float)
    zf = np.where(m > 0, z, 0.0)
    nfft = 1 << int(np.ceil(np.log2(2 * n)))
    fm, fz, fz2 = (np.fft.rfft(a, n=nfft, axis=1) for a in (m, zf, zf * zf))

    def corr(fa, fb):  # Σ_n a_n b_{n+k}, k = 0 … n−1, summed over scans
        return np.fft.irfft(np.conj(fa) * fb, n=nfft, axis=1)[:, :n].sum(axis=0)

    num_all = corr(fm, fz2) + corr(fz2, fm) - 2 * corr(fz, fz)
    pairs_all = np.rint(corr(fm, fm))
    num = np.zeros(kmax + 1)
    pairs = np.zeros(kmax + 1)
    top = min(kmax, n - 1)
    num[: top + 1] = num_all[: top + 1]
    pairs[: top + 1] = pairs_all[: top + 1]
    return num, pairs


def hdc(profiles, dx: float | None = None, lags=None, *, periodic: bool = False,
        detrend: Detrend = "none", max_lag: float | None = None, nan: str = "error"
        ) -> tuple[np.ndarray, np.ndarray]:
    """Height-difference correlation ``R_zz(λ) = <(z(x+λ) − z(x))²>`` [mm²] (paper eq. 9).

    No factor 1/2 (the paper's convention: one sine of amplitude ``Δ`` has
    ``R_zz(λ) = 2Δ² sin²(qλ/2)``, plateau ``2Δ²``).

    Parameters
    ----------
    profiles, dx
        Line scans and their sampling step [mm] (see the module docstring).
    lags
        Lags ``λ`` [mm]; each is rounded to the nearest multiple ``k·dx`` (the lags
        actually used are returned). Default: every ``k·dx`` for ``k = 1 … max_lag/dx``.
    periodic
        ``False`` (default, for measured scans): the non-periodic estimator, the mean of
        ``(z[n+k] − z[n])²`` over the ``N − k`` overlapping pairs inside each scan, pooled
        over all scans. ``True``: each scan is taken as one period of a periodic profile
        (pairs wrap around, ``N`` pairs at every lag) — exact for synthetic scans that
        span whole periods, biased for measured scans (the wrap-around jump).
    detrend
        ``"none"`` (default; the HDC ignores the mean anyway), ``"mean"`` or ``"linear"``
        (a least-squares line removed from each scan first).
    max_lag
        Largest default lag [mm]; default half the longest scan (the periodic case; the
        HDC is symmetric about it) or the longest scan minus one step (non-periodic).
    nan
        ``"error"`` (default): NaN heights raise :class:`InputError`. ``"omit"``: NaN are
        dropouts and only pairs with both ends finite count (non-periodic only) — the
        whole scan is used, no height is invented (the masked estimator; SurfaceTopography's
        ``autocorrelation_from_profile`` of masked data gives the same, as ``R_zz/2``).

    Returns
    -------
    lags, R
        Lags used [mm] (``k·dx``) and ``R_zz`` at those lags [mm²].
    """
    if nan not in ("error", "omit"):
        raise InputError(f"nan: expected 'error' or 'omit', got {nan!r}")
    if nan == "omit" and periodic:
        raise InputError("nan: 'omit' needs the non-periodic estimator (periodic=False)")
    z, dx = _unpack(profiles, dx, allow_nan=nan == "omit")
    _check_detrend(detrend)
    nmax = max(p.size for p in z)
    klimit = nmax - 1
    if lags is None:
        if max_lag is None:
            kmax = nmax // 2 if periodic else klimit
        else:
            kmax = int(np.floor(positive_scalar("max_lag", max_lag, unit="mm") / dx + 1e-9))
            if kmax < 1 or kmax > klimit:
                raise InputError(f"max_lag: must lie between dx = {dx} mm and "
                                 f"{klimit * dx:g} mm for these scans, got {max_lag}")
        k = np.arange(1, kmax + 1)
    else:
        lag_arr = np.asarray(lags, dtype=float)
        if lag_arr.ndim > 1 or not np.all(np.isfinite(lag_arr)) or np.any(lag_arr < 0):
            raise InputError(f"lags: expected finite lags >= 0 mm, got {lags!r}")
        k = np.rint(np.atleast_1d(lag_arr) / dx).astype(int)
        if k.size and k.max() > klimit:
            raise InputError(f"lags: {lag_arr.max():g} mm exceeds the longest usable lag "
                             f"{klimit * dx:g} mm of these scans")
    kmax = int(k.max()) if k.size else 0
    num = np.zeros(kmax + 1)
    pairs = np.zeros(kmax + 1)
    for block in _groups(z, detrend):
        n_, p_ = _hdc_sums(block, kmax, periodic)
        num += n_
        pairs += p_
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.where(pairs > 0, num / np.where(pairs > 0, pairs, 1), np.nan)
    r[0] = 0.0
    out = np.maximum(r[k], 0.0)  # round-off can give -1e-17 at tiny lags
    if lags is not None and np.ndim(lags) == 0:
        return np.asarray(k[0] * dx), np.asarray(out[0])
    return k * dx, out


def log_lags(dx: float, max_lag: float, *, min_lag: float | None = None,
             per_decade: int = 25) -> np.ndarray:
    """Log-spaced lags [mm] that are distinct integer multiples of ``dx``.

    From ``min_lag`` (default ``dx``) to ``max_lag``, about ``per_decade`` per decade —
    the lag grid for fits on log–log axes, so that every decade weighs the same.
    """
    dx = positive_scalar("dx", dx, unit="mm")
    max_lag = positive_scalar("max_lag", max_lag, unit="mm")
    lo = dx if min_lag is None else positive_scalar("min_lag", min_lag, unit="mm")
    kmin, kmax = max(1, int(np.ceil(lo / dx - 1e-9))), int(np.floor(max_lag / dx + 1e-9))
    if kmax < kmin:
        raise InputError(f"max_lag: {max_lag} mm is shorter than the smallest lag {lo} mm "
                         f"(dx = {dx} mm)")
    n = max(2, int(np.ceil(np.log10(kmax / kmin) * per_decade)) + 1)
    k = np.unique(np.rint(np.geomspace(kmin, kmax, n)).astype(int))
    return k * dx


# -- power spectral density -----------------------------------------------------------------
def psd(profiles, dx: float | None = None, *, detrend: Detrend = "mean"
        ) -> tuple[np.ndarray, np.ndarray]:
    """One-sided 1D power spectral density ``C1(q)`` [mm³], averaged over equal-length scans.

    For a scan of ``N`` points (length ``L = N·dx``), with ``Z_k = Σ_n z_n e^{−2πikn/N}``
    (numpy's FFT), the wavenumbers are ``q_k = 2πk/L`` [rad/mm], ``k = 1 … ⌊N/2⌋`` and

    ``C1(q_k) = 2·dx·|Z_k|² / (2πN)`` (``k < N/2``), ``dx·|Z_k|² / (2πN)`` at the Nyquist
    wavenumber ``k = N/2`` (N even),

    normalized so that **Σ_k C1(q_k) Δq = variance of the (detrended) scan**, with
    ``Δq = 2π/L`` (Parseval). The two-sided density of the 1D version of paper eq. 11,
    ``C(q) = (2π)⁻¹ ∫ R(x) e^{−iqx} dx``, is ``C1/2`` at ``±q``. The scan is treated as
    one period (no window): leakage from non-periodic scans shows as a ``q⁻²`` floor;
    ``detrend="linear"`` reduces it.

    Returns ``(q, C1)``. All scans must have the same length.
    """
    z, dx = _unpack(profiles, dx)
    _check_detrend(detrend)
    n = z[0].size
    for i, p in enumerate(z):
        if p.size != n:
            raise InputError(f"profiles[{i}]: length {p.size} differs from profiles[0] "
                             f"({n}); the PSD needs scans of equal length (cut windows)")
    block = _groups(z, detrend)[0]
    spec = np.fft.rfft(block, axis=1)[:, 1:]
    power = np.mean(np.abs(spec) ** 2, axis=0)
    c1 = 2 * dx * power / (2 * np.pi * n)
    if n % 2 == 0:
        c1[-1] /= 2  # the Nyquist term has no negative-frequency twin
    q = 2 * np.pi * np.arange(1, n // 2 + 1) / (n * dx)
    return q, c1


# -- rms height and slope -------------------------------------------------------------------
def rms_height(profiles, *, detrend: Detrend = "mean") -> float:
    """Root-mean-square height [mm] over all points of all scans, each scan detrended
    first (``"mean"`` by default: the rms about each scan's own mean)."""
    z = as_profile_list(profiles, min_points=1)
    _check_detrend(detrend)
    total = sum(float(np.sum(b * b)) for b in _groups(z, detrend))
    return float(np.sqrt(total / sum(p.size for p in z)))


def rms_slope(profiles, dx: float | None = None, *, periodic: bool = False) -> float:
    """Root-mean-square slope [-] from first differences ``(z[n+1] − z[n])/dx``.

    Equals ``sqrt(R_zz(dx))/dx``. For a sampled sine of wavenumber ``q`` this is
    ``m2·|sin(q·dx/2)|/(q·dx/2)``: it underestimates ``m2 = qΔ/√2`` by at most
    ``(q·dx)²/24`` (relative), four times less than central differences. ``periodic``
    adds the wrap-around difference of each scan (exact for scans spanning whole periods).
    Spikes of the instrument inflate it: despike measured scans first.
    """
    z, dx = _unpack(profiles, dx)
    total, count = 0.0, 0
    for p in z:
        d = np.diff(np.append(p, p[0])) if periodic else np.diff(p)
        total += float(np.sum(d * d))
        count += d.size
    return float(np.sqrt(total / count) / dx)
