"""One material from a plain-data spec (a config's ``[material]`` table).

Exactly one source:

* ``preset = "sbr"``;
* ``file = "fitted.toml"`` (a Prony table, TOML or CSV; see
  :meth:`GeneralizedMaxwell.from_file`);
* ``dma = "dma.csv"`` (fitted with :func:`fit_prony`; isothermal sweeps are first built
  into a master curve), with optional ``frequency_unit``, ``modulus_unit``, ``modulus``
  (``"E"``/``"G"`` for columns named without the letter), ``terms``,
  ``tolerance``;
* inline ``equilibrium_modulus``, ``moduli``, ``relaxation_times`` [MPa, s].

Optional: ``reference_temperature`` [°C] and a ``shift`` table (``law = "WLF"``, ``c1``,
``c2`` [K], or ``law = "Arrhenius"``, ``activation_energy`` [J/mol]; its ``t_ref``
defaults to ``reference_temperature``), attached to the material so that
``material.at_temperature(T)`` works. Relative paths are taken from ``base_dir``.

Optional ``thermal`` table: the compound's ``conductivity`` [W/(m·K)], ``density`` [kg/m³],
``specific_heat`` [J/(kg·K)] (and ``source``), read by :func:`load_thermal` (missing values
take the filled-SBR defaults of :mod:`rubbercontact.thermal.properties`, which states the
conversion into mm, MPa, s: ``K`` is the same number in mW/(mm·K), ``ρc`` × 1e-6 in MPa/K).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from ..errors import InputError
from ..thermal.properties import ThermalProperties
from .dma import read_dma
from .fit import fit_prony
from .master import master_curve
from .maxwell import GeneralizedMaxwell, sbr
from .shift import shift_law_from_dict

_SOURCES = ("preset", "file", "dma", "equilibrium_modulus")
_KEYS = set(_SOURCES) | {"moduli", "relaxation_times", "name", "frequency_unit",
                         "modulus_unit", "modulus", "terms", "tolerance",
                         "reference_temperature", "shift", "thermal"}
_DMA_ONLY = ("frequency_unit", "modulus_unit", "modulus", "terms", "tolerance")


def _shift(spec: Mapping, t_ref: float | None):
    raw = spec.get("shift")
    if raw is None:
        return None
    if not isinstance(raw, Mapping):
        raise InputError(f"material.shift: expected a table, got {raw!r}")
    raw = dict(raw)
    if "t_ref" not in raw:
        if t_ref is None:
            raise InputError("material.shift: give t_ref or material.reference_temperature")
        raw["t_ref"] = t_ref
    elif t_ref is not None and float(raw["t_ref"]) != float(t_ref):
        raise InputError(f"material.shift.t_ref {raw['t_ref']} differs from "
                         f"material.reference_temperature {t_ref}")
    return shift_law_from_dict(raw)


def load_thermal(spec: Mapping) -> ThermalProperties:
    """The compound's thermal properties from a ``[material]`` table's ``thermal`` table
    (the filled-SBR defaults without one; keys in the module docstring)."""
    return ThermalProperties.from_dict(spec.get("thermal"))


def load_material(spec: Mapping, *, base_dir: str | Path | None = None) -> GeneralizedMaxwell:
    """Build the material a ``[material]`` table describes (keys in the module docstring).

    Raises
    ------
    InputError
        Unknown keys, none or several sources, DMA-only keys without ``dma``, and every
        error of the reader, the fit and the shift law (one line, key named).
    """
    unknown = set(spec) - _KEYS
    if unknown:
        raise InputError(f"material: unknown key(s) {sorted(unknown)}")
    given = [k for k in _SOURCES if spec.get(k) is not None]
    if len(given) != 1:
        raise InputError(f"material: give exactly one of {list(_SOURCES)}, got {given}")
    source = given[0]
    if source != "dma" and any(k in spec for k in _DMA_ONLY):
        raise InputError(f"material: {[k for k in _DMA_ONLY if k in spec]} apply to "
                         f"'dma' only")
    t_ref = spec.get("reference_temperature")
    t_ref = None if t_ref is None else float(t_ref)
    law = _shift(spec, t_ref)
    base = Path(base_dir) if base_dir is not None else Path.cwd()
    if source == "preset":
        if spec["preset"] != "sbr":
            raise InputError(f"material.preset: expected 'sbr', got {spec['preset']!r}")
        mat = sbr()
    elif source == "file":
        mat = GeneralizedMaxwell.from_file(base / spec["file"])
    elif source == "equilibrium_modulus":
        mat = GeneralizedMaxwell(spec["equilibrium_modulus"], spec.get("moduli", []),
                                 spec.get("relaxation_times", []),
                                 name=spec.get("name", "config"))
    else:
        dma = read_dma(base / spec["dma"], spec.get("frequency_unit"), t_ref,
                       modulus_unit=spec.get("modulus_unit"), shift=law,
                       modulus=spec.get("modulus"))
        if not dma.is_isothermal:
            if law is not None:
                raise InputError("material.shift: isothermal sweeps get their shift law "
                                 "fitted; remove material.shift")
            dma = master_curve(dma).data
        mat = fit_prony(dma, spec.get("terms"), tolerance=spec.get("tolerance", 0.01),
                        name=spec.get("name"))
    if law is not None and mat.shift != law:
        mat = GeneralizedMaxwell(mat.equilibrium_modulus, mat.moduli, mat.relaxation_times,
                                 name=mat.name, shift=law, provenance=mat.provenance)
    return mat
