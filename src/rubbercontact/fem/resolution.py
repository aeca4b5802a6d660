"""The cell's mesh from its surface, and each test's check of its own resolution.

``FemOptions.mesh = "auto"`` (:func:`auto_mesh`) puts ``columns_per_wave`` columns on the
surface's shortest wave, rows at the face about as tall as a column is wide, and grades
them geometrically up to rows of a small fraction of the cell width at the plate. After a
test, :func:`narrowest_patch` measures its contact patches in columns; a test on an
automatic mesh whose narrowest patch is below ``patch_columns`` is re-solved on a finer
mesh (:func:`refine_factor`: 1.5x or 2x the columns, :mod:`.sliding`), unless its cell
sheared as a whole beyond the limit (flagged whatever the mesh). N and the patch
width come from the convergence study ``studies/mesh_resolution.py``
(docs/validation/mesh_resolution.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..roughness.sines import SineSeries
from .contact import ContactState

#: The study behind the automatic mesh and the resolution check.
RESOLUTION_STUDY = "docs/validation/mesh_resolution.md"
#: Height of the face row over the column width: square-ish elements where the contact is.
FACE_ASPECT = 1.5
#: The top row (at the plate) is at most the cell width over this: the cell's longest wave
#: (its width) decays over its own length, and still needs several rows there.
TOP_ROWS_PER_WIDTH = 8
#: Fewest rows of an automatic mesh.
MIN_ROWS = 8
#: Factors of the columns per wave a test with a too narrow patch is re-solved with, the
#: smallest that suffices first: on the station 1 cell's under-resolved 1 mm/s points
#: (patches of about 3 columns) 1.5x resolves them at a quarter to four fifths of the
#: Newton iterations of 2x (docs/validation/steep_cells.md, "Refining by the factor").
REFINE_FACTORS = (1.5, 2.0)
#: Most rows an automatic mesh tries before it takes the last (a bound, never reached by
#: the cells of the rule's range).
MAX_ROWS = 400


@dataclass(frozen=True)
class AutoMesh:
    """An automatic mesh: elements and the vertical grading.

    Attributes
    ----------
    nx, ny
        Elements along x and y.
    grading
        Top-row / face-row height ratio (>= 1).
    """

    nx: int
    ny: int
    grading: float


def auto_nx(surface: SineSeries, columns_per_wave: int) -> int:
    """Columns that put ``columns_per_wave`` on the shortest wave of ``surface`` (even, so
    that the nested iteration can halve it)."""
    waves = surface.period / float(np.min(surface.wavelengths))
    nx = int(np.ceil(columns_per_wave * waves - 1e-9))
    return nx + nx % 2


def graded_rows(height: float, face_row: float, top_row: float) -> tuple[int, float]:
    """Fewest rows ``ny`` (>= :data:`MIN_ROWS`) of a geometric grading that starts at
    ``face_row`` [mm] and fills ``height`` [mm] with its top row at most ``top_row`` [mm];
    ``(ny, grading)``, grading = top / face row (1: uniform rows no taller than
    ``face_row``)."""
    if MIN_ROWS * face_row >= height:
        return MIN_ROWS, 1.0
    for ny in range(MIN_ROWS, MAX_ROWS + 1):
        if ny * face_row >= height:
            return ny, 1.0
        r = _ratio(height / face_row, ny)
        if face_row * r ** (ny - 1) <= top_row:
            return ny, float(r ** (ny - 1))
    return MAX_ROWS, float(_ratio(height / face_row, MAX_ROWS) ** (MAX_ROWS - 1))


def _ratio(total: float, n: int) -> float:
    """``r > 1`` with ``1 + r + … + r^(n-1) = total`` (``total > n``), by bisection."""
    lo, hi = 1.0, 2.0
    while (hi**n - 1) / (hi - 1) < total:
        hi *= 2
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if (mid**n - 1) / (mid - 1) < total:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def auto_mesh(surface: SineSeries, height_ratio: float, columns_per_wave: int) -> AutoMesh:
    """The mesh of a cell of width ``surface.period`` and height ``height_ratio`` times it:
    ``nx`` from :func:`auto_nx`, rows from :func:`graded_rows` with the face row
    :data:`FACE_ASPECT` columns tall and the top row at most the width over
    :data:`TOP_ROWS_PER_WIDTH`."""
    width = float(surface.period)
    nx = auto_nx(surface, columns_per_wave)
    ny, grading = graded_rows(height_ratio * width, FACE_ASPECT * width / nx,
                              width / TOP_ROWS_PER_WIDTH)
    return AutoMesh(nx, ny, grading)


def refine_factor(patch_columns: float, need: int) -> float:
    """The factor of the columns per wave a test whose narrowest patch is ``patch_columns``
    wide is re-solved with: the smallest of :data:`REFINE_FACTORS` that widens the patch to
    ``need`` columns if its width in mm holds, else the largest."""
    return next((f for f in REFINE_FACTORS if patch_columns * f >= need), REFINE_FACTORS[-1])


def refined_mesh(surface: SineSeries, height_ratio: float, columns_per_wave: int,
                 factor: float = REFINE_FACTORS[-1]) -> AutoMesh:
    """The mesh a test on the automatic mesh of ``columns_per_wave`` is re-solved on when
    its narrowest patch is too narrow: the rule's mesh for ``factor`` times the columns per
    wave (rows and grading the rule's for it, so the face rows keep their aspect). The
    default, the largest factor, is the most a refinement costs."""
    return auto_mesh(surface, height_ratio, int(round(factor * columns_per_wave)))


def patch_widths(x: np.ndarray, gap: np.ndarray, width: float) -> np.ndarray:
    """Widths [mm] of the contact patches of a periodic face, each abscissa once.

    ``x``, ``gap`` as for :func:`~.contact.contact_fraction` (the face's points in order,
    gap interpolated linearly between them, negative = in contact); patches that overlap
    or touch modulo ``width`` are one patch. Empty without contact; ``[width]`` in full
    contact.
    """
    x = np.asarray(x, float)
    g = np.append(np.asarray(gap, float), gap[0])
    u = np.append(x - x[0], width)
    g0, g1, u0, u1 = g[:-1], g[1:], u[:-1], u[1:]
    c0, c1 = g0 < 0, g1 < 0
    touch = c0 | c1
    if not np.any(touch):
        return np.zeros(0)
    with np.errstate(divide="ignore", invalid="ignore"):
        cross = u0 + g0 / (g0 - g1) * (u1 - u0)
    a = np.where(c0, u0, cross)[touch]
    b = np.where(c1, u1, cross)[touch]
    lo = np.mod(np.minimum(a, b), width)
    hi = lo + np.abs(b - a)
    return _union_lengths(lo, hi, width)


def _union_lengths(lo: np.ndarray, hi: np.ndarray, width: float) -> np.ndarray:
    """Lengths of the connected parts of the union of ``[lo, hi]`` (``lo`` in
    ``[0, width)``) on the circle of length ``width``."""
    order = np.argsort(lo, kind="stable")
    lo, hi = lo[order], hi[order]
    parts: list[list[float]] = []
    for a, b in zip(lo, hi, strict=True):
        if parts and a <= parts[-1][1]:
            parts[-1][1] = max(parts[-1][1], b)
        else:
            parts.append([a, b])
    if len(parts) > 1 and parts[-1][1] >= parts[0][0] + width:   # across the seam
        first = parts.pop(0)
        parts[-1][1] = max(parts[-1][1], first[1] + width)
    return np.array([min(b - a, width) for a, b in parts])


def narrowest_patch(surface: SineSeries, shift: float, cs: ContactState, width: float,
                    hx: float) -> float:
    """The narrowest contact patch of a converged state, in columns of width ``hx`` [-];
    ``inf`` without contact or in full contact (no patch edge to resolve). Contact as in
    :func:`~.contact.face_contact_fraction` (gaps within the chord sag and the barrier's
    reach count)."""
    m = cs.points_per_segment
    x = cs.point_x
    dx = np.diff(np.append(x[::m], x[0] + width))
    sag = np.repeat(dx, m) ** 2 * np.abs(surface.curvatures(x + shift)) / 8.0
    w = patch_widths(x, cs.gap - cs.reach - sag, width)
    if w.size == 0 or (w.size == 1 and w[0] >= width):
        return float("inf")
    return float(w.min() / hx)


def under_resolved_message(columns: float, need: int, mesh: tuple[int, int], p: float,
                           v: float) -> str:
    """The one line of a test whose narrowest contact patch is below ``need`` columns."""
    return (f"FEM sliding test (p̄ = {p:g} MPa, v = {v:g} mm/s): the narrowest contact patch "
            f"is {columns:.1f} columns wide on {mesh[0]} x {mesh[1]}, below {need}: "
            f"under-resolved ({RESOLUTION_STUDY})")
