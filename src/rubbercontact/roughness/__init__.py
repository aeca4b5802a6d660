"""Roughness: sine-series surfaces, statistics of measured profiles, HDC fitting."""

from .presets import TABLE2, asphalt_ac8, high_slope_wave, section3
from .sines import SineSeries

__all__ = ["SineSeries", "TABLE2", "asphalt_ac8", "section3", "high_slope_wave"]
