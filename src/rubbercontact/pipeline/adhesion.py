r"""Adhesive friction from the real contact area (paper §2.1, after eq. 8).

A model with parameters the user supplies (``[friction.adhesion]``): the interface
transmits a shear stress ``τ_f(v)`` over the real contact area, so

.. math::  μ_{adh} = τ_f(v)\, \frac{A_c}{A_0} \frac{1}{σ_0},

beside the hysteretic ``μ`` every model computes, and ``μ_total = μ + μ_adh``. The shear
strength is a constant ``τ_0`` [MPa] or the usual bell in ``log10 v``,

.. math::  τ_f(v) = τ_0 \exp\left(-\frac{\log_{10}^2(v/v_0)}{2c^2}\right),

with its peak speed ``v_0`` [mm/s] and width ``c`` [decades]. With temperatures, ``τ_f`` is
read at the reduced speed ``a_T v`` (the adhesive peak shifts with the same WLF law as the
hysteresis, Grosch 1963), so ``v_0`` is the peak speed at the reference temperature.
"""

from __future__ import annotations

import json
from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..config import AdhesionConfig


@dataclass(frozen=True)
class AdhesionLaw:
    """The interfacial shear strength ``τ_f(v)`` (module docstring).

    Attributes
    ----------
    law
        ``"constant"`` or ``"gaussian"``.
    shear_strength
        ``τ_0`` [MPa].
    peak_velocity
        ``v_0`` [mm/s] (gaussian).
    width
        ``c`` [decades of speed] (gaussian).
    """

    law: str
    shear_strength: float
    peak_velocity: float | None = None
    width: float | None = None

    @classmethod
    def from_config(cls, cfg: AdhesionConfig) -> AdhesionLaw:
        return cls(cfg.law, cfg.shear_strength, cfg.peak_velocity, cfg.width)

    def tau(self, velocity) -> np.ndarray:
        """``τ_f`` [MPa] at ``velocity`` [mm/s] (the reduced speed with temperatures); 0 at
        ``v = 0`` for the gaussian."""
        v = np.asarray(velocity, float)
        if self.law == "constant":
            return np.full(v.shape, self.shear_strength)
        with np.errstate(divide="ignore"):
            x = np.log10(v / self.peak_velocity)
        return self.shear_strength * np.exp(-(x**2) / (2 * self.width**2))

    def describe(self) -> str:
        if self.law == "constant":
            return f"tau_f = {self.shear_strength:g} MPa"
        return (f"tau_f = {self.shear_strength:g} MPa exp(-(log10(v/{self.peak_velocity:g} "
                f"mm/s))^2/(2 {self.width:g}^2))")


def add_adhesion(ds: xr.Dataset, law: AdhesionLaw) -> xr.Dataset:
    """Add ``adhesion_shear_strength`` (per speed), ``friction_adhesion`` and
    ``friction_total`` (per model, speed, realization, load) to results whose ``velocity``
    is the computed (reduced) speed."""
    tau = xr.DataArray(law.tau(ds["velocity"].values), dims="velocity",
                       coords={"velocity": ds["velocity"]},
                       attrs={"units": "MPa", "long_name": "interfacial shear strength tau_f "
                                                           "at the (reduced) speed"})
    ds["adhesion_shear_strength"] = tau
    mu_adh = tau * ds["contact_fraction"] / ds["pressure"]
    ds["friction_adhesion"] = mu_adh.transpose(*ds["friction"].dims).assign_attrs(
        units="1", long_name="adhesive friction tau_f A_c/(A_0 sigma0)")
    ds["friction_total"] = (ds["friction"] + ds["friction_adhesion"]).assign_attrs(
        units="1", long_name="hysteretic + adhesive friction")
    ds.attrs["adhesion"] = json.dumps({"law": law.law, "shear_strength_MPa": law.shear_strength,
                                       "peak_velocity_mm_s": law.peak_velocity,
                                       "width_decades": law.width, "formula": law.describe()})
    return ds
