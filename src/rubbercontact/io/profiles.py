"""Read measured line scans into :class:`Profiles` (heights in mm, one sampling step).

Formats
-------
``text``
    Plain text or CSV: one or many numeric columns; the delimiter (comma, semicolon,
    tab or blanks) is sniffed; header lines that are not numbers, and comment lines
    starting with ``#``, ``%`` or ``//``, are skipped; ``NaN`` or empty fields are
    dropouts. Either the sampling step ``dx`` [mm] is given and every column is a
    scan, or (``dx=None``) the first column (or ``x_column``) holds the positions and
    the other columns are scans. The numbers are in ``unit`` (``mm``, ``um``, ``nm``,
    ``m``, ``in``) and converted to mm.
``captif``
    The CAPTIF stationary laser profilometer: a tab-separated header, the line
    ``*****DATA*****``, then ``Data Point No:  Distance (mm)  Depth (mm)``. The
    instrument's reference plates (about 45 mm above the road) are trimmed, see
    :func:`trim_plates`.
``topography``
    Instrument formats (x3p, sur, opd, di, datx, plu, nc, …) through the optional
    SurfaceTopography package (``pip install rubbercontact[topography]``). A height map
    gives one scan per row along its first (x) axis.

Dropouts (NaN)
--------------
Leading and trailing NaN are always dropped. Inner gaps are handled by ``nan=``:

- ``"windows"`` (**default**): each scan that has gaps is cut into NaN-free windows
  of ``window`` mm (default 16 mm, the paper's scan length), consecutive windows of a
  gap-free stretch overlapping by ``window_overlap`` (default 0.5); gap-free scans are
  kept whole. No height is invented, but windows shorter than the gaps' spacing are
  lost, and dropouts tend to sit on steep flanks, so the windows under-sample them.
- ``"interpolate"``: straight lines across the gaps (keeps every length scale up to
  the scan length; the lines lower the HDC at lags shorter than the gaps).
- ``"error"``: raise :class:`InputError` naming the scan.

Spikes: ``despike=True`` replaces points that differ from the running median of
``despike_window`` points by more than ``despike_k`` scaled MADs (a Hampel filter).
"""

from __future__ import annotations

import hashlib
import math
import re
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np

from .._validation import positive_scalar
from ..errors import InputError
from ..roughness.fit import RoughnessWarning

NanPolicy = Literal["windows", "interpolate", "error"]
Format = Literal["auto", "text", "captif", "topography"]

#: Length units accepted in files, in mm.
UNITS_MM = {"mm": 1.0, "um": 1e-3, "µm": 1e-3, "μm": 1e-3, "micron": 1e-3, "nm": 1e-6,
            "m": 1e3, "cm": 10.0, "in": 25.4}
#: File extensions read through SurfaceTopography under ``format="auto"``.
TOPOGRAPHY_EXTENSIONS = {
    ".x3p", ".sur", ".opd", ".opdx", ".di", ".spm", ".datx", ".nc", ".plu", ".plux",
    ".al3d", ".gwy", ".ibw", ".mi", ".sdf", ".frt", ".vk3", ".vk4", ".vk6", ".zmg", ".zon",
    ".tmd", ".oir", ".poir", ".lext", ".ezd", ".nid", ".nms", ".npy", ".npz", ".h5", ".hdf5",
    ".mat", ".mnt", ".wsxm", ".stp", ".bcr", ".fc", ".qep", ".omnisurf3d", ".hgt",
}
CAPTIF_MARKER = "*****DATA*****"
#: Largest deviation of the positions from a uniform grid, as a fraction of dx (the
#: CAPTIF files round x to 1 µm at dx = 37.5 µm: 1.3 %).
SPACING_RTOL = 0.1
_SPACING_HINT = "resample the scan to a uniform grid first"
_COMMENT = ("#", "%", "//")


# -- the result -----------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Profiles:
    """Line scans sharing one sampling step.

    Attributes
    ----------
    profiles
        Read-only 1D height arrays [mm], NaN-free.
    dx
        Sampling step [mm].
    sources
        One dict per file: ``path``, ``sha256``, ``format``, ``unit`` and what was done
        (plates trimmed, dropouts, spikes replaced, scans kept).
    """

    profiles: tuple[np.ndarray, ...]
    dx: float
    sources: tuple[dict[str, Any], ...] = field(default_factory=tuple)

    def __post_init__(self) -> None:
        dx = positive_scalar("dx", self.dx, unit="mm")
        if not self.profiles:
            raise InputError("profiles: no scan left (empty input, or every window had "
                             "a dropout)")
        frozen = []
        for i, z in enumerate(self.profiles):
            arr = np.array(z, dtype=float)
            label = f"profiles[{i}]"
            if arr.ndim != 1:
                raise InputError(f"{label}: expected a 1D scan, got shape {arr.shape}")
            if arr.size < 2:
                raise InputError(f"{label}: needs at least 2 points, got {arr.size}"
                                 + (" (empty profile)" if arr.size == 0 else ""))
            if not np.all(np.isfinite(arr)):
                raise InputError(f"{label}: contains NaN heights; choose nan='windows' "
                                 "or 'interpolate'")
            arr.setflags(write=False)
            frozen.append(arr)
        object.__setattr__(self, "profiles", tuple(frozen))
        object.__setattr__(self, "dx", dx)
        object.__setattr__(self, "sources", tuple(dict(s) for s in self.sources))

    def __len__(self) -> int:
        return len(self.profiles)

    def __iter__(self):
        return iter(self.profiles)

    @property
    def lengths(self) -> np.ndarray:
        """Length of each scan [mm] (``points × dx``)."""
        return np.array([z.size for z in self.profiles]) * self.dx

    @property
    def n_points(self) -> int:
        return int(sum(z.size for z in self.profiles))

    def as_array(self) -> np.ndarray:
        """Scans stacked as rows (they must have equal length)."""
        sizes = {z.size for z in self.profiles}
        if len(sizes) != 1:
            raise InputError(f"profiles: scans have different lengths {sorted(sizes)}; "
                             "cut windows (nan='windows') for equal lengths")
        return np.stack(self.profiles)

    def windows(self, length: float, overlap: float = 0.5) -> Profiles:
        """Cut every scan into windows of ``length`` mm (consecutive ones overlap by
        ``overlap``), e.g. to compare statistics at one scale."""
        n = _window_points(length, self.dx)
        out = [w for z in self.profiles for w in _cut(z, n, _step(n, overlap))]
        return Profiles(tuple(out), self.dx, self.sources)

    def __repr__(self) -> str:
        lens = self.lengths
        return (f"Profiles({len(self)} scans, dx={self.dx:g} mm, length "
                f"{lens.min():g}–{lens.max():g} mm, from {len(self.sources)} source(s))")


# -- helpers --------------------------------------------------------------------------------
def sha256_file(path: str | Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def unit_factor(unit: str, name: str = "unit") -> float:
    """Factor that converts ``unit`` to mm."""
    key = str(unit).strip()
    if key not in UNITS_MM:
        raise InputError(f"{name}: unknown length unit {unit!r}; use one of "
                         f"{', '.join(sorted(set(UNITS_MM) - {'μm', 'micron'}))}")
    return UNITS_MM[key]


def _window_points(length: float, dx: float) -> int:
    length = positive_scalar("window", length, unit="mm")
    n = int(round(length / dx))
    if n < 2:
        raise InputError(f"window: {length} mm holds fewer than 2 points at dx = {dx:g} mm")
    return n


def _step(n: int, overlap: float) -> int:
    if not 0 <= overlap < 1:
        raise InputError(f"window_overlap: must be in [0, 1), got {overlap}")
    return max(1, int(round(n * (1 - overlap))))


def _cut(z: np.ndarray, n: int, step: int) -> list[np.ndarray]:
    return [z[i:i + n] for i in range(0, z.size - n + 1, step)]


def _finite_runs(z: np.ndarray) -> list[tuple[int, int]]:
    """``[start, stop)`` index ranges of the NaN-free stretches of ``z``."""
    ok = np.isfinite(z)
    edges = np.flatnonzero(np.diff(np.concatenate([[0], ok.astype(np.int8), [0]])))
    return list(zip(edges[::2].tolist(), edges[1::2].tolist(), strict=True))


def strip_nan(z: np.ndarray) -> np.ndarray:
    """Drop leading and trailing NaN."""
    ok = np.flatnonzero(np.isfinite(z))
    return z[ok[0]:ok[-1] + 1] if ok.size else z[:0]


def gap_free_windows(z: np.ndarray, dx: float, window: float = 16.0,
                     overlap: float = 0.5) -> list[np.ndarray]:
    """NaN-free windows of ``window`` mm (rounded to whole points): in every gap-free
    stretch, windows start at its first point and every ``(1 − overlap)·window`` after
    it, while they fit."""
    n = _window_points(window, dx)
    step = _step(n, overlap)
    out: list[np.ndarray] = []
    for a, b in _finite_runs(z):
        out.extend(_cut(z[a:b], n, step))
    return out


def interpolate_gaps(z: np.ndarray) -> np.ndarray:
    """Linear interpolation across NaN gaps (leading/trailing NaN are dropped, not
    extrapolated)."""
    z = strip_nan(np.asarray(z, dtype=float))
    bad = ~np.isfinite(z)
    if bad.any():
        idx = np.arange(z.size)
        z = z.copy()
        z[bad] = np.interp(idx[bad], idx[~bad], z[~bad])
    return z


def despike(z: np.ndarray, window: int = 7, k: float = 5.0) -> tuple[np.ndarray, int]:
    """Hampel filter: replace points farther than ``k`` scaled MADs (1.4826·MAD) from the
    running median of ``window`` points by that median. NaN are ignored and kept.

    Returns the filtered copy and the number of points replaced.
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


def uniform_step(x: np.ndarray, name: str = "x") -> float:
    """The sampling step of positions ``x`` [same unit], checked to be uniform within
    :data:`SPACING_RTOL` of a step, else :class:`InputError`."""
    x = np.asarray(x, dtype=float)
    if x.size < 2:
        raise InputError(f"{name}: needs at least 2 positions, got {x.size}")
    if not np.all(np.isfinite(x)):
        raise InputError(f"{name}: contains NaN positions (first at index "
                         f"{int(np.argmax(~np.isfinite(x)))})")
    steps = np.diff(x)
    if np.any(steps <= 0):
        i = int(np.argmax(steps <= 0))
        raise InputError(f"{name}: positions must increase, but x[{i + 1}] = {x[i + 1]:g} "
                         f"<= x[{i}] = {x[i]:g}")
    dx = (x[-1] - x[0]) / (x.size - 1)
    dev = np.abs(x - (x[0] + dx * np.arange(x.size)))
    if dev.max() > SPACING_RTOL * dx:
        raise InputError(f"{name}: non-uniform spacing (steps from {steps.min():g} to "
                         f"{steps.max():g}, positions off a uniform grid by up to "
                         f"{dev.max() / dx:.0%} of the mean step {dx:g}); {_SPACING_HINT}")
    return float(dx)


def check_plausible(profiles: Iterable[np.ndarray], source: str, unit: str) -> None:
    """Warn (:class:`RoughnessWarning`) when the rms height is implausible for mm."""
    zs = [z for z in profiles if z.size]
    if not zs:
        return
    total = sum(float(np.sum((z - z.mean()) ** 2)) for z in zs)
    rms = math.sqrt(total / sum(z.size for z in zs))
    if rms > 100.0:
        warnings.warn(f"{source}: rms height {rms:g} mm (> 100 mm) is implausible for a "
                      f"rough surface: are the heights in {unit}? (did you give mm as µm, "
                      f"or pass unit='{unit}' for data in µm?)", RoughnessWarning, stacklevel=3)
    elif 0 < rms < 1e-6:
        warnings.warn(f"{source}: rms height {rms:g} mm (< 1 nm) is implausibly small: did "
                      f"you give metres as mm? Pass the file's unit (unit='m').",
                      RoughnessWarning, stacklevel=3)


def _handle_nan(z: np.ndarray, dx: float, *, nan: NanPolicy, window: float,
                window_overlap: float, label: str) -> tuple[list[np.ndarray], dict]:
    if nan not in ("windows", "interpolate", "error"):
        raise InputError(f"nan: expected 'windows', 'interpolate' or 'error', got {nan!r}")
    z = strip_nan(z)
    if z.size == 0:
        raise InputError(f"{label}: empty profile (no finite height)")
    n_nan = int(np.count_nonzero(~np.isfinite(z)))
    info = {"points": int(z.size), "nan_points": n_nan, "nan_policy": nan}
    if n_nan == 0:
        return [z], info
    if nan == "error":
        raise InputError(f"{label}: contains NaN heights ({n_nan} of {z.size}, first at "
                         f"index {int(np.argmax(~np.isfinite(z)))}); choose "
                         f"nan='windows' or 'interpolate'")
    if nan == "interpolate":
        return [interpolate_gaps(z)], info
    wins = gap_free_windows(z, dx, window, window_overlap)
    info.update(window_mm=float(window), window_overlap=float(window_overlap),
                windows=len(wins))
    return wins, info


def _finish(scans: list[np.ndarray], dx: float, *, label: str, nan: NanPolicy,
            window: float, window_overlap: float, despike_: bool, despike_window: int,
            despike_k: float, meta: dict) -> tuple[list[np.ndarray], dict]:
    """Despike, then NaN handling, for the scans of one source."""
    out: list[np.ndarray] = []
    details = []
    for j, z in enumerate(scans):
        lab = label if len(scans) == 1 else f"{label} scan {j}"
        n_spikes = 0
        if despike_:
            z, n_spikes = despike(z, despike_window, despike_k)
        pieces, info = _handle_nan(z, dx, nan=nan, window=window,
                                   window_overlap=window_overlap, label=lab)
        info["spikes_replaced"] = n_spikes
        details.append(info)
        out.extend(pieces)
    meta = dict(meta)
    meta["scans"] = details
    meta["profiles_out"] = len(out)
    return out, meta


# -- arrays ---------------------------------------------------------------------------------
def profiles_from_arrays(heights, dx: float | None = None, *, x=None, unit: str = "mm",
                         nan: NanPolicy = "error", window: float = 16.0,
                         window_overlap: float = 0.5, despike: bool = False,
                         despike_window: int = 7, despike_k: float = 5.0,
                         source: str = "array") -> Profiles:
    """:class:`Profiles` from in-memory heights: a 1D scan, a 2D array (one scan per row)
    or a list of 1D scans, in ``unit``; either ``dx`` [mm] or positions ``x`` [``unit``]
    shared by all scans. NaN are refused unless ``nan`` says otherwise."""
    fac = unit_factor(unit)
    if isinstance(heights, np.ndarray) and heights.ndim == 2:
        scans = list(heights)
    elif isinstance(heights, np.ndarray) or (isinstance(heights, Sequence) and len(heights)
                                             and np.isscalar(heights[0])):
        scans = [heights]
    elif isinstance(heights, Sequence):
        scans = list(heights)
    else:
        raise InputError(f"heights: expected an array or a list of arrays, got "
                         f"{type(heights).__name__}")
    if not scans:
        raise InputError("heights: no profile given (empty list)")
    arrs = []
    for i, z in enumerate(scans):
        label = "heights" if len(scans) == 1 else f"heights[{i}]"
        try:
            a = np.asarray(z, dtype=float) * fac
        except (TypeError, ValueError) as exc:
            raise InputError(f"{label}: cannot be read as numbers ({exc})") from None
        if a.ndim != 1:
            raise InputError(f"{label}: expected a 1D scan, got shape {a.shape}")
        if a.size == 0:
            raise InputError(f"{label}: empty profile (no height values)")
        arrs.append(a)
    if x is not None:
        xs = np.asarray(x, dtype=float) * fac
        for i, a in enumerate(arrs):
            if a.size != xs.size:
                label = "heights" if len(arrs) == 1 else f"heights[{i}]"
                raise InputError(f"x and {label}: mismatched lengths ({xs.size} positions, "
                                 f"{a.size} heights)")
        step = uniform_step(xs, "x")
        if dx is not None and not math.isclose(step, positive_scalar("dx", dx, unit="mm"),
                                                rel_tol=SPACING_RTOL):
            raise InputError(f"dx: {dx} mm disagrees with the step of x ({step:g} mm)")
        dx = step
    elif dx is None:
        raise InputError("dx: give the sampling step [mm] or the positions x")
    dx = positive_scalar("dx", dx, unit="mm")
    out, meta = _finish(arrs, dx, label="heights" if len(arrs) == 1 else source, nan=nan,
                        window=window, window_overlap=window_overlap, despike_=despike,
                        despike_window=despike_window, despike_k=despike_k,
                        meta={"path": source, "format": "array", "unit": unit})
    check_plausible(out, source, unit)
    return Profiles(tuple(out), dx, (meta,))


# -- text -----------------------------------------------------------------------------------
_NUM = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$|^[+-]?(nan|inf|infinity)$",
                  re.IGNORECASE)


def _split(line: str, delim: str | None) -> list[str]:
    parts = line.split(delim) if delim else line.split()
    return [p.strip() for p in parts]


def _is_data(fields: list[str]) -> bool:
    vals = [f for f in fields if f != ""]
    return bool(vals) and all(_NUM.match(f) for f in vals)


def _sniff(lines: list[str]) -> str | None:
    sample = [ln for ln in lines if ln.strip() and not ln.lstrip().startswith(_COMMENT)]
    for delim in (",", ";", "\t"):
        data = [ln for ln in sample[-20:] if delim in ln]
        if data and all(_is_data(_split(ln, delim)) for ln in data):
            return delim
    return None


def read_text_columns(path: str | Path) -> tuple[np.ndarray, list[str]]:
    """Numeric table of a text file: ``(values[rows, cols], header_lines)``; NaN where a
    field is empty or NaN."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8-sig", errors="replace")
    except IsADirectoryError:
        raise InputError(f"{path}: is a directory, not a profile file") from None
    lines = [ln.rstrip("\r\n") for ln in text.splitlines()]
    delim = _sniff(lines)
    header: list[str] = []
    rows: list[list[str]] = []
    for lineno, ln in enumerate(lines, start=1):
        s = ln.strip()
        if not s or s.startswith(_COMMENT):
            continue
        fields = _split(s, delim)
        if delim and fields and fields[-1] == "":
            fields = fields[:-1]
        if _is_data(fields):
            rows.append(fields)
        elif rows:
            raise InputError(f"{path}: line {lineno} is not numeric: {s[:60]!r} "
                             f"(only header lines before the data are skipped)")
        else:
            header.append(s)
    if not rows:
        raise InputError(f"{path}: no numeric data found (empty profile)")
    ncol = max(len(r) for r in rows)
    values = np.full((len(rows), ncol), np.nan)
    for i, r in enumerate(rows):
        values[i, : len(r)] = [float(f) if f else np.nan for f in r]
    return values, header


def read_text(path: str | Path, *, unit: str = "mm", dx: float | None = None,
              x_column: int | None = None, columns: Sequence[int] | None = None,
              nan: NanPolicy = "windows", window: float = 16.0, window_overlap: float = 0.5,
              despike: bool = False, despike_window: int = 7,
              despike_k: float = 5.0) -> Profiles:
    """Read a text/CSV file of one or many scans (module docstring, ``text``).

    ``dx`` [mm] given: every column (or ``columns``) is a scan, unless ``x_column`` names
    a position column to drop. ``dx=None``: ``x_column`` (default 0) holds the positions
    in ``unit``, which must be uniform (:data:`SPACING_RTOL`). Heights in ``unit``.
    """
    path = Path(path)
    fac = unit_factor(unit)
    values, header = read_text_columns(path)
    ncol = values.shape[1]
    if dx is None:
        xc = 0 if x_column is None else int(x_column)
        if ncol < 2:
            raise InputError(f"dx: {path.name} has a single column; give the sampling "
                             f"step dx [mm] (or add a column of positions)")
        if not 0 <= xc < ncol:
            raise InputError(f"x_column: {xc} is not a column of {path.name} ({ncol} columns)")
        x = values[:, xc] * fac
        good = np.isfinite(x)
        dx_val = uniform_step(x[good], f"{path.name}: x (column {xc})")
    else:
        xc = x_column
        dx_val = positive_scalar("dx", dx, unit="mm")
    zcols = [c for c in range(ncol) if c != xc] if columns is None else list(columns)
    for c in zcols:
        if not 0 <= int(c) < ncol:
            raise InputError(f"columns: {c} is not a column of {path.name} ({ncol} columns)")
    if not zcols:
        raise InputError(f"{path.name}: no height column (only the x column)")
    scans = []
    for c in zcols:
        z = values[:, c] * fac
        if dx is None:
            z = np.where(np.isfinite(values[:, xc]), z, np.nan)
        scans.append(z)
    meta = {"path": str(path), "sha256": sha256_file(path), "format": "text", "unit": unit,
            "header": header[:20], "columns": zcols, "x_column": xc}
    out, meta = _finish(scans, dx_val, label=path.name, nan=nan, window=window,
                        window_overlap=window_overlap, despike_=despike,
                        despike_window=despike_window, despike_k=despike_k, meta=meta)
    check_plausible(out, path.name, unit)
    return Profiles(tuple(out), dx_val, (meta,))


# -- CAPTIF laser profilometer --------------------------------------------------------------
def is_captif(path: str | Path) -> bool:
    try:
        with open(path, "rb") as fh:
            head = fh.read(4096)
    except OSError:
        return False
    return CAPTIF_MARKER.encode() in head


def read_captif_raw(path: str | Path) -> tuple[np.ndarray, np.ndarray, dict[str, str]]:
    """``(x, z, header)`` of a CAPTIF SLP file [mm], untouched (NaN kept, plates included)."""
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
    """Points on a reference plate: heights more than ``step/2`` above the median road
    height, in runs of at least ``min_points`` (shorter runs are spikes, not plates)."""
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
    """The road section ``(x_start, x_end)`` [mm] between the reference plates.

    Plates are the big step (``step`` ≈ 45 mm) above the road (:func:`plate_mask`); their
    insides are dropouts. The road is the longest stretch without plate points, less
    ``margin`` mm next to each plate (the plate's edge is seen over about 1 mm). The
    two CAPTIF files of the project's shared data (their README: about [62, 1870] and
    [70, 1878] mm) give [61.7, 1870.9] and [69.8, 1879.2] mm.
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

    ``trim=True`` detects the reference plates (:func:`trim_plates`); ``(x0, x1)`` keeps
    that x-range [mm]; ``False`` keeps everything (plates included). ``dx`` is the mean
    step of the section (the file rounds x to 1 µm: steps alternate 0.037/0.038 mm).
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
    out, meta = _finish([zs], dx, label=path.name, nan=nan, window=window,
                        window_overlap=window_overlap, despike_=despike,
                        despike_window=despike_window, despike_k=despike_k, meta=meta)
    check_plausible(out, path.name, "mm")
    return Profiles(tuple(out), dx, (meta,))


# -- instrument formats through SurfaceTopography -------------------------------------------
def _surface_topography():
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
    axis). ``unit`` is needed only when the file does not say; ``dx`` [mm] only when the
    file has no lateral size. Undefined (masked) points are dropouts, handled by ``nan``.
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
    out, meta = _finish(scans, step, label=path.name, nan=nan, window=window,
                        window_overlap=window_overlap, despike_=despike,
                        despike_window=despike_window, despike_k=despike_k, meta=meta)
    check_plausible(out, path.name, str(file_unit))
    return Profiles(tuple(out), step, (meta,))


# -- any file -------------------------------------------------------------------------------
def detect_format(path: str | Path) -> str:
    """``"captif"``, ``"topography"`` or ``"text"`` from the file's head and extension."""
    path = Path(path)
    if is_captif(path):
        return "captif"
    if path.suffix.lower() in TOPOGRAPHY_EXTENSIONS:
        return "topography"
    return "text"


def read_profiles(paths: str | Path | Sequence[str | Path], *, format: Format = "auto",
                  unit: str | None = None, dx: float | None = None,
                  nan: NanPolicy = "windows", window: float = 16.0,
                  window_overlap: float = 0.5, despike: bool = False,
                  despike_window: int = 7, despike_k: float = 5.0,
                  **format_options) -> Profiles:
    """Read one or many files into one :class:`Profiles` (all must share the step).

    ``format="auto"`` picks CAPTIF by its ``*****DATA*****`` line, SurfaceTopography by
    the extension (:data:`TOPOGRAPHY_EXTENSIONS`), else text. ``unit`` is the unit of the
    numbers in the files (default mm; instrument files state their own). ``dx`` [mm] is
    the sampling step for text files without a position column. NaN handling defaults to
    gap-free windows of 16 mm (module docstring). Other keywords go to the reader
    (``x_column``, ``columns`` for text; ``trim``, ``plate_margin`` for CAPTIF;
    ``channel`` for instrument files).
    """
    if isinstance(paths, str | Path):
        paths = [paths]
    paths = [Path(p) for p in paths]
    if not paths:
        raise InputError("paths: no file given")
    common = {"nan": nan, "window": window, "window_overlap": window_overlap,
              "despike": despike, "despike_window": despike_window, "despike_k": despike_k}
    parts: list[Profiles] = []
    for p in paths:
        if not p.exists():
            raise FileNotFoundError(f"{p}: no such file")
        fmt = detect_format(p) if format == "auto" else format
        if fmt == "captif":
            if unit not in (None, "mm"):
                raise InputError(f"unit: CAPTIF files are in mm, got {unit!r}")
            parts.append(read_captif(p, **common, **format_options))
        elif fmt == "text":
            parts.append(read_text(p, unit=unit or "mm", dx=dx, **common, **format_options))
        elif fmt == "topography":
            parts.append(read_topography_file(p, unit=unit, dx=dx, **common,
                                              **format_options))
        else:
            raise InputError(f"format: expected auto, text, captif or topography, got "
                             f"{format!r}")
    dx0 = parts[0].dx
    for p, part in zip(paths[1:], parts[1:], strict=True):
        if not math.isclose(part.dx, dx0, rel_tol=0.01):
            raise InputError(f"{p.name}: sampling step {part.dx:g} mm differs from "
                             f"{paths[0].name} ({dx0:g} mm); statistics need one step")
    return Profiles(tuple(z for part in parts for z in part.profiles), dx0,
                    tuple(s for part in parts for s in part.sources))
