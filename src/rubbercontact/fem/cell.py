"""The discretized micromechanical test cell: periodic rubber, rigid plate, contact.

Unknowns: the displacements of all nodes below the top edge (left/right edges
tied by the periodic mesh) plus one rigid-plate DOF, the common vertical
displacement of the top edge. The top edge's horizontal displacement is held at 0:
the rubber is at rest and the rigid surface moves in −x beneath it (sliding
distance ``s``, surface ``y = z(x + s)``), which is the same as the rubber moving
in +x over a fixed surface. The plate carries the load ``p̄ L0`` (force per unit
depth [N/mm]) pushing the rubber down.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..roughness.sines import SineSeries
from .assembly import Assembler
from .barrier import BarrierLaw, feasible_step
from .constitutive import MaterialParameters, ViscousState
from .contact import ContactState, evaluate_contact, face_points
from .element import ElementOutput, deformation_gradient
from .mesh import PeriodicCell


@dataclass
class Evaluation:
    """Everything computed at one trial state (kept for the converged one)."""

    elements: ElementOutput
    contact: ContactState
    u_full: np.ndarray


class CellModel:
    """Residual and tangent of the test cell.

    Parameters
    ----------
    cell
        The periodic mesh; its contact face (row 0) sits at ``cell.y0``.
    surface
        Rigid surface.
    params
        Material parameters.
    penalty
        Contact penalty ``ε`` [MPa/mm].
    smoothing
        Penalty-kink rounding ``δ`` [mm] (see :func:`~.contact.evaluate_contact`).
    contact_points
        Contact points per face segment (1: node-to-surface; see
        :func:`~.contact.evaluate_contact`).
    sliding_plate
        Give the top edge's common horizontal displacement its own unknown
        (``plate_x``, the last one); the steady solver decides what holds it.
    barrier
        Barrier contact instead of the penalty (see :mod:`.barrier`).
    """

    def __init__(self, cell: PeriodicCell, surface: SineSeries, params: MaterialParameters,
                 penalty: float, smoothing: float = 0.0, contact_points: int = 4,
                 sliding_plate: bool = False, barrier: BarrierLaw | None = None) -> None:
        self.cell = cell
        self.surface = surface
        self.params = params
        self.penalty = float(penalty)
        self.smoothing = float(smoothing)
        self.contact_points = int(contact_points)
        self.barrier = barrier
        n_dofs = 2 * cell.n_nodes
        dof_map = -np.ones(n_dofs, dtype=np.int64)
        top = np.zeros(cell.n_nodes, bool)
        top[cell.top_nodes] = True
        free_nodes = np.flatnonzero(~top)
        dof_map[2 * free_nodes] = 2 * np.arange(free_nodes.size)
        dof_map[2 * free_nodes + 1] = 2 * np.arange(free_nodes.size) + 1
        self.plate = 2 * free_nodes.size
        dof_map[2 * cell.top_nodes + 1] = self.plate
        self.n = self.plate + 1
        self.plate_x = None
        if sliding_plate:
            self.plate_x = self.n
            dof_map[2 * cell.top_nodes] = self.plate_x
            self.n += 1
        self.dof_map = dof_map
        bottom = cell.bottom_nodes
        self.bx = dof_map[2 * bottom]
        self.by = dof_map[2 * bottom + 1]
        extra = None
        if sliding_plate:
            # The steady solver's preconditioner couples every element to its upstream
            # neighbour in the row (see streamline.StreamlineKernel); both orders, so the
            # pattern stays structurally symmetric.
            red = dof_map[cell.element_dofs]
            up = self.upstream_elements()
            rows = np.broadcast_to(red[:, :, None], red.shape + (8,)).ravel()
            cols = np.broadcast_to(red[up][:, None, :], red.shape + (8,)).ravel()
            ok = (rows >= 0) & (cols >= 0)
            extra = (np.concatenate([rows[ok], cols[ok]]), np.concatenate([cols[ok], rows[ok]]))
        self.asm = Assembler(cell, dof_map, self.n, extra)
        if sliding_plate:
            self._upos = self.asm.positions(rows[ok], cols[ok])
            self._uvalid = ok
        # segment k joins face nodes k and k+1 (periodic); they share a bottom-row
        # element, so all 4x4 blocks are in the element pattern
        seg = np.stack([self.bx, self.by, np.roll(self.bx, -1), np.roll(self.by, -1)], axis=1)
        rows = np.broadcast_to(seg[:, :, None], seg.shape + (4,))
        cols = np.broadcast_to(seg[:, None, :], seg.shape + (4,))
        self._cpos = self.asm.positions(rows.ravel(), cols.ravel())
        self.segment_length = np.full(cell.nx, cell.hx)
        self.X_face = cell.X[bottom]

    def upstream_elements(self) -> np.ndarray:
        """Element id of each element's upstream neighbour (same row, one column to −x)."""
        cell = self.cell
        e = np.arange(cell.n_elements)
        i, j = e % cell.nx, e // cell.nx
        return j * cell.nx + (i - 1) % cell.nx

    def upwind_data(self, blocks: np.ndarray) -> np.ndarray:
        """CSR data of the element-to-upstream blocks ``(n_el, 8, 8)`` (steady cell only)."""
        return np.bincount(self._upos, weights=blocks.ravel()[self._uvalid],
                           minlength=self.asm.nnz)

    def new_state(self) -> ViscousState:
        return ViscousState.zeros((self.cell.n_elements, 4), self.params.n_branches,
                                  self.params.viscous_model)

    def face_positions(self, u_full: np.ndarray) -> np.ndarray:
        """Current positions of the contact-face nodes ``(nx, 2)`` [mm]."""
        b = self.cell.bottom_nodes
        return self.X_face + np.column_stack([u_full[2 * b], u_full[2 * b + 1]])

    def evaluate(self, U: np.ndarray, state: ViscousState, dt: float, shift: float,
                 load: float, tangent: bool = True):
        """``(r, K, Evaluation)`` at unknowns ``U``.

        ``load`` is the plate force per unit depth [N/mm] pushing down; ``shift`` the
        sliding distance [mm]; ``dt`` the step [s] for the viscous update.
        """
        u_full = self.asm.full_displacement(U)
        with np.errstate(invalid="ignore", divide="ignore"):
            out = self.asm.element_output(self.params, u_full, state, dt, tangent)
        r = self.asm.vector(out.fe)
        cs = self.contact(u_full, shift)
        self.add_contact_forces(r, cs)
        r[self.plate] += load
        if np.any(out.theta <= 0) or np.any(~np.isfinite(out.fe)):
            r[:] = np.nan
        K = None
        if tangent:
            K = self.asm.csr(self.add_contact_stiffness(self.asm.matrix_data(out.ke), cs))
        return r, K, Evaluation(out, cs, u_full)

    def contact(self, u_full: np.ndarray, shift: float, smoothing: float | None = None
                ) -> ContactState:
        """Penalty contact of the face at displacements ``u_full`` on the surface at ``shift``
        (``smoothing`` [mm] overrides the model's)."""
        return evaluate_contact(self.surface, shift, self.face_positions(u_full), self.cell.width,
                                self.segment_length, self.penalty, self.contact_points,
                                self.smoothing if smoothing is None else smoothing,
                                self.barrier)

    def feasible_step(self, U: np.ndarray, dU: np.ndarray, shift: float) -> float:
        """The largest step ``α ≤ 1`` along ``dU`` from ``U`` that keeps every contact point
        above the surface (1 without a barrier; see :func:`.barrier.feasible_step`)."""
        if self.barrier is None:
            return 1.0
        m, w = self.contact_points, self.cell.width
        pos = self.face_positions(self.asm.full_displacement(U))
        dpos = self.face_positions(self.asm.full_displacement(dU)) - self.X_face
        p0 = face_points(pos, w, m)
        # the points are linear in the nodes: their moves are the nodes' moves interpolated
        dp = face_points(dpos, 0.0, m)
        return feasible_step(self.surface, shift, p0, dp)

    def add_contact_forces(self, r: np.ndarray, cs: ContactState) -> None:
        """Residual = ∂Π/∂u: the contact force acts ON the rubber, so subtract it."""
        r[self.bx] -= cs.force[:, 0]   # face DOFs are distinct unknowns
        r[self.by] -= cs.force[:, 1]

    def add_contact_stiffness(self, data: np.ndarray, cs: ContactState) -> np.ndarray:
        """CSR data with the contact tangent added (a node belongs to two segments)."""
        data += np.bincount(self._cpos, weights=cs.stiffness.ravel(), minlength=data.size)
        return data

    def shift_field(self, U: np.ndarray, ds: float) -> np.ndarray:
        """Predictor: the nodal field translated with the surface, ``u(X) ← u(X + ds)``.

        In steady sliding the field is a function of ``X + s``; columns are periodic and
        uniformly spaced, so the shift is a periodic linear interpolation in the column
        index (an exact roll when ``ds`` is a whole number of elements).
        """
        cell = self.cell
        u_full = self.asm.full_displacement(U).reshape(cell.ny + 1, cell.nx, 2)
        c = ds / cell.hx
        k = int(np.floor(c))
        f = c - k
        a = np.roll(u_full, -k, axis=1)
        if f > 1e-12:
            a = (1 - f) * a + f * np.roll(u_full, -(k + 1), axis=1)
        a = a.reshape(-1)
        V = U.copy()
        free = self.dof_map >= 0
        free[2 * cell.top_nodes + 1] = False     # the plate keeps its value
        free[2 * cell.top_nodes] = False
        V[self.dof_map[free]] = a[free]
        return V

    def predictor(self, U: np.ndarray, ds: float, shift: float) -> np.ndarray:
        """Shifted field with the face's vertical gaps carried along with the surface.

        ``shift`` is the sliding distance of the state ``U``; the prediction is for
        ``shift + ds``. Interpolating a curved contact face (fractional shifts) or a
        non-steady field puts face nodes deep into the surface, and the penalty turns
        that into forces far above the load, which costs many Newton iterations. So the
        face nodes that were in contact, or would penetrate, get the vertical gap their
        source point had: in steady state this changes nothing.
        """
        V = self.shift_field(U, ds)
        cell = self.cell
        old = self.face_positions(self.asm.full_displacement(U))
        gap_old = old[:, 1] - self.surface.heights(old[:, 0] + shift)
        c = ds / cell.hx
        k = int(np.floor(c))
        f = c - k
        want = np.roll(gap_old, -k)
        if f > 1e-12:
            want = (1 - f) * want + f * np.roll(gap_old, -(k + 1))
        new = self.face_positions(self.asm.full_displacement(V))
        z_new = self.surface.heights(new[:, 0] + shift + ds)
        if self.barrier is None:
            fix = (want < 0) | (new[:, 1] - z_new < 0)
            y_target = z_new + np.minimum(want, 0.0)
        else:
            # the barrier's face never touches: keep each node at least half the reach up
            floor = 0.5 * self.barrier.dhat
            fix = (want < self.barrier.dhat) | (new[:, 1] - z_new < floor)
            y_target = z_new + np.clip(want, floor, self.barrier.dhat)
        # at most a quarter of the face row's height, and only if no element of the face
        # row inverts (on steep flanks a vertical correction can be large)
        h_row = float(cell.y_nodes[1] - cell.y_nodes[0])
        dy = np.clip(y_target - new[:, 1], -0.25 * h_row, 0.25 * h_row)
        W = V.copy()
        W[self.by[fix]] += dy[fix]
        nx = cell.nx
        ue = self.asm.full_displacement(W)[self.asm.edofs[:nx]].reshape(nx, 4, 2)
        F = deformation_gradient(self.asm.dNdX[:nx], ue)
        J = F[..., 0, 0] * F[..., 1, 1] - F[..., 0, 1] * F[..., 1, 0]
        return W if np.all(J > 0.05) else V
