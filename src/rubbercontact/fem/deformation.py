"""How strained a cell state is: what a steady solve that stopped had reached.

On steep cells pressed beyond the relaxed modulus the rubber wraps crests whose radius is
a few columns: the face segments stretch to two or three times their length and the
elements beside the crests are crushed (docs/validation/steep_cells.md, part
``strain``). A stop there is a question of the cell's strain, not of the contact law or
the line search; :func:`measure_deformation` gives the figures a failure reports.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Deformation:
    """The strain of one cell state.

    Attributes
    ----------
    face_stretch_min, face_stretch_max
        Current over reference length of the face segments [-].
    face_slope_deg
        Steepest face segment [°].
    face_turn_deg
        Sharpest turn between two neighbouring face segments [°].
    stretch_min, stretch_max
        Smallest and largest principal stretch at the quadrature points [-].
    J_min
        Smallest Jacobian ``det F`` at the quadrature points [-].
    worst_element
        The element with the smallest Jacobian (row-major from the face).
    worst_x
        Its centre's current abscissa [mm].
    """

    face_stretch_min: float
    face_stretch_max: float
    face_slope_deg: float
    face_turn_deg: float
    stretch_min: float
    stretch_max: float
    J_min: float
    worst_element: int
    worst_x: float

    def describe(self) -> str:
        """One clause for a failure message."""
        return (f"face stretched up to ×{self.face_stretch_max:.2g}, principal stretches "
                f"{self.stretch_min:.2g}–{self.stretch_max:.2g}")


def measure_deformation(model, U: np.ndarray) -> Deformation:
    """The :class:`Deformation` of the unknowns ``U`` of the cell ``model``
    (a :class:`~.cell.CellModel`), its viscous history at rest."""
    u = model.asm.full_displacement(U)
    face = model.face_positions(u)
    width = model.cell.width
    seg = np.diff(np.vstack([face, face[:1] + [width, 0.0]]), axis=0)
    ref = np.diff(np.append(model.X_face[:, 0], model.X_face[0, 0] + width))
    stretch = np.linalg.norm(seg, axis=1) / ref
    angle = np.arctan2(seg[:, 1], seg[:, 0])
    turn = np.angle(np.exp(1j * (np.roll(angle, -1) - angle)))
    with np.errstate(invalid="ignore", divide="ignore"):
        F = model.asm.element_output(model.params, u, model.new_state(), np.inf, False).F
    J = np.linalg.det(F)
    lam = np.sqrt(np.abs(np.linalg.eigvalsh(np.einsum("...ki,...kj->...ij", F, F))))
    worst = int(np.argmin(J.reshape(J.shape[0], -1).min(axis=1)))
    conn = model.cell.conn[worst]
    centre = (model.cell.Xe[worst] + np.column_stack([u[2 * conn], u[2 * conn + 1]])).mean(0)
    return Deformation(float(stretch.min()), float(stretch.max()),
                       float(np.degrees(np.abs(angle).max())),
                       float(np.degrees(np.abs(turn).max())),
                       float(lam[..., 0].min()), float(lam[..., -1].max()), float(J.min()),
                       worst, float(centre[0]))
