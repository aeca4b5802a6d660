"""Structured plane-strain Q1 meshes: the periodic rubber cell and plain patches.

The periodic cell has ``nx`` node columns (column ``nx`` is column 0 shifted by
the width, so left and right edges are tied by construction, no constraint
equations) and ``ny + 1`` node rows; row 0 is the contact face, row ``ny`` the
top edge. Node ``(i, j)`` has id ``j·nx + i``; its DOFs are ``2·id`` (x) and
``2·id + 1`` (y). Elements list their nodes counter-clockwise and carry their own
reference coordinates, so the wrap-around column has the correct geometry.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validation import positive_scalar
from ..errors import InputError


@dataclass(frozen=True, eq=False)
class Mesh:
    """A Q1 mesh: reference coordinates and connectivity.

    Attributes
    ----------
    X
        Node reference coordinates ``(n_nodes, 2)`` [mm].
    conn
        Element node ids ``(n_elements, 4)``, counter-clockwise.
    Xe
        Element reference coordinates ``(n_elements, 4, 2)`` [mm] (wrap-corrected).
    """

    X: np.ndarray
    conn: np.ndarray
    Xe: np.ndarray

    @property
    def n_nodes(self) -> int:
        return int(self.X.shape[0])

    @property
    def n_elements(self) -> int:
        return int(self.conn.shape[0])

    @property
    def element_dofs(self) -> np.ndarray:
        """``(n_elements, 8)`` DOF ids ordered ``[x0, y0, x1, y1, ...]``."""
        return (2 * self.conn[:, :, None] + np.arange(2)).reshape(-1, 8)


@dataclass(frozen=True, eq=False)
class PeriodicCell(Mesh):
    """The periodic rubber cell of width ``width`` and height ``height`` [mm].

    Attributes
    ----------
    nx, ny
        Elements along x and y.
    width, height
        Cell size [mm]; the contact face is at ``y = y0``.
    x_nodes, y_nodes
        Node coordinates along x (``nx`` values, periodic) and y (``ny + 1``).
    """

    nx: int = 0
    ny: int = 0
    width: float = 0.0
    height: float = 0.0
    y0: float = 0.0
    x_nodes: np.ndarray | None = None
    y_nodes: np.ndarray | None = None

    @property
    def bottom_nodes(self) -> np.ndarray:
        return np.arange(self.nx)

    @property
    def top_nodes(self) -> np.ndarray:
        return self.ny * self.nx + np.arange(self.nx)

    @property
    def hx(self) -> float:
        return self.width / self.nx


def periodic_cell(width: float, height: float, nx: int, ny: int, *, grading: float = 1.0,
                  y0: float = 0.0) -> PeriodicCell:
    """Build the structured periodic cell.

    Parameters
    ----------
    width, height
        Cell width ``L0`` and height ``H`` [mm].
    nx, ny
        Number of elements along x and y (``nx >= 3``, ``ny >= 1``).
    grading
        Ratio of the top row's height to the bottom row's (geometric progression);
        ``> 1`` refines toward the contact face, 1 is uniform.
    y0
        Height of the contact face in the reference configuration [mm].
    """
    width = positive_scalar("width", width, unit="mm")
    height = positive_scalar("height", height, unit="mm")
    grading = positive_scalar("grading", grading)
    for name, n, lo in (("mesh nx", nx, 3), ("mesh ny", ny, 1)):
        if int(n) != n or n < lo:
            raise InputError(f"{name}: must be an integer >= {lo}, got {n}")
    nx, ny = int(nx), int(ny)
    x = np.arange(nx) * (width / nx)
    if grading == 1.0 or ny == 1:
        dy = np.full(ny, height / ny)
    else:
        r = grading ** (1.0 / (ny - 1))
        dy = r ** np.arange(ny)
        dy *= height / dy.sum()
    y = y0 + np.concatenate([[0.0], np.cumsum(dy)])
    y[-1] = y0 + height
    X = np.column_stack([np.tile(x, ny + 1), np.repeat(y, nx)])
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="xy")
    i, j = i.ravel(), j.ravel()
    ip = (i + 1) % nx
    conn = np.column_stack([j * nx + i, j * nx + ip, (j + 1) * nx + ip, (j + 1) * nx + i])
    Xe = X[conn].copy()
    wrap = (i == nx - 1)
    Xe[wrap, 1, 0] += width
    Xe[wrap, 2, 0] += width
    return PeriodicCell(X=X, conn=conn, Xe=Xe, nx=nx, ny=ny, width=width, height=height,
                        y0=y0, x_nodes=x, y_nodes=y)


def rectangle_mesh(x_nodes, y_nodes) -> Mesh:
    """A plain (non-periodic) structured mesh on the tensor grid ``x_nodes × y_nodes``."""
    x = np.asarray(x_nodes, float)
    y = np.asarray(y_nodes, float)
    nx, ny = x.size - 1, y.size - 1
    X = np.column_stack([np.tile(x, ny + 1), np.repeat(y, nx + 1)])
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="xy")
    i, j = i.ravel(), j.ravel()
    n = nx + 1
    conn = np.column_stack([j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i])
    return Mesh(X=X, conn=conn, Xe=X[conn].copy())
