"""FEM contact, static indentation and the Newton solver.

References: exact closest-point geometry of a sine, Westergaard's elastic
solution for a sinusoid (plane strain, E_r = 4E/3 for ν = 1/2), global equilibrium
and Newton's quadratic convergence.
"""

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.fem.cell import CellModel
from rubbercontact.fem.constitutive import MaterialParameters
from rubbercontact.fem.contact import closest_point, contact_fraction, evaluate_contact
from rubbercontact.fem.mesh import periodic_cell
from rubbercontact.fem.solver import SolverCounters, newton


def test_closest_point_is_orthogonal_projection():
    surf = rc.roughness.SineSeries([1.0, 0.5], [0.1, 0.04], [0.3, 1.0])
    rng = np.random.default_rng(0)
    xi0 = rng.uniform(0, 1, 50)
    shift = 0.37
    # points at a known signed distance d along the exact normal of the curve
    z = surf.heights(xi0 + shift)
    dz = surf.slopes(xi0 + shift)
    a = np.sqrt(1 + dz**2)
    d = rng.uniform(-0.01, 0.01, 50)
    px, py = xi0 - d * dz / a, z + d / a
    xi, g, n, t, kappa = closest_point(surf, shift, px, py)
    np.testing.assert_allclose(xi, xi0, atol=1e-12)
    np.testing.assert_allclose(g, d, atol=1e-12)
    np.testing.assert_allclose(np.einsum("ij,ij->i", n, t), 0, atol=1e-14)


def _global_stiffness(cs, n):
    K = np.zeros((2 * n, 2 * n))
    for k in range(n):
        d = np.array([2 * k, 2 * k + 1, 2 * ((k + 1) % n), 2 * ((k + 1) % n) + 1])
        K[np.ix_(d, d)] += cs.stiffness[k]
    return K


@pytest.mark.parametrize("points", [1, 4])
def test_contact_tangent_matches_finite_differences(points):
    surf = rc.roughness.high_slope_wave()
    rng = np.random.default_rng(1)
    n = 40
    x = np.sort(rng.uniform(0, surf.period, n))
    pos = np.column_stack([x, surf.heights(x + 0.01) + rng.uniform(-2e-3, 1e-3, n)])
    seg = np.full(n, surf.period / n)
    eps = 1e5
    cs = evaluate_contact(surf, 0.01, pos, surf.period, seg, eps, points)
    K = _global_stiffness(cs, n)
    h = 1e-9
    num = np.zeros_like(K)
    for j in range(2 * n):
        d = np.zeros(2 * n)
        d[j] = h
        fp = evaluate_contact(surf, 0.01, pos + d.reshape(n, 2), surf.period, seg, eps,
                              points).force.ravel()
        fm = evaluate_contact(surf, 0.01, pos - d.reshape(n, 2), surf.period, seg, eps,
                              points).force.ravel()
        num[:, j] = -(fp - fm) / (2 * h)   # stiffness = -∂(force on rubber)/∂p
    np.testing.assert_allclose(num, K, atol=1e-5 * np.abs(K).max())


def test_segment_points_catch_a_crest_between_nodes():
    # A flat face y = D/2 whose two nodes sit over the zeros of z = D sin(qx): the nodes
    # are above the surface, so node-to-surface contact sees nothing, while the crest
    # passes D/2 through the face between them.
    lam, amp = 0.0625, 0.001          # max slope qD = 0.1: normal ≈ vertical gap (0.5 %)
    s = rc.roughness.SineSeries([lam], [amp], [0.0])
    pos = np.array([[0.0, 0.5 * amp], [lam / 2, 0.5 * amp]])
    seg = np.array([lam / 2, lam / 2])
    eps = 1e4
    nodal = evaluate_contact(s, 0.0, pos, lam, seg, eps, 1)
    assert np.all(nodal.force == 0.0)
    # 32 points per segment: the trapezoidal rule of ε ∫ ⟨z − y⟩ dx over the crest pushes
    # the face up (tolerance 3 %: slope 0.1 and the sampling of the contact edges), split
    # equally between the two nodes by symmetry, with no net horizontal force.
    seg_c = evaluate_contact(s, 0.0, pos, lam, seg, eps, 32)
    fy = seg_c.force[:, 1]
    assert fy[0] == pytest.approx(fy[1], rel=1e-9) and fy[0] > 0
    x = np.linspace(0, lam / 2, 20001)
    exact = eps * np.trapezoid(np.maximum(s.heights(x) - 0.5 * amp, 0.0), x)
    assert fy.sum() == pytest.approx(exact, rel=0.03)
    assert seg_c.force[:, 0].sum() == pytest.approx(0.0, abs=1e-9 * fy.sum())
    # contact fraction from the points: the crest is in contact where sin(qx) > 1/2,
    # qx in (π/6, 5π/6), i.e. over 1/3 of the period (one point spacing, 1/64)
    from rubbercontact.fem.contact import contact_fraction
    assert contact_fraction(seg_c.point_x, seg_c.gap, lam) == pytest.approx(1 / 3, abs=1 / 64)


def test_contact_fraction_interpolates_edges():
    x = np.arange(10) * 0.1
    gap = np.array([1, 1, -1, -1, -1, 1, 1, 1, 1, 1], float)
    # two half segments + two full segments = 0.3 of the length 1.0
    assert contact_fraction(x, gap, 1.0) == pytest.approx(0.3)


# A face folded over itself (Z-fold, as on an impaled or inverted face): it runs forward
# 0 -> 0.7, back 0.7 -> 0.3 lifted off the surface in the middle (gap +1 at x = 0.5),
# forward again 0.3 -> 0.95. Linear gaps: contact over [0, 0.7] ∪ [0.6, 0.7] ∪ [0.3, 0.4]
# ∪ [0.3, 0.925] ∪ [0.975, 1] = [0, 0.925] ∪ [0.975, 1], a share of 0.95 of the period.
_FOLD_X = np.array([0.0, 0.7, 0.5, 0.3, 0.9, 0.95])
_FOLD_GAP = np.array([-1.0, -1.0, 1.0, -1.0, -1.0, 1.0])


def test_contact_fraction_counts_a_folded_face_once():
    x, gap = _FOLD_X, _FOLD_GAP
    # the former count, the signed sum of the projections in contact, counted [0.3, 0.7]
    # twice (both forward layers) and gave 1.15 > 1
    x1 = np.append(x[1:], x[0] + 1.0)
    g1 = np.roll(gap, -1)
    with np.errstate(divide="ignore", invalid="ignore"):
        part = np.where(gap < 0, gap / (gap - g1), g1 / (g1 - gap))
    frac = np.where((gap < 0) & (g1 < 0), 1.0, np.where((gap < 0) != (g1 < 0), part, 0.0))
    assert np.sum(frac * (x1 - x)) == pytest.approx(1.15)
    assert contact_fraction(x, gap, 1.0) == pytest.approx(0.95, abs=1e-12)


@pytest.mark.parametrize("start", [0, 2, 3, 5])
@pytest.mark.parametrize("offset", [0.0, 0.37, -2.6])
def test_contact_fraction_of_a_fold_across_the_period_seam(start, offset):
    # the same face listed from another point, moved by whole and partial periods: the
    # fold now straddles the seam x[0] + width and the count wraps it onto the period
    x = np.concatenate([_FOLD_X[start:], _FOLD_X[:start] + 1.0]) + offset
    gap = np.roll(_FOLD_GAP, -start)
    assert contact_fraction(x, gap, 1.0) == pytest.approx(0.95, abs=1e-12)


@pytest.mark.parametrize("x", [np.arange(10) * 0.1 + 0.123, _FOLD_X, _FOLD_X[::-1] - 3.0])
def test_contact_fraction_of_full_and_no_contact(x):
    # exactly 1 and 0, also for a folded face and one listed backwards
    assert contact_fraction(x, -np.ones(x.size), 1.0) == 1.0
    assert contact_fraction(x, np.ones(x.size), 1.0) == 0.0
    assert contact_fraction(x, np.zeros(x.size), 1.0) == 0.0   # touching is g < 0


def test_face_contact_fraction_of_a_folded_face():
    # The fold as a face of nodes on a (nearly) flat surface, through evaluate_contact's
    # contact points and the chord-sag tolerance: the node heights ±0.1 give the same
    # crossings as the gaps ±1 above, and the share 0.95.
    from rubbercontact.fem.contact import face_contact_fraction

    surf = rc.roughness.SineSeries([1.0], [1e-9], [0.0])
    pos = np.column_stack([_FOLD_X, 0.1 * _FOLD_GAP])
    seg = np.full(pos.shape[0], 1.0 / pos.shape[0])
    for points in (1, 4):
        cs = evaluate_contact(surf, 0.0, pos, 1.0, seg, 1e3, points)
        assert face_contact_fraction(surf, 0.0, cs, 1.0) == pytest.approx(0.95, abs=1e-6)
    flat = np.column_stack([np.arange(8) / 8, np.full(8, -0.1)])
    cs = evaluate_contact(surf, 0.0, flat, 1.0, np.full(8, 1 / 8), 1e3, 4)
    assert face_contact_fraction(surf, 0.0, cs, 1.0) == 1.0
    cs = evaluate_contact(surf, 0.0, flat + [0.0, 0.2], 1.0, np.full(8, 1 / 8), 1e3, 4)
    assert face_contact_fraction(surf, 0.0, cs, 1.0) == 0.0


def _small_cell(surface, material, nx=24, ny=18, dt=1e-4):
    L0 = surface.period
    y0 = float(surface.heights(np.arange(nx) * L0 / nx).max()) - 1e-3 * L0 / nx
    cell = periodic_cell(L0, 0.75 * L0, nx, ny, y0=y0)
    par = MaterialParameters.from_material(material)
    return CellModel(cell, surface, par, 100 * 3 * par.algorithmic_shear_modulus(dt) * nx / L0)


def test_cell_tangent_with_contact_matches_finite_differences():
    surf = rc.roughness.SineSeries([1.0], [0.05])
    model = _small_cell(surf, rc.materials.sbr(), nx=12, ny=6)
    rng = np.random.default_rng(4)
    st = model.new_state()
    U = 1e-3 * rng.standard_normal(model.n)
    U[model.plate] = -0.02           # several face nodes penetrate
    U[model.by] -= 0.03
    r, K, ev = model.evaluate(U, st, 1e-4, 0.1, 0.3)
    assert ev.contact.active.sum() >= 3
    K = K.toarray()
    h = 1e-8
    cols = np.concatenate([model.bx[:4], model.by[:4], [model.plate], [5, 17]])
    for j in cols:
        e = np.zeros(model.n)
        e[j] = h
        num = (model.evaluate(U + e, st, 1e-4, 0.1, 0.3, False)[0]
               - model.evaluate(U - e, st, 1e-4, 0.1, 0.3, False)[0]) / (2 * h)
        np.testing.assert_allclose(num, K[:, j], atol=1e-5 * np.abs(K).max())
    np.testing.assert_allclose(K, K.T, atol=1e-10 * np.abs(K).max())


def test_newton_converges_quadratically():
    # Static elastic indentation; the residual ratios r_{k+1}/r_k² stay bounded in the
    # last iterations (quadratic convergence with the consistent tangent).
    surf = rc.roughness.SineSeries([1.0], [0.02])
    model = _small_cell(surf, rc.materials.GeneralizedMaxwell.elastic(4.0))
    st = model.new_state()
    load = 0.2 * surf.period
    counters = SolverCounters()

    def res(U, tangent):
        return model.evaluate(U, st, 1.0, 0.0, load, tangent)

    U = np.zeros(model.n)
    for frac in np.linspace(0.125, 1.0, 8):   # press in increments, as the protocol does
        U, _, _ = newton(lambda V, tangent, f=frac: model.evaluate(V, st, 1.0, 0.0, f * load,
                                                                     tangent),
                         U, atol=1e-10 * load, max_iter=60)
    # restart from a perturbed converged state: active set unchanged, pure Newton
    U0 = U + 1e-5 * np.random.default_rng(5).standard_normal(model.n)
    _, _, hist = newton(res, U0, atol=1e-11 * load, counters=counters)
    hist = np.array(hist)
    print("residual norms", hist)
    print("ratios r_k+1/r_k", hist[1:] / hist[:-1])
    assert len(hist) <= 6
    # quadratic: log r_{k+1} ≈ 2 log r_k (relative to the first residual)
    rel = hist / hist[0]
    k = np.flatnonzero(rel[1:] < 1e-2)[0] + 1   # first iterate in the asymptotic range
    if k + 1 < len(rel):
        assert rel[k + 1] <= 10 * rel[k] ** 2 * 1e2 or rel[k + 1] < 1e-11


def test_westergaard_elastic_indentation():
    # Elastic sine (m2 = 0.044, small slope) pressed to p̄ = 0.3 p_full:
    # Westergaard p̄/p_full = sin²(πa/λ), p(0) = 2 p̄ / sin(πa/λ).
    E = 4.0
    lam, amp = 1.0, 0.01
    surf = rc.roughness.SineSeries([lam], [amp], [np.pi / 2])   # peak at x = 0
    p_full = np.pi * (4 * E / 3) * amp / lam
    pbar = 0.3 * p_full
    out = rc.fem.sliding_test(surf, rc.materials.GeneralizedMaxwell.elastic(E), pbar, 0.0,
                              mesh=(40, 30))
    a = lam / np.pi * np.arcsin(np.sqrt(pbar / p_full))
    # contact edges are resolved to about one element each: 2 h/λ = 0.05
    assert out.contact_fraction == pytest.approx(2 * a / lam, abs=0.05)
    prof = out.pressure_profile
    # global equilibrium: contact force balances the plate load (penalty forces are exact)
    dx = np.gradient(prof.x)
    assert np.sum(prof.pressure * dx) / lam == pytest.approx(pbar, rel=0.02)
    # peak pressure vs Westergaard within 5 % (P1 resolution of a smooth profile)
    xs = np.mod(prof.x + lam / 2, lam) - lam / 2
    p0 = prof.pressure[np.argmin(np.abs(xs))]
    assert p0 == pytest.approx(2 * pbar / np.sin(np.pi * a / lam), rel=0.05)
    # pressure shape inside the contact vs Westergaard's
    # p(x) = 2 p̄ cos(πx/λ) sqrt(sin²(πa/λ) − sin²(πx/λ)) / sin²(πa/λ)
    inner = np.abs(xs) < 0.7 * a
    ref = (2 * pbar * np.cos(np.pi * xs[inner] / lam)
           * np.sqrt(np.sin(np.pi * a / lam) ** 2 - np.sin(np.pi * xs[inner] / lam) ** 2)
           / np.sin(np.pi * a / lam) ** 2)
    np.testing.assert_allclose(prof.pressure[inner], ref, rtol=0.08)
    # no checkerboard: the node-to-node alternating part of the pressure is small
    p = prof.pressure[inner][np.argsort(xs[inner])]
    alt = p[1:-1] - 0.5 * (p[:-2] + p[2:])
    assert np.max(np.abs(alt)) < 0.02 * p.max()
    assert out.friction == pytest.approx(0.0, abs=1e-10)   # static and symmetric
    # penalty ε = 100 E/h: penetration ≈ p_max h/(100 E) ≈ 1.1e-5 mm, plus, at the
    # interior contact points of a straight segment on the convex crest, up to its chord
    # sag h² q² D / 8 ≈ 3.1e-5 mm; together below 0.5 % of the amplitude
    h = lam / 40
    sag = h**2 * (2 * np.pi / lam) ** 2 * amp / 8
    assert out.stats.max_penetration < 1.2 * prof.pressure.max() * h / (100 * E) + sag
    assert out.stats.max_penetration < 5e-3 * amp
    # nothing passed through the face: the result says its numbers stand
    assert out.stats.as_dict()["impaled"] is False


@pytest.mark.parametrize("nx", [50, 100])
@pytest.mark.parametrize("offset", [0.0, 0.25, 0.5])
@pytest.mark.parametrize("points", [2, 4])
def test_small_contact_area_within_one_element_of_westergaard(nx, offset, points):
    # A small contact (2a/λ = 0.04, h/a = 1 and 0.5): each edge falls anywhere inside an
    # element, and the gap is interpolated linearly between contact points, so the
    # contact fraction is resolved to half an element per edge: |A − A_W| <= h/λ.
    # The offsets move the sine against the nodes (0, 1/4, 1/2 element).
    E, lam, amp, frac = 4.0, 1.0, 0.01, 0.04
    h = lam / nx
    surf = rc.roughness.SineSeries([lam], [amp], [np.pi / 2 + 2 * np.pi * offset * h / lam])
    p_full = np.pi * (4 * E / 3) * amp / lam
    pbar = p_full * np.sin(np.pi * frac / 2) ** 2
    out = rc.fem.sliding_test(surf, rc.materials.GeneralizedMaxwell.elastic(E), pbar, 0.0,
                              mesh=(nx, 45), grading=4.0, contact_points=points)
    assert abs(out.contact_fraction - frac) <= h / lam


def _bad(**kw):
    args = dict(surface=rc.roughness.high_slope_wave(), material=rc.materials.sbr(),
                mean_pressure=1.0, velocity=10.0, mesh=(30, 23))
    args.update(kw)
    return args


@pytest.mark.parametrize("kw, field", [
    ({"mean_pressure": -1.0}, "mean_pressure"),
    ({"mean_pressure": 0.0}, "mean_pressure"),
    ({"velocity": -1.0}, "velocity"),
    ({"surface": rc.roughness.SineSeries([], [])}, "surface"),
    ({"surface": "sine"}, "surface"),
    ({"material": 4.17}, "material"),
    ({"mesh": (6, 5)}, "mesh"),
    ({"mesh": (30,)}, "mesh"),
    ({"mesh": (30.5, 20)}, "mesh"),
    ({"height_ratio": 0.0}, "height_ratio"),
    ({"periods": 0}, "periods"),
    ({"steps_per_period": 2}, "steps_per_period"),
])
def test_bad_input_names_the_field(kw, field):
    with pytest.raises(InputError, match=field):
        rc.fem.sliding_test(**_bad(**kw))


def test_mesh_too_coarse_for_shortest_wavelength():
    surf = rc.roughness.SineSeries([1.0, 0.0625], [0.1, 0.005])
    with pytest.raises(InputError, match="elements per shortest wavelength"):
        rc.fem.sliding_test(surf, rc.materials.sbr(), 1.0, 1.0, mesh=(64, 48))


def test_convergence_error_carries_diagnostics_and_last_state():
    from rubbercontact.errors import ConvergenceError

    with pytest.raises(ConvergenceError) as info:
        rc.fem.sliding_test(rc.roughness.high_slope_wave(), rc.materials.sbr(), 1.0, 10.0,
                            mesh=(16, 12), max_newton=1, max_cutbacks=1, solver="transient")
    err = info.value
    for key in ("step", "time", "residual_history", "cutbacks"):
        assert key in err.diagnostics
    assert err.diagnostics["cutbacks"] >= 1
    assert "U" in err.last_state and "history" in err.last_state


def test_segment_penetration_closed_forms():
    # A flat face y = 0 with nodes at the zeros of z = D sin(qx): the segment spans the
    # whole crest, so the penetration is the amplitude D exactly (t = 1/2 is sampled).
    from rubbercontact.fem.contact import segment_penetration

    lam, amp = 0.0625, 0.01
    s = rc.roughness.SineSeries([lam], [amp], [0.0])
    pos = np.array([[0.0, 0.0], [lam / 2, 0.0]])
    assert segment_penetration(s, 0.0, pos, lam) == pytest.approx(amp, rel=1e-12)
    # A face lying on the surface itself misses it only by the chord sag h^2/(8R) at the
    # crest, R = 1/(q^2 D); the samples at t = k/8 see at most that (tolerance 1 %).
    n = 64
    x = np.arange(n) * lam / n
    pos = np.column_stack([x, s.heights(x)])
    sag = (lam / n) ** 2 * (2 * np.pi / lam) ** 2 * amp / 8
    assert 0.0 < segment_penetration(s, 0.0, pos, lam) <= 1.01 * sag
    # a face above the surface: no penetration
    pos[:, 1] += 2 * amp
    assert segment_penetration(s, 0.0, pos, lam) == 0.0


@pytest.mark.slow
def test_impaled_face_is_reported():
    # Node-to-surface contact (one contact point per segment) on the three-wave surface at
    # 8 elements per 0.0625 mm: the asperities pass between face nodes (measured 6-7
    # element widths); the test must say so, not return a number.
    from rubbercontact.errors import ConvergenceError

    surf = rc.roughness.section3().realizations(1, seed=2021)[0]
    out = None
    with pytest.warns(RuntimeWarning, match="impaled"):
        try:
            out = rc.fem.sliding_test(surf, rc.materials.sbr(), 0.35, 10.0, mesh=(32, 24),
                                      periods=1, min_periods=1, contact_points=1,
                                      solver="transient")
        except ConvergenceError:
            pass
    if out is not None:   # and the result carries it, with a contact fraction <= 1
        assert out.stats.impaled
        assert 0.0 <= out.contact_fraction <= 1.0


@pytest.mark.slow
def test_segment_contact_keeps_the_asperities_out():
    # The same case with 4 contact points per segment: the surface stays outside the face
    # within the chord sag of the sampling, (h/4)^2 |z''|max / 8 = 0.03 element widths for
    # |z''|max = 274 /mm and h = 7.8 µm, plus the penalty penetration; allow 0.2 widths.
    import warnings

    surf = rc.roughness.section3().realizations(1, seed=2021)[0]
    with warnings.catch_warnings():
        warnings.filterwarnings("error", message=".*impaled")
        out = rc.fem.sliding_test(surf, rc.materials.sbr(), 0.35, 10.0, mesh=(32, 24),
                                  periods=1, min_periods=1, contact_points=4,
                                  solver="transient")
    h = surf.period / 32
    assert out.stats.max_segment_penetration < 0.2 * h
    assert not out.stats.impaled
    assert out.friction > 0
