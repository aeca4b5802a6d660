"""The half-space models' flash in a run (``vhs``, ``hybrid``, ``hybrid-windowed``): one
sweep task per model, run temperature and load (:func:`~.flash_task.halfspace_flash_task`),
through the run's runner and result cache.

Per task, over the realizations: the half-space solve (the run's grid, interaction law and
tolerance; the hybrids' low-slope solve with the law at the reduced speed) at the
contact's own mean temperature ``T0 + T_c``, each speed's search started from the lower
ones and each heated solve from the nearest one already solved; each realization's search
from the previous realization's roots (``FlashPlan.guided``), and the first realization of
the second hybrid from the first hybrid's last (so the second hybrid's tasks run after the
first's, in a second round of the runner); the mean over the realizations is the
isothermal columns' phase average. The hybrids' high-slope law at its spots' own
temperature (:mod:`.flash_scales`) unless ``FlashPlan.per_scale`` is False.

A speed where the heat of the run's own isothermal friction cannot raise the surface by the
search's tolerance in any realization (:func:`cold_speeds`) is not searched: its search
would end at its first solve, the isothermal one, with no rise, and that is the run's own
task's solve; so it is taken from the run (μ, contact fraction; heat ``μ σ0 v``; the bound
counts as its residual). A (model, temperature, load) with no speed to search has no task.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

from ..hybrid.lawspeed import LawSpeeds
from ..materials import GeneralizedMaxwell
from ..materials.shift import shift_law_from_dict
from ..models import registry
from ..models.planning import RunPoint
from ..thermal.kernel import rise_bound
from .flash_hybrid import HYBRID_FLASH_MODELS, LawReads, halfspace_solver
from .flash_scales import ScaleSpots, spots_bound
from .flash_task import FLASH_TASK, ROWS, guide_of
from .setup import RunSetup, task_material

if TYPE_CHECKING:
    from .flash import FlashPlan, Tally

#: The half-space models computed with the flash.
HALFSPACE_FLASH_MODELS = ("vhs", *HYBRID_FLASH_MODELS)
#: The variables of a half-space flash, in the order of the task's first rows.
OUT_ROWS = ("friction_flash", "contact_fraction_flash", "flash_temperature",
            "flash_heat_flux", "flash_temperature_hs")
#: The task's rows that give them.
OUT_ROWS_OF_TASK = ROWS[:len(OUT_ROWS)]


@dataclass(frozen=True)
class FlashPoint:
    """One model's flash at one run temperature and load: a sweep task.

    Attributes
    ----------
    model
        The model.
    it, ip
        Indices of the run temperature (0 without temperatures) and the load.
    temperature
        The run temperature [°C] (None: the shift law's reference).
    pressure
        ``σ0`` [MPa].
    kwargs
        The task's arguments (None: no task, e.g. no speed to search).
    function
        The task's import path.
    cold
        The half-space models: speeds (mask over the run's) not searched (module
        docstring).
    bound
        The rise bound at each speed [K] (:func:`cold_speeds`).
    isothermal
        The run's isothermal friction and contact fraction, ``(2, velocity,
        realization)``.
    """

    model: str
    it: int
    ip: int
    temperature: float | None
    pressure: float
    kwargs: dict | None
    function: str = FLASH_TASK
    cold: np.ndarray | None = None
    bound: np.ndarray | None = None
    isothermal: np.ndarray | None = None


def law_kwargs(laws: LawSpeeds | None) -> dict | None:
    """The law at its tabulated speeds as a task reads it (None without a law)."""
    if laws is None:
        return None
    return {"speeds": laws.speeds.tolist(), "tables": [laws.table(s) for s in laws.speeds]}


def solve_kwargs(setup: RunSetup, model: str, realization: int, pressure: float,
                 laws: LawSpeeds | None) -> dict:
    """The arguments of one realization's half-space solve as the run's task writes them
    (:meth:`~rubbercontact.models.halfspace.Hybrid.run_task`; the ones the flash reads)."""
    material = GeneralizedMaxwell(**task_material(setup.material))
    cls = registry.model_class(model)
    table0 = None if laws is None else laws.table(laws.speeds[0])
    _, kw = cls.run_task(model, RunPoint(setup, material, float(setup.speeds.computed[0]),
                                         np.array([pressure]), table0, realization,
                                         cls.run_data(model, setup)))
    keep = ("surface", "period", "material", "n", "nu", "law", "tol", "hs_window")
    return {k: kw[k] for k in keep if k in kw}


def hybrid_solver(setup: RunSetup, model: str, realization: int, pressure: float,
                  laws: LawSpeeds | None, reads: LawReads
                  ) -> Callable[[float, object], object] | None:
    """``solve(reduced_speed, start=None)`` of one realization's half-space solve in a run
    (:func:`~.flash_hybrid.halfspace_solver` of :func:`solve_kwargs`)."""
    return halfspace_solver(solve_kwargs(setup, model, realization, pressure, laws),
                            pressure, laws, reads, memo=model != "vhs")


def isothermal(ds: xr.Dataset, model: str, it: int | None, ip: int) -> np.ndarray:
    """The run's isothermal friction and contact fraction of ``model`` at one temperature
    (index ``it``, None without temperatures) and load (index ``ip``), shape
    ``(2, velocity, realization)``."""
    def at(name: str) -> np.ndarray:
        da = ds[name].sel(model=model).isel(pressure=ip)
        if it is not None:
            da = da.isel(temperature=it)
        return da.transpose("velocity", "realization").values

    return np.stack([at("friction"), at("contact_fraction")])


def cold_speeds(v: np.ndarray, iso: np.ndarray, pressure: float, setup: RunSetup,
                plan: FlashPlan, spots: ScaleSpots | None) -> tuple[np.ndarray, np.ndarray]:
    """The speeds (mask) where the heat of the run's isothermal friction cannot raise the
    surface by the search's tolerance anywhere, in any realization
    (:func:`~rubbercontact.thermal.rise_bound`; with a high-slope scale, plus its spots'
    bound :func:`~.flash_scales.spots_bound` on the isothermal real contact), and the
    bounds [K]."""
    def bound(speed, mu, area):
        flux = abs(mu) * pressure * speed
        extra = 0.0 if spots is None else spots_bound(flux, area, speed, spots)
        return rise_bound(flux, setup.period, plan.thermal) + extra

    bounds = np.array([max(bound(speed, mu, a) for mu, a in zip(mus, areas, strict=True))
                       for speed, mus, areas in zip(v, iso[0], iso[1], strict=True)])
    return bounds <= plan.search.tolerance, bounds          # NaN (a failed task): searched


def plan_points(ds: xr.Dataset, setup: RunSetup, plan: FlashPlan,
                laws: LawSpeeds | None) -> list[FlashPoint]:
    """Every half-space model's :class:`FlashPoint`, in the run's order (model, temperature,
    load)."""
    temps = setup.speeds.temperatures
    per_t = [None] if temps is None else [float(t) for t in temps]
    law_kw = law_kwargs(laws)
    v = setup.speeds.velocities
    shift = shift_law_from_dict(setup.material.shift).as_dict()
    points = []
    for m in (m for m in plan.models if m in HALFSPACE_FLASH_MODELS):
        scale = _scale_kwargs(setup, plan, m, laws)
        spots = None if scale is None else ScaleSpots.of_cell(
            scale["period"], scale["spot_radius"], plan.thermal, scale["tolerance"])
        for it, temp in enumerate(per_t):
            for ip, p in enumerate(ds["pressure"].values):
                iso = isothermal(ds, m, it if temps is not None else None, ip)
                cold, bound = cold_speeds(v, iso, float(p), setup, plan, spots)
                hot = np.sort(v[~cold])
                kw = None if not hot.size else {
                    "solves": [solve_kwargs(setup, m, ir, float(p), laws)
                               for ir in range(len(setup.realizations))],
                    "pressure": float(p), "velocities": hot.tolist(),
                    "shift": shift, "thermal": plan.thermal.as_dict(),
                    "temperature": temp, "search": asdict(plan.search),
                    "laws": law_kw if m != "vhs" else None, "scale": scale,
                    "guided": plan.guided, "memo": m != "vhs"}
                points.append(FlashPoint(m, it, ip, temp, float(p), kw, cold=cold,
                                          bound=bound, isothermal=iso))
    return points


def _scale_kwargs(setup: RunSetup, plan: FlashPlan, m: str, laws) -> dict | None:
    """The high-slope scale of hybrid ``m`` as the task reads it (None: ``vhs``, no law,
    or one temperature for both scales)."""
    if (not plan.per_scale or m not in HYBRID_FLASH_MODELS or laws is None
            or setup.hs0.size == 0):
        return None
    windowed = registry.model_class(m).READINGS[m] == "windowed"
    return {"period": float(setup.hs0.period), "spot_radius": plan.options.spot_radius,
            "tolerance": plan.search.tolerance,
            "window": float(setup.hs0.period) if windowed else None}


def run_points(points: list[FlashPoint], plan: FlashPlan, runner) -> list:
    """Each point's task result (an ``xr.Dataset``, a failure record, or None without a
    task): every model's tasks in one round of ``runner`` but the second hybrid's, which
    start from the first's roots (``plan.guided``), in a second."""
    from ..sweep import Task

    results: list = [None] * len(points)
    first = {}
    for pt in points:
        group = "hybrid" if pt.model in HYBRID_FLASH_MODELS else pt.model
        first.setdefault((group, pt.it, pt.ip), pt.model)
    rounds = ([k for k, pt in enumerate(points) if pt.kwargs is not None and _leads(pt, first)],
              [k for k, pt in enumerate(points) if pt.kwargs is not None
               and not _leads(pt, first)])
    lead = {(pt.it, pt.ip): k for k, pt in enumerate(points)
            if pt.model in HYBRID_FLASH_MODELS and _leads(pt, first)}
    for ks in rounds:
        tasks = []
        for k in ks:
            pt, kw = points[k], points[k].kwargs
            if not _leads(pt, first) and plan.guided:
                kw = {**kw, "guide": _guide(results[lead.get((pt.it, pt.ip))], kw)}
            tasks.append(Task(pt.function, kw, label=_label(pt)))
        for k, res in zip(ks, runner(tasks) if tasks else [], strict=True):
            results[k] = res
    return results


def _leads(pt: FlashPoint, first: dict) -> bool:
    group = "hybrid" if pt.model in HYBRID_FLASH_MODELS else pt.model
    return first[(group, pt.it, pt.ip)] == pt.model


def _guide(lead, kw: dict) -> dict | None:
    """The first hybrid's last roots, when it searched the same speeds (None: none)."""
    if not isinstance(lead, xr.Dataset):
        return None
    if not np.array_equal(lead["velocity"].values, np.asarray(kw["velocities"], float)):
        return None
    return guide_of(lead)


def _label(pt: FlashPoint) -> str:
    at = "" if pt.temperature is None else f" T={pt.temperature:g}"
    return f"flash {pt.model}{at} p={pt.pressure:.4g}"


def fill_point(out: dict, at: tuple, pt: FlashPoint, result, setup: RunSetup,
               acc: Tally, reads: LawReads) -> None:
    """The realizations' mean of one point's flash μ(v) into ``out[...][at]`` (NaN at a
    speed where a realization failed); its notes, residuals, solves and law reads tallied."""
    v = setup.speeds.velocities
    cold, iso, p = pt.cold, pt.isothermal, pt.pressure
    if cold.any():
        acc.residual = max(acc.residual, float(pt.bound[cold].max()))
    rows = np.full((len(setup.realizations), len(OUT_ROWS), v.size), np.nan)
    if cold.any():
        for ir in range(len(setup.realizations)):
            mu = iso[0][cold, ir]
            zero = (np.zeros(mu.size) if pt.kwargs and pt.kwargs["scale"] is not None
                    else np.full(mu.size, np.nan))
            rows[ir, :, cold] = np.stack([mu, iso[1][cold, ir], np.zeros(mu.size),
                                          mu * p * v[cold], zero], axis=-1)
    if pt.kwargs is not None:
        _fill_hot(rows, pt, result, v, acc, reads)
    mean = rows.mean(axis=0)
    for i, key in enumerate(OUT_ROWS):
        out[key][at] = mean[i]


def _fill_hot(rows: np.ndarray, pt: FlashPoint, result, v: np.ndarray, acc: Tally,
              reads: LawReads) -> None:
    """The searched speeds' rows of a point (speeds ``v`` [mm/s]) from its task's
    ``result``."""
    if not isinstance(result, xr.Dataset):
        acc.failed(pt.model, pt.pressure, pt.temperature,
                   f"flash task failed: {getattr(result, 'message', result)}")
        return
    hot = np.flatnonzero(~pt.cold)
    order = hot[np.argsort(v[hot])]
    flat = set(json.loads(result.attrs["flat"]))
    failures = json.loads(result.attrs["failures"])
    acc.solves += int(result.attrs["solves"])
    merge_reads(reads, json.loads(result.attrs["reads"]))
    values = {k: result[k].values for k in ROWS}
    for ir in range(rows.shape[0]):
        if ir in flat:
            acc.failed(pt.model, pt.pressure, pt.temperature,
                       f"r={ir}: flat low-slope surface, no half-space contact to heat")
            continue
        for r, speed, message in failures:
            if r == ir:
                acc.failed(pt.model, pt.pressure, pt.temperature,
                           f"r={ir}, {speed:g} mm/s: {message}")
        for j, k in enumerate(order):
            if np.isfinite(values["rise"][ir, j]):          # solved (NaN: failed)
                acc.residual = max(acc.residual, float(values["residual"][ir, j]),
                                   float(values["residual_hs"][ir, j]))
                rows[ir, :, k] = [values[n][ir, j] for n in OUT_ROWS_OF_TASK]


def merge_reads(reads: LawReads, task: dict) -> None:
    """A task's law reads added to the run's."""
    if task["slowest"] is not None and reads.slowest is None:
        reads.slowest = task["slowest"]
    reads.lowest = min(reads.lowest, task["lowest"])
    reads.clamped += task["clamped"]
    reads.reads += task["reads"]
