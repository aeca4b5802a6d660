"""The hybrid multiscale pipeline and its two reference models (paper §2.1, §3, §4).

``run(config)`` builds the surface (preset, sine table, or a fit of measured
profiles), draws random-phase realizations, partitions each into high- and
low-slope parts, computes the effective law of the high-slope scale with the FEM,
and runs, on the same loads:

- ``vhs``: the viscoelastic half-space on the whole surface;
- ``hybrid``: the half-space on ``z_ls`` with the integrated-LJ + ``σ_hs`` law,
  ``μ = μ_ls + μ_hs`` (eqs. 5–7) and ``A_c`` by eq. 8;
- ``hybrid-windowed``: the same solve, with ``μ_hs`` and ``A_c`` reading the law at the
  low-slope pressure averaged over one high-slope period (our extension for contact
  patches narrower than ``λ_hs``; see :mod:`.windowing`);
- ``fem``: the FEM sliding test on the whole surface (cell width = longest wavelength).

The result is one ``xarray.Dataset`` with dims ``model, velocity, realization,
pressure`` (and ``contact_area`` when loads are given as target areas), the law
table (``law_*`` variables), and provenance in ``attrs``.

With ``fem.realizations = R`` below ``realizations = N`` the full FEM, by far the dearest
model, runs on the first R realizations only and the cheap models on all N. The FEM's
phase average is then estimated per load as ``mean_N(VHS) + mean_R(FEM − VHS)``
(:func:`.metrics.control_variate_mean`): unbiased, and far less noisy than the plain mean of
R FEM tests because the VHS follows the FEM realization by realization. Those estimates are
the ``*_phase_mean`` variables, and eq. 28 compares against them.
"""

from __future__ import annotations

import json
import time
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

from ..config import RunConfig
from ..errors import InputError
from ..materials import GeneralizedMaxwell, sbr
from ..roughness import SineSeries, presets
from .law import (
    LAW_VARIABLES,
    STEADINESS_UNITS,
    STEADINESS_VARIABLES,
    as_law,
    check_coverage,
    check_law_matches,
    continue_with_linear_shape,
    creep_unsettled_message,
    describe_unsteady,
    effective_law,
    law_at_velocity,
    screen_monotone,
    sheared_cells_message,
)
from .metrics import (
    control_variate_by_column,
    interpolate_at_areas,
    mean_relative_error,
    rising_branch,
)

if TYPE_CHECKING:   # imported lazily at run time, as everywhere in this module
    from ..sweep import Task

#: Executes a list of sweep tasks; returns per task an ``xr.Dataset`` or a failure record.
Runner = Callable[[list], list]

#: Models that run the low-slope solve with the high-slope law.
HYBRID_MODELS = {"hybrid", "hybrid-windowed"}


#: Status of a solve skipped by design (the FEM beyond ``fem.realizations``): not a failure.
NOT_RUN = "not run"


def failed_solves(status) -> np.ndarray:
    """Boolean mask of the solves that failed: status neither ``"ok"`` nor :data:`NOT_RUN`."""
    s = np.asarray(status).astype(str)
    return (s != "ok") & ~np.char.startswith(s, NOT_RUN)


def failure_message(res) -> str | None:
    """``None`` for a successful task result, else why it failed (one line)."""
    if isinstance(res, xr.Dataset):
        return None
    return "missing result" if res is None else str(res)

#: Result variables produced per (model, velocity, realization, pressure).
RESULT_VARIABLES = {
    "friction": ("1", "total hysteretic friction coefficient mu"),
    "friction_ls": ("1", "low-slope part mu_ls (eq. 7); equals mu for vhs and fem"),
    "friction_hs": ("1", "high-slope part mu_hs (eq. 6); 0 for vhs and fem"),
    "contact_fraction": ("1", "normalized real contact area A_c/A_0 (eq. 8 for hybrid)"),
    "mean_separation": ("mm", "mean interface separation"),
    "wall_time": ("s", "wall time of the solve"),
}


def build_material(cfg: RunConfig) -> GeneralizedMaxwell:
    m = cfg.material
    if m.file is not None:
        return GeneralizedMaxwell.from_file(m.file)
    if m.equilibrium_modulus is not None:
        return GeneralizedMaxwell(m.equilibrium_modulus, m.moduli, m.relaxation_times,
                                  name="config")
    if m.preset == "sbr":
        return sbr()
    raise InputError("material: give 'preset', 'file' or 'equilibrium_modulus'")


def build_surface(cfg: RunConfig) -> tuple[SineSeries, dict]:
    """The base sine series and a description of where it came from."""
    s = cfg.surface
    if s.preset is not None:
        return getattr(presets, s.preset)(), {"source": f"preset:{s.preset}"}
    if s.wavelengths is not None:
        return SineSeries(s.wavelengths, s.amplitudes), {"source": "sine table"}
    from ..io.profiles import read_profiles
    from ..roughness.fit import default_wavelengths, fit_hdc_details

    p = s.profiles
    profiles = read_profiles(p.files, format=p.format, unit=p.unit, dx=p.dx,
                             window=p.window or 16.0, despike=p.despike)
    shortest = min(z.size for z in profiles.profiles) * profiles.dx
    wavelengths = default_wavelengths(profiles.dx, shortest, n_waves=p.waves,
                                      lower_cutoff=p.lower_cutoff, upper_cutoff=p.upper_cutoff)
    fit = fit_hdc_details(profiles, wavelengths=wavelengths, method=p.method)
    series = fit.series
    info = {"source": "fit of measured profiles", "files": [str(f) for f in p.files],
            "sources": [dict(src) for src in profiles.sources], "fit_method": p.method,
            "n_scans": len(profiles.profiles), "dx_mm": profiles.dx,
            "log10_rms_error": float(fit.log10_rms_error)}
    return series, info


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


def _pressure_grid_for_areas(cfg: RunConfig, surfaces: list[SineSeries],
                             material: GeneralizedMaxwell) -> np.ndarray:
    """Pressures spanning the target contact areas at every speed, estimated with the VHS.

    The area at a given load depends on the speed (the rubber stiffens with frequency),
    so the bounds are taken over all velocities: the smallest pressure reaching the
    smallest target and the largest reaching the largest one. The hybrid and FEM
    contact areas differ from the VHS ones, so the grid extends a factor 2 beyond on
    either side and is interpolated afterwards.
    """
    from scipy.optimize import brentq

    from .. import halfspace

    targets = np.asarray(cfg.loads.contact_areas)
    s0 = surfaces[0]
    n = min(cfg.halfspace.n, 2048)

    def area(logp: float, v: float) -> float:
        res = halfspace.solve_sliding(s0, s0.period, material, v, float(np.exp(logp)), n=n,
                                      nu=cfg.material.nu)
        return res.contact_fraction

    # full contact needs about E_r m2: bracket with the relaxed modulus below and the
    # modulus at the highest excitation frequency above
    slope = s0.rms_slope
    e_lo = float(abs(material.reduced_modulus(0.0, cfg.material.nu))) * slope
    w_max = float(np.max(s0.wavenumbers)) * max(cfg.velocities)
    e_hi = float(abs(material.reduced_modulus(w_max, cfg.material.nu))) * slope
    lo, hi = np.log(1e-6 * e_lo), np.log(2.0 * max(e_lo, e_hi))
    p_lo, p_hi = np.inf, -np.inf
    for v in sorted(set(cfg.velocities)):
        p_lo = min(p_lo, brentq(lambda lp, v=v: area(lp, v) - targets.min(), lo, hi, xtol=1e-3))
        p_hi = max(p_hi, brentq(lambda lp, v=v: area(lp, v) - targets.max(), lo, hi, xtol=1e-3))
    n_p = cfg.loads.sweep_points or max(6, targets.size + 2)
    return np.geomspace(np.exp(p_lo) / 2, np.exp(p_hi) * 2, n_p)


def build_law(cfg: RunConfig, hs0: SineSeries, material: GeneralizedMaxwell,
              pressures: np.ndarray, runner: Runner, law: xr.Dataset | None = None
              ) -> tuple[xr.Dataset, dict[float, dict], float | None]:
    """The high-slope law of a run and the tables the hybrid reads, one per velocity.

    ``law`` (or ``cfg.law.file``, a ``law.nc`` or a run's ``results.nc``) is used when
    given, after checking that it was built for ``hs0``, this rubber and every speed of the
    run (:func:`~rubbercontact.hybrid.law.check_law_matches`); otherwise the FEM sweep runs on
    ``hs0`` at ``cfg.law.pressures`` (default: 8 pressures from half the smallest to 8× the
    largest load). Non-monotone points are screened out, and past the FEM's highest pressure
    each table follows the linear law's shape, anchored there.

    Returns
    -------
    law, tables, fem_time
        The screened law dataset, ``{velocity: table}`` and the wall time of the FEM sweep
        [s] (``None`` when the law was given).
    """
    fem_time = None
    source = "law"
    if law is None and cfg.law.file is not None:
        from ..io.results import read_results

        law, source = read_results(cfg.law.file), f"law.file {cfg.law.file}"
    if law is not None:
        law = as_law(law, source)
        check_law_matches(law, hs0, material, cfg.velocities, source)
    else:
        law_p = (np.asarray(cfg.law.pressures, float) if cfg.law.pressures is not None
                 else np.geomspace(pressures.min() / 2, pressures.max() * 8, 8))
        t0 = time.perf_counter()
        law = effective_law(hs0, material, law_p, np.asarray(cfg.velocities, float),
                            options=cfg.fem.options(material), runner=runner)
        fem_time = time.perf_counter() - t0
    law = screen_monotone(law)
    tables = {float(v): continue_with_linear_shape(law_at_velocity(law, float(v)), hs0,
                                                   material, float(v), nu=cfg.material.nu)
              for v in cfg.velocities}
    return law, tables, fem_time


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
        the high-slope scale); it must match the run's high-slope scale, rubber and speeds.
    progress
        Progress display of the sweeps (``"auto"``, True, False).
    retry_failed
        Recompute tasks whose failure is recorded in the cache.
    """
    cfg = _as_config(config)
    t_start = time.perf_counter()
    timings: dict[str, float] = {}
    runner = runner or make_runner(cfg, progress, retry_failed)
    material = build_material(cfg)
    base, surface_info = build_surface(cfg)
    realizations = base.realizations(cfg.realizations, seed=cfg.seed)
    parts = [r.partition(cfg.surface.m2_threshold) for r in realizations]
    # The law is a property of the high-slope scale up to a translation: shift the first
    # high-slope wave to zero phase (keeps the relative phases of several hs waves).
    hs0 = _translated_to_zero_phase(parts[0][0])
    period = base.period
    velocities = np.asarray(cfg.velocities, float)
    models = list(dict.fromkeys(cfg.models))
    n_fem = cfg.fem.realizations or cfg.realizations   # the FEM on the first n_fem only

    if cfg.loads.pressures is not None:
        pressures = np.sort(np.asarray(cfg.loads.pressures, float))
    else:
        pressures = _pressure_grid_for_areas(cfg, realizations, material)

    # -- effective law of the high-slope scale ---------------------------------------
    law_tables: dict[float, dict | None] = {float(v): None for v in velocities}
    if HYBRID_MODELS & set(models) and hs0.size:
        law, tables, fem_time = build_law(cfg, hs0, material, pressures, runner, law)
        law_tables.update(tables)
        if fem_time is not None:
            timings["law"] = fem_time
        law = _law_with_vhs(law, hs0, material, cfg, runner)

    # -- one task per (model, velocity, realization, pressure) ------------------------
    from ..sweep import Task

    hsc = cfg.halfspace
    index, tasks = [], []
    for m in models:
        for iv, v in enumerate(velocities):
            for ir, (real, (_hs, ls)) in enumerate(zip(realizations, parts, strict=True)):
                if m == "fem" and ir >= n_fem:
                    continue
                for ip, p in enumerate(pressures):
                    common = {"material": material.as_dict(), "velocity": float(v),
                              "mean_pressure": float(p)}
                    keep = ir == 0
                    if m == "fem":
                        task = full_fem_task(cfg, real, material, float(v), float(p))
                        fn, kw = task.function, task.kwargs
                    else:
                        surf = real if (m == "vhs" or not _hs.size) else ls
                        kw = {"surface": surf.as_dict(), "period": period, **common,
                              "n": hsc.n, "nu": cfg.material.nu, "law": hsc.law,
                              "interface_law": (law_tables[float(v)] if m in HYBRID_MODELS
                                                else None),
                              "keep_profile": keep}
                        if m == "hybrid-windowed" and _hs.size:
                            kw["hs_window"] = float(hs0.period)
                        fn = "rubbercontact.hybrid.tasks:halfspace_task"
                    tasks.append(Task(function=fn, kwargs=kw,
                                      label=f"{m} v={v:g} r={ir} p={p:.4g}"))
                    index.append((m, iv, ir, ip))
    t0 = time.perf_counter()
    results = runner(tasks)
    timings["models"] = time.perf_counter() - t0

    ds = _assemble(models, velocities, realizations, pressures, index, results, material,
                   n_fem)
    ds = _add_profiles(ds, index, results)
    per_model_time = {m: float(ds["wall_time"].sel(model=m).sum()) for m in models}
    if law is not None:
        for k in LAW_VARIABLES:
            if k in law:
                ds[f"law_{k}"] = law[k].rename(pressure="law_pressure")
        ds = ds.assign_coords(law_pressure=("law_pressure", law["pressure"].values,
                                            {"units": "MPa"}))
        # what law_from_results needs to give the law back, checkable on reuse
        ds.attrs["law_attrs"] = json.dumps({k: np.asarray(v).tolist() if not isinstance(v, str)
                                            else v for k, v in law.attrs.items()})
        per_model_time["law (FEM, counted once)"] = float(np.nansum(law["wall_time"].values))
        hybrid = [m for m in models if m in HYBRID_MODELS]
        if hybrid:   # the same low-slope solve for both variants: check once
            for v in velocities:
                check_coverage(law, float(v), float(ds["max_local_pressure"].sel(
                    model=hybrid[0], velocity=v).max()))
    if cfg.loads.contact_areas is not None:
        ds = _at_areas(ds, np.asarray(cfg.loads.contact_areas, float), stacklevel=3)
    if "fem" in models and n_fem < len(realizations):
        ds = add_phase_means(ds, n_fem)
    ds = _add_errors(ds)

    # -- realization geometry and provenance ------------------------------------------
    ds["wavelength"] = ("wave", base.wavelengths, {"units": "mm"})
    ds["amplitude"] = ("wave", base.amplitudes, {"units": "mm"})
    ds["m2"] = ("wave", base.rms_slopes(), {"units": "1", "long_name": "rms slope per wave"})
    ds["phase"] = (("realization", "wave"), np.array([r.phases for r in realizations]),
                   {"units": "rad"})
    ds["high_slope"] = ("wave", (base.rms_slopes() > cfg.surface.m2_threshold).astype(int))
    timings["total"] = time.perf_counter() - t_start
    from .. import __version__

    ds.attrs.update({
        "title": "rubbercontact hybrid multiscale results",
        "rubbercontact_version": __version__,
        "config": cfg.model_dump_json(),
        "surface": json.dumps(surface_info, default=str),
        "material": json.dumps(material.as_dict()),
        "period_mm": period,
        "timings_s": json.dumps(timings),
        "model_cpu_time_s": json.dumps(per_model_time),
    })
    return ds


def full_fem_task(cfg: RunConfig, surface: SineSeries, material: GeneralizedMaxwell,
                  velocity: float, mean_pressure: float) -> Task:
    """The sweep task of one full-FEM sliding test (model ``fem``) with the config's options
    (``cfg.fem.options(material, full=True)``); the surface is translated to zero phase, so
    that on an all-high-slope surface it is the law's cell and shares its cache entries."""
    from ..sweep import Task

    kw = {"surface": _translated_to_zero_phase(surface).as_dict(),
          "material": material.as_dict(), "velocity": float(velocity),
          "mean_pressure": float(mean_pressure),
          "options": cfg.fem.options(material, full=True).to_dict()}
    return Task(function="rubbercontact.hybrid.tasks:fem_task", kwargs=kw,
                label=f"fem v={velocity:g} p={mean_pressure:.4g}")


def _as_config(config) -> RunConfig:
    from ..config import load_config, parse_config

    if isinstance(config, RunConfig):
        return config
    if isinstance(config, dict):
        return parse_config(config)
    return load_config(config)


def _translated_to_zero_phase(surface: SineSeries) -> SineSeries:
    """``surface(x + x0)`` with ``x0`` chosen so that its shortest wave has phase 0."""
    if surface.size == 0:
        return surface
    x0 = -surface.phases[0] / surface.wavenumbers[0]
    return surface.with_phases(surface.phases + surface.wavenumbers * x0)


def _law_with_vhs(law: xr.Dataset, hs: SineSeries, material: GeneralizedMaxwell,
                  cfg: RunConfig, runner: Runner) -> xr.Dataset:
    """Add the VHS friction of the high-slope wave alone at the law's pressures (Fig. 7)."""
    from ..sweep import Task

    tasks = [Task(function="rubbercontact.hybrid.tasks:halfspace_task",
                  kwargs={"surface": hs.as_dict(), "period": hs.period,
                          "material": material.as_dict(), "velocity": float(v),
                          "mean_pressure": float(p), "n": min(cfg.halfspace.n, 4096),
                          "nu": cfg.material.nu, "law": cfg.halfspace.law},
                  label=f"vhs on z_hs v={v:g} p={p:.4g}")
             for v in law["velocity"].values for p in law["pressure"].values]
    res = runner(tasks)
    mu = np.full((law.sizes["velocity"], law.sizes["pressure"]), np.nan)
    area = np.full_like(mu, np.nan)
    for k, r in enumerate(res):
        if failure_message(r) is None:
            mu.flat[k], area.flat[k] = float(r["friction"]), float(r["contact_fraction"])
    law = law.copy()
    law["vhs_friction"] = (("velocity", "pressure"), mu,
                           {"units": "1", "long_name": "VHS friction on z_hs alone"})
    law["vhs_contact_fraction"] = (("velocity", "pressure"), area, {"units": "1"})
    return law


def _assemble(models, velocities, realizations, pressures, index, results,
              material: GeneralizedMaxwell, n_fem: int) -> xr.Dataset:
    shape = (len(models), len(velocities), len(realizations), len(pressures))
    names = list(RESULT_VARIABLES) + ["max_local_pressure"]
    data = {k: np.full(shape, np.nan) for k in names}
    status = np.full(shape, "ok", dtype=object)
    if "fem" in models and n_fem < len(realizations):
        status[models.index("fem"), :, n_fem:] = f"{NOT_RUN} (fem.realizations = {n_fem})"
    # full-FEM steadiness (1/0; NaN where failed or not recorded) and the relative change
    # of its friction over the last sliding period
    fem_diag = {k: np.full(shape[1:], np.nan) for k in STEADINESS_VARIABLES}
    for (m, iv, ir, ip), res in zip(index, results, strict=True):
        im = models.index(m)
        msg = failure_message(res)
        if msg is not None:
            status[im, iv, ir, ip] = msg
            continue
        if m == "fem":
            for k, arr in fem_diag.items():
                if k in res:     # results cached before the period changes existed lack them
                    arr[iv, ir, ip] = float(res[k])
        for k in names:
            if k in res:
                data[k][im, iv, ir, ip] = float(res[k])
        if m not in HYBRID_MODELS:
            data["friction_ls"][im, iv, ir, ip] = float(res["friction"])
            data["friction_hs"][im, iv, ir, ip] = 0.0
    dims = ("model", "velocity", "realization", "pressure")
    ds = xr.Dataset(
        {k: (dims, data[k], {"units": RESULT_VARIABLES.get(k, ("MPa", ""))[0],
                             "long_name": RESULT_VARIABLES.get(k, ("", "max local pressure"))[1]})
         for k in names},
        coords={"model": list(models),
                "velocity": ("velocity", velocities, {"units": "mm/s"}),
                "realization": np.arange(len(realizations)),
                "pressure": ("pressure", pressures, {"units": "MPa",
                                                     "long_name": "mean pressure sigma0"})},
    )
    ds["status"] = (dims, status.astype(str))
    n_run = int((~np.char.startswith(status.astype(str), NOT_RUN)).sum())
    n_failed = int(failed_solves(status).sum())
    if n_failed:
        warnings.warn(f"{n_failed} of {n_run} solves failed; see the 'status' variable",
                      RuntimeWarning, stacklevel=3)
    if "fem" in models:
        ds = _add_fem_steadiness(ds, fem_diag, material, stacklevel=4)
    for k in ("friction", "contact_fraction", "mean_separation"):
        ds[f"{k}_mean"] = ds[k].mean("realization")
        ds[f"{k}_std"] = ds[k].std("realization")
        ds[f"{k}_mean"].attrs["units"] = ds[f"{k}_std"].attrs["units"] = ds[k].attrs["units"]
    return ds


def _add_fem_steadiness(ds: xr.Dataset, diag: dict, material: GeneralizedMaxwell,
                        stacklevel: int = 2) -> xr.Dataset:
    """Store whether each full-FEM test reached steady sliding, and say which did not.

    An unsteady test keeps its result (the last period's averages), as the FEM itself
    does, but the run says so instead of leaving the warning in a worker's log.
    """
    dims = ("velocity", "realization", "pressure")
    for k, text in STEADINESS_VARIABLES.items():
        ds[f"fem_{k}"] = (dims, diag[k], {"units": STEADINESS_UNITS.get(k, "1"),
                                           "long_name": f"full FEM: {text}"})
    v, p = ds["velocity"].values, ds["pressure"].values
    def label(iv, ir, ip):
        return f"v={v[iv]:g} σ0={p[ip]:g} r={ir}"

    n_bad, where, recorded = describe_unsteady(diag, label)
    if n_bad:
        brackets = ("; change of friction / contact fraction over the last period in "
                    "brackets" if recorded else "")
        warnings.warn(f"{n_bad} of {int(np.isfinite(diag['steady']).sum())} full-FEM tests "
                      f"did not reach "
                      f"steady sliding in the periods allowed (fem.full_periods, else "
                      f"fem.periods){brackets}: {where}. Their results are the last period's "
                      f"averages (see 'fem_steady'); more periods, or fem.min_creep_times, would "
                      f"settle them",
                      RuntimeWarning, stacklevel=stacklevel)
    creep = creep_unsettled_message(diag, material, label, "full FEM")
    if creep:
        warnings.warn(creep, RuntimeWarning, stacklevel=stacklevel)
    sheared = sheared_cells_message(diag, label, "full FEM")
    if sheared:
        warnings.warn(sheared, RuntimeWarning, stacklevel=stacklevel)
    return ds


def _add_profiles(ds: xr.Dataset, index, results) -> xr.Dataset:
    """Pressure along the surface for realization 0 (paper Fig. 8)."""
    profiles: dict[str, np.ndarray] = {}
    for (m, iv, ir, ip), res in zip(index, results, strict=True):
        if failure_message(res) or ir != 0 or "pressure_profile" not in res or m == "fem":
            continue
        arr = profiles.setdefault(m, np.full((ds.sizes["velocity"], ds.sizes["pressure"],
                                              res.sizes["x"]), np.nan))
        arr[iv, ip] = res["pressure_profile"].values
        ds = ds.assign_coords(x=("x", res["x"].values, {"units": "mm"}))
        if "heights" not in ds and m == "vhs":
            ds["heights"] = ("x", res["heights_profile"].values, {"units": "mm"})
    for m, arr in profiles.items():
        ds[f"pressure_profile_{m}"] = (("velocity", "pressure", "x"), arr,
                                       {"units": "MPa", "long_name": f"{m} contact pressure, "
                                                                     f"realization 0"})
    return ds


def _at_areas(ds: xr.Dataset, targets: np.ndarray, stacklevel: int = 2) -> xr.Dataset:
    """Friction at the target contact areas, per realization, by load-sweep interpolation.

    Only the loads on the sweep's rising branch are used (``rising_branch``); a load whose
    contact area does not exceed that of a lower load is left out and named in a warning.
    """
    out = np.full((ds.sizes["model"], ds.sizes["velocity"], ds.sizes["realization"],
                   targets.size), np.nan)
    p = ds["pressure"].values
    folded = []
    for im in range(ds.sizes["model"]):
        for iv in range(ds.sizes["velocity"]):
            for ir in range(ds.sizes["realization"]):
                sel = ds.isel(model=im, velocity=iv, realization=ir)
                a, mu = sel["contact_fraction"].values, sel["friction"].values
                ok = np.isfinite(a) & np.isfinite(mu)
                if ok.sum() < 2:
                    continue
                keep = rising_branch(p[ok], a[ok])
                # full contact repeated at higher loads is no fold: nothing to report
                fold = ~keep & (a[ok] < 1.0 - 1e-9)
                if fold.any():
                    folded.append(f"{ds['model'].values[im]} v={ds['velocity'].values[iv]:g} "
                                  f"r={ir}: σ0=" + ", ".join(f"{x:g}" for x in p[ok][fold]))
                out[im, iv, ir] = interpolate_at_areas(a[ok][keep], mu[ok][keep], targets)
    if folded:
        n = len(folded)
        warnings.warn(f"friction at contact area: {n} load sweep{'s' if n > 1 else ''} "
                      f"ha{'ve' if n > 1 else 's'} loads whose "
                      "contact area does not exceed that at a lower load; those loads are "
                      "left out of the interpolation (the area stopped growing with the "
                      "load there, e.g. a full FEM cell sheared beyond 1): "
                      + "; ".join(folded), RuntimeWarning, stacklevel=stacklevel)
    ds = ds.assign_coords(contact_area=("contact_area", targets,
                                        {"units": "1", "long_name": "target A_c/A_0"}))
    dims = ("model", "velocity", "realization", "contact_area")
    ds["friction_at_area"] = (dims, out, {"units": "1"})
    ds["friction_at_area_mean"] = ds["friction_at_area"].mean("realization")
    return ds


#: Per-realization variables whose phase average ``add_phase_means`` estimates.
PHASE_MEAN_VARIABLES = ("friction", "contact_fraction", "mean_separation", "friction_at_area")


def add_phase_means(ds: xr.Dataset, n_fem: int) -> xr.Dataset:
    """Each model's estimate of its phase average, the FEM's with the VHS as control variate.

    For every variable ``k`` of :data:`PHASE_MEAN_VARIABLES` in ``ds`` adds ``k_phase_mean``
    (dims ``model, velocity`` and the load dim): the plain mean over all realizations for
    the cheap models, and for ``fem``, run on the first ``n_fem`` realizations only,
    ``mean_N(VHS) + mean_R(FEM − VHS)`` per load. A FEM test that failed is left out at its
    load (with its VHS partner), so R can vary by load; ``k_phase_se`` holds the FEM
    estimate's standard error, ``sqrt(var(VHS)/N + var(FEM − VHS)/R + 2 cov(VHS, FEM −
    VHS)/N)`` (NaN with fewer than two FEM tests at a load).

    Parameters
    ----------
    ds
        Results with models ``fem`` and ``vhs`` on dims ``model, velocity, realization, ...``.
    n_fem
        Realizations the FEM ran on (the first ``n_fem``).
    """
    for k in PHASE_MEAN_VARIABLES:
        if k not in ds:
            continue
        x = ds[k].transpose("model", "realization", ...)
        models = list(ds["model"].values)
        vals = x.values
        with warnings.catch_warnings():     # a load every realization failed: NaN
            warnings.simplefilter("ignore", RuntimeWarning)
            mean = np.nanmean(vals, axis=1)
        vhs = vals[models.index("vhs")]
        est, se = control_variate_by_column(vals[models.index("fem"), :n_fem], vhs[:n_fem], vhs)
        mean[models.index("fem")] = est
        dims = ("model", *x.dims[2:])
        units = ds[k].attrs.get("units", "1")
        ds[f"{k}_phase_mean"] = (dims, mean, {
            "units": units,
            "long_name": f"phase average of {k}: mean over the realizations; for fem "
                         f"mean_N(vhs) + mean_R(fem - vhs), R = {n_fem}"})
        ds[f"{k}_phase_se"] = (dims[1:], se, {
            "units": units, "long_name": f"standard error of the fem {k}_phase_mean"})
    ds.attrs["fem_realizations"] = n_fem
    return ds


def mean_of(ds: xr.Dataset, k: str) -> xr.DataArray:
    """``k_phase_mean`` when the run estimated phase averages, else ``k_mean``."""
    return ds[f"{k}_phase_mean"] if f"{k}_phase_mean" in ds else ds[f"{k}_mean"]


def _add_errors(ds: xr.Dataset) -> xr.Dataset:
    """Eq. 28 error of each model against FEM, over the comparison points."""
    if "fem" not in ds["model"].values:
        return ds
    base, dim = (("friction_at_area", "contact_area") if "friction_at_area_mean" in ds
                 else ("friction", "pressure"))
    mean = mean_of(ds, base)
    others = [m for m in ds["model"].values if m != "fem"]
    err = np.full((len(others), ds.sizes["velocity"]), np.nan)
    for i, m in enumerate(others):
        for iv in range(ds.sizes["velocity"]):
            ref = mean.sel(model="fem").isel(velocity=iv).values
            cand = mean.sel(model=m).isel(velocity=iv).values
            ok = np.isfinite(ref) & np.isfinite(cand) & (ref != 0)
            if ok.any():
                err[i, iv] = mean_relative_error(ref[ok], cand[ok])
    ds["error_vs_fem"] = (("compared_model", "velocity"), err,
                          {"units": "1", "long_name": f"eq. 28 mean relative error vs FEM "
                                                      f"over {dim}", "compared_over": dim,
                           "fem_reference": ("phase average: mean_N(vhs) + mean_R(fem - vhs)"
                                             if "fem_realizations" in ds.attrs
                                             else "mean over the realizations")})
    return ds.assign_coords(compared_model=others)
