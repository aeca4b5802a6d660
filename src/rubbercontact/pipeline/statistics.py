"""Statistics over the random-phase realizations, and the eq. 28 comparison against the FEM.

The results file keeps each statistic as its own variable (``friction_mean``,
``friction_std``, ``friction_phase_mean``, ``friction_phase_se``, ...); read them through
the ``ds.rc`` accessor (:class:`rubbercontact.io.results.ResultsAccessor`) rather than by
their names.

With ``fem.realizations = R`` below ``realizations = N`` the full FEM runs on the first R
realizations only and the cheap models on all N; the FEM's phase average is then estimated
per load as ``mean_N(VHS) + mean_R(FEM − VHS)`` (:func:`.metrics.control_variate_mean`):
unbiased, and far less noisy than the plain mean of R FEM tests because the VHS follows
the FEM realization by realization. Those estimates are the ``*_phase_mean`` variables,
and eq. 28 compares against them.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..hybrid.metrics import control_variate_by_column, mean_relative_error
from ..io.results import mean_of

__all__ = ["PHASE_MEAN_VARIABLES", "REALIZATION_STATISTICS", "Peak", "add_errors",
           "add_phase_means", "add_realization_statistics", "friction_peak", "mean_of"]

#: Per-realization variables whose mean and standard deviation over the realizations the
#: results carry (``k_mean``, ``k_std``).
REALIZATION_STATISTICS = ("friction", "contact_fraction", "mean_separation",
                          "friction_adhesion", "friction_total")
#: Per-realization variables whose phase average ``add_phase_means`` estimates.
PHASE_MEAN_VARIABLES = ("friction", "contact_fraction", "mean_separation", "friction_at_area",
                        "friction_adhesion", "friction_total", "friction_total_at_area")


def add_realization_statistics(ds: xr.Dataset) -> xr.Dataset:
    """``k_mean`` and ``k_std`` over the realizations for :data:`REALIZATION_STATISTICS`."""
    for k in REALIZATION_STATISTICS:
        if k not in ds:
            continue
        ds[f"{k}_mean"] = ds[k].mean("realization")
        ds[f"{k}_std"] = ds[k].std("realization")
        ds[f"{k}_mean"].attrs["units"] = ds[f"{k}_std"].attrs["units"] = ds[k].attrs["units"]
    return ds


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


def add_errors(ds: xr.Dataset) -> xr.Dataset:
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
    ds = ds.assign_coords(compared_model=others)
    if dim == "pressure":
        ds["error_vs_fem_at_area"] = (("compared_model", "velocity"), _at_area(ds, others), {
            "units": "1", "long_name": "eq. 28 mean relative error vs FEM at equal contact "
                                       "area (the validation's statistic)",
            "compared_over": "contact_area",
            "fem_reference": ds["error_vs_fem"].attrs["fem_reference"]})
    return ds


def _at_area(ds: xr.Dataset, others: list[str]) -> np.ndarray:
    """Eq. 28 at the areas every model's mean load sweep covers
    (:func:`rubbercontact.compare.eq28_of_curves`, as VALIDATION.md and the README)."""
    from ..compare import eq28_of_curves

    mu, area = mean_of(ds, "friction"), mean_of(ds, "contact_fraction")
    err = np.full((len(others), ds.sizes["velocity"]), np.nan)
    for iv in range(ds.sizes["velocity"]):
        curves = {m: (area.sel(model=m).isel(velocity=iv).values,
                      mu.sel(model=m).isel(velocity=iv).values)
                  for m in [*others, "fem"]}
        e = eq28_of_curves(curves, others)
        err[:, iv] = [e[m] for m in others]
    return err


@dataclass(frozen=True)
class Peak:
    """Where a friction curve peaks.

    Attributes
    ----------
    velocity
        Speed of the maximum [mm/s]: the vertex of the parabola in ``log10 v`` through the
        largest sample and its two neighbours, or the largest sample at an end of the range.
    friction
        The friction there [-] (the parabola's vertex value, or the sample).
    interior
        False when the largest sample is the first or the last speed: the peak may lie
        beyond the range.
    """

    velocity: float
    friction: float
    interior: bool


def friction_peak(velocities, friction) -> Peak | None:
    """The :class:`Peak` of ``friction`` sampled at ``velocities`` [mm/s] (> 0, finite
    points only; None with fewer than two)."""
    v = np.asarray(velocities, float)
    mu = np.asarray(friction, float)
    ok = np.isfinite(mu) & (v > 0)
    if ok.sum() < 2:
        return None
    order = np.argsort(v[ok])
    x, y = np.log10(v[ok][order]), mu[ok][order]
    k = int(np.argmax(y))
    if k == 0 or k == y.size - 1:
        return Peak(float(10 ** x[k]), float(y[k]), False)
    xs, ys = x[k - 1:k + 2], y[k - 1:k + 2]
    a, b, c = np.polyfit(xs, ys, 2)
    if not a < 0:
        return Peak(float(10 ** x[k]), float(y[k]), True)
    xv = float(np.clip(-b / (2 * a), xs[0], xs[-1]))
    return Peak(float(10**xv), float(np.polyval([a, b, c], xv)), True)
