"""The CAPTIF stationary laser profilometer: :func:`read_captif` (format ``captif``).

A tab-separated header, the line ``*****DATA*****``, then ``Data Point No:  Distance
(mm)  Depth (mm)``. The instrument's reference plates (about 45 mm above the road) are
trimmed, see :func:`trim_plates`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ...errors import InputError
from .cleaning import _finish
from .common import NanPolicy, check_plausible, sha256_file, uniform_step
from .container import Profiles

CAPTIF_MARKER = "*****DATA*****"


def is_captif(path: str | Path) -> bool:
    """Whether the file's first 4 KiB hold :data:`CAPTIF_MARKER` (False if unreadable)."""
    try:
        with open(path, "rb") as fh:
            head = fh.read(4096)
    except OSError:
        return False
    return CAPTIF_MARKER.encode() in head


def read_captif_raw(path: str | Path) -> tuple[np.ndarray, np.ndarray, dict[str, str]]:
    """A CAPTIF SLP file, untouched (NaN kept, plates included).

    Parameters
    ----------
    path
        The file.

    Returns
    -------
    tuple of (numpy.ndarray, numpy.ndarray, dict)
        ``(x, z, header)``: distances and depths [mm], and the header's key/value pairs.

    Raises
    ------
    InputError
        If the file has no :data:`CAPTIF_MARKER` line, no data or an unreadable data
        line.
    """
    path = Path(path)
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    try:
        start = next(i for i, ln in enumerate(lines) if ln.strip().startswith(CAPTIF_MARKER))
    except StopIteration:
        raise InputError(f"{path}: not a CAPTIF profile (no line {CAPTIF_MARKER!r})") from None
    header = {}
    for ln in lines[:start]:
        parts = [p.strip() for p in ln.split("\t")]
        if parts and parts[0]:
            header[parts[0]] = parts[1] if len(parts) > 1 else ""
    body = [ln for ln in lines[start + 2:] if ln.strip()]
    if not body:
        raise InputError(f"{path}: empty profile (no data after {CAPTIF_MARKER})")
    try:
        data = np.array([[float(v) if v.strip() else np.nan for v in ln.split("\t")[:3]]
                         for ln in body])
    except ValueError as exc:
        raise InputError(f"{path}: unreadable data line ({exc})") from None
    if data.ndim != 2 or data.shape[1] < 3:
        raise InputError(f"{path}: expected 3 columns (point, distance, depth)")
    return data[:, 1], data[:, 2], header


def plate_mask(z: np.ndarray, *, step: float = 45.0, min_points: int = 3) -> np.ndarray:
    """Points on a reference plate.

    Parameters
    ----------
    z
        Depths [mm], NaN at the dropouts.
    step
        Height of the plates above the road [mm]; points more than ``step/2`` above
        the median road height are candidates.
    min_points
        Shortest run of candidates that is a plate (shorter runs are spikes).

    Returns
    -------
    numpy.ndarray
        Boolean mask, True on the plates.
    """
    finite = np.isfinite(z)
    if not finite.any():
        return np.zeros(z.shape, dtype=bool)
    high = finite & (z > np.nanmedian(z) + step / 2)
    runs = np.flatnonzero(np.diff(np.concatenate([[0], high.astype(np.int8), [0]])))
    mask = np.zeros(z.shape, dtype=bool)
    for a, b in zip(runs[::2], runs[1::2], strict=True):
        if b - a >= min_points:
            mask[a:b] = True
    return mask


def trim_plates(x: np.ndarray, z: np.ndarray, *, step: float = 45.0,
                margin: float = 1.5) -> tuple[float, float]:
    """The road section between the reference plates.

    Plates are the big step (``step`` ≈ 45 mm) above the road (:func:`plate_mask`); their
    insides are dropouts. The road is the longest stretch without plate points, less
    ``margin`` mm next to each plate (the plate's edge is seen over about 1 mm). The
    two CAPTIF files of the project's shared data (their README: about [62, 1870] and
    [70, 1878] mm) give [61.7, 1870.9] and [69.8, 1879.2] mm.

    Parameters
    ----------
    x, z
        Distances and depths [mm] (:func:`read_captif_raw`).
    step
        Height of the plates above the road [mm].
    margin
        Distance kept from each plate [mm].

    Returns
    -------
    tuple of (float, float)
        ``(x_start, x_end)`` [mm].

    Raises
    ------
    InputError
        If no road is left between the plates.
    """
    mask = plate_mask(z, step=step)
    n = x.size
    if not mask.any():
        return float(x[0]), float(x[-1])
    idx = np.flatnonzero(mask)
    starts = np.concatenate([[0], idx + 1])   # stretches [start, stop) free of plate points
    stops = np.concatenate([idx, [n]])
    ok = stops > starts
    starts, stops = starts[ok], stops[ok]
    best = int(np.argmax(x[stops - 1] - x[starts]))
    a, b = int(starts[best]), int(stops[best])
    lo = x[a] + (margin if a > 0 else 0.0)
    hi = x[b - 1] - (margin if b < n else 0.0)
    if hi <= lo:
        raise InputError("trim_plates: no road section left between the reference plates")
    return float(lo), float(hi)


def read_captif(path: str | Path, *, trim: bool | tuple[float, float] = True,
                plate_step: float = 45.0, plate_margin: float = 1.5,
                nan: NanPolicy = "windows", window: float = 16.0, window_overlap: float = 0.5,
                despike: bool = False, despike_window: int = 7,
                despike_k: float = 5.0) -> Profiles:
    """Read a CAPTIF SLP file: the road section only, dropouts handled by ``nan``.

    ``dx`` is the mean step of the section (the file rounds x to 1 µm: steps alternate
    0.037/0.038 mm).

    Parameters
    ----------
    path
        The file.
    trim
        ``True`` detects the reference plates (:func:`trim_plates`); ``(x0, x1)`` keeps
        that x-range [mm]; ``False`` keeps everything (plates included).
    plate_step, plate_margin
        ``step`` and ``margin`` of :func:`trim_plates` [mm].
    nan, window, window_overlap
        Dropout policy and window settings (package docstring).
    despike, despike_window, despike_k
        Whether to apply the Hampel filter (:func:`despike`), and its settings.

    Returns
    -------
    Profiles
        The road section's scan (or windows) [mm], one source dict
        (``format="captif"``).

    Raises
    ------
    InputError
        On an unreadable file, a bad ``trim``, an empty or non-uniform section, or NaN
        refused by ``nan``.
    """
    path = Path(path)
    x, z, header = read_captif_raw(path)
    if trim is True:
        lo, hi = trim_plates(x, z, step=plate_step, margin=plate_margin)
    elif trim is False or trim is None:
        lo, hi = float(x[0]), float(x[-1])
    else:
        try:
            lo, hi = (float(v) for v in trim)
        except (TypeError, ValueError):
            raise InputError(f"trim: expected True, False or (x_start, x_end), got "
                             f"{trim!r}") from None
        if not hi > lo:
            raise InputError(f"trim: x_end must exceed x_start, got {trim!r}")
    keep = (x >= lo) & (x <= hi)
    if keep.sum() < 2:
        raise InputError(f"{path.name}: the section [{lo:g}, {hi:g}] mm holds no data")
    xs, zs = x[keep], z[keep]
    dx = uniform_step(xs, f"{path.name}: Distance")
    meta = {"path": str(path), "sha256": sha256_file(path), "format": "captif", "unit": "mm",
            "header": header, "section_mm": [float(xs[0]), float(xs[-1])],
            "plates_trimmed": trim is True}
    cleaned = _finish([zs], dx, label=path.name, nan=nan, window=window,
                      window_overlap=window_overlap, despike_=despike,
                      despike_window=despike_window, despike_k=despike_k, meta=meta)
    check_plausible(cleaned.scans, path.name, "mm")
    return Profiles(tuple(cleaned.scans), dx, (cleaned.meta,))
