"""Finite-strain generalized Maxwell solid (plane strain), vectorized over points.

Model (Simo 1987; Holzapfel 2000, §6.10), decoupled volumetric/isochoric:

* equilibrium branch: compressible neo-Hookean,
  ``ψ = U(J) + μ∞/2 (tr C̄ − 3)``, ``C̄ = J^{-2/3} C``,
  ``U(J) = κ/4 (J² − 1 − 2 ln J)`` (so ``U' = κ/2 (J − 1/J)``, ``U'' > 0`` for all J);
* one viscous branch per Maxwell element with a stress-like internal variable
  ``Q_i`` (second Piola–Kirchhoff, reference configuration) obeying the *linear*
  evolution equation ``Q̇_i + Q_i/τ_i = β_i Ṡ_iso`` ("finite linear
  viscoelasticity": large deformations, linear evolution, small deviation from
  equilibrium). ``S = S_vol + S_iso + Σ Q_i``.

Moduli: the Prony series stores Young's moduli of an incompressible material, so
shear moduli are ``μ∞ = E∞/3`` and ``μ_i = E_i/3``; ``β_i = E_i/E∞``. In the
small-strain limit the shear relaxation modulus is ``μ(t) = E(t)/3`` exactly.

Time integration: ``S_iso`` is taken piecewise linear in time over a step, which
makes the convolution integral exact::

    Q_i^{n+1} = e^{−ξ_i} Q_i^n + β_i γ_i (S_iso^{n+1} − S_iso^n),
    ξ_i = Δt/τ_i,   γ_i = (1 − e^{−ξ_i})/ξ_i.

For ``ξ_i ≫ 1`` a branch contributes ``β_i τ_i/Δt`` (its correct viscous stress
for a linear rate), never zero as a midpoint factor ``e^{−ξ/2}`` would give; for
``ξ_i → 0`` it is glassy (``γ → 1``). ``γ`` is evaluated with ``expm1`` so it is
accurate for any ``ξ`` and never ill-conditioned. The consistent tangent is
``ℂ = ℂ_vol + (1 + Σ β_i γ_i) ℂ_iso``.

The piecewise-linear input is second order for branches with ``ξ ≲ 1`` but only first
order for the fast ones (``τ_i ≪ Δt``, e.g. the SBR's τ ≤ 1.3e-5 s against the 5e-5 s
steps of a sliding test): there ``Q_i ≈ β_i τ_i (S^{n+1} − S^n)/Δt`` is the rate half a
step late, and the lag adds ``O(ω Δt)`` to the storage modulus (the loss modulus is
second order with either update; measured in docs/validation/fem_convergence.md).
``history_order = 2`` (the default of the sliding test) interpolates ``S_iso``
quadratically through ``t_{n−1}, t_n, t_{n+1}`` (steps ``h₀``, ``h``), again integrated
exactly::

    Q_i^{n+1} = e^{−ξ_i} Q_i^n + β_i [γ_i ΔS + c_i h² D₂],
    D₂ = (ΔS/h − ΔS_prev/h₀)/(h + h₀),   c_i = ∫₀¹ e^{−ξ_i(1−s)} (2s − 1) ds,

whose ``ξ → ∞`` limit is variable-step BDF2 (used for step ratios ``h/h₀`` in [0.4, 2.4],
where that is zero-stable; the linear update otherwise). The tangent factor becomes
``1 + Σ β_i (γ_i + c_i h/(h + h₀))``; the update stays linear in ``S_iso^{n+1}``, so a
step keeps its incremental potential.

Plane strain: in-plane tensors are 2 × 2, ``C₃₃ = 1``; traces and the volumetric
split use the 3-D tensor. Symmetric tensors use Voigt order ``[11, 22, 12]``;
fourth-order tangents are 3 × 3 with tensor (not engineering) components, to be
contracted with the engineering strain ``[E11, E22, 2 E12]``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validation import positive_scalar
from ..errors import InputError
from ..materials.protocol import PronyMaterial, check_prony

#: Default bulk modulus [MPa]. Rubbers have K ≈ 1–3 GPa (filled SBR ≈ 2 GPa), far above
#: their shear moduli, so near-incompressibility is physical. 2000 MPa keeps the plane-strain
#: contact modulus 4G(3K+G)/(3K+4G) within G/K ≲ 1 % of the incompressible value 4G for the
#: algorithmic shear moduli met in sliding (G ≲ 20 MPa), while the mean-dilatation element
#: keeps the stiffness matrix free of locking.
DEFAULT_BULK_MODULUS = 2000.0

#: Finite-strain viscoelastic models: Simo's (default) and Reese–Govindjee's.
VISCOUS_MODELS = ("simo", "reese-govindjee")

_VI = np.array([0, 1, 0])  # Voigt index -> (i, j)
_VJ = np.array([0, 1, 1])


@dataclass(frozen=True)
class MaterialParameters:
    """Parameters of the finite-strain model [MPa, s].

    Attributes
    ----------
    mu
        Equilibrium shear modulus ``μ∞ = E∞/3`` [MPa].
    kappa
        Bulk modulus ``κ`` [MPa].
    beta
        Branch ratios ``β_i = E_i/E∞`` [-].
    tau
        Relaxation times ``τ_i`` [s].
    history_order
        1: ``S_iso`` piecewise linear in time; 2: quadratic through the last three
        states (see the module docstring). Simo model only.
    viscous_model
        ``"simo"`` (stress-like internal variables, linear evolution; default) or
        ``"reese-govindjee"`` (multiplicative split ``F = F_e F_v`` per branch, see
        :func:`update_stress`).
    """

    mu: float
    kappa: float
    beta: np.ndarray
    tau: np.ndarray
    history_order: int = 1
    viscous_model: str = "simo"

    @classmethod
    def from_material(cls, material: PronyMaterial, bulk_modulus: float | None = None,
                      history_order: int = 1, viscous_model: str = "simo"
                      ) -> MaterialParameters:
        """Build from a Prony series (Young's moduli of an incompressible solid)."""
        if viscous_model not in VISCOUS_MODELS:
            raise InputError(f"viscous_model: must be one of {', '.join(VISCOUS_MODELS)}, "
                             f"got {viscous_model!r}")
        if history_order not in (1, 2):
            raise InputError(f"history_order: must be 1 (linear) or 2 (quadratic), got "
                             f"{history_order!r}")
        check_prony(material)
        kappa = (DEFAULT_BULK_MODULUS if bulk_modulus is None
                 else positive_scalar("bulk_modulus", bulk_modulus, unit="MPa"))
        mu = material.equilibrium_modulus / 3.0
        if kappa < 10 * mu:
            raise InputError(f"bulk_modulus: {kappa} MPa is not >> the shear modulus {mu:.4g} "
                             f"MPa; the model is meant for nearly incompressible rubber")
        beta = np.asarray(material.moduli, float) / material.equilibrium_modulus
        return cls(mu, kappa, beta, np.asarray(material.relaxation_times, float),
                   int(history_order), viscous_model)

    @property
    def n_branches(self) -> int:
        return int(self.beta.size)

    def step_factors(self, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """``(e^{−ξ_i}, γ_i)`` for a step ``dt`` [s], ``ξ_i = dt/τ_i``, exact for any ξ."""
        xi = dt / self.tau
        decay = np.exp(-xi)
        with np.errstate(divide="ignore", invalid="ignore"):
            gamma = np.where(xi > 1e-12, -np.expm1(-xi) / np.where(xi > 0, xi, 1.0), 1.0)
        return decay, gamma

    def curvature_factors(self, dt: float) -> np.ndarray:
        """``c_i = ∫₀¹ e^{−ξ_i(1−s)} (2s − 1) ds`` for a step ``dt`` [s], ``ξ_i = dt/τ_i``.

        The weight of the second divided difference of ``S_iso`` in the quadratic history
        update; ``c → ξ/6`` for ``ξ → 0`` (series below 1e-2, where the closed form
        cancels) and ``c → 1/ξ`` for ``ξ → ∞``.
        """
        xi = dt / self.tau
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            big = -np.expm1(-xi) / xi - 2.0 * (-np.expm1(-xi) - xi * np.exp(-xi)) / xi**2
            small = xi / 6.0 - xi**2 / 12.0 + xi**3 / 40.0
        return np.where(xi < 1e-2, small, np.where(np.isfinite(xi), big, 0.0))

    def algorithmic_shear_modulus(self, dt: float) -> float:
        """``μ∞ (1 + Σ β_i γ_i)`` [MPa]: the shear stiffness seen by one step ``dt``."""
        _, gamma = self.step_factors(dt)
        return float(self.mu * (1.0 + np.sum(self.beta * gamma)))


def to_voigt(A: np.ndarray) -> np.ndarray:
    """``(..., 2, 2)`` symmetric -> ``(..., 3)`` as ``[A11, A22, A12]``."""
    return A[..., _VI, _VJ]


def from_voigt(a: np.ndarray) -> np.ndarray:
    """``(..., 3)`` -> ``(..., 2, 2)`` symmetric."""
    out = np.empty(a.shape[:-1] + (2, 2))
    out[..., 0, 0] = a[..., 0]
    out[..., 1, 1] = a[..., 1]
    out[..., 0, 1] = out[..., 1, 0] = a[..., 2]
    return out


def _outer(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """``A_ij B_kl`` in Voigt form ``(..., 3, 3)``."""
    return to_voigt(A)[..., :, None] * to_voigt(B)[..., None, :]


def _odot(A: np.ndarray) -> np.ndarray:
    """``(A_ik A_jl + A_il A_jk)/2`` in Voigt form ``(..., 3, 3)``."""
    i, j = _VI[:, None], _VJ[:, None]
    k, l = _VI[None, :], _VJ[None, :]
    return 0.5 * (A[..., i, k] * A[..., j, l] + A[..., i, l] * A[..., j, k])


def kinematics(F: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(J, C⁻¹, I1)`` of in-plane deformation gradients ``F`` ``(..., 2, 2)`` (F33 = 1)."""
    J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
    C = np.swapaxes(F, -1, -2) @ F
    detC = J * J
    Cinv = np.empty_like(C)
    Cinv[..., 0, 0] = C[..., 1, 1] / detC
    Cinv[..., 1, 1] = C[..., 0, 0] / detC
    Cinv[..., 0, 1] = Cinv[..., 1, 0] = -C[..., 0, 1] / detC
    I1 = C[..., 0, 0] + C[..., 1, 1] + 1.0
    return J, Cinv, I1


def isochoric_stress(mu: float, J: np.ndarray, Cinv: np.ndarray, I1: np.ndarray,
                     tangent: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
    """Neo-Hookean isochoric 2nd Piola–Kirchhoff stress and material tangent.

    ``S_iso = μ J^{−2/3} (I − I1/3 C⁻¹)`` (Voigt, MPa) and
    ``ℂ_iso = 2 ∂S_iso/∂C = 2μ J^{−2/3} [−(I⊗C⁻¹ + C⁻¹⊗I)/3 + I1/9 C⁻¹⊗C⁻¹ + I1/3 C⁻¹⊙C⁻¹]``.
    """
    jm23 = J ** (-2.0 / 3.0)
    eye = np.broadcast_to(np.eye(2), Cinv.shape)
    S = (mu * jm23)[..., None] * to_voigt(eye - (I1 / 3.0)[..., None, None] * Cinv)
    if not tangent:
        return S, None
    CC = (2 * mu * jm23)[..., None, None] * (
        -(_outer(eye, Cinv) + _outer(Cinv, eye)) / 3.0
        + (I1 / 9.0)[..., None, None] * _outer(Cinv, Cinv)
        + (I1 / 3.0)[..., None, None] * _odot(Cinv))
    return S, CC


def volumetric_stress(p: np.ndarray, J: np.ndarray, Cinv: np.ndarray,
                      tangent: bool = True) -> tuple[np.ndarray, np.ndarray | None]:
    """``S_vol = p J C⁻¹`` and ``2 ∂S_vol/∂C|_p = p J (C⁻¹⊗C⁻¹ − 2 C⁻¹⊙C⁻¹)``."""
    pJ = p * J
    S = pJ[..., None] * to_voigt(Cinv)
    if not tangent:
        return S, None
    CC = pJ[..., None, None] * (_outer(Cinv, Cinv) - 2.0 * _odot(Cinv))
    return S, CC


def pressure(kappa: float, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(U'(θ), U''(θ))`` for ``U = κ/4 (θ² − 1 − 2 ln θ)`` [MPa]."""
    return 0.5 * kappa * (theta - 1.0 / theta), 0.5 * kappa * (1.0 + 1.0 / theta**2)


@dataclass
class ViscousState:
    """History at every quadrature point at the end of the last converged step.

    Attributes
    ----------
    s_iso
        Isochoric equilibrium stress ``S_iso^n`` ``(npts, 3)`` [MPa].
    q
        Branch stresses ``Q_i^n`` ``(n_branches, npts, 3)`` [MPa].
    """

    s_iso: np.ndarray
    q: np.ndarray
    #: ``S_iso^{n−1}`` and the step ``t_n − t_{n−1}`` [s] that led to ``S_iso^n`` (None / 0
    #: before the first step): the quadratic history integration needs them.
    s_iso_prev: np.ndarray | None = None
    dt_prev: float = 0.0
    #: Reese–Govindjee only: ``C_v⁻¹`` per branch ``(n_branches, npts, 4)`` as
    #: ``[11, 22, 12, 33]`` (identity = undeformed, relaxed).
    cv_inv: np.ndarray | None = None

    @classmethod
    def zeros(cls, shape: tuple[int, ...], n_branches: int,
              viscous_model: str = "simo") -> ViscousState:
        if viscous_model == "reese-govindjee":
            # the branches live in C_v⁻¹; Simo's stress-like q has no branches here
            cv_inv = np.zeros((n_branches,) + shape + (4,))
            cv_inv[..., [0, 1, 3]] = 1.0
            return cls(np.zeros(shape + (3,)), np.zeros((0,) + shape + (3,)), cv_inv=cv_inv)
        return cls(np.zeros(shape + (3,)), np.zeros((n_branches,) + shape + (3,)))

    def copy(self) -> ViscousState:
        return ViscousState(self.s_iso.copy(), self.q.copy(),
                            None if self.s_iso_prev is None else self.s_iso_prev.copy(),
                            self.dt_prev,
                            None if self.cv_inv is None else self.cv_inv.copy())


def update_stress(params: MaterialParameters, F: np.ndarray, p: np.ndarray,
                  state: ViscousState, dt: float, tangent: bool = True):
    """Total 2nd Piola–Kirchhoff stress, tangent and trial history for one step.

    Parameters
    ----------
    params
        Material parameters.
    F
        Deformation gradients ``(..., 2, 2)`` at the end of the step.
    p
        Pressure ``U'(θ)`` [MPa] at the points, shape ``F.shape[:-2]`` (the element's
        mean-dilatation pressure, constant per element).
    state
        History at the start of the step (not modified).
    dt
        Step [s] (> 0; ``np.inf`` gives the fully relaxed state).
    tangent
        Also return the tangent.

    Returns
    -------
    S, CC, J, Cinv, new_state
        ``S`` ``(..., 3)``, ``CC`` ``(..., 3, 3)`` (or None), the Jacobian, ``C⁻¹`` and the
        trial history to store if the step is accepted.
    """
    J, Cinv, I1 = kinematics(F)
    s_iso, cc_iso = isochoric_stress(params.mu, J, Cinv, I1, tangent)
    s_vol, cc_vol = volumetric_stress(p, J, Cinv, tangent)
    if params.viscous_model == "reese-govindjee" and params.n_branches:
        nb, shape = params.n_branches, F.shape[:-2]
        Fp = F.reshape(-1, 2, 2)
        cv = state.cv_inv.reshape(nb, -1, 4)
        s_neq, cv_new, eps = _rg_stress(params, Fp, cv, dt)
        S = s_iso + s_vol + s_neq.reshape(shape + (3,))
        CC = None
        if tangent:
            cc_neq = _rg_tangent(params, Fp, cv, dt, s_neq, eps).reshape(shape + (3, 3))
            CC = cc_iso + cc_vol + cc_neq
        return S, CC, J, Cinv, ViscousState(s_iso, state.q, state.s_iso, float(dt),
                                            cv_new.reshape(state.cv_inv.shape))
    if params.n_branches:
        decay, gamma = params.step_factors(dt)
        nb = params.n_branches
        ds = s_iso - state.s_iso
        q = decay[:, None, None] * state.q.reshape(nb, -1, 3)
        ratio = dt / state.dt_prev if state.dt_prev > 0 else np.inf
        # Quadratic S_iso(t) through the last three states: the second divided difference
        # enters with weight c_i. Only for step ratios in [0.4, 2.4], where variable-step
        # BDF2 (its ξ → ∞ limit) is zero-stable; else (first step, settle, phase changes)
        # the linear update.
        if params.history_order == 2 and state.s_iso_prev is not None and 0.4 <= ratio <= 2.4:
            c = params.curvature_factors(dt)
            r = dt / (dt + state.dt_prev)
            weight = gamma + c * r
            ds_prev = (state.s_iso - state.s_iso_prev).reshape(1, -1, 3)
            q = q - (params.beta * c * r * ratio)[:, None, None] * ds_prev
        else:
            weight = gamma
        bg = params.beta * weight
        q = (q + bg[:, None, None] * ds.reshape(1, -1, 3)).reshape(state.q.shape)
        S = s_iso + s_vol + q.sum(axis=0)
        factor = 1.0 + bg.sum()
    else:
        q = state.q
        S = s_iso + s_vol
        factor = 1.0
    CC = factor * cc_iso + cc_vol if tangent else None
    return S, CC, J, Cinv, ViscousState(s_iso, q, state.s_iso, float(dt), state.cv_inv)


def cauchy_from_pk2(F: np.ndarray, S: np.ndarray) -> np.ndarray:
    """In-plane Cauchy stress ``σ = F S Fᵀ / J`` ``(..., 3)`` [MPa] from Voigt ``S``."""
    J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
    sig = F @ from_voigt(S) @ np.swapaxes(F, -1, -2)
    return to_voigt(sig) / J[..., None]


# ----------------------------------------------------------------------------------------
# Reese–Govindjee (1998) finite-strain viscoelasticity
# ----------------------------------------------------------------------------------------
#: Local Newton tolerance: relative size of the last step on the elastic logarithmic
#: strains; far below the 1e-7 perturbation of the finite-difference tangent, so the
#: tangent is smooth (Newton is quadratic, so the iterate after such a step is exact
#: to round-off).
RG_LOCAL_TOL = 1e-12
RG_LOCAL_MAX_ITER = 50
#: Relative perturbation of C for the branch tangent (forward differences; truncation
#: ~1e-7, round-off ~1e-16/1e-7 and local tolerance 1e-13/1e-7 ≈ 1e-6 of the branch stress).
RG_TANGENT_STEP = 1e-7


def _sym_eig2(a11: np.ndarray, a22: np.ndarray, a12: np.ndarray):
    """Eigenvalues ``(λ1 ≥ λ2)`` and the unit eigenvector ``(c, s)`` of λ1 of 2 × 2 symmetric
    matrices (closed form; any basis when λ1 = λ2)."""
    half = 0.5 * (a11 - a22)
    mean = 0.5 * (a11 + a22)
    rad = np.hypot(half, a12)
    phi = 0.5 * np.arctan2(a12, half)
    return mean + rad, mean - rad, np.cos(phi), np.sin(phi)


def _rg_local_solve(eps_trial: np.ndarray, xi: np.ndarray,
                    guess: np.ndarray | None = None) -> np.ndarray:
    """Deviatoric elastic log strains after one implicit step of the RG flow rule.

    Solves ``ε + ξ/2 (e − ē) = ε_tr`` for every point, ``e_A = exp(2ε_A)``, ``ē`` their
    mean, ``ξ = Δt/τ`` (with ``τ = η/μ``, the linear relaxation time): the
    exponential-map backward-Euler step of ``−½ L_v b_e b_e⁻¹ = τ_neq/(2η)`` for an
    isochoric neo-Hookean branch, written in the principal axes of ``b_e^tr`` (they
    coincide with those of ``b_e`` for isotropy). It is the stationarity condition of the
    convex ``½|ε − ε_tr|² + ξ/4 Σ e_A``, so Newton from the linearized solution
    ``ε_tr/(1 + ξ)`` converges for any ξ. Points that do not converge in
    ``RG_LOCAL_MAX_ITER`` iterations come back NaN: an inadmissible state, on which the
    global solver cuts the step.

    Parameters
    ----------
    eps_trial
        Deviatoric trial log strains ``(nb, npts, 3)`` (sum zero).
    xi
        ``Δt/τ_i`` ``(nb,)``.
    guess
        Starting point (default the linearized solution).
    """
    # Component-first layout: sums over the three principal values become two additions
    # of whole arrays (numpy reductions over a length-3 last axis are slow).
    et = np.moveaxis(eps_trial, -1, 0)
    x = xi[:, None]
    eps = et / (1.0 + x) if guess is None else np.moveaxis(guess, -1, 0).copy()
    eps = np.where(np.isfinite(eps), eps, et / (1.0 + x))
    ok = np.isfinite(et[0]) & np.isfinite(et[1]) & np.isfinite(et[2])
    for _ in range(RG_LOCAL_MAX_ITER):
        em1 = np.expm1(2.0 * eps)
        r = eps + 0.5 * x * (em1 - (em1[0] + em1[1] + em1[2]) / 3.0) - et
        # Exactly deviatoric in exact arithmetic; dropping the round-off in the mean keeps
        # it out of the step (the Jacobian is 1, not 1 + ξ, along (1, 1, 1)).
        r -= (r[0] + r[1] + r[2]) / 3.0
        # Jacobian I + ξ (diag(e) − 1 eᵀ/3) = D − u eᵀ with D = diag(1 + ξ e), u = ξ/3:
        # Sherman–Morrison, elementwise.
        e = 1.0 + em1
        d_inv = 1.0 / (1.0 + x * e)
        dr, du = d_inv * r, d_inv * (x / 3.0)
        edr = e[0] * dr[0] + e[1] * dr[1] + e[2] * dr[2]
        # 1 − eᵀD⁻¹u written without cancellation (it → 0 as ξ → ∞)
        denom = (d_inv[0] + d_inv[1] + d_inv[2]) / 3.0
        step = dr + du * (edr / denom)
        eps = eps - step
        # Relative step test: Newton is quadratic, so after such a step the iterate is
        # exact to round-off. (expm1 keeps e − ē accurate for the tiny elastic strains
        # ~ε_tr/ξ of the branches with ξ ≫ 1.)
        size = np.maximum(np.abs(eps[0]), np.maximum(np.abs(eps[1]), np.abs(eps[2])))
        big = np.maximum(np.abs(step[0]), np.maximum(np.abs(step[1]), np.abs(step[2])))
        if not np.any(ok & ~(big <= RG_LOCAL_TOL * np.maximum(size, 1e-300))):
            break
    else:
        ok &= big <= RG_LOCAL_TOL * np.maximum(size, 1e-300)
    eps[:, ~ok] = np.nan
    return np.moveaxis(eps, 0, -1)


def _rg_stress(params: MaterialParameters, F: np.ndarray, cv_inv: np.ndarray, dt: float,
               guess: np.ndarray | None = None):
    """Sum of the RG branch PK2 stresses ``(npts, 3)``, the new ``C_v⁻¹`` ``(nb, npts, 4)``
    and the deviatoric elastic log strains ``(nb, npts, 3)`` (a starting point for nearby
    solves).

    ``F`` is ``(npts, 2, 2)``; ``cv_inv`` stores ``[C_v⁻¹₁₁, C_v⁻¹₂₂, C_v⁻¹₁₂, C_v⁻¹₃₃]``
    per branch (plane strain: the 33 direction is principal).
    """
    nb = params.n_branches
    a11, a22, a12, a33 = (cv_inv[..., k] for k in range(4))
    f11, f12, f21, f22 = F[:, 0, 0], F[:, 0, 1], F[:, 1, 0], F[:, 1, 1]
    # b_e^tr = F C_v⁻¹ Fᵀ (in plane); b_e^tr₃₃ = C_v⁻¹₃₃.
    t11, t12 = f11 * a11 + f12 * a12, f11 * a12 + f12 * a22
    t21, t22 = f21 * a11 + f22 * a12, f21 * a12 + f22 * a22
    b11, b22, b12 = t11 * f11 + t12 * f12, t21 * f21 + t22 * f22, t11 * f21 + t12 * f22
    l1, l2, c, s = _sym_eig2(b11, b22, b12)
    with np.errstate(invalid="ignore", divide="ignore"):
        eps_tr = 0.5 * np.log(np.stack([l1, l2, a33], axis=-1))
    vol = eps_tr.mean(axis=-1, keepdims=True)
    xi = np.full(nb, np.inf) if not np.isfinite(dt) else dt / params.tau
    eps = _rg_local_solve(eps_tr - vol, np.minimum(xi, 1e200), guess)
    em1 = np.expm1(2.0 * eps)
    # Kirchhoff branch stress μ_i dev(b̄_e) in principal axes; b_e = J_e^{2/3} exp(2ε_dev).
    tau = (params.mu * params.beta)[:, None, None] * (em1 - em1.mean(axis=-1, keepdims=True))
    be = np.exp(2.0 * (eps + vol))

    def in_plane(v):  # Σ_A v_A n_A ⊗ n_A (in plane) as (11, 22, 12)
        return (v[..., 0] * c * c + v[..., 1] * s * s, v[..., 0] * s * s + v[..., 1] * c * c,
                (v[..., 0] - v[..., 1]) * c * s)

    J = f11 * f22 - f12 * f21
    g11, g12, g21, g22 = f22 / J, -f12 / J, -f21 / J, f11 / J   # F⁻¹

    def pull_back(x11, x22, x12):  # F⁻¹ X F⁻ᵀ
        u11, u12 = g11 * x11 + g12 * x12, g11 * x12 + g12 * x22
        u21, u22 = g21 * x11 + g22 * x12, g21 * x12 + g22 * x22
        return u11 * g11 + u12 * g12, u21 * g21 + u22 * g22, u11 * g21 + u12 * g22

    s11, s22, s12 = pull_back(*in_plane(tau))
    S = np.stack([s11.sum(axis=0), s22.sum(axis=0), s12.sum(axis=0)], axis=-1)
    n11, n22, n12 = pull_back(*in_plane(be))
    new = np.stack([n11, n22, n12, be[..., 2]], axis=-1)
    return S, new, eps


def _rg_tangent(params: MaterialParameters, F: np.ndarray, cv_inv: np.ndarray, dt: float,
                S0: np.ndarray, eps0: np.ndarray) -> np.ndarray:
    """``2 ∂S_neq/∂C`` ``(npts, 3, 3)`` by forward differences in C (see RG_TANGENT_STEP).

    ``F + ½ F⁻ᵀ δC`` changes ``C`` by ``δC`` to first order; the columns are the
    engineering-strain components ``[E11, E22, 2 E12]`` like the analytic tangents.
    """
    h = RG_TANGENT_STEP * np.maximum(1.0, np.abs(F).max(axis=(-1, -2)))[:, None, None]
    Finv_t = np.swapaxes(np.linalg.inv(F), -1, -2)
    out = np.empty(S0.shape + (3,))
    for col, dC in enumerate((np.array([[2.0, 0.0], [0.0, 0.0]]),
                              np.array([[0.0, 0.0], [0.0, 2.0]]),
                              np.array([[0.0, 1.0], [1.0, 0.0]]))):
        Fp = F + 0.5 * h * (Finv_t @ dC)
        out[..., col] = (_rg_stress(params, Fp, cv_inv, dt, eps0)[0] - S0) / h[:, 0]
    # The step has an incremental potential, so the exact tangent is symmetric.
    return 0.5 * (out + np.swapaxes(out, -1, -2))
