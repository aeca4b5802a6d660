"""Generalized Maxwell (Prony series) viscoelastic solid.

Moduli are Young's moduli in MPa, relaxation times in s, angular frequencies
in rad/s. The complex modulus follows the engineering convention
``σ(t) = Re[E(ω) ε̂ e^{iωt}]`` so that the loss modulus ``E''(ω) >= 0`` for
``ω > 0`` and ``E(-ω) = conj(E(ω))``.
"""

from __future__ import annotations

import csv
import numbers
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

import numpy as np

from .._validation import finite_array, positive_scalar
from ..errors import InputError
from .shift import ZERO_CELSIUS, ShiftLaw, shift_law_from_dict

_TOML_KEYS = {"equilibrium_modulus", "moduli", "relaxation_times", "name", "shift", "provenance"}


@dataclass(frozen=True)
class GeneralizedMaxwell:
    """Equilibrium spring in parallel with Maxwell branches ``(E_i, τ_i)``.

    Parameters
    ----------
    equilibrium_modulus
        Rubbery (long-time) Young's modulus ``E_∞`` [MPa], > 0.
    moduli
        Branch Young's moduli ``E_i`` [MPa], each > 0.
    relaxation_times
        Branch relaxation times ``τ_i`` [s], each > 0 and distinct.
    name
        Label used in results and plots.
    shift
        Optional time–temperature shift law (:class:`~rubbercontact.materials.WLF` or
        :class:`~rubbercontact.materials.Arrhenius`, or its ``as_dict()`` form) whose
        ``t_ref`` is the temperature this series describes; lets :meth:`at_temperature`
        work without ``shift=``.
    provenance
        Optional plain data (strings, numbers, booleans, lists, tables) saying where the
        series came from: source file, fit report, ... (see
        :func:`~rubbercontact.materials.fit_prony`). Stored read-only; not part of equality.

    Notes
    -----
    ``E(ω) = E_∞ + Σ_i E_i · iωτ_i / (1 + iωτ_i)``;
    relaxation modulus ``E(t) = E_∞ + Σ_i E_i exp(−t/τ_i)``.
    An empty series is a purely elastic material.
    :meth:`as_dict` holds ``shift`` and ``provenance`` only when they are set, so a material
    without them has the same plain-data form (and cache keys) as before they existed.
    """

    equilibrium_modulus: float
    moduli: np.ndarray = field(default_factory=lambda: np.zeros(0))
    relaxation_times: np.ndarray = field(default_factory=lambda: np.zeros(0))
    name: str = "generalized Maxwell"
    shift: ShiftLaw | None = None
    provenance: Mapping | None = None

    def __post_init__(self) -> None:
        e_inf = positive_scalar("equilibrium_modulus", self.equilibrium_modulus, unit="MPa")
        moduli = finite_array("moduli", self.moduli, ndim=1, min_size=0).copy()
        times = finite_array("relaxation_times", self.relaxation_times, ndim=1, min_size=0).copy()
        if moduli.shape != times.shape:
            raise InputError(f"moduli and relaxation_times: lengths differ "
                             f"({moduli.size} vs {times.size})")
        for i, (e, t) in enumerate(zip(moduli, times, strict=True)):
            if e <= 0:
                raise InputError(f"moduli[{i}]: must be > 0 MPa, got {e}")
            if t <= 0:
                raise InputError(f"relaxation_times[{i}]: must be > 0 s, got {t}")
        if np.unique(times).size != times.size:
            raise InputError("relaxation_times: duplicate values; merge branches with "
                             "equal times into one")
        moduli.setflags(write=False)
        times.setflags(write=False)
        if self.shift is not None:
            object.__setattr__(self, "shift", shift_law_from_dict(self.shift))
        if self.provenance is not None:
            if not isinstance(self.provenance, Mapping):
                raise InputError(f"provenance: expected a table (dict), got "
                                 f"{type(self.provenance).__name__}")
            object.__setattr__(self, "provenance", _freeze("provenance", self.provenance))
        object.__setattr__(self, "equilibrium_modulus", e_inf)
        object.__setattr__(self, "moduli", moduli)
        object.__setattr__(self, "relaxation_times", times)

    # -- constructors -----------------------------------------------------------------
    @classmethod
    def elastic(cls, modulus: float) -> GeneralizedMaxwell:
        """A purely elastic material of Young's modulus ``modulus`` [MPa]."""
        return cls(modulus, name="elastic")

    @classmethod
    def from_file(cls, path: str | Path) -> GeneralizedMaxwell:
        """Read a Prony table from TOML or CSV.

        TOML: ``equilibrium_modulus = 4.17`` and ``moduli = [...]``,
        ``relaxation_times = [...]`` (optionally ``name``, a ``[shift]`` table such as
        ``law = "WLF"``, ``c1``, ``c2``, ``t_ref``, and a ``[provenance]`` table), as
        :meth:`to_toml` writes it.
        CSV: two columns ``modulus, relaxation_time`` with an optional header; the
        row whose relaxation time is empty, ``inf`` or ``-`` is the equilibrium spring.
        """
        path = Path(path)
        if not path.is_file():
            raise InputError(f"material file {path}: not found")
        if path.suffix.lower() == ".toml":
            try:
                data = tomllib.loads(path.read_text())
            except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
                raise InputError(f"material file {path}: not valid TOML ({exc})") from None
            unknown = set(data) - _TOML_KEYS
            if unknown:
                raise InputError(f"material file {path}: unknown key(s) {sorted(unknown)}")
            if "equilibrium_modulus" not in data:
                raise InputError(f"material file {path}: missing key 'equilibrium_modulus'")
            try:
                return cls(data["equilibrium_modulus"], data.get("moduli", []),
                           data.get("relaxation_times", []), name=data.get("name", path.stem),
                           shift=data.get("shift"), provenance=data.get("provenance"))
            except InputError as exc:
                raise InputError(f"material file {path}: {exc}") from None
        return cls._from_csv(path)

    def to_toml(self, path: str | Path) -> Path:
        """Write the series (with its shift law and provenance) to a TOML file.

        :meth:`from_file` reads it back to a material with the same :meth:`as_dict`
        (floats are written in their shortest exact form). Returns the path.
        """
        from ._toml import dumps

        path = Path(path)
        if path.suffix.lower() != ".toml":
            raise InputError(f"material file {path}: expected a .toml extension")
        path.parent.mkdir(parents=True, exist_ok=True)
        header = "# Generalized Maxwell (Prony) series: moduli [MPa], relaxation times [s]\n"
        if self.shift is not None:
            header += "# shift: temperatures in °C, activation energy in J/mol\n"
        path.write_text(header + dumps(self.as_dict()), encoding="utf-8")
        return path

    @classmethod
    def _from_csv(cls, path: Path) -> GeneralizedMaxwell:
        e_inf = None
        moduli, times = [], []
        try:
            rows = list(csv.reader(path.read_text().splitlines()))
        except UnicodeDecodeError as exc:
            raise InputError(f"material file {path}: not a text file ({exc})") from None
        for lineno, row in enumerate(rows, start=1):
            cells = [c.strip() for c in row if c.strip() != ""]
            if not cells or cells[0].startswith("#"):
                continue
            try:
                e = float(cells[0])
            except ValueError:
                if lineno == 1 or not moduli:
                    continue  # header line
                raise InputError(f"material file {path}, line {lineno}: "
                                 f"modulus {cells[0]!r} is not a number") from None
            tau_txt = cells[1] if len(cells) > 1 else ""
            if tau_txt.lower() in ("", "inf", "-", "—", "eq", "equilibrium"):
                if e_inf is not None:
                    raise InputError(f"material file {path}, line {lineno}: "
                                     f"second equilibrium modulus")
                e_inf = e
                continue
            try:
                times.append(float(tau_txt))
            except ValueError:
                raise InputError(f"material file {path}, line {lineno}: relaxation time "
                                 f"{tau_txt!r} is not a number") from None
            moduli.append(e)
        if e_inf is None:
            raise InputError(f"material file {path}: no equilibrium modulus row "
                             f"(a row with an empty relaxation time)")
        return cls(e_inf, moduli, times, name=path.stem)

    # -- properties -------------------------------------------------------------------
    @property
    def n_branches(self) -> int:
        return int(self.moduli.size)

    @property
    def rubbery_modulus(self) -> float:
        """``E(ω→0) = E_∞`` [MPa]."""
        return self.equilibrium_modulus

    @property
    def glassy_modulus(self) -> float:
        """``E(ω→∞) = E_∞ + Σ E_i`` [MPa]."""
        return float(self.equilibrium_modulus + self.moduli.sum())

    @property
    def is_elastic(self) -> bool:
        return self.n_branches == 0

    def complex_modulus(self, omega) -> np.ndarray:
        """Complex Young's modulus ``E(ω)`` [MPa] at angular frequency ``omega`` [rad/s]."""
        w = np.asarray(omega, dtype=float)
        iwt = 1j * w[..., None] * self.relaxation_times
        return self.equilibrium_modulus + (self.moduli * iwt / (1.0 + iwt)).sum(axis=-1)

    def storage_modulus(self, omega) -> np.ndarray:
        """``E'(ω)`` [MPa]."""
        return self.complex_modulus(omega).real

    def loss_modulus(self, omega) -> np.ndarray:
        """``E''(ω)`` [MPa]; >= 0 for ``ω >= 0``."""
        return self.complex_modulus(omega).imag

    def loss_tangent(self, omega) -> np.ndarray:
        """``tan δ = E''/E'`` [-]."""
        e = self.complex_modulus(omega)
        return e.imag / e.real

    def reduced_modulus(self, omega, nu: float = 0.5) -> np.ndarray:
        """Plane-strain (contact) modulus ``E_r(ω) = E(ω)/(1 − ν²)`` [MPa]."""
        if not 0.0 <= nu <= 0.5:
            raise InputError(f"nu: Poisson's ratio must lie in [0, 0.5], got {nu}")
        return self.complex_modulus(omega) / (1.0 - nu**2)

    def relaxation_modulus(self, t) -> np.ndarray:
        """``E(t) = E_∞ + Σ E_i exp(−t/τ_i)`` [MPa] for ``t >= 0`` [s]."""
        t = np.asarray(t, dtype=float)
        if np.any(t < 0):
            raise InputError("t: relaxation modulus is defined for t >= 0 only")
        return self.equilibrium_modulus + (
            self.moduli * np.exp(-t[..., None] / self.relaxation_times)).sum(axis=-1)

    def retardation_times(self) -> np.ndarray:
        """Retardation (creep) times ``λ_k`` [s], ascending; empty for an elastic material.

        Under a constant stress the strain creeps as ``J(t)`` (:meth:`creep_compliance`),
        whose exponentials decay with these times. They are the zeros ``s_k = −1/λ_k`` of
        ``Ê(s) = E_∞ + Σ E_i sτ_i/(1 + sτ_i)``, one between each pair of neighbouring poles
        ``−1/τ_i`` and one between ``−1/τ_max`` and 0, so ``λ_k`` interlace the relaxation
        times and the longest exceeds the longest ``τ_i``. Found by bracketed root search
        on each interval (a polynomial in ``s`` would be ill-conditioned for times spread
        over many decades).
        """
        from scipy.optimize import brentq

        tau = np.sort(self.relaxation_times)[::-1]            # longest first
        moduli = self.moduli[np.argsort(self.relaxation_times)[::-1]]
        e_inf = self.equilibrium_modulus

        def e_hat(x: float) -> float:                  # Ê(−x), x = 1/λ > 0
            return e_inf - float(np.sum(moduli * x * tau / (1.0 - x * tau)))

        poles = np.concatenate([[0.0], 1.0 / tau])            # ascending in x
        roots = []
        for lo, hi in zip(poles[:-1], poles[1:], strict=True):
            # Ê(−x) runs from +∞ (or E_∞ at x = 0) down to −∞ across each interval
            eps = 1e-12 * (hi - lo)
            roots.append(brentq(e_hat, lo + eps, hi - eps, xtol=1e-15 * hi, rtol=1e-13,
                                maxiter=500))
        return np.sort(1.0 / np.asarray(roots))

    def creep_compliance(self, t) -> np.ndarray:
        """``J(t)`` [1/MPa]: the strain per unit stress applied at ``t = 0`` and held.

        ``J(0) = 1/E_glassy``, ``J(∞) = 1/E_∞``;
        ``J(t) = 1/E_∞ + Σ_k r_k exp(−t/λ_k)`` with the residues
        ``r_k = 1/(s_k Ê'(s_k))`` of ``1/(s Ê(s))`` at ``s_k = −1/λ_k``.
        """
        t = np.asarray(t, dtype=float)
        if np.any(t < 0):
            raise InputError("t: creep compliance is defined for t >= 0 only")
        lam = self.retardation_times()
        s_k = -1.0 / lam
        de_hat = (self.moduli * self.relaxation_times
                  / (1.0 + s_k[:, None] * self.relaxation_times) ** 2).sum(axis=1)
        residues = 1.0 / (s_k * de_hat)
        return 1.0 / self.equilibrium_modulus + (
            residues * np.exp(-t[..., None] / lam)).sum(axis=-1)

    def at_temperature(self, temperature: float, shift: ShiftLaw | None = None, *,
                       vertical: bool = False) -> GeneralizedMaxwell:
        """The material at ``temperature`` [°C] by time–temperature superposition.

        Relaxation times are scaled by ``a_T = shift.shift(temperature)``, so
        ``at_temperature(T).complex_modulus(ω) == complex_modulus(a_T ω)`` (up to
        round-off). The moduli are unchanged: the vertical (entropic) shift is neglected
        unless ``vertical=True``, which multiplies every modulus by ``T/T_ref`` in kelvin
        (rubber elasticity, ``E ∝ ρT``, with the density change neglected).

        Parameters
        ----------
        temperature
            Target temperature [°C].
        shift
            Shift law referred to this material's temperature (its ``t_ref``); default: the
            material's own :attr:`shift`.
        vertical
            Apply the ``T/T_ref`` modulus factor.

        Returns
        -------
        GeneralizedMaxwell
            Carrying the shift law re-referred to ``temperature`` (so a second
            ``at_temperature`` composes) and this material's provenance.
        """
        law = self.shift if shift is None else shift_law_from_dict(shift)
        if law is None:
            raise InputError("at_temperature: the material has no shift law; pass "
                             "shift=rc.materials.WLF(c1, c2, t_ref) or Arrhenius(E_a, t_ref)")
        if isinstance(temperature, bool) or not isinstance(temperature, numbers.Real):
            raise InputError(f"temperature: expected a number in °C, got {temperature!r}")
        a_t = float(law.shift(float(temperature)))
        b_t = ((float(temperature) + ZERO_CELSIUS) / (law.t_ref + ZERO_CELSIUS)
               if vertical else 1.0)
        return GeneralizedMaxwell(self.equilibrium_modulus * b_t, self.moduli * b_t,
                                  self.relaxation_times * a_t,
                                  name=f"{self.name} at {float(temperature):g} °C",
                                  shift=law.rereferenced(float(temperature)),
                                  provenance=self.provenance)

    def as_dict(self, *, provenance: bool = True) -> dict:
        """Plain-data form (for configs, hashing and NetCDF attributes).

        ``GeneralizedMaxwell(**m.as_dict())`` rebuilds the material. The keys ``shift``
        and ``provenance`` appear only when set (``provenance=False`` leaves the latter
        out, e.g. for a cache key that should not depend on where the series came from).
        """
        out = {"name": self.name, "equilibrium_modulus": self.equilibrium_modulus,
               "moduli": self.moduli.tolist(), "relaxation_times": self.relaxation_times.tolist()}
        if self.shift is not None:
            out["shift"] = self.shift.as_dict()
        if provenance and self.provenance is not None:
            out["provenance"] = _thaw(self.provenance)
        return out

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, GeneralizedMaxwell):
            return NotImplemented
        return (self.equilibrium_modulus == other.equilibrium_modulus
                and np.array_equal(self.moduli, other.moduli)
                and np.array_equal(self.relaxation_times, other.relaxation_times)
                and self.shift == other.shift)

    def __hash__(self) -> int:
        return hash((self.equilibrium_modulus, self.moduli.tobytes(),
                     self.relaxation_times.tobytes(), self.shift))


def _freeze(name: str, value):
    """Plain data → read-only (tables as ``MappingProxyType``, lists as tuples)."""
    if isinstance(value, Mapping):
        out = {}
        for k, v in value.items():
            if not isinstance(k, str):
                raise InputError(f"{name}: keys must be strings, got {k!r}")
            out[k] = _freeze(f"{name}.{k}", v)
        return MappingProxyType(out)
    if isinstance(value, list | tuple | np.ndarray):
        return tuple(_freeze(f"{name}[{i}]", v) for i, v in enumerate(value))
    if isinstance(value, bool | str):
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        return float(value)
    raise InputError(f"{name}: expected a string, number, boolean, list or table, "
                     f"got {value!r}")


def _thaw(value):
    if isinstance(value, Mapping):
        return {k: _thaw(v) for k, v in value.items()}
    if isinstance(value, tuple):
        return [_thaw(v) for v in value]
    return value


def sbr() -> GeneralizedMaxwell:
    """Styrene-butadiene rubber of the paper's Table 1 (Wriggers & Reinelt 1996)."""
    return GeneralizedMaxwell(
        equilibrium_modulus=4.17,
        moduli=np.array([1.72, 7.36, 70.98, 505.87, 1125.85, 1185.94]),
        relaxation_times=np.array([1.134e-02, 2.628e-04, 1.316e-05, 1.295e-06, 7.708e-08,
                                   4.200e-10]),
        name="SBR (Table 1)",
    )
