"""The transient FEM sliding test: small-slope limit vs linear viscoelastic theory, sign
convention, zero friction of an elastic solid, global equilibrium, result container.

Reference for full contact of one sine on a viscoelastic half-space (plane strain,
ν = 1/2): μ = q²Δ² Im E_r(qv)/(4 σ0), E_r = 4E/3.
"""

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.fem.result import BULK_SHEAR_LIMIT, bulk_shear_message

LAM = 0.0625


def _small_slope_case(v=1.0, m2=0.1, nx=32, ny=24, material=None, periods=4):
    mat = material or rc.materials.sbr()
    q = 2 * np.pi / LAM
    amp = m2 * np.sqrt(2) / q
    er = mat.reduced_modulus(q * v)
    # twice the full-contact pressure of the (complex) modulus keeps the contact full
    p = 2 * np.pi * abs(er) * amp / LAM
    out = rc.fem.sliding_test(rc.roughness.SineSeries([LAM], [amp]), mat, p, v,
                              mesh=(nx, ny), periods=periods, solver="transient")
    mu_th = q**2 * amp**2 * er.imag / (4 * p)
    return out, mu_th, amp


@pytest.fixture(scope="module")
def small_slope():
    return _small_slope_case()


def test_small_slope_friction_matches_linear_theory(small_slope):
    out, mu_th, _ = small_slope
    assert out.contact_fraction == pytest.approx(1.0, abs=1e-12)
    # Issue requirement: within 5 %. Measured agreement is ~0.1 %, the residual error
    # coming from the mesh (16 elements per λ in depth decay) and the cell height.
    assert out.friction == pytest.approx(mu_th, rel=0.05)
    assert out.friction > 0
    assert out.stats.steady
    # steady means the last two period averages agree within steady_tol (1 %) + 1e-4
    assert out.stats.period_change <= 0.01 + 1e-4 / out.friction


def test_sign_convention_pressure_higher_on_rising_flanks(small_slope):
    # v > 0: rubber moves +x relative to the surface; pressure higher where dz/dx > 0.
    out, _, _ = small_slope
    prof = out.pressure_profile
    slope = np.cos(2 * np.pi * prof.x / LAM)   # dz/dx sign for phase 0
    rising, falling = prof.pressure[slope > 0.3].mean(), prof.pressure[slope < -0.3].mean()
    assert rising > falling
    # μ from the pressure profile, <σ dz/dx>/σ0 (projected-length weights), agrees with
    # the contact-force friction (different formula, same physics; 2 % for the
    # trapezoid-vs-lumped weights).
    dzdx = rc.roughness.SineSeries([LAM], [out.surface["amplitudes"][0]]).slopes(prof.x)
    mu_profile = np.mean(prof.pressure * dzdx) / out.mean_pressure
    assert mu_profile == pytest.approx(out.friction, rel=0.02)


def test_global_equilibrium_top_reaction_equals_contact_friction(small_slope):
    out, _, _ = small_slope
    h = out.history
    slide = h["phase"] == 2
    # the horizontal reaction of the top edge balances the contact force: only the
    # Newton tolerance (1e-6 p̄ L0) separates them
    np.testing.assert_allclose(h["friction_top"][slide], h["friction"][slide], atol=1e-5)
    # vertical: the load history reaches p̄
    assert h["load"][-1] == pytest.approx(out.mean_pressure)


def test_face_lag_grows_with_cell_height_as_friction_stress_over_relaxed_modulus():
    # x-periodicity makes the x-force across every horizontal material line the friction
    # force τ L0. Away from the face (decay length λ/2π) the cell is in uniform simple
    # shear, for which a neo-Hookean solid has σ_xy = G γ exactly, and once the creep has
    # settled G = G∞ = E∞/3. Near the face, second-order kinematics (of the same order in
    # the slope as τ itself) add a lag that does not depend on the height: about 10 % of
    # τ H/G∞ at H/L0 = 0.75 on this wave. So two heights are compared: the face lag grows
    # by τ ΔH/G∞. Each test slides at least 2 periods (0.125 s, 7.7 of SBR's longest
    # retardation times; exp(-7.7) = 5e-4 left). Tolerance 2 %: measured 0.5 %, from the
    # near-face lag not being quite height-independent.
    mat = rc.materials.sbr()
    q = 2 * np.pi / LAM
    amp = 0.1 * np.sqrt(2) / q
    p = 2 * np.pi * abs(mat.reduced_modulus(q)) * amp / LAM     # full contact at 1 mm/s
    runs = [rc.fem.sliding_test(rc.roughness.SineSeries([LAM], [amp]), mat, p, 1.0,
                                mesh=(32, ny), height_ratio=hr, periods=4, solver="transient")
            for hr, ny in ((1.5, 24), (3.0, 48))]
    tau = np.mean([r.shear_stress for r in runs])
    lag = [r.history["face_shift"][-1] for r in runs]
    slope = (lag[1] - lag[0]) / (runs[1].height - runs[0].height)
    assert slope == pytest.approx(-tau / (mat.equilibrium_modulus / 3), rel=0.02)
    for r in runs:      # the face lags the driven top; the diagnostic is that lag over H
        assert r.history["face_shift"][-1] < 0
        assert r.stats.bulk_shear == pytest.approx(-r.history["face_shift"][-1] / r.height)
        assert abs(r.stats.bulk_shear_change) < 0.01 * r.stats.bulk_shear   # settled
        assert r.stats.bulk_shear < BULK_SHEAR_LIMIT


def test_bulk_shear_message_names_load_and_says_what_to_do():
    msg = bulk_shear_message(1.15, 2.0, 50.0, "transient")
    assert "sheared as a whole by 1.15" in msg and "p̄ = 2 MPa, v = 50 mm/s" in msg
    assert "steady solver" in msg and len(msg) <= 300
    assert "steady solver" not in bulk_shear_message(1.15, 2.0, 50.0, "steady")


def test_mean_separation_definition(small_slope):
    # In full contact the deformed face follows z, whose mean is 0 (the trapezoid rule of a
    # sine at uniform nodes is exact), except for the penalty penetration p̄/ε with
    # ε = 100 E_alg/h, bounded using E∞ < E_alg.
    out, _, amp = small_slope
    h = LAM / 32
    assert out.mean_separation < 0
    assert abs(out.mean_separation) < out.mean_pressure * h / (100 * 4.17)


def test_elastic_material_gives_zero_friction():
    mat = rc.materials.GeneralizedMaxwell.elastic(4.17)
    surf = rc.roughness.SineSeries([LAM], [0.005])        # m2 = 0.36, partial contact
    out = rc.fem.sliding_test(surf, mat, 0.3, 10.0, mesh=(32, 24), periods=2, solver="transient")
    assert 0.05 < out.contact_fraction < 0.95
    # exactly zero up to round-off: every step is a symmetric configuration
    assert abs(out.friction) < 1e-8


def test_min_sliding_time_sets_the_sliding_distance():
    # An elastic cell is steady from the first period, so without a minimum time the test
    # stops after 2 periods. 20 ms at 10 mm/s over a 0.0625 mm cell is 3.2 periods:
    # rounded up to whole periods (the check compares period averages), 4 periods, even
    # though only 2 were allowed.
    mat = rc.materials.GeneralizedMaxwell.elastic(4.17)
    surf = rc.roughness.SineSeries([LAM], [0.003])
    kw = {"mesh": (16, 8), "periods": 2, "steps_per_period": 8}
    assert rc.fem.sliding_test(surf, mat, 0.3, 10.0, **kw, solver="transient").stats.periods == 2
    out = rc.fem.sliding_test(surf, mat, 0.3, 10.0, min_sliding_time=0.02, **kw, solver="transient")
    assert out.stats.periods == 4 and out.stats.steady
    for bad in (-0.01, float("nan")):
        with pytest.raises(rc.errors.InputError, match="min_sliding_time"):
            rc.fem.sliding_test(surf, mat, 0.3, 10.0, min_sliding_time=bad, solver="transient",
                                **kw)


def test_static_test_has_no_friction_and_relaxed_state():
    # v = 0: fully relaxed static indentation; with the equilibrium modulus alone the
    # result equals that of the elastic material E∞ (exact relaxation in one big step).
    surf = rc.roughness.SineSeries([LAM], [0.004])
    visco = rc.fem.sliding_test(surf, rc.materials.sbr(), 0.3, 0.0, mesh=(24, 18),
                                solver="transient")
    elastic = rc.fem.sliding_test(surf, rc.materials.GeneralizedMaxwell.elastic(4.17), 0.3,
                                  0.0, mesh=(24, 18), solver="transient")
    assert visco.friction == pytest.approx(0.0, abs=1e-10)
    # e^{-100} relaxation: identical up to the Newton tolerance
    assert visco.contact_fraction == pytest.approx(elastic.contact_fraction, abs=1e-6)
    assert visco.mean_separation == pytest.approx(elastic.mean_separation, rel=1e-5)


def test_result_dataset_has_units(small_slope):
    out, _, _ = small_slope
    ds = out.to_dataset()
    assert ds["friction"].attrs["units"] == "1"
    assert ds["mean_separation"].attrs["units"] == "mm"
    assert ds["profile_pressure"].attrs["units"] == "MPa"
    assert ds["history_friction"].size == out.stats.steps
    assert float(ds["shear_stress"]) == pytest.approx(out.friction * out.mean_pressure)


def _partial_contact_case():
    """m2 = 0.1 sine at p̄ = 0.4 p_full, v = 1 mm/s, and its half-space (BEM) solution."""
    mat = rc.materials.sbr()
    q = 2 * np.pi / LAM
    amp = 0.1 * np.sqrt(2) / q
    v = 1.0
    p = 0.4 * np.pi * abs(mat.reduced_modulus(q * v)) * amp / LAM
    surf = rc.roughness.SineSeries([LAM], [amp])
    return surf, mat, p, v, rc.halfspace.solve_sliding(surf, None, mat, v, p, n=2048)


def test_small_slope_partial_contact_agrees_with_halfspace_solver():
    # Peer check in partial contact (m2 = 0.1, p̄ = 0.4 p_full, v = 1 mm/s): FEM and the
    # viscoelastic half-space BEM must agree in the small-slope limit. Measured: μ 3 %,
    # α 2.6 %, ū 1.8 % at 32 x 24 (1.4 %, 2.5 %, 1.6 % at 64 x 48); 5 % allows for the
    # mesh, the finite slope (O(m2²)), K = 2 GPa vs ν = 1/2 and the cell height.
    surf, mat, p, v, bem = _partial_contact_case()
    fem = rc.fem.sliding_test(surf, mat, p, v, mesh=(32, 24), periods=4, solver="transient")
    assert fem.friction == pytest.approx(bem.friction, rel=0.05)
    assert fem.contact_fraction == pytest.approx(bem.contact_fraction, rel=0.05)
    assert fem.mean_separation == pytest.approx(bem.mean_separation, rel=0.05)


@pytest.mark.slow
def test_small_slope_friction_fine_mesh_two_speeds():
    for v in (1.0, 10.0):
        out, mu_th, _ = _small_slope_case(v=v, nx=64, ny=48, periods=4)
        assert out.friction == pytest.approx(mu_th, rel=0.02)


@pytest.mark.slow
def test_high_slope_wave_mesh_convergence():
    # Paper's high-slope wave at 1 MPa and 10 mm/s. Sequence 30x23 -> 60x45 (the
    # 120x90 point is in benchmarks/fem.md): friction and contact fraction must change
    # by less than 10 % between the two meshes and the contact pressure must be smooth.
    res = [rc.fem.sliding_test(rc.roughness.high_slope_wave(), rc.materials.sbr(), 1.0,
                               10.0, mesh=m, periods=6, solver="transient")
           for m in ((30, 23), (60, 45))]
    for r in res:
        print(r.mesh, r.friction, r.contact_fraction, r.mean_separation, r.stats)
        assert 0.05 < r.contact_fraction < 0.5
        assert r.friction > 0
    assert res[1].friction == pytest.approx(res[0].friction, rel=0.10)
    assert res[1].contact_fraction == pytest.approx(res[0].contact_fraction, rel=0.10)
    prof = res[1].pressure_profile
    p = prof.pressure
    inside = np.flatnonzero(p > 0.1 * p.max())
    inside = inside[(inside > inside.min() + 1) & (inside < inside.max() - 1)]
    alt = p[inside] - 0.5 * (p[inside - 1] + p[inside + 1])
    assert np.max(np.abs(alt)) < 0.1 * p.max()


def test_several_steps_per_element_predict_from_one_column_back():
    # steps_per_period = 2 nx: half an element of travel per step. The field one element
    # of travel back, rolled by one column, is the steady-state predictor (no fractional
    # interpolation of the contact face). Same physics as the BEM peer check above, and
    # the halved step keeps the iterations per step about the same as whole-column steps
    # (measured at 120 x 90 on the section 3 cell: 8.6/step with interpolation, ~3 now).
    surf, mat, p, v, bem = _partial_contact_case()
    one = rc.fem.sliding_test(surf, mat, p, v, mesh=(32, 24), periods=4, solver="transient")
    two = rc.fem.sliding_test(surf, mat, p, v, mesh=(32, 24), periods=4, steps_per_period=64,
                              solver="transient")
    assert two.friction == pytest.approx(bem.friction, rel=0.05)
    # small slope, ωτ spread over the Prony series: the time-step effect is below 2 %
    assert two.friction == pytest.approx(one.friction, rel=0.02)
    per_step = [r.stats.newton_iterations / r.stats.steps for r in (one, two)]
    assert per_step[1] <= 1.5 * per_step[0]


def test_reese_govindjee_small_slope_friction_matches_linear_theory():
    # The paper's finite-strain model reduces to linear viscoelasticity at small strain.
    # Its backward-Euler update is first order in dt (measured −6.3 % at the default 32
    # steps per period, −1.1 % at 128; Simo +1.3/+1.1 %), so 128 steps per period here;
    # 5 % as for the Simo model above.
    mat = rc.materials.sbr()
    q, v = 2 * np.pi / LAM, 1.0
    amp = 0.1 * np.sqrt(2) / q
    er = mat.reduced_modulus(q * v)
    p = 2 * np.pi * abs(er) * amp / LAM
    out = rc.fem.sliding_test(rc.roughness.SineSeries([LAM], [amp]), mat, p, v,
                              mesh=(32, 24), periods=3, steps_per_period=128,
                              viscous_model="reese-govindjee", solver="transient")
    mu_th = q**2 * amp**2 * er.imag / (4 * p)
    assert out.contact_fraction == pytest.approx(1.0, abs=1e-12)
    assert out.friction == pytest.approx(mu_th, rel=0.05)
