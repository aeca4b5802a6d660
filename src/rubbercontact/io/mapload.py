"""A height map file made ready for the spectral statistics and the half-space solve.

One loader for the command line (``rubbercontact roughness map``, ``halfspace --map``) and
the map runs (``[surface.map]``), so that both read, detrend and periodize a file alike.
"""

from __future__ import annotations

from pathlib import Path


def load_map(path: Path, *, fmt: str = "auto", unit: str | None = None,
             dx: float | None = None, nan: str = "error", detrend: str | None = None,
             periodize: str = "mirror"):
    """Read ``path``, remove its mean or plane, and make it one period for the FFT.

    Parameters
    ----------
    path
        The map file.
    fmt, unit, dx, nan
        As :func:`rubbercontact.io.read_map` (``dx`` [``unit``], default mm).
    detrend
        ``"plane"`` (a measured map's tilt), ``"mean"`` or ``"none"``; default ``"plane"``
        when mirrored, ``"mean"`` for a map that is one period already (it has no tilt).
    periodize
        ``"mirror"`` (a measured map) or ``"none"`` (the map is one period already).

    Returns
    -------
    tuple of HeightMap
        The detrended map as read, and its periodic version [mm].
    """
    from .maps import read_map

    if detrend is None:
        detrend = "plane" if periodize == "mirror" else "mean"
    hmap = read_map(path, format=fmt, unit=unit, dx=dx, nan=nan).detrended(detrend)
    return hmap, hmap.periodized(periodize)
