"""Thermal properties of the rubber compound, and their units in the package's system.

The package measures length in mm, stress in MPa and time in s; its energy unit is then
``MPa·mm³ = N·mm = mJ`` and its power unit ``mJ/s = mW``. The properties are given in the
SI units of every handbook and converted here:

* conductivity ``K``: ``1 W/(m·K) = 1 mW/(mm·K) = 1 MPa·mm²/(s·K)`` (the same number);
* volumetric heat capacity ``ρc``: ``1 J/(m³·K) = 10⁻⁶ mJ/(mm³·K) = 10⁻⁶ MPa/K``;
* diffusivity ``D = K/(ρc)``: ``1 m²/s = 10⁶ mm²/s``.

Defaults (:data:`FILLED_SBR`): a carbon-black-filled SBR tread compound, ``K = 0.25 W/(m·K)``,
``ρ = 1150 kg/m³``, ``c = 1800 J/(kg·K)`` (so ``D = 0.121 mm²/s``). Typical ranges for
filled tread compounds are 0.2–0.3 W/(m·K), 1100–1250 kg/m³ and 1.6–2.0 kJ/(kg·K) near room
temperature (e.g. J. E. Mark (ed.), *Physical Properties of Polymers Handbook*, 2nd ed.,
Springer 2007, chapters on thermal conductivity and heat capacity; the carbon black raises
the conductivity of the gum, ≈ 0.19 W/(m·K), and lowers its specific heat). They are
representative, not measured on the paper's SBR; give the compound's own values when known.
"""

from __future__ import annotations

import numbers
from collections.abc import Mapping
from dataclasses import dataclass

from ..errors import InputError

#: ``1 J/(m³·K)`` in the package's ``MPa/K`` (= ``mJ/(mm³·K)``).
VOLUMETRIC_HEAT_SI_TO_PACKAGE = 1e-6
#: ``1 W/(m·K)`` in the package's ``mW/(mm·K)`` (= ``MPa·mm²/(s·K)``).
CONDUCTIVITY_SI_TO_PACKAGE = 1.0

_KEYS = ("conductivity", "density", "specific_heat")
_UNITS = {"conductivity": "W/(m·K)", "density": "kg/m³", "specific_heat": "J/(kg·K)"}


def _positive(name: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InputError(f"thermal.{name}: expected a number in {_UNITS[name]}, got {value!r}")
    v = float(value)
    if not (v > 0 and v < float("inf")):
        raise InputError(f"thermal.{name}: must be finite and > 0 {_UNITS[name]}, got {v}")
    return v


@dataclass(frozen=True)
class ThermalProperties:
    """Heat conduction in the rubber (SI inputs, package-unit properties).

    Parameters
    ----------
    conductivity
        Thermal conductivity ``K`` [W/(m·K)], > 0.
    density
        Density ``ρ`` [kg/m³], > 0.
    specific_heat
        Specific heat ``c`` [J/(kg·K)], > 0.
    source
        Where the values come from (carried into results' provenance).
    """

    conductivity: float = 0.25
    density: float = 1150.0
    specific_heat: float = 1800.0
    source: str = ("typical carbon-black-filled SBR tread compound (Mark, Physical "
                   "Properties of Polymers Handbook, 2007)")

    def __post_init__(self) -> None:
        for name in _KEYS:
            object.__setattr__(self, name, _positive(name, getattr(self, name)))
        if not isinstance(self.source, str):
            raise InputError(f"thermal.source: expected a string, got {self.source!r}")

    @property
    def conductivity_package(self) -> float:
        """``K`` [mW/(mm·K)] = [MPa·mm²/(s·K)]."""
        return self.conductivity * CONDUCTIVITY_SI_TO_PACKAGE

    @property
    def volumetric_heat_capacity(self) -> float:
        """``ρc`` [MPa/K] = [mJ/(mm³·K)]."""
        return self.density * self.specific_heat * VOLUMETRIC_HEAT_SI_TO_PACKAGE

    @property
    def diffusivity(self) -> float:
        """``D = K/(ρc)`` [mm²/s]."""
        return self.conductivity_package / self.volumetric_heat_capacity

    def as_dict(self) -> dict:
        """Plain data in the input (SI) units, with the diffusivity [mm²/s] for reading."""
        return {"conductivity": self.conductivity, "density": self.density,
                "specific_heat": self.specific_heat, "source": self.source,
                "diffusivity_mm2_per_s": self.diffusivity}

    @classmethod
    def from_dict(cls, data: Mapping | None) -> ThermalProperties:
        """Read a ``[material.thermal]`` table (keys ``conductivity``, ``density``,
        ``specific_heat``, ``source``; the missing ones take the filled-SBR defaults)."""
        if data is None:
            return cls()
        if not isinstance(data, Mapping):
            raise InputError(f"material.thermal: expected a table, got {data!r}")
        known = set(_KEYS) | {"source", "diffusivity_mm2_per_s"}
        unknown = set(data) - known
        if unknown:
            raise InputError(f"material.thermal: unknown key(s) {sorted(unknown)}; expected "
                             f"{list(_KEYS) + ['source']}")
        given = {k: data[k] for k in (*_KEYS, "source") if k in data}
        if "source" not in given and any(k in given for k in _KEYS):
            given["source"] = "given"
        out = cls(**given)
        if "diffusivity_mm2_per_s" in data and abs(
                float(data["diffusivity_mm2_per_s"]) - out.diffusivity) > 1e-9 * out.diffusivity:
            raise InputError("material.thermal.diffusivity_mm2_per_s: differs from "
                             "conductivity/(density·specific_heat); give the three only")
        return out


#: The default compound (module docstring).
FILLED_SBR = ThermalProperties()
