"""The sweep tasks of a run's models.

The half-space models (``vhs``, ``hybrid``, ``hybrid-windowed``) run one task per speed and
realization over every load (the solves are short, and each task is one cache file); the
full FEM one per speed, realization and load; the mean-field models see only the spectrum,
so they run once per speed and load and their answer stands for every realization. Speeds
are the *computed* speeds of the :class:`~.speeds.SpeedPlan` (the reduced speeds of a run
with temperatures).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from ..config import RunConfig
from ..hybrid.grid import low_slope_points
from ..materials import GeneralizedMaxwell
from ..roughness import SineSeries
from .setup import (
    HYBRID_MODELS,
    MEANFIELD_MODELS,
    RunSetup,
    static_series,
    task_material,
    translated_to_zero_phase,
)

if TYPE_CHECKING:
    from ..sweep import Task

HALFSPACE_TASK = "rubbercontact.hybrid.tasks:halfspace_task"
HALFSPACE_LOADS_TASK = "rubbercontact.hybrid.tasks:halfspace_loads_task"
MEANFIELD_TASK = "rubbercontact.meanfield.tasks:meanfield_task"


class Slot(NamedTuple):
    """Where a task's result goes: model, speed index, realization (None: every one), load
    (None: every load, the result on a ``pressure`` dimension)."""

    model: str
    iv: int
    ir: int | None
    ip: int | None


def model_tasks(setup: RunSetup, material: GeneralizedMaxwell, pressures: np.ndarray,
                tables: dict) -> tuple[list[Slot], list[Task]]:
    """Every model task of a run and the slot of each.

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

    cfg = setup.config
    slots, tasks = [], []
    spectrum = meanfield_surfaces(setup) if MEANFIELD_MODELS & set(setup.models) else {}
    for m in setup.models:
        for iv, v in enumerate(setup.speeds.computed):
            table = tables.get(float(v))
            if m not in MEANFIELD_MODELS and m != "fem":
                # the half-space models: one task per realization over every load
                for ir, (real, parts) in enumerate(zip(setup.realizations, setup.parts,
                                                       strict=True)):
                    kw = halfspace_kwargs(cfg, m, real, parts.low, parts.high.size > 0, setup,
                                          material, float(v), pressures, table, keep=ir == 0)
                    tasks.append(Task(function=HALFSPACE_LOADS_TASK, kwargs=kw,
                                      label=f"{m} v={v:g} r={ir}"))
                    slots.append(Slot(m, iv, ir, None))
                continue
            for ip, p in enumerate(pressures):
                if m in MEANFIELD_MODELS:
                    fn, kw = meanfield_call(cfg, m, spectrum[m], material, float(v), float(p),
                                            table, setup.period)
                    tasks.append(Task(function=fn, kwargs=kw, label=f"{m} v={v:g} p={p:.4g}"))
                    slots.append(Slot(m, iv, None, ip))
                    continue
                for ir, real in enumerate(setup.realizations[:setup.n_fem]):
                    task = full_fem_task(cfg, real, material, float(v), float(p))
                    tasks.append(Task(function=task.function, kwargs=task.kwargs,
                                      label=f"{m} v={v:g} r={ir} p={p:.4g}"))
                    slots.append(Slot(m, iv, ir, ip))
    return slots, tasks


def halfspace_kwargs(cfg: RunConfig, model: str, real: SineSeries, low: SineSeries,
                     has_high: bool, setup: RunSetup, material: GeneralizedMaxwell,
                     v: float, pressures: np.ndarray, table, keep: bool) -> dict:
    """Keyword arguments of one half-space task at every load (VHS, or the hybrid's
    low-slope solve, on ``halfspace.hybrid_n`` points or the grid of
    :func:`~rubbercontact.hybrid.grid.low_slope_points`)."""
    from ..models.halfspace import HalfspaceOptions, loads_kwargs

    hsc = cfg.halfspace
    surf = real if (model == "vhs" or not has_high) else low
    n = hsc.n
    if model in HYBRID_MODELS and has_high:
        # the low-slope solve on its own grid (rubbercontact.hybrid.grid)
        n = hsc.hybrid_n or low_slope_points(hsc.n, real, low)
    options = HalfspaceOptions(n=hsc.n, nu=cfg.material.nu, law=hsc.law, tol=hsc.tol)
    window = (float(setup.hs0.period) if model == "hybrid-windowed" and has_high else None)
    return loads_kwargs(surf, setup.period, material, v, pressures, options, n=n,
                        interface_law=table if model in HYBRID_MODELS else None,
                        hs_window=window, keep_profile=keep)


def meanfield_surfaces(setup: RunSetup) -> dict:
    """The surface each mean-field model reads, as plain data.

    ``meanfield``: the whole spectrum (the sine series, or the measured profiles'
    periodogram with ``meanfield.spectrum = "profiles"``); ``meanfield-strips``: the sine
    series; ``meanfield-hybrid``: the low-slope waves (the high-slope law carries the rest),
    or the whole series when it has no high-slope wave.
    """
    cfg = setup.config
    series = static_series(setup.base)
    out = {}
    if cfg.meanfield.spectrum == "profiles":
        from ..meanfield import PSD
        from ..meanfield.psd import NODES_PER_DECADE

        psd = PSD.from_profiles(setup.surface.profiles,
                                nodes_per_decade=cfg.meanfield.nodes_per_decade
                                or NODES_PER_DECADE)
        out["meanfield"] = psd.as_dict()
    else:
        out["meanfield"] = series.as_dict()
    out["meanfield-strips"] = series.as_dict()
    high, low = series.partition(cfg.surface.m2_threshold)
    out["meanfield-hybrid"] = (low if high.size else series).as_dict()
    return out


def meanfield_call(cfg: RunConfig, model: str, surface: dict, material: GeneralizedMaxwell,
                   v: float, p: float, table, period: float) -> tuple[str, dict]:
    """Function and keyword arguments of one mean-field task.

    ``meanfield-hybrid`` on a surface whose waves are all high-slope has no low-slope
    spectrum: the interface is flat and the exact answer is the law itself, which the
    half-space task's flat-interface solve gives (as for the hybrid).
    """
    law = table if model == "meanfield-hybrid" else None
    if law is not None and not surface["wavelengths"]:
        return HALFSPACE_TASK, {"surface": surface, "period": period,
                                "material": task_material(material), "velocity": v,
                                "mean_pressure": p, "n": cfg.halfspace.n,
                                "nu": cfg.material.nu, "law": cfg.halfspace.law,
                                "interface_law": law}
    from ..models.meanfield import task_kwargs

    # without a law (no high-slope wave) meanfield-hybrid is the plain theory: no interface
    opts = cfg.meanfield.options(model if law is not None or model != "meanfield-hybrid"
                                 else "meanfield")
    return MEANFIELD_TASK, task_kwargs(surface, task_material(material), v, p,
                                       cfg.material.nu, opts, interface_law=law)


def full_fem_task(cfg: RunConfig, surface: SineSeries, material: GeneralizedMaxwell,
                  velocity: float, mean_pressure: float) -> Task:
    """The sweep task of one full-FEM sliding test (model ``fem``) with the config's options
    (``cfg.fem.options(material, full=True)``); the surface is translated to zero phase, so
    that on an all-high-slope surface it is the law's cell and shares its cache entries."""
    from ..sweep import Task

    kw = {"surface": translated_to_zero_phase(surface).as_dict(),
          "material": task_material(material), "velocity": float(velocity),
          "mean_pressure": float(mean_pressure),
          "options": cfg.fem.options(material, full=True).to_dict()}
    return Task(function="rubbercontact.hybrid.tasks:fem_task", kwargs=kw,
                label=f"fem v={velocity:g} p={mean_pressure:.4g}")
