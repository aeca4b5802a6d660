"""FEM constitutive model and element against closed forms (no FEM output as reference).

Closed forms used: the plane-strain compressible neo-Hookean Cauchy stress
``σ = μ J^{-5/3} dev(b) + U'(J) I`` with ``U' = κ/2 (J − 1/J)`` (written here in the
spatial form, independently of the code's material-frame formulas), the Prony
relaxation modulus ``E(t)/3`` in shear, and the complex modulus ``E(ω)/3``.
"""

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.fem.assembly import Assembler
from rubbercontact.fem.constitutive import (
    MaterialParameters,
    ViscousState,
    cauchy_from_pk2,
    update_stress,
)
from rubbercontact.fem.element import element_arrays, shape_gradients
from rubbercontact.fem.mesh import Mesh, periodic_cell
from rubbercontact.fem.solver import newton

MU, KAPPA = 1.5, 300.0


def cauchy_closed_form(F, mu=MU, kappa=KAPPA):
    """Plane-strain neo-Hookean Cauchy stress [σxx, σyy, σxy] from the spatial form."""
    F3 = np.eye(3)
    F3[:2, :2] = F
    J = np.linalg.det(F3)
    b = F3 @ F3.T
    dev = b - np.trace(b) / 3 * np.eye(3)
    sig = mu * J ** (-5 / 3) * dev + kappa / 2 * (J - 1 / J) * np.eye(3)
    return np.array([sig[0, 0], sig[1, 1], sig[0, 1]])


def elastic_params(mu=MU, kappa=KAPPA):
    return MaterialParameters(mu, kappa, np.zeros(0), np.zeros(0))


CASES = {
    "uniaxial": np.array([[1.3, 0.0], [0.0, 1.0]]),
    "uniaxial_compression": np.array([[1.0, 0.0], [0.0, 0.7]]),
    "simple_shear": np.array([[1.0, 0.8], [0.0, 1.0]]),
    "volumetric": np.array([[1.05, 0.0], [0.0, 1.05]]),
    "general": np.array([[1.2, 0.3], [-0.1, 0.9]]),
}


@pytest.mark.parametrize("name", list(CASES))
def test_homogeneous_stress_point(name):
    F = CASES[name]
    par = elastic_params()
    st = ViscousState.zeros((1,), 0)
    J = np.linalg.det(F)
    p = np.array([KAPPA / 2 * (J - 1 / J)])
    S, _, _, _, _ = update_stress(par, F[None], p, st, 1.0)
    # Round-off only: both sides are closed forms of the same model.
    np.testing.assert_allclose(cauchy_from_pk2(F[None], S)[0], cauchy_closed_form(F),
                               rtol=1e-12, atol=1e-12 * KAPPA)


def _distorted_element():
    return np.array([[[0.0, 0.0], [1.1, 0.1], [1.3, 0.9], [-0.2, 1.2]]])


@pytest.mark.parametrize("name", list(CASES))
def test_homogeneous_one_element_nodal_forces(name):
    # Affine displacement of one distorted element: nodal forces must equal the consistent
    # forces of the closed-form first Piola stress P = J σ F^{-T}: f_a = P ∫∇N_a dV0.
    F = CASES[name]
    Xe = _distorted_element()
    dNdX, w, _ = shape_gradients(Xe)
    ue = (Xe @ (F - np.eye(2)).T)
    out = element_arrays(elastic_params(), dNdX, w, ue, ViscousState.zeros((1, 4), 0), 1.0)
    s = cauchy_closed_form(F)
    sig = np.array([[s[0], s[2]], [s[2], s[1]]])
    P = np.linalg.det(F) * sig @ np.linalg.inv(F).T
    gradN = np.einsum("g,gaI->aI", w[0], dNdX[0])
    f_ref = (gradN @ P.T).ravel()
    np.testing.assert_allclose(out.fe[0], f_ref, rtol=1e-10, atol=1e-10 * np.abs(f_ref).max())
    # mean dilatation of an affine field is exact: θ = det F
    assert out.theta[0] == pytest.approx(np.linalg.det(F), rel=1e-12)


def _patch_mesh():
    # 3 x 3 patch with a distorted interior (classic patch test).
    x = np.array([0.0, 1.0, 2.0, 3.0])
    X = np.array([[xi, yi] for yi in x for xi in x])
    X[5] += [0.23, 0.11]
    X[6] += [-0.17, 0.2]
    X[9] += [0.1, -0.21]
    X[10] += [-0.12, -0.08]
    conn = []
    for j in range(3):
        for i in range(3):
            n0 = 4 * j + i
            conn.append([n0, n0 + 1, n0 + 5, n0 + 4])
    conn = np.array(conn)
    return Mesh(X=X, conn=conn, Xe=X[conn])


@pytest.mark.parametrize("name", ["uniaxial", "simple_shear", "general"])
def test_patch_newton_recovers_homogeneous_state(name):
    F = CASES[name]
    mesh = _patch_mesh()
    interior = np.array([5, 6, 9, 10])
    dof_map = -np.ones(2 * mesh.n_nodes, int)
    dof_map[(2 * interior[:, None] + np.arange(2)).ravel()] = np.arange(8)
    asm = Assembler(mesh, dof_map, 8)
    u_affine = (mesh.X @ (F - np.eye(2)).T).ravel()
    par = elastic_params()
    st = ViscousState.zeros((mesh.n_elements, 4), 0)

    def res(U, tangent):
        u = asm.full_displacement(U, u_affine)
        out = asm.element_output(par, u, st, 1.0, tangent)
        return asm.vector(out.fe), (asm.csr(asm.matrix_data(out.ke)) if tangent else None), out

    # start from the affine field with interior nodes displaced by up to 0.1
    U0 = u_affine[dof_map >= 0] + 0.1 * np.random.default_rng(3).uniform(-1, 1, 8)
    U, out, hist = newton(res, U0, atol=1e-12)
    np.testing.assert_allclose(U, u_affine[dof_map >= 0], atol=1e-10)
    sig = cauchy_from_pk2(out.F, out.S).reshape(-1, 3)
    np.testing.assert_allclose(sig, np.tile(cauchy_closed_form(F), (sig.shape[0], 1)),
                               atol=1e-9 * KAPPA)


def test_relaxation_after_step_shear_matches_prony(step_shear):
    # Finite simple shear γ = 0.5 applied in a step of 1e-15 s, then held. For the
    # neo-Hookean branch σ_xy = μγ exactly and the model relaxes every branch with its
    # own exponential, so σ_xy(t) = γ E(t)/3 at finite strain. Uneven hold steps test
    # that the exponential integrator is exact for any Δt/τ.
    mat = rc.materials.sbr()
    times, sxy = step_shear(mat, np.geomspace(1e-11, 0.05, 40), shear=0.5)
    ref = 0.5 * mat.relaxation_modulus(times) / 3.0
    # tolerance: the step of 1e-15 s is glassy to 1e-15/4.2e-10 ≈ 2e-6 relative.
    np.testing.assert_allclose(sxy, ref, rtol=1e-5)


def harmonic_shear_moduli(par, omega, n_per, n_cycles, g0=1e-5):
    """``(G', G'', dt)`` fitted to the last of ``n_cycles`` cycles of harmonic simple shear
    ``γ0 sin ωt`` from the relaxed state, ``n_per`` steps per cycle."""
    dt = 2 * np.pi / omega / n_per
    st = ViscousState.zeros((1,), par.n_branches, par.viscous_model)
    ts, ss = [], []
    for k in range(1, n_cycles * n_per + 1):
        t = k * dt
        F = np.array([[[1.0, g0 * np.sin(omega * t)], [0.0, 1.0]]])
        S, _, _, _, st = update_stress(par, F, np.zeros(1), st, dt, tangent=False)
        if k > (n_cycles - 1) * n_per:
            ts.append(t)
            ss.append(S[0, 2])
    ts = np.array(ts)
    A = np.column_stack([np.sin(omega * ts), np.cos(omega * ts)])
    (g1, g2), *_ = np.linalg.lstsq(A, np.array(ss) / g0, rcond=None)
    return g1, g2, dt


def test_harmonic_shear_gives_complex_modulus():
    # Small-amplitude steady harmonic shear γ0 sin ωt: σ_xy = γ0 (G' sin + G'' cos) with
    # G = E(ω)/3. ω near 1/τ2 gives a large loss modulus; 400 steps per cycle make the
    # piecewise-linear-input error of the exponential integrator O((ωΔt)²/12) ≈ 2e-5;
    # we run 10 τ1 so the start transient of the slowest branch has decayed (e^-10).
    mat = rc.materials.sbr()
    par = MaterialParameters.from_material(mat)
    omega = 1.0 / mat.relaxation_times[1]
    period = 2 * np.pi / omega
    n_per = 400
    n_cycles = int(np.ceil(10 * mat.relaxation_times[0] / period)) + 1
    g1, g2, _ = harmonic_shear_moduli(par, omega, n_per, n_cycles)
    G = mat.complex_modulus(omega) / 3.0
    # 0.5 %: integrator error ~1e-4 plus O(γ0) non-linearity ~1e-5.
    assert g1 == pytest.approx(G.real, rel=5e-3)
    assert g2 == pytest.approx(G.imag, rel=5e-3)
    assert g2 > 0.2 * g1  # the test really probes a lossy state


def material_tangent_and_fd(par, F, p, st, dt, h=1e-6):
    """``(CC, numeric)``: the code's tangent and central differences of ``S(C)``, both
    ``(n, 3, 3)``, columns for the engineering strain ``[E11, E22, 2 E12]``."""
    _, CC, _, _, _ = update_stress(par, F, p, st, dt)
    C = np.swapaxes(F, -1, -2) @ F

    def S_of_C(Cm):
        Fp = np.swapaxes(np.linalg.cholesky(Cm), -1, -2)  # any F with FᵀF = C
        return update_stress(par, Fp, p, st, dt, tangent=False)[0]

    num = np.empty_like(CC)
    for col, (i, j) in enumerate([(0, 0), (1, 1), (0, 1)]):
        dC = np.zeros((2, 2))
        dC[i, j] = dC[j, i] = 2.0 if i == j else 1.0  # engineering strain increment 1
        num[:, :, col] = (S_of_C(C + h * dC) - S_of_C(C - h * dC)) / (2 * h)
    return CC, num


def test_constitutive_tangent_matches_finite_differences():
    par = MaterialParameters.from_material(rc.materials.sbr())
    rng = np.random.default_rng(1)
    n = 6
    F = np.eye(2) + 0.25 * rng.standard_normal((n, 2, 2))
    st = ViscousState(0.2 * rng.standard_normal((n, 3)), 0.1 * rng.standard_normal((6, n, 3)))
    CC, num = material_tangent_and_fd(par, F, np.full(n, 0.7), st, 3e-5)
    # central differences: error O(h²)·|S'''| ~ 1e-9 relative
    np.testing.assert_allclose(num, CC, rtol=1e-6, atol=1e-6 * np.abs(CC).max())


def element_tangent_and_fd(par, dNdX, w, ue, st, dt, h=1e-7):
    """Element tangent of two elements and its central finite difference of the forces."""
    ke = element_arrays(par, dNdX, w, ue, st, dt).ke
    num = np.empty_like(ke)
    for k in range(8):
        d = np.zeros((2, 8))
        d[:, k] = h
        d = d.reshape(2, 4, 2)
        fp = element_arrays(par, dNdX, w, ue + d, st, dt, False).fe
        fm = element_arrays(par, dNdX, w, ue - d, st, dt, False).fe
        num[:, :, k] = (fp - fm) / (2 * h)
    return ke, num


def test_element_tangent_matches_finite_differences():
    par = MaterialParameters.from_material(rc.materials.sbr())
    rng = np.random.default_rng(2)
    Xe = np.concatenate([_distorted_element(), _distorted_element() + [2.0, 0.0]])
    dNdX, w, _ = shape_gradients(Xe)
    ue = 0.1 * rng.standard_normal((2, 4, 2))
    st = ViscousState(0.05 * rng.standard_normal((2, 4, 3)),
                      0.02 * rng.standard_normal((6, 2, 4, 3)))
    ke, num = element_tangent_and_fd(par, dNdX, w, ue, st, 1e-4)
    np.testing.assert_allclose(num, ke, atol=1e-6 * np.abs(ke).max())
    np.testing.assert_allclose(ke, np.swapaxes(ke, 1, 2), atol=1e-12 * np.abs(ke).max())


def test_step_factors_exact_and_stable():
    par = MaterialParameters.from_material(rc.materials.sbr())
    for dt in (1e-20, 1e-6, 1.0, np.inf):
        decay, gamma = par.step_factors(dt)
        xi = dt / par.tau
        ref = np.where(xi < 1e-8, 1 - xi / 2, (1 - np.exp(-xi)) / np.where(xi > 0, xi, 1))
        np.testing.assert_allclose(gamma, np.nan_to_num(ref), rtol=1e-12, atol=1e-300)
        assert np.all(np.isfinite(decay)) and np.all(np.isfinite(gamma))
    # A branch with τ ≪ Δt still carries its viscous stress β τ/Δt (not 0).
    _, gamma = par.step_factors(5e-5)
    assert gamma[3] == pytest.approx(par.tau[3] / 5e-5, rel=1e-6)


def test_moduli_mapping():
    mat = rc.materials.sbr()
    par = MaterialParameters.from_material(mat)
    assert par.mu == pytest.approx(4.17 / 3)
    np.testing.assert_allclose(par.mu * par.beta, mat.moduli / 3)


def test_periodic_cell_geometry():
    cell = periodic_cell(2.0, 1.5, 8, 5, grading=3.0)
    # wrap-around elements span the last column correctly and all areas are positive
    _, w, _ = shape_gradients(cell.Xe)
    assert w.sum() == pytest.approx(2.0 * 1.5, rel=1e-12)
    dy = np.diff(cell.y_nodes)
    assert dy[-1] / dy[0] == pytest.approx(3.0, rel=1e-12)


# -- quadratic history integration (history_order = 2) ---------------------------------


def _history_run(par, F_of_t, t_end, n):
    st = ViscousState.zeros((1,), par.n_branches)
    dt = t_end / n
    for j in range(n):
        _, _, _, _, st = update_stress(par, F_of_t((j + 1) * dt), np.zeros(1), st, dt,
                                       tangent=False)
    return st.q.sum(axis=0)[0]


def test_quadratic_history_is_second_order_where_linear_is_first():
    # Finite, non-proportional deformation history; the reference is the convolution
    # Q_i(T) = β_i ∫ e^{−(T−t)/τ_i} Ṡ_iso(t) dt by adaptive quadrature (Ṡ by central
    # differences of the closed-form S_iso, h = 1e-9 s: relative error ~1e-9). One
    # branch has τ = 1e-7 s ≪ Δt (ξ = 30…1000), the case the linear update lags.
    from scipy.integrate import quad

    from rubbercontact.fem.constitutive import isochoric_stress, kinematics

    mat = rc.materials.GeneralizedMaxwell(4.0, [3.0, 5.0, 50.0], [1e-3, 1e-5, 1e-7])
    w = 2 * np.pi * 200.0

    def F_of_t(t):
        s = 1.0 + 0.1 * np.sin(w * t)
        g = 0.3 * np.sin(w * t) + 0.2 * (1 - np.cos(0.5 * w * t))
        return np.array([[[s, g], [0.0, 1.0 / s]]])

    def s_iso(t):
        J, Ci, I1 = kinematics(F_of_t(t))
        return isochoric_stress(mat.equilibrium_modulus / 3, J, Ci, I1, False)[0][0]

    T = 4e-3
    par2 = MaterialParameters.from_material(mat, history_order=2)
    ref = np.zeros(3)
    for b, tau in zip(par2.beta, par2.tau, strict=True):
        for k in range(3):
            def f(t, tau=tau, k=k):
                return np.exp(-(T - t) / tau) * (s_iso(t + 1e-9) - s_iso(t - 1e-9))[k] / 2e-9
            ref[k] += b * quad(f, max(0.0, T - 60 * tau), T, limit=4000, epsabs=1e-13)[0]
    ns = (80, 160, 320, 640)
    err = {o: np.array([np.abs(_history_run(MaterialParameters.from_material(
        mat, history_order=o), F_of_t, T, n) - ref).max() for n in ns]) for o in (1, 2)}
    rate = {o: np.log2(e[:-1] / e[1:]) for o, e in err.items()}
    # measured rates: linear 1.68/1.73/1.66 (tending to 1), quadratic 2.5/2.6/2.5
    assert np.all(rate[2] > 1.9)
    assert np.all(rate[1] < 1.9)
    assert np.all(err[2] < err[1] / 20)


@pytest.mark.parametrize("n_per", [20, 40])
def test_quadratic_history_harmonic_shear_at_coarse_steps(n_per):
    # As test_harmonic_shear_gives_complex_modulus, but with 20/40 steps per cycle. The
    # linear update overestimates G' by 8.6/3.5 % there (first order: the fast branches'
    # rate is half a step late); the quadratic one misses G' by 0.45/0.05 % only. G'' is
    # second order with both, error ~(ωΔt)²/8 = 1.2/0.31 % (measured: linear −1.3/−0.29 %,
    # quadratic +1.6/+0.32 %); the bound allows 1.5 times that.
    mat = rc.materials.sbr()
    omega = 1.0 / mat.relaxation_times[1]
    dt = 2 * np.pi / omega / n_per
    n_cycles = int(np.ceil(10 * mat.relaxation_times[0] * omega / (2 * np.pi))) + 1
    g0 = 1e-5
    G = mat.complex_modulus(omega) / 3.0
    rel = {}
    for order in (1, 2):
        par = MaterialParameters.from_material(mat, history_order=order)
        st = ViscousState.zeros((1,), par.n_branches)
        ts, ss = [], []
        for k in range(1, n_cycles * n_per + 1):
            F = np.array([[[1.0, g0 * np.sin(omega * k * dt)], [0.0, 1.0]]])
            S, _, _, _, st = update_stress(par, F, np.zeros(1), st, dt, tangent=False)
            if k > (n_cycles - 1) * n_per:
                ts.append(k * dt)
                ss.append(S[0, 2])
        ts = np.array(ts)
        A = np.column_stack([np.sin(omega * ts), np.cos(omega * ts)])
        (g1, g2), *_ = np.linalg.lstsq(A, np.array(ss) / g0, rcond=None)
        rel[order] = (g1 / G.real - 1, g2 / G.imag - 1)
    bound = 1.5 * (2 * np.pi / n_per) ** 2 / 8
    assert abs(rel[2][1]) < bound
    assert abs(rel[2][0]) < bound / 3
    assert rel[1][0] > 3 * abs(rel[2][0])   # what the quadratic update removes


def test_quadratic_history_tangent_matches_finite_differences():
    par = MaterialParameters.from_material(rc.materials.sbr(), history_order=2)
    rng = np.random.default_rng(3)
    n = 6
    F = np.eye(2) + 0.25 * rng.standard_normal((n, 2, 2))
    for dt_prev in (3e-5, 6e-5, 1.5e-5, 1e-3):   # uniform, ratio 0.5, 2; 0.03 → linear
        st = ViscousState(0.2 * rng.standard_normal((n, 3)),
                          0.1 * rng.standard_normal((6, n, 3)),
                          0.2 * rng.standard_normal((n, 3)), dt_prev)
        p = np.full(n, 0.7)
        dt = 3e-5
        S0 = update_stress(par, F, p, st, dt, tangent=False)[0]
        CC, num = material_tangent_and_fd(par, F, p, st, dt)
        np.testing.assert_allclose(num, CC, rtol=1e-6, atol=1e-6 * np.abs(CC).max())
        # the previous state changes the stress only when the quadratic update is used
        st_lin = ViscousState(st.s_iso, st.q)
        S_lin = update_stress(par, F, p, st_lin, dt, tangent=False)[0]
        assert np.allclose(S0, S_lin) == (dt / dt_prev < 0.4)


def test_curvature_factors_limits_and_quadrature():
    from scipy.integrate import quad

    par = MaterialParameters.from_material(rc.materials.sbr(), history_order=2)
    for dt in (1e-12, 1e-9, 3e-8, 1e-6, 5e-5, 1e-2):
        c = par.curvature_factors(dt)
        xi = dt / par.tau
        # u = 1 − s: c = ∫₀¹ (e^{−ξu} − 1)(1 − 2u) du, as ∫(1 − 2u) = 0; expm1 keeps the
        # small-ξ integrand free of cancellation. For large ξ, e^{−ξu} is gone past 60/ξ
        # and the rest is ∫(u>a) −(1 − 2u) du = a − a², a = min(1, 60/ξ).
        ref = []
        for x in xi:
            a = min(1.0, 60 / x)
            ref.append(quad(lambda u, x=x: np.expm1(-x * u) * (1 - 2 * u), 0, a,
                            epsabs=0.0, epsrel=1e-11, limit=200)[0] + a - a * a)
        np.testing.assert_allclose(c, ref, rtol=1e-7, atol=1e-14)
    assert np.all(par.curvature_factors(np.inf) == 0)
    with pytest.raises(rc.errors.InputError, match="history_order"):
        MaterialParameters.from_material(rc.materials.sbr(), history_order=3)
