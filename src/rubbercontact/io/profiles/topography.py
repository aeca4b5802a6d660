"""Instrument formats through SurfaceTopography: :func:`read_topography_file`.

Format ``topography``: x3p, sur, opd, di, datx, plu, nc, … through the optional
SurfaceTopography package (``pip install rubbercontact[topography]``). A height map
gives one scan per row along its first (x) axis.
"""

from __future__ import annotations

from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np

from ...errors import InputError
from .cleaning import _finish
from .common import _SPACING_HINT, NanPolicy, check_plausible, sha256_file, unit_factor
from .container import Profiles

#: File extensions read through SurfaceTopography under ``format="auto"``.
TOPOGRAPHY_EXTENSIONS = {
    ".x3p", ".sur", ".opd", ".opdx", ".di", ".spm", ".datx", ".nc", ".plu", ".plux",
    ".al3d", ".gwy", ".ibw", ".mi", ".sdf", ".frt", ".vk3", ".vk4", ".vk6", ".zmg", ".zon",
    ".tmd", ".oir", ".poir", ".lext", ".ezd", ".nid", ".nms", ".npy", ".npz", ".h5", ".hdf5",
    ".mat", ".mnt", ".wsxm", ".stp", ".bcr", ".fc", ".qep", ".omnisurf3d", ".hgt",
}


def _surface_topography() -> ModuleType:
    """The SurfaceTopography module, else :class:`InputError` saying how to install it."""
    try:
        import SurfaceTopography
    except ImportError:
        raise InputError("instrument formats (x3p, sur, opd, di, …) need the optional "
                         "SurfaceTopography package: pip install rubbercontact[topography]"
                         ) from None
    return SurfaceTopography


def read_topography_file(path: str | Path, *, unit: str | None = None,
                         dx: float | None = None, channel: int | None = None,
                         nan: NanPolicy = "windows", window: float = 16.0,
                         window_overlap: float = 0.5, despike: bool = False,
                         despike_window: int = 7, despike_k: float = 5.0) -> Profiles:
    """Read an instrument file with SurfaceTopography (optional dependency).

    A line scan gives one scan; a height map gives one scan per row along x (its first
    axis). Undefined (masked) points are dropouts, handled by ``nan``.

    Parameters
    ----------
    path
        The file.
    unit
        The file's length unit, needed only when the file does not say.
    dx
        Sampling step [mm], needed only when the file has no lateral size.
    channel
        Index of the data channel (default: the reader's default channel).
    nan, window, window_overlap
        Dropout policy and window settings (package docstring).
    despike, despike_window, despike_k
        Whether to apply the Hampel filter (:func:`despike`), and its settings.

    Returns
    -------
    Profiles
        The scans [mm] with one source dict (``format="topography"``).

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    InputError
        If SurfaceTopography is missing or cannot read the file, the channel does not
        exist, the unit or lateral size is unknown and not given, the spacing is
        non-uniform, or NaN are refused by ``nan``.
    """
    path = Path(path)
    st = _surface_topography()
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such file")
    try:
        reader = st.open_topography(str(path))
    except Exception as exc:  # noqa: BLE001 - SurfaceTopography raises many kinds
        raise InputError(f"{path}: SurfaceTopography cannot read it ("
                         f"{type(exc).__name__}: {str(exc).splitlines()[0][:200]})") from None
    channels = reader.channels
    ch = reader.default_channel if channel is None else None
    if channel is not None:
        if not 0 <= int(channel) < len(channels):
            raise InputError(f"channel: {channel} not in 0…{len(channels) - 1} for {path.name}")
        ch = channels[int(channel)]
    kwargs: dict[str, Any] = {"channel_index": ch.index}
    if ch.unit is None:
        if unit is None:
            raise InputError(f"unit: {path.name} does not state its length unit; pass it "
                             f"(--unit mm|um|m)")
        kwargs["unit"] = {"um": "µm", "μm": "µm"}.get(unit, unit)
    if ch.physical_sizes is None:
        if dx is None:
            raise InputError(f"dx: {path.name} does not state its lateral size; give the "
                             f"sampling step [mm] (--dx)")
        fac = 1.0 / unit_factor(kwargs.get("unit", ch.unit) or "mm")  # mm → file unit
        kwargs["physical_sizes"] = tuple(n * dx * fac for n in ch.nb_grid_pts)
    try:
        topo = reader.topography(**kwargs)
        if not topo.is_uniform:
            raise InputError(f"{path.name}: non-uniform spacing; {_SPACING_HINT}")
        topo = topo.to_unit("mm")
        heights = topo.heights()
    except InputError:
        raise
    except Exception as exc:  # noqa: BLE001
        raise InputError(f"{path}: SurfaceTopography failed ({type(exc).__name__}: "
                         f"{str(exc).splitlines()[0][:200]})") from None
    heights = np.ma.filled(np.ma.asarray(heights, dtype=float), np.nan)
    pixel = np.atleast_1d(np.asarray(topo.pixel_size, dtype=float))
    step = float(pixel[0])
    scans = [heights] if heights.ndim == 1 else list(heights.T)
    file_unit = ch.unit or unit
    meta = {"path": str(path), "sha256": sha256_file(path), "format": "topography",
            "reader": type(reader).__name__, "unit": str(file_unit),
            "channel": ch.name, "nb_grid_pts": list(map(int, np.atleast_1d(heights.shape)))}
    cleaned = _finish(scans, step, label=path.name, nan=nan, window=window,
                      window_overlap=window_overlap, despike_=despike,
                      despike_window=despike_window, despike_k=despike_k, meta=meta)
    check_plausible(cleaned.scans, path.name, str(file_unit))
    return Profiles(tuple(cleaned.scans), step, (cleaned.meta,))
