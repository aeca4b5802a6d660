"""Barrier contact: a C² log barrier on the gap, impenetrable by construction.

The penalty contact (:mod:`.contact`) lets the face into the surface and switches a
point's force on at ``g = 0``: a point crossing the surface inside a Newton step changes
the residual's derivative there, and on steep crests Newton cycles between the states
(docs/validation/steep_cells.md). Incremental-potential-contact style (Li et al. 2020),
the barrier energy per unit reference length of the face is

    ``Π_c = κ b(g)``,  ``b(g) = −(g − d̂)² ln(g/d̂)`` for ``0 < g < d̂``, 0 for ``g ≥ d̂``,

with ``g`` the exact normal gap to the analytic surface (:func:`.contact.closest_point`).
``b`` is C² at ``d̂`` (``b = b' = b'' = 0`` there) and infinite at ``g = 0``: the force
``−κ b'(g) n`` grows without bound as the face approaches, so no state with finite
residual penetrates. A state with any contact point at ``g ≤ 0`` has a NaN residual
(inadmissible, like an inverted element), and the Newton line search never gets there:
:func:`feasible_step` bounds the step by conservative advancement (a lower bound of
each point's vertical gap along the step, from the surface's largest curvature), so no
point crosses the surface even between the trial states.

Sizing (:func:`barrier_law`): ``d̂`` is a small fraction of the face's resolution, and
``κ`` puts the gap under the reference pressure ``p_ref`` at ``d̂/10``
(``−b'(d̂/10) = 12.2 d̂``); under a local pressure ``p ≫ p_ref`` the gap is about
``κ d̂²/p``. Points within ``d̂`` of the surface carry force: they are the contact.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..roughness.sines import SineSeries
from .contact import closest_point

#: ``−b'(d̂/10)/d̂``: the barrier's force at a tenth of its reach, per ``κ d̂``.
_FORCE_AT_TENTH = 2.0 * 0.9 * np.log(10.0) + 0.81 / 0.1


def barrier_derivatives(g: np.ndarray, dhat: float):
    """``(b, b', b'')`` of the unit barrier at gaps ``0 < g`` [mm] (0 beyond ``d̂``)."""
    g = np.asarray(g, dtype=float)
    inside = g < dhat
    gi = np.where(inside, g, dhat)
    lg = np.log(gi / dhat)
    e = gi - dhat
    b = np.where(inside, -e * e * lg, 0.0)
    db = np.where(inside, -2.0 * e * lg - e * e / gi, 0.0)
    d2b = np.where(inside, -2.0 * lg - 4.0 * e / gi + e * e / (gi * gi), 0.0)
    return b, db, d2b


@dataclass(frozen=True)
class BarrierLaw:
    """The barrier's reach ``dhat`` [mm] and stiffness ``kappa`` [MPa] (force per length
    per unit ``b'``)."""

    dhat: float
    kappa: float

    def points(self, surface: SineSeries, shift: float, px: np.ndarray, py: np.ndarray,
               weight: np.ndarray):
        """``(gap, force, stiffness, energy)`` at points ``(px, py)`` with reference
        lengths ``weight`` [mm] (the layout of :func:`.contact._point_penalty`); force and
        stiffness are NaN where a point is on or below the surface (inadmissible)."""
        k = px.size
        gap = py - surface.heights(px + shift)
        force = np.zeros((k, 2))
        stiff = np.zeros((k, 2, 2))
        # the normal gap is at least the vertical one times cos θ: only points below
        # d̂ √(1 + max z'²) vertically can be within the barrier's reach
        slope_max = float(np.sum(surface.wavenumbers * surface.amplitudes))
        cand = np.flatnonzero(gap < self.dhat * np.sqrt(1.0 + slope_max**2))
        energy = 0.0
        if cand.size:
            _, g_c, n_c, t_c, k_c = closest_point(surface, shift, px[cand], py[cand])
            gap[cand] = g_c
            # a point below the graph has a negative vertical gap whatever its projection
            bad = (g_c <= 0.0) | (gap[cand] <= 0.0)
            g_safe = np.where(bad, self.dhat, g_c)
            b, db, d2b = barrier_derivatives(g_safe, self.dhat)
            kw = self.kappa * weight[cand]
            force[cand] = (-kw * db)[:, None] * n_c
            curv = k_c / (1.0 - g_safe * k_c)
            stiff[cand] = kw[:, None, None] * (
                d2b[:, None, None] * n_c[:, :, None] * n_c[:, None, :]
                - (db * curv)[:, None, None] * t_c[:, :, None] * t_c[:, None, :])
            energy = float(np.sum(kw * b))
            if np.any(bad):
                force[cand[bad]] = np.nan
                stiff[cand[bad]] = np.nan
                energy = np.inf
        return gap, force, stiff, energy


def barrier_law(scale: float, reference_pressure: float, distance: float = 0.1,
                stiffness: float = 1.0) -> BarrierLaw:
    """The barrier of a face resolved to ``scale`` [mm] under ``p̄`` [MPa].

    ``d̂ = distance · scale``; ``κ`` puts the gap at ``d̂/10`` under ``stiffness · p̄``.
    """
    dhat = float(distance) * float(scale)
    kappa = float(stiffness) * float(reference_pressure) / (_FORCE_AT_TENTH * dhat)
    return BarrierLaw(dhat, kappa)


def feasible_step(surface: SineSeries, shift: float, p0: np.ndarray, dp: np.ndarray,
                  eta: float = 0.9, iterations: int = 60) -> float:
    """The largest ``t ≤ 1`` found such that the points ``p0 + τ dp`` ``(k, 2)`` [mm] stay
    above the graph of the surface for every ``τ ≤ t`` (conservative advancement).

    Along its path a point's vertical gap ``f(τ) = y(τ) − z(x(τ) + s)`` has
    ``f'' = −z'' dx² ≥ −c dx²`` with ``c = Σ k² a`` the largest curvature of the graph, so
    ``f(τ + h) ≥ f + f' h − c dx² h²/2``: no crossing before the first positive root of
    that bound. Each point advances by ``η`` times that root, re-evaluated, until it
    reaches 1 or stops (its time of impact, approached from below); the step is the
    smallest point's. Unlike the distance bound ``|Δp| < g`` this lets a point slide along
    the surface at a small gap (a contact moving along a flank). Points already on or
    below the surface give 0.
    """
    x0, y0 = p0[:, 0], p0[:, 1]
    dx, dy = dp[:, 0], dp[:, 1]
    c = float(np.sum(surface.wavenumbers**2 * surface.amplitudes))
    a = 0.5 * c * dx * dx
    t = np.zeros(x0.size)
    moving = np.ones(x0.size, bool)
    for _ in range(iterations):
        idx = np.flatnonzero(moving)
        if idx.size == 0:
            break
        x = x0[idx] + t[idx] * dx[idx] + shift
        f = y0[idx] + t[idx] * dy[idx] - surface.heights(x)
        if np.any(f <= 0.0):
            # on or below the graph: at the start, or round-off at an impact
            return float(min(np.min(t[idx][f <= 0.0]), np.min(t)))
        fp = dy[idx] - surface.slopes(x) * dx[idx]
        ai = a[idx]
        with np.errstate(divide="ignore", invalid="ignore"):
            root = np.where(ai > 0.0, (fp + np.sqrt(fp * fp + 4.0 * ai * f)) / (2.0 * ai),
                            np.where(fp < 0.0, -f / fp, np.inf))
        h = eta * root
        t[idx] = np.minimum(t[idx] + h, 1.0)
        done = (t[idx] >= 1.0) | (h <= 1e-9)
        moving[idx[done]] = False
    return float(np.min(t, initial=1.0))
