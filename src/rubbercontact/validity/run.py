"""A run's results against the validated classes: the notes of every model it computed.

:func:`assess_run` reads from a results dataset and its set-up what :func:`~.assess.assess`
takes (the waves and the split, each model's realization-mean friction and contact fraction
per load beside the VHS's, the highest local pressure the law was read at against the law's
highest FEM point, the rubber's loss peak at each temperature) and returns the notes.
"""

from __future__ import annotations

import json
import math

import numpy as np
import xarray as xr

from .assess import Note, SpeedPoint, SurfaceStats, assess, loss_peak_frequency


def assess_run(ds: xr.Dataset, setup) -> tuple[Note, ...]:
    """The notes of every model of a run (``rubbercontact.pipeline.run``'s results).

    Parameters
    ----------
    ds
        The results: ``friction`` and ``contact_fraction`` on ``(model, [temperature,]
        velocity, realization, pressure)``, ``max_local_pressure`` for the law models, the
        law table (``law_*``) when a model read one.
    setup
        The run's :class:`~rubbercontact.pipeline.setup.RunSetup` (the base surface, the
        split threshold, the rubber at its reference temperature, the speeds' shift factors).

    Returns
    -------
    tuple of Note
        Per model in the run's order, :func:`assess`'s notes; speeds are the run's (not the
        reduced ones), with the temperature in a run with temperatures.
    """
    stats = SurfaceStats.from_series(setup.base, setup.config.surface.m2_threshold)
    # an elastic rubber has no loss peak (and no hysteretic friction): no speed bounds
    peak = math.inf if setup.material.is_elastic else loss_peak_frequency(setup.material)
    law = _law(ds)
    notes: list[Note] = []
    for model in setup.models:
        if model not in ds["model"].values:
            continue
        # an under-resolved FEM explains a departure from the VHS as well as the class does
        resolution = _law_resolution(model, law) + _fem_resolution(model, ds)
        for temperature, shift in _temperatures(ds, setup):
            points = [_point(ds, model, float(v), temperature, shift, law)
                      for v in ds["velocity"].values]
            found = assess(model, stats, points, peak / shift, resolution)
            # the surface's notes once per model, not once per temperature
            notes.extend(n for n in found if n.velocity is not None or n not in notes)
        notes.extend(resolution)
    return tuple(notes)


def _fem_resolution(model: str, ds: xr.Dataset) -> list[Note]:
    """One note if the full FEM's tests were under-resolved (``fem_under_resolved``)."""
    from ..fem.resolution import RESOLUTION_STUDY

    if model != "fem" or "fem_under_resolved" not in ds:
        return []
    flag = ds["fem_under_resolved"].values == 1
    if not flag.any():
        return []
    cols = float(np.nanmin(np.where(flag, ds["fem_patch_columns"].values, np.inf)))
    reason = (f"{int(flag.sum())} of {int(np.isfinite(ds['fem_under_resolved'].values).sum())}"
              f" FEM tests under-resolved, narrowest contact patch {cols:.1f} columns; a "
              f"finer fem.full_mesh resolves them ({RESOLUTION_STUDY})")
    return [Note(model, "fem_resolution", reason, detail=reason)]


def _law_resolution(model: str, law: xr.Dataset | None) -> list[Note]:
    """One note if ``model`` reads a law whose FEM points were under-resolved (their
    narrowest contact patch below the check's width, :mod:`rubbercontact.fem.resolution`)."""
    from ..fem.resolution import RESOLUTION_STUDY
    from ..models.registry import needs_law

    if not needs_law(model) or law is None or "under_resolved" not in law:
        return []
    law = law.transpose("velocity", "pressure")
    flag = law["under_resolved"].values == 1
    if not flag.any():
        return []
    cols = law["patch_columns"].values
    i, j = np.unravel_index(np.argmin(np.where(flag, cols, np.inf)), flag.shape)
    v, p = law["velocity"].values[i], law["pressure"].values[j]
    reason = (f"{int(flag.sum())} of {flag.size} law FEM points under-resolved, narrowest "
              f"contact patch {cols[i, j]:.1f} columns (p = {p:g} MPa, v = {v:g} mm/s); "
              f"{_finer(law)} refines them ({RESOLUTION_STUDY})")
    return [Note(model, "law_resolution", reason, detail=reason)]


def _finer(law: xr.Dataset) -> str:
    """The option that refines the law's cell: ``columns_per_wave`` applies only to the
    automatic mesh, so a law on a given mesh is told to take a finer one (or "auto")."""
    try:
        mesh = json.loads(law.attrs.get("fem_options", "{}")).get("mesh", "auto")
    except (TypeError, ValueError):
        mesh = "auto"
    if mesh == "auto":
        return "a larger fem.columns_per_wave"
    return f'fem.mesh = "auto" or a finer fem.mesh than {mesh[0]} x {mesh[1]}'


def _temperatures(ds: xr.Dataset, setup) -> list[tuple[float | None, float]]:
    """``(temperature, a_T)`` of each temperature of the run (``(None, 1)`` isothermal)."""
    if "temperature" not in ds.dims:
        return [(None, 1.0)]
    shifts = np.asarray(setup.speeds.shift_factors, float)
    return [(float(t), float(a)) for t, a in zip(ds["temperature"].values, shifts,
                                                  strict=True)]


def _law(ds: xr.Dataset) -> xr.Dataset | None:
    if "law_pressure" not in ds.coords:
        return None
    from ..hybrid.lawio import law_from_results

    return law_from_results(ds)


def _point(ds: xr.Dataset, model: str, v: float, temperature: float | None, shift: float,
           law: xr.Dataset | None) -> SpeedPoint:
    """What the run has for ``model`` at speed ``v`` (and ``temperature``)."""
    where = {"velocity": v} | ({} if temperature is None else {"temperature": temperature})

    def mean(name: str, m: str) -> tuple[float, ...]:
        values = ds[name].sel(model=m, **where)
        return tuple(np.atleast_1d(values.mean("realization", skipna=True).values).tolist())

    mu = mean("friction", model)
    ref = mean("friction", "vhs") if "vhs" in ds["model"].values else ()
    local = top = None
    if law is not None and "max_local_pressure" in ds:
        reached = ds["max_local_pressure"].sel(model=model, **where).values
        if np.isfinite(reached).any():
            from ..hybrid.lawtable import law_top

            local, top = float(np.nanmax(reached)), law_top(law, v * shift)
    return SpeedPoint(v, contact=mean("contact_fraction", model), friction=mu if ref else (),
                      friction_vhs=ref, local_pressure=local, law_top=top,
                      temperature=temperature)

