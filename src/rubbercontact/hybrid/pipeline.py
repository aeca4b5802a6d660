"""Former home of the run pipeline, now :mod:`rubbercontact.pipeline` (it runs every model,
not the hybrid only). These names stay importable from here for existing scripts."""

from __future__ import annotations

from ..inputs import build_material as _build_material
from ..inputs import build_surface as _build_surface
from ..pipeline.assemble import NOT_RUN, RESULT_VARIABLES, failed_solves, failure_message
from ..pipeline.execute import make_runner, run
from ..pipeline.lawstage import build_law as _build_law
from ..pipeline.plan import full_fem_task
from ..pipeline.setup import HYBRID_MODELS
from ..pipeline.setup import translated_to_zero_phase as _translated_to_zero_phase
from ..pipeline.statistics import PHASE_MEAN_VARIABLES, add_phase_means, mean_of

__all__ = ["run", "make_runner", "build_material", "build_surface", "build_law",
           "full_fem_task", "failed_solves", "failure_message", "add_phase_means", "mean_of",
           "NOT_RUN", "RESULT_VARIABLES", "PHASE_MEAN_VARIABLES", "HYBRID_MODELS",
           "_translated_to_zero_phase"]


def build_material(cfg):
    """The material of a :class:`~rubbercontact.config.RunConfig`."""
    return _build_material(cfg.material)


def build_surface(cfg):
    """``(series, info)``: the base sine series of a config and where it came from."""
    built = _build_surface(cfg.surface)
    return built.series, built.info


def build_law(cfg, hs0, material, pressures, runner, law=None):
    """``(law, tables, fem_time)`` of :func:`rubbercontact.pipeline.lawstage.build_law`."""
    stage = _build_law(cfg, hs0, material, pressures, runner, law)
    return stage.law, stage.tables, stage.fem_time
