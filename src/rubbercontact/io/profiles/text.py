"""Plain text and CSV line scans: :func:`read_text` (format ``text``).

One or many numeric columns; the delimiter (comma, semicolon, tab or blanks) is
sniffed; header lines that are not numbers, and comment lines starting with ``#``,
``%`` or ``//``, are skipped; ``NaN`` or empty fields are dropouts.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from ..._validation import positive_scalar
from ...errors import InputError
from .cleaning import _finish
from .common import NanPolicy, check_plausible, sha256_file, uniform_step, unit_factor
from .container import Profiles

_COMMENT = ("#", "%", "//")
_NUM = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$|^[+-]?(nan|inf|infinity)$",
                  re.IGNORECASE)


def _split(line: str, delim: str | None) -> list[str]:
    """Fields of ``line`` at ``delim`` (blanks if None), stripped."""
    parts = line.split(delim) if delim else line.split()
    return [p.strip() for p in parts]


def _is_data(fields: list[str]) -> bool:
    """Whether the non-empty fields are all numbers (NaN and inf included)."""
    vals = [f for f in fields if f != ""]
    return bool(vals) and all(_NUM.match(f) for f in vals)


def _sniff(lines: list[str]) -> str | None:
    """The delimiter (``,``, ``;`` or tab) of the last 20 data lines, else None (blanks)."""
    sample = [ln for ln in lines if ln.strip() and not ln.lstrip().startswith(_COMMENT)]
    for delim in (",", ";", "\t"):
        data = [ln for ln in sample[-20:] if delim in ln]
        if data and all(_is_data(_split(ln, delim)) for ln in data):
            return delim
    return None


def read_text_columns(path: str | Path) -> tuple[np.ndarray, list[str]]:
    """Numeric table of a text file.

    Parameters
    ----------
    path
        The file (UTF-8, a BOM is dropped).

    Returns
    -------
    tuple of (numpy.ndarray, list of str)
        ``values[rows, cols]``, NaN where a field is empty or NaN (or a row is short),
        and the header lines before the data.

    Raises
    ------
    InputError
        If ``path`` is a directory, has no numeric line, or has a non-numeric line
        after the data started.
    """
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
    """Read a text/CSV file of one or many scans (package docstring, ``text``).

    Parameters
    ----------
    path
        The file.
    unit
        Unit of the numbers (positions and heights), a key of :data:`UNITS_MM`.
    dx
        Sampling step [mm]: every column (or ``columns``) is a scan, unless
        ``x_column`` names a position column to drop. ``None``: ``x_column``
        (default 0) holds the positions in ``unit``, which must be uniform
        (:data:`SPACING_RTOL`).
    x_column
        Index of the position column.
    columns
        Indices of the height columns (default: all but ``x_column``).
    nan, window, window_overlap
        Dropout policy and window settings (package docstring).
    despike, despike_window, despike_k
        Whether to apply the Hampel filter (:func:`despike`), and its settings.

    Returns
    -------
    Profiles
        The scans [mm] with one source dict (``format="text"``).

    Raises
    ------
    InputError
        On an unreadable table, bad column indices, a missing ``dx`` for a single
        column, non-uniform positions, or NaN refused by ``nan``.
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
    cleaned = _finish(scans, dx_val, label=path.name, nan=nan, window=window,
                      window_overlap=window_overlap, despike_=despike,
                      despike_window=despike_window, despike_k=despike_k, meta=meta)
    check_plausible(cleaned.scans, path.name, unit)
    return Profiles(tuple(cleaned.scans), dx_val, (cleaned.meta,))
