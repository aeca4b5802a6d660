"""Cleaning measured scans: dropouts (NaN), windows and spikes.

Leading and trailing NaN are dropped (:func:`strip_nan`); inner gaps are cut around
(:func:`gap_free_windows`), bridged (:func:`interpolate_gaps`) or refused, as the
readers' ``nan=`` says; :func:`despike` is a Hampel filter. :func:`_finish` despikes
the scans of one source, then applies the dropout policy.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..._validation import positive_scalar
from ...errors import InputError
from .common import NanPolicy


@dataclass(frozen=True, eq=False)
class CleanedScans:
    """What cleaning one scan, or the scans of one source, gave.

    Attributes
    ----------
    scans
        NaN-free height arrays (one scan may give several windows).
    meta
        What was done: for one scan ``points``, ``nan_points``, ``nan_policy`` (and the
        window settings and ``windows`` count under ``nan="windows"``,
        ``spikes_replaced`` once despiked); for a source its metadata plus ``scans``
        (one such dict per scan) and ``profiles_out``.
    """

    scans: list[np.ndarray]
    meta: dict[str, Any] = field(default_factory=dict)


def _window_points(length: float, dx: float) -> int:
    """Points in a window of ``length`` mm at step ``dx`` [mm] (at least 2)."""
    length = positive_scalar("window", length, unit="mm")
    n = int(round(length / dx))
    if n < 2:
        raise InputError(f"window: {length} mm holds fewer than 2 points at dx = {dx:g} mm")
    return n


def _step(n: int, overlap: float) -> int:
    """Points between the starts of consecutive windows of ``n`` points."""
    if not 0 <= overlap < 1:
        raise InputError(f"window_overlap: must be in [0, 1), got {overlap}")
    return max(1, int(round(n * (1 - overlap))))


def _cut(z: np.ndarray, n: int, step: int) -> list[np.ndarray]:
    """Windows of ``n`` points of ``z``, starting every ``step`` points, while they fit."""
    return [z[i:i + n] for i in range(0, z.size - n + 1, step)]


def _finite_runs(z: np.ndarray) -> list[tuple[int, int]]:
    """``[start, stop)`` index ranges of the NaN-free stretches of ``z``."""
    ok = np.isfinite(z)
    edges = np.flatnonzero(np.diff(np.concatenate([[0], ok.astype(np.int8), [0]])))
    return list(zip(edges[::2].tolist(), edges[1::2].tolist(), strict=True))


def strip_nan(z: np.ndarray) -> np.ndarray:
    """Drop leading and trailing NaN.

    Parameters
    ----------
    z
        A 1D array.

    Returns
    -------
    numpy.ndarray
        The view from the first to the last finite value (empty if there is none).
    """
    ok = np.flatnonzero(np.isfinite(z))
    return z[ok[0]:ok[-1] + 1] if ok.size else z[:0]


def gap_free_windows(z: np.ndarray, dx: float, window: float = 16.0,
                     overlap: float = 0.5) -> list[np.ndarray]:
    """NaN-free windows of ``window`` mm (rounded to whole points).

    In every gap-free stretch, windows start at its first point and every
    ``(1 − overlap)·window`` after it, while they fit.

    Parameters
    ----------
    z
        A 1D scan, NaN at the dropouts.
    dx
        Sampling step [mm].
    window
        Window length [mm]; it must hold at least 2 points.
    overlap
        Fraction of a window shared by consecutive ones, in [0, 1).

    Returns
    -------
    list of numpy.ndarray
        The windows (views of ``z``), in order.
    """
    n = _window_points(window, dx)
    step = _step(n, overlap)
    out: list[np.ndarray] = []
    for a, b in _finite_runs(z):
        out.extend(_cut(z[a:b], n, step))
    return out


def interpolate_gaps(z: np.ndarray) -> np.ndarray:
    """Linear interpolation across NaN gaps.

    Parameters
    ----------
    z
        A 1D scan, NaN at the dropouts.

    Returns
    -------
    numpy.ndarray
        The scan without leading/trailing NaN (dropped, not extrapolated) and with
        straight lines across the inner gaps.
    """
    z = strip_nan(np.asarray(z, dtype=float))
    bad = ~np.isfinite(z)
    if bad.any():
        idx = np.arange(z.size)
        z = z.copy()
        z[bad] = np.interp(idx[bad], idx[~bad], z[~bad])
    return z


def despike(z: np.ndarray, window: int = 7, k: float = 5.0) -> tuple[np.ndarray, int]:
    """Hampel filter: replace outliers from the running median by that median.

    A point is an outlier when it is farther than ``k`` scaled MADs (1.4826·MAD) from
    the median of the ``window`` points centred on it. NaN are ignored and kept. The
    scale is floored at half the typical MAD plus the smallest height step, so that a
    flat stretch does not flag the instrument's height quantization.

    Parameters
    ----------
    z
        A 1D scan.
    window
        Odd number of points of the running median, at least 3.
    k
        Threshold in scaled MADs, > 0.

    Returns
    -------
    tuple of (numpy.ndarray, int)
        The filtered copy and the number of points replaced.
    """
    if int(window) != window or window < 3 or window % 2 == 0:
        raise InputError(f"despike_window: must be an odd integer >= 3, got {window}")
    k = positive_scalar("despike_k", k)
    z = np.asarray(z, dtype=float)
    if z.size < window:
        return z.copy(), 0
    h = window // 2
    padded = np.pad(z, h, mode="constant", constant_values=np.nan)
    win = np.lib.stride_tricks.sliding_window_view(padded, window)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # all-NaN windows inside gaps
        med = np.nanmedian(win, axis=1)
        mad = 1.4826 * np.nanmedian(np.abs(win - med[:, None]), axis=1)
    # A flat stretch has MAD 0, which would flag the instrument's height quantization:
    # floor the scale at half the typical local MAD plus the smallest height step.
    steps = np.abs(np.diff(z[np.isfinite(z)]))
    resolution = float(steps[steps > 0].min()) if np.any(steps > 0) else 0.0
    typical = float(np.nanmedian(mad)) if np.isfinite(mad).any() else 0.0
    floor = max(0.5 * typical + resolution, np.finfo(float).tiny)
    spike = np.isfinite(z) & (np.abs(z - med) > k * np.maximum(mad, floor))
    out = z.copy()
    out[spike] = med[spike]
    return out, int(spike.sum())


def _handle_nan(z: np.ndarray, dx: float, *, nan: NanPolicy, window: float,
                window_overlap: float, label: str) -> CleanedScans:
    """Apply the dropout policy ``nan`` to one scan (``label`` names it in errors)."""
    if nan not in ("windows", "interpolate", "error"):
        raise InputError(f"nan: expected 'windows', 'interpolate' or 'error', got {nan!r}")
    z = strip_nan(z)
    if z.size == 0:
        raise InputError(f"{label}: empty profile (no finite height)")
    n_nan = int(np.count_nonzero(~np.isfinite(z)))
    info = {"points": int(z.size), "nan_points": n_nan, "nan_policy": nan}
    if n_nan == 0:
        return CleanedScans([z], info)
    if nan == "error":
        raise InputError(f"{label}: contains NaN heights ({n_nan} of {z.size}, first at "
                         f"index {int(np.argmax(~np.isfinite(z)))}); choose "
                         f"nan='windows' or 'interpolate'")
    if nan == "interpolate":
        return CleanedScans([interpolate_gaps(z)], info)
    wins = gap_free_windows(z, dx, window, window_overlap)
    info.update(window_mm=float(window), window_overlap=float(window_overlap),
                windows=len(wins))
    return CleanedScans(wins, info)


def _finish(scans: list[np.ndarray], dx: float, *, label: str, nan: NanPolicy,
            window: float, window_overlap: float, despike_: bool, despike_window: int,
            despike_k: float, meta: dict[str, Any]) -> CleanedScans:
    """Despike, then NaN handling, for the scans of one source.

    Parameters
    ----------
    scans
        The source's scans [mm], NaN at the dropouts.
    dx
        Sampling step [mm].
    label
        The source's name in error messages (``"<label> scan <j>"`` for several scans).
    nan, window, window_overlap
        The dropout policy and the window settings (:func:`gap_free_windows`).
    despike_, despike_window, despike_k
        Whether to apply :func:`despike`, and its settings.
    meta
        The source's metadata; a copy gets ``scans`` and ``profiles_out``.

    Returns
    -------
    CleanedScans
        The NaN-free scans (or windows) and the completed metadata.
    """
    out: list[np.ndarray] = []
    details = []
    for j, z in enumerate(scans):
        lab = label if len(scans) == 1 else f"{label} scan {j}"
        n_spikes = 0
        if despike_:
            z, n_spikes = despike(z, despike_window, despike_k)
        cleaned = _handle_nan(z, dx, nan=nan, window=window,
                              window_overlap=window_overlap, label=lab)
        info = cleaned.meta
        info["spikes_replaced"] = n_spikes
        details.append(info)
        out.extend(cleaned.scans)
    meta = dict(meta)
    meta["scans"] = details
    meta["profiles_out"] = len(out)
    return CleanedScans(out, meta)
