"""The mean-field models: Persson's theory (``"meanfield"``) and the strip cascade of a 1D
sine series (``"meanfield-strips"``); one solve per mean pressure."""

from __future__ import annotations

from typing import Any

from ..errors import InputError
from ..roughness import SineSeries
from .base import TaskModel, scalar_rows
from .halfspace import _material_dict

__all__ = ["MeanField", "MeanFieldStrips"]

MEANFIELD_TASK = "rubbercontact.meanfield.tasks:meanfield_task"


def task_kwargs(surface: dict, material: dict, velocity: float, mean_pressure: float,
                nu: float, options: Any, interface_law: dict | None = None) -> dict:
    """The mean-field task's arguments (the one writer: scripts and runs share entries)."""
    return {"surface": surface, "material": material, "velocity": float(velocity),
            "mean_pressure": float(mean_pressure), "nu": float(nu),
            "interface_law": interface_law, "options": options.to_dict()}


class MeanField(TaskModel):
    """Persson's mean-field theory with ``S(q)`` on the surface's spectrum.

    Parameters
    ----------
    options
        :class:`rubbercontact.meanfield.MeanFieldOptions` (default: its defaults).
    nu
        Poisson's ratio [-].
    """

    name = "meanfield"
    _options_class = "MeanFieldOptions"

    def __init__(self, options: Any = None, nu: float = 0.5) -> None:
        from .. import meanfield as mf

        cls = getattr(mf, self._options_class)
        opts = cls() if options is None else options
        if not isinstance(opts, cls):
            raise InputError(f"model {self.name}: options must be {cls.__name__}, got "
                             f"{type(opts).__name__}")
        self.options = opts
        self.nu = float(nu)

    def tasks(self, surface, material, velocity, pressures):
        from ..meanfield import PSD
        from ..sweep import Task

        data = surface.as_dict() if isinstance(surface, (SineSeries, PSD)) else dict(surface)
        mat = _material_dict(material)
        return [Task(MEANFIELD_TASK, task_kwargs(data, mat, velocity, p, self.nu, self.options),
                     label=f"{self.name} v={velocity:g} p={p:.4g}") for p in pressures]

    def collect(self, results, velocity, pressures):
        return scalar_rows(self.name, results, velocity, pressures,
                           {k: str(v) for k, v in self.options.to_dict().items()})


class MeanFieldStrips(MeanField):
    """The cascade of Westergaard strips of a 1D sine series
    (:class:`rubbercontact.meanfield.StripOptions`)."""

    name = "meanfield-strips"
    _options_class = "StripOptions"
