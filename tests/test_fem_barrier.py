"""Barrier contact (rubbercontact.fem.barrier): the barrier function's closed form and
smoothness, its forces and tangent against finite differences, and the step filter that
never lets a contact point cross the surface."""

import numpy as np
import pytest
from test_fem_contact import _global_stiffness  # the same assembly of segment stiffnesses

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.fem.barrier import (
    BarrierLaw,
    barrier_derivatives,
    barrier_law,
    feasible_step,
)
from rubbercontact.fem.contact import closest_point, evaluate_contact, face_points
from rubbercontact.fem.options import FemOptions


def test_barrier_is_c2_at_its_reach_and_its_derivatives_are_exact():
    dhat = 0.3
    g = np.array([dhat, dhat * (1 - 1e-7), 1.5 * dhat])
    b, db, d2b = barrier_derivatives(g, dhat)
    # b, b', b'' all vanish at d̂ (C²); O(δ²), O(δ), O(δ) just inside
    assert np.all(np.abs(b) < 1e-12) and np.all(np.abs(db) < 1e-7)
    assert np.all(np.abs(d2b) < 1e-6)
    # central differences of b and b' (step 1e-6 d̂: truncation ~1e-12 relative)
    x = np.linspace(0.01, 0.99, 25) * dhat
    h = 1e-6 * dhat
    bp, dbp, _ = barrier_derivatives(x + h, dhat)
    bm, dbm, _ = barrier_derivatives(x - h, dhat)
    _, db, d2b = barrier_derivatives(x, dhat)
    np.testing.assert_allclose((bp - bm) / (2 * h), db, rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose((dbp - dbm) / (2 * h), d2b, rtol=1e-6, atol=1e-9)
    # the force grows without bound toward contact: −b'(g) → d̂²/g
    _, db0, _ = barrier_derivatives(np.array([1e-9 * dhat]), dhat)
    assert -db0[0] == pytest.approx(dhat / 1e-9, rel=1e-6)


def test_barrier_law_puts_the_gap_at_a_tenth_of_its_reach_under_the_reference_pressure():
    law = barrier_law(scale=0.02, reference_pressure=2.0, distance=0.1, stiffness=1.0)
    assert law.dhat == pytest.approx(2e-3)
    _, db, _ = barrier_derivatives(np.array([law.dhat / 10]), law.dhat)
    assert -law.kappa * db[0] == pytest.approx(2.0, rel=1e-12)


@pytest.mark.parametrize("points", [1, 4])
def test_barrier_tangent_matches_finite_differences(points):
    # A face just above the steep high-slope wave, most points within the reach: the
    # stiffness (Hessian of the barrier energy, curvature term included) is the negative
    # derivative of the force. Step 1e-9 mm against gaps >= 2e-4 mm: truncation ~1e-10.
    surf = rc.roughness.high_slope_wave()
    rng = np.random.default_rng(1)
    n = 40
    shift = 0.01
    law = BarrierLaw(dhat=2e-3, kappa=1e3)
    x = np.sort(rng.uniform(0, surf.period, n))
    y = surf.heights(x + shift)
    pos = np.column_stack([x, y])
    # lift every contact point at least 2e-4 mm above the graph (normal gap)
    for _ in range(50):
        pts = face_points(pos, surf.period, points)
        _, g, _, _, _ = closest_point(surf, shift, pts[:, 0], pts[:, 1])
        low = g.reshape(n, points).min(axis=1)
        if np.all(low >= 2e-4):
            break
        pos[:, 1] += np.where(low < 2e-4, 2e-4 - low + rng.uniform(0, 1e-3, n), 0.0)
    seg = np.full(n, surf.period / n)
    cs = evaluate_contact(surf, shift, pos, surf.period, seg, 0.0, points, barrier=law)
    assert np.count_nonzero(cs.active) >= n // 2 and np.all(cs.gap > 0)
    K = _global_stiffness(cs, n)
    h = 1e-9
    num = np.zeros_like(K)
    for j in range(2 * n):
        d = np.zeros(2 * n)
        d[j] = h
        fp = evaluate_contact(surf, shift, pos + d.reshape(n, 2), surf.period, seg, 0.0,
                              points, barrier=law).force.ravel()
        fm = evaluate_contact(surf, shift, pos - d.reshape(n, 2), surf.period, seg, 0.0,
                              points, barrier=law).force.ravel()
        num[:, j] = -(fp - fm) / (2 * h)
    np.testing.assert_allclose(num, K, atol=1e-5 * np.abs(K).max())
    np.testing.assert_allclose(K, K.T, atol=1e-10 * np.abs(K).max())


def test_a_point_on_or_below_the_surface_is_inadmissible():
    surf = rc.roughness.SineSeries([1.0], [0.05])
    law = BarrierLaw(dhat=1e-3, kappa=10.0)
    x = np.linspace(0, 1, 8, endpoint=False)
    pos = np.column_stack([x, surf.heights(x) + 5e-4])
    pos[3, 1] -= 1e-3
    cs = evaluate_contact(surf, 0.0, pos, 1.0, np.full(8, 1 / 8), 0.0, 1, barrier=law)
    assert not np.all(np.isfinite(cs.force)) and cs.energy == np.inf


def test_feasible_step_never_lets_a_point_cross_the_surface():
    # Points above a steep sine, each moved along a random direction that crosses the
    # graph within the step: the step found keeps every point strictly above the graph all
    # the way (checked on 2000 sub-steps), and is within 10 % of the first crossing (the
    # advancement's safety factor 0.9 and its stopping rule).
    surf = rc.roughness.SineSeries([0.25], [0.1])
    rng = np.random.default_rng(7)
    for _ in range(20):
        k = 30
        x = rng.uniform(0, 0.25, k)
        p0 = np.column_stack([x, surf.heights(x) + rng.uniform(1e-3, 0.05, k)])
        dp = rng.normal(0, 0.1, (k, 2))
        dp[:, 1] -= 0.15
        t = feasible_step(surf, 0.0, p0, dp)
        tau = np.linspace(0, 1, 2001)[:, None, None]
        path = p0 + tau * dp
        below = path[..., 1] - surf.heights(path[..., 0]) <= 0
        first = np.flatnonzero(below.any(axis=1))
        crossing = tau[first[0], 0, 0] if first.size else np.inf
        assert t < crossing
        assert t >= 0.9 * min(crossing - 1e-3, 1.0) - 0.1
        ok = tau[:, 0, 0] <= t
        assert not below[ok].any()


def test_feasible_step_is_one_for_a_move_away_from_the_surface():
    surf = rc.roughness.SineSeries([0.25], [0.1])
    x = np.linspace(0, 0.25, 10)
    p0 = np.column_stack([x, surf.heights(x) + 1e-3])
    assert feasible_step(surf, 0.0, p0, np.tile([0.0, 0.5], (10, 1))) == 1.0


@pytest.mark.parametrize("kw, field", [({"contact": "glue"}, "contact"),
                                       ({"barrier_distance": 0.7}, "barrier_distance"),
                                       ({"barrier_distance": 0.0}, "barrier_distance"),
                                       ({"barrier_stiffness": -1.0}, "barrier_stiffness")])
def test_bad_barrier_options_name_the_field(kw, field):
    with pytest.raises(InputError, match=field):
        FemOptions(**kw)


@pytest.mark.parametrize("gauge", ["face", "top"])
def test_steady_cell_jacobian_with_the_barrier_matches_central_differences(gauge):
    # The steady cell's exact Jacobian (sparse part with the barrier's tangent + FFT
    # memory) against central differences of its residual at the face just touching the
    # crest (the crest's points inside the reach), slightly perturbed. The step moves no
    # point by more than 1e-3 of the smallest gap, so the difference stays on the smooth
    # barrier; O(ε²) truncation and round-off give ~1e-7: tolerance 1e-5.
    from rubbercontact.fem.setup import build_cell
    from rubbercontact.fem.steady import SteadyCell
    from rubbercontact.fem.streamline import streamline_kernel

    mesh = (16, 8)
    setup = build_cell(rc.roughness.high_slope_wave(), rc.materials.sbr(), 1.0, 10.0,
                       FemOptions(mesh=mesh, contact="barrier", barrier_distance=0.4),
                       sliding_plate=True)
    cell = SteadyCell(setup.model, streamline_kernel(setup.params, setup.dt, mesh[0]))
    rng = np.random.default_rng(0)
    dhat = setup.model.barrier.dhat
    U = 1e-3 * dhat * rng.standard_normal(setup.model.n)
    ev = cell.evaluate(U, 0.0, setup.load, gauge)
    assert np.any(ev.contact.active) and np.all(ev.contact.gap > 0)
    eps = 1e-3 * float(ev.contact.gap.min())
    for _ in range(3):
        v = rng.standard_normal(U.size)
        v /= np.abs(v).max()
        fd = (cell.evaluate(U + eps * v, 0.0, setup.load, gauge).r
              - cell.evaluate(U - eps * v, 0.0, setup.load, gauge).r) / (2 * eps)
        assert np.linalg.norm(cell.jvp(ev, v) - fd) <= 1e-5 * np.linalg.norm(fd)
