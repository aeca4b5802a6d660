"""The inverse form ``u = g(σ)`` of a Lennard-Jones wall, for the mixed Newton.

:mod:`.newton` linearises the rows in a wall's contact range in this form (see its module
docstring); a law offers it through :meth:`~.laws.InteractionLaw.inverse`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["InverseWall"]


@dataclass(frozen=True)
class InverseWall:
    """Inverse ``g = f⁻¹`` of a Lennard-Jones wall ``f(u) = p_ref (ℓ/u)⁹`` and ``c = −g'``.

    ``g(σ) = ℓ (p_ref/σ)^(1/9)`` up to ``σ = 4⁹ p_ref``, linear beyond (the law's own linear
    continuation below ``u = ℓ/4``); ``g = +∞`` for ``σ <= 0``. ``c(σ) = 1/k(g(σ))``.

    Attributes
    ----------
    length, reference_pressure
        ``ℓ`` [mm] and ``p_ref`` [MPa] of the resolved law.
    """

    length: float
    reference_pressure: float

    @property
    def threshold(self) -> float:
        """``f(2ℓ)`` [MPa]: rows with ``σ`` or ``f(u)`` above it are solved in inverse form."""
        return self.reference_pressure / 512.0

    @property
    def u_min(self) -> float:
        """``ℓ/4`` [mm]: the law is linear below."""
        return 0.25 * self.length

    @property
    def s_min(self) -> float:
        """``f(ℓ/4) = 4⁹ p_ref`` [MPa]."""
        return self.reference_pressure * 4.0**9

    @property
    def k_min(self) -> float:
        """Stiffness of the linear piece [MPa/mm]."""
        return 9.0 * self.s_min / self.u_min

    def separation(self, sig: np.ndarray) -> np.ndarray:
        """``g(σ)`` [mm]."""
        s_min = self.s_min
        pos = np.maximum(sig, 1e-300)
        u = np.where(sig <= s_min, self.length * (self.reference_pressure / pos) ** (1.0 / 9.0),
                     self.u_min - (sig - s_min) / self.k_min)
        return np.where(sig > 0, u, np.inf)

    def compliance(self, sig: np.ndarray, u: np.ndarray) -> np.ndarray:
        """``c = 1/k(u)`` at ``u = g(σ)``: ``k = 9σ/u`` on the power law, ``k_min`` beyond."""
        return np.where(sig <= self.s_min, u / (9.0 * np.maximum(sig, 1e-300)),
                        1.0 / self.k_min)
