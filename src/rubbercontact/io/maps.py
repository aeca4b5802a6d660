"""Reading and writing areal height maps (:class:`rubbercontact.roughness.maps.HeightMap`).

Formats
-------
``text``
    A grid of numbers, one row of the map (one ``y``) per line, ``x`` along the line;
    comma, semicolon, tab or blanks between the numbers; ``NaN`` marks a dropout. Comment
    lines start with ``#``; the header lines ``# dx = <value>``, ``# dy = <value>`` [mm] and
    ``# unit = <unit>`` (of the heights and of dx, dy) are read when present, else ``dx``,
    ``dy`` and ``unit`` must be passed. Written by :func:`write_map` (``.txt``, ``.csv``,
    ``.asc``) with those header lines, in mm.
``npy``
    A 2D NumPy array ``(ny, nx)``, x along the last axis; it carries no pixel size or
    unit: pass ``dx`` (and ``dy``, ``unit`` unless mm).
``topography``
    Instrument files (x3p, sur, opd, datx, plu, di, …) through the optional
    SurfaceTopography package, with their own units and sizes. SurfaceTopography stores
    maps as ``(nx, ny)``; they are transposed here so that x (the instrument's first axis)
    is the sliding direction. :func:`write_map` writes ``.x3p`` through it.

Every reader records the file, its SHA-256, the format and the unit in
:attr:`HeightMap.source`; dropouts are refused or filled by ``nan`` (``"error"`` /
``"fill"``, :mod:`rubbercontact.roughness.maps`). A corrupt or truncated file raises one
:class:`~rubbercontact.errors.InputError` line naming the file and what is wrong.
"""

from __future__ import annotations

import os
import re
import secrets
from pathlib import Path

import numpy as np

from .._validation import positive_scalar
from ..errors import InputError
from ..roughness.maps import HeightMap, NanMode
from .profiles.common import check_plausible, sha256_file, unit_factor
from .profiles.topography import TOPOGRAPHY_EXTENSIONS, _surface_topography

TEXT_EXTENSIONS = (".txt", ".csv", ".asc", ".dat")
_HEADER = re.compile(r"^\s*#\s*(dx|dy|unit)\s*[=:]\s*(\S+)", re.IGNORECASE)


def map_format(path: Path, format: str = "auto") -> str:
    """The format of ``path``: ``format`` itself, or by its extension under ``"auto"``."""
    if format != "auto":
        if format not in ("text", "npy", "topography"):
            raise InputError(f"format: expected 'auto', 'text', 'npy' or 'topography', "
                             f"got {format!r}")
        return format
    ext = path.suffix.lower()
    if ext in TEXT_EXTENSIONS:
        return "text"
    if ext == ".npy":
        return "npy"
    if ext in TOPOGRAPHY_EXTENSIONS:
        return "topography"
    raise InputError(f"{path.name}: unknown map format {ext!r}; pass format='text', 'npy' "
                     f"or 'topography'")


def read_map(path: str | Path, *, format: str = "auto", unit: str | None = None,
             dx: float | None = None, dy: float | None = None, nan: NanMode = "error",
             channel: int | None = None) -> HeightMap:
    """Read a height map (module docstring for the formats).

    Parameters
    ----------
    path
        The file.
    format
        ``"auto"`` (by extension), ``"text"``, ``"npy"`` or ``"topography"``.
    unit
        Unit of the heights and pixel sizes when the file does not state it (default mm).
    dx, dy
        Pixel sizes along x and y in ``unit`` when the file does not state them (``dy``
        defaults to ``dx``).
    nan
        ``"error"`` or ``"fill"`` (harmonic fill) for dropouts.
    channel
        Data channel of an instrument file (default: the reader's default).

    Returns
    -------
    HeightMap
        Heights and lengths in mm, not periodic.
    """
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such file")
    fmt = map_format(path, format)
    if fmt == "topography":
        z, dxy, file_unit, meta = _read_topography(path, unit, dx, dy, channel)
    else:
        z, header = (_read_text(path) if fmt == "text" else (_read_npy(path), {}))
        file_unit = header.get("unit") or unit or "mm"
        fac = unit_factor(file_unit)
        step_x = header.get("dx", dx)
        if step_x is None:
            raise InputError(f"dx: {path.name} does not state its pixel size; pass dx "
                             f"(in {file_unit})")
        step_y = header.get("dy", dy if dy is not None else step_x)
        dxy = (positive_scalar("dx", float(step_x)) * fac, positive_scalar("dy", float(step_y))
               * fac)
        z = z * fac
        meta = {}
    check_plausible(list(z[np.isfinite(z).all(axis=1)]), path.name, str(file_unit))
    source = {"path": str(path), "sha256": sha256_file(path), "format": fmt,
              "unit": str(file_unit), **meta}
    return HeightMap.from_array(z, dxy[0], dxy[1], nan=nan, source=source)


def _read_text(path: Path) -> tuple[np.ndarray, dict]:
    """Heights of a text grid and its header values (``dx``, ``dy`` as str, ``unit``)."""
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError:
        raise InputError(f"{path.name}: not a text file (cannot be decoded as UTF-8)") from None
    header: dict = {}
    rows = []
    for lineno, line in enumerate(text.splitlines(), 1):
        if not line.strip():
            continue
        if line.lstrip().startswith("#"):
            m = _HEADER.match(line)
            if m:
                key, val = m.group(1).lower(), m.group(2)
                header[key] = val if key == "unit" else _number(val, path, lineno)
            continue
        fields = [f for f in re.split(r"[,;\s]+", line.strip()) if f]
        try:
            rows.append((lineno, [float(f) for f in fields]))
        except ValueError:
            raise InputError(f"{path.name}: line {lineno} is not a row of numbers "
                             f"({line.strip()[:60]!r})") from None
    if not rows:
        raise InputError(f"{path.name}: no rows of numbers (empty map)")
    width = len(rows[0][1])
    for lineno, vals in rows:
        if len(vals) != width:
            raise InputError(f"{path.name}: line {lineno} has {len(vals)} values, the first "
                             f"row {width} (truncated or corrupt file)")
    return np.array([v for _, v in rows]), header


def _number(val: str, path: Path, lineno: int) -> float:
    try:
        return float(val)
    except ValueError:
        raise InputError(f"{path.name}: line {lineno}: header value {val!r} is not a "
                         f"number") from None


def _read_npy(path: Path) -> np.ndarray:
    try:
        z = np.load(path, allow_pickle=False)
    except (ValueError, OSError, EOFError) as exc:
        raise InputError(f"{path.name}: not a readable .npy array ({type(exc).__name__}: "
                         f"{str(exc).splitlines()[0][:120]}); truncated or corrupt file"
                         ) from None
    if (not isinstance(z, np.ndarray) or z.ndim != 2 or not np.issubdtype(z.dtype, np.number)
            or np.iscomplexobj(z)):     # complex: astype(float) would drop the imaginary part
        raise InputError(f"{path.name}: expected a 2D real numeric array (ny, nx), got "
                         f"{getattr(z, 'shape', '?')} {getattr(z, 'dtype', '')}")
    return z.astype(float)


def _read_topography(path: Path, unit, dx, dy, channel
                     ) -> tuple[np.ndarray, tuple[float, float], str, dict]:
    """Heights ``(ny, nx)`` [mm] and pixel sizes [mm] of an instrument file."""
    st = _surface_topography()
    try:
        reader = st.open_topography(str(path))
        chans = reader.channels
        if channel is not None and not 0 <= int(channel) < len(chans):
            raise InputError(f"channel: {channel} not in 0…{len(chans) - 1} for {path.name}")
        ch = reader.default_channel if channel is None else chans[int(channel)]
        kwargs = {"channel_index": ch.index}
        if ch.unit is None:
            kwargs["unit"] = {"um": "µm", "μm": "µm"}.get(unit or "mm", unit or "mm")
        if ch.physical_sizes is None:
            if dx is None:
                raise InputError(f"dx: {path.name} does not state its lateral size; pass dx")
            f = 1.0 / unit_factor(kwargs.get("unit", ch.unit) or "mm")
            steps = (dx, dy if dy is not None else dx)
            kwargs["physical_sizes"] = tuple(n * s * f for n, s in zip(ch.nb_grid_pts, steps,
                                                                       strict=False))
        topo = reader.topography(**kwargs)
        if topo.dim != 2:
            raise InputError(f"{path.name}: a line scan, not a map; read it with "
                             f"rubbercontact.io.read_profiles")
        if not topo.is_uniform:
            raise InputError(f"{path.name}: non-uniform spacing; resample to a grid first")
        topo = topo.to_unit("mm")
        heights = np.ma.filled(np.ma.asarray(topo.heights(), dtype=float), np.nan)
        px = np.asarray(topo.pixel_size, dtype=float)
    except InputError:
        raise
    except Exception as exc:  # noqa: BLE001 - SurfaceTopography raises many kinds
        raise InputError(f"{path.name}: SurfaceTopography cannot read it ({type(exc).__name__}"
                         f": {str(exc).splitlines()[0][:160] if str(exc) else 'no message'})"
                         ) from None
    meta = {"reader": type(reader).__name__, "channel": ch.name}
    return heights.T, (float(px[0]), float(px[1])), str(ch.unit or unit), meta


def write_map(hmap: HeightMap, path: str | Path, *, overwrite: bool = False) -> Path:
    """Write a map in the format of ``path``'s extension (text, ``.npy`` or ``.x3p``), in mm.

    Filled dropouts are written as NaN (masked in x3p).
    The file appears whole or not at all (written under a temporary name, then renamed).
    ``.npy`` stores the heights only: read it back with ``dx`` (and ``dy``).
    """
    if not isinstance(hmap, HeightMap):
        raise InputError(f"map: expected a HeightMap, got {type(hmap).__name__}")
    path = Path(path)
    if path.exists() and not overwrite:
        raise FileExistsError(f"path: {str(path)!r} already exists; pass overwrite=True")
    ext = path.suffix.lower()
    if ext not in (*TEXT_EXTENSIONS, ".npy", ".x3p"):
        raise InputError(f"path: cannot write maps as {ext!r}; use .txt, .csv, .npy or .x3p")
    tmp = path.with_name(f".{path.name}.{secrets.token_hex(6)}.tmp{ext}")
    # filled dropouts are written as NaN, so that reading back with nan="fill" restores them
    z = np.where(hmap.measured, hmap.heights, np.nan)
    try:
        if ext == ".npy":
            with open(tmp, "wb") as fh:
                np.save(fh, z)
        elif ext == ".x3p":
            st = _surface_topography()
            st.Topography(np.ma.masked_invalid(z).T, (hmap.lengths[1], hmap.lengths[0]),
                          unit="mm").to_x3p(str(tmp))
        else:
            delim = "," if ext == ".csv" else " "
            header = f"dx = {hmap.dx!r}\ndy = {hmap.dy!r}\nunit = mm"
            np.savetxt(tmp, z, fmt="%.17g", delimiter=delim, header=header,
                       comments="# ")
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
    return path
