"""Q1/P0 mean-dilatation element (total Lagrangian), vectorized over all elements.

Why Q1/P0 mean dilatation (Simo, Taylor & Pister 1985; Hughes 1980): the
three-field Hu–Washizu form with a constant pressure ``p`` and dilatation ``θ``
per element removes volumetric locking of the nearly incompressible rubber; both
fields are condensed at element level (``θ = v_e/V_e``, ``p = U'(θ)``), so the
unknowns stay the nodal displacements and — unlike F-bar — the tangent stays
**symmetric** (a rank-one element term ``U''(θ)/V_e · b bᵀ`` with ``b = ∂v_e/∂u``),
which keeps symmetric direct solvers usable. The isochoric part and the viscous
branches use the full 2 × 2 Gauss rule; only the volumetric response is averaged,
so the element has no hourglass modes. The pressure is element-wise constant; the
contact pressure itself comes from the nodal penalty forces (see ``contact.py``)
and shows no checkerboard (tested).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .constitutive import MaterialParameters, ViscousState, pressure, update_stress

_G = 1.0 / np.sqrt(3.0)
#: Gauss points (ξ, η) of the 2 × 2 rule, all with weight 1.
GAUSS = np.array([[-_G, -_G], [_G, -_G], [_G, _G], [-_G, _G]])
_XI = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], float)


def shape_gradients(Xe: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Reference gradients of the Q1 shape functions at the Gauss points.

    Parameters
    ----------
    Xe
        Element reference coordinates ``(n_el, 4, 2)`` [mm].

    Returns
    -------
    dNdX
        ``(n_el, 4 gauss, 4 nodes, 2)`` [1/mm].
    w
        Integration weights ``det J0 · 1`` ``(n_el, 4)`` [mm²].
    N
        Shape function values ``(4 gauss, 4 nodes)``.
    """
    xi, eta = GAUSS[:, 0:1], GAUSS[:, 1:2]
    N = 0.25 * (1 + _XI[:, 0] * xi) * (1 + _XI[:, 1] * eta)
    dN = np.stack([0.25 * _XI[:, 0] * (1 + _XI[:, 1] * eta),
                   0.25 * _XI[:, 1] * (1 + _XI[:, 0] * xi)], axis=-1)  # (g, a, 2)
    jac = np.einsum("gak,eai->egik", dN, Xe)  # dX_i/dξ_k
    det = jac[..., 0, 0] * jac[..., 1, 1] - jac[..., 0, 1] * jac[..., 1, 0]
    if np.any(det <= 0):
        raise ValueError("element with non-positive reference Jacobian (check node order)")
    inv = np.empty_like(jac)
    inv[..., 0, 0] = jac[..., 1, 1] / det
    inv[..., 1, 1] = jac[..., 0, 0] / det
    inv[..., 0, 1] = -jac[..., 0, 1] / det
    inv[..., 1, 0] = -jac[..., 1, 0] / det
    dNdX = np.einsum("gak,egki->egai", dN, inv)
    return dNdX, det, N


@dataclass
class ElementOutput:
    """Element vectors, matrices and trial history of one evaluation."""

    fe: np.ndarray               # (n_el, 8) internal forces [N/mm]
    ke: np.ndarray | None        # (n_el, 8, 8) tangent [N/mm²]
    state: ViscousState          # trial history at the Gauss points
    S: np.ndarray                # (n_el, 4, 3) 2nd PK stress [MPa]
    F: np.ndarray                # (n_el, 4, 2, 2)
    theta: np.ndarray            # (n_el,) mean dilatation [-]
    p: np.ndarray                # (n_el,) pressure U'(θ) [MPa]


def deformation_gradient(dNdX: np.ndarray, ue: np.ndarray) -> np.ndarray:
    """``F = I + Σ_a u_a ⊗ ∇₀N_a`` ``(n_el, 4, 2, 2)`` from displacements ``(n_el, 4, 2)``."""
    return np.eye(2) + np.einsum("eai,egaJ->egiJ", ue, dNdX)


def strain_operator(dNdX: np.ndarray, F: np.ndarray) -> np.ndarray:
    """``B[e, g, I, 8]``: the Green–Lagrange strain increment ``δE_I`` (Voigt, engineering
    shear) per unit element displacement ``δu_{a,i}`` at every Gauss point."""
    nel = F.shape[0]
    B = np.empty((nel, 4, 3, 4, 2))
    dN1 = dNdX[..., 0][..., :, None]  # (e, g, a, 1)
    dN2 = dNdX[..., 1][..., :, None]
    F1 = F[..., None, :, 0]           # F_{i1} -> (e, g, 1, i)
    F2 = F[..., None, :, 1]
    B[:, :, 0] = dN1 * F1
    B[:, :, 1] = dN2 * F2
    B[:, :, 2] = dN2 * F1 + dN1 * F2
    return B.reshape(nel, 4, 3, 8)


def internal_forces(B: np.ndarray, w: np.ndarray, S: np.ndarray) -> np.ndarray:
    """Element internal forces ``Σ_g w Bᵀ S`` ``(n_el, 8)`` [N/mm]."""
    nel = B.shape[0]
    wS = w[..., None] * S
    return (wS.reshape(nel, 1, 12) @ B.reshape(nel, 12, 8)).reshape(nel, 8)


def tangent_matrices(B: np.ndarray, w: np.ndarray, CC: np.ndarray, S: np.ndarray,
                     dNdX: np.ndarray, F: np.ndarray, dp: np.ndarray) -> np.ndarray:
    """Element tangents ``(n_el, 8, 8)``: material part ``Bᵀ ℂ B``, geometric stiffness
    ``δ_ik ∇N_a·S·∇N_b`` and the mean-dilatation rank-one term ``U''(θ)/V0 · b bᵀ``."""
    nel = B.shape[0]
    # Batched small matmuls with the Gauss points folded into the contraction index
    # are several times faster than einsum here.
    DB = (CC @ B).reshape(nel, 12, 8)                       # (e, g·I, 8)
    Bt = (B * w[..., None, None]).transpose(0, 3, 1, 2).reshape(nel, 8, 12)
    ke = Bt @ DB
    wS = w[..., None] * S
    Sm = np.empty((nel, 4, 2, 2))
    Sm[..., 0, 0] = wS[..., 0]
    Sm[..., 1, 1] = wS[..., 1]
    Sm[..., 0, 1] = Sm[..., 1, 0] = wS[..., 2]
    T = (dNdX @ Sm).transpose(0, 2, 1, 3).reshape(nel, 4, 8)
    G = T @ dNdX.transpose(0, 1, 3, 2).reshape(nel, 8, 4)
    ke4 = ke.reshape(nel, 4, 2, 4, 2)
    ke4[:, :, 0, :, 0] += G
    ke4[:, :, 1, :, 1] += G
    # b_{a,i} = Σ_g w J ∂N_a/∂x_i
    J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
    Finv = np.empty_like(F)
    Finv[..., 0, 0] = F[..., 1, 1] / J
    Finv[..., 1, 1] = F[..., 0, 0] / J
    Finv[..., 0, 1] = -F[..., 0, 1] / J
    Finv[..., 1, 0] = -F[..., 1, 0] / J
    b = ((w * J)[..., None, None] * (dNdX @ Finv)).sum(axis=1).reshape(nel, 8)
    V0 = w.sum(axis=1)
    ke += (dp / V0)[:, None, None] * b[:, :, None] * b[:, None, :]
    return ke


def mean_dilatation(w: np.ndarray, F: np.ndarray, kappa: float
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(θ, p, dp)``: mean dilatation ``θ = v_e/V_e`` of each element and ``U'(θ)``,
    ``U''(θ)`` [MPa]."""
    J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
    theta = (w * J).sum(axis=1) / w.sum(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        p, dp = pressure(kappa, theta)
    return theta, p, dp


def element_arrays(params: MaterialParameters, dNdX: np.ndarray, w: np.ndarray,
                   ue: np.ndarray, state: ViscousState, dt: float,
                   tangent: bool = True) -> ElementOutput:
    """Internal forces and consistent tangent of all elements at once.

    Parameters
    ----------
    params
        Material parameters.
    dNdX, w
        From :func:`shape_gradients`.
    ue
        Element nodal displacements ``(n_el, 4, 2)`` [mm].
    state
        History at the start of the step, arrays shaped ``(n_el, 4, 3)``.
    dt
        Time step [s].
    tangent
        Also compute the element matrices.
    """
    F = deformation_gradient(dNdX, ue)
    theta, p, dp = mean_dilatation(w, F, params.kappa)
    S, CC, _, _, new_state = update_stress(
        params, F, np.broadcast_to(p[:, None], theta.shape + (4,)), state, dt, tangent)
    B = strain_operator(dNdX, F)
    fe = internal_forces(B, w, S)
    ke = tangent_matrices(B, w, CC, S, dNdX, F, dp) if tangent else None
    return ElementOutput(fe, ke, new_state, S, F, theta, p)
