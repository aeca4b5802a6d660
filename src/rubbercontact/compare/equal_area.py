"""Eq. 28 of the paper at equal contact area, and its sampling uncertainty over realizations.

The paper compares models by eq. 28, ``e = mean_k |μ_model,k − μ_FEM,k| / μ_FEM,k``, at a
few contact areas ``A_k``: at equal area, not at equal mean pressure, because the models'
area–load curves differ and friction is read against the contact the model predicts. The
areas are log-spaced over the range every model's (realization-mean) load sweep covers, so
nothing is extrapolated.

The random phases of the surface are the sampling unit: intervals come from a paired
bootstrap over realizations (every model resampled on the same drawn realizations). The
eq. 28 figure is a mean of absolute values, so resampling folds its noise upward: near a
true error of zero its percentile interval lies above the estimate. :func:`signed_errors`
and :func:`eq28_bounds` report instead the signed error at each area with its interval and
the range of eq. 28 over those intervals, which contains the estimate and narrows as
1/√R with the number of realizations.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..hybrid.metrics import (
    interpolate_at_areas,
    mean_relative_error,
    rising_branch,
)

#: Bootstrap resamples and the two-sided level of every interval of eq. 28.
RESAMPLES = 2000
INTERVAL_LEVEL = 0.9
#: Factors on the FEM's contact fractions of :func:`area_sensitivity`.
AREA_FACTORS = (1.05, 1.0, 0.95, 0.9)


def common_areas(curves: dict, points: int = 4):
    """``points`` areas log-spaced over the range every ``(area, μ)`` sweep covers, and
    each model's μ there (nothing extrapolated); None when the sweeps share no range.
    The sweeps come in increasing load; only their rising branch is used (a load whose
    area does not exceed a lower load's is left out, ``rising_branch``)."""
    curves = {m: (a[np.isfinite(a) & np.isfinite(mu)], mu[np.isfinite(a) & np.isfinite(mu)])
              for m, (a, mu) in curves.items()}    # failed loads (NaN) are left out
    for m, (a, mu) in curves.items():
        if a.size:   # per load, in increasing load: the index orders the loads
            keep = rising_branch(np.arange(a.size), a)
            curves[m] = (a[keep], mu[keep])
    if any(a.size < 2 for a, _ in curves.values()):
        return None
    lo = max(a.min() for a, _ in curves.values())
    hi = min(a.max() for a, _ in curves.values())
    if not hi > lo:
        return None
    areas = np.geomspace(lo, hi, points)
    return areas, {m: interpolate_at_areas(a, mu, areas) for m, (a, mu) in curves.items()}


def friction_at_common_areas(ds, points: int = 4) -> dict:
    """Per velocity: target areas and each model's mean friction there.

    With target areas in the config these are the config's (pipeline output); with loads
    given as pressures, ``points`` areas log-spaced over the range that every model's
    load sweep covers (so nothing is extrapolated).
    """
    models = list(ds["model"].values)
    out = {}
    for v in ds["velocity"].values:
        if "friction_at_area_mean" in ds:
            areas = ds["contact_area"].values
            mus = {m: ds["friction_at_area_mean"].sel(model=m, velocity=v).values
                   for m in models}
        else:
            s = ds.sel(velocity=v)
            common = common_areas({m: (s["contact_fraction_mean"].sel(model=m).values,
                                        s["friction_mean"].sel(model=m).values)
                                    for m in models}, points)
            if common is None:
                continue
            areas, mus = common
        ok = np.all([np.isfinite(mus[m]) for m in models], axis=0)
        out[float(v)] = (areas[ok], {m: mus[m][ok] for m in models})
    return out


def eq28_intervals(ds, models=("hybrid", "hybrid-windowed", "vhs"),
                   level: float = INTERVAL_LEVEL, resamples: int = RESAMPLES,
                   points: int = 4) -> dict:
    """``{v: {model: (low, high, used)}}``: the sampling uncertainty of eq. 28 at equal area,
    the range of :class:`Eq28` (which contains the estimate of :func:`eq28_at_equal_area`).

    A paired bootstrap over realizations: each resample redoes the mean curves of every
    model on the same drawn realizations, read at the areas of the whole set.
    """
    models = [m for m in models if m in ds["model"].values]
    out = {}
    for v in ds["velocity"].values:
        if "friction_at_area" in ds:
            res = _at_area_bounds(ds, float(v), models, level, resamples)
        else:
            res = eq28_realization_bounds(ds, float(v), models, level=level,
                                          resamples=resamples, points=points)
        out[float(v)] = {m: (b.low, b.high, b.used) for m, b in res.items()}
    return out


def _at_area_bounds(ds, velocity: float, models, level: float, resamples: int) -> dict:
    """:class:`Eq28` of each model where the run interpolated every realization at the
    config's target areas (``friction_at_area``)."""
    s = ds.sel(velocity=velocity)
    mu_k = {m: s["friction_at_area"].sel(model=m).transpose("realization", ...).values
            for m in ds["model"].values}
    n = ds.sizes["realization"]
    areas = np.asarray(ds["contact_area"].values, float)

    def signed(idx, m):
        fem, mod = mu_k["fem"][idx].mean(axis=0), mu_k[m][idx].mean(axis=0)
        return (mod - fem) / fem

    rng = np.random.default_rng(0)
    draws = [rng.integers(0, n, n) for _ in range(int(resamples))]
    out = {}
    for m in models:
        r_hat = signed(np.arange(n), m)
        ok = np.isfinite(r_hat)
        if ok.any():
            r_star = np.array([signed(idx, m)[ok] for idx in draws])
            out[m] = _project(areas[ok], r_hat[ok], r_star, level)
    return out


def with_realization_means(ds):
    """``ds`` with ``friction_mean`` and ``contact_fraction_mean`` redone from the
    realizations it holds (after a subset, a replaced model or a scaled area)."""
    return ds.assign(friction_mean=ds["friction"].mean("realization"),
                     contact_fraction_mean=ds["contact_fraction"].mean("realization"))


def eq28_at_equal_area(ds, models=("hybrid", "hybrid-windowed", "vhs")) -> dict:
    """``{v: (areas, {model: e})}``: eq. 28 against the FEM at the common areas of
    ``friction_at_common_areas`` (the comparison of VALIDATION.md)."""
    return {v: (areas, {m: mean_relative_error(mus["fem"], mus[m]) for m in models
                        if m in mus})
            for v, (areas, mus) in friction_at_common_areas(ds).items()}


def eq28_first(ds, k: int | None = None,
               models=("hybrid", "hybrid-windowed", "vhs")) -> dict:
    """``{v: (areas, {model: e}, {model: (low, high, used)})}``: eq. 28 at equal area over
    the first ``k`` realizations (all: None), with its bootstrap interval (none for one
    realization)."""
    sub = ds if k is None else with_realization_means(ds.isel(realization=slice(0, k)))
    ci = eq28_intervals(sub, models=models) if sub.sizes["realization"] >= 2 else {}
    return {v: (areas, e, ci.get(v, {}))
            for v, (areas, e) in eq28_at_equal_area(sub, models).items()}


def with_area_factor(ds, factor: float):
    """``ds`` with the FEM's contact fractions multiplied by ``factor`` (friction unchanged)."""
    ds = ds.copy(deep=True)
    ds["contact_fraction"].loc[{"model": "fem"}] = ds["contact_fraction"].sel(model="fem") * factor
    return with_realization_means(ds)


def area_sensitivity(ds, models=("hybrid-windowed", "vhs")) -> dict:
    """``{factor: {v: {model: e}}}``: eq. 28 at equal area with every FEM contact fraction
    scaled by each of ``AREA_FACTORS``."""
    return {factor: {v: e for v, (_, e) in
                     eq28_at_equal_area(with_area_factor(ds, factor), models).items()}
            for factor in AREA_FACTORS}


def per_realization_errors(ds, models=("hybrid-windowed", "vhs"), points: int = 4) -> dict:
    """``{v: {model: [e_r]}}``: eq. 28 at equal area within each realization.

    The paper's eq. 28 compares realization means. This compares each realization's own
    load sweep (common areas as in ``common_areas``), so it says how well a model predicts
    one surface rather than the ensemble; NaN where that realization's sweeps share no area.
    """
    models = [m for m in models if m in ds["model"].values]
    out: dict = {}
    for v in ds["velocity"].values:
        s = ds.sel(velocity=v)
        errs: dict = {m: [] for m in models}
        for r in range(ds.sizes["realization"]):
            sr = s.isel(realization=r)
            common = common_areas({m: (sr["contact_fraction"].sel(model=m).values,
                                        sr["friction"].sel(model=m).values)
                                    for m in [*models, "fem"]}, points)
            for m in models:
                errs[m].append(np.nan if common is None
                               else mean_relative_error(common[1]["fem"], common[1][m]))
        out[float(v)] = errs
    return out


def eq28_of_curves(curves: dict, models, points: int = 4) -> dict:
    """``{m: e}``: eq. 28 against ``curves["fem"]`` at the common areas of mean curves."""
    common = common_areas(curves, points)
    if common is None:
        return {m: np.nan for m in models}
    _, mus = common
    ok = np.all([np.isfinite(x) for x in mus.values()], axis=0)
    return {m: mean_relative_error(mus["fem"][ok], mus[m][ok]) if ok.any() else np.nan
            for m in models}


@dataclass(frozen=True)
class Eq28:
    """Eq. 28 of one model against the FEM at one speed, with its sampling uncertainty.

    Attributes
    ----------
    areas
        The comparison areas A_k [-] (common to every model's mean load sweep).
    signed
        Signed relative errors ``r_k = (μ_model − μ_FEM)/μ_FEM`` at the areas [-].
    signed_low, signed_high
        Their percentile intervals (paired bootstrap over realizations, ``level``).
    error
        Eq. 28, ``mean_k |r_k|`` [-].
    low, high
        The range of eq. 28 over the intervals of the ``r_k``: from the mean distance of
        each interval to zero to the mean of its farthest end. It contains ``error``
        (each ``r_k`` lies in its interval) and narrows as 1/√R.
    used
        Resamples that gave a finite error at every area.
    """

    areas: np.ndarray
    signed: np.ndarray
    signed_low: np.ndarray
    signed_high: np.ndarray
    error: float
    low: float
    high: float
    used: int

    @property
    def bias(self) -> float:
        """Mean signed error ``mean_k r_k`` [-]: the model high (+) or low (−) on average."""
        return float(np.mean(self.signed))


def _signed_at(curves: dict, models, points: int) -> dict:
    """``{model: r_k}`` at the ``points`` common areas of the mean load sweeps ``curves``
    (NaN where they share no area range)."""
    common = common_areas(curves, points)
    if common is None:
        return {m: np.full(points, np.nan) for m in models}
    _, mus = common
    return {m: (mus[m] - mus["fem"]) / mus["fem"] for m in models}


def eq28_bounds(curves_of, draw, models, *, resamples: int = RESAMPLES,
                level: float = INTERVAL_LEVEL, seed: int = 0, points: int = 4) -> dict:
    """``{model: Eq28}``: eq. 28 at equal area with the per-area signed intervals.

    Parameters
    ----------
    curves_of
        ``curves_of(sample) -> {model: (A, μ)}``: the mean load sweeps of every model and
        ``"fem"`` on a resample of the realizations (``sample=None``: all of them).
    draw
        ``draw(rng) -> sample``: one bootstrap resample (realization indices).
    models
        The models compared with ``"fem"``.
    resamples, level, seed
        Bootstrap resamples, two-sided level of the per-area intervals, seed.
    points
        Number of comparison areas.
    """
    common = common_areas(curves_of(None), points)
    if common is None:
        return {}
    areas, mus = common
    rng = np.random.default_rng(seed)
    # each resample at its own common areas (k-th to k-th), as eq. 28 itself is taken
    draws = [_signed_at(curves_of(draw(rng)), models, points) for _ in range(int(resamples))]
    out = {}
    for m in models:
        r_hat = (mus[m] - mus["fem"]) / mus["fem"]
        res = _project(areas, r_hat, np.array([d[m] for d in draws]), level)
        if res is not None:
            out[m] = res
    return out


def _project(areas: np.ndarray, r_hat: np.ndarray, r_star: np.ndarray, level: float
             ) -> Eq28 | None:
    """:class:`Eq28` from the signed errors ``r_hat`` and their resamples ``r_star``
    (resamples, areas); resamples with a NaN (an area a resampled curve misses) left out."""
    r_star = r_star[np.all(np.isfinite(r_star), axis=1)]
    if r_star.shape[0] == 0:
        return None
    lo, hi = np.quantile(r_star, [(1 - level) / 2, (1 + level) / 2], axis=0)
    # the estimate lies in its interval for a smooth statistic; make the containment exact
    # where a resampled curve's rising branch leaves a point out at the edge
    lo, hi = np.minimum(lo, r_hat), np.maximum(hi, r_hat)
    near = np.where((lo <= 0) & (hi >= 0), 0.0, np.minimum(np.abs(lo), np.abs(hi)))
    far = np.maximum(np.abs(lo), np.abs(hi))
    return Eq28(areas, r_hat, lo, hi, float(np.mean(np.abs(r_hat))), float(np.mean(near)),
                float(np.mean(far)), int(r_star.shape[0]))


def eq28_realization_bounds(ds, velocity: float, models=("hybrid", "hybrid-windowed", "vhs"),
                            **kwargs) -> dict:
    """:func:`eq28_bounds` of the realization means of a run's results at ``velocity``."""
    s = ds.sel(velocity=velocity)
    arr = {m: (s["contact_fraction"].sel(model=m).transpose("realization", ...).values,
               s["friction"].sel(model=m).transpose("realization", ...).values)
           for m in ds["model"].values}
    n = ds.sizes["realization"]

    def curves_of(idx):
        idx = np.arange(n) if idx is None else idx
        return {k: (a[idx].mean(axis=0), mu[idx].mean(axis=0)) for k, (a, mu) in arr.items()}

    return eq28_bounds(curves_of, lambda rng: rng.integers(0, n, n),
                       [m for m in models if m in arr], **kwargs)
