"""The modulus of a rubber on log-frequency tables, for solvers that read it many times.

The flash temperature (:mod:`.flash`) gives every node of a spectrum its own temperature,
hence its own frequency ``a_T(T_i) q_i v``, at every step of its fixed point: the complex
modulus is read off these tables instead of summing the Prony series each time.
"""

from __future__ import annotations

import numpy as np

from .patches import LOSS_PER_DECADE

#: Points per decade of the cubic tables.
TABLE_PER_DECADE = 400


class ModulusTables:
    """The modulus on grids uniform in ``log ω`` between ``10^lo`` and ``10^hi`` [rad/s].

    ``power(ω) = Σ_φ w_φ |E_r(ω cos φ)|²`` [MPa²] and ``loss(ω) = Σ_φ w_φ cos φ
    Im E_r(ω cos φ)`` [MPa] (the angular averages of :mod:`.contact`; one direction in 1D)
    at :data:`TABLE_PER_DECADE` points per decade, read cubically (relative error < 1e-9);
    ``−2 Im[1/E_r(ω)]`` [1/MPa] up to ``10^(hi + harmonics)`` on the very nodes that
    :func:`.patches.patch_loss` reads, linearly as it does (so the patch spectrum is the
    same number as in :func:`.friction_curve`). Beyond the ends: the end values."""

    def __init__(self, material, nu: float, dimension: int, angles: int, lo: float, hi: float,
                 harmonics: float):
        self.step = 1.0 / TABLE_PER_DECADE
        self.lo = lo - self.step                    # one node below: the cubic's stencil
        omega = 10.0 ** (self.lo + self.step * np.arange(int((hi - lo) / self.step) + 4))
        cos_phi, weights = _angles(dimension, angles)
        e_r = material.complex_modulus(omega[:, None] * cos_phi) / (1.0 - nu**2)
        self.power = np.sum(weights * np.abs(e_r) ** 2, axis=-1)
        self.loss = np.sum(weights * cos_phi * e_r.imag, axis=-1)
        self.loss_nodes = np.arange(np.floor(lo * LOSS_PER_DECADE),
                                    np.ceil((hi + harmonics) * LOSS_PER_DECADE) + 2)
        e1 = material.complex_modulus(10.0 ** (self.loss_nodes / LOSS_PER_DECADE))
        self.patch = -2.0 * np.imag((1.0 - nu**2) / e1)

    @staticmethod
    def _read(table: np.ndarray, x: np.ndarray) -> np.ndarray:
        i = np.clip(x.astype(int), 0, table.size - 2)
        t = np.clip(x - i, 0.0, 1.0)
        return (1 - t) * table[i] + t * table[i + 1]

    def __call__(self, name: str, omega: np.ndarray) -> np.ndarray:
        """``power`` or ``loss`` at ``omega`` [rad/s], by 4-point Lagrange interpolation
        in ``log ω`` (error ``~h⁴``, < 1e-9 relative at :data:`TABLE_PER_DECADE`)."""
        table = getattr(self, name)
        x = (np.log10(np.maximum(omega, 1e-300)) - self.lo) / self.step
        i = np.clip(x.astype(int), 1, table.size - 3)
        t = np.clip(x - i, 0.0, 1.0)
        return (-t * (t - 1) * (t - 2) / 6 * table[i - 1]
                + (t + 1) * (t - 1) * (t - 2) / 2 * table[i]
                - (t + 1) * t * (t - 2) / 2 * table[i + 1]
                + (t + 1) * t * (t - 1) / 6 * table[i + 2])

    def patch_loss(self, omega: np.ndarray) -> np.ndarray:
        """``−2 Im[1/E_r(ω)]`` [1/MPa] (0 at ``ω = 0``)."""
        x = np.log10(np.maximum(omega, 1e-300)) * LOSS_PER_DECADE - self.loss_nodes[0]
        return np.where(omega > 0, self._read(self.patch, x), 0.0)


def _angles(dimension: int, angles: int) -> tuple[np.ndarray, np.ndarray]:
    """The directions of :func:`.contact.half_space_compliance` (cos φ, weights)."""
    if dimension == 1:
        return np.ones(1), np.ones(1)
    x, w = np.polynomial.legendre.leggauss(int(angles))
    return np.cos(np.pi / 4 * (x + 1)), w / 2
