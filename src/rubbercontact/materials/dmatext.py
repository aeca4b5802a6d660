"""The text of a DMA file: encoding, delimiter, decimal comma, header and data rows.

Instrument exports are not all CSV: the delimiter may be a comma, a semicolon, a tab or
runs of spaces, numbers may carry a decimal comma (with any delimiter but the comma),
metadata lines may precede the header, and a row of units may follow it. The rule here: the
first line that reads as two or more numbers under some delimiter (tried in the order tab,
semicolon, comma, whitespace) starts the data and fixes the delimiter; the line above it
holds the column names, or the units when every cell of it is a unit, the names then being
the line above that. Earlier (non-empty) lines are a preamble, counted but not read. ``#`` starts a
comment line anywhere.
"""

from __future__ import annotations

import csv
import re
from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError
from .dmacolumns import is_unit

__all__ = ["Row", "TextTable", "read_table"]

_DELIMITERS = ("\t", ";", ",", None)            # None: runs of whitespace
_DELIMITER_NAMES = {"\t": "tab", ";": "semicolon", ",": "comma", None: "whitespace"}
#: units of the other columns instrument exports carry (strain, time, torque, viscosity...):
#: a units row holds only these and the units the reader knows
_OTHER_UNITS = {"%", "s", "min", "h", "°", "rad", "m", "mm", "µm", "um", "nm", "n", "mn",
                "kn", "n·m", "µn·m", "mn·m", "pa.s", "pa·s", "pas", "mpa.s", "mpa·s",
                "j", "w", "1", "-"}


@dataclass(frozen=True)
class Row:
    """One data line: its number in the file (from 1) and its cells as written."""

    line: int
    cells: tuple[str, ...]


@dataclass(frozen=True)
class TextTable:
    """The header and data rows of a DMA file.

    ``header`` cells carry their units (a units row is merged as ``name [unit]``); data
    cells have the decimal comma already replaced by a point.
    """

    header: tuple[str, ...]
    rows: tuple[Row, ...]
    delimiter: str
    decimal_comma: bool
    preamble_lines: int


def _text(path: Path) -> str:
    if not path.is_file():
        raise InputError(f"DMA file {path}: not found")
    data = path.read_bytes()
    if data[:2] in (b"\xff\xfe", b"\xfe\xff"):   # Windows "Unicode" exports
        return data.decode("utf-16")
    if b"\x00" in data:
        raise InputError(f"DMA file {path}: not a text file (NUL bytes)")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError:
        return data.decode("cp1252")            # older Windows exports (°C as 0xB0)


def _split(line: str, delimiter: str | None) -> list[str]:
    if delimiter is None:
        cells = line.split()
    else:
        cells = [c.strip() for c in next(csv.reader([line], delimiter=delimiter))]
    while cells and not cells[-1]:              # a trailing delimiter
        cells.pop()
    return cells


def _is_number(text: str, decimal_comma: bool = False) -> bool:
    if decimal_comma:
        text = text.replace(",", ".")
    try:
        float(text)
    except ValueError:
        return False
    return True


def _numeric_format(line: str) -> tuple[str | None, bool] | None:
    """``(delimiter, decimal comma)`` under which ``line`` is >= 2 numbers, else ``None``."""
    for d in _DELIMITERS:
        cells = _split(line, d)
        if len(cells) < 2:
            continue
        if all(_is_number(c) for c in cells):
            return d, False
        if d != "," and all(_is_number(c, True) for c in cells):
            return d, True
    return None


def _header_cells(line: str, delimiter: str | None, n: int) -> list[str]:
    if delimiter is not None:
        return _split(line, delimiter)
    # whitespace files: names may hold single spaces ("Storage modulus"), so columns are
    # first taken as separated by tabs or 2+ spaces, and by any whitespace if that fits
    for pattern in (r"\t|\s{2,}", r"\s+"):
        cells = [c for c in re.split(pattern, line.strip()) if c]
        if len(cells) == n:
            return cells
    return [c for c in re.split(r"\t|\s{2,}", line.strip()) if c]


def read_table(path: Path) -> TextTable:
    """Header and rows of a DMA text file (rule in the module docstring).

    Raises
    ------
    InputError
        Missing or binary file, no header, no data (one line naming the file).
    """
    lines = [(no, ln) for no, ln in enumerate(_text(path).splitlines(), start=1)
             if ln.strip() and not ln.lstrip().startswith("#")]
    if not lines:
        raise InputError(f"DMA file {path}: empty (no header line)")
    first = next((k for k, (_, ln) in enumerate(lines) if _numeric_format(ln)), None)
    if first is None:
        if len(lines) == 1:
            raise InputError(f"DMA file {path}: no data rows below the header")
        raise InputError(f"DMA file {path}: no line of numbers found (read "
                         f"{len(lines)} lines of text)")
    if first == 0:
        raise InputError(f"DMA file {path}: the first line holds numbers, not column names; "
                         f"add a header such as 'frequency [Hz], E_storage [MPa], E_loss [MPa]'")
    delimiter, _ = _numeric_format(lines[first][1])
    n = len(_split(lines[first][1], delimiter))
    head = first - 1
    header = _header_cells(lines[head][1], delimiter, n)
    if sum(_is_number(c, delimiter != ",") for c in header) > len(header) / 2:
        raise InputError(f"{path}, line {lines[head][0]}: {lines[head][1].strip()!r} is "
                         f"neither column names nor numbers")
    units = [c.strip().strip("[]()").strip() for c in header]      # "[Pa]" as "Pa"
    if head > 0 and any(units) and all(
            not u or is_unit(u) or u.lower().replace(" ", "") in _OTHER_UNITS for u in units):
        names = _header_cells(lines[head - 1][1], delimiter, n)
        header = [f"{nm} [{u}]" if u else nm
                  for nm, u in zip(names, units + [""] * (len(names) - len(units)),
                                   strict=False)]
        head -= 1
    if delimiter is None and len(header) != n:
        raise InputError(f"{path}, line {lines[head][0]}: {len(header)} column name(s) over "
                         f"{n} columns of numbers; separate the names by tabs or 2+ spaces")
    rows = tuple(Row(no, tuple(_split(ln, delimiter))) for no, ln in lines[first:])
    decimal_comma = delimiter != "," and any("," in c for r in rows for c in r.cells)
    if decimal_comma:
        rows = tuple(Row(r.line, tuple(c.replace(",", ".") for c in r.cells)) for r in rows)
    return TextTable(tuple(c.strip() for c in header), rows, _DELIMITER_NAMES[delimiter],
                     decimal_comma, head)
