"""A run's friction with the flash temperature (``[friction.flash_temperature]``): the plan,
the run's flash, its variables.

With the flash, a (T, v) point is no longer the single reduced speed ``a_T v``: the heat
``μσ0v`` depends on the true speed. So, per temperature and load over the run's true
speeds:

* ``meanfield``: one :func:`~rubbercontact.meanfield.flash.flash_friction_curve` (its
  answer stands for every realization, as the isothermal one does), in-process
  (:mod:`.flash_meanfield`);
* ``vhs``: per realization one :func:`~rubbercontact.thermal.flash_sweep` — the
  half-space solve (the run's grid, interaction law and tolerance) at the contact's own
  mean temperature ``T0 + T_c``, each speed's search started from the lower ones and
  each heated solve from the nearest one already solved (``warm_start``) — and the mean
  over the realizations (the isothermal columns' phase average). One temperature for the
  whole contact (:mod:`rubbercontact.thermal.contact`): its spots are hotter than their
  mean and each scale sees its own, which the mean-field flash resolves and this does not;
* ``hybrid``, ``hybrid-windowed``: the same per realization with the hybrid's low-slope
  solve, each scale at its own temperature — the half-space (and the law's
  load–separation, its interface) at the low-slope contact's mean ``T0 + T_c``, the
  high-slope law's friction and real contact at its spots' ``T0 + T_c + ΔT_hs``, read at
  ``a_T v`` interpolated in ``ln v`` between its tabulated speeds and clamped (and said)
  below the slowest (:mod:`.flash_hybrid`, :mod:`.flash_scales`).

* ``meanfield-hybrid``: per load, at each speed the temperature its own heat gives to its
  finest low-slope spots, ``T0 + T_c`` (the mean-field flash's cascade), for the
  mean-field solve; the law's share at the high-slope spots' ``T0 + T_c + ΔT_hs``, one
  cascade level further (:mod:`.flash_meanfield_task`, :mod:`.flash_scales`).

All but ``meanfield``'s run as sweep tasks, one per model, run temperature and load,
through the run's runner and result cache (:mod:`.flash_halfspace`, :mod:`.flash_task`,
:mod:`.flash_meanfield`, :mod:`.flash_meanfield_task`): a second run is served from the
cache, a killed one resumes.

``ΔT_hs``, the high-slope spots' own flash on top of the low-slope contact, is one step of
the mean-field cascade, solved with the law's friction it heats (:mod:`.flash_scales`;
``FlashPlan.per_scale`` False: one temperature for both scales, as before).

``meanfield-strips`` and ``fem`` are not computed with the flash yet: the run says so in
``attrs["flash_note"]``, one line (and ``run --check``'s plan, and ``summary``).

Variables added (``model, [temperature,] velocity, pressure``; NaN for the models without
the flash): ``friction_flash``, ``contact_fraction_flash``, ``flash_temperature`` [K] (the
rise of the finest contact spots above the run's temperature; ``vhs`` and the hybrids: of
the (low-slope) contact's mean; ``meanfield-hybrid``: of its finest low-slope spots),
``flash_heat_flux`` [mW/mm²] (the frictional heat into the rubber per nominal area,
``μ σ0 v``; the half-space models: of the solved pressure), ``flash_temperature_hs`` [K]
(the hybrids and ``meanfield-hybrid``: the high-slope spots' rise, ``flash_temperature``
plus ``ΔT_hs``; NaN for the others); per
scale, ``flash_scale_temperature`` [K] on ``flash_wavenumber`` [rad/mm] (the
``meanfield`` spectrum's nodes), the rise of the contact spots seen at each magnification.
"""

from __future__ import annotations

import json
import time
from dataclasses import asdict, dataclass

import numpy as np
import xarray as xr

from ..errors import InputError
from ..materials.spec import load_thermal
from ..meanfield import PSD, MeanFieldOptions
from ..meanfield.flash import FlashOptions
from ..thermal import FlashSearch, ThermalProperties
from .flash_halfspace import (
    HALFSPACE_FLASH_MODELS,
    fill_point,
    law_kwargs,
    plan_points,
    run_points,
)
from .flash_hybrid import HYBRID_FLASH_MODELS, LawReads, law_speeds
from .flash_meanfield import MODEL as MEANFIELD_HYBRID
from .flash_meanfield import fill_meanfield, fill_meanfield_hybrid, plan_meanfield_points
from .plan import meanfield_surfaces
from .setup import RunSetup

#: Models the run computes with the flash temperature.
FLASH_MODELS = ("meanfield", MEANFIELD_HYBRID, "vhs", *HYBRID_FLASH_MODELS)
#: Prefix of every message about the flash (the config table).
KEY = "friction.flash_temperature"
#: The variables added, with their units and long names.
VARIABLES = {
    "friction_flash": ("1", "friction coefficient with the flash temperature"),
    "contact_fraction_flash": ("1", "real contact fraction with the flash temperature"),
    "flash_temperature": ("K", "rise of the finest contact spots above the run's "
                               "temperature (vhs, hybrids: of the contact's mean; "
                               "meanfield-hybrid: of the finest low-slope spots)"),
    "flash_heat_flux": ("mW/mm^2", "frictional heat into the rubber per nominal area"),
    "flash_temperature_hs": ("K", "rise of the high-slope contact spots above the run's "
                                  "temperature (hybrids, meanfield-hybrid: flash_temperature "
                                  "plus their own flash)"),
}
#: The per-scale variable, on ``flash_wavenumber`` besides the dims above.
SCALE_VARIABLES = {
    "flash_scale_temperature": ("K", "rise of the contact spots at each node of the "
                                     "spectrum above the run's temperature"),
}


@dataclass(frozen=True)
class FlashPlan:
    """What a run computes with the flash temperature.

    Attributes
    ----------
    models
        The run's models computed with the flash (of :data:`FLASH_MODELS`).
    skipped
        The run's other models (named in the note).
    thermal
        The compound's thermal properties (``[material.thermal]``).
    options
        The flash options except the temperature (set per run temperature).
    mean_field
        The mean-field options of the run's ``[meanfield]`` table.
    search
        The half-space models' search of the contact temperature.
    guided
        Each realization's search starts at the previous realization's roots (and the
        first of ``hybrid-windowed`` at ``hybrid``'s): the same roots to the search's
        tolerance in fewer solves (:func:`~rubbercontact.thermal.flash_sweep`'s
        ``guide``; ``benchmarks/flash_run.md``); False: each from its own lower speeds.
    per_scale
        The hybrids' high-slope law at its spots' own temperature (:mod:`.flash_scales`);
        False: at the low-slope contact's, one temperature for both scales (the earlier
        approximation, kept to compare with).
    """

    models: tuple[str, ...]
    skipped: tuple[str, ...]
    thermal: ThermalProperties
    options: FlashOptions
    mean_field: MeanFieldOptions
    search: FlashSearch = FlashSearch(warm_start=True)
    guided: bool = True
    per_scale: bool = True

    @property
    def note(self) -> str:
        """One line naming the models without the flash ("" when none)."""
        parts = []
        if self.skipped:
            parts.append(f"flash temperature computed for {', '.join(self.models) or 'no model'}"
                         f" only; not yet for {', '.join(self.skipped)} (isothermal)")
        hs = [m for m in self.models if m in HALFSPACE_FLASH_MODELS]
        if hs and self.options.contact_time is not None:
            parts.append(f"{', '.join(hs)}: without contact_time's background heating")
        return "; ".join(parts)


def plan_flash(setup: RunSetup) -> FlashPlan | None:
    """The run's :class:`FlashPlan`, or None when the flash is off; checks every input
    before a task runs.

    Raises
    ------
    InputError
        No shift law or speeds ≤ 0 (one line, naming the key).
    """
    cfg = setup.config
    fc = cfg.friction.flash_temperature
    if not fc.enabled:
        return None
    if setup.material.shift is None:
        raise InputError(f"{KEY}: the material has no time-temperature shift law, so its "
                         "modulus cannot follow the flash; add [material.shift]")
    if np.any(np.asarray(cfg.velocities, float) <= 0):
        raise InputError(f"{KEY}: needs speeds > 0 mm/s (the heat is μσ0v)")
    thermal = load_thermal({"thermal": cfg.material.thermal})
    opts = cfg.meanfield.options("meanfield")
    models = tuple(m for m in setup.models if m in FLASH_MODELS)
    options = FlashOptions(thermal=thermal, spot_radius=fc.spot_radius,
                           contact_time=fc.contact_time, tolerance=fc.tolerance,
                           max_iterations=fc.max_iterations)
    return FlashPlan(models=models, skipped=tuple(m for m in setup.models if m not in models),
                     thermal=thermal, options=options, mean_field=opts)


def add_flash(ds: xr.Dataset, setup: RunSetup, plan: FlashPlan | None,
              tables: dict | None = None, runner=None) -> tuple[xr.Dataset, float]:
    """``ds`` with the flash variables (module docstring) and their provenance in
    ``attrs`` (``flash_thermal``, ``flash_options``, ``flash_note``, ``flash_residual_K``,
    ``flash_halfspace_solves``, ``flash_per_scale``), and the wall time [s]; ``ds``
    unchanged (and 0 s) when ``plan`` is None. ``tables``: the law at each computed speed
    (:attr:`~.lawstage.LawStage.tables`; None without a law), for the hybrids;
    ``runner``: runs the half-space models' flash tasks (the run's, with its cache;
    default: in this process, uncached)."""
    if plan is None:
        return ds, 0.0
    t0 = time.perf_counter()
    temps = setup.speeds.temperatures
    per_t = [None] if temps is None else [float(t) for t in temps]
    pressures = ds["pressure"].values
    shape = (ds.sizes["model"], len(per_t), setup.speeds.velocities.size, pressures.size)
    out = {k: np.full(shape, np.nan) for k in VARIABLES}
    nodes = (PSD.from_dict(meanfield_surfaces(setup)["meanfield"]).wavenumbers
             if "meanfield" in plan.models else np.empty(0))
    out["flash_scale_temperature"] = np.full((*shape, nodes.size), np.nan)
    acc = Tally([plan.note] if plan.note else [])
    laws, reads = law_speeds(tables), LawReads()
    points = (plan_points(ds, setup, plan, laws)
              + plan_meanfield_points(setup, plan, pressures, laws, law_kwargs(laws)))
    results = run_points(points, plan, runner or _in_process)
    found = {(pt.model, pt.it, pt.ip): (pt, res)
             for pt, res in zip(points, results, strict=True)}
    models = list(ds["model"].values)
    for m in plan.models:
        for it, temp in enumerate(per_t):
            for ip, p in enumerate(pressures):
                at = (models.index(m), it, slice(None), ip)
                if m == MEANFIELD_HYBRID:
                    fill_meanfield_hybrid(out, at, *found[(m, it, ip)], acc, reads)
                elif m in HALFSPACE_FLASH_MODELS:
                    fill_point(out, at, *found[(m, it, ip)], setup, acc, reads)
                else:
                    fill_meanfield(out, at, m, setup, float(p), temp, plan, acc)
    hybrids = tuple(m for m in plan.models if m in (*HYBRID_FLASH_MODELS, MEANFIELD_HYBRID))
    if reads.note(hybrids):
        acc.notes.append(reads.note(hybrids))
    ds = _with_variables(ds, out, nodes, temps is not None, plan, acc.notes, acc.residual)
    ds.attrs["flash_halfspace_solves"] = acc.solves
    return ds, time.perf_counter() - t0


def _in_process(tasks: list) -> list:
    """The tasks' results, run here one after the other, uncached."""
    from ..sweep.tasks import resolve_function

    return [resolve_function(t.function)(**t.kwargs) for t in tasks]


@dataclass
class Tally:
    """Notes, the largest fixed-point residual [K] and the half-space solves of a run."""

    notes: list
    residual: float = 0.0
    solves: int = 0

    def failed(self, model: str, pressure: float, temperature: float | None,
               message: str) -> None:
        at = "" if temperature is None else f", {temperature:g} °C"
        self.notes.append(f"{model} at {pressure:g} MPa{at}: {message}")


def _with_variables(ds: xr.Dataset, out: dict, nodes: np.ndarray, with_temperature: bool,
                    plan: FlashPlan, notes: list[str], residual: float) -> xr.Dataset:
    dims = (("model", "temperature", "velocity", "pressure") if with_temperature
            else ("model", "velocity", "pressure"))
    ds = ds.assign_coords(flash_wavenumber=("flash_wavenumber", nodes, {
        "units": "rad/mm", "long_name": "wavenumber of a node of the meanfield spectrum"}))
    for key, (units, name) in {**VARIABLES, **SCALE_VARIABLES}.items():
        on = dims + (("flash_wavenumber",) if key in SCALE_VARIABLES else ())
        values = out[key] if with_temperature else out[key][:, 0]
        ds[key] = (on, values, {"units": units, "long_name": name})
    options = asdict(plan.options)
    options.pop("thermal")
    options.pop("shift")
    ds.attrs.update({"flash_thermal": json.dumps(plan.thermal.as_dict()),
                     "flash_options": json.dumps(options, default=float),
                     "flash_models": json.dumps(list(plan.models)),
                     "flash_halfspace_search": json.dumps(asdict(plan.search), default=float),
                     "flash_per_scale": int(plan.per_scale),
                     "flash_note": "; ".join(notes),
                     "flash_residual_K": residual})
    return ds
