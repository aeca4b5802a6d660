"""Surfaces of the paper, ready to use."""

from __future__ import annotations

import numpy as np

from .sines import SineSeries

#: Table 2 of the paper: AC-8 asphalt as 8 sine waves (wavelength mm, amplitude mm, m2).
TABLE2 = np.array([
    (0.0625, 0.01867, 1.3275),
    (0.125, 0.02648, 0.9403),
    (0.25, 0.02939, 0.5223),
    (0.5, 0.06626, 0.5888),
    (1.0, 0.06177, 0.2744),
    (2.0, 0.21635, 0.4806),
    (4.0, 0.14772, 0.1641),
    (8.0, 0.48995, 0.2721),
])


def asphalt_ac8(phases=None) -> SineSeries:
    """The 8-wave AC-8 asphalt surface of Table 2 (paper section 4)."""
    return SineSeries(TABLE2[:, 0], TABLE2[:, 1], phases)


def section3(phases=None) -> SineSeries:
    """The three-wave validation surface of paper section 3 (eqs. 25–27)."""
    return SineSeries(TABLE2[:3, 0], TABLE2[:3, 1], phases)


def high_slope_wave() -> SineSeries:
    """The single high-slope wave of the paper: λ = 0.0625 mm, Δ = 0.01867 mm (m2 ≈ 1.33)."""
    return SineSeries(TABLE2[:1, 0], TABLE2[:1, 1])


#: The surface presets by name: the one list the config, the pipeline and the CLI read.
PRESETS = {
    "section3": section3,
    "asphalt_ac8": asphalt_ac8,
    "high_slope_wave": high_slope_wave,
}


def preset(name: str) -> SineSeries:
    """The preset surface ``name`` (a key of :data:`PRESETS`), with zero phases."""
    from ..errors import InputError

    if name not in PRESETS:
        raise InputError(f"surface: unknown preset {name!r}; choose one of "
                         f"{', '.join(PRESETS)} or give wavelengths and amplitudes")
    return PRESETS[name]()
