"""DMA data in memory: :class:`DMAData` (storage and loss moduli against frequency).

Frequencies are angular [rad/s], moduli Young's [MPa]. :meth:`DMAData.to_csv` writes the
CSV convention that :func:`~rubbercontact.materials.read_dma` reads (module
:mod:`rubbercontact.materials.dma`); :func:`dma_from_material` gives the (noisy) data of a
Prony series.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from .._validation import finite_array
from ..errors import InputError
from .shift import ShiftLaw, shift_law_from_dict

__all__ = ["DMAData", "DMAWarning", "dma_from_material"]

_FREQ_UNITS = {"hz": ("Hz", 2 * np.pi), "rad/s": ("rad/s", 1.0)}
_MOD_UNITS = {"pa": ("Pa", 1e-6), "kpa": ("kPa", 1e-3), "mpa": ("MPa", 1.0),
              "gpa": ("GPa", 1e3), "n/mm2": ("MPa", 1.0), "n/mm²": ("MPa", 1.0)}


class DMAWarning(UserWarning):
    """DMA data that a Prony series cannot represent well (see the message)."""


@dataclass(frozen=True, eq=False)
class DMAData:
    """Storage and loss Young's moduli against angular frequency.

    Parameters
    ----------
    frequency
        Angular frequencies ``ω`` [rad/s], > 0.
    storage, loss
        ``E'(ω)`` and ``E''(ω)`` [MPa], both > 0 (a viscoelastic solid dissipates at every
        ``ω > 0``).
    temperature
        Reference temperature of the (master) curve [°C], or None if not stated.
    temperatures
        Optional per-point measuring temperature [°C] (isothermal sweeps).
    shift
        Optional shift law of the master curve (its ``t_ref`` must equal ``temperature``).
    source
        Where the data came from (file path, or a description).
    frequency_unit
        Unit the source used (``"Hz"`` or ``"rad/s"``), for display only.
    provenance
        How the data were read (columns, units, conversions, file hash).

    Points are sorted by (temperature, frequency).
    """

    frequency: np.ndarray
    storage: np.ndarray
    loss: np.ndarray
    temperature: float | None = None
    temperatures: np.ndarray | None = None
    shift: ShiftLaw | None = None
    source: str = ""
    frequency_unit: str = "rad/s"
    provenance: Mapping = field(default_factory=dict)

    def __post_init__(self) -> None:
        w = finite_array("frequency", self.frequency, ndim=1)
        e1 = finite_array("storage", self.storage, ndim=1)
        e2 = finite_array("loss", self.loss, ndim=1)
        if not (w.size == e1.size == e2.size):
            raise InputError(f"frequency, storage, loss: lengths differ "
                             f"({w.size}, {e1.size}, {e2.size})")
        for name, arr, unit in (("frequency", w, "rad/s"), ("storage", e1, "MPa"),
                                ("loss", e2, "MPa")):
            if np.any(arr <= 0):
                i = int(np.argmax(arr <= 0))
                raise InputError(f"{name}: must be > 0 {unit}, got {arr[i]:g} at point {i}")
        temps = None
        if self.temperatures is not None:
            temps = finite_array("temperatures", self.temperatures, ndim=1)
            if temps.size != w.size:
                raise InputError(f"temperatures: {temps.size} values for {w.size} points")
        t_ref = None if self.temperature is None else float(self.temperature)
        law = None if self.shift is None else shift_law_from_dict(self.shift)
        if law is not None:
            if t_ref is None:
                t_ref = law.t_ref
            elif abs(law.t_ref - t_ref) > 1e-9:
                raise InputError(f"shift: t_ref {law.t_ref:g} °C differs from the data's "
                                 f"reference temperature {t_ref:g} °C")
        order = np.lexsort((w, temps if temps is not None else np.zeros_like(w)))
        for name, arr in (("frequency", w), ("storage", e1), ("loss", e2),
                          ("temperatures", temps)):
            if arr is not None:
                arr = arr[order]
                arr.setflags(write=False)
                object.__setattr__(self, name, arr)
        object.__setattr__(self, "temperature", t_ref)
        object.__setattr__(self, "shift", law)
        object.__setattr__(self, "provenance", dict(self.provenance))

    # -- views ------------------------------------------------------------------------
    @property
    def n_points(self) -> int:
        return int(self.frequency.size)

    @property
    def complex_modulus(self) -> np.ndarray:
        """``E* = E' + iE''`` [MPa]."""
        return self.storage + 1j * self.loss

    @property
    def loss_tangent(self) -> np.ndarray:
        """``tan δ = E''/E'`` [-]."""
        return self.loss / self.storage

    @property
    def isotherm_temperatures(self) -> np.ndarray:
        """Distinct measuring temperatures [°C] (empty without a temperature column)."""
        return np.zeros(0) if self.temperatures is None else np.unique(self.temperatures)

    @property
    def is_isothermal(self) -> bool:
        """True unless the data hold sweeps at more than one temperature."""
        return self.isotherm_temperatures.size <= 1

    def isotherms(self) -> list[DMAData]:
        """One :class:`DMAData` per measuring temperature, coldest first."""
        if self.temperatures is None:
            return [self]
        out = []
        for t in self.isotherm_temperatures:
            sel = self.temperatures == t
            out.append(replace(self, frequency=self.frequency[sel], storage=self.storage[sel],
                               loss=self.loss[sel], temperatures=None, temperature=float(t),
                               shift=None))
        return out

    def to_csv(self, path: str | Path, *, frequency_unit: str = "Hz",
               modulus_unit: str = "MPa", header: str = "") -> Path:
        """Write ``frequency, E', E''`` (and ``T``) with units in the header."""
        fu = _unit(frequency_unit, _FREQ_UNITS, "frequency_unit")
        mu = _unit(modulus_unit, _MOD_UNITS, "modulus_unit")
        cols = [f"frequency [{fu[0]}]", f"E_storage [{mu[0]}]", f"E_loss [{mu[0]}]"]
        data = [self.frequency / fu[1], self.storage / mu[1], self.loss / mu[1]]
        if self.temperatures is not None:
            cols.append("temperature [°C]")
            data.append(self.temperatures)
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        lines = [f"# {ln}" for ln in header.splitlines()] + [",".join(cols)]
        lines += [",".join(f"{v:.10g}" for v in row) for row in zip(*data, strict=True)]
        path.write_text("\n".join(lines) + "\n", encoding="utf-8")
        return path

    def physical_problems(self, tolerance: float = 0.03) -> list[str]:
        """What a Prony series cannot represent: ``E'`` falling with frequency.

        A generalized Maxwell solid has ``E'`` rising monotonically with ``ω``. Within each
        isotherm, ``E'`` smoothed by a 5-point running median is compared with its running
        maximum from low frequency; a fall of more than ``max(tolerance, 5 σ)`` is
        reported, where ``tolerance`` is 3 % by default and ``σ`` is the data's relative
        scatter, estimated from the median absolute second difference of ``log E'``.
        """
        problems = []
        for iso in self.isotherms():
            log_e = np.log(iso.storage)
            if log_e.size < 3:
                continue
            scatter = float(np.median(np.abs(np.diff(log_e, 2)))) / 0.6745 / np.sqrt(6.0)
            smooth = np.array([np.median(log_e[max(i - 2, 0):i + 3])
                               for i in range(log_e.size)])
            drop = 1.0 - np.exp(smooth - np.maximum.accumulate(smooth))
            k = int(np.argmax(drop))
            limit = max(tolerance, 5.0 * scatter)
            if drop[k] > limit:
                j = int(np.argmax(smooth[:k + 1]))
                at = "" if iso is self else f" at {iso.temperature:g} °C"
                problems.append(
                    f"E' falls by {100 * drop[k]:.1f} % (> {100 * limit:.1f} %, the scatter "
                    f"allowance) between ω = {iso.frequency[j]:.4g} and "
                    f"{iso.frequency[k]:.4g} rad/s{at}; a Prony series needs E' rising with "
                    f"frequency: check the shift factors and units")
        return problems


def _unit(text: str, table: dict, what: str):
    key = text.strip().lower().replace(" ", "")
    if key not in table:
        names = sorted({v[0] if isinstance(v, tuple) else v for v in table.values()})
        raise InputError(f"{what}: unknown unit {text!r}; expected one of {names}")
    return table[key]


def dma_from_material(material, frequency, *, noise: float = 0.0, seed: int | None = None,
                      temperature: float | None = None, frequency_unit: str = "rad/s",
                      source: str = "") -> DMAData:
    """Synthetic DMA data of a Prony series, with optional multiplicative Gaussian noise.

    ``E'`` and ``E''`` are each multiplied by independent ``1 + noise·N(0, 1)`` factors.

    Parameters
    ----------
    material
        :class:`~rubbercontact.materials.GeneralizedMaxwell`.
    frequency
        Angular frequencies [rad/s].
    noise
        Relative standard deviation of the noise [-], >= 0 (e.g. 0.005 for 0.5 %).
    seed
        Seed of ``numpy.random.default_rng``.
    """
    w = finite_array("frequency", frequency, ndim=1)
    if not 0.0 <= float(noise) < 0.3:
        raise InputError(f"noise: relative noise must lie in [0, 0.3), got {noise}")
    e = material.complex_modulus(w)
    rng = np.random.default_rng(seed)
    f1 = 1.0 + noise * rng.standard_normal(w.size)
    f2 = 1.0 + noise * rng.standard_normal(w.size)
    return DMAData(w, e.real * f1, e.imag * f2, temperature=temperature,
                   shift=getattr(material, "shift", None),
                   source=source or f"synthetic from {material.name}, noise {noise:g}",
                   frequency_unit=frequency_unit,
                   provenance={"synthetic": material.name, "noise": float(noise),
                               "seed": -1 if seed is None else int(seed)})
