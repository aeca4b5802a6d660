"""A run's friction with the flash temperature (``[friction.flash_temperature]``).

With the flash, a (T, v) point is no longer the single reduced speed ``a_T v``: the heat
``μσ0v`` depends on the true speed. So, in-process, per temperature and load over the
run's true speeds:

* ``meanfield``: one :func:`~rubbercontact.meanfield.flash.flash_friction_curve` (its
  answer stands for every realization, as the isothermal one does);
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
  cascade level further (:mod:`.flash_meanfield`, :mod:`.flash_scales`).

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
from collections.abc import Callable
from dataclasses import asdict, dataclass, replace

import numpy as np
import xarray as xr

from ..errors import ConvergenceError, InputError
from ..materials import GeneralizedMaxwell
from ..materials.shift import shift_law_from_dict
from ..materials.spec import load_thermal
from ..meanfield import PSD, MeanFieldOptions
from ..meanfield.flash import FlashOptions, flash_friction_curve
from ..models import registry
from ..thermal import FlashSearch, FlashSweep, ThermalProperties, flash_sweep
from ..thermal.contact import start_pressure
from ..thermal.kernel import rise_bound
from .flash_hybrid import (
    HYBRID_FLASH_MODELS,
    SCALE_FLASH,
    LawReads,
    hybrid_scale,
    hybrid_solver,
    law_speeds,
)
from .flash_meanfield import MODEL as MEANFIELD_HYBRID
from .flash_meanfield import meanfield_hybrid_flash, meanfield_hybrid_solver, meanfield_scale
from .flash_scales import ScaleSpots, spots_bound
from .plan import meanfield_surfaces
from .setup import RunSetup, task_material

#: Models the run computes with the flash temperature.
FLASH_MODELS = ("meanfield", MEANFIELD_HYBRID, "vhs", *HYBRID_FLASH_MODELS)
#: The half-space models among them.
HALFSPACE_FLASH_MODELS = ("vhs", *HYBRID_FLASH_MODELS)
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
              tables: dict | None = None) -> tuple[xr.Dataset, float]:
    """``ds`` with the flash variables (module docstring) and their provenance in
    ``attrs`` (``flash_thermal``, ``flash_options``, ``flash_note``, ``flash_residual_K``,
    ``flash_halfspace_solves``, ``flash_per_scale``), and the wall time [s]; ``ds``
    unchanged (and 0 s) when ``plan`` is None. ``tables``: the law at each computed speed
    (:attr:`~.lawstage.LawStage.tables`; None without a law), for the hybrids."""
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
    acc = _Tally([plan.note] if plan.note else [])
    laws, reads = law_speeds(tables), LawReads()
    guides: dict = {}          # (model group, temperature, load): a sweep to start from
    for m in plan.models:
        im = list(ds["model"].values).index(m)
        for it, temp in enumerate(per_t):
            for ip, p in enumerate(pressures):
                at = (im, it, slice(None), ip)
                if m == MEANFIELD_HYBRID:
                    _fill_meanfield_hybrid(out, at, setup, float(p), temp, plan, acc,
                                           laws, reads)
                    continue
                if m not in HALFSPACE_FLASH_MODELS:
                    _fill_meanfield(out, at, m, setup, float(p), temp, plan, acc)
                    continue
                solver = (_vhs_solver(setup, float(p)) if m == "vhs" else
                          lambda ir, m=m, p=float(p): hybrid_solver(setup, m, ir, p, laws,
                                                                    reads))
                key = ("hybrid" if m in HYBRID_FLASH_MODELS else m, it, ip)
                iso = _isothermal(ds, m, it if temps is not None else None, ip)
                guides[key] = _fill_halfspace(out, at, m, setup, float(p), temp, plan, acc,
                                              solver, guides.get(key) if plan.guided else None,
                                              iso, _scale(setup, plan, m, float(p), laws,
                                                          reads))
    hybrids = tuple(m for m in plan.models if m in (*HYBRID_FLASH_MODELS, MEANFIELD_HYBRID))
    if reads.note(hybrids):
        acc.notes.append(reads.note(hybrids))
    ds = _with_variables(ds, out, nodes, temps is not None, plan, acc.notes, acc.residual)
    ds.attrs["flash_halfspace_solves"] = acc.solves
    return ds, time.perf_counter() - t0


@dataclass
class _Tally:
    """Notes, the largest fixed-point residual [K] and the half-space solves of a run."""

    notes: list
    residual: float = 0.0
    solves: int = 0

    def failed(self, model: str, pressure: float, temperature: float | None,
               message: str) -> None:
        at = "" if temperature is None else f", {temperature:g} °C"
        self.notes.append(f"{model} at {pressure:g} MPa{at}: {message}")


def _fill_meanfield(out: dict, at: tuple, m: str, setup: RunSetup, pressure: float,
                    temperature: float | None, plan: FlashPlan, acc: _Tally) -> None:
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


def _fill_meanfield_hybrid(out: dict, at: tuple, setup: RunSetup, pressure: float,
                           temperature: float | None, plan: FlashPlan, acc: _Tally,
                           laws, reads: LawReads) -> None:
    """One ``meanfield-hybrid`` flash μ(v) into ``out[...][at]`` (:mod:`.flash_meanfield`)."""
    m = MEANFIELD_HYBRID
    solve = meanfield_hybrid_solver(setup, pressure, laws, reads)
    if solve is None:
        acc.failed(m, pressure, temperature, "no low-slope wave: the law's flat-interface "
                                             "solve, isothermal")
        return
    scale = None
    if setup.hs0.size and plan.per_scale:
        spots = ScaleSpots.of_cell(setup.hs0.period, plan.options.spot_radius, plan.thermal,
                                   plan.options.tolerance)
        scale = meanfield_scale(pressure, laws, reads, spots, setup.material.shift)
    res = meanfield_hybrid_flash(solve, setup.speeds.velocities, pressure,
                                 setup.material.shift, temperature,
                                 replace(plan.options, temperature=temperature), scale)
    for speed, message in res.failures.items():
        acc.failed(m, pressure, temperature, f"{speed:g} mm/s: {message}")
    if solve.beyond > 0:
        acc.failed(m, pressure, temperature, f"up to {solve.beyond:.1f} % of a flash "
                                             f"solve's low-slope contact beyond the law's "
                                             f"highest pressure, where it is held")
    if np.isfinite(res.residual).any():
        acc.residual = max(acc.residual, float(np.nanmax(res.residual)))
    for key, values in (("friction_flash", res.friction),
                        ("contact_fraction_flash", res.contact_fraction),
                        ("flash_temperature", res.rise), ("flash_heat_flux", res.heat_flux),
                        ("flash_temperature_hs", res.rise_hs)):
        out[key][at] = values


def _vhs_solver(setup: RunSetup, pressure: float) -> Callable[[int], Callable]:
    """``solver(realization)``: that realization's ``vhs`` solve at ``pressure`` [MPa] as a
    function of the reduced speed [mm/s] and the solve to start from."""
    from ..halfspace import solve_sliding
    from ..hybrid.tasks import halfspace_law

    cfg = setup.config
    hs = cfg.halfspace
    material = GeneralizedMaxwell(**task_material(setup.material))   # the series at T_ref
    law = halfspace_law(hs.law)

    def solver(ir: int) -> Callable:
        real = setup.realizations[ir]

        def solve(u: float, start=None):
            return solve_sliding(real, setup.period, material, u, pressure, law=law,
                                 n=hs.n, nu=cfg.material.nu, tol=hs.tol,
                                 start=None if start is None else start_pressure(start))
        return solve

    return solver


def _isothermal(ds: xr.Dataset, model: str, it: int | None, ip: int) -> np.ndarray:
    """The run's isothermal friction and contact fraction of ``model`` at one temperature
    (index ``it``, None without temperatures) and load (index ``ip``), shape
    ``(2, velocity, realization)``."""
    def at(name: str) -> np.ndarray:
        da = ds[name].sel(model=model).isel(pressure=ip)
        if it is not None:
            da = da.isel(temperature=it)
        return da.transpose("velocity", "realization").values

    return np.stack([at("friction"), at("contact_fraction")])


@dataclass(frozen=True)
class _Scale:
    """A hybrid's high-slope scale at its own temperature (:mod:`.flash_scales`).

    Attributes
    ----------
    hook
        ``scale(result, temperature, velocity)`` of :func:`.flash_hybrid.hybrid_scale`.
    spots
        Its spots.
    """

    hook: Callable
    spots: ScaleSpots


def _scale(setup: RunSetup, plan: FlashPlan, m: str, pressure: float, laws,
           reads: LawReads) -> _Scale | None:
    """The high-slope scale of hybrid ``m`` at ``pressure`` [MPa] (None: ``vhs``, or no
    law)."""
    if (not plan.per_scale or m not in HYBRID_FLASH_MODELS or laws is None
            or setup.hs0.size == 0):
        return None
    spots = ScaleSpots.of_cell(setup.hs0.period, plan.options.spot_radius, plan.thermal,
                               plan.search.tolerance)
    windowed = registry.model_class(m).READINGS[m] == "windowed"
    hook = hybrid_scale(pressure, laws, reads, float(setup.hs0.period) if windowed else None,
                        spots, shift_law_from_dict(setup.material.shift))
    return _Scale(hook, spots)


def _cold(v: np.ndarray, isothermal: np.ndarray, pressure: float, setup: RunSetup,
          plan: FlashPlan, scale: _Scale | None) -> tuple[np.ndarray, np.ndarray]:
    """The speeds (mask) where the heat of the run's isothermal friction cannot raise the
    surface by the search's tolerance anywhere, in any realization
    (:func:`~rubbercontact.thermal.rise_bound`; with a high-slope scale, plus its spots'
    bound :func:`~.flash_scales.spots_bound` on the isothermal real contact), and the
    bounds [K]."""
    def bound(speed, mu, area):
        flux = abs(mu) * pressure * speed
        extra = 0.0 if scale is None else spots_bound(flux, area, speed, scale.spots)
        return rise_bound(flux, setup.period, plan.thermal) + extra

    bounds = np.array([max(bound(speed, mu, a) for mu, a in zip(mus, areas, strict=True))
                       for speed, mus, areas in zip(v, isothermal[0], isothermal[1],
                                                    strict=True)])
    return bounds <= plan.search.tolerance, bounds          # NaN (a failed task): searched


def _fill_halfspace(out: dict, at: tuple, m: str, setup: RunSetup, pressure: float,
                    temperature: float | None, plan: FlashPlan, acc: _Tally,
                    solver: Callable[[int], Callable | None],
                    guide: FlashSweep | None = None,
                    isothermal: np.ndarray | None = None,
                    scale: _Scale | None = None) -> FlashSweep | None:
    """The realizations' mean of one half-space flash μ(v) into ``out[...][at]`` (NaN at
    a speed where a realization failed); ``solver(realization)`` gives the realization's
    solve of the reduced speed (None: nothing to solve, said in a note); ``scale``: a
    hybrid's high-slope scale at its own temperature. Each realization's search starts
    from the previous realization's roots (``guide`` for the first: e.g. the other
    hybrid's; :func:`~rubbercontact.thermal.flash_sweep`); returns the last sweep, to
    guide the next.

    A speed where the heat of the run's own isothermal friction (``isothermal``, of
    :func:`_isothermal`) cannot raise the surface by the search's tolerance (:func:`_cold`)
    is not searched: its search would end at its first solve, the isothermal one, with no
    rise, and that is the run's own task's solve; so it is taken from the run (μ, contact
    fraction; heat ``μ σ0 v``; the bound counts as its residual)."""
    v = setup.speeds.velocities
    cold = np.zeros(v.size, bool)
    if isothermal is not None:
        cold, bound = _cold(v, isothermal, pressure, setup, plan, scale)
        if cold.any():
            acc.residual = max(acc.residual, float(bound[cold].max()))
    hot = np.flatnonzero(~cold)
    order = hot[np.argsort(v[hot])]
    if guide is not None and not np.array_equal(guide.velocities, np.sort(v[hot])):
        guide = None
    rows = np.full((len(setup.realizations), len(_ROWS), v.size), np.nan)
    for ir in range(len(setup.realizations)):
        if cold.any():
            mu = isothermal[0][cold, ir]
            zero = np.zeros(mu.size) if scale is not None else np.full(mu.size, np.nan)
            rows[ir, :, cold] = np.stack([mu, isothermal[1][cold, ir], np.zeros(mu.size),
                                          mu * pressure * v[cold], zero], axis=-1)
        solve = solver(ir) if hot.size else None
        if solve is None:
            if hot.size:
                acc.failed(m, pressure, temperature, f"r={ir}: flat low-slope surface, no "
                                                     f"half-space contact to heat")
            continue
        sweep = flash_sweep(solve, v[hot], setup.material.shift, plan.thermal, temperature,
                            plan.search, guide=guide, scale=scale and scale.hook)
        guide = sweep if plan.guided else None
        acc.solves += sweep.solves
        for speed, message in sweep.failures.items():
            acc.failed(m, pressure, temperature, f"r={ir}, {speed:g} mm/s: {message}")
        for k, f in zip(order, sweep.flashes, strict=True):
            if f is not None:
                rows[ir, :, k] = _row(f, acc)
    mean = rows.mean(axis=0)
    for i, key in enumerate(_ROWS):
        out[key][at] = mean[i]
    return guide


#: The variables of a half-space flash, in the order of :func:`_row`.
_ROWS = ("friction_flash", "contact_fraction_flash", "flash_temperature", "flash_heat_flux",
         "flash_temperature_hs")


def _row(f, acc: _Tally) -> tuple:
    """One speed's :data:`_ROWS` from its :class:`~rubbercontact.thermal.ContactFlash`
    (the high-slope spots' rise NaN without a high-slope scale); its residuals tallied."""
    rise = f.contact_temperature - f.background_temperature
    acc.residual = max(acc.residual, f.residual)
    hs = f.result.info.get(SCALE_FLASH) if isinstance(f.result.info, dict) else None
    if hs is not None:
        acc.residual = max(acc.residual, hs.residual)
    return (f.result.friction, f.result.contact_fraction, rise, f.heating.mean_heat_flux,
            np.nan if hs is None else rise + hs.rise)


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
                     "flash_halfspace_search": json.dumps(asdict(plan.search), default=float),
                     "flash_per_scale": int(plan.per_scale),
                     "flash_note": "; ".join(notes),
                     "flash_residual_K": residual})
    return ds
