"""The full FEM as a model: one steady (or time-stepped) sliding test per mean pressure."""

from __future__ import annotations

from typing import Any

from ..errors import InputError
from ..roughness import SineSeries
from .base import TaskModel, scalar_rows
from .halfspace import _material_dict
from .planning import PER_REALIZATION_LOAD, Planning, RunPoint

__all__ = ["FEM"]

FEM_TASK = "rubbercontact.hybrid.tasks:fem_task"


class FEM(TaskModel):
    """The finite-strain viscoelastic FEM on the whole surface (``"fem"``).

    Parameters
    ----------
    options
        :class:`rubbercontact.fem.FemOptions` (default: the steady solver on 120 × 90), or
        ``None``; ``**changes`` set its fields by name (``mesh=(240, 45)``, ``grading=8``, ...).
    """

    name = "fem"
    planning = Planning(PER_REALIZATION_LOAD)

    def __init__(self, options: Any = None, **changes: Any) -> None:
        from ..fem import make_options

        self.options = make_options(options, **changes)

    def tasks(self, surface, material, velocity, pressures):
        from ..pipeline.setup import translated_to_zero_phase
        from ..sweep import Task

        if not isinstance(surface, SineSeries):
            raise InputError(f"surface: the FEM takes a SineSeries, got {type(surface).__name__}")
        opts = self.options.to_dict()
        # translated as a run's full FEM is (the same answer on a periodic cell), so that a
        # script and a run share the cache entry
        surface = translated_to_zero_phase(surface)
        return [Task(FEM_TASK, {"surface": surface.as_dict(),
                                "material": _material_dict(material), "velocity": velocity,
                                "mean_pressure": float(p), "options": opts},
                     label=f"fem v={velocity:g} p={p:.4g}") for p in pressures]

    @classmethod
    def run_task(cls, name: str, point: RunPoint) -> tuple[str, dict]:
        """One test of a realization (of the first ``fem.realizations``) at one load."""
        s = point.setup
        return FEM_TASK, config_kwargs(s.config, s.realizations[point.realization],
                                       point.material, point.velocity, point.pressure)

    def collect(self, results, velocity, pressures):
        return scalar_rows(self.name, results, velocity, pressures,
                           {"solver": self.options.solver})


def config_kwargs(cfg: Any, surface: SineSeries, material: Any, velocity: float,
                  mean_pressure: float) -> dict:
    """Arguments of one full-surface FEM test with a run config's options
    (``cfg.fem.options(material, full=True)``); the surface is translated to zero phase, so
    that on an all-high-slope surface it is the law's cell and shares its cache entries."""
    from ..pipeline.setup import translated_to_zero_phase

    return {"surface": translated_to_zero_phase(surface).as_dict(),
            "material": _material_dict(material), "velocity": float(velocity),
            "mean_pressure": float(mean_pressure),
            "options": cfg.fem.options(material, full=True).to_dict()}
