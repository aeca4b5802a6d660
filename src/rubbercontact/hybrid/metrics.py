"""Comparison metrics between models (paper §3)."""

from __future__ import annotations

import numpy as np

from .._validation import finite_array
from ..errors import InputError


def mean_relative_error(reference, candidate) -> float:
    """Paper eq. 28: ``e = mean_k |μ_ref,k − μ_k| / μ_ref,k`` (a fraction, not %).

    Parameters
    ----------
    reference
        ``μ_FEM,k`` at the K comparison points (e.g. contact areas 0.01…0.1); non-zero.
    candidate
        ``μ_H,k`` (or ``μ_VHS,k``) at the same points.
    """
    ref = finite_array("reference", reference, ndim=1)
    cand = finite_array("candidate", candidate, ndim=1)
    if ref.shape != cand.shape:
        raise InputError(f"reference and candidate: lengths differ ({ref.size} vs {cand.size})")
    if np.any(ref == 0):
        raise InputError("reference: contains zeros; the relative error is undefined there")
    return float(np.mean(np.abs(ref - cand) / np.abs(ref)))


def rising_branch(loads, contact_area) -> np.ndarray:
    """Which points of a load sweep lie on the branch where the contact area grows.

    A point is kept when its area exceeds the area at every lower load. Friction at a
    given area is single-valued only there: where a sweep's area stops growing (the full
    FEM at 50 mm/s above about 1 MPa, once creep has settled: the cell shears by more
    than 1 and its contact shrinks, docs/validation/settled_loads.md), ``μ(A)`` folds back
    and sorting by area would interleave the two branches.

    Parameters
    ----------
    loads
        Mean pressures of the sweep [MPa], in any order, distinct.
    contact_area
        Contact fraction at each load [1].

    Returns
    -------
    numpy.ndarray of bool
        In the order given.
    """
    p = finite_array("loads", loads, ndim=1)
    a = finite_array("contact_area", contact_area, ndim=1)
    if p.shape != a.shape:
        raise InputError(f"loads and contact_area: lengths differ ({p.size} vs {a.size})")
    if np.unique(p).size != p.size:
        raise InputError("loads: repeated values; a load sweep needs distinct loads")
    order = np.argsort(p)
    below = np.maximum.accumulate(np.concatenate([[-np.inf], a[order][:-1]]))
    keep = np.empty(p.shape, bool)
    keep[order] = a[order] > below
    return keep


def interpolate_at_areas(contact_area, friction, targets, loads=None) -> np.ndarray:
    """Friction at target contact areas by interpolation along a load sweep.

    Interpolation is linear in ``log(area)`` (area grows roughly like a power of the
    load), and targets outside the computed range give NaN rather than an extrapolated
    guess. Without ``loads`` the area must increase with the load (the points may come in
    any order); with ``loads`` [MPa] only the :func:`rising_branch` is used.
    """
    a = finite_array("contact_area", contact_area, ndim=1)
    mu = finite_array("friction", friction, ndim=1)
    t = finite_array("targets", targets, ndim=1)
    if a.shape != mu.shape:
        raise InputError("contact_area and friction: lengths differ")
    if loads is not None:
        keep = rising_branch(loads, a)
        a, mu = a[keep], mu[keep]
    order = np.argsort(a)
    a, mu = a[order], mu[order]
    keep = a > 0
    a, mu = a[keep], mu[keep]
    if a.size < 2:
        return np.full(t.shape, np.nan)
    out = np.interp(np.log(t), np.log(a), mu, left=np.nan, right=np.nan)
    return out


def bootstrap_interval(statistic, n_realizations: int, *, resamples: int = 2000,
                       level: float = 0.9, seed: int = 0) -> tuple[float, float, int]:
    """Percentile bootstrap interval of a statistic over resampled realizations.

    The realizations of a random-phase study are the sampling unit: every model was run
    on the same ones, so one resample of realization indices (drawn with replacement) is
    applied to all models at once (a paired bootstrap). This gives the sampling
    uncertainty of, e.g., the eq. 28 error of a 5-realization comparison.

    Parameters
    ----------
    statistic
        ``statistic(indices) -> float``: the statistic recomputed on the realizations
        ``indices`` (an integer array of length ``n_realizations``). NaN (e.g. a resample
        whose load sweeps share no contact-area range) is left out.
    n_realizations
        Number of realizations available (≥ 2).
    resamples
        Number of bootstrap resamples (≥ 100; the interval ends are quantiles of these).
    level
        Two-sided coverage, 0 < level < 1.
    seed
        Seed of the resampling (the interval is reproducible).

    Returns
    -------
    (low, high, used)
        The interval ends (the ``(1 - level) / 2`` and ``(1 + level) / 2`` quantiles) and
        the number of resamples that gave a finite statistic.
    """
    if int(n_realizations) != n_realizations or n_realizations < 2:
        raise InputError(f"n_realizations: need an integer >= 2, got {n_realizations!r}")
    if int(resamples) != resamples or resamples < 100:
        raise InputError(f"resamples: need an integer >= 100, got {resamples!r}")
    if not 0.0 < level < 1.0:
        raise InputError(f"level: need 0 < level < 1, got {level!r}")
    rng = np.random.default_rng(seed)
    draws = rng.integers(0, n_realizations, size=(int(resamples), int(n_realizations)))
    values = np.array([statistic(idx) for idx in draws], dtype=float)
    values = values[np.isfinite(values)]
    if values.size == 0:
        raise InputError("statistic: no resample gave a finite value")
    low, high = np.quantile(values, [(1.0 - level) / 2.0, (1.0 + level) / 2.0])
    return float(low), float(high), int(values.size)


def control_variate_mean(target, control, control_all) -> np.ndarray:
    """Mean of an expensive model over random phases, with a cheap one as control variate.

    ``mean(control_all) + mean(target − control)`` along the first axis: the difference
    estimator. ``target`` and ``control`` hold the two models on the same R realizations
    (e.g. the full FEM and the VHS, paired); ``control_all`` the cheap model on N
    realizations drawn from the same distribution (they may include those R). It is
    unbiased for ``E[target]`` and its variance is ``var(target − control)/R +
    var(control)/N`` (plus ``2 cov(target − control, control)/N`` when the N include the
    R), against ``var(target)/R`` for the plain mean: a large gain when the two models
    respond alike to the phases, as the VHS and the FEM do on the same crests.

    Parameters
    ----------
    target, control
        ``(R, ...)`` arrays, the same realizations in the same order (R ≥ 1).
    control_all
        ``(N, ...)`` array with the same trailing shape.

    Returns
    -------
    numpy.ndarray
        The estimate, shape ``(...)``, in the units of ``target``.
    """
    t = np.asarray(target, dtype=float)
    c = np.asarray(control, dtype=float)
    call = np.asarray(control_all, dtype=float)
    if t.ndim == 0 or t.shape != c.shape:
        raise InputError(f"target and control: need the same shape (R, ...), got {t.shape} "
                         f"and {c.shape}")
    if call.ndim == 0 or call.shape[1:] != t.shape[1:] or call.shape[0] < 1 or t.shape[0] < 1:
        raise InputError(f"control_all: need shape (N, {', '.join(map(str, t.shape[1:]))}) "
                         f"with N >= 1, got {call.shape}")
    for name, x in (("target", t), ("control", c), ("control_all", call)):
        if not np.all(np.isfinite(x)):
            raise InputError(f"{name}: contains NaN or inf (a failed solve?); drop that "
                             "realization from both paired arrays")
    return control_variate_by_column(t, c, call)[0]


def regression_coefficient(target, control) -> float:
    """``cov(t, c) / var(c)`` of paired samples: the control's least-squares coefficient."""
    return float(np.cov(target, control)[0, 1] / np.var(control, ddof=1))


def control_variate_by_column(target, control, control_all, beta: str = "difference"
                              ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`control_variate_mean` per column (e.g. per load), failed solves left out.

    The estimate is ``mean_R(t) + β (mean_N(c) − mean_R(c))``. With ``beta="difference"``
    β = 1, which is :func:`control_variate_mean`: unbiased whatever R. With
    ``beta="regression"`` β is fitted per column on the R pairs, ``cov(t, c)/var(c)``
    (Cochran's regression estimator): when the FEM responds to the phases more or less
    strongly than the VHS (on section 3, β = 0.63-1.29), the residual ``t − βc`` varies much
    less than ``t − c`` and so does the estimate, at the price of a bias of order 1/R. It
    needs three pairs in a column (NaN otherwise).

    At each trailing index the realizations where ``target`` or ``control`` is not finite
    (a failed FEM test) are dropped from the pairs, and non-finite ``control_all`` values
    from the N; a column with no pair left is NaN. The standard error is estimated from
    the samples, with ``e = t − βc``, as ``sqrt(var(e)/R + β² var(c)/N + 2β cov(e, c)/N)``,
    the variance of the estimator when the N realizations include the R (``var(e)`` with
    one more degree of freedom spent when β is fitted; NaN with too few samples).

    Parameters
    ----------
    target, control
        ``(R, ...)`` arrays, paired realization by realization.
    control_all
        ``(N, ...)`` array with the same trailing shape.
    beta
        ``"difference"`` (β = 1) or ``"regression"`` (β fitted per column).

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        The estimate and its standard error, each of shape ``(...)``.
    """
    if beta not in ("difference", "regression"):
        raise InputError(f"beta: 'difference' or 'regression', got {beta!r}")
    t = np.asarray(target, dtype=float)
    c = np.asarray(control, dtype=float)
    call = np.asarray(control_all, dtype=float)
    if t.ndim == 0 or t.shape != c.shape or call.ndim == 0 or call.shape[1:] != t.shape[1:]:
        raise InputError(f"target, control, control_all: need shapes (R, ...), (R, ...), "
                         f"(N, ...) with the same trailing shape, got {t.shape}, {c.shape}, "
                         f"{call.shape}")
    fitted = beta == "regression"
    tail = t.shape[1:]
    t, c, call = (x.reshape(x.shape[0], -1) for x in (t, c, call))
    est = np.full(t.shape[1], np.nan)
    se = np.full(t.shape[1], np.nan)
    for k in range(t.shape[1]):
        pair = np.isfinite(t[:, k]) & np.isfinite(c[:, k])
        every = call[np.isfinite(call[:, k]), k]
        tk, ck, r, n = t[pair, k], c[pair, k], int(pair.sum()), every.size
        if r == 0 or n == 0 or (fitted and (r < 3 or np.var(ck) == 0.0)):
            continue
        b = regression_coefficient(tk, ck) if fitted else 1.0
        est[k] = tk.mean() + b * (every.mean() - ck.mean())
        e = tk - b * ck
        if r >= 2 + fitted and n >= 2:
            var = (np.sum((e - e.mean()) ** 2) / (r - 1 - fitted) / r
                   + b**2 * np.var(every, ddof=1) / n + 2.0 * b * np.cov(ck, e)[0, 1] / n)
            se[k] = np.sqrt(max(var, 0.0))
    return est.reshape(tail), se.reshape(tail)
