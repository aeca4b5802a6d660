"""Nested iteration for the steady cell: solve on a coarse mesh, carry the solution up.

The steady solver's continuation (press, then the viscous memory switched on) costs
many Newton iterations; on a mesh with a quarter of the elements each costs a quarter.
The coarse solution, interpolated onto the finer mesh, starts Newton there within its
quadratic range, so the fine mesh needs only a few iterations.

Coarse meshes halve ``nx`` (same rows) while they keep ``SteadyOptions.coarse_elements``
elements per shortest wavelength. The displacement field is interpolated
trigonometrically along the rows, the face nodes where the coarse face touched are put
onto the surface at the coarse penetration, and the interior is relaxed with the face
held before the face is released (:mod:`.steady_solver`).
"""

from __future__ import annotations

import numpy as np

from .cell import CellModel


def coarse_meshes(nx: int, ny: int, min_nx: int, levels: int) -> list[tuple[int, int]]:
    """Meshes from the coarsest to ``(nx, ny)``: halved while ``nx/2 >= min_nx``."""
    out = [(nx, ny)]
    while len(out) <= levels and out[-1][0] % 2 == 0 and out[-1][0] // 2 >= min_nx:
        cx, cy = out[-1]
        out.append((cx // 2, cy))
    return out[::-1]


def _periodic_interp(n_new: int, values: np.ndarray) -> np.ndarray:
    """Band-limited (trigonometric) interpolation of ``values`` along the last axis, periodic,
    from ``n`` to ``n_new`` equally spaced points starting at the same origin.

    Why not linear: in contact the face follows the curved surface, and a linear
    interpolant cuts the crest by its chord sag ``h² κ/8`` — several per cent of a face
    element's height on the high-slope wave, which the nearly incompressible element turns
    into pressures of hundreds of MPa. The face is smooth at the coarse resolution, so the
    trigonometric interpolant is accurate to far below that.
    """
    n = values.shape[-1]
    spec = np.fft.rfft(values, axis=-1)
    if n % 2 == 0:   # split the Nyquist mode between ±n/2 so the interpolant stays real
        spec[..., -1] *= 0.5
    return np.fft.irfft(spec, n=n_new, axis=-1) * (n_new / n)


def prolong(coarse: CellModel, U: np.ndarray, fine: CellModel, shift: float) -> np.ndarray:
    """The coarse unknowns ``U`` interpolated onto ``fine`` (both with ``sliding_plate``)."""
    cc, fc = coarse.cell, fine.cell
    uc = coarse.asm.full_displacement(U).reshape(cc.ny + 1, cc.nx, 2)
    # along x on every coarse row, then along y on every fine column
    ux = _periodic_interp(fc.nx, np.moveaxis(uc, 1, -1))      # (ny+1, 2, nx_fine)
    # Each mesh's face sits just below the highest surface point *of its own nodes*, so
    # the reference faces differ by dy0: keep the deformed positions, not the displacements.
    dy0 = cc.y0 - fc.y0
    uf = np.empty((fc.ny + 1, fc.nx, 2))
    for k in range(2):
        for i in range(fc.nx):
            uf[:, i, k] = np.interp(fc.y_nodes - fc.y0, cc.y_nodes - cc.y0, ux[:, k, i])
    uf[..., 1] += dy0
    u_full = uf.reshape(-1)
    V = np.zeros(fine.n)
    free = fine.dof_map >= 0
    V[fine.dof_map[free]] = u_full[free]
    V[fine.plate] = U[coarse.plate] + dy0
    V[fine.plate_x] = U[coarse.plate_x]
    return _onto_coarse_contact(coarse, U, fine, V, shift)


def _onto_coarse_contact(coarse: CellModel, U: np.ndarray, fine: CellModel, V: np.ndarray,
                         shift: float) -> np.ndarray:
    """Fine face nodes where the coarse face touched: onto the surface, at its penetration.

    A coarse face segment in contact cuts the crest with its chord; interpolated, the fine
    nodes between would float above it and carry no load. The coarse face's gaps at all
    its contact points (nodes and interior points) are interpolated to the fine nodes.
    """
    cs = coarse.contact(coarse.asm.full_displacement(U), shift)
    width = coarse.cell.width
    xp = np.mod(cs.point_x, width)
    order = np.argsort(xp)
    pf = fine.face_positions(fine.asm.full_displacement(V))
    want = np.interp(np.mod(pf[:, 0], width), xp[order], cs.gap[order], period=width)
    z = fine.surface.heights(pf[:, 0] + shift)
    fix = want < 0
    W = V.copy()
    W[fine.by[fix]] += (z + want - pf[:, 1])[fix]
    return W
