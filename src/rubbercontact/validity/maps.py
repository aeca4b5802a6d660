"""A run on a height map against the validated classes (:mod:`rubbercontact.pipeline.maprun`).

Every class was measured on one-dimensional surfaces (sine series, line scans): its
``dimension`` condition (:mod:`.classes`) gives each model on a map one note saying so,
pointing at the two measurements on maps, docs/validation/maps_split.md (the hybrid's scale
split with the linear law against the 2D VHS) and maps_meanfield.md (the mean-field against
the 2D BEM). The classes' other conditions are read off
the map's octave bands (:func:`rubbercontact.roughness.mapsplit.octave_bands`): a band
stands for a wave of its wavelength with the band's rms slope along x (the sliding
direction) as its per-wave m2 — the quantity the map's split compares with the threshold,
as the 1D split compares each wave's — so the wavelength ratio at the split is that of the
bands on either side of it.

Left out on maps: ``law_pressure`` (the map hybrids read the *linear* law of their cell, not
the FEM's: there are no FEM points to leave) and temperatures (a map run is isothermal).
``spacing`` holds by construction (the bands are octaves).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from .assess import Note, SpeedPoint, SurfaceStats, assess, loss_peak_frequency


def map_surface_stats(hmap, m2_threshold: float = 1.0) -> SurfaceStats:
    """The waves of a periodic map as the classes see them: one per octave band.

    Parameters
    ----------
    hmap
        A periodic :class:`~rubbercontact.roughness.HeightMap` [mm].
    m2_threshold
        The split: a band whose rms slope along x exceeds it is high-slope.
    """
    from ..roughness.mapsplit import octave_bands

    bands = octave_bands(hmap, m2_threshold)
    # a band with round-off power only is no wave (it would add a spurious frequency)
    variance = bands["variance"].values
    live = variance > 1e-15 * variance.sum()
    return SurfaceStats(tuple(map(float, bands["wavelength"].values[live])),
                        tuple(map(float, bands["rms_slope_x"].values[live])),
                        float(m2_threshold), dimension=2)


def assess_map_run(ds: xr.Dataset, hmap, material, m2_threshold: float) -> tuple[Note, ...]:
    """The notes of every model of a map run.

    Parameters
    ----------
    ds
        The map run's results: ``friction`` and ``contact_fraction`` on ``(model, velocity,
        pressure)``.
    hmap
        The periodic map the run solved on [mm].
    material
        The run's rubber (``complex_modulus``, ``is_elastic``).
    m2_threshold
        The run's split threshold.

    Returns
    -------
    tuple of Note
        Per model in the run's order, :func:`~.assess.assess`'s notes on the map's bands
        (the first: the model's class was measured in 1D) and the run's speeds.
    """
    stats = map_surface_stats(hmap, m2_threshold)
    # an elastic rubber has no loss peak (and no hysteretic friction): no speed bounds
    peak = math.inf if material.is_elastic else loss_peak_frequency(material)
    notes: list[Note] = []
    for model in map(str, ds["model"].values):
        points = [_point(ds, model, float(v)) for v in ds["velocity"].values]
        notes.extend(assess(model, stats, points, peak))
    return tuple(notes)


def _point(ds: xr.Dataset, model: str, v: float) -> SpeedPoint:
    """What the map run has for ``model`` at speed ``v`` (no law pressure: linear law)."""
    def at(name: str, m: str) -> tuple[float, ...]:
        return tuple(np.atleast_1d(ds[name].sel(model=m, velocity=v).values).tolist())

    ref = at("friction", "vhs") if "vhs" in ds["model"].values else ()
    return SpeedPoint(v, contact=at("contact_fraction", model),
                      friction=at("friction", model) if ref else (), friction_vhs=ref)
