"""The hybrid multiscale method: effective law of the high-slope scale + half-space on the rest."""

from .law import LawWarning, effective_law, law_at_velocity, screen_monotone
from .metrics import bootstrap_interval, interpolate_at_areas, mean_relative_error

__all__ = ["effective_law", "law_at_velocity", "screen_monotone", "run", "mean_relative_error",
           "interpolate_at_areas", "bootstrap_interval", "LawWarning"]


def __getattr__(name: str):
    # rc.hybrid.run is the run pipeline (rubbercontact.pipeline.run), which sits above this
    # package: imported on first use, so that this package never imports it.
    if name == "run":
        from ..pipeline import run

        return run
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
