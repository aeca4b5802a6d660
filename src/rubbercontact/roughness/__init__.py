"""Roughness: sine-series surfaces, statistics of measured profiles, HDC fitting, height maps."""

from .analysis import fit_default, format_table
from .fit import (
    HDCFit,
    RoughnessWarning,
    check_resolution,
    default_wavelengths,
    fit_hdc,
    fit_hdc_curve,
    fit_hdc_details,
    octave_wavelengths,
    wave_hdc,
)
from .maps import HeightMap, max_height
from .mapsplit import MapSplit, octave_bands, split_map
from .mapsynth import isotropic_from_line_psd, self_affine_map, synthetic_map
from .presets import TABLE2, asphalt_ac8, high_slope_wave, section3
from .protocol import Profile, Surface, SurfaceMap, WaveProfile, check_surface, check_waves
from .sines import SineSeries
from .statistics import detrend, hdc, log_lags, psd, rms_height, rms_slope
from .synthetic import random_ladder, self_affine_profile, synthetic_line_scans

__all__ = ["SineSeries", "TABLE2", "asphalt_ac8", "section3", "high_slope_wave",
           "hdc", "psd", "rms_height", "rms_slope", "detrend", "log_lags",
           "fit_hdc", "fit_hdc_details", "fit_hdc_curve", "HDCFit", "RoughnessWarning",
           "octave_wavelengths", "default_wavelengths", "check_resolution", "wave_hdc",
           "synthetic_line_scans", "fit_default", "format_table", "HeightMap", "max_height",
           "MapSplit", "octave_bands", "split_map", "isotropic_from_line_psd",
           "self_affine_map", "synthetic_map", "random_ladder", "self_affine_profile",
           "Surface", "Profile", "SurfaceMap", "WaveProfile", "check_surface", "check_waves"]
