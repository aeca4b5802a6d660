"""Dynamic mechanical analysis (DMA) data: storage and loss moduli against frequency.

:class:`DMAData` holds angular frequencies [rad/s], Young's storage and loss moduli
``E'``, ``E''`` [MPa], the reference temperature [°C] and where the data came from.
:func:`read_dma` reads it from a CSV file with a header naming the columns. The data
class and :func:`dma_from_material` live in :mod:`rubbercontact.materials.dmadata` and are
importable from here as well.

CSV convention
--------------
* Lines starting with ``#`` are comments; the first other line is the header; the
  delimiter is ``,`` (or ``;`` / tab, taken from the header line).
* Each header cell is a name with an optional unit in brackets or parentheses:
  ``frequency [Hz]``, ``E_storage [Pa]``, ``tan_delta``, ``T (°C)``. Names are matched
  ignoring case, spaces, ``_``, ``-`` and ``.``; ``′``/``″``/``"`` count as primes:

  ========== =========================================================== ===============
  role       accepted names                                              units
  ========== =========================================================== ===============
  frequency  ``f``, ``freq``, ``frequency``; ``omega``, ``ω``,            Hz, rad/s
             ``angular_frequency`` (these imply rad/s)
  E′, E″     ``E'``, ``E_storage``, ``E_prime``; ``E''``, ``E_loss``,     Pa, kPa, MPa,
             ``E_double_prime``                                          GPa, N/mm2
  G′, G″     the same with ``G``                                         as E
  tan δ      ``tan_delta``, ``tan δ``, ``tand``, ``loss_factor``,         none, ``-``, 1
             ``loss_tangent``
  temperature ``T``, ``temp``, ``temperature``                           °C, C, degC, K
  ========== =========================================================== ===============

* Units must be stated, in the header or by the ``frequency_unit`` / ``modulus_unit``
  arguments (a header unit and a different argument are an error): a silent factor 2π or
  10⁶ is the commonest DMA mistake.
* The moduli are ``E'`` with ``E''`` or with ``tan δ``, or ``G'`` with ``G''`` or with
  ``tan δ``. Shear moduli are converted with ``E = 3G`` (incompressible rubber, ν = 0.5).
  When a file has several, E beats G and a loss modulus beats tan δ; the others are
  ignored (and listed in ``provenance``). ``columns=`` names the columns explicitly.
* An optional temperature column holds isothermal sweeps at several temperatures (for
  :func:`~rubbercontact.materials.master_curve`).
"""

from __future__ import annotations

import csv
import hashlib
import re
import warnings
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from ..errors import InputError
from .dmadata import _FREQ_UNITS, _MOD_UNITS, DMAData, DMAWarning, _unit, dma_from_material
from .shift import ZERO_CELSIUS, ShiftLaw

__all__ = ["DMAData", "DMAWarning", "read_dma", "dma_from_material"]

_TEMP_UNITS = {"°c": "°C", "c": "°C", "degc": "°C", "k": "K"}
_NAMES = {
    "frequency": {"f", "freq", "frequency"},
    "omega": {"omega", "ω", "angularfrequency", "w"},
    "E'": {"e'", "estorage", "eprime", "storagee"},
    "E''": {"e''", "eloss", "edoubleprime", "losse"},
    "G'": {"g'", "gstorage", "gprime", "storageg"},
    "G''": {"g''", "gloss", "gdoubleprime", "lossg"},
    "tan_delta": {"tandelta", "tanδ", "tand", "lossfactor", "losstangent"},
    "temperature": {"t", "temp", "temperature"},
}
_ROLES = ("frequency", "E'", "E''", "G'", "G''", "tan_delta", "temperature")


def _split_header(cell: str) -> tuple[str, str | None]:
    m = re.match(r"^(.*?)\s*[\[(]\s*([^\])]*?)\s*[\])]\s*$", cell)
    return (m.group(1), m.group(2)) if m else (cell, None)


def _normalise(name: str) -> str:
    s = name.strip().lower()
    for a, b in (("″", "''"), ('"', "''"), ("′", "'"), ("’", "'"), ("δ", "delta")):
        s = s.replace(a, b)
    return re.sub(r"[\s_\-.]", "", s)


def _role(name: str) -> str | None:
    key = _normalise(name)
    for role, names in _NAMES.items():
        if key in {_normalise(n) for n in names}:
            return role
    return None


def _delimiter(line: str) -> str:
    return max((",", ";", "\t"), key=line.count)


def _assign_columns(path: Path, header: list[str], columns: Mapping | None) -> dict:
    """Map roles to (index, unit) from the header, or from an explicit ``columns`` map."""
    parsed = [_split_header(c.strip()) for c in header]
    found: dict[str, tuple[int, str | None]] = {}
    if columns is not None:
        bad = set(columns) - set(_ROLES)
        if bad:
            raise InputError(f"columns: unknown role(s) {sorted(bad)}; expected {_ROLES}")
        names = [p[0].strip() for p in parsed]
        for role, col in columns.items():
            if col not in names and col not in header:
                raise InputError(f"{path}: column {col!r} (for {role}) not in the header "
                                 f"{header}")
            i = names.index(col) if col in names else header.index(col)
            found[role] = (i, parsed[i][1])
        return found
    for i, (name, unit) in enumerate(parsed):
        role = _role(name)
        if role == "omega":
            role, unit = "frequency", unit or "rad/s"
        if role is None:
            continue
        if role in found:
            raise InputError(f"{path}: columns {header[found[role][0]]!r} and {header[i]!r} "
                             f"both read as {role}; keep one or pass columns=")
        found[role] = (i, unit)
    return found


def _column_unit(path: Path, label: str, header_unit: str | None, argument: str | None,
                 table: dict, arg_name: str):
    if header_unit is None and argument is None:
        raise InputError(f"{path}: column {label!r} states no unit; write it in the header "
                         f"(e.g. '{label} [{'Hz' if table is _FREQ_UNITS else 'MPa'}]') "
                         f"or pass {arg_name}=")
    if header_unit is not None and argument is not None:
        h = _unit(header_unit, table, f"{path}: column {label!r}")
        a = _unit(argument, table, arg_name)
        if h != a:
            raise InputError(f"{path}: column {label!r} is in {h[0]} but {arg_name}="
                             f"{argument!r}; remove one")
        return h
    if header_unit is not None:
        return _unit(header_unit, table, f"{path}: column {label!r}")
    return _unit(argument, table, arg_name)


def _read_rows(path: Path) -> tuple[list[str], list[tuple[int, list[str]]]]:
    if not path.is_file():
        raise InputError(f"DMA file {path}: not found")
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(f"DMA file {path}: not a text file ({exc})") from None
    header, rows, delim = None, [], ","
    for lineno, line in enumerate(text.splitlines(), start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        if header is None:
            delim = _delimiter(line)
            header = [c.strip() for c in next(csv.reader([line], delimiter=delim))]
            continue
        rows.append((lineno, [c.strip() for c in next(csv.reader([line], delimiter=delim))]))
    if header is None:
        raise InputError(f"DMA file {path}: empty (no header line)")
    if header and all(_is_number(c) for c in header):
        raise InputError(f"DMA file {path}: the first line holds numbers, not column names; "
                         f"add a header such as 'frequency [Hz], E_storage [MPa], E_loss [MPa]'")
    return header, rows


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _column(path: Path, header: list[str], rows, index: int) -> np.ndarray:
    out = np.empty(len(rows))
    for k, (lineno, cells) in enumerate(rows):
        cell = cells[index] if index < len(cells) else ""
        try:
            out[k] = float(cell)
        except ValueError:
            raise InputError(f"{path}, line {lineno}: column {header[index]!r}: "
                             f"{cell!r} is not a number") from None
        if not np.isfinite(out[k]):
            raise InputError(f"{path}, line {lineno}: column {header[index]!r}: "
                             f"{cell!r} is not finite")
    return out


def read_dma(path: str | Path, frequency_unit: str | None = None, temperature: float | None = None,
             *, modulus_unit: str | None = None, shift: ShiftLaw | None = None,
             columns: Mapping[str, str] | None = None) -> DMAData:
    """Read a DMA (master) curve from a CSV file (convention in the module docstring).

    Parameters
    ----------
    path
        CSV file with a header naming the columns.
    frequency_unit
        ``"Hz"`` or ``"rad/s"`` when the header states no frequency unit.
    temperature
        Reference temperature of the curve [°C] (default: the single temperature of a
        temperature column, or the shift law's ``t_ref``, else not stated).
    modulus_unit
        ``"Pa"``, ``"kPa"``, ``"MPa"`` or ``"GPa"`` when the header states none.
    shift
        Shift law of the master curve (WLF or Arrhenius referred to ``temperature``).
    columns
        Explicit column names per role (``"frequency"``, ``"E'"``, ``"E''"``, ``"G'"``,
        ``"G''"``, ``"tan_delta"``, ``"temperature"``), instead of recognising them.

    Returns
    -------
    DMAData
        Frequencies in rad/s, Young's moduli in MPa.

    Raises
    ------
    InputError
        Missing file, column or unit, conflicting units, non-numbers, non-positive moduli
        (one line naming the file and column).
    """
    path = Path(path)
    header, rows = _read_rows(path)
    cols = _assign_columns(path, header, columns)
    if not rows:
        raise InputError(f"DMA file {path}: no data rows below the header")
    if "frequency" not in cols:
        raise InputError(f"DMA file {path}: no frequency column in the header {header}; "
                         f"name one 'frequency [Hz]' or 'omega [rad/s]', or pass columns=")
    kind = "E" if "E'" in cols else "G" if "G'" in cols else None
    if kind is None:
        raise InputError(f"DMA file {path}: no storage modulus column (E' or G') in the "
                         f"header {header}")
    loss_role = f"{kind}''" if f"{kind}''" in cols else ("tan_delta" if "tan_delta" in cols
                                                         else None)
    if loss_role is None:
        other = "G''" if kind == "E" else "E''"
        hint = f" (the file has {other}: E and G cannot be mixed)" if other in cols else ""
        raise InputError(f"DMA file {path}: no {kind}'' or tan δ column beside "
                         f"{header[cols[kind + chr(39)][0]]!r}{hint}")
    storage_role = kind + "'"
    fi, fu_header = cols["frequency"]
    fu = _column_unit(path, header[fi], fu_header, frequency_unit, _FREQ_UNITS,
                      "frequency_unit")
    si, su_header = cols[storage_role]
    mu = _column_unit(path, header[si], su_header, modulus_unit, _MOD_UNITS, "modulus_unit")
    freq = _column(path, header, rows, fi) * fu[1]
    storage = _column(path, header, rows, si) * mu[1]
    li, lu_header = cols[loss_role]
    if loss_role == "tan_delta":
        if lu_header not in (None, "", "-", "1"):
            raise InputError(f"{path}: column {header[li]!r}: tan δ is dimensionless, "
                             f"got unit {lu_header!r}")
        loss = storage * _column(path, header, rows, li)
    else:
        lu = _column_unit(path, header[li], lu_header, modulus_unit, _MOD_UNITS,
                          "modulus_unit")
        if lu != mu:
            raise InputError(f"{path}: columns {header[si]!r} and {header[li]!r} are in "
                             f"different units ({mu[0]}, {lu[0]}); state one")
        loss = _column(path, header, rows, li) * lu[1]
    for label, arr, i, unit in (("storage", storage, si, mu[0]), ("loss", loss, li, "")):
        if np.any(arr <= 0):
            k = int(np.argmax(arr <= 0))
            raise InputError(f"{path}, line {rows[k][0]}: column {header[i]!r}: {label} "
                             f"value {rows[k][1][i]} {unit} must be > 0".rstrip())
    if np.any(freq <= 0):
        k = int(np.argmax(freq <= 0))
        raise InputError(f"{path}, line {rows[k][0]}: column {header[fi]!r}: frequency "
                         f"must be > 0, got {rows[k][1][fi]}")
    factor = 3.0 if kind == "G" else 1.0
    temps = None
    if "temperature" in cols:
        ti, tu = cols["temperature"]
        unit = _unit(tu, _TEMP_UNITS, f"{path}: column {header[ti]!r}") if tu else None
        if unit is None:
            raise InputError(f"{path}: column {header[ti]!r} states no unit; write "
                             f"'{header[ti]} [°C]' or '[K]'")
        temps = _column(path, header, rows, ti) - (ZERO_CELSIUS if unit == "K" else 0.0)
        if temperature is None and np.unique(temps).size == 1 and shift is None:
            temperature = float(temps[0])
    used = {"frequency", storage_role, loss_role, "temperature"}
    provenance = {
        "source": str(path), "sha256": hashlib.sha256(path.read_bytes()).hexdigest(),
        "frequency_column": header[fi], "storage_column": header[si],
        "loss_column": header[li], "frequency_unit": fu[0], "modulus_unit": mu[0],
        "ignored_columns": [header[i] for r, (i, _) in cols.items() if r not in used],
    }
    if kind == "G":
        provenance["conversion"] = "E = 3 G (incompressible rubber, nu = 0.5)"
    e_max = float(storage.max()) * factor
    if e_max > 1e6:
        raise InputError(f"{path}: column {header[si]!r}: E' up to {e_max:g} MPa is stiffer "
                         f"than diamond; are the values in Pa? state the unit")
    if e_max < 1e-3:
        warnings.warn(f"{path}: E' at most {e_max:g} MPa (1 kPa) is a gel, not a rubber: "
                      f"check the modulus unit", DMAWarning, stacklevel=2)
    return DMAData(freq, storage * factor, loss * factor, temperature=temperature,
                   temperatures=temps, shift=shift, source=str(path), frequency_unit=fu[0],
                   provenance=provenance)
