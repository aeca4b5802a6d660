"""The columns of a DMA file: what each header cell is, and in which unit.

A header cell is a name with an optional unit, written the ways instruments and people
write them: in brackets or parentheses (``Frequency (Hz)``, ``Storage modulus [MPa]``),
after a slash (``E'/MPa``, ``Temp./°C``) or as a suffix (``frequency_Hz``,
``E_storage_MPa``). :func:`split_unit` separates the two, :func:`role` tells what the name
stands for (table in :mod:`rubbercontact.materials.dma`), and the unit tables here convert
to rad/s, MPa and °C.
"""

from __future__ import annotations

import re

import numpy as np

from ..errors import InputError
from .dmadata import _FREQ_UNITS, _MOD_UNITS

__all__ = ["ANGULAR_UNITS", "FREQ_UNITS", "MOD_UNITS", "ROLES", "TEMP_UNITS", "is_unit",
           "role", "split_unit", "unit"]

#: frequency units -> (display name, factor to rad/s)
FREQ_UNITS = {**_FREQ_UNITS, "khz": ("kHz", 2e3 * np.pi), "rad/sec": ("rad/s", 1.0),
              "rads-1": ("rad/s", 1.0), "rad·s⁻¹": ("rad/s", 1.0)}
#: an *angular* frequency may also be written per second (rheometers write ``ω [1/s]``);
#: for a plain "frequency" ``1/s`` would be ambiguous (Hz or rad/s?) and is refused
ANGULAR_UNITS = {**FREQ_UNITS, "1/s": ("rad/s", 1.0), "s-1": ("rad/s", 1.0),
                 "s^-1": ("rad/s", 1.0), "s⁻¹": ("rad/s", 1.0)}
#: modulus units -> (display name, factor to MPa)
MOD_UNITS = {**_MOD_UNITS, "n/m2": ("Pa", 1e-6), "n/m²": ("Pa", 1e-6), "n/m^2": ("Pa", 1e-6),
             "n/mm^2": ("MPa", 1.0)}
#: temperature units -> display name (values are converted to °C)
TEMP_UNITS = {"°c": "°C", "c": "°C", "degc": "°C", "℃": "°C", "celsius": "°C", "k": "K",
              "kelvin": "K"}
#: what a dimensionless column (tan δ) may state as its unit
DIMENSIONLESS = ("", "-", "1", "—")

#: every role a column can play (``M`` is a modulus that does not say whether E or G)
ROLES = ("frequency", "omega", "E'", "E''", "E*", "G'", "G''", "G*", "M'", "M''", "M*",
         "tan_delta", "temperature")
_NAMES = {
    "frequency": {"f", "freq", "frequency", "testfrequency", "oscillationfrequency"},
    "omega": {"omega", "w", "angularfrequency", "angularfreq", "angfrequency",
              "angfreq", "circularfrequency"},
    "tan_delta": {"tandelta", "tand", "lossfactor", "losstangent", "dampingfactor",
                  "tangentdelta"},
    "temperature": {"t", "temp", "temperature", "sampletemperature", "testtemperature"},
}
#: a modulus name: optional E/G before or after, the quantity in words and/or in marks
_MODULUS = re.compile(r"([eg]?)(storage|loss|complex)?(?:modulus|mod)?([eg]?)"
                      r"(''|'|\*|doubleprime|prime)?")
_QUANTITY = {"storage": "'", "loss": "''", "complex": "*", "'": "'", "prime": "'",
             "''": "''", "doubleprime": "''", "*": "*"}
_BRACKETS = re.compile(r"^(.*?)\s*[\[(]\s*([^\])]*?)\s*[\])]\s*$")


def normalise(name: str) -> str:
    """Lower case; primes, δ and ω spelled out; spaces and ``_-.()|`` removed."""
    s = name.strip().lower()
    for a, b in (("″", "''"), ('"', "''"), ("′", "'"), ("’", "'"), ("‘", "'"), ("`", "'"),
                 ("δ", "delta"), ("ω", "omega")):
        s = s.replace(a, b)
    return re.sub(r"[\s_\-.()|]", "", s)


def role(name: str) -> str | None:
    """The role (one of :data:`ROLES`) of a column name without its unit, or ``None``."""
    key = normalise(name)
    for r, names in _NAMES.items():
        if key in names:
            return r
    m = _MODULUS.fullmatch(key)
    if m is None:
        return None
    before, words, after, marks = m.groups()
    if before and after and before != after:
        return None
    quantities = {_QUANTITY[q] for q in (words, marks) if q}
    if len(quantities) != 1:        # neither said (a bare "E", "modulus") or contradictory
        return None
    return (before or after or "m").upper() + quantities.pop()


def is_unit(text: str) -> bool:
    """True when ``text`` is a unit of one of the tables here (not the dimensionless ones)."""
    key = text.strip().lower().replace(" ", "")
    return bool(key) and (key in ANGULAR_UNITS or key in MOD_UNITS or key in TEMP_UNITS)


def split_unit(cell: str) -> tuple[str, str | None]:
    """``(name, unit)`` of a header cell; ``unit`` is ``None`` when the cell states none.

    A cell that is a known name as a whole is not split (``Tan(delta)`` is no unit
    ``delta``); a slash or a suffix splits only off a known unit from a known name.
    """
    cell = cell.strip()
    if role(cell) is not None:
        return cell, None
    m = _BRACKETS.match(cell)
    if m:
        return m.group(1), m.group(2)
    for i, ch in enumerate(cell):          # "E'/MPa", "Frequency/Hz", "omega/rad/s"
        if ch == "/" and role(cell[:i]) is not None and is_unit(cell[i + 1:]):
            return cell[:i].strip(), cell[i + 1:].strip()
    parts = re.split(r"[\s_]+", cell)
    if len(parts) >= 3 and parts[-2].lower() == "rad" and parts[-1].lower() in ("s", "sec"):
        return " ".join(parts[:-2]), "rad/s"          # "omega_rad_s"
    if len(parts) >= 2 and is_unit(parts[-1]) and role(" ".join(parts[:-1])) is not None:
        return " ".join(parts[:-1]), parts[-1]        # "frequency_Hz", "E_storage_MPa"
    return cell, None


def unit(text: str, table: dict, what: str):
    """The entry of ``table`` for a unit (spaces and case ignored), else one error line."""
    key = text.strip().lower().replace(" ", "")
    if key not in table:
        names = sorted({v[0] if isinstance(v, tuple) else v for v in table.values()})
        raise InputError(f"{what}: unknown unit {text!r}; expected one of {names}")
    return table[key]
