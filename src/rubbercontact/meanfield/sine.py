r"""One sliding sine as Westergaard's strips: the step of the strip cascade (:mod:`.strips`).

A sine ``Δ cos qx`` under the mean pressure ``p̄ < p* = qΔE_r/2`` touches on strips of the
fraction ``r = (2/π) arcsin √(p̄/p*)`` of its wavelength (Westergaard; :mod:`.patches`).

Pressure variance of one wave
-----------------------------
With ``x = p̄/p*`` and ``β = α/2 = arcsin √x`` the mean square of ``p(θ)`` over a period is
``(4p*²/π)[x(β + sin 2β/2) − (β − sin 4β/4)/4]`` (substitute ``s = sin(θ/2)``), so the
pressure variance is that minus ``p̄²`` (:func:`westergaard_variance`): ``p*²/2`` in full
contact (the mode's ``s_i``), ``(2π²/3) r³ p*²`` for narrow strips (Hertz).

A sliding strip is stiffer
--------------------------
A strip of half-width ``a`` is loaded and unloaded while the rubber slides over it, in the
time ``2a/v``: we take that time as half a period of the excitation, so the strip's modulus
is ``|E_r(ω)|`` at ``ω = πv/(2a) = qv/(2r)`` (the mode's own ``qv`` once ``r ≥ ½``). Its
fraction solves ``r = (2/π) arcsin √(p̄/(e(r) p*))`` with ``e = |E_r(qv/min(1, 2r))|/
|E_r(qv)|`` (:func:`sliding_fraction`; at ``v = 0`` Westergaard's). On one sliding sine this
is the BEM's area (tests/test_meanfield_strips.py).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..materials.protocol import Material
from .crests import SMALLEST_FRACTION
from .patches import LossFilter, patch_loss

#: Log grids on which a wave's strip fraction (in ``p̄/p*``) and loss (in ``r``) are read.
TABLE_POINTS = 300
SMALLEST_RATIO = 1e-12


def westergaard_variance(pressure_ratio) -> np.ndarray:
    """Pressure variance of one sine over its period, in units of ``p*²`` [-], at
    ``x = p̄/p*`` (module docstring; ``1/2`` at ``x ≥ 1``, full contact)."""
    x = np.clip(np.asarray(pressure_ratio, float), 0.0, 1.0)
    beta = np.arcsin(np.sqrt(x))
    mean_square = 4.0 / np.pi * (x * (beta + 0.5 * np.sin(2 * beta))
                                 - 0.25 * (beta - 0.25 * np.sin(4 * beta)))
    return np.where(np.asarray(pressure_ratio) >= 1.0, 0.5, mean_square - x**2)


@dataclass(frozen=True)
class SlidingStrip:
    """Strips of one sliding sine at the load ratios ``x = p̄/p*(qv)``.

    Attributes
    ----------
    fraction
        ``r`` [-]: the share of the wavelength in contact (1: full contact).
    stiffening
        ``e = |E_r(qv/min(1, 2r))| / |E_r(qv)|`` [-]: the strip's modulus over the mode's.
    """

    fraction: np.ndarray
    stiffening: np.ndarray


def _modulus_ratio(material: Material, wavenumber: float, speed: float,
                   fraction: np.ndarray) -> np.ndarray:
    omega = wavenumber * speed
    own = abs(complex(material.complex_modulus(omega)))
    return np.abs(material.complex_modulus(omega / np.minimum(1.0, 2.0 * fraction))) / own


def sliding_fraction(pressure_ratio, wavenumber: float, material: Material,
                     velocity: float, nu: float = 0.5, iterations: int = 60) -> SlidingStrip:
    """Solve ``r = (2/π) arcsin √(x/e(r))`` for each ``x`` (bisection in ``ln r``;
    module docstring). ``wavenumber`` [rad/mm], ``velocity`` [mm/s]."""
    x = np.asarray(pressure_ratio, float)
    speed = abs(float(velocity))
    if speed == 0.0:
        r = 2.0 / np.pi * np.arcsin(np.sqrt(np.clip(x, 0.0, 1.0)))
        return SlidingStrip(r, np.ones_like(r))
    lo = np.full(x.shape, np.log(SMALLEST_FRACTION))
    hi = np.zeros(x.shape)
    for _ in range(int(iterations)):
        mid = 0.5 * (lo + hi)
        e = _modulus_ratio(material, wavenumber, speed, np.exp(mid))
        above = 2.0 / np.pi * np.arcsin(np.sqrt(np.clip(x / e, 0.0, 1.0))) > np.exp(mid)
        lo, hi = np.where(above, mid, lo), np.where(above, hi, mid)
    r = np.where(x >= 1.0, 1.0, np.exp(0.5 * (lo + hi)))
    return SlidingStrip(r, _modulus_ratio(material, wavenumber, speed, r))


@dataclass(frozen=True)
class WaveTables:
    """One wave at one speed: its strips against ``x`` and its strips' loss against ``r``."""

    wavenumber: float
    amplitude: float
    p_star: float                 # qΔ|E_r(qv)|/2 [MPa]
    ratios: np.ndarray            # x grid
    strips: SlidingStrip          # on the x grid
    fractions: np.ndarray         # r grid
    loss: np.ndarray              # Σ h_n(r)(−2 Im[1/E_r(nqv)]) on the r grid [1/MPa]
    own_loss: float               # −2 Im[1/E_r(qv)] [1/MPa]: the loss in full contact

    @property
    def curvature(self) -> float:
        """Crest curvature ``q²Δ`` [1/mm]."""
        return self.wavenumber**2 * self.amplitude

    def at(self, ratio: np.ndarray) -> SlidingStrip:
        """Strips at the load ratios ``ratio`` (log interpolation; full contact at ≥ 1)."""
        full = ratio >= 1.0
        lx = np.log(np.clip(ratio, self.ratios[0], 1.0))
        lg = np.log(self.ratios)
        r = np.where(full, 1.0, np.exp(np.interp(lx, lg, np.log(self.strips.fraction))))
        e = np.where(full, 1.0, np.interp(lx, lg, self.strips.stiffening))
        return SlidingStrip(r, e)

    def loss_at(self, fraction: np.ndarray) -> np.ndarray:
        """The strips' loss [1/MPa] at the fractions (clipped to the grid; the mode's own,
        exactly, in full contact)."""
        lr = np.log(np.clip(fraction, self.fractions[0], 1.0))
        return np.where(fraction >= 1.0, self.own_loss,
                        np.interp(lr, np.log(self.fractions), self.loss))


def wave_tables(wavenumber: float, amplitude: float, material: Material,
                velocity: float, nu: float, loss_filter: LossFilter | None = None
                ) -> WaveTables:
    """Tabulate :func:`sliding_fraction` and :func:`~.patches.patch_loss` for one wave
    (the losses through ``loss_filter`` if given, :data:`~.patches.LossFilter`)."""
    modulus = complex(material.complex_modulus(wavenumber * abs(velocity))) / (1.0 - nu**2)
    ratios = np.geomspace(SMALLEST_RATIO, 1.0, TABLE_POINTS)
    fractions = np.geomspace(SMALLEST_FRACTION, 1.0, TABLE_POINTS)
    loss = patch_loss(fractions, np.full(fractions.size, wavenumber), material, velocity, nu,
                      loss_filter)
    own = -2.0 * (1.0 / modulus).imag
    if loss_filter is not None:
        own = float(loss_filter(np.array(wavenumber * abs(velocity)), np.array(own)))
    own *= np.sign(velocity)                                   # E(−ω) = conj E(ω)
    return WaveTables(wavenumber, amplitude, wavenumber * amplitude * abs(modulus) / 2,
                      ratios, sliding_fraction(ratios, wavenumber, material, velocity, nu),
                      fractions, loss, float(own))
