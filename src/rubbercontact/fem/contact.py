"""Frictionless contact of the rubber's contact face with the analytic rigid surface.

The rigid surface is the graph ``y = z(x + s)`` of a :class:`SineSeries` shifted by
the sliding distance ``s`` (the surface moves in −x under the rubber, i.e. the
rubber slides in +x relative to it). Gap and normal are exact (closest-point
projection on the analytic curve, no faceting). Penalty energy
``Π_c = ∫ ε ⟨−g⟩²/2 dS`` over the reference face, integrated at points along every
face segment (the nodes and ``m − 1`` interior points per segment, see
:func:`evaluate_contact`), ``ε`` [MPa/mm] sized on the algorithmic modulus (see
:func:`penalty_parameter`).

Derivatives for a point ``p`` with closest point ``c(ξ) = (ξ, z)``, unit tangent
``t``, outward normal ``n = (−z', 1)/√(1+z'²)`` and signed curvature
``κ = z''/(1+z'²)^{3/2}``: ``∂g/∂p = n`` and ``∂n/∂p = −κ/(1 − gκ) t⊗t``, so the
point force is ``ε w min(g, 0) n`` and its exact tangent
``ε w [n⊗n − min(g, 0) κ/(1 − gκ) t⊗t]`` on active points; a point
``p = N_a x_a + N_b x_b`` of a segment passes ``N_i`` of its force to node ``i`` and
``N_i N_j`` of its tangent to the node pair ``(i, j)``.
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
    """Contact quantities of a periodic face of ``n`` nodes and ``n`` segments.

    Contact is sampled at ``m = points_per_segment`` points per segment (the segment's
    first node and ``m − 1`` interior points), ordered along the face.
    """

    gap: np.ndarray          # (n m,) signed normal gap where penetrating, vertical elsewhere [mm]
    active: np.ndarray       # (n m,) bool, g < reach: the point carries force
    point_x: np.ndarray      # (n m,) current abscissa of the contact points [mm]
    points_per_segment: int  # m
    force: np.ndarray        # (n, 2) nodal force of the surface ON the rubber [N/mm]
    stiffness: np.ndarray    # (n, 4, 4) per segment ∂(−force)/∂(a_x, a_y, b_x, b_y) [N/mm²]
    energy: float            # penalty (or barrier) energy [N·mm/mm]
    reach: float = 0.0       # gap [mm] below which a point carries force (barrier: d̂)


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


def _point_penalty(surface: SineSeries, shift: float, px: np.ndarray, py: np.ndarray,
                   weight: np.ndarray, penalty: float, smoothing: float):
    """Penalty ``(gap, force, stiffness, energy)`` at free points ``(px, py)``.

    ``force`` ``(k, 2)`` acts on the rubber, ``stiffness`` ``(k, 2, 2)`` is its negative
    derivative with respect to the point position (see the module docstring).
    """
    k = px.size
    gap = py - surface.heights(px + shift)  # vertical gap: > 0 means above the graph
    force = np.zeros((k, 2))
    stiff = np.zeros((k, 2, 2))
    d = float(smoothing)
    # normal gap >= vertical gap · cos θ >= vertical gap / sqrt(1 + max z'²): only points
    # below that bound can carry force
    slope_max = float(np.sum(surface.wavenumbers * surface.amplitudes))
    cand = np.flatnonzero(gap < d * np.sqrt(1.0 + slope_max**2))
    energy = 0.0
    if cand.size:
        _, g_c, n_c, t_c, k_c = closest_point(surface, shift, px[cand], py[cand])
        gap[cand] = g_c
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
    return gap, force, stiff, energy


def face_points(pos: np.ndarray, width: float, points_per_segment: int) -> np.ndarray:
    """The contact points ``(n m, 2)`` [mm] of the periodic face ``pos`` ``(n, 2)``: each
    segment's first node and ``m − 1`` interior points (linear in the node positions)."""
    m = int(points_per_segment)
    b = np.vstack([pos[1:], pos[:1] + [width, 0.0]])
    t = (np.arange(m) / m)[None, :, None]
    return (pos[:, None, :] + t * (b - pos)[:, None, :]).reshape(-1, 2)


def evaluate_contact(surface: SineSeries, shift: float, pos: np.ndarray, width: float,
                     segment_length: np.ndarray, penalty: float, points_per_segment: int = 4,
                     smoothing: float = 0.0, barrier=None) -> ContactState:
    """Penalty forces and tangent of the periodic rubber face ``pos`` ``(n, 2)`` [mm].

    The face is the closed polyline of its nodes (segment ``k`` joins node ``k`` to node
    ``k + 1``, the last one to node 0 shifted by ``width``). The penalty energy
    ``∫ ε ⟨−g⟩²/2 dS`` over the reference face is integrated with the composite
    trapezoidal rule on ``m = points_per_segment`` sub-intervals per segment: the points
    are the segment's first node and ``m − 1`` interior points, each carrying
    ``1/m`` of the reference length. ``m = 1`` is plain node-to-surface contact, which
    lets an asperity sharper than the element pass between two nodes unseen and impale
    the face (see :func:`segment_penetration`); interior points push such a segment
    out, their forces shared by the two end nodes with the linear shape functions.

    Parameters
    ----------
    surface
        Rigid surface ``z(x)``.
    shift
        Sliding distance ``s`` [mm]; the surface under the rubber is ``z(x + s)``.
    pos
        Current face node positions, in order along the face.
    width
        Period of the face ``L0`` [mm].
    segment_length
        Reference length of each segment ``(n,)`` [mm].
    penalty
        ``ε`` [MPa/mm].
    points_per_segment
        ``m`` >= 1.
    smoothing
        Half-width ``δ`` [mm] of a C¹ rounding of the penalty kink: the normal force per
        unit length is ``ε φ(−g)`` with ``φ(x) = x`` for ``x ≥ δ``, ``(x + δ)²/(4δ)`` for
        ``|x| < δ`` and 0 below (0 gives the plain penalty). The contact force is exact
        for penetrations beyond ``δ``; it only softens the on/off switch that makes Newton
        cycle on the active set.
    barrier
        A :class:`~.barrier.BarrierLaw`: the barrier replaces the penalty (``penalty``
        and ``smoothing`` unused); its points within ``d̂`` of the surface are active.
    """
    m = int(points_per_segment)
    n = pos.shape[0]
    t = np.arange(m) / m
    pts = face_points(pos, width, m)
    px, py = pts[:, 0], pts[:, 1]
    seg = np.asarray(segment_length, dtype=float)
    w = np.tile(seg[:, None] / m, (1, m))
    # the node's own point stands for half of each adjacent sub-interval
    w[:, 0] = 0.5 * (seg + np.roll(seg, 1)) / m
    if barrier is None:
        gap, f, k, energy = _point_penalty(surface, shift, px, py, w.ravel(), penalty,
                                           smoothing)
        reach = 0.0
    else:
        gap, f, k, energy = barrier.points(surface, shift, px, py, w.ravel())
        reach = barrier.dhat
    shape = np.column_stack([1.0 - t, t])                        # (m, 2): N_a, N_b
    f = f.reshape(n, m, 2)
    force = np.einsum("qi,kqa->kia", shape, f)                   # (n, 2 ends, 2)
    nodal = force[:, 0] + np.roll(force[:, 1], 1, axis=0)
    stiff = np.einsum("qi,qj,kqab->kiajb", shape, shape, k.reshape(n, m, 2, 2))
    return ContactState(gap=gap, active=gap < reach, point_x=px, points_per_segment=m,
                        force=nodal, stiffness=stiff.reshape(n, 4, 4), energy=energy,
                        reach=reach)


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


def face_contact_fraction(surface: SineSeries, shift: float, cs: ContactState,
                          width: float) -> float:
    """Contact fraction of the face from its contact points (see :func:`contact_fraction`).

    A straight segment on a curved surface is off it by up to its chord sag
    ``Δx² |z''| / 8`` (nodes or interior points lift off by that much, whichever side
    is convex); smaller gaps are below the resolution of the face and count as contact,
    as do the gaps within the barrier's reach (``cs.reach``), where points carry force.
    Evaluated once per converged step, not in the Newton iterations.
    """
    m = cs.points_per_segment
    x = cs.point_x
    dx = np.diff(np.append(x[::m], x[0] + width))            # segment projections
    sag = np.repeat(dx, m) ** 2 * np.abs(surface.curvatures(x + shift)) / 8.0
    return contact_fraction(x, cs.gap - cs.reach - sag, width)


def contact_fraction(x: np.ndarray, gap: np.ndarray, width: float) -> float:
    """Share of the period covered by the face's contact, gap interpolated linearly.

    The contact set is the set of abscissae, modulo the period, over which some part of
    the face is in contact; its length over ``width`` is the contact fraction, in
    ``[0, 1]`` by construction. On a face that runs forward in x this is the projected
    length in contact.

    Parameters
    ----------
    x
        Current abscissae of the points of the periodic face, in order along it ``(k,)``
        [mm]; the face is closed from the last point to ``x[0] + width``.
    gap
        Their gaps ``(k,)`` [mm], negative = in contact; between two points the gap is
        interpolated linearly.
    width
        Period of the face ``L0`` [mm].

    Returns
    -------
    float
        Contact fraction [-].

    Notes
    -----
    A face folded back over itself (sub-segments that run in −x, as on an impaled or
    inverted face) covers some abscissae two or three times. A signed sum of the contact
    projections ``Σ frac Δx`` then counts the forward layers' contact twice where the
    backward layer between them is off the surface (above 1 when that layer is off over
    more than the forward layers leave out), and subtracts a backward layer in contact:
    it is the projected length only of a face without folds. The union counts every
    abscissa once, whatever the face does.
    """
    x = np.asarray(x, dtype=float)
    gap = np.asarray(gap, dtype=float)
    if x.size == 0:
        return 0.0
    # Abscissae from the first point, the closing point at exactly ``width``: an unfolded
    # face's contact intervals then lie in [0, width], so full contact tiles it exactly.
    u = np.append(x - x[0], width)
    g = np.append(gap, gap[0])
    u0, u1, g0, g1 = u[:-1], u[1:], g[:-1], g[1:]
    c0, c1 = g0 < 0, g1 < 0
    touch = c0 | c1
    if not np.any(touch):
        return 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        t = g0 / (g0 - g1)      # zero of the gap; in [0, 1] where exactly one end touches
    cross = u0 + t * (u1 - u0)
    a = np.where(c0, u0, cross)[touch]
    b = np.where(c1, u1, cross)[touch]
    return _covered_share(np.minimum(a, b), np.maximum(a, b), width)


def _covered_share(lo: np.ndarray, hi: np.ndarray, width: float) -> float:
    """Length of the union of the intervals ``[lo, hi]`` [mm] modulo ``width`` [mm], over
    ``width`` [-]."""
    if np.any(hi - lo >= width):
        return 1.0
    # onto [0, width); an interval that then reaches past ``width`` is split at the seam
    k = np.floor(lo / width) * width      # 0 (exactly) for the intervals already inside
    lo, hi = lo - k, hi - k
    over = hi > width
    starts = np.concatenate([lo, np.zeros(np.count_nonzero(over))])
    ends = np.concatenate([np.minimum(hi, width), hi[over] - width])
    order = np.argsort(starts, kind="stable")
    starts, ends = starts[order], ends[order]
    reach = np.maximum.accumulate(ends)
    # The uncovered length is a sum of non-negative holes, so the share is <= 1 exactly
    # (and exactly 1 when intervals sharing their end points tile the period).
    holes = (starts[0] + np.sum(np.maximum(starts[1:] - reach[:-1], 0.0))
             + (width - reach[-1]))
    # the floor only catches rounding of holes that sum to the whole period
    return float(max(1.0 - holes / width, 0.0))


def mean_separation(x: np.ndarray, y: np.ndarray, width: float) -> float:
    """``ū = (1/L0) ∫ y dx`` under the deformed periodic face polyline [mm] (trapezoid, exact)."""
    x1 = np.append(x[1:], x[0] + width)
    y1 = np.roll(y, -1)
    return float(np.sum(0.5 * (y + y1) * (x1 - x)) / width)
