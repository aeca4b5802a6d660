"""The steady-sliding cell: residual and Jacobian of the travelling-wave problem.

In the frame of the surface a periodic cell sliding at constant speed over a periodic
rigid surface is steady: its state is a function of position only. Its unknowns are
the nodal displacements, the rigid plate's height (which carries the load) and the
plate's horizontal position; the viscous history is not an unknown but a function of
the displacements, integrated along the rows by :mod:`.streamline`.

Stress at a quadrature point: ``S = S_iso + S_vol + (H ⊛ S_iso)`` with ``H`` the row
circulant of :class:`~.streamline.StreamlineKernel`. The Jacobian is split into the
*local* tangent (the transient test's tangent, sparse, symmetric: the point's own
stress feeds its history with the circulant's diagonal) and the *memory* of the
upstream points (dense along each row, applied matrix-free through the same FFT).

Gauge of the plate's horizontal position (see :data:`GAUGES`):

* ``"top"`` holds the plate at ``x = 0`` — the transient test's boundary condition.
  The face then lags the plate by the bulk shear, which can be many columns, so a
  Newton step from a pressed state would have to slide the contact across them;
* ``"face"`` holds the face's mean horizontal displacement at 0 and lets the plate
  lead it. The two differ by a rigid translation of the rubber relative to the
  surface: the ``"face"`` solution with the plate at ``T`` is exactly the ``"top"``
  solution on the surface shifted by ``T``. The solver continues in the ``"face"``
  gauge and finishes in the ``"top"`` gauge on a whole-column shift, where the steady
  state is the one the transient test reaches.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .cell import CellModel
from .constitutive import isochoric_stress, kinematics, volumetric_stress
from .contact import ContactState
from .element import (
    deformation_gradient,
    internal_forces,
    mean_dilatation,
    strain_operator,
    tangent_matrices,
)
from .solver import factorize_general
from .streamline import StreamlineKernel

#: What holds the plate's horizontal position (see the module docstring).
GAUGES = ("top", "face")


@dataclass
class SteadyEvaluation:
    """The cell at one iterate; the tangent is formed on demand (:meth:`SteadyCell.tangent`).

    Attributes
    ----------
    r
        Residual in the evaluation's gauge [N/mm]; NaN where the state is inadmissible.
    forces
        The plain residual before the gauge row is replaced: its ``plate_x`` entry is
        the plate's horizontal reaction [N/mm].
    """

    U: np.ndarray
    shift: float
    load: float
    r: np.ndarray
    forces: np.ndarray
    u_full: np.ndarray
    contact: ContactState
    gauge: str
    # kept for the tangent and the Jacobian product
    B: np.ndarray
    F: np.ndarray
    S: np.ndarray
    dp: np.ndarray
    cc_iso: np.ndarray
    cc_vol: np.ndarray
    K: sp.csr_matrix | None = None

    @property
    def norm(self) -> float:
        return float(np.linalg.norm(self.r))

    @property
    def admissible(self) -> bool:
        return bool(np.all(np.isfinite(self.r)))


class GaugedFactor:
    """Solves with the local tangent under either gauge, from one symmetric factorization.

    The factorization is of ``K`` with the plate's horizontal unknown ``t`` (and any
    ``held`` unknowns) held: their rows and columns replaced by the identity. That is the
    ``"top"`` gauge directly. The ``"face"`` gauge replaces row ``t`` by the face-mean
    constraint ``c·u = b_t`` and keeps column ``t`` (the coupling ``k_t`` of the plate's
    translation to the rest); block elimination with ``z = K_held⁻¹ k_t`` costs one dot
    product more per solve.
    """

    def __init__(self, K: sp.csr_matrix, t: int, c: np.ndarray,
                 held: np.ndarray | None = None) -> None:
        keep = np.ones(K.shape[0])
        keep[t] = 0.0
        if held is not None:
            keep[held] = 0.0
        self.keep = keep
        D = sp.diags(keep)
        k_t = np.asarray(K[:, [t]].todense()).ravel() * keep
        matrix = (D @ K @ D + sp.diags(1.0 - keep)).tocsr()
        matrix.sort_indices()
        # single precision: only GMRES's preconditioner and the line search's merit use it
        self.lu = factorize_general(matrix, single=True)
        self.t, self.c = t, c
        self.z = self.lu.solve(k_t)
        self.cz = float(c @ self.z)

    def solve(self, b: np.ndarray, gauge: str) -> np.ndarray:
        bb = np.where(self.keep > 0, b, 0.0)
        y = self.lu.solve(bb)
        if gauge == "top":
            held = self.keep == 0
            y[held] = b[held]
            return y
        tval = (self.c @ y - b[self.t]) / self.cz
        x = y - tval * self.z
        x[self.t] = tval
        held = self.keep == 0
        held[self.t] = False
        x[held] = b[held]
        return x


class SteadyCell:
    """Residual and Jacobian of the steady-sliding cell.

    Parameters
    ----------
    model
        The cell (built with ``sliding_plate=True``): mesh, DOF map, assembler, contact.
    kernel
        The history operator along the rows.
    held
        Unknowns held at their starting values.
    bias
        Subtracted from the residual (in its gauge) [N/mm]: ``r(U) − bias = 0`` is the
        Newton homotopy that starts exactly at a state ``U₀`` with ``bias = r(U₀)``.
    """

    def __init__(self, model: CellModel, kernel: StreamlineKernel,
                 held: np.ndarray | None = None, bias: np.ndarray | None = None) -> None:
        if model.plate_x is None:
            raise ValueError("the steady cell needs a model with sliding_plate=True")
        self.model = model
        self.kernel = kernel
        self.ny, self.nx = model.cell.ny, model.cell.nx
        #: unknowns held at their starting values (rows of the residual: the change)
        self.held = None if held is None else np.asarray(held, dtype=np.int64)
        self.bias = bias
        #: the face-mean horizontal displacement as a linear form on the unknowns
        self.c = np.zeros(model.n)
        np.add.at(self.c, model.bx, 1.0 / model.bx.size)

    def with_kernel(self, kernel: StreamlineKernel, bias: np.ndarray | None = None
                    ) -> SteadyCell:
        """The same cell with another history kernel and residual bias."""
        return SteadyCell(self.model, kernel, self.held, bias)

    def holding(self, held: np.ndarray | None) -> SteadyCell:
        """The same cell with ``held`` unknowns fixed (None: none)."""
        return SteadyCell(self.model, self.kernel, held, self.bias)

    def history(self, s_iso: np.ndarray) -> np.ndarray:
        """``Σ_b Q_b`` at every quadrature point ``(n_el, 4, 3)`` (rows of ``nx`` elements)."""
        rows = s_iso.reshape(self.ny, self.nx, *s_iso.shape[1:])
        return self.kernel.apply(rows, axis=1).reshape(s_iso.shape)

    def _gauge_row(self, U: np.ndarray, gauge: str) -> float:
        return float(U[self.model.plate_x] if gauge == "top" else self.c @ U)

    def evaluate(self, U: np.ndarray, shift: float, load: float, gauge: str
                 ) -> SteadyEvaluation:
        """Residual at unknowns ``U`` on the surface at ``shift`` [mm] under ``load`` [N/mm]."""
        m = self.model
        asm = m.asm
        u_full = asm.full_displacement(U)
        ue = u_full[asm.edofs].reshape(-1, 4, 2)
        params = m.params
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            F = deformation_gradient(asm.dNdX, ue)
            theta, p, dp = mean_dilatation(asm.w, F, params.kappa)
            J, Cinv, I1 = kinematics(F)
            s_iso, cc_iso = isochoric_stress(params.mu, J, Cinv, I1)
            s_vol, cc_vol = volumetric_stress(np.broadcast_to(p[:, None], J.shape), J, Cinv)
            S = s_iso + s_vol + self.history(s_iso)
            B = strain_operator(asm.dNdX, F)
            fe = internal_forces(B, asm.w, S)
        forces = asm.vector(fe)
        cs = m.contact(u_full, shift)
        m.add_contact_forces(forces, cs)
        forces[m.plate] += load
        if np.any(~(theta > 0)) or np.any(~np.isfinite(fe)):
            forces[:] = np.nan
        r = forces.copy()
        r[m.plate_x] = self._gauge_row(U, gauge)
        if self.bias is not None:
            r -= self.bias
        if self.held is not None:
            r[self.held] = 0.0     # held at the start: Newton never moves them
        return SteadyEvaluation(U, float(shift), float(load), r, forces, u_full, cs, gauge, B,
                                F, S, dp, cc_iso, cc_vol)

    def tangent(self, ev: SteadyEvaluation) -> sp.csr_matrix:
        """The sparse part of the Jacobian at ``ev``: the local tangent with the history's
        ``h₀ (1 − z)`` (own point and upstream neighbour). Formed once, kept on ``ev``."""
        if ev.K is None:
            m = self.model
            asm = m.asm
            h0 = self.kernel.weight
            cc = (1.0 + h0) * ev.cc_iso + ev.cc_vol
            with np.errstate(invalid="ignore", divide="ignore"):
                ke = tangent_matrices(ev.B, asm.w, cc, ev.S, asm.dNdX, ev.F, ev.dp)
            data = m.add_contact_stiffness(asm.matrix_data(ke), ev.contact)
            if h0:
                # f_e += Σ_g w B_eᵀ (−h₀ ℂ_iso,e' B_e') δu_e' from the upstream element e'
                up = m.upstream_elements()
                nel = ev.B.shape[0]
                Bt = (ev.B * asm.w[..., None, None]).transpose(0, 3, 1, 2).reshape(nel, 8, 12)
                DB = (ev.cc_iso @ ev.B)[up].reshape(nel, 12, 8)
                data += m.upwind_data(-h0 * (Bt @ DB))
            ev.K = asm.csr(data)
        return ev.K

    def factor(self, ev: SteadyEvaluation) -> GaugedFactor:
        return GaugedFactor(self.tangent(ev), self.model.plate_x, self.c, self.held)

    def memory_product(self, ev: SteadyEvaluation, v: np.ndarray) -> np.ndarray:
        """The part of the Jacobian beyond :meth:`tangent` (the longer memory) times ``v``."""
        asm = self.model.asm
        ve = np.append(v, 0.0)[asm.dof_map][asm.edofs]          # (nel, 8)
        dE = ev.B @ ve[:, None, :, None]                         # (nel, 4, 3, 1)
        ds = (ev.cc_iso @ dE)[..., 0]                            # (nel, 4, 3)
        rows = ds.reshape(self.ny, self.nx, *ds.shape[1:])
        dq = self.kernel.apply_remainder(rows, axis=1).reshape(ds.shape)
        return asm.vector(internal_forces(ev.B, asm.w, dq))

    def jvp(self, ev: SteadyEvaluation, v: np.ndarray) -> np.ndarray:
        """The exact Jacobian of ``ev``'s residual (in its gauge) times ``v``."""
        out = self.tangent(ev) @ v + self.memory_product(ev, v)
        out[self.model.plate_x] = self._gauge_row(v, ev.gauge)
        if self.held is not None:
            out[self.held] = v[self.held]
        return out
