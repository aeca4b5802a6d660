"""Time–temperature superposition: horizontal shift factors ``a_T``.

Temperatures are in °C, activation energies in J/mol. The shift factor is the ratio of
relaxation times, ``a_T = τ(T)/τ(T_ref)``, so a material at ``T`` has
``E_T(ω) = E_ref(a_T ω)``; ``a_T < 1`` above ``T_ref`` (faster relaxation).

Both laws are frozen dataclasses with ``log10_shift(T)``, ``shift(T)``, ``rereferenced(T0)``
(the same law referred to another temperature) and ``as_dict()``;
:func:`shift_law_from_dict` reads the plain-data form back.
"""

from __future__ import annotations

import numbers
from dataclasses import dataclass

import numpy as np

from ..errors import InputError

#: Molar gas constant [J/(mol K)] (CODATA 2018, exact).
GAS_CONSTANT = 8.314462618
#: 0 °C in kelvin.
ZERO_CELSIUS = 273.15


def _number(name: str, value, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise InputError(f"{name}: expected a number in {unit}, got {value!r}")
    v = float(value)
    if not np.isfinite(v):
        raise InputError(f"{name}: must be finite, got {v} {unit}")
    return v


def _temperatures(name: str, value) -> np.ndarray:
    try:
        t = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected temperature(s) in °C, got {value!r}") from None
    if not np.all(np.isfinite(t)):
        raise InputError(f"{name}: temperatures must be finite, got {value!r} °C")
    if np.any(t <= -ZERO_CELSIUS):
        raise InputError(f"{name}: temperature below absolute zero ({t.min():g} °C)")
    return t


def _scalar_or_array(x: np.ndarray):
    return float(x) if x.ndim == 0 else x


def _power(log10_a, law: str):
    log10_a = np.asarray(log10_a)
    if np.any(np.abs(log10_a) > 300):
        worst = float(log10_a.flat[np.argmax(np.abs(log10_a))])
        raise InputError(f"temperature: the {law} shift factor a_T = 10^{worst:.4g} "
                         f"overflows; the law is far outside its range there")
    return _scalar_or_array(10.0**log10_a)


@dataclass(frozen=True)
class WLF:
    """Williams–Landel–Ferry shift: ``log10 a_T = −C1 (T − T_ref) / (C2 + T − T_ref)``.

    Parameters
    ----------
    c1
        ``C1`` [-], > 0.
    c2
        ``C2`` [K] (= °C difference), > 0.
    t_ref
        Reference temperature ``T_ref`` [°C].

    Notes
    -----
    The law is singular at ``T = T_ref − C2`` and meaningless below it: asking for such a
    temperature raises :class:`~rubbercontact.errors.InputError`. WLF describes polymers
    from about their glass transition to ~100 K above it.
    """

    c1: float
    c2: float
    t_ref: float

    def __post_init__(self) -> None:
        c1 = _number("c1", self.c1, "-")
        c2 = _number("c2", self.c2, "K")
        if c1 <= 0:
            raise InputError(f"c1: WLF C1 must be > 0, got {c1}")
        if c2 <= 0:
            raise InputError(f"c2: WLF C2 must be > 0 K, got {c2}")
        t_ref = float(_temperatures("t_ref", _number("t_ref", self.t_ref, "°C")))
        object.__setattr__(self, "c1", c1)
        object.__setattr__(self, "c2", c2)
        object.__setattr__(self, "t_ref", t_ref)

    @property
    def singular_temperature(self) -> float:
        """``T_ref − C2`` [°C]: the law diverges there."""
        return self.t_ref - self.c2

    def log10_shift(self, temperature):
        """``log10 a_T`` [-] at ``temperature`` [°C] (scalar or array)."""
        t = _temperatures("temperature", temperature)
        dt = t - self.t_ref
        if np.any(self.c2 + dt <= 0):
            raise InputError(f"temperature: {t.min():g} °C is at or below the WLF singularity "
                             f"T_ref − C2 = {self.singular_temperature:g} °C")
        return _scalar_or_array(-self.c1 * dt / (self.c2 + dt))

    def shift(self, temperature):
        """``a_T = τ(T)/τ(T_ref)`` [-] at ``temperature`` [°C]."""
        return _power(self.log10_shift(temperature), "WLF")

    def rereferenced(self, t_ref: float) -> WLF:
        """The same law referred to ``t_ref`` [°C]: ``C1' = C1 C2/(C2 + ΔT)``, ``C2' = C2 + ΔT``.

        With ``ΔT = t_ref − T_ref``; ``a'_T = a_T / a_{t_ref}`` at every temperature.
        """
        self.log10_shift(t_ref)  # validity
        dt = float(t_ref) - self.t_ref
        return WLF(self.c1 * self.c2 / (self.c2 + dt), self.c2 + dt, float(t_ref))

    def as_dict(self) -> dict:
        return {"law": "WLF", "c1": self.c1, "c2": self.c2, "t_ref": self.t_ref}


@dataclass(frozen=True)
class Arrhenius:
    """Arrhenius shift: ``ln a_T = (E_a/R) (1/T − 1/T_ref)``, temperatures in kelvin.

    Parameters
    ----------
    activation_energy
        ``E_a`` [J/mol], > 0.
    t_ref
        Reference temperature ``T_ref`` [°C] (converted with ``T[K] = T[°C] + 273.15``).
    """

    activation_energy: float
    t_ref: float

    def __post_init__(self) -> None:
        ea = _number("activation_energy", self.activation_energy, "J/mol")
        if ea <= 0:
            raise InputError(f"activation_energy: must be > 0 J/mol, got {ea}")
        t_ref = float(_temperatures("t_ref", _number("t_ref", self.t_ref, "°C")))
        object.__setattr__(self, "activation_energy", ea)
        object.__setattr__(self, "t_ref", t_ref)

    def log10_shift(self, temperature):
        """``log10 a_T`` [-] at ``temperature`` [°C] (scalar or array)."""
        t = _temperatures("temperature", temperature) + ZERO_CELSIUS
        ln_a = self.activation_energy / GAS_CONSTANT * (1.0 / t - 1.0 / (self.t_ref
                                                                         + ZERO_CELSIUS))
        return _scalar_or_array(ln_a / np.log(10.0))

    def shift(self, temperature):
        """``a_T = τ(T)/τ(T_ref)`` [-] at ``temperature`` [°C]."""
        return _power(self.log10_shift(temperature), "Arrhenius")

    def rereferenced(self, t_ref: float) -> Arrhenius:
        """The same law referred to ``t_ref`` [°C] (same activation energy)."""
        return Arrhenius(self.activation_energy, float(t_ref))

    def as_dict(self) -> dict:
        return {"law": "Arrhenius", "activation_energy": self.activation_energy,
                "t_ref": self.t_ref}


ShiftLaw = WLF | Arrhenius


def shift_law_from_dict(data) -> ShiftLaw:
    """Rebuild a shift law from its :meth:`as_dict` form (``{"law": "WLF", ...}``)."""
    if isinstance(data, WLF | Arrhenius):
        return data
    if not isinstance(data, dict):
        raise InputError(f"shift: expected a WLF/Arrhenius law or a table with 'law', "
                         f"got {data!r}")
    kind = str(data.get("law", "")).lower()
    fields = {"wlf": ("c1", "c2", "t_ref"), "arrhenius": ("activation_energy", "t_ref")}
    if kind not in fields:
        raise InputError(f"shift.law: expected 'WLF' or 'Arrhenius', got {data.get('law')!r}")
    keys = set(data) - {"law"}
    if keys != set(fields[kind]):
        raise InputError(f"shift: a {data['law']} law takes exactly {list(fields[kind])}, "
                         f"got {sorted(keys)}")
    cls = WLF if kind == "wlf" else Arrhenius
    return cls(**{k: data[k] for k in fields[kind]})
