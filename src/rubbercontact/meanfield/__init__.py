"""Mean-field (Persson) rubber friction and contact for roughness over many decades.

``PSD`` (the spectrum: from line scans, a map, a sine series or self-affine), ``solve`` (one
speed and load; ``law=`` enriches it by the hybrid's FEM law of the high-slope scale) and
``friction_curve`` (many speeds at once), each with the options object of one model
(:mod:`.options`): ``MeanFieldOptions`` (Persson's theory with ``S(q)``, model
``meanfield``) or ``StripOptions`` (the strip cascade of a 1D sine series,
``meanfield-strips``); ``flash_friction_curve`` (the same with the flash
temperature of :mod:`.flash`). The 1D (plane strain) form of the theory and its
constants are derived in :mod:`.contact`, the friction and its ``S(q)`` in :mod:`.friction`,
the enrichment in :mod:`.enriched`; the validation against the BEM is
docs/validation/meanfield.md.
"""

from .contact import AreaCurve, PressureDistribution
from .enriched import PressureLaw
from .flash import FlashCurve, FlashOptions, FlashWarning, flash_friction_curve
from .options import (
    DEFAULT_GAMMA,
    Dissipation,
    MeanFieldOptions,
    SCorrection,
    StripOptions,
    Weighting,
    options_from_dict,
)
from .psd import PSD
from .solve import FrictionCurve, MeanFieldResult, friction_curve, solve

__all__ = ["PSD", "solve", "friction_curve", "MeanFieldOptions", "MeanFieldResult",
           "FrictionCurve", "PressureDistribution", "AreaCurve", "PressureLaw",
           "SCorrection", "Weighting", "Dissipation", "StripOptions", "DEFAULT_GAMMA",
           "options_from_dict", "flash_friction_curve", "FlashOptions", "FlashCurve",
           "FlashWarning"]
