"""The half-space flash as a sweep task: one model's μ(v) with the flash temperature at one
run temperature and load, over its realizations (``vhs``, ``hybrid``, ``hybrid-windowed``).

:func:`halfspace_flash_task` is a pure function of plain data, so a run's flash goes
through the result cache as its model tasks do (:mod:`rubbercontact.sweep`): its key holds
its arguments and the digest of the code it runs (this module, :mod:`.flash_hybrid`,
:mod:`.flash_scales`, :mod:`rubbercontact.thermal`, the half-space solver), a second run
is served from the cache bit for bit, and a kill loses only the tasks running at that
moment. It is :func:`~rubbercontact.thermal.flash_sweep` per realization as
:mod:`.flash_halfspace` plans it: each realization's search started from the previous
realization's roots (``guided``; the first from ``guide``, e.g. ``hybrid``'s last, given
to ``hybrid-windowed``), the hybrids' high-slope scale at its own temperature
(:mod:`.flash_scales`). Its module imports only what the computation runs (no run set-up,
no config), so an edit elsewhere in a run leaves its key.

The result, on dims ``(realization, velocity)`` (the searched speeds, increasing):
``friction``, ``contact_fraction``, ``rise`` [K], ``heat_flux`` [mW/mm²], ``rise_hs``
[K] (NaN without a high-slope scale), ``residual`` and ``residual_hs`` [K] (NaN where a
speed failed, or without a scale); on ``velocity`` the roots of the last realization
searched, to guide the next task (``guide_contact_temperature``,
``guide_background_temperature`` [°C], ``guide_log_slope``; NaN: none); in ``attrs`` the
solves, the failures (JSON ``[[realization, speed, message], ...]``), the flat
realizations (no half-space contact to heat) and the law's reads (:class:`.flash_hybrid.LawReads`).
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass

import numpy as np
import xarray as xr

from ..hybrid.lawspeed import LawSpeeds
from ..materials.shift import shift_law_from_dict
from ..thermal.contact import FlashSearch
from ..thermal.properties import ThermalProperties
from ..thermal.sweep import FlashSweep, flash_sweep
from .flash_hybrid import SCALE_FLASH, LawReads, halfspace_solver, hybrid_scale
from .flash_scales import ScaleSpots

#: The task's import path.
FLASH_TASK = "rubbercontact.pipeline.flash_task:halfspace_flash_task"
#: The per-speed variables of a realization, in the order of :func:`_row`.
ROWS = ("friction", "contact_fraction", "rise", "heat_flux", "rise_hs", "residual",
        "residual_hs")
#: The guide's variables (:class:`GuideRoot`'s fields).
GUIDE = ("contact_temperature", "background_temperature", "log_slope")


@dataclass(frozen=True)
class GuideRoot:
    """A speed's root as a guide reads it (:func:`~rubbercontact.thermal.sweep.guided_start`).

    Attributes
    ----------
    contact_temperature, background_temperature
        ``T0 + T_c`` and ``T0`` [°C].
    log_slope
        ``d ln F / d ln T`` at the root [-] (None: unknown).
    """

    contact_temperature: float
    background_temperature: float
    log_slope: float | None


def halfspace_flash_task(solves: list, pressure: float, velocities: list, shift: dict,
                         thermal: dict, temperature: float | None, search: dict,
                         laws: dict | None = None, scale: dict | None = None,
                         guide: dict | None = None, guided: bool = True,
                         memo: bool = True) -> xr.Dataset:
    """One half-space model's flash μ(v) at one run temperature and load (module docstring).

    Parameters
    ----------
    solves
        Per realization the arguments of its half-space task
        (:func:`~.flash_hybrid.halfspace_solver`), or None.
    pressure
        ``σ0`` [MPa].
    velocities
        The true speeds to search [mm/s], > 0.
    shift, thermal
        The material's shift law and the compound's thermal properties, as plain data.
    temperature
        The run temperature [°C] (None: the shift law's reference).
    search
        :class:`~rubbercontact.thermal.FlashSearch` as plain data (no ``start``).
    laws
        ``{"speeds": [...], "tables": [...]}``: the high-slope law at its tabulated speeds
        (None: ``vhs``, or no law).
    scale
        The high-slope scale at its own temperature: ``{"period" [mm], "spot_radius",
        "tolerance" [K], "window" [mm] or None}`` (None: one temperature for both scales).
    guide
        The roots to start the first realization from (:data:`GUIDE` lists of
        ``velocities``' length; None: from its own lower speeds).
    guided
        Each realization after the first starts from the previous one's roots.
    memo
        A hybrid's solve at a speed already solved is returned again
        (:func:`~.flash_hybrid.halfspace_solver`).
    """
    v = np.asarray(velocities, float)
    shift_law, props = shift_law_from_dict(shift), ThermalProperties.from_dict(thermal)
    reads = LawReads()
    table = None if laws is None else LawSpeeds(dict(zip((float(s) for s in laws["speeds"]),
                                                         laws["tables"], strict=True)))
    hook = None
    if scale is not None and table is not None:
        spots = ScaleSpots.of_cell(scale["period"], scale["spot_radius"], props,
                                   scale["tolerance"])
        hook = hybrid_scale(pressure, table, reads, scale["window"], spots, shift_law)
    flash = FlashSearch(**search)
    last = _sweep_of(guide, v)
    rows = np.full((len(solves), len(ROWS), v.size), np.nan)
    failures, flat, solves_done = [], [], 0
    for ir, kw in enumerate(solves):
        solve = None if kw is None or v.size == 0 else halfspace_solver(
            kw, pressure, table, reads, memo)
        if solve is None:
            flat.append(ir)
            continue
        sweep = flash_sweep(solve, v, shift, props, temperature, flash, guide=last,
                            scale=hook)
        last = sweep if guided else None
        solves_done += sweep.solves
        failures += [[ir, speed, message] for speed, message in sweep.failures.items()]
        for k, f in enumerate(sweep.flashes):
            if f is not None:
                rows[ir, :, k] = _row(f)
    return _dataset(rows, v, last, {"solves": solves_done, "failures": json.dumps(failures),
                                    "flat": json.dumps(flat),
                                    "reads": json.dumps(asdict(reads))})


def _row(f) -> tuple:
    """One speed's :data:`ROWS` from its :class:`~rubbercontact.thermal.ContactFlash`."""
    rise = f.contact_temperature - f.background_temperature
    hs = f.result.info.get(SCALE_FLASH) if isinstance(f.result.info, dict) else None
    return (f.result.friction, f.result.contact_fraction, rise, f.heating.mean_heat_flux,
            np.nan if hs is None else rise + hs.rise, f.residual,
            np.nan if hs is None else hs.residual)


def _sweep_of(guide: dict | None, velocities: np.ndarray) -> FlashSweep | None:
    """The :class:`FlashSweep` of roots a guide gives (None: none)."""
    if guide is None:
        return None
    roots = []
    for tc, t0, slope in zip(*(guide[k] for k in GUIDE), strict=True):
        roots.append(None if not np.isfinite(tc) else
                     GuideRoot(float(tc), float(t0),
                               None if not np.isfinite(slope) else float(slope)))
    return FlashSweep(velocities, tuple(roots))


def guide_of(ds: xr.Dataset) -> dict | None:
    """The guide a task's result gives to the next task (None: none)."""
    if not ds.attrs.get("guided_roots", 0):
        return None
    return {k: ds[f"guide_{k}"].values.tolist() for k in GUIDE}


def _dataset(rows: np.ndarray, v: np.ndarray, last: FlashSweep | None,
             attrs: dict) -> xr.Dataset:
    ds = xr.Dataset({k: (("realization", "velocity"), rows[:, i])
                     for i, k in enumerate(ROWS)}, coords={"velocity": v})
    guide = np.full((len(GUIDE), v.size), np.nan)
    if last is not None:
        for k, f in enumerate(last.flashes):
            if f is not None:
                slope = f.log_slope
                guide[:, k] = (f.contact_temperature, f.background_temperature,
                               np.nan if slope is None else slope)
    for i, k in enumerate(GUIDE):
        ds[f"guide_{k}"] = ("velocity", guide[i])
    ds.attrs.update(attrs, guided_roots=int(last is not None))
    return ds
