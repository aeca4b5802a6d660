"""Reese–Govindjee finite-strain viscoelasticity against closed forms and an ODE reference.

References used (none of them is output of the code under test):

* glassy and relaxed limits: the compressible neo-Hookean solid with the summed or the
  equilibrium shear modulus (closed form, ``test_fem_material.cauchy_closed_form``);
* small strain: the complex modulus of a Prony series under the backward-Euler recurrence
  of each Maxwell branch (a closed-form transfer function), and its ``dt → 0`` limit
  ``E(ω)/3``;
* finite strain: the flow rule ``ε̇_A = −(e_A − ē)/(2τ)`` of a branch held at fixed
  deformation, integrated by ``scipy.integrate.solve_ivp`` to 1e-11;
* tangents: central finite differences; objectivity: a superposed rotation.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from test_fem_material import (
    CASES,
    _distorted_element,
    cauchy_closed_form,
    element_tangent_and_fd,
    harmonic_shear_moduli,
    material_tangent_and_fd,
)

import rubbercontact as rc
from rubbercontact.fem.constitutive import (
    MaterialParameters,
    ViscousState,
    cauchy_from_pk2,
    update_stress,
)
from rubbercontact.fem.element import element_arrays, shape_gradients

RG = "reese-govindjee"


def rg_params(material=None):
    return MaterialParameters.from_material(material or rc.materials.sbr(), viscous_model=RG)


def relaxed(n, par):
    return ViscousState.zeros((n,), par.n_branches, RG)


def _pressure(F, kappa):
    J = np.linalg.det(F)
    return kappa / 2 * (J - 1 / J)


@pytest.mark.parametrize("name", list(CASES))
def test_glassy_and_relaxed_limits_are_neo_hookean(name):
    F = CASES[name]
    par = rg_params()
    p = np.array([_pressure(F, par.kappa)])
    mu_glassy = par.mu * (1 + par.beta.sum())
    # A step of 1e-16 s from the relaxed state: every branch is elastic to ξ = Δt/τ_min
    # ≈ 2.4e-7, so the solid is neo-Hookean with μ(1 + Σβ) to that relative accuracy.
    S, _, _, _, st = update_stress(par, F[None], p, relaxed(1, par), 1e-16, tangent=False)
    np.testing.assert_allclose(cauchy_from_pk2(F[None], S)[0],
                               cauchy_closed_form(F, mu_glassy, par.kappa),
                               rtol=1e-6, atol=1e-6 * mu_glassy)
    # Then held for an infinite step: fully relaxed, the equilibrium branch alone (exact).
    S, _, _, _, _ = update_stress(par, F[None], p, st, np.inf, tangent=False)
    np.testing.assert_allclose(cauchy_from_pk2(F[None], S)[0],
                               cauchy_closed_form(F, par.mu, par.kappa),
                               rtol=1e-9, atol=1e-9 * mu_glassy)


def test_small_strain_is_the_backward_euler_prony_series():
    # Three branches with ωτ = 0.1, 1, 10 and one with ωτ = 1e-4 (ξ ≫ 1, the regime of
    # the SBR's fast branches in sliding); 40 steps per cycle. Each branch's discrete
    # recurrence ε_e^{n+1}(1 + ξ) = ε_e^n + Δε has the transfer function
    # (1 − z⁻¹)/(1 + ξ − z⁻¹), z = e^{iωΔt}: the exact response of the discrete model.
    omega = 1000.0
    tau = np.array([1e-4, 1e-3, 1e-2, 1e-7])
    mat = rc.materials.GeneralizedMaxwell(2.0, [3.0, 5.0, 4.0, 50.0], tau)
    par = rg_params(mat)
    n_cycles = int(np.ceil(12 * tau.max() * omega / (2 * np.pi))) + 1
    g1, g2, dt = harmonic_shear_moduli(par, omega, 40, n_cycles)
    zi = np.exp(-1j * omega * dt)
    xi = dt / tau
    discrete = par.mu + np.sum(par.mu * par.beta * (1 - zi) / (1 + xi - zi))
    # γ0 = 1e-5: the non-linearity is O(γ0²); the start transient e^{-12} ≈ 6e-6.
    assert g1 == pytest.approx(discrete.real, rel=1e-4)
    assert g2 == pytest.approx(discrete.imag, rel=1e-4)
    # ... and that is first order in Δt away from the Prony series E(ω)/3:
    exact = mat.complex_modulus(omega) / 3.0
    err40 = abs(complex(g1, g2) - exact) / abs(exact)
    g1b, g2b, _ = harmonic_shear_moduli(par, omega, 160, n_cycles)
    err160 = abs(complex(g1b, g2b) - exact) / abs(exact)
    assert err160 < 0.02
    assert 2.5 < err40 / err160 < 6.0  # ratio 4 for first order


def test_finite_strain_relaxation_follows_the_flow_rule():
    # One branch, suddenly sheared to γ = 1 and held: the principal axes of b_e are fixed,
    # and the elastic log strains obey ε̇_A = −(e_A − ē)/(2τ), e_A = exp(2ε_A) — an ODE
    # integrated here independently. The branch Cauchy shear stress is
    # μ₁ Σ_A (e_A − ē) n_Ax n_Ay / J (J = 1 in simple shear).
    tau1, E1 = 1e-3, 9.0
    mat = rc.materials.GeneralizedMaxwell(3.0, [E1], [tau1])
    par = rg_params(mat)
    g = 1.0
    F = np.array([[[1.0, g], [0.0, 1.0]]])
    b = F[0] @ F[0].T
    lam, vec = np.linalg.eigh(b)
    eps0 = np.array([0.5 * np.log(lam[1]), 0.5 * np.log(lam[0]), 0.0])
    n1, n2 = vec[:, 1], vec[:, 0]

    def rhs(_t, eps):
        e = np.exp(2 * eps)
        return -(e - e.mean()) / (2 * tau1)

    n_steps, t_end = 400, 2 * tau1
    t_eval = np.linspace(0, t_end, n_steps + 1)[1:]
    ref = solve_ivp(rhs, (0, t_end), eps0, t_eval=t_eval, rtol=1e-11, atol=1e-14,
                    method="LSODA").y.T
    e = np.exp(2 * ref)
    dev = e - e.mean(axis=1, keepdims=True)
    sxy_ref = par.mu * par.beta[0] * (dev[:, 0] * n1[0] * n1[1] + dev[:, 1] * n2[0] * n2[1])
    sxy_eq = cauchy_closed_form(F[0], par.mu, par.kappa)[2]

    st = relaxed(1, par)
    _, _, _, _, st = update_stress(par, F, np.zeros(1), st, 1e-14, tangent=False)
    sxy = []
    for _ in range(n_steps):
        S, _, _, _, st = update_stress(par, F, np.zeros(1), st, t_end / n_steps,
                                       tangent=False)
        sxy.append(cauchy_from_pk2(F, S)[0, 2] - sxy_eq)
    sxy = np.array(sxy)
    # Backward Euler at Δt = τ/200: relative error ≈ Δt/(2τ)·(decay) ≲ 0.3 %; compare
    # over the first time constant, where the branch stress is still ≥ e^{-1} of its start.
    first = t_eval <= tau1
    np.testing.assert_allclose(sxy[first], sxy_ref[first], rtol=5e-3)
    # Finite strain shows: the relaxation is not a single exponential (Simo's model would
    # give exactly e^{-t/τ} here); the check above is therefore not the linear one.
    linear = sxy_ref[0] * np.exp(-(t_eval - t_eval[0]) / tau1)
    assert np.max(np.abs(sxy_ref[first] - linear[first]) / np.abs(linear[first])) > 0.02


def test_superposed_rotation_leaves_material_quantities_unchanged():
    par = rg_params()
    rng = np.random.default_rng(3)
    n = 5
    F0 = np.eye(2) + 0.3 * rng.standard_normal((n, 2, 2))
    F1 = F0 + 0.2 * rng.standard_normal((n, 2, 2))
    p = np.full(n, 0.3)
    st = update_stress(par, F0, p, relaxed(n, par), 2e-5, tangent=False)[-1]
    a = update_stress(par, F1, p, st, 7e-5)
    c, s = np.cos(0.7), np.sin(0.7)
    R = np.array([[c, -s], [s, c]])
    b = update_stress(par, R @ F1, p, st, 7e-5)
    scale = np.abs(a[0]).max()
    np.testing.assert_allclose(b[0], a[0], atol=1e-11 * scale)          # PK2
    np.testing.assert_allclose(b[4].cv_inv, a[4].cv_inv, atol=1e-12)    # C_v⁻¹
    np.testing.assert_allclose(b[1], a[1], atol=1e-5 * np.abs(a[1]).max())  # FD tangent


def test_constitutive_tangent_matches_finite_differences():
    par = rg_params()
    rng = np.random.default_rng(1)
    n = 6
    F = np.eye(2) + 0.25 * rng.standard_normal((n, 2, 2))
    p = np.full(n, 0.7)
    st = update_stress(par, np.eye(2) + 0.2 * rng.standard_normal((n, 2, 2)), p,
                       relaxed(n, par), 3e-5, tangent=False)[-1]
    CC, num = material_tangent_and_fd(par, F, p, st, 3e-5)
    # the code's tangent is a forward difference with step 1e-7: error ~1e-6 relative
    np.testing.assert_allclose(num, CC, atol=1e-5 * np.abs(CC).max())


def test_element_tangent_matches_finite_differences_and_is_symmetric():
    par = rg_params()
    rng = np.random.default_rng(2)
    Xe = np.concatenate([_distorted_element(), _distorted_element() + [2.0, 0.0]])
    dNdX, w, _ = shape_gradients(Xe)
    ue = 0.1 * rng.standard_normal((2, 4, 2))
    st = ViscousState.zeros((2, 4), par.n_branches, RG)
    st = element_arrays(par, dNdX, w, 0.05 * rng.standard_normal((2, 4, 2)), st, 5e-5).state
    ke, num = element_tangent_and_fd(par, dNdX, w, ue, st, 1e-4)
    np.testing.assert_allclose(num, ke, atol=1e-5 * np.abs(ke).max())
    np.testing.assert_allclose(ke, np.swapaxes(ke, 1, 2), atol=1e-10 * np.abs(ke).max())


def test_inverted_state_is_reported_as_nan_not_raised():
    par = rg_params()
    F = np.array([[[1.0, 0.0], [0.0, -0.5]]])   # J < 0
    with np.errstate(invalid="ignore"):   # as in the element evaluation
        S, _, _, _, _ = update_stress(par, F, np.zeros(1), relaxed(1, par), 1e-4,
                                      tangent=False)
    assert np.all(np.isnan(S))


def test_unknown_viscous_model_is_rejected():
    with pytest.raises(rc.errors.InputError, match="viscous_model"):
        MaterialParameters.from_material(rc.materials.sbr(), viscous_model="maxwell")
