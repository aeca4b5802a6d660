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


def interpolate_at_areas(contact_area, friction, targets) -> np.ndarray:
    """Friction at target contact areas by interpolation along a load sweep.

    ``contact_area`` must increase with the load; interpolation is linear in
    ``log(area)`` (area grows roughly like a power of the load), and targets outside
    the computed range give NaN rather than an extrapolated guess.
    """
    a = finite_array("contact_area", contact_area, ndim=1)
    mu = finite_array("friction", friction, ndim=1)
    t = finite_array("targets", targets, ndim=1)
    if a.shape != mu.shape:
        raise InputError("contact_area and friction: lengths differ")
    order = np.argsort(a)
    a, mu = a[order], mu[order]
    keep = a > 0
    a, mu = a[keep], mu[keep]
    if a.size < 2:
        return np.full(t.shape, np.nan)
    out = np.interp(np.log(t), np.log(a), mu, left=np.nan, right=np.nan)
    return out
