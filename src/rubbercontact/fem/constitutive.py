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
step late, and the lag adds ``O(ω Δt)`` to the storage modulus (+3.5 % at 40 steps per
cycle; the loss modulus is second order with either update, −0.29 % linear and +0.32 %
quadratic there). ``history_order = 2`` (the default of the sliding test) interpolates ``S_iso``
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
from ..materials.maxwell import GeneralizedMaxwell

#: Default bulk modulus [MPa]. Rubbers have K ≈ 1–3 GPa (filled SBR ≈ 2 GPa), far above
#: their shear moduli, so near-incompressibility is physical. 2000 MPa keeps the plane-strain
#: contact modulus 4G(3K+G)/(3K+4G) within G/K ≲ 1 % of the incompressible value 4G for the
#: algorithmic shear moduli met in sliding (G ≲ 20 MPa), while the mean-dilatation element
#: keeps the stiffness matrix free of locking.
DEFAULT_BULK_MODULUS = 2000.0

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
        states (see the module docstring).
    """

    mu: float
    kappa: float
    beta: np.ndarray
    tau: np.ndarray
    history_order: int = 1

    @classmethod
    def from_material(cls, material: GeneralizedMaxwell, bulk_modulus: float | None = None,
                      history_order: int = 1) -> MaterialParameters:
        """Build from a Prony series (Young's moduli of an incompressible solid)."""
        if history_order not in (1, 2):
            raise InputError(f"history_order: must be 1 (linear) or 2 (quadratic), got "
                             f"{history_order!r}")
        if not isinstance(material, GeneralizedMaxwell):
            raise InputError(f"material: expected a GeneralizedMaxwell, got "
                             f"{type(material).__name__}")
        kappa = (DEFAULT_BULK_MODULUS if bulk_modulus is None
                 else positive_scalar("bulk_modulus", bulk_modulus, unit="MPa"))
        mu = material.equilibrium_modulus / 3.0
        if kappa < 10 * mu:
            raise InputError(f"bulk_modulus: {kappa} MPa is not >> the shear modulus {mu:.4g} "
                             f"MPa; the model is meant for nearly incompressible rubber")
        beta = np.asarray(material.moduli, float) / material.equilibrium_modulus
        return cls(mu, kappa, beta, np.asarray(material.relaxation_times, float),
                   int(history_order))

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

    @classmethod
    def zeros(cls, shape: tuple[int, ...], n_branches: int) -> ViscousState:
        return cls(np.zeros(shape + (3,)), np.zeros((n_branches,) + shape + (3,)))

    def copy(self) -> ViscousState:
        return ViscousState(self.s_iso.copy(), self.q.copy(),
                            None if self.s_iso_prev is None else self.s_iso_prev.copy(),
                            self.dt_prev)


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
    return S, CC, J, Cinv, ViscousState(s_iso, q, state.s_iso, float(dt))


def cauchy_from_pk2(F: np.ndarray, S: np.ndarray) -> np.ndarray:
    """In-plane Cauchy stress ``σ = F S Fᵀ / J`` ``(..., 3)`` [MPa] from Voigt ``S``."""
    J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
    sig = F @ from_voigt(S) @ np.swapaxes(F, -1, -2)
    return to_voigt(sig) / J[..., None]
