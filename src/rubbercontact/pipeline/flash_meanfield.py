"""The mean-field models' flash in a run: ``meanfield`` in-process, ``meanfield-hybrid`` as
sweep tasks (:mod:`.flash_meanfield_task` says what it computes), one per run temperature
and load, through the run's runner and cache.
"""

from __future__ import annotations

import json
from dataclasses import asdict, replace
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

from ..errors import ConvergenceError
from ..hybrid.lawspeed import LawSpeeds
from ..materials import GeneralizedMaxwell
from ..materials.shift import shift_law_from_dict
from ..meanfield import PSD
from ..meanfield.flash import flash_friction_curve
from ..models import registry
from ..models.planning import RunPoint
from .flash_meanfield_task import MEANFIELD_FLASH_TASK, MODEL
from .plan import meanfield_surfaces
from .setup import RunSetup, task_material

if TYPE_CHECKING:
    from .flash import FlashPlan, Tally
    from .flash_halfspace import FlashPoint
    from .flash_hybrid import LawReads


def solve_kwargs(setup: RunSetup, pressure: float, laws: LawSpeeds | None) -> dict | None:
    """The arguments of ``meanfield-hybrid``'s task at ``pressure`` [MPa] that its flash
    solve reads (:func:`~.flash_meanfield_task.meanfield_solver`); None when the model has
    no low-slope wave (its answer is the law's flat-interface half-space solve, not a
    mean-field one)."""
    cls = registry.model_class(MODEL)
    data = cls.run_data(MODEL, setup)
    if not data.get("wavelengths"):
        return None
    material = GeneralizedMaxwell(**task_material(setup.material))
    table0 = None if laws is None else laws.table(laws.speeds[0])
    _, kw = cls.run_task(MODEL, RunPoint(setup, material, float(setup.speeds.computed[0]),
                                         np.array([pressure]), table0, None, data))
    return {k: kw[k] for k in ("surface", "material", "nu", "options")}


def plan_meanfield_points(setup: RunSetup, plan: FlashPlan, pressures: np.ndarray,
                          laws: LawSpeeds | None, law_kw: dict | None) -> list[FlashPoint]:
    """``meanfield-hybrid``'s flash points (:class:`~.flash_halfspace.FlashPoint`), one per
    run temperature and load (none when the run does not compute it with the flash)."""
    from .flash_halfspace import FlashPoint

    if MODEL not in plan.models:
        return []
    temps = setup.speeds.temperatures
    per_t = [None] if temps is None else [float(t) for t in temps]
    shift = shift_law_from_dict(setup.material.shift).as_dict()
    flash = {k: v for k, v in asdict(plan.options).items()
             if k not in ("thermal", "shift", "temperature")}
    scale = None
    if setup.hs0.size and plan.per_scale:
        scale = {"period": float(setup.hs0.period), "spot_radius": plan.options.spot_radius,
                 "tolerance": plan.options.tolerance}
    points = []
    for ip, p in enumerate(pressures):
        solve = solve_kwargs(setup, float(p), laws)
        for it, temp in enumerate(per_t):
            kw = None if solve is None else {
                "solve": solve, "pressure": float(p),
                "velocities": setup.speeds.velocities.tolist(), "shift": shift,
                "thermal": plan.thermal.as_dict(), "flash": flash, "temperature": temp,
                "laws": law_kw, "scale": scale if laws is not None else None}
            points.append(FlashPoint(MODEL, it, ip, temp, float(p), kw,
                                     function=MEANFIELD_FLASH_TASK))
    return points


def fill_meanfield(out: dict, at: tuple, m: str, setup: RunSetup, pressure: float,
                    temperature: float | None, plan: FlashPlan, acc: Tally) -> None:
    """One mean-field flash μ(v) into ``out[...][at]``."""
    psd = PSD.from_dict(meanfield_surfaces(setup)[m])
    try:
        curve = _curve(psd, setup, setup.speeds.velocities, pressure, temperature, plan)
    except ConvergenceError as exc:
        acc.failed(m, pressure, temperature, str(exc).splitlines()[0])
        return
    acc.residual = max(acc.residual, float(np.max(curve.residual)))
    for key, values in (("friction_flash", curve.friction),
                        ("contact_fraction_flash", curve.contact_fraction),
                        ("flash_temperature", curve.flash_temperature),
                        ("flash_heat_flux", curve.friction * pressure
                         * setup.speeds.velocities)):
        out[key][at] = values
    out["flash_scale_temperature"][at] = (curve.node_temperature
                                          - curve.background_temperature)


def fill_meanfield_hybrid(out: dict, at: tuple, pt: FlashPoint, result, acc: Tally,
                          reads: LawReads) -> None:
    """One ``meanfield-hybrid`` flash μ(v) into ``out[...][at]`` from its task's
    ``result``; its notes, residual and law reads tallied."""
    m, pressure, temperature = MODEL, pt.pressure, pt.temperature
    if pt.kwargs is None:
        acc.failed(m, pressure, temperature, "no low-slope wave: the law's flat-interface "
                                             "solve, isothermal")
        return
    if not isinstance(result, xr.Dataset):
        acc.failed(m, pressure, temperature,
                   f"flash task failed: {getattr(result, 'message', result)}")
        return
    from .flash_halfspace import merge_reads

    merge_reads(reads, json.loads(result.attrs["reads"]))
    for speed, message in json.loads(result.attrs["failures"]):
        acc.failed(m, pressure, temperature, f"{speed:g} mm/s: {message}")
    beyond = float(result["beyond"])
    if beyond > 0:
        acc.failed(m, pressure, temperature, f"up to {beyond:.1f} % of a flash "
                                             f"solve's low-slope contact beyond the law's "
                                             f"highest pressure, where it is held")
    residual = result["residual"].values
    if np.isfinite(residual).any():
        acc.residual = max(acc.residual, float(np.nanmax(residual)))
    for key, row in (("friction_flash", "friction"),
                     ("contact_fraction_flash", "contact_fraction"),
                     ("flash_temperature", "rise"), ("flash_heat_flux", "heat_flux"),
                     ("flash_temperature_hs", "rise_hs")):
        out[key][at] = result[row].values


def _curve(psd: PSD, setup: RunSetup, velocities: np.ndarray, pressure: float,
           temperature: float | None, plan: FlashPlan):
    """One flash μ(v) at a run temperature [°C] (None: the reference) and load [MPa]."""
    return flash_friction_curve(psd, setup.material, velocities, pressure,
                                nu=setup.config.material.nu, options=plan.mean_field,
                                flash=replace(plan.options, temperature=temperature))
