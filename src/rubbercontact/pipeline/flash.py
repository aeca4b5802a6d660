"""A run's friction with the flash temperature (``[friction.flash_temperature]``).

With the flash, a (T, v) point is no longer the single reduced speed ``a_T v``: the heat
``μσ0v`` depends on the true speed. The mean-field model ``meanfield`` therefore gets one
:func:`~rubbercontact.meanfield.flash.flash_friction_curve` per temperature and load over
the run's true speeds (its answer stands for every realization, as the isothermal one
does). The half-space models (``vhs``, the hybrids), ``meanfield-hybrid`` (the high-slope
law is an isothermal FEM table) and ``fem`` are not computed with the flash yet: the run
says so in ``attrs["flash_note"]``, one line.

Variables added (``model, [temperature,] velocity, pressure``; NaN for the models without
the flash): ``friction_flash``, ``contact_fraction_flash`` and ``flash_temperature`` [K],
the rise of the finest contact spots above the run's temperature; per scale,
``flash_scale_temperature`` [K] on ``flash_wavenumber`` [rad/mm] (the ``meanfield``
spectrum's nodes), the rise of the contact spots seen at each magnification.
"""

from __future__ import annotations

import json
import time
from dataclasses import asdict, dataclass, replace

import numpy as np
import xarray as xr

from ..errors import ConvergenceError, InputError
from ..materials.spec import load_thermal
from ..meanfield import PSD, MeanFieldOptions
from ..meanfield.flash import FlashOptions, flash_friction_curve
from ..thermal import ThermalProperties
from .plan import meanfield_surfaces
from .setup import RunSetup

#: Models the run computes with the flash temperature.
FLASH_MODELS = ("meanfield",)
#: Prefix of every message about the flash (the config table).
KEY = "friction.flash_temperature"
#: The variables added, with their units and long names.
VARIABLES = {
    "friction_flash": ("1", "friction coefficient with the flash temperature"),
    "contact_fraction_flash": ("1", "real contact fraction with the flash temperature"),
    "flash_temperature": ("K", "rise of the finest contact spots above the run's "
                               "temperature"),
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
    """

    models: tuple[str, ...]
    skipped: tuple[str, ...]
    thermal: ThermalProperties
    options: FlashOptions
    mean_field: MeanFieldOptions

    @property
    def note(self) -> str:
        """One line naming the models without the flash ("" when none)."""
        if not self.skipped:
            return ""
        return (f"flash temperature computed for {', '.join(self.models) or 'no model'} "
                f"only; not yet for {', '.join(self.skipped)} (isothermal)")


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


def add_flash(ds: xr.Dataset, setup: RunSetup, plan: FlashPlan | None
              ) -> tuple[xr.Dataset, float]:
    """``ds`` with the flash variables (module docstring) and their provenance in
    ``attrs`` (``flash_thermal``, ``flash_options``, ``flash_note``, ``flash_residual_K``),
    and the wall time [s]; ``ds`` unchanged (and 0 s) when ``plan`` is None."""
    if plan is None:
        return ds, 0.0
    t0 = time.perf_counter()
    temps = setup.speeds.temperatures
    per_t = [None] if temps is None else [float(t) for t in temps]
    pressures = ds["pressure"].values
    v = setup.speeds.velocities
    shape = (ds.sizes["model"], len(per_t), v.size, pressures.size)
    out = {k: np.full(shape, np.nan) for k in VARIABLES}
    nodes = (PSD.from_dict(meanfield_surfaces(setup)["meanfield"]).wavenumbers
             if plan.models else np.empty(0))
    out["flash_scale_temperature"] = np.full((*shape, nodes.size), np.nan)
    notes, worst = [plan.note] if plan.note else [], 0.0
    for m in plan.models:
        im = list(ds["model"].values).index(m)
        psd = PSD.from_dict(meanfield_surfaces(setup)[m])
        for it, temp in enumerate(per_t):
            for ip, p in enumerate(pressures):
                try:
                    curve = _curve(psd, setup, v, float(p), temp, plan)
                except ConvergenceError as exc:
                    at = "" if temp is None else f", {temp:g} °C"
                    notes.append(f"{m} at {p:g} MPa{at}: {str(exc).splitlines()[0]}")
                    continue
                worst = max(worst, float(np.max(curve.residual)))
                for key, values in (("friction_flash", curve.friction),
                                    ("contact_fraction_flash", curve.contact_fraction),
                                    ("flash_temperature", curve.flash_temperature)):
                    out[key][im, it, :, ip] = values
                out["flash_scale_temperature"][im, it, :, ip] = (
                    curve.node_temperature - curve.background_temperature)
    return _with_variables(ds, out, nodes, temps is not None, plan, notes, worst), (
        time.perf_counter() - t0)


def _curve(psd: PSD, setup: RunSetup, velocities: np.ndarray, pressure: float,
           temperature: float | None, plan: FlashPlan):
    """One flash μ(v) at a run temperature [°C] (None: the reference) and load [MPa]."""
    return flash_friction_curve(psd, setup.material, velocities, pressure,
                                nu=setup.config.material.nu, options=plan.mean_field,
                                flash=replace(plan.options, temperature=temperature))


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
                     "flash_note": "; ".join(notes),
                     "flash_residual_K": residual})
    return ds
