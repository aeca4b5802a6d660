"""Persson's mean-field theory as a model (``"meanfield"``): one solve per mean pressure."""

from __future__ import annotations

from dataclasses import asdict
from typing import Any

from ..roughness import SineSeries
from .base import TaskModel, scalar_rows
from .halfspace import _material_dict

__all__ = ["MeanField"]

MEANFIELD_TASK = "rubbercontact.meanfield.tasks:meanfield_task"
#: The task's options (the fields of MeanFieldOptions that cross the task boundary).
_TASK_OPTIONS = ("correction", "gamma", "weighting", "interface", "dissipation", "geometry")


class MeanField(TaskModel):
    """Persson's mean-field theory on the surface's spectrum.

    Parameters
    ----------
    options
        :class:`rubbercontact.meanfield.MeanFieldOptions` (default: its defaults).
    nu
        Poisson's ratio [-].
    """

    name = "meanfield"

    def __init__(self, options: Any = None, nu: float = 0.5) -> None:
        from ..meanfield import MeanFieldOptions

        self.options = options or MeanFieldOptions()
        self.nu = float(nu)

    def tasks(self, surface, material, velocity, pressures):
        from ..meanfield import PSD
        from ..sweep import Task

        data = surface.as_dict() if isinstance(surface, (SineSeries, PSD)) else dict(surface)
        opts = {k: v for k, v in asdict(self.options).items() if k in _TASK_OPTIONS}
        return [Task(MEANFIELD_TASK, {"surface": data, "material": _material_dict(material),
                                      "velocity": velocity, "mean_pressure": float(p),
                                      "nu": self.nu, "interface_law": None, **opts},
                     label=f"meanfield v={velocity:g} p={p:.4g}") for p in pressures]

    def collect(self, results, velocity, pressures):
        return scalar_rows(self.name, results, velocity, pressures,
                           {k: str(v) for k, v in asdict(self.options).items()
                            if k in _TASK_OPTIONS})
