"""The strain a stopped steady solve reports (:mod:`rubbercontact.fem.deformation`),
against homogeneous deformations of the cell, whose stretches are closed forms."""

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.fem.deformation import measure_deformation
from rubbercontact.fem.options import FemOptions
from rubbercontact.fem.setup import build_cell


def _model():
    surf = rc.roughness.SineSeries([1.0], [0.01])
    opts = FemOptions(mesh=(8, 4))
    return build_cell(surf, rc.materials.sbr(), 0.1, 1.0, opts, sliding_plate=True).model


def _field(model, ux, uy):
    """The unknowns of the displacement ``(ux(X), uy(X))`` (the plate's dofs from the top
    nodes, which they hold)."""
    U = np.zeros(model.n)
    X = model.cell.X
    dofs = model.dof_map.reshape(-1, 2)
    for k, u in ((0, ux(X)), (1, uy(X))):
        own = dofs[:, k] >= 0
        U[dofs[own, k]] = u[own]
    return U


def test_vertical_compression():
    # u_y = -e (y - y0): principal stretches 1 - e and 1, J = 1 - e; the face is unmoved
    m, e = _model(), 0.3
    y0 = m.cell.y0
    d = measure_deformation(m, _field(m, lambda X: 0 * X[:, 0], lambda X: -e * (X[:, 1] - y0)))
    assert d.stretch_min == pytest.approx(1 - e, rel=1e-12)
    assert d.stretch_max == pytest.approx(1.0, rel=1e-12)
    assert d.J_min == pytest.approx(1 - e, rel=1e-12)
    assert d.face_stretch_min == pytest.approx(1.0) and d.face_stretch_max == pytest.approx(1.0)
    assert d.face_slope_deg == pytest.approx(0.0, abs=1e-9)


def test_simple_shear():
    # u_x = g (y - y0): C = [[1, g], [g, 1 + g^2]], principal stretches
    # sqrt(1 + g^2/2 +- g sqrt(1 + g^2/4)) (product 1), J = 1
    m, g = _model(), 1.5
    y0 = m.cell.y0
    d = measure_deformation(m, _field(m, lambda X: g * (X[:, 1] - y0), lambda X: 0 * X[:, 1]))
    big = np.sqrt(1 + g * g / 2 + g * np.sqrt(1 + g * g / 4))
    assert d.stretch_max == pytest.approx(big, rel=1e-12)
    assert d.stretch_min == pytest.approx(1 / big, rel=1e-12)
    assert d.J_min == pytest.approx(1.0, rel=1e-12)


def test_a_face_wave_stretches_the_face():
    # u_y = a sin(2 pi x / L) on the face only (zero above): the face's segments are the
    # chords of that sine, their stretch and slope computed here from the nodes
    m, a = _model(), 0.02
    L, nx = m.cell.width, m.cell.nx
    y0 = m.cell.y0

    def uy(X):
        return np.where(np.isclose(X[:, 1], y0), a * np.sin(2 * np.pi * X[:, 0] / L), 0.0)

    d = measure_deformation(m, _field(m, lambda X: 0 * X[:, 0], uy))
    x = np.arange(nx + 1) * L / nx
    dy = np.diff(a * np.sin(2 * np.pi * x / L))
    chord = np.hypot(L / nx, dy) / (L / nx)
    assert d.face_stretch_max == pytest.approx(chord.max(), rel=1e-12)
    assert d.face_stretch_min == pytest.approx(chord.min(), rel=1e-12)
    assert d.face_slope_deg == pytest.approx(np.degrees(np.arctan(np.abs(dy).max() * nx / L)),
                                             rel=1e-12)
