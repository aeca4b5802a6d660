"""Frictionless contact of the rubber's face nodes with the analytic rigid surface.

The rigid surface is the graph ``y = z(x + s)`` of a :class:`SineSeries` shifted by
the sliding distance ``s`` (the surface moves in −x under the rubber, i.e. the
rubber slides in +x relative to it). Gap and normal are exact (closest-point
projection on the analytic curve, no faceting). Node-to-surface penalty with the
energy ``Π_c = Σ_k ε w_k ⟨−g_k⟩²/2``, ``w_k`` the node's reference tributary length,
``ε`` [MPa/mm] sized on the algorithmic modulus (see :func:`penalty_parameter`).

Derivatives for a point ``p`` with closest point ``c(ξ) = (ξ, z)``, unit tangent
``t``, outward normal ``n = (−z', 1)/√(1+z'²)`` and signed curvature
``κ = z''/(1+z'²)^{3/2}``: ``∂g/∂p = n`` and ``∂n/∂p = −κ/(1 − gκ) t⊗t``, so the
nodal force is ``ε w min(g, 0) n`` and its exact tangent
``ε w [n⊗n − min(g, 0) κ/(1 − gκ) t⊗t]`` on active nodes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..roughness.sines import SineSeries


def penalty_parameter(shear_modulus: float, element_size: float, factor: float = 100.0) -> float:
    """Penalty ``ε = factor · E_alg / h`` [MPa/mm] with ``E_alg = 3 μ_alg``.

    ``E_alg = E∞(1 + Σ β_i γ_i)`` is the Young's modulus one time step actually sees
    (the glassy modulus would over-stiffen by ~100× and spoil Newton convergence); with
    ``factor = 100`` the penetration is about ``p h /(100 E_alg)``, i.e. well below a
    per cent of the element size ``h`` for contact pressures of the order of ``E_alg``.
    """
    return factor * 3.0 * shear_modulus / element_size


@dataclass
class ContactState:
    """Contact quantities at the face nodes (arrays of length ``n_face``)."""

    gap: np.ndarray          # signed normal gap where penetrating, vertical gap elsewhere [mm]
    active: np.ndarray       # bool, g < 0
    force: np.ndarray        # (n, 2) force of the surface ON the rubber [N/mm]
    normal: np.ndarray       # (n, 2) surface normal at the closest point
    xi: np.ndarray           # closest-point abscissa in the moving-surface frame [mm]
    stiffness: np.ndarray    # (n, 2, 2) ∂(−force)/∂p [N/mm²]
    energy: float            # penalty energy [N·mm/mm]


def closest_point(surface: SineSeries, shift: float, px: np.ndarray, py: np.ndarray,
                  iterations: int = 30):
    """Closest point of ``(px, py)`` on ``y = z(x + shift)``.

    Newton on ``f(ξ) = (ξ − px) + (z(ξ) − py) z'(ξ) = 0`` from ``ξ = px``; converges in
    a few iterations for points near the curve (penetrations ≪ curvature radius).

    Returns ``(xi, g, n, t, kappa)``.
    """
    xi = px.copy()
    max_step = float(surface.wavelengths[0]) / 16.0
    for _ in range(iterations):
        z = surface.heights(xi + shift)
        dz = surface.slopes(xi + shift)
        d2z = surface.curvatures(xi + shift)
        f = (xi - px) + (z - py) * dz
        fp = 1.0 + dz * dz + (z - py) * d2z
        # Safeguards for points far below the curve: a positive-curvature floor and a
        # step limit of λ_min/16 keep the iteration on the local branch.
        step = np.clip(f / np.where(fp > 0.1, fp, 0.1), -max_step, max_step)
        xi = xi - step
        if np.all(np.abs(step) <= 1e-15 * max(1.0, float(np.max(np.abs(px), initial=1.0)))):
            break
    z = surface.heights(xi + shift)
    dz = surface.slopes(xi + shift)
    d2z = surface.curvatures(xi + shift)
    a = np.sqrt(1.0 + dz * dz)
    n = np.column_stack([-dz / a, 1.0 / a])
    t = np.column_stack([1.0 / a, dz / a])
    g = (px - xi) * n[:, 0] + (py - z) * n[:, 1]
    kappa = d2z / a**3
    return xi, g, n, t, kappa


def evaluate_contact(surface: SineSeries, shift: float, pos: np.ndarray, weight: np.ndarray,
                     penalty: float, smoothing: float = 0.0) -> ContactState:
    """Penalty forces and tangent at face nodes of current positions ``pos`` ``(n, 2)`` [mm].

    Parameters
    ----------
    surface
        Rigid surface ``z(x)``.
    shift
        Sliding distance ``s`` [mm]; the surface under the rubber is ``z(x + s)``.
    pos
        Current node positions.
    weight
        Reference tributary lengths ``w_k`` [mm].
    penalty
        ``ε`` [MPa/mm].
    smoothing
        Half-width ``δ`` [mm] of a C¹ rounding of the penalty kink: the normal force per
        unit length is ``ε φ(−g)`` with ``φ(x) = x`` for ``x ≥ δ``, ``(x + δ)²/(4δ)`` for
        ``|x| < δ`` and 0 below (0 gives the plain penalty). The contact force is exact
        for penetrations beyond ``δ``; it only softens the on/off switch that makes Newton
        cycle on the active set.
    """
    px, py = pos[:, 0], pos[:, 1]
    n_face = px.size
    gap = py - surface.heights(px + shift)  # vertical gap: > 0 means the node is above the graph
    normal = np.tile([0.0, 1.0], (n_face, 1))
    xi = px.copy()
    force = np.zeros((n_face, 2))
    stiff = np.zeros((n_face, 2, 2))
    d = float(smoothing)
    # normal gap >= vertical gap · cos θ >= vertical gap / sqrt(1 + max z'²): only nodes
    # below that bound can carry force
    slope_max = float(np.sum(surface.wavenumbers * surface.amplitudes))
    cand = np.flatnonzero(gap < d * np.sqrt(1.0 + slope_max**2))
    energy = 0.0
    if cand.size:
        xi_c, g_c, n_c, t_c, k_c = closest_point(surface, shift, px[cand], py[cand])
        gap[cand] = g_c
        normal[cand] = n_c
        xi[cand] = xi_c
        x = -g_c
        if d > 0:
            phi = np.where(x >= d, x, np.where(x > -d, (x + d) ** 2 / (4 * d), 0.0))
            dphi = np.where(x >= d, 1.0, np.where(x > -d, (x + d) / (2 * d), 0.0))
            ephi = np.where(x >= d, x**2 / 2 + d**2 / 6,
                            np.where(x > -d, (x + d) ** 3 / (12 * d), 0.0))
        else:
            phi = np.maximum(x, 0.0)
            dphi = (x > 0).astype(float)
            ephi = phi**2 / 2
        ew = penalty * weight[cand]
        force[cand] = (ew * phi)[:, None] * n_c
        curv = phi * k_c / (1.0 - g_c * k_c)
        stiff[cand] = ew[:, None, None] * (
            dphi[:, None, None] * n_c[:, :, None] * n_c[:, None, :]
            + curv[:, None, None] * t_c[:, :, None] * t_c[:, None, :])
        energy = float(np.sum(ew * ephi))
    return ContactState(gap=gap, active=gap < 0.0, force=force, normal=normal, xi=xi,
                        stiffness=stiff, energy=energy)


def segment_penetration(surface: SineSeries, shift: float, pos: np.ndarray, width: float,
                        samples: int = 7) -> float:
    """Deepest vertical penetration of the rigid surface between face nodes [mm].

    Contact is enforced at the nodes only; the face between two nodes is a straight
    segment. A surface whose curvature radius is not large against the element size can
    poke through a segment unseen by the nodal penalty, impale the rubber and lock the
    sliding (the friction then grows linearly with the travel, like a sheared block).
    This samples ``samples`` interior points of every segment of the periodic face
    ``pos`` ``(n, 2)`` and returns ``max(z(x + shift) − y, 0)``.
    """
    x0, y0 = pos[:, 0], pos[:, 1]
    x1 = np.append(x0[1:], x0[0] + width)
    y1 = np.roll(y0, -1)
    t = np.linspace(0.0, 1.0, samples + 2)[1:-1]
    xs = x0[:, None] + t * (x1 - x0)[:, None]
    ys = y0[:, None] + t * (y1 - y0)[:, None]
    return float(max(np.max(surface.heights(xs + shift) - ys), 0.0))


def contact_fraction(x: np.ndarray, gap: np.ndarray, width: float) -> float:
    """Fraction of the projected length in contact, gap interpolated linearly between nodes.

    ``x`` are the current abscissae of the periodic face nodes (in order), ``gap`` their
    gaps (negative = in contact); the segment from the last node to the first is closed
    with ``x[0] + width``.
    """
    x1 = np.append(x[1:], x[0] + width)
    g0, g1 = gap, np.roll(gap, -1)
    dx = x1 - x
    both = (g0 < 0) & (g1 < 0)
    one = (g0 < 0) != (g1 < 0)
    frac = np.where(both, 1.0, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        part = np.where(g0 < 0, g0 / (g0 - g1), g1 / (g1 - g0))
    frac = np.where(one, part, frac)
    return float(np.sum(frac * dx) / width)


def mean_separation(x: np.ndarray, y: np.ndarray, width: float) -> float:
    """``ū = (1/L0) ∫ y dx`` under the deformed periodic face polyline [mm] (trapezoid, exact)."""
    x1 = np.append(x[1:], x[0] + width)
    y1 = np.roll(y, -1)
    return float(np.sum(0.5 * (y + y1) * (x1 - x)) / width)
