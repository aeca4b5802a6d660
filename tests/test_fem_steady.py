"""The steady FEM sliding test against what it must equal: the settled transient test, the
recurrence it integrates, finite differences, closed forms and the static limits.

Reference for full contact of one sine on a viscoelastic half-space (plane strain,
ν = 1/2): μ = q²Δ² Im E_r(qv)/(4 σ0) = m2² Im E_r/(2 σ0), E_r = 4E/3.
"""

import warnings

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.errors import ConvergenceError, InputError
from rubbercontact.fem.constitutive import MaterialParameters
from rubbercontact.fem.options import FemOptions
from rubbercontact.fem.setup import build_cell
from rubbercontact.fem.steady import SteadyCell
from rubbercontact.fem.streamline import streamline_kernel

LAM = 0.0625


@pytest.mark.parametrize("order", [1, 2])
@pytest.mark.parametrize("dt", [1e-6, 5e-5, 1e-3])
def test_streamline_kernel_is_the_periodic_fixed_point_of_the_transient_update(order, dt):
    # A row whose stress pattern travels one column per step: a material point sees
    # pattern[0], pattern[1], ... and its history obeys the transient update (the weights
    # of the next test). After a warm-up loop one loop is the affine map Q -> A Q + b with
    # A = e^{-nx dt/τ} per branch, whose fixed point b/(1 − A) is exact. The circulant
    # kernel must give it at column 0 (to round-off).
    params = MaterialParameters.from_material(rc.materials.sbr(), history_order=order)
    nx = 12
    pattern = np.random.default_rng(1).standard_normal((nx, 3))
    expected = streamline_kernel(params, dt, nx).apply(pattern[None], axis=1)[0, 0]
    decay, gamma = params.step_factors(dt)
    c = params.curvature_factors(dt) if order == 2 else np.zeros_like(gamma)
    w1, w2 = params.beta * (gamma + c / 2), -params.beta * c / 2

    def one_loop(q):
        for i in range(1, nx + 1):
            ds = pattern[i % nx] - pattern[i - 1]
            ds_prev = pattern[i - 1] - pattern[i - 2]
            q = decay[:, None] * q + w1[:, None] * ds + w2[:, None] * ds_prev
        return q

    q0 = np.zeros((params.n_branches, 3))
    b = one_loop(q0)
    A = decay[:, None] ** nx
    np.testing.assert_allclose(one_loop(q0 + 1.0) - b, A * np.ones_like(q0), rtol=1e-9,
                               atol=1e-13)   # affine with that A (a check on the map)
    fixed = b / (1.0 - A)
    np.testing.assert_allclose(fixed.sum(axis=0), expected, rtol=1e-9, atol=1e-12)


def test_streamline_kernel_update_matches_constitutive_module():
    # The kernel's weights are those of update_stress: one step of it with the quadratic
    # history at equal steps changes Q by β(γ + c/2)ΔS − β(c/2)ΔS_prev (checked through the
    # code path that the transient test runs).
    from rubbercontact.fem.constitutive import ViscousState, update_stress

    params = MaterialParameters.from_material(rc.materials.sbr(), history_order=2)
    dt = 3e-5
    F = np.eye(2)[None] + 0.01 * np.array([[[0.3, 0.5], [-0.2, 0.1]]])
    F0 = np.eye(2)[None]
    p = np.zeros(1)
    s0 = np.zeros((1, 3))
    q0 = np.zeros((params.n_branches, 1, 3))
    st = ViscousState(s0, q0, s0.copy() - 0.001, dt)
    _, _, _, _, new = update_stress(params, F, p, st, dt, tangent=False)
    ds = new.s_iso - s0
    decay, gamma = params.step_factors(dt)
    c = params.curvature_factors(dt)
    manual = (params.beta * (gamma + c / 2))[:, None, None] * ds \
        - (params.beta * c / 2)[:, None, None] * 0.001
    np.testing.assert_allclose(new.q, manual, rtol=1e-12, atol=1e-15)
    del F0


def _cell(mesh=(16, 8), v=10.0):
    surf = rc.roughness.high_slope_wave()
    setup = build_cell(surf, rc.materials.sbr(), 1.0, v, FemOptions(mesh=mesh),
                       sliding_plate=True)
    return setup, SteadyCell(setup.model, streamline_kernel(setup.params, setup.dt, mesh[0]))


@pytest.mark.parametrize("gauge", ["face", "top"])
def test_jacobian_matches_central_differences(gauge):
    # The exact Jacobian (sparse part + FFT memory) against central differences of the
    # residual at a deformed, partly-in-contact state; the difference error is O(ε²)
    # ~ 1e-10 relative and round-off ~1e-16/ε² ~ 1e-2 · 1e-14: tolerance 1e-6.
    setup, cell = _cell()
    rng = np.random.default_rng(0)
    U = 1e-5 * rng.standard_normal(setup.model.n)
    U[setup.model.plate] = -0.002
    ev = cell.evaluate(U, 0.0, setup.load, gauge)
    assert np.any(ev.contact.active)
    for _ in range(3):
        v = rng.standard_normal(U.size)
        eps = 1e-7
        fd = (cell.evaluate(U + eps * v, 0.0, setup.load, gauge).r
              - cell.evaluate(U - eps * v, 0.0, setup.load, gauge).r) / (2 * eps)
        assert np.linalg.norm(cell.jvp(ev, v) - fd) <= 1e-6 * np.linalg.norm(fd)


def test_newton_converges_quadratically_near_the_solution():
    # From a converged steady state perturbed by 1e-4 of an element, exact Newton (tight
    # GMRES) must converge quadratically: r_{k+1} <= C r_k² with C from the first step.
    from rubbercontact.fem.newton_krylov import Counters, newton_krylov
    from rubbercontact.fem.options import SteadyOptions

    res = rc.fem.steady_sliding(rc.roughness.high_slope_wave(), rc.materials.sbr(), 1.0, 10.0,
                                mesh=(24, 12))
    st = res.state
    setup, cell = _cell(mesh=(24, 12))
    U = st.U + 1e-4 * setup.cell.hx * np.random.default_rng(2).standard_normal(st.U.size)
    out = newton_krylov(cell, U, 0.0, setup.load, "face", 1e-11 * setup.load,
                        SteadyOptions(krylov_rtol=1e-12, max_krylov=400), Counters())
    r = np.array(out.residuals)
    assert out.converged and len(r) <= 6
    # convergence order from consecutive residuals above the round-off floor: quadratic
    # once the contact set has settled (a face point may change state in the first steps;
    # measured 2.4e-2, 1.1e-5, 4.7e-7, 1.1e-9: order 1.9 at the end)
    r = r[r > 1e-10 * setup.load]
    order = np.log(r[2:] / r[1:-1]) / np.log(r[1:-1] / r[:-2])
    assert order.size >= 1 and order[-1] > 1.6, r


def test_steady_equals_the_settled_transient_test():
    # The steady state is the fixed point of the transient test at one element of travel
    # per step, started at the same surface offset. Coarse cell (24 x 12), 10 mm/s, 1 MPa;
    # the transient slides 20 periods (125 ms, 7.8 of the SBR's longest retardation
    # times). Tolerance: ten times the transient's own change over its last period, at
    # least 1e-4 (measured: the two agree to 1e-6 on 40 x 30 after 30 periods).
    surf, mat = rc.roughness.high_slope_wave(), rc.materials.sbr()
    st = rc.fem.steady_sliding(surf, mat, 1.0, 10.0, mesh=(24, 12))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        tr = rc.fem.sliding_test(surf, mat, 1.0, 10.0, mesh=(24, 12), solver="transient",
                                 periods=20, min_periods=20, steady_tol=1e-12,
                                 surface_offset=st.stats.surface_offset)
    h = tr.history
    slide = h["phase"] == 2
    n = 24
    for key, value in (("friction", st.friction), ("contact_fraction", st.contact_fraction),
                       ("mean_separation", st.mean_separation)):
        series = h[key][slide]
        last, before = series[-n:].mean(), series[-2 * n:-n].mean()
        drift = max(abs(last - before), np.ptp(series[-n:])) / abs(last)
        assert value == pytest.approx(last, rel=max(1e-4, 10 * drift)), key
        # the transient tends to a travelling wave: every step of a period the same state
        assert np.ptp(series[-n:]) < 0.1 * np.ptp(series[:n])
    assert st.stats.bulk_shear == pytest.approx(tr.stats.bulk_shear, rel=1e-3)


@pytest.mark.parametrize("contact", ["penalty", "barrier"])
def test_small_slope_full_contact_matches_linear_theory(contact):
    # m2 = 0.1 sine pressed at twice its full-contact pressure (full contact), 10 mm/s:
    # μ = m2² Im E_r(qv)/(2 σ0). 5 % as for the transient test (mesh of 16 elements per
    # decay length λ/2π in depth, the cell height, O(m2²)); measured about 1 %. The
    # barrier holds to the same closed form and never penetrates.
    mat = rc.materials.sbr()
    q, v = 2 * np.pi / LAM, 10.0
    amp = 0.1 * np.sqrt(2) / q
    er = mat.reduced_modulus(q * v)
    p = 2 * np.pi * abs(er) * amp / LAM
    out = rc.fem.steady_sliding(rc.roughness.SineSeries([LAM], [amp]), mat, p, v,
                                mesh=(32, 24), contact=contact)
    assert out.contact_fraction == pytest.approx(1.0, abs=1e-12)
    assert out.friction == pytest.approx(0.01 * er.imag / (2 * p), rel=0.05)
    if contact == "barrier":
        assert out.stats.max_penetration == 0.0
    assert out.stats.solver == "steady" and out.stats.steady


def test_elastic_material_has_no_friction_and_the_static_state():
    # No history: the steady problem is the static one. The sine's crest sits on a node
    # (nx divisible by 4), so the configuration is symmetric and μ vanishes to round-off;
    # ū equals the static (v = 0) test's within the Newton tolerance.
    mat = rc.materials.GeneralizedMaxwell.elastic(4.17)
    surf = rc.roughness.SineSeries([LAM], [0.005])
    moving = rc.fem.steady_sliding(surf, mat, 0.3, 10.0, mesh=(32, 24))
    static = rc.fem.sliding_test(surf, mat, 0.3, 0.0, mesh=(32, 24), solver="transient")
    assert 0.05 < moving.contact_fraction < 0.95
    assert abs(moving.friction) < 1e-8
    assert moving.mean_separation == pytest.approx(static.mean_separation, rel=1e-5)
    assert moving.contact_fraction == pytest.approx(static.contact_fraction, abs=1e-4)


@pytest.mark.filterwarnings("ignore:mean_pressure")
def test_speed_limits_are_the_relaxed_and_the_glassy_static_solutions():
    # v -> 0: every branch relaxes within a step, the history vanishes: the elastic solid
    # E∞, exactly. v -> ∞: the oscillating part of the stress sees the glassy modulus
    # E∞ + Σ E_i, the row means stay relaxed, which differs from the glassy static
    # solution only at second order in the strain (m2 = 0.02 here: 1 %). At both ends the
    # friction vanishes against its value at 10 mm/s.
    mat = rc.materials.sbr()
    surf = rc.roughness.SineSeries([LAM], [0.02 * np.sqrt(2) * LAM / (2 * np.pi)])
    e_glass = mat.equilibrium_modulus + float(np.sum(mat.moduli))
    kw = {"mesh": (32, 24), "bulk_modulus": 1e6}   # incompressible at the glassy modulus too
    for v, modulus, rel, speeds in ((1e-9, mat.equilibrium_modulus, 1e-5, (1.0, 1e2, 1e4)),
                                    (1e14, e_glass, 0.01, (1e6, 1e8, 1e10))):
        p = 0.3 * np.pi * 4 * modulus / 3 * surf.amplitudes[0] / LAM   # 30 % of full contact
        moving = rc.fem.steady_sliding(surf, mat, p, v, **kw)
        scan = max(rc.fem.steady_sliding(surf, mat, p, u, **kw).friction for u in speeds)
        static = rc.fem.steady_sliding(surf, rc.materials.GeneralizedMaxwell.elastic(modulus),
                                       p, 0.0, **kw)
        assert abs(moving.friction) < 1e-3 * scan
        assert moving.mean_separation == pytest.approx(static.mean_separation, rel=rel)
        assert moving.contact_fraction == pytest.approx(static.contact_fraction,
                                                        abs=max(rel, 1e-4))


def test_a_neighbouring_speed_starts_the_next_solve():
    # Continuation: the solution at 10 mm/s starts the one at 20 mm/s; the answer is the
    # one a fresh solve finds (same discrete problem; the steady states may sit at other
    # surface offsets, so within the sub-column sensitivity measured on this mesh, 2 %),
    # in fewer Newton iterations.
    surf, mat = rc.roughness.high_slope_wave(), rc.materials.sbr()
    a = rc.fem.steady_sliding(surf, mat, 1.0, 10.0, mesh=(24, 12))
    fresh = rc.fem.steady_sliding(surf, mat, 1.0, 20.0, mesh=(24, 12))
    cont = rc.fem.steady_sliding(surf, mat, 1.0, 20.0, mesh=(24, 12), start=a.state)
    assert cont.friction == pytest.approx(fresh.friction, rel=0.02)
    assert cont.mean_separation == pytest.approx(fresh.mean_separation, rel=0.02)
    assert cont.stats.newton_iterations < fresh.stats.newton_iterations
    assert "neighbour" in cont.stats.tried[0]


def test_failure_falls_back_to_the_transient_test_and_says_so():
    import warnings

    surf, mat = rc.roughness.high_slope_wave(), rc.materials.sbr()
    with pytest.warns(RuntimeWarning, match="steady FEM solve failed"), \
            warnings.catch_warnings():
        # the fallback's own note that its coarse 16 x 8 transient has not settled in its
        # periods is not what this test is about
        warnings.filterwarnings("ignore", message=".*period averages still change")
        out = rc.fem.steady_sliding(surf, mat, 1.0, 10.0, mesh=(16, 8), newton_per_step=1,
                                    max_steps=2)
    assert out.stats.solver == "transient (fallback)"
    assert "steady failed" in out.stats.status and "press" in out.stats.status
    # the barrier rescue ran first (two continuation steps cannot reach the load) and the
    # status names both failures
    assert "barrier rescue:" in out.stats.status
    with pytest.raises(ConvergenceError) as info:
        rc.fem.steady_sliding(surf, mat, 1.0, 10.0, mesh=(16, 8), newton_per_step=1,
                              max_steps=2, fallback=False)
    assert info.value.diagnostics["tried"]


def test_a_failed_penalty_solve_is_rescued_by_the_barrier_before_the_transient():
    # One Newton iteration per continuation step stops the penalty's press; the rescue is
    # the barrier contact with 60 (RESCUE_NEWTON), solved afresh: the very solve of the
    # barrier asked for directly, so the numbers agree to the last bit, and no transient
    # test runs.
    import warnings

    from rubbercontact.fem.options import RESCUE_NEWTON

    surf, mat = rc.roughness.high_slope_wave(), rc.materials.sbr()
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        out = rc.fem.steady_sliding(surf, mat, 1.0, 10.0, mesh=(16, 8), newton_per_step=1)
    assert not [w for w in seen if "transient" in str(w.message)]
    assert out.stats.solver == "steady (barrier rescue)"
    assert out.stats.tried[0].startswith("penalty contact failed: frictionless press")
    direct = rc.fem.steady_sliding(surf, mat, 1.0, 10.0, mesh=(16, 8), contact="barrier",
                                   newton_per_step=RESCUE_NEWTON)
    assert (out.friction, out.contact_fraction) == (direct.friction, direct.contact_fraction)
    assert out.stats.max_penetration == 0.0
    with pytest.raises(ConvergenceError, match="steady FEM solve failed: frictionless"):
        rc.fem.steady_sliding(surf, mat, 1.0, 10.0, mesh=(16, 8), newton_per_step=1,
                              rescue="none", fallback=False)


def test_a_penalty_solve_with_an_impaled_face_is_solved_again_with_the_barrier():
    # One contact point per face segment lets the section 3 asperities (0.0625 mm waves,
    # 8 columns each) pass between two nodes: the penalty converges with the face impaled
    # (μ and A meaningless), so the steady solve tries the barrier rescue, afresh — the
    # very solve of the barrier asked for directly, to the last bit. With one point per
    # segment the barrier cannot keep the crest out between the nodes either: the result
    # stays flagged and the warning says so, once.
    import warnings

    from rubbercontact.fem.options import RESCUE_NEWTON

    surf = rc.roughness.section3().realizations(1, seed=2021)[0]
    args = (surf, rc.materials.sbr(), 0.35, 10.0)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        out = rc.fem.steady_sliding(*args, mesh=(32, 24), contact_points=1, fallback=False)
        plain = rc.fem.steady_sliding(*args, mesh=(32, 24), contact_points=1, rescue="none",
                                      fallback=False)
    assert plain.stats.impaled and plain.stats.solver == "steady"
    assert out.stats.solver == "steady (barrier rescue)"
    assert out.stats.tried[0].startswith("penalty contact impaled the face")
    with pytest.warns(RuntimeWarning, match="impaled"):
        direct = rc.fem.steady_sliding(*args, mesh=(32, 24), contact_points=1,
                                       contact="barrier", newton_per_step=RESCUE_NEWTON,
                                       fallback=False)
    assert (out.friction, out.contact_fraction) == (direct.friction, direct.contact_fraction)
    assert out.stats.impaled and direct.stats.impaled
    assert sum("impaled" in str(w.message) for w in seen) == 2   # out's, and plain's


@pytest.mark.parametrize("kw, field", [
    ({"viscous_model": "reese-govindjee"}, "viscous_model"),
    ({"periods": 4}, "periods"),
    ({"mesh": (6, 5)}, "mesh"),
    ({"coarse_elements": -1}, "coarse_elements"),
    ({"krylov_rtol": 2.0}, "krylov_rtol"),
    ({"bogus": 1}, "bogus"),
])
def test_bad_input_names_the_field(kw, field):
    with pytest.raises(InputError, match=field):
        rc.fem.steady_sliding(rc.roughness.high_slope_wave(), rc.materials.sbr(), 1.0, 10.0,
                              **kw)


def test_result_dataset_and_options_round_trip():
    out = rc.fem.steady_sliding(rc.roughness.high_slope_wave(), rc.materials.sbr(), 1.0, 10.0,
                                mesh=(24, 12))
    ds = out.to_dataset()
    assert ds.attrs["solver"] == "steady"
    assert ds["friction"].attrs["units"] == "1" and float(ds["friction"]) == out.friction
    opts = FemOptions(mesh=(24, 12), grading=2.0)
    assert FemOptions.from_dict(opts.to_dict()) == opts
    with pytest.raises(InputError, match="unknown"):
        FemOptions.from_dict({"meshes": [1, 2]})


def test_speed_sweep_by_continuation_follows_the_loss_peak():
    # Friction against speed over six decades on a coarse cell: each point starts from its
    # neighbour (one homotopy step each); the curve rises from ~0 at 1e-3 mm/s, peaks and
    # falls, and every point agrees with a fresh solve within the sub-column sensitivity
    # of this mesh (2 %, see the continuation test above).
    surf, mat = rc.roughness.high_slope_wave(), rc.materials.sbr()
    v = np.geomspace(1e-3, 1e3, 7)
    sweep = rc.fem.steady_sweep(surf, mat, 1.0, v, mesh=(24, 12))
    mu = np.array([r.friction for r in sweep])
    assert all(r.stats.solver == "steady" for r in sweep)
    # the middle point is pressed, the others continue outwards from their neighbour
    middle = v.size // 2
    assert "neighbour" not in sweep[middle].stats.tried[0]
    assert all("neighbour" in r.stats.tried[0] for i, r in enumerate(sweep) if i != middle)
    k = int(np.argmax(mu))
    assert 0 < k < v.size - 1 and mu[0] < 0.05 * mu[k] and mu[-1] < 0.5 * mu[k]
    fresh = rc.fem.steady_sliding(surf, mat, 1.0, float(v[k]), mesh=(24, 12))
    assert mu[k] == pytest.approx(fresh.friction, rel=0.02)
    with pytest.raises(InputError, match="equal length"):
        rc.fem.steady_sweep(surf, mat, [1.0, 2.0], [1.0, 2.0, 3.0])


def test_continuation_order_visits_each_point_once_after_its_neighbour():
    for n in range(1, 9):
        order = rc.fem.continuation_order(n)
        assert sorted(i for i, _ in order) == list(range(n))
        seen = set()
        for i, j in order:
            assert (j is None and not seen) or (j in seen and abs(i - j) == 1)
            seen.add(i)
    assert rc.fem.continuation_order(5, first=0) == [(0, None), (1, 0), (2, 1), (3, 2), (4, 3)]
    with pytest.raises(InputError, match="index"):
        rc.fem.continuation_order(3, first=3)


def _settled_transient(surface, mat, p, v, mesh, grading, offset, retardation_times):
    """The transient test at one column per step from the press, slid ``retardation_times``
    of the SBR's longest retardation time, started at the steady solution's offset."""
    t_min = retardation_times * float(mat.retardation_times().max())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return rc.fem.sliding_test(surface, mat, p, v, mesh=mesh, grading=grading,
                                   solver="transient", min_sliding_time=t_min, periods=500,
                                   steady_tol=1e-12, surface_offset=offset)


def _agree(st, tr, n):
    h = tr.history
    slide = h["phase"] == 2
    for key, value in (("friction", st.friction), ("contact_fraction", st.contact_fraction),
                       ("mean_separation", st.mean_separation)):
        series = h[key][slide]
        last, before = series[-n:].mean(), series[-2 * n:-n].mean()
        drift = max(abs(last - before), np.ptp(series[-n:])) / abs(last)
        assert value == pytest.approx(last, rel=max(1e-3, 10 * drift)), key


@pytest.mark.slow
@pytest.mark.parametrize("v", [10.0, 50.0])
def test_paper_size_law_cell_steady_equals_settled_transient(v):
    # The validation's law cell (120 x 23 graded x8) at 1 MPa: the transient slides 8
    # retardation times (130 ms: 21 periods at 10 mm/s, 104 at 50 mm/s); agreement to the
    # transient's remaining drift, at least 0.1 %.
    surf, mat = rc.roughness.high_slope_wave(), rc.materials.sbr()
    st = rc.fem.steady_sliding(surf, mat, 1.0, v, mesh=(120, 23), grading=8.0)
    tr = _settled_transient(surf, mat, 1.0, v, (120, 23), 8.0, st.stats.surface_offset, 8)
    _agree(st, tr, 120)


@pytest.mark.slow
def test_paper_size_section3_cell_steady_equals_settled_transient():
    # One section 3 realization on the validation's full-FEM mesh (240 x 45 graded x8) at
    # 0.35 MPa, 10 mm/s: the transient slides 6 retardation times (98 ms, 4 periods).
    surf = rc.roughness.section3().realizations(1, seed=2021)[0]
    mat = rc.materials.sbr()
    st = rc.fem.steady_sliding(surf, mat, 0.35, 10.0, mesh=(240, 45), grading=8.0)
    tr = _settled_transient(surf, mat, 0.35, 10.0, (240, 45), 8.0, st.stats.surface_offset, 6)
    _agree(st, tr, 240)


def test_newton_homotopy_starts_exactly_at_its_start_and_ends_at_the_solution():
    # r(U) − (1 − λ) r(U₀) = 0 holds at U₀ for λ = 0 to round-off, and its end (λ = 1) is
    # the steady state: from the converged state's displacements scaled by 0.97 (the face
    # partly lifted off the surface, the bulk shear and the plate's lead cut by 3 %) the
    # path must come back to that state. Newton's solution is locally unique, so to
    # within what the tolerances leave: |ΔU| <= 1e-6 of an element.
    from rubbercontact.fem.newton_krylov import Counters, Endpoint, follow
    from rubbercontact.fem.options import SteadyOptions

    res = rc.fem.steady_sliding(rc.roughness.high_slope_wave(), rc.materials.sbr(), 1.0, 10.0,
                                mesh=(24, 12))
    setup, cell = _cell(mesh=(24, 12))
    kern = cell.kernel
    U0 = 0.97 * res.state.U
    bias = cell.evaluate(U0, 0.0, setup.load, "face").r
    assert np.linalg.norm(bias) > 1e3 * setup.atol
    start = cell.with_kernel(kern, bias).evaluate(U0, 0.0, setup.load, "face")
    assert start.norm <= 1e-12 * np.linalg.norm(bias)
    counters = Counters()
    path = follow(cell, U0, Endpoint(kern, setup.load, bias), Endpoint(kern, setup.load), 0.0,
                  "face", setup.atol, SteadyOptions(), counters, "test", first_step=0.5)
    assert path.converged, counters.tried
    assert np.max(np.abs(path.U - res.state.U)) <= 1e-6 * setup.cell.hx


def test_nested_iteration_reaches_the_state_of_a_direct_solve():
    # The press on 12 columns carried to 24 (repair, then the Newton homotopy that
    # releases the face) against the press on 24 columns directly: the same discrete
    # problem, so the same friction, contact fraction and ū to within the sub-column
    # sensitivity of this mesh (the two may sit at other surface offsets, 2 %, as in
    # test_a_neighbouring_speed_starts_the_next_solve).
    surf, mat = rc.roughness.high_slope_wave(), rc.materials.sbr()
    nested = rc.fem.steady_sliding(surf, mat, 1.0, 10.0, mesh=(24, 12), coarse_columns=12,
                                   coarse_elements=4)
    direct = rc.fem.steady_sliding(surf, mat, 1.0, 10.0, mesh=(24, 12), coarse_elements=0)
    assert any(t.startswith("release 24x12") for t in nested.stats.tried), nested.stats.tried
    assert nested.friction == pytest.approx(direct.friction, rel=0.02)
    assert nested.contact_fraction == pytest.approx(direct.contact_fraction, rel=0.02)
    assert nested.mean_separation == pytest.approx(direct.mean_separation, rel=0.02)


def test_press_by_height_reaches_the_load_controlled_state():
    # Displacement control: the plate held at a height, its reaction is the load under
    # which the same state solves the load-controlled problem (free residual <= the
    # tolerance); and the press by height, bracketing the target load by regula falsi,
    # ends at the state the load-controlled press reaches (locally unique; tolerance as
    # in the homotopy test above, 1e-6 of an element).
    from rubbercontact.fem.newton_krylov import Counters
    from rubbercontact.fem.options import SteadyOptions
    from rubbercontact.fem.press import HeightPress

    res = rc.fem.steady_sliding(rc.roughness.high_slope_wave(), rc.materials.sbr(), 1.0, 10.0,
                                mesh=(24, 12), coarse_elements=0)
    setup, cell = _cell(mesh=(24, 12))
    m = setup.model
    hp = HeightPress(cell, setup.load, setup.atol, SteadyOptions(), Counters())
    point, _ = hp.at(np.zeros(m.n), 0.05 * float(res.state.U[m.plate]))
    assert point is not None and 0.0 < point.load < setup.load
    free = cell.evaluate(point.U, 0.0, point.load, "face")
    assert free.norm <= 1.5 * setup.atol
    out = hp.run(np.zeros(m.n), 0.002, 1e-7)
    assert out.converged, out.reason
    assert np.max(np.abs(out.U - res.state.U)) <= 1e-6 * setup.cell.hx


def test_loose_intermediate_steps_end_at_the_state_of_the_fully_converged_path():
    # The press converged to 1e-3 of the load at every intermediate step (the default)
    # against the same press with every step converged to the Newton tolerance: the end of
    # both is converged to the tolerance, so both are the same locally unique state (to
    # 1e-6 of an element, as the homotopy test above), and the loose path needs fewer
    # Newton iterations for it.
    from rubbercontact.fem.newton_krylov import Counters, Endpoint, follow
    from rubbercontact.fem.options import SteadyOptions

    setup, cell = _cell(mesh=(24, 12))
    U0 = np.zeros(setup.model.n)
    runs = {}
    for factor in (1.0, 1000.0):
        counters = Counters()
        runs[factor] = (follow(cell, U0, Endpoint(cell.kernel, 0.0),
                               Endpoint(cell.kernel, setup.load), 0.0, "face", setup.atol,
                               SteadyOptions(), counters, "press", path_tol_factor=factor),
                        counters)
    (plain, c_plain), (loose, c_loose) = runs[1.0], runs[1000.0]
    assert plain.converged and loose.converged, (c_plain.tried, c_loose.tried)
    assert loose.ev.norm <= 30 * setup.atol
    assert np.max(np.abs(loose.U - plain.U)) <= 1e-6 * setup.cell.hx
    assert c_loose.newton_iterations < c_plain.newton_iterations


def test_step_growth_rule_ends_at_the_state_of_the_doubling_only_path(monkeypatch):
    # The continuation step grown by 1.5 after a step of 6-8 Newton iterations (the
    # default) against the earlier rule (doubled after <= 5, else kept): both ends are
    # converged to the Newton tolerance, so both are the same locally unique state (to
    # 1e-6 of an element, as the homotopy test above) on a steep cell's press.
    from rubbercontact.fem import newton_krylov
    from rubbercontact.fem.newton_krylov import Counters, Endpoint, follow
    from rubbercontact.fem.options import SteadyOptions

    assert newton_krylov.growth(5) == 2.0 and newton_krylov.growth(8) == 1.5
    assert newton_krylov.growth(9) == 1.0
    setup, cell = _cell(mesh=(24, 12))
    U0 = np.zeros(setup.model.n)
    ends = {}
    for rule in (((5, 2.0),), newton_krylov.STEP_GROWTH):
        monkeypatch.setattr(newton_krylov, "STEP_GROWTH", rule)
        counters = Counters()
        ends[rule] = follow(cell, U0, Endpoint(cell.kernel, 0.0),
                            Endpoint(cell.kernel, setup.load), 0.0, "face", setup.atol,
                            SteadyOptions(first_step=1.0 / 32), counters, "press")
        assert ends[rule].converged, counters.tried
    old, new = ends.values()
    assert old.steps != new.steps      # the rules took different paths here
    assert np.max(np.abs(new.U - old.U)) <= 1e-6 * setup.cell.hx


def test_gmres_that_stagnates_gives_no_direction_after_one_restart_cycle():
    # A singular operator (half of the unknowns have no stiffness: a floating cell) with a
    # right-hand side mostly in its null space: GMRES cannot get below the null part's
    # share (0.89 here), so the direction is refused after one restart cycle instead of
    # max_krylov iterations; a regular operator still gets its direction to the tolerance.
    from types import SimpleNamespace

    from rubbercontact.fem.newton_krylov import _direction
    from rubbercontact.fem.options import SteadyOptions

    n = 200
    rng = np.random.default_rng(3)
    b = np.concatenate([rng.normal(size=n // 2), 2.0 * rng.normal(size=n // 2)])
    pre = SimpleNamespace(solve=lambda v, gauge: v)
    ev = SimpleNamespace(r=-b)
    calls = []

    def singular(v):
        calls.append(1)
        return np.concatenate([np.linspace(1.0, 50.0, n // 2) * v[:n // 2], 0.0 * v[n // 2:]])

    opts = SteadyOptions(max_krylov=200)
    assert _direction(SimpleNamespace(jvp=lambda e, v: singular(v)), ev, pre, "face", 1e-2,
                      opts) is None
    assert len(calls) <= 61
    d = np.linspace(1.0, 50.0, n)
    lin = _direction(SimpleNamespace(jvp=lambda e, v: d * v), ev, pre, "face", 1e-8, opts)
    assert lin is not None and lin.residual <= 1e-8
    assert np.allclose(d * lin.x, b, rtol=0, atol=1e-6 * np.linalg.norm(b))


def test_single_precision_preconditioner_is_close_and_falls_back_to_double():
    # A 2D Laplacian (well conditioned for float32: 5e3) solves in single precision to
    # float32's rounding times its condition; a graded diagonal spanning 1e12 (beyond
    # float32's range of exactly representable ratios at the check's 5 %) must be
    # refactorized in double precision and then solve to double accuracy.
    import scipy.sparse as sp

    from rubbercontact.fem.solver import SINGLE_RESIDUAL, factorize_general

    n = 40
    lap1 = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n))
    K = (sp.kron(lap1, sp.eye(n)) + sp.kron(sp.eye(n), lap1)).tocsr()
    b = np.random.default_rng(0).normal(size=n * n)
    f = factorize_general(K, single=True)
    x = f.solve(b)
    assert f.single and x.dtype == np.float64
    rel = np.linalg.norm(K @ x - b) / np.linalg.norm(b)
    assert 1e-12 < rel <= 1e3 * np.finfo(np.float32).eps
    exact = factorize_general(K).solve(b)
    assert np.linalg.norm(K @ exact - b) / np.linalg.norm(b) < 1e-12

    # float32 underflows the smallest pivots (1e-50): the single factor is refused
    D = sp.diags(np.logspace(0, -50, n * n)).tocsr()
    g = factorize_general(D, single=True)
    y = g.solve(np.ones(n * n))
    assert not g.single
    assert np.linalg.norm(D @ y - 1.0) / np.sqrt(n * n) <= 1e-12 < SINGLE_RESIDUAL


def test_a_newton_step_does_not_lift_a_touching_cell_off_the_surface():
    # r(U) = d (U − 1) with the surface pushing only while U < 0.75: the full Newton step
    # (U = 1) decreases the residual but leaves no contact to carry the load, so from a
    # touching state the line search takes α = 1/2; from a state without contact (the
    # undeformed cell above the surface) the full step is taken.
    from types import SimpleNamespace

    from rubbercontact.fem.newton_krylov import Counters, _newton_step
    from rubbercontact.fem.options import SteadyOptions

    d = np.array([1.0, 2.0, 3.0])

    def evaluate(U, shift, load, gauge):
        r = d * (U - 1.0)
        force = np.array([[0.0, 1.0]]) if U[0] < 0.75 else np.zeros((1, 2))
        return SimpleNamespace(U=U, shift=shift, load=load, r=r, admissible=True,
                               norm=float(np.linalg.norm(r)),
                               contact=SimpleNamespace(force=force))

    # penalty contact: no barrier, no step filter
    model = SimpleNamespace(barrier=None, feasible_step=lambda U, dU, shift: 1.0)
    cell = SimpleNamespace(evaluate=evaluate, jvp=lambda ev, v: d * v, model=model)
    pre = SimpleNamespace(solve=lambda b, gauge: b)
    opts = SteadyOptions()
    touching = evaluate(np.zeros(3), 0.0, 1.0, "face")
    step = _newton_step(cell, touching, pre, "face", 1e-8, opts, Counters())
    assert step.alpha == 0.5 and np.any(step.trial.contact.force)
    above = SimpleNamespace(**{**vars(touching), "contact": SimpleNamespace(
        force=np.zeros((1, 2)))})
    assert _newton_step(cell, above, pre, "face", 1e-8, opts, Counters()).alpha == 1.0
