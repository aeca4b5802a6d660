"""``run(config)``: the models of a config, from set-up to the results dataset.

Steps (each in its module): resolve and check the set-up (:mod:`.setup`, :mod:`.speeds`),
the loads (:mod:`.loads`), the high-slope law (:mod:`.lawstage`), the model tasks (one per
model, speed and realization over every load for the half-space models; :mod:`.plan`),
their results stacked (:mod:`.assemble`), the
adhesive part (:mod:`.adhesion`), statistics and eq. 28 (:mod:`.statistics`), the
spread over temperatures (:mod:`.temperature`) and the flash temperature (:mod:`.flash`).
"""

from __future__ import annotations

import functools
import inspect
import json
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from ..config import RunConfig
from ..materials import GeneralizedMaxwell
from ..models.registry import needs_law
from .adhesion import AdhesionLaw, add_adhesion
from .assemble import add_law, add_profiles, assemble, model_times
from .flash import add_flash, plan_flash
from .lawcheck import add_quasi_static
from .lawcover import MAX_ROUNDS, coverage, describe, plan_extension
from .lawstage import LawStage, add_vhs, build_law, extend_law
from .loads import at_areas, run_pressures
from .plan import model_tasks
from .setup import RunSetup, resolve, task_material
from .statistics import add_errors, add_phase_means, add_realization_statistics
from .temperature import spread_over_temperatures

#: Executes a list of sweep tasks; returns per task an ``xr.Dataset`` or a failure record.
Runner = Callable[[list], list]

#: Version of the results file layout: 2 adds the optional ``temperature`` dimension, the
#: mean-field models and the adhesive friction; files without the attribute are version 1,
#: read alike.
RESULTS_FORMAT = 2


def make_runner(cfg: RunConfig, progress: bool | str = "auto",
                retry_failed: bool = False) -> Runner:
    """A runner backed by the sweep executor and result cache of the config."""
    from ..sweep import ExecutorConfig, ResultCache, run_sweep

    ex = cfg.execution
    cache = ResultCache(ex.cache) if ex.cache is not None else ResultCache.default()
    executor = ExecutorConfig(workers=ex.workers, threads_per_worker=ex.threads_per_worker,
                              scheduler=ex.scheduler)

    def runner(tasks: list, description: str = "sweep") -> list:
        return run_sweep(tasks, cache=cache, executor=executor, progress=progress,
                         retry_failed=retry_failed, description=description).results

    return runner


def run(config: RunConfig | dict | str | Path, *, runner: Runner | None = None,
        law: xr.Dataset | None = None, progress: bool | str = "auto",
        retry_failed: bool = False) -> xr.Dataset:
    """Run the models of a configuration and return the results dataset.

    Parameters
    ----------
    config
        A validated :class:`~rubbercontact.config.RunConfig`, a plain mapping with the
        same keys, or the path of a TOML file.
    runner
        Executes lists of sweep tasks; default: Dask executor + result cache from
        ``config.execution``.
    law
        A precomputed law table, or the results of a run that built one (skips the FEM on
        the high-slope scale); it must match the run's high-slope scale, rubber and speeds
        (the reduced speeds of a run with temperatures).
    progress
        Progress display of the sweeps (``"auto"``, True, False).
    retry_failed
        Recompute tasks whose failure is recorded in the cache.

    Returns
    -------
    xarray.Dataset
        Dims ``model, velocity, realization, pressure`` (``model, temperature, velocity,
        ...`` with ``temperatures``; ``contact_area`` when loads are target areas); the law
        table (``law_*``), the surface's waves, and provenance in ``attrs``.
    """
    cfg = as_config(config)
    if cfg.surface.map is not None:          # areal map: its own small run (.maprun)
        from .maprun import run_map

        return run_map(cfg)
    t_start = time.perf_counter()
    timings: dict[str, float] = {}
    setup = resolve(cfg)                       # every config-level check, before any task
    cfg = setup.config                         # with what the surface resolved (crest radius)
    flash = plan_flash(setup)                  # None unless [friction.flash_temperature]
    runner = runner or make_runner(cfg, progress, retry_failed)
    material = GeneralizedMaxwell(**task_material(setup.material))   # the series at T_ref
    speeds = setup.speeds.computed
    pressures = run_pressures(setup)

    stage = None
    if setup.needs_law:
        stage = build_law(cfg, setup.hs0, material, pressures, named(runner, "law FEM"), law,
                          velocities=speeds, progress=progress)
    t0 = time.perf_counter()
    models = run_models(setup, material, pressures, stage, runner, progress)
    timings["models"] = time.perf_counter() - t0 - models.law_time
    stage, slots, results, ds = models.stage, models.slots, models.results, models.ds
    if stage is not None:
        if stage.fem_time is not None:
            timings["law"] = stage.fem_time
        stage_law = add_vhs(stage.law, setup.hs0, material, cfg,
                            named(runner, "law VHS (Fig. 7)"))
    ds = add_profiles(ds, slots, results)
    per_model_time = model_times(slots, results)
    if stage is not None:
        if setup.speeds.isothermal:
            ds = add_law(ds, stage_law)
        per_model_time["law (FEM, counted once)"] = float(np.nansum(stage.law["wall_time"]))
    if cfg.friction.adhesion is not None:
        ds = add_adhesion(ds, AdhesionLaw.from_config(cfg.friction.adhesion))
    ds = add_realization_statistics(ds)
    if cfg.loads.contact_areas is not None:
        ds = at_areas(ds, np.asarray(cfg.loads.contact_areas, float), stacklevel=3)
    if "fem" in setup.models and setup.n_fem < len(setup.realizations):
        ds = add_phase_means(ds, setup.n_fem)
    ds = add_errors(ds)
    ds = spread_over_temperatures(ds, setup.speeds)
    ds, flash_time = add_flash(ds, setup, flash, stage.tables if stage is not None else None,
                               named(runner, "flash temperature"))
    if flash is not None:
        timings["flash"] = flash_time
    if stage is not None and not setup.speeds.isothermal:
        ds = add_law(ds, stage_law, on="law_velocity")
    ds = _with_validity(ds, setup)
    if stage is not None and stage.quasi_static is not None:
        ds = add_quasi_static(ds, stage.quasi_static)
    if models.coverage:
        ds.attrs["law_coverage"] = models.coverage
    timings["total"] = time.perf_counter() - t_start
    return _describe(ds, setup, timings, per_model_time)


@dataclass(frozen=True)
class ModelRuns:
    """The model tasks of a run, after the law was extended to cover them.

    Attributes
    ----------
    stage
        The law (extended), or None without one.
    slots, results
        The model tasks' slots and results (:func:`~.plan.model_tasks`).
    ds
        The results assembled (:func:`~.assemble.assemble`).
    coverage
        One line on the law's coverage of the local pressures ("" without a law).
    law_time
        Wall time of the law's extension FEM [s] (counted in ``stage.fem_time``).
    """

    stage: LawStage | None
    slots: list
    results: list
    ds: xr.Dataset
    coverage: str
    law_time: float


def run_models(setup: RunSetup, material: GeneralizedMaxwell, pressures: np.ndarray,
               stage: LawStage | None, runner: Runner,
               progress: bool | str = False) -> ModelRuns:
    """Run the model tasks; while the law models' local pressures go beyond the law's FEM
    points, extend the law (``law.extend``, :mod:`.lawcover`) and run those models again."""
    cfg = setup.config
    slots, tasks = model_tasks(setup, material, pressures, stage.tables if stage else {})
    order = longest_first(slots)
    results = [None] * len(tasks)
    for k, res in zip(order, named(runner, "models")([tasks[k] for k in order]), strict=True):
        results[k] = res
    ds = _assemble(setup, material, pressures, slots, results)
    if stage is None:
        return ModelRuns(None, slots, results, ds, "", 0.0)
    law_time0 = stage.fem_time or 0.0
    added: list[float] = []
    stopped: dict[float, str] = {}
    rounds = 0
    cov = coverage(ds, stage.law)
    top = cfg.law.max_pressure or np.inf
    while (cfg.law.extend and stage.raw is not None and cov.uncovered.any()
           and rounds < MAX_ROUNDS):
        ext = plan_extension(cov, stage.law, top, float(material.equilibrium_modulus))
        stopped.update(ext.stopped)
        if not ext.points:
            break
        rounds += 1
        added += list(ext.points)
        stage = extend_law(stage, ext.points, cfg, setup.hs0, material,
                           setup.speeds.computed, named(runner, "law FEM (extension)"),
                           progress)
        slots, tasks = model_tasks(setup, material, pressures, stage.tables)
        redo = [k for k, sl in enumerate(slots) if needs_law(sl.model)]
        again = named(runner, "models (law extended)")
        for k, res in zip(redo, again([tasks[k] for k in redo]), strict=True):
            results[k] = res
        ds = _assemble(setup, material, pressures, slots, results)
        cov = coverage(ds, stage.law)
    law_time = (stage.fem_time or 0.0) - law_time0
    text = describe(cov, added, stopped, rounds) if stage.raw is not None else ""
    return ModelRuns(stage, slots, results, ds, text, law_time)


def longest_first(slots: list) -> list[int]:
    """The order to hand the model tasks to the workers: the tasks of the models planned
    per speed, realization and load (the full FEM: minutes each) first, then the rest
    (half-space and mean-field solves: seconds). Long tasks first keep every worker busy
    to the end; the progress ETA weighs the tasks by their cost hints
    (:mod:`rubbercontact.sweep.progress`), so the short ones after them are not priced as
    long."""
    from ..models.planning import PER_REALIZATION_LOAD
    from ..models.registry import planning

    long = {m for m in {sl.model for sl in slots} if planning(m).per == PER_REALIZATION_LOAD}
    return sorted(range(len(slots)), key=lambda k: slots[k].model not in long)


def named(runner: Runner, description: str) -> Runner:
    """``runner`` with its progress lines naming the stage (``description``), when it takes
    a ``description`` (:func:`make_runner`'s does); a runner that does not is used as is."""
    try:
        params = inspect.signature(runner).parameters.values()
    except (TypeError, ValueError):
        return runner
    if any(p.name == "description" or p.kind is p.VAR_KEYWORD for p in params):
        return functools.partial(runner, description=description)
    return runner


def _assemble(setup: RunSetup, material: GeneralizedMaxwell, pressures: np.ndarray,
              slots: list, results: list) -> xr.Dataset:
    return assemble(setup.models, setup.speeds.computed, len(setup.realizations), pressures,
                    slots, results, material, setup.n_fem)


def _with_validity(ds: xr.Dataset, setup: RunSetup) -> xr.Dataset:
    """Each model's notes where the run leaves its validated class, one line a model, in
    ``attrs["validity_<model>"]`` ("" inside; :mod:`rubbercontact.validity`)."""
    from ..validity import as_attrs, assess_run

    notes = assess_run(ds, setup)
    for m in setup.models:
        ds.attrs.update(as_attrs(m, notes))
    return ds


def _describe(ds: xr.Dataset, setup: RunSetup, timings: dict, per_model_time: dict
              ) -> xr.Dataset:
    """The surface's waves and realizations, and the run's provenance."""
    from .. import __version__

    cfg, base = setup.config, setup.base
    ds["wavelength"] = ("wave", base.wavelengths, {"units": "mm"})
    ds["amplitude"] = ("wave", base.amplitudes, {"units": "mm"})
    ds["m2"] = ("wave", base.rms_slopes(), {"units": "1", "long_name": "rms slope per wave"})
    ds["phase"] = (("realization", "wave"), np.array([r.phases for r in setup.realizations]),
                   {"units": "rad"})
    ds["high_slope"] = ("wave", (base.rms_slopes() > cfg.surface.m2_threshold).astype(int))
    ds.attrs.update({
        "title": "rubbercontact hybrid multiscale results",
        "rubbercontact_version": __version__,
        "config": cfg.model_dump_json(),
        "surface": json.dumps(setup.surface.info, default=str),
        "material": json.dumps(setup.material.as_dict()),
        "period_mm": setup.period,
        "timings_s": json.dumps(timings),
        "model_cpu_time_s": json.dumps(per_model_time),
        "results_format": RESULTS_FORMAT,
    })
    radius = cfg.fem.crest_radius
    if setup.needs_law and cfg.law.file is None and isinstance(radius, float):
        ds.attrs["law_cell_note"] = (
            f"law cell: the high-slope crests rounded to {radius:.3g} mm"
            + (" (the profiles' sampling)" if radius == setup.surface.info.get("dx_mm") else "")
            + "; the law's friction depends on that radius (fem.crest_radius; "
              "docs/validation/steep_cells.md)")
    return ds


def as_config(config) -> RunConfig:
    """A :class:`RunConfig` from a config, a mapping or a TOML path."""
    from ..config import load_config, parse_config

    if isinstance(config, RunConfig):
        return config
    if isinstance(config, dict):
        return parse_config(config)
    return load_config(config)
