"""How a run plans a model: which tasks, how many, and what each reads.

Every registered model class says it (:attr:`~.base.TaskModel.planning`, a
:class:`Planning`) and writes its task at each place of a run
(:meth:`~.base.TaskModel.run_task` at a :class:`RunPoint`); :mod:`rubbercontact.pipeline.plan`
loops over the speeds and the places the planning names, asking the registry, so a new
model is its module and one registration. The model's module writes the task's arguments
for a script and for a run alike: both share cache entries.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import InputError

__all__ = ["PER", "PER_LOAD", "PER_REALIZATION", "PER_REALIZATION_LOAD", "Planning",
           "RunPoint"]

#: One task per speed and realization over every load (the half-space models: short solves,
#: one cache file per task).
PER_REALIZATION = "realization"
#: One task per speed and load, standing for every realization (the mean-field models see
#: only the spectrum, which the phases do not change).
PER_LOAD = "load"
#: One task per speed, load and realization of the first ``fem.realizations`` (the full
#: FEM: each test is long).
PER_REALIZATION_LOAD = "realization-load"
PER = (PER_REALIZATION, PER_LOAD, PER_REALIZATION_LOAD)


@dataclass(frozen=True)
class Planning:
    """How a run plans a model.

    Attributes
    ----------
    per
        The places of its tasks (:data:`PER`).
    reads_law
        It reads the high-slope law (a run then builds one when the surface has a
        high-slope scale).
    splits
        Its friction is a low-slope part plus the law's high-slope part (``friction_hs``);
        otherwise all of its friction is the low-slope part.
    """

    per: str
    reads_law: bool = False
    splits: bool = False

    def __post_init__(self) -> None:
        if self.per not in PER:
            raise InputError(f"planning: per must be one of {', '.join(PER)}, got "
                             f"{self.per!r}")


@dataclass(frozen=True)
class RunPoint:
    """One task's place in a run, as a model's :meth:`~.base.TaskModel.run_task` reads it.

    Attributes
    ----------
    setup
        The resolved run (:class:`rubbercontact.pipeline.setup.RunSetup`).
    material
        The rubber as the tasks see it.
    velocity
        The computed sliding speed [mm/s].
    pressures
        Mean pressures σ0 [MPa]: every load of the run (``per = "realization"``) or the
        task's one load.
    table
        The high-slope law at this speed as plain data, or ``None``.
    realization
        Index of the realization, or ``None`` (``per = "load"``).
    shared
        The model's per-run data (:meth:`~.base.TaskModel.run_data`, e.g. a spectrum).
    """

    setup: Any
    material: Any
    velocity: float
    pressures: np.ndarray
    table: dict | None
    realization: int | None
    shared: Any = None

    @property
    def pressure(self) -> float:
        """The task's one mean pressure [MPa]."""
        (p,) = self.pressures
        return float(p)
