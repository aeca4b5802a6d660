"""The hybrid multiscale method: effective law of the high-slope scale + half-space on the rest."""

from .law import LawWarning, effective_law, law_at_velocity, screen_monotone
from .maps import MapHybridOptions, MapHybridResult, linear_law_map, solve_map, solve_map_hybrid
from .metrics import bootstrap_interval, interpolate_at_areas, mean_relative_error

__all__ = ["effective_law", "law_at_velocity", "screen_monotone", "mean_relative_error",
           "interpolate_at_areas", "bootstrap_interval", "LawWarning", "MapHybridOptions",
           "MapHybridResult", "linear_law_map", "solve_map", "solve_map_hybrid"]

