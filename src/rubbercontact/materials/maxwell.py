"""Generalized Maxwell (Prony series) viscoelastic solid.

Moduli are Young's moduli in MPa, relaxation times in s, angular frequencies
in rad/s. The complex modulus follows the engineering convention
``σ(t) = Re[E(ω) ε̂ e^{iωt}]`` so that the loss modulus ``E''(ω) >= 0`` for
``ω > 0`` and ``E(-ω) = conj(E(ω))``.
"""

from __future__ import annotations

import csv
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .._validation import finite_array, positive_scalar
from ..errors import InputError


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

    Notes
    -----
    ``E(ω) = E_∞ + Σ_i E_i · iωτ_i / (1 + iωτ_i)``;
    relaxation modulus ``E(t) = E_∞ + Σ_i E_i exp(−t/τ_i)``.
    An empty series is a purely elastic material.
    """

    equilibrium_modulus: float
    moduli: np.ndarray = field(default_factory=lambda: np.zeros(0))
    relaxation_times: np.ndarray = field(default_factory=lambda: np.zeros(0))
    name: str = "generalized Maxwell"

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
        ``relaxation_times = [...]`` (optionally ``name``).
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
            unknown = set(data) - {"equilibrium_modulus", "moduli", "relaxation_times", "name"}
            if unknown:
                raise InputError(f"material file {path}: unknown key(s) {sorted(unknown)}")
            if "equilibrium_modulus" not in data:
                raise InputError(f"material file {path}: missing key 'equilibrium_modulus'")
            return cls(data["equilibrium_modulus"], data.get("moduli", []),
                       data.get("relaxation_times", []), name=data.get("name", path.stem))
        return cls._from_csv(path)

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

    def as_dict(self) -> dict:
        """Plain-data form (for configs, hashing and NetCDF attributes)."""
        return {"name": self.name, "equilibrium_modulus": self.equilibrium_modulus,
                "moduli": self.moduli.tolist(), "relaxation_times": self.relaxation_times.tolist()}

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, GeneralizedMaxwell):
            return NotImplemented
        return (self.equilibrium_modulus == other.equilibrium_modulus
                and np.array_equal(self.moduli, other.moduli)
                and np.array_equal(self.relaxation_times, other.relaxation_times))

    def __hash__(self) -> int:
        return hash((self.equilibrium_modulus, self.moduli.tobytes(),
                     self.relaxation_times.tobytes()))


def sbr() -> GeneralizedMaxwell:
    """Styrene-butadiene rubber of the paper's Table 1 (Wriggers & Reinelt 1996)."""
    return GeneralizedMaxwell(
        equilibrium_modulus=4.17,
        moduli=np.array([1.72, 7.36, 70.98, 505.87, 1125.85, 1185.94]),
        relaxation_times=np.array([1.134e-02, 2.628e-04, 1.316e-05, 1.295e-06, 7.708e-08,
                                   4.200e-10]),
        name="SBR (Table 1)",
    )
