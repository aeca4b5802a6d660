"""The sweep tasks of a run's models, planned by asking the model registry.

Each registered model says how a run plans it (:class:`rubbercontact.models.planning.Planning`):
the half-space models (``vhs``, ``hybrid``, ``hybrid-windowed``) run one task per speed and
realization over every load (the solves are short, and each task is one cache file); the
full FEM one per speed, realization and load; the mean-field models see only the spectrum,
so they run once per speed and load and their answer stands for every realization. The
model's module writes each task (``run_task``). Speeds are the *computed* speeds of the
:class:`~.speeds.SpeedPlan` (the reduced speeds of a run with temperatures).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from ..config import RunConfig
from ..fem.loadrange import held
from ..materials import GeneralizedMaxwell
from ..models import registry
from ..models.fem import FEM_TASK, config_kwargs
from ..models.meanfield import config_call
from ..models.planning import PER_LOAD, PER_REALIZATION, PER_REALIZATION_LOAD, RunPoint
from ..roughness import SineSeries
from .cost import model_task_seconds
from .setup import RunSetup

if TYPE_CHECKING:
    from ..sweep import Task

#: The mean-field models whose surfaces :func:`meanfield_surfaces` returns.
MEANFIELD_SURFACES = ("meanfield", "meanfield-strips", "meanfield-hybrid")


class Slot(NamedTuple):
    """Where a task's result goes: model, speed index, realization (None: every one), load
    (None: every load, the result on a ``pressure`` dimension)."""

    model: str
    iv: int
    ir: int | None
    ip: int | None


def model_tasks(setup: RunSetup, material: GeneralizedMaxwell, pressures: np.ndarray,
                tables: dict) -> tuple[list[Slot], list[Task]]:
    """Every model task of a run and the slot of each, as each model's planning says.

    Parameters
    ----------
    setup
        The resolved run.
    material
        The rubber as the tasks see it (:func:`~.setup.task_material`).
    pressures
        Mean pressures σ0 [MPa].
    tables
        ``{speed: law table or None}`` at each computed speed.
    """
    from ..sweep import Task

    slots, tasks = [], []
    for m in setup.models:
        cls = registry.model_class(m)
        per = cls.planning.per
        shared = cls.run_data(m, setup)
        for iv, v in enumerate(setup.speeds.computed):
            table = tables.get(float(v))
            for ir, ip in places(per, len(setup.realizations), setup.n_fem,
                                 run_loads(per, pressures, material)):
                p = pressures if ip is None else pressures[ip:ip + 1]
                fn, kw = cls.run_task(m, RunPoint(setup, material, float(v), p, table, ir,
                                                  shared))
                tasks.append(Task(function=fn, kwargs=kw, label=_label(m, v, ir, p, ip),
                                  cost=model_task_seconds(setup, m, p)))
                slots.append(Slot(m, iv, ir, ip))
    return slots, tasks


def run_loads(per: str, pressures: np.ndarray, material: GeneralizedMaxwell) -> list[int]:
    """The indices of the loads a model planned ``per`` runs tasks at: every one, except
    that the full FEM (per realization and load) skips those above the rubber's ``E∞``,
    outside its cell's range (:mod:`rubbercontact.fem.loadrange`; the results say so,
    :func:`~.assemble.assemble`)."""
    if per != PER_REALIZATION_LOAD:
        return list(range(len(pressures)))
    return [int(i) for i in np.flatnonzero(held(pressures, material.equilibrium_modulus))]


def places(per: str, realizations: int, n_fem: int, loads: list[int]
           ) -> Iterator[tuple[int | None, int | None]]:
    """``(realization, load)`` index of each task of one model at one speed (``None``:
    every one), in the order of its tasks; ``loads`` the indices of the loads it runs
    (:func:`run_loads`)."""
    if per == PER_REALIZATION:
        yield from ((ir, None) for ir in range(realizations))
    elif per == PER_LOAD:
        yield from ((None, ip) for ip in loads)
    else:
        yield from ((ir, ip) for ip in loads for ir in range(n_fem))


def _label(model: str, v: float, ir: int | None, p: np.ndarray, ip: int | None) -> str:
    return " ".join([model, f"v={v:g}"] + ([] if ir is None else [f"r={ir}"])
                    + ([] if ip is None else [f"p={float(p[0]):.4g}"]))


def meanfield_surfaces(setup: RunSetup) -> dict:
    """The surface each mean-field model reads, as plain data (each model's ``run_data``).

    ``meanfield``: the whole spectrum (the sine series, or the measured profiles'
    periodogram with ``meanfield.spectrum = "profiles"``); ``meanfield-strips``: the sine
    series; ``meanfield-hybrid``: the low-slope waves (the high-slope law carries the rest),
    or the whole series when it has no high-slope wave.
    """
    return {m: registry.model_class(m).run_data(m, setup) for m in MEANFIELD_SURFACES}


def meanfield_call(cfg: RunConfig, model: str, surface: dict, material: GeneralizedMaxwell,
                   v: float, p: float, table, period: float) -> tuple[str, dict]:
    """Function and keyword arguments of one mean-field task
    (:func:`rubbercontact.models.meanfield.config_call`; ``table`` is read by the models
    that read the law)."""
    law = table if registry.needs_law(model) else None
    return config_call(cfg, model, surface, material, v, p, law, period)


def full_fem_task(cfg: RunConfig, surface: SineSeries, material: GeneralizedMaxwell,
                  velocity: float, mean_pressure: float) -> Task:
    """The sweep task of one full-FEM sliding test (model ``fem``) with the config's options
    (:func:`rubbercontact.models.fem.config_kwargs`)."""
    from ..sweep import Task

    return Task(function=FEM_TASK,
                kwargs=config_kwargs(cfg, surface, material, velocity, mean_pressure),
                label=f"fem v={velocity:g} p={mean_pressure:.4g}")
