"""Dynamic mechanical analysis (DMA) data: storage and loss moduli against frequency.

:class:`DMAData` holds angular frequencies [rad/s], Young's storage and loss moduli
``E'``, ``E''`` [MPa], the reference temperature [°C] and where the data came from.
:func:`read_dma` reads it from a text file as instruments export it. The data class and
:func:`dma_from_material` live in :mod:`rubbercontact.materials.dmadata` and are
importable from here as well.

File convention
---------------
* The text layout (delimiter, decimal comma, preamble, units row, ``#`` comments) is
  detected: :mod:`rubbercontact.materials.dmatext`.
* Each header cell is a name with an optional unit in brackets or parentheses
  (``Frequency (Hz)``, ``Storage modulus [MPa]``), after a slash (``E'/MPa``) or as a
  suffix (``frequency_Hz``, ``E_storage_MPa``). Names are matched ignoring case, spaces,
  ``_``, ``-``, ``.``, ``(``, ``)`` and ``|``; ``′``/``″``/``"`` count as primes:

  =========== =========================================================== ==============
  role        accepted names                                              units
  =========== =========================================================== ==============
  frequency   ``f``, ``freq``, ``frequency``                              Hz, kHz, rad/s
  ω           ``omega``, ``ω``, ``angular frequency`` (rad/s if unstated) as above, 1/s
  E′, E″      ``E'``, ``E_storage``, ``storage modulus E'``; ``E''``,     Pa, kPa, MPa,
              ``E_loss``, ``loss modulus E''``                            GPa, N/mm2
  E*          ``E*``, ``|E*|``, ``complex modulus E*`` (with tan δ)       as E′
  G′, G″, G*  the same with ``G``                                         as E′
  E or G      ``storage modulus``, ``loss modulus``, ``complex modulus``  as E′
              (the letter comes from ``modulus=``)
  tan δ       ``tan delta``, ``Tan(delta)``, ``tan δ``, ``loss factor``,  none, ``-``, 1
              ``damping factor``, ``loss tangent``
  temperature ``T``, ``temp``, ``temperature``                            °C, C, K
  =========== =========================================================== ==============

* Units must be stated, in the header or by the ``frequency_unit`` / ``modulus_unit``
  arguments (a header unit and a different argument are an error): a silent factor 2π or
  10⁶ is the commonest DMA mistake. For the same reason a modulus named without E or G
  (``Storage modulus``: tensile DMA writes E, a shear rheometer G) needs ``modulus=``.
* The moduli are the storage modulus with the loss modulus or with ``tan δ``, or ``|E*|``
  with ``tan δ``. Shear moduli are converted with ``E = 2 (1 + ν) G``, ``ν`` the
  ``poisson_ratio`` (0.5, incompressible rubber: ``E = 3 G``). When a file has several,
  E beats G, ω beats f (they must agree), a loss modulus beats tan δ and ``E'`` beats
  ``|E*|``; the others are ignored and listed in ``provenance``. ``columns=`` names the
  columns explicitly.
* An optional temperature column holds isothermal sweeps at several temperatures (for
  :func:`~rubbercontact.materials.master_curve`).
"""

from __future__ import annotations

import hashlib
import numbers
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError
from .dmacolumns import (
    ANGULAR_UNITS,
    DIMENSIONLESS,
    FREQ_UNITS,
    MOD_UNITS,
    ROLES,
    TEMP_UNITS,
    role,
    split_unit,
    unit,
)
from .dmadata import DMAData, DMAWarning, dma_from_material
from .dmatext import Row, TextTable, read_table
from .shift import ZERO_CELSIUS, ShiftLaw

__all__ = ["DMAData", "DMAWarning", "read_dma", "dma_from_material"]

#: the roles ``columns=`` may name (a generic modulus is named by its letter there)
_EXPLICIT_ROLES = tuple(r for r in ROLES if not r.startswith("M"))


@dataclass(frozen=True)
class _Column:
    """A recognised column: its position and the unit its header states (or ``None``)."""

    index: int
    unit: str | None


@dataclass(frozen=True)
class _Choice:
    """The roles read: frequency, storage (``X'`` or ``X*``), loss (``X''`` or tan δ)."""

    frequency: str
    kind: str
    storage: str
    loss: str


def _explicit_columns(path: Path, header: tuple[str, ...], columns: Mapping) -> dict:
    bad = set(columns) - set(_EXPLICIT_ROLES)
    if bad:
        raise InputError(f"columns: unknown role(s) {sorted(bad)}; expected {_EXPLICIT_ROLES}")
    parsed = [split_unit(c) for c in header]
    names = [p[0].strip() for p in parsed]
    found = {}
    for r, col in columns.items():
        if col not in names and col not in header:
            raise InputError(f"{path}: column {col!r} (for {r}) not in the header "
                             f"{list(header)}")
        i = names.index(col) if col in names else header.index(col)
        found[r] = _Column(i, parsed[i][1])
    return found


def _assign_columns(path: Path, header: tuple[str, ...], columns: Mapping | None,
                    modulus: str | None) -> dict[str, _Column]:
    """Map roles to columns from the header, or from an explicit ``columns`` map."""
    if columns is not None:
        return _explicit_columns(path, header, columns)
    found: dict[str, _Column] = {}
    for i, cell in enumerate(header):
        name, unit_text = split_unit(cell)
        r = role(name)
        if r is None:
            continue
        if r.startswith("M"):
            if modulus is None:
                raise InputError(f"{path}: column {cell!r} does not say E or G; pass "
                                 f"modulus='E' (tensile/bending DMA) or modulus='G' (shear)")
            r = modulus + r[1:]
        if r in found:
            raise InputError(f"{path}: columns {header[found[r].index]!r} and {cell!r} "
                             f"both read as {r}; keep one or pass columns=")
        found[r] = _Column(i, unit_text)
    return found


def _choose(path: Path, header: tuple[str, ...], cols: dict[str, _Column]) -> _Choice:
    """Which columns give the frequency and the moduli (precedence in the docstring)."""
    freq = "omega" if "omega" in cols else "frequency" if "frequency" in cols else None
    if freq is None:
        raise InputError(f"DMA file {path}: no frequency column in the header {list(header)}; "
                         f"name one 'frequency [Hz]' or 'omega [rad/s]', or pass columns=")
    kind = next((k for k in "EG" if f"{k}'" in cols or f"{k}*" in cols), None)
    if kind is None:
        raise InputError(f"DMA file {path}: no storage modulus column (E' or G') in the "
                         f"header {list(header)}")
    storage = f"{kind}'" if f"{kind}'" in cols else f"{kind}*"
    if storage == f"{kind}'" and f"{kind}''" in cols:
        return _Choice(freq, kind, storage, f"{kind}''")
    if "tan_delta" in cols:
        return _Choice(freq, kind, storage, "tan_delta")
    other = "G''" if kind == "E" else "E''"
    hint = f" (the file has {other}: E and G cannot be mixed)" if other in cols else ""
    needs = "tan δ" if storage.endswith("*") else f"{kind}'' or tan δ"
    raise InputError(f"DMA file {path}: no {needs} column beside "
                     f"{header[cols[storage].index]!r}{hint}")


def _column_unit(path: Path, label: str, header_unit: str | None, argument: str | None,
                 table: dict, arg_name: str):
    if header_unit is None and argument is None:
        raise InputError(f"{path}: column {label!r} states no unit; write it in the header "
                         f"(e.g. '{label} [{'Hz' if 'hz' in table else 'MPa'}]') "
                         f"or pass {arg_name}=")
    if header_unit is not None and argument is not None:
        h = unit(header_unit, table, f"{path}: column {label!r}")
        a = unit(argument, table, arg_name)
        if h != a:
            raise InputError(f"{path}: column {label!r} is in {h[0]} but {arg_name}="
                             f"{argument!r}; remove one")
        return h
    if header_unit is not None:
        return unit(header_unit, table, f"{path}: column {label!r}")
    return unit(argument, table, arg_name)


def _column(path: Path, table: TextTable, index: int) -> np.ndarray:
    out = np.empty(len(table.rows))
    for k, row in enumerate(table.rows):
        cell = row.cells[index] if index < len(row.cells) else ""
        try:
            out[k] = float(cell)
        except ValueError:
            raise InputError(f"{path}, line {row.line}: column {table.header[index]!r}: "
                             f"{cell!r} is not a number") from None
        if not np.isfinite(out[k]):
            raise InputError(f"{path}, line {row.line}: column {table.header[index]!r}: "
                             f"{cell!r} is not finite")
    return out


def _positive(path: Path, table: TextTable, arr: np.ndarray, index: int, label: str) -> None:
    if np.any(arr <= 0):
        row: Row = table.rows[int(np.argmax(arr <= 0))]
        raise InputError(f"{path}, line {row.line}: column {table.header[index]!r}: {label} "
                         f"value {row.cells[index]} must be > 0")


def _frequency(path: Path, table: TextTable, cols: dict[str, _Column], choice: _Choice,
               argument: str | None) -> tuple[np.ndarray, str]:
    """Angular frequencies [rad/s] and the unit read; ω and f must agree when both given."""
    col = cols[choice.frequency]
    label = table.header[col.index]
    if choice.frequency == "omega":
        fu = _column_unit(path, label, col.unit or ("rad/s" if argument is None else None),
                          argument, ANGULAR_UNITS, "frequency_unit")
    else:
        fu = _column_unit(path, label, col.unit, argument, FREQ_UNITS, "frequency_unit")
    freq = _column(path, table, col.index) * fu[1]
    _positive(path, table, freq, col.index, "frequency")
    if choice.frequency == "omega" and "frequency" in cols and cols["frequency"].unit:
        other = cols["frequency"]
        f = _column(path, table, other.index) * unit(
            other.unit, FREQ_UNITS, f"{path}: column {table.header[other.index]!r}")[1]
        # instruments round both columns to 3-5 digits: agreement to 1 % tells units apart
        bad = np.abs(f - freq) > 1e-2 * freq
        if np.any(bad):
            line = table.rows[int(np.argmax(bad))].line
            raise InputError(f"{path}, line {line}: columns {label!r} and "
                             f"{table.header[other.index]!r} disagree (ω ≠ 2π f); check units")
    return freq, fu[0]


def _moduli(path: Path, table: TextTable, cols: dict[str, _Column], choice: _Choice,
            argument: str | None) -> tuple[np.ndarray, np.ndarray, str]:
    """Storage and loss moduli [MPa, of the file's kind E or G] and the storage unit."""
    sc = cols[choice.storage]
    su = _column_unit(path, table.header[sc.index], sc.unit, argument, MOD_UNITS,
                      "modulus_unit")
    first = _column(path, table, sc.index) * su[1]
    _positive(path, table, first, sc.index, "modulus")
    lc = cols[choice.loss]
    if choice.loss == "tan_delta":
        if (lc.unit or "").strip() not in DIMENSIONLESS:
            raise InputError(f"{path}: column {table.header[lc.index]!r}: tan δ is "
                             f"dimensionless, got unit {lc.unit!r}")
        tan = _column(path, table, lc.index)
        _positive(path, table, tan, lc.index, "tan δ")
        storage = first / np.sqrt(1.0 + tan**2) if choice.storage.endswith("*") else first
        return storage, storage * tan, su[0]
    lu = _column_unit(path, table.header[lc.index], lc.unit, argument, MOD_UNITS,
                      "modulus_unit")
    loss = _column(path, table, lc.index) * lu[1]
    _positive(path, table, loss, lc.index, "loss")
    return first, loss, su[0]


def _temperatures(path: Path, table: TextTable, cols: dict[str, _Column]) -> np.ndarray | None:
    if "temperature" not in cols:
        return None
    col = cols["temperature"]
    label = table.header[col.index]
    if not col.unit:
        raise InputError(f"{path}: column {label!r} states no unit; write "
                         f"'{label} [°C]' or '[K]'")
    tu = unit(col.unit, TEMP_UNITS, f"{path}: column {label!r}")
    return _column(path, table, col.index) - (ZERO_CELSIUS if tu == "K" else 0.0)


def _check_options(modulus: str | None, poisson_ratio: float) -> float:
    if modulus is not None and modulus not in ("E", "G"):
        raise InputError(f"modulus: expected 'E' or 'G', got {modulus!r}")
    if isinstance(poisson_ratio, bool) or not isinstance(poisson_ratio, numbers.Real) \
            or not 0.0 <= poisson_ratio <= 0.5:
        raise InputError(f"poisson_ratio: must lie in [0, 0.5], got {poisson_ratio!r}")
    return float(poisson_ratio)


def read_dma(path: str | Path, frequency_unit: str | None = None, temperature: float | None = None,
             *, modulus_unit: str | None = None, shift: ShiftLaw | None = None,
             columns: Mapping[str, str] | None = None, modulus: str | None = None,
             poisson_ratio: float = 0.5) -> DMAData:
    """Read a DMA (master) curve from a text file (convention in the module docstring).

    Parameters
    ----------
    path
        Text file (CSV, semicolon- or tab-separated, or columns) with a header naming the
        columns.
    frequency_unit
        ``"Hz"``, ``"kHz"`` or ``"rad/s"`` when the header states no frequency unit.
    temperature
        Reference temperature of the curve [°C] (default: the single temperature of a
        temperature column, or the shift law's ``t_ref``, else not stated).
    modulus_unit
        ``"Pa"``, ``"kPa"``, ``"MPa"`` or ``"GPa"`` when the header states none.
    shift
        Shift law of the master curve (WLF or Arrhenius referred to ``temperature``).
    columns
        Explicit column names per role (``"frequency"``, ``"omega"``, ``"E'"``, ``"E''"``,
        ``"E*"``, ``"G'"``, ``"G''"``, ``"G*"``, ``"tan_delta"``, ``"temperature"``),
        instead of recognising them.
    modulus
        ``"E"`` or ``"G"``: what the columns named without a letter (``Storage modulus``)
        hold.
    poisson_ratio
        ``ν`` in ``E = 2 (1 + ν) G`` for shear data [-], in [0, 0.5].

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
    nu = _check_options(modulus, poisson_ratio)
    path = Path(path)
    table = read_table(path)
    cols = _assign_columns(path, table.header, columns, modulus)
    choice = _choose(path, table.header, cols)
    freq, freq_unit = _frequency(path, table, cols, choice, frequency_unit)
    storage, loss, mod_unit = _moduli(path, table, cols, choice, modulus_unit)
    factor = 2.0 * (1.0 + nu) if choice.kind == "G" else 1.0
    temps = _temperatures(path, table, cols)
    if temps is not None and temperature is None and np.unique(temps).size == 1 \
            and shift is None:
        temperature = float(temps[0])
    used = {choice.frequency, choice.storage, choice.loss, "temperature"}
    provenance = {
        "source": str(path), "sha256": hashlib.sha256(path.read_bytes()).hexdigest(),
        "frequency_column": table.header[cols[choice.frequency].index],
        "storage_column": table.header[cols[choice.storage].index],
        "loss_column": table.header[cols[choice.loss].index],
        "frequency_unit": freq_unit, "modulus_unit": mod_unit,
        "ignored_columns": [table.header[c.index] for r, c in cols.items() if r not in used],
        "delimiter": table.delimiter, "decimal_comma": table.decimal_comma,
        "preamble_lines": table.preamble_lines,
    }
    if choice.kind == "G":
        provenance["conversion"] = (f"E = 2 (1 + nu) G with nu = {nu:g}: "
                                    f"E = {factor:g} G")
    _check_magnitude(path, table.header[cols[choice.storage].index],
                     float(storage.max()) * factor)
    return DMAData(freq, storage * factor, loss * factor, temperature=temperature,
                   temperatures=temps, shift=shift, source=str(path),
                   frequency_unit=freq_unit, provenance=provenance)


def _check_magnitude(path: Path, label: str, e_max: float) -> None:
    """Moduli far outside rubber's range are a unit mistake (an error, or a warning)."""
    if e_max > 1e6:
        raise InputError(f"{path}: column {label!r}: E' up to {e_max:g} MPa is stiffer "
                         f"than diamond; are the values in Pa? state the unit")
    if e_max < 1e-3:
        warnings.warn(f"{path}: E' at most {e_max:g} MPa (1 kPa) is a gel, not a rubber: "
                      f"check the modulus unit", DMAWarning, stacklevel=3)
