r"""Closed forms of moving heat sources on a half-space (Jaeger; Carslaw & Jaeger 1959).

The surface temperature of a steady point source of power ``P`` moving at ``v`` on a
half-space (3D conduction) is ``P e^{−u(r − x)}/(2πK r)``, of a line source of power ``P``
per unit length (2D conduction, a 1D surface) ``(P/πK) e^{ux} K0(u|x|)``, ``u = v/(2D)``,
the warm wake at ``x > 0`` in the convention of :mod:`.kernel` (Carslaw & Jaeger, *Conduction
of Heat in Solids*, 1959, §10.7). Integrating them over uniform sources gives, per unit
flux density [K per mW/mm²]:

* :func:`disc_centre_temperature`: the centre of a disc of radius ``R`` (2D),
  ``(R/K) e^{−uR}(I0(uR) + I1(uR))`` — from ``∫_0^x e^{−t} I0 dt = x e^{−x}(I0 + I1)``;
* :func:`band_centre_temperature`: the centre of a band ``|x| < R`` (1D),
  ``(2R/πK)(cosh(uR) K0(uR) + sinh(uR) K1(uR))`` — from
  ``∫_0^x cosh(t) K0(t) dt = x (cosh x K0 + sinh x K1)``;
* :func:`band_mean_temperature`: the mean over a band of half-width ``a`` (Jaeger's band
  source), ``(1/πK a u²) [(2x²/3)(cosh x K0 + sinh x K1) + (x/3) cosh x K1 − 1/3]`` at
  ``x = 2au`` — from ``∫_0^x t cosh(t) K0(t) dt = (x/3)[x(cosh K0 + sinh K1) − cosh K1] + 1/3``.

All three reduce, at high speed (``uR ≫ 1``), to the one-dimensional transient conduction
under a source passing in the time ``2R/v``: centre ``(2/K)√(RD/πv)``, band mean
``(4/3K)√(2aD/πv)``. At low speed the disc tends to the stationary ``R/K`` and the band's
temperatures grow as ``ln(D/va)`` (a line source on a half-plane has no steady state).
Each derivative identity is checked in tests/test_thermal_kernel.py.
"""

from __future__ import annotations

import numpy as np
from scipy.special import i0e, i1e, k0e, k1e

from .properties import ThermalProperties


def _u(velocity, thermal: ThermalProperties) -> np.ndarray:
    return np.abs(np.asarray(velocity, float)) / (2.0 * thermal.diffusivity)


def _cosh_k(x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``cosh x K0(x)``, ``sinh x K1(x)``, ``cosh x K1(x)`` without overflow (x > 0)."""
    e = np.exp(-2.0 * x)
    k0, k1 = k0e(x), k1e(x)
    return 0.5 * k0 * (1 + e), 0.5 * k1 * (1 - e), 0.5 * k1 * (1 + e)


def disc_centre_temperature(radius, velocity, thermal: ThermalProperties) -> np.ndarray:
    """Temperature rise [K] at the centre of a uniform unit-flux (1 mW/mm²) disc of
    ``radius`` [mm] moving at ``velocity`` [mm/s] over a half-space (module docstring)."""
    r = np.asarray(radius, float)
    x = _u(velocity, thermal) * r
    return r / thermal.conductivity_package * (i0e(x) + i1e(x))


def band_centre_temperature(half_width, velocity, thermal: ThermalProperties) -> np.ndarray:
    """Temperature rise [K] at the centre of a uniform unit-flux band ``|x| < half_width``
    [mm] moving at ``velocity`` [mm/s] (> 0: a line source has no stationary state)."""
    r = np.asarray(half_width, float)
    x = _u(velocity, thermal) * r
    ck0, sk1, _ = _cosh_k(x)
    return 2.0 * r / (np.pi * thermal.conductivity_package) * (ck0 + sk1)


def band_mean_temperature(half_width, velocity, thermal: ThermalProperties) -> np.ndarray:
    """Mean temperature rise [K] over a uniform unit-flux band of ``half_width`` [mm]
    moving at ``velocity`` [mm/s] > 0 (Jaeger's band source, module docstring)."""
    a = np.asarray(half_width, float)
    u = _u(velocity, thermal)
    x = 2.0 * a * u
    ck0, sk1, ck1 = _cosh_k(x)
    bracket = 2.0 * x**2 / 3.0 * (ck0 + sk1) + x / 3.0 * ck1 - 1.0 / 3.0
    return bracket / (np.pi * thermal.conductivity_package * a * u**2)
