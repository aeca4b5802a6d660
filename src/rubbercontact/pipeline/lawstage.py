"""The run's high-slope law: FEM points (or a reused law), screened and tabulated per speed.

The FEM law points are independent sweep tasks, one per (speed, pressure), cached and
resumed point by point; or, with the steady solver and several speeds, one task per
pressure that follows the speeds by continuation (``law.speed_path``): each steady state
starts the next (:func:`rubbercontact.fem.steady_sliding`'s ``start``); its cost against
fresh points is in BENCHMARKS.md ("Steady FEM").
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import xarray as xr

from ..config import RunConfig
from ..hybrid.law import (
    as_law,
    assemble_law,
    check_law_matches,
    law_at_velocity,
    screen_monotone,
)
from ..materials import GeneralizedMaxwell
from ..roughness import SineSeries
from .batch import Batch, run_batches
from .costmodel import LAW_TABLE_SPEED_S, halfspace_solve_seconds, law_task_seconds
from .lawcheck import QuasiStaticCheck, quasi_static_batch
from .lawcover import NOT_NEEDED, merge_points
from .setup import task_material

#: ``law.speed_path = "auto"`` follows the speeds by continuation from this many speeds on.
CONTINUATION_SPEEDS = 3


@dataclass(frozen=True)
class LawStage:
    """The law of a run.

    Attributes
    ----------
    law
        The screened law table (dims ``velocity, pressure``), with the VHS friction of the
        high-slope waves alone (``vhs_friction``, Fig. 7) once :func:`add_vhs` ran.
    tables
        ``{speed: table}``: the law at each computed speed as the hybrid reads it
        (:func:`~rubbercontact.hybrid.law.law_at_velocity`, continued past the FEM's
        highest pressure with the linear law's shape).
    fem_time
        Wall time of the FEM sweep [s] (None when the law was given).
    raw
        The law table before the monotonicity screen (every FEM point tried, with its
        status), which an extension (:func:`extend_law`) adds to; None when the law was
        given.
    readings
        ``{speed: reading}``: the law read at each speed before its continuation, which an
        extension compares to reuse the tables of the speeds it did not change.
    quasi_static
        The cell's quasi-static check at the FEM pressures (:mod:`.lawcheck`); None when
        the law was given or ``law.quasi_static_check`` is off.
    """

    law: xr.Dataset
    tables: dict
    fem_time: float | None
    raw: xr.Dataset | None = None
    readings: dict = field(default_factory=dict, repr=False)
    quasi_static: QuasiStaticCheck | None = None


def law_pressures(cfg: RunConfig, pressures: np.ndarray) -> np.ndarray:
    """``law.pressures``, default 8 pressures from half the smallest to 8× the largest load."""
    if cfg.law.pressures is not None:
        return np.asarray(cfg.law.pressures, float)
    return np.geomspace(pressures.min() / 2, pressures.max() * 8, 8)


def uses_continuation(cfg: RunConfig, n_speeds: int) -> bool:
    """Whether the law's FEM points follow the speeds by continuation."""
    if cfg.law.speed_path == "points" or cfg.fem.solver != "steady":
        return False
    return cfg.law.speed_path == "continuation" or n_speeds >= CONTINUATION_SPEEDS


def build_law(cfg: RunConfig, hs0: SineSeries, material: GeneralizedMaxwell,
              pressures: np.ndarray, runner, law: xr.Dataset | None = None,
              velocities=None, progress: bool | str = False) -> LawStage:
    """The high-slope law of a run and the tables the hybrid reads, one per speed.

    ``law`` (or ``cfg.law.file``, a ``law.nc`` or a run's ``results.nc``) is used when
    given, after checking that it was built for ``hs0``, this rubber and every speed
    (:func:`~rubbercontact.hybrid.law.check_law_matches`); otherwise the FEM runs on ``hs0``
    at :func:`law_pressures`. Non-monotone points are screened out.

    Parameters
    ----------
    velocities
        The speeds to tabulate [mm/s] (default ``cfg.velocities``; a run with temperatures
        passes its reduced speeds).
    progress
        Progress display of the tables (``"auto"``, True, False) when ``runner`` is None
        (computed in this process); a runner shows them as its stage "law tables".
    """
    speeds = np.asarray(cfg.velocities if velocities is None else velocities, float)
    if law is None and cfg.law.file is not None:
        from ..io.results import read_results

        law, source = read_results(cfg.law.file), f"law.file {cfg.law.file}"
    else:
        source = "law"
    if law is not None:
        law = as_law(law, source)
        check_law_matches(law, hs0, material, speeds, source)
        return _stage(law, None, hs0, material, speeds, cfg, raw=None, progress=progress,
                      runner=runner)
    t0 = time.perf_counter()
    at = law_pressures(cfg, pressures)
    # the quasi-static points in the same sweep: they fill the workers while the law's
    # longest speed path runs
    raw, qs = run_batches(runner, [_grid_batch(cfg, hs0, material, at, speeds),
                                   _quasi_static(cfg, hs0, material, at, None)])
    return _stage(raw, time.perf_counter() - t0, hs0, material, speeds, cfg, raw=raw,
                  progress=progress, quasi_static=qs, runner=runner)


def extend_law(stage: LawStage, points: dict[float, list[float]], cfg: RunConfig,
               hs0: SineSeries, material: GeneralizedMaxwell, speeds: np.ndarray,
               runner, progress: bool | str = False) -> LawStage:
    """``stage`` with FEM law points added at ``{pressure [MPa]: speeds [mm/s]}``
    (:mod:`.lawcover`), screened and tabulated again (a speed whose reading did not change
    keeps its table)."""
    if stage.raw is None:
        raise ValueError("extend_law: a given law cannot be extended (no FEM options)")
    t0 = time.perf_counter()
    v = stage.raw["velocity"].values
    # no transient fallback for an added point: where the steady solve (and its barrier
    # rescue) stops, the extension stops and says so, instead of minutes of a transient test
    # at a load past the cell's steady range (impaled on speed_sweep.toml's cell at 3.16 MPa)
    new, qs = run_batches(runner, [
        law_batch(cfg, hs0, material, points, v,
                  continuation=uses_continuation(cfg, np.unique(speeds).size),
                  fallback=False),
        _quasi_static(cfg, hs0, material, list(points), stage.quasi_static)])
    raw = merge_points(stage.raw, new)
    if stage.quasi_static is not None:
        qs = stage.quasi_static if qs is None else stage.quasi_static.merged(qs)
    fem_time = (stage.fem_time or 0.0) + time.perf_counter() - t0
    return _stage(raw, fem_time, hs0, material, speeds, cfg, raw=raw, progress=progress,
                  before=stage, quasi_static=qs, runner=runner)


def _stage(law: xr.Dataset, fem_time: float | None, hs0: SineSeries,
           material: GeneralizedMaxwell, speeds: np.ndarray, cfg: RunConfig,
           raw: xr.Dataset | None, progress: bool | str = False,
           before: LawStage | None = None,
           quasi_static: QuasiStaticCheck | None = None, runner=None) -> LawStage:
    """Screen ``law`` for monotonicity and tabulate it at each speed (``before``: a
    speed read as there keeps its table); the tables are sweep tasks of ``runner``
    (:func:`law_tables`)."""
    law = screen_monotone(law)
    readings = {float(v): law_at_velocity(law, float(v)) for v in speeds}
    old = before or LawStage(law, {}, None)
    todo = [v for v, r in readings.items()
            if v not in old.tables or not _same_reading(r, old.readings.get(v))]
    tables = {v: old.tables[v] for v in readings if v not in todo}
    if todo:
        tables.update(law_tables(todo, readings, hs0, material, cfg, runner, progress))
    tables = {v: tables[v] for v in readings}
    return LawStage(law, tables, fem_time, raw, readings, quasi_static)


def law_tables(speeds, readings: dict, hs0: SineSeries, material: GeneralizedMaxwell,
               cfg: RunConfig, runner, progress: bool | str = False) -> dict:
    """``{speed: table}`` of ``readings`` at ``speeds``, each a cached sweep task
    (:func:`~rubbercontact.hybrid.lawtask.law_table_task`): a table is computed once for
    its reading, so the hybrid tasks that read it keep their keys from run to run (its
    half-space solves differ in their last bits with the thread count of the process)."""
    from ..hybrid.lawtask import table_from_dataset
    from ..sweep import Task
    from .assemble import failure_message

    speeds = [float(v) for v in speeds]
    tasks = [Task(function="rubbercontact.hybrid.lawtask:law_table_task",
                  kwargs={"reading": readings[v], "surface": hs0.as_dict(),
                          "material": task_material(material), "velocity": v,
                          "nu": float(cfg.material.nu)},
                  label=f"law table v={v:g} mm/s", cost=LAW_TABLE_SPEED_S)
             for v in speeds]
    if runner is None:                       # no sweep: in this process, not cached
        from ..sweep import run_sweep

        answers = run_sweep(tasks, cache=None, progress=progress,
                            description="law tables").results
    else:
        from .execute import named

        answers = named(runner, "law tables")(tasks)
    out = {}
    for v, res in zip(speeds, answers, strict=True):
        why = failure_message(res)
        if why is not None:
            raise RuntimeError(f"law table at v={v:g} mm/s failed: {why}")
        out[v] = table_from_dataset(res)
    return out


def _same_reading(a: dict, b: dict | None) -> bool:
    """Whether two readings of the law at one speed are equal, key by key."""
    if b is None or a.keys() != b.keys():
        return False
    return all(np.array_equal(np.asarray(a[k]), np.asarray(b[k]), equal_nan=True)
               for k in a)


def fem_law(cfg: RunConfig, hs0: SineSeries, material: GeneralizedMaxwell,
            pressures: np.ndarray, speeds: np.ndarray, runner) -> xr.Dataset:
    """Run the FEM law points on ``pressures × speeds``, by continuation in speed where
    :func:`uses_continuation`."""
    return run_batches(runner, [_grid_batch(cfg, hs0, material, pressures, speeds)])[0]


def _grid_batch(cfg: RunConfig, hs0: SineSeries, material: GeneralizedMaxwell,
                pressures, speeds) -> Batch:
    """:func:`law_batch` of every point of ``pressures × speeds``."""
    v = np.unique(speeds)
    return law_batch(cfg, hs0, material, {float(p): v.tolist() for p in pressures}, v,
                     continuation=uses_continuation(cfg, v.size))


def _quasi_static(cfg: RunConfig, hs0: SineSeries, material: GeneralizedMaxwell,
                  pressures, before: QuasiStaticCheck | None) -> Batch | None:
    """The quasi-static check's batch at ``pressures`` not checked ``before`` (None: the
    check is off, or nothing new to check)."""
    if not cfg.law.quasi_static_check:
        return None
    done = set() if before is None else set(before.pressure.tolist())
    fresh = [float(p) for p in pressures if float(p) not in done]
    return (quasi_static_batch(_fem_options(cfg, material), hs0, material, fresh)
            if fresh else None)


def law_batch(cfg: RunConfig, hs0: SineSeries, material: GeneralizedMaxwell,
              points: dict[float, list[float]], speeds: np.ndarray,
              continuation: bool, fallback: bool = True) -> Batch:
    """The tasks of the FEM points ``{pressure [MPa]: speeds [mm/s]}`` and how to read
    the raw law table on the grid ``speeds × pressures`` from them; the grid points not
    asked for have the status :data:`~.lawcover.NOT_NEEDED`. ``continuation``: one task
    per pressure following its speeds (steady solver), else one task per point;
    ``fallback=False``: no transient test where the steady solve stops
    (``steady.fallback``)."""
    from ..sweep import Task

    options = _fem_options(cfg, material)                       # fails here, not per task
    if not fallback:
        options = options.with_(steady={"fallback": False})
    opts = options.to_dict()
    p = np.sort(np.asarray(list(points), float))
    v = np.sort(np.asarray(speeds, float))
    wanted = np.array([[float(vi) in set(points[float(pj)]) for pj in p] for vi in v])
    results = np.full(wanted.shape, NOT_NEEDED, dtype=object)
    e_inf = material.equilibrium_modulus
    if continuation:
        # highest pressure first: the paths at the highest loads take the longest (most
        # Newton iterations per speed), and started last they would leave workers idle
        order = [j for j in range(p.size)[::-1] if wanted[:, j].any()]
        tasks = [Task(function="rubbercontact.hybrid.tasks:fem_speed_path_task",
                      kwargs={"surface": hs0.as_dict(), "material": task_material(material),
                              "velocities": v[wanted[:, j]].tolist(),
                              "mean_pressure": float(p[j]), "options": opts},
                      label=f"law FEM p={p[j]:g} MPa, {int(wanted[:, j].sum())} speeds by "
                            f"continuation",
                      # the progress ETA's hint: run --check's price of the task
                      cost=law_task_seconds(options, hs0, float(p[j]), e_inf,
                                            int(wanted[:, j].sum()), continuation=True))
                 for j in order]

        def collect(answers: list) -> xr.Dataset:
            for j, path in zip(order, answers, strict=True):
                for k, i in enumerate(np.flatnonzero(wanted[:, j])):
                    results[i, j] = _path_point(path, k)
            return assemble_law(results.ravel().tolist(), p, v, hs0, material, opts)
    else:
        at = np.argwhere(wanted)
        tasks = [Task(function="rubbercontact.hybrid.tasks:fem_task",
                      kwargs={"surface": hs0.as_dict(), "material": material.as_dict(),
                              "velocity": float(v[i]), "mean_pressure": float(p[j]),
                              "options": opts},
                      label=f"law FEM v={v[i]:g} mm/s p={p[j]:g} MPa",
                      cost=law_task_seconds(options, hs0, float(p[j]), e_inf))
                 for i, j in at]

        def collect(answers: list) -> xr.Dataset:
            for (i, j), res in zip(at, answers, strict=True):
                results[i, j] = res
            return assemble_law(results.ravel().tolist(), p, v, hs0, material, opts)
    return Batch(tasks, collect)


def _fem_options(cfg: RunConfig, material: GeneralizedMaxwell):
    """The law cell's :class:`~rubbercontact.fem.FemOptions` from the config."""
    from ..fem import make_options

    return make_options(cfg.fem.options(material))


def _path_point(path, i: int):
    """Point ``i`` of a speed-path result: its scalars, or why it (or the path) failed."""
    if not isinstance(path, xr.Dataset):
        return path
    point = path.isel(velocity=i)
    status = str(point["status"].values)
    return point.drop_vars("status") if status == "ok" else status


def add_vhs(law: xr.Dataset, hs: SineSeries, material: GeneralizedMaxwell, cfg: RunConfig,
            runner) -> xr.Dataset:
    """Add the VHS friction of the high-slope wave alone at the law's pressures (Fig. 7)."""
    from ..sweep import Task
    from .assemble import failure_message

    # one task per speed over the law's pressures, as the models' half-space tasks
    tasks = [Task(function="rubbercontact.hybrid.tasks:halfspace_loads_task",
                  kwargs={"surface": hs.as_dict(), "period": hs.period,
                          "material": task_material(material), "velocity": float(v),
                          "mean_pressures": [float(p) for p in law["pressure"].values],
                          "n": min(cfg.halfspace.n, 4096), "nu": cfg.material.nu,
                          "law": cfg.halfspace.law, "tol": cfg.halfspace.tol},
                  label=f"vhs on z_hs v={v:g}",
                  cost=law.sizes["pressure"] * halfspace_solve_seconds(min(cfg.halfspace.n,
                                                                           4096)))
             for v in law["velocity"].values]
    res = runner(tasks)
    mu = np.full((law.sizes["velocity"], law.sizes["pressure"]), np.nan)
    area = np.full_like(mu, np.nan)
    for k, r in enumerate(res):
        if failure_message(r) is None:
            ok = r["status"].values == "ok"
            mu[k, ok] = r["friction"].values[ok]
            area[k, ok] = r["contact_fraction"].values[ok]
    law = law.copy()
    law["vhs_friction"] = (("velocity", "pressure"), mu,
                           {"units": "1", "long_name": "VHS friction on z_hs alone"})
    law["vhs_contact_fraction"] = (("velocity", "pressure"), area, {"units": "1"})
    return law
