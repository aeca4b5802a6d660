"""Frictional heating of the rubber: thermal properties, the moving heat source, flash
temperature.

``ThermalProperties`` (conductivity, density, specific heat of the compound, SI in, package
units out; :data:`FILLED_SBR` the default), ``surface_temperature`` (the steady temperature
of a periodic heat flux sliding over the rubber, by FFT, :mod:`.kernel`) and the closed
forms of uniform moving sources (:mod:`.spots`) that the mean-field flash temperature
(:mod:`rubbercontact.meanfield.flash`) is built from; the heat and temperature of a solved
half-space contact and its flash temperature self-consistent with its friction
(``contact_heating``, ``flash_contact``, :mod:`.contact`), over a sweep of speeds each
started from its neighbours (``flash_sweep``, :mod:`.sweep`).
"""

from .contact import (
    ContactFlash,
    ContactHeating,
    FlashSearch,
    FlashStart,
    contact_heating,
    flash_contact,
)
from .kernel import (
    subsurface_temperature,
    surface_temperature,
    temperature_kernel,
    thermal_admittance,
)
from .properties import FILLED_SBR, ThermalProperties
from .spots import band_centre_temperature, band_mean_temperature, disc_centre_temperature
from .sweep import FlashSweep, flash_sweep

__all__ = ["ThermalProperties", "FILLED_SBR", "surface_temperature", "subsurface_temperature",
           "temperature_kernel",
           "thermal_admittance", "band_centre_temperature", "band_mean_temperature",
           "disc_centre_temperature", "contact_heating", "flash_contact", "ContactHeating",
           "ContactFlash", "FlashSearch", "FlashStart", "FlashSweep", "flash_sweep"]
