"""Comparing models with the full FEM: the paper's eq. 28 at equal contact area.

One implementation for ``rubbercontact run``, the studies and VALIDATION.md. Modules:
:mod:`.equal_area` (common areas, eq. 28, paired bootstrap intervals over realizations,
the signed errors and the range of eq. 28 they allow, :class:`Eq28`) and :mod:`.phase`
(the FEM's phase average by a control variate and eq. 28 against it).
"""

from .equal_area import (
    AREA_FACTORS,
    INTERVAL_LEVEL,
    RESAMPLES,
    Eq28,
    area_sensitivity,
    common_areas,
    eq28_at_equal_area,
    eq28_bounds,
    eq28_first,
    eq28_intervals,
    eq28_of_curves,
    eq28_realization_bounds,
    friction_at_common_areas,
    per_realization_errors,
    with_area_factor,
    with_realization_means,
)
from .phase import (
    CHEAP_MODELS,
    below_load,
    eq28_phase_averaged,
    eq28_phase_bounds,
    merge_phase_data,
    phase_area_range,
    phase_mean_curves,
    without_model,
)

__all__ = ["AREA_FACTORS", "CHEAP_MODELS", "INTERVAL_LEVEL", "RESAMPLES", "Eq28",
           "area_sensitivity", "below_load", "common_areas", "eq28_at_equal_area",
           "eq28_bounds", "eq28_first", "eq28_intervals", "eq28_of_curves",
           "eq28_phase_averaged", "eq28_phase_bounds", "eq28_realization_bounds",
           "friction_at_common_areas", "merge_phase_data", "per_realization_errors",
           "phase_area_range", "phase_mean_curves", "with_area_factor",
           "with_realization_means", "without_model"]
