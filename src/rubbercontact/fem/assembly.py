"""Global assembly on a fixed sparsity pattern (CSR scatter map built once).

A DOF map sends every mesh DOF to an unknown of the reduced system or to ``-1``
(prescribed). Several mesh DOFs may share one unknown (e.g. all top-edge vertical
DOFs share the rigid plate's displacement), which is how the rigid plate is built
in without constraint equations. Element vectors and matrices are scattered with
``np.bincount`` into precomputed positions of the CSR data array, so each
assembly is a handful of vectorized numpy calls.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .constitutive import MaterialParameters, ViscousState
from .element import ElementOutput, element_arrays, shape_gradients
from .mesh import Mesh


class Assembler:
    """Residual and tangent of a mesh with a DOF map.

    Parameters
    ----------
    mesh
        The mesh.
    dof_map
        ``(2 n_nodes,)`` unknown index of each mesh DOF, ``-1`` if prescribed.
    n_unknowns
        Size of the reduced system.
    extra_pairs
        Optional ``(rows, cols)`` of reduced indices that must exist in the pattern
        (e.g. contact blocks); entries coupling through elements are always present.
    """

    def __init__(self, mesh: Mesh, dof_map: np.ndarray, n_unknowns: int,
                 extra_pairs: tuple[np.ndarray, np.ndarray] | None = None) -> None:
        self.mesh = mesh
        self.dof_map = np.asarray(dof_map, dtype=np.int64)
        self.n = int(n_unknowns)
        self.dNdX, self.w, self.N = shape_gradients(mesh.Xe)
        self.edofs = mesh.element_dofs
        red = self.dof_map[self.edofs]                      # (nel, 8)
        self.red = red
        rows = np.broadcast_to(red[:, :, None], red.shape + (8,)).ravel()
        cols = np.broadcast_to(red[:, None, :], red.shape + (8,)).ravel()
        self._kvalid = (rows >= 0) & (cols >= 0)
        keys = rows[self._kvalid] * self.n + cols[self._kvalid]
        all_keys = keys
        if extra_pairs is not None:
            er, ec = (np.asarray(a, np.int64).ravel() for a in extra_pairs)
            all_keys = np.concatenate([keys, er * self.n + ec])
        self._keys = np.unique(all_keys)
        self._kpos = np.searchsorted(self._keys, keys)
        r = self._keys // self.n
        self.indices = (self._keys % self.n).astype(np.int32)
        self.indptr = np.concatenate([[0], np.cumsum(np.bincount(r, minlength=self.n))]
                                     ).astype(np.int32)
        self._fvalid = red >= 0
        self._fidx = red[self._fvalid]

    @property
    def nnz(self) -> int:
        return int(self._keys.size)

    def positions(self, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
        """CSR data positions of reduced ``(rows, cols)`` pairs (must be in the pattern)."""
        keys = np.asarray(rows, np.int64) * self.n + np.asarray(cols, np.int64)
        pos = np.searchsorted(self._keys, keys)
        if np.any(pos >= self._keys.size) or np.any(self._keys[np.minimum(
                pos, self._keys.size - 1)] != keys):
            raise ValueError("pair not in the sparsity pattern")
        return pos

    def full_displacement(self, U: np.ndarray, prescribed: np.ndarray | None = None
                          ) -> np.ndarray:
        """Mesh DOF vector from the unknowns (prescribed DOFs from ``prescribed`` or 0)."""
        u = np.append(U, 0.0)[self.dof_map]
        if prescribed is not None:
            fixed = self.dof_map < 0
            u[fixed] = prescribed[fixed]
        return u

    def element_output(self, params: MaterialParameters, u_full: np.ndarray,
                       state: ViscousState, dt: float, tangent: bool = True) -> ElementOutput:
        ue = u_full[self.edofs].reshape(-1, 4, 2)
        return element_arrays(params, self.dNdX, self.w, ue, state, dt, tangent)

    def vector(self, fe: np.ndarray) -> np.ndarray:
        """Reduced vector from element vectors ``(nel, 8)``."""
        return np.bincount(self._fidx, weights=fe[self._fvalid], minlength=self.n)

    def full_vector(self, fe: np.ndarray) -> np.ndarray:
        """Mesh-DOF vector (reactions included) from element vectors."""
        return np.bincount(self.edofs.ravel(), weights=fe.ravel(),
                           minlength=2 * self.mesh.n_nodes)

    def matrix_data(self, ke: np.ndarray) -> np.ndarray:
        """CSR data array from element matrices ``(nel, 8, 8)``."""
        return np.bincount(self._kpos, weights=ke.ravel()[self._kvalid], minlength=self.nnz)

    def csr(self, data: np.ndarray) -> sp.csr_matrix:
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n, self.n))
