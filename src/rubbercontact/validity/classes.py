"""The validated class of each model: the conditions it was validated under, as data.

Every bound points at the report that measured it; :data:`CLASSES` maps each model to its
:class:`ValidatedClass`. The guide's table is docs/guide/models.md ("Where each model was
validated"); :mod:`.assess` checks a run against these classes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..roughness.presets import TABLE2

VHS_REPORT = "docs/validation/slope_nonlinearity.md"
SECTION3_REPORT = "VALIDATION.md"
SPLIT_REPORT = "docs/validation/scale_separation.md"
MEANFIELD_REPORT = "docs/validation/meanfield.md"
LAW_REPORT = "docs/guide/law.md"
#: The one measurement on height maps: the hybrid's split, linear law, against the 2D VHS.
MAPS_REPORT = "docs/validation/maps_split.md"

#: Largest per-wave rms slope of the FEM-against-VHS sweep on one sine (the paper's m2 of
#: its steep wave), docs/validation/slope_nonlinearity.md; the FEM law and the full FEM are
#: validated up to the same slope on the section 3 surface (VALIDATION.md).
MEASURED_SLOPE = 1.33
#: The VHS against the full FEM on section 3 (eq. 28, phase-averaged, the larger of the
#: two speeds), VALIDATION.md: the tolerance of the VHS and the FEM against each other.
VHS_FEM_TOLERANCE = 0.16
#: The paper's area range of the section 3 comparison (VALIDATION.md), which the scale
#: separation studies' loads also fall in (docs/validation/scale_separation.md).
SECTION3_CONTACT = (0.01, 0.1)

#: The scale separation studies (docs/validation/scale_separation.md, 10 mm/s, and
#: scale_separation_50mms.md, 50 mm/s): the high-slope wave, the speeds, the steepest
#: low-slope wave, and per hybrid the smallest wavelength ratio of its class with the
#: largest |μ error| against the VHS measured at that ratio or above.
SPLIT_HIGH_WAVELENGTH = 0.0625        # mm
SPLIT_SPEEDS = (10.0, 50.0)           # mm/s
#: The steepest low-slope wave validated: Table 2's 0.125 mm wave (m2 = qΔ/√2), the section
#: 3 surface's (VALIDATION.md; the scale separation studies' 0.94 is the same wave rounded).
SPLIT_LOW_SLOPE = float(2 * np.pi / TABLE2[1, 0] * TABLE2[1, 1] / np.sqrt(2))
POINTWISE_RATIO, POINTWISE_TOLERANCE = 8.0, 0.12
WINDOWED_RATIO, WINDOWED_TOLERANCE = 2.0, 0.15

#: The strip cascade's target class (meanfield-strips), docs/validation/meanfield.md
#: ("Validation"): random octave ladders from 8 mm down (up to 10 waves), per-wave m2 drawn
#: up to 0.6, SBR at 1 to 500 mm/s, the BEM's contact fraction in 1-50 %, μ and A within 15 %.
LADDER_WAVELENGTHS = (8.0 / 2**9, 8.0)   # mm
LADDER_SPEEDS = (1.0, 500.0)             # mm/s
LADDER_SLOPE = 0.6
LADDER_CONTACT = (0.01, 0.5)
LADDER_TOLERANCE = 0.15
#: Persson's theory (meanfield, γ = 0.8) on the same ladders: its largest |μ error| there
#: (docs/validation/meanfield.md, "Persson's S(q) and its γ"; A within 41 %).
PERSSON_LADDER_TOLERANCE = 0.45
#: Octave ladders: the ratio of neighbouring wavelengths, within this relative slack.
OCTAVE, OCTAVE_SLACK = 2.0, 0.01
#: meanfield-hybrid against the VHS with the linear law, docs/validation/meanfield.md
#: ("meanfield-hybrid against hybrid-windowed"): the separated surface (ratio 16, low-slope
#: m2 up to 0.4, contact 2-20 %, 10 and 50 mm/s) is the one within its tolerance (0.07
#: with S = 1 after the wave; 0.09 with Persson's S, γ = 0.8, the default since issue 38).
SEPARATED_RATIO, SEPARATED_LOW_SLOPE = 16.0, 0.4
SEPARATED_CONTACT = (0.02, 0.2)
SEPARATED_HIGH_WAVELENGTH = 1.0 / 16    # mm, at SPLIT_SPEEDS
SEPARATED_TOLERANCE = 0.09

#: Absolute μ below which a departure from the VHS is the half-space grids' noise, not a
#: model's: the hybrids' grid moves μ by this much at the slowest speeds on the asphalt
#: (docs/guide/models.md, "Grids of the half-space models").
MU_NOISE = 1.5e-4

#: Relative slack of a bound against the rounding of a value computed from its inputs.
ROUNDING = 1e-9

#: What a condition bounds: a label and the unit of its value.
QUANTITIES = {
    "m2": "per-wave rms slope m2",
    "m2_low": "low-slope per-wave m2",
    "m2_high": "high-slope per-wave m2 (the law's cell)",
    "split_ratio": "wavelength ratio at the split (shortest low- / longest high-slope)",
    "spacing": "neighbouring wavelength ratio",
    "contact": "contact fraction",
    "frequency": "wave frequency q·v",
    "frequency_high": "high-slope wave frequency q·v",
    "law_pressure": "local pressure / the law's highest FEM pressure",
    "dimension": "surface dimension (1: profiles, 2: maps)",
}
#: The quantities that vary with the speed (the rest are the surface's).
SPEED_QUANTITIES = frozenset({"contact", "frequency", "frequency_high", "law_pressure"})


@dataclass(frozen=True)
class Condition:
    """One bound of a validated class: ``low <= value <= high`` for every value.

    Attributes
    ----------
    quantity
        A key of :data:`QUANTITIES`.
    low, high
        The bounds (frequencies in rad/s on the SBR's scale; slopes, ratios and fractions
        dimensionless).
    report
        The report that measured the bound.
    """

    quantity: str
    low: float = -math.inf
    high: float = math.inf
    report: str = ""

    def excess(self, values: np.ndarray) -> float:
        """The factor (>= 1) by which the worst value lies outside the bounds, 1 if inside
        (or if there is no value: the condition does not apply)."""
        v = np.asarray(values, float)
        v = v[np.isfinite(v)]
        if v.size == 0:
            return 1.0
        over = v.max() / self.high if v.max() > self.high else 1.0
        under = 1.0
        if v.min() < self.low:
            under = self.low / v.min() if v.min() > 0 else math.inf
        worst = float(max(over, under))
        # a value at the bound up to rounding (an m2 recomputed from its amplitude) is on it
        return 1.0 if worst <= 1.0 + ROUNDING else worst

    def bounds_text(self) -> str:
        if self.low > -math.inf and self.high < math.inf:
            return f"{self.low:.3g}–{self.high:.3g}"
        return f"≤ {self.high:.3g}" if self.high < math.inf else f"≥ {self.low:.3g}"


@dataclass(frozen=True)
class ValidatedClass:
    """Where a model was validated: its conditions and its tolerance there.

    Attributes
    ----------
    model
        The model's name (``vhs``, ``hybrid``, ...).
    name
        The class in a few words, for the notes.
    conditions
        Its bounds, each with its report.
    reference
        What the model was compared with.
    tolerance
        The largest relative μ error against the reference measured inside the class.
    report
        The report of the tolerance.
    reduces_to
        The model it is without a high-slope wave (a law model: no law to read), or "".
    departs
        Whether its μ is compared with the VHS's (not for the VHS itself, the reference).
    """

    model: str
    name: str
    conditions: tuple[Condition, ...]
    reference: str
    tolerance: float
    report: str
    reduces_to: str = ""
    departs: bool = True


def _band(wavelengths: tuple[float, float], speeds: tuple[float, float]) -> tuple[float, float]:
    """The frequencies q v [rad/s] of waves in ``wavelengths`` [mm] at ``speeds`` [mm/s]."""
    return (2 * math.pi / max(wavelengths) * speeds[0],
            2 * math.pi / min(wavelengths) * speeds[1])


def _with_dimension(cls: ValidatedClass) -> ValidatedClass:
    """``cls`` bounded to the one-dimensional surfaces every class was measured on."""
    profiles = Condition("dimension", high=1.0, report=MAPS_REPORT)
    return replace(cls, conditions=(profiles, *cls.conditions))


def _classes() -> dict[str, ValidatedClass]:
    return {m: _with_dimension(c) for m, c in _classes_1d().items()}


def _classes_1d() -> dict[str, ValidatedClass]:
    slope = Condition("m2", high=MEASURED_SLOPE, report=VHS_REPORT)
    high = Condition("m2_high", high=MEASURED_SLOPE, report=SECTION3_REPORT)
    split_band = _band((SPLIT_HIGH_WAVELENGTH,) * 2, SPLIT_SPEEDS)
    hs_speeds = Condition("frequency_high", *split_band, report=SPLIT_REPORT)
    law = Condition("law_pressure", high=1.0, report=LAW_REPORT)
    contact3 = Condition("contact", *SECTION3_CONTACT, report=SECTION3_REPORT)
    split_low = Condition("m2_low", high=SPLIT_LOW_SLOPE, report=SECTION3_REPORT)
    ladders = ValidatedClass(
        "meanfield-strips", "random octave ladders",
        (Condition("m2", high=LADDER_SLOPE, report=MEANFIELD_REPORT),
         Condition("spacing", OCTAVE * (1 - OCTAVE_SLACK), OCTAVE * (1 + OCTAVE_SLACK),
                   report=MEANFIELD_REPORT),
         Condition("contact", *LADDER_CONTACT, report=MEANFIELD_REPORT),
         Condition("frequency", *_band(LADDER_WAVELENGTHS, LADDER_SPEEDS),
                   report=MEANFIELD_REPORT)),
        "the VHS", LADDER_TOLERANCE, MEANFIELD_REPORT)
    return {
        "vhs": ValidatedClass("vhs", "slopes within the FEM sweep's", (slope,),
                              "the full FEM", VHS_FEM_TOLERANCE, SECTION3_REPORT,
                              departs=False),
        "fem": ValidatedClass("fem", "the section 3 surface's slopes and areas",
                              (slope, contact3), "the VHS", VHS_FEM_TOLERANCE,
                              SECTION3_REPORT),
        "hybrid": ValidatedClass(
            "hybrid", "scale-separated split, the section 3 law",
            (Condition("split_ratio", low=POINTWISE_RATIO, report=SPLIT_REPORT), split_low,
             high, contact3, hs_speeds, law),
            "the VHS", POINTWISE_TOLERANCE, SPLIT_REPORT, reduces_to="vhs"),
        "hybrid-windowed": ValidatedClass(
            "hybrid-windowed", "octave split or wider, the section 3 law",
            (Condition("split_ratio", low=WINDOWED_RATIO, report=SPLIT_REPORT), split_low,
             high, contact3, hs_speeds, law),
            "the VHS", WINDOWED_TOLERANCE, SPLIT_REPORT, reduces_to="vhs"),
        "meanfield": replace(ladders, model="meanfield",
                             tolerance=PERSSON_LADDER_TOLERANCE),
        "meanfield-strips": ladders,
        "meanfield-hybrid": ValidatedClass(
            "meanfield-hybrid", "scale-separated surfaces, ratio 16 at the split",
            (Condition("split_ratio", low=SEPARATED_RATIO, report=MEANFIELD_REPORT),
             Condition("m2_low", high=SEPARATED_LOW_SLOPE, report=MEANFIELD_REPORT), high,
             Condition("contact", *SEPARATED_CONTACT, report=MEANFIELD_REPORT),
             Condition("frequency_high", *_band((SEPARATED_HIGH_WAVELENGTH,) * 2, SPLIT_SPEEDS),
                       report=MEANFIELD_REPORT), law),
            "the VHS", SEPARATED_TOLERANCE, MEANFIELD_REPORT, reduces_to="meanfield"),
    }


#: The validated class of each model, by name.
CLASSES: dict[str, ValidatedClass] = _classes()


