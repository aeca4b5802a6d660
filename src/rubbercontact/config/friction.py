"""The ``[friction]`` table: contributions to friction beyond the models' hysteresis
(adhesion, the flash temperature)."""

from __future__ import annotations

from typing import Literal

import numpy as np
from pydantic import Field, model_validator

from ..inputs import PositiveFloat
from ..inputs import Strict as _Strict


class AdhesionConfig(_Strict):
    """Adhesive friction ``μ_adh = τ_f(v) A_c/σ0`` (paper §2.1 after eq. 8), a model whose
    parameters the user supplies: ``τ_f`` constant, or a Gaussian in ``log10 v``,
    ``τ_f = τ_0 exp(−(log10(v/v_0))²/(2c²))``, evaluated at the reduced speed ``a_T v``."""

    law: Literal["constant", "gaussian"] = Field(
        "constant", description="constant tau_0, or gaussian in log10 v")
    shear_strength: PositiveFloat = Field(description="tau_0, interfacial shear strength [MPa]")
    peak_velocity: PositiveFloat | None = Field(
        None, description="v_0, speed of the gaussian's peak at the reference temperature "
                          "[mm/s]")
    width: PositiveFloat | None = Field(
        None, description="c, standard deviation of the gaussian in decades of speed [-]")

    @model_validator(mode="after")
    def _parameters(self) -> AdhesionConfig:
        shape = [k for k in ("peak_velocity", "width") if getattr(self, k) is not None]
        if self.law == "gaussian" and len(shape) != 2:
            raise ValueError("law = 'gaussian' needs peak_velocity [mm/s] and width [decades]")
        if self.law == "constant" and shape:
            raise ValueError(f"{', '.join(shape)} apply to law = 'gaussian' only")
        return self


class FlashTemperatureConfig(_Strict):
    """The flash temperature of the contact spots, self-consistent with the friction
    (:mod:`rubbercontact.meanfield.flash`; the compound's ``[material.thermal]``)."""

    enabled: bool = Field(False, description="compute mu(v) with the flash temperature beside "
                                             "the isothermal one (mean-field models)")
    contact_time: PositiveFloat | None = Field(
        None, description="time the rubber slides in nominal contact [s]: the tread's "
                          "background heating (default: none, the run's temperature)")
    spot_radius: PositiveFloat = Field(
        float(np.pi / 2), description="q R of a contact spot at the wavenumber q [-]")
    tolerance: PositiveFloat = Field(1e-3, description="fixed point's tolerance [K]")
    max_iterations: int = Field(500, ge=1, le=100_000, description="fixed-point steps")


class FrictionConfig(_Strict):
    """Contributions to friction beyond the hysteresis the models compute."""

    adhesion: AdhesionConfig | None = None
    flash_temperature: FlashTemperatureConfig = FlashTemperatureConfig()

