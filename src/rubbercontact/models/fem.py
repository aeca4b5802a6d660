"""The full FEM as a model: one steady (or time-stepped) sliding test per mean pressure."""

from __future__ import annotations

from typing import Any

from ..errors import InputError
from ..roughness import SineSeries
from .base import TaskModel, scalar_rows
from .halfspace import _material_dict

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

    def collect(self, results, velocity, pressures):
        return scalar_rows(self.name, results, velocity, pressures,
                           {"solver": self.options.solver})
