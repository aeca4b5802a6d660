r"""Areal topography: a height map ``z(x, y)`` [mm] sliding along ``x``.

A :class:`HeightMap` holds finite heights on a uniform grid, rows along ``y`` and columns
along ``x`` (``heights[j, i] = z(x_i, y_j)``, the layout of
:func:`rubbercontact.halfspace.solve_sliding`, whose last axis is the sliding direction).
Positions are ``x_i = i·dx``, ``y_j = j·dy``; the map spans ``Lx = nx·dx`` by
``Ly = ny·dy``, which is its period once it is periodic.

Measured maps come in with dropouts and are not periodic. What this module does to them,
and says it did (in :attr:`HeightMap.source`):

* **Dropouts (NaN).** Refused (``nan="error"``) or filled by the harmonic function that
  takes the measured values on the gap's rim (``nan="fill"``: the discrete Laplace equation,
  the smoothest surface through the rim, no slope invented beyond what the rim sets). The
  filled points are kept in :attr:`HeightMap.filled`; the real-space statistics exclude them
  (:mod:`rubbercontact.roughness.mapstats`), the FFT-based ones (the spectrum, the solves)
  see the filled map.
* **Periodization.** The FFT half-space and the spectrum take the map as one period. A
  measured map's opposite edges do not match, and the jump at the seams is a slope the
  surface does not have (a ``q⁻²`` floor in the spectrum, a cliff in the contact solve).
  :meth:`HeightMap.periodized` mirrors the map (even reflection about its last row and
  column, period ``2(n − 1)`` points per axis): heights are continuous across the seams and
  every first difference of the mirrored map is ± one of the original, so no slope is
  invented; the price is a kink (the slope changes sign) along the seams and a doubled size.
  For spectra alone, :func:`rubbercontact.roughness.mapstats.spectrum_2d` offers a Hann
  window instead.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar, Literal

import numpy as np

from .._validation import finite_array, positive_scalar
from ..errors import InputError

MapDetrend = Literal["none", "mean", "plane"]
NanMode = Literal["error", "fill"]

#: Fewest points per axis of a map (a spectrum needs a few harmonics).
MIN_MAP_POINTS = 4


@dataclass(frozen=True, eq=False)
class HeightMap:
    """A height map on a uniform grid (module docstring), heights [mm], lengths [mm].

    Attributes
    ----------
    heights
        ``z`` [mm], shape ``(ny, nx)``, finite, read-only; ``x`` is the last axis.
    lengths
        ``(Ly, Lx)`` [mm]: ``ny·dy`` and ``nx·dx``.
    filled
        Boolean ``(ny, nx)`` mask of the points that were dropouts and are filled, or
        ``None`` when every point was measured.
    periodic
        Whether the map is one period of a periodic surface (synthetic maps, periodized
        measured maps). Only then are its spectral statistics free of seam leakage.
    source
        Provenance (file, hash, unit, what was filled, detrended, periodized), plain data.
    """

    #: a map z(y, x): what the solvers dispatch on (:mod:`~rubbercontact.roughness.protocol`)
    dimension: ClassVar[int] = 2
    heights: np.ndarray
    lengths: tuple[float, float]
    filled: np.ndarray | None = None
    periodic: bool = False
    source: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        z = finite_array("heights", self.heights, ndim=2)
        if min(z.shape) < MIN_MAP_POINTS:
            raise InputError(f"heights: a map needs at least {MIN_MAP_POINTS} points per axis, "
                             f"got shape {z.shape}")
        if np.ndim(self.lengths) != 1 or len(self.lengths) != 2:
            raise InputError(f"lengths: expected (Ly, Lx) in mm, got {self.lengths!r}")
        lengths = tuple(positive_scalar(n, v, unit="mm")
                        for n, v in zip(("Ly", "Lx"), self.lengths, strict=True))
        z = np.array(z, dtype=float)
        z.setflags(write=False)
        object.__setattr__(self, "heights", z)
        object.__setattr__(self, "lengths", lengths)
        if self.filled is not None:
            m = np.asarray(self.filled, dtype=bool)
            if m.shape != z.shape:
                raise InputError(f"filled: mask shape {m.shape} differs from heights {z.shape}")
            m = m.copy() if m.any() else None
            if m is not None:
                m.setflags(write=False)
            object.__setattr__(self, "filled", m)
        object.__setattr__(self, "periodic", bool(self.periodic))
        object.__setattr__(self, "source", dict(self.source))

    # -- constructors -------------------------------------------------------------------
    @classmethod
    def from_array(cls, heights, dx: float, dy: float | None = None, *,
                   nan: NanMode = "error", periodic: bool = False,
                   source: dict | None = None) -> HeightMap:
        """A map from heights [mm] ``(ny, nx)`` (x along the last axis) and pixel sizes [mm].

        Parameters
        ----------
        heights
            Heights [mm]; NaN are dropouts, handled by ``nan``.
        dx, dy
            Pixel sizes along x and y [mm]; ``dy`` defaults to ``dx`` (square pixels).
        nan
            ``"error"``: dropouts raise :class:`InputError`; ``"fill"``: harmonic fill
            (module docstring), the filled points recorded in :attr:`filled`.
        periodic
            Whether the heights are one period of a periodic surface.
        source
            Provenance to keep (plain data).
        """
        try:
            z = np.asarray(heights, dtype=float)
        except (TypeError, ValueError) as exc:
            raise InputError(f"heights: cannot be read as numbers ({exc})") from None
        if z.ndim != 2:
            raise InputError(f"heights: expected a 2D map (ny, nx), got shape {z.shape}")
        dx = positive_scalar("dx", dx, unit="mm")
        dy = dx if dy is None else positive_scalar("dy", dy, unit="mm")
        src = dict(source or {})
        if np.isinf(z).any():
            raise InputError(f"heights: {int(np.isinf(z).sum())} infinite values (first at "
                             f"{tuple(int(i) for i in np.argwhere(np.isinf(z))[0])})")
        gaps = np.isnan(z)
        filled = None
        if gaps.any():
            if nan == "error":
                first = tuple(int(i) for i in np.argwhere(gaps)[0])
                raise InputError(f"heights: {int(gaps.sum())} of {z.size} points are NaN "
                                 f"(first at (y, x) = {first}); pass nan='fill' to fill them "
                                 f"by harmonic interpolation")
            if nan != "fill":
                raise InputError(f"nan: expected 'error' or 'fill', got {nan!r}")
            z, filled = harmonic_fill(z), gaps
            src["nan"] = {"policy": "harmonic fill", "points": int(gaps.sum()),
                          "fraction": float(gaps.mean())}
        return cls(z, (z.shape[0] * dy, z.shape[1] * dx), filled, periodic, src)

    # -- geometry -----------------------------------------------------------------------
    @property
    def shape(self) -> tuple[int, int]:
        return self.heights.shape

    @property
    def dx(self) -> float:
        """Pixel size along x (sliding) [mm]."""
        return self.lengths[1] / self.shape[1]

    @property
    def dy(self) -> float:
        """Pixel size along y [mm]."""
        return self.lengths[0] / self.shape[0]

    @property
    def x(self) -> np.ndarray:
        return np.arange(self.shape[1]) * self.dx

    @property
    def y(self) -> np.ndarray:
        return np.arange(self.shape[0]) * self.dy

    @property
    def measured(self) -> np.ndarray:
        """Boolean mask of the measured (not filled) points."""
        return np.ones(self.shape, bool) if self.filled is None else ~self.filled

    def replace(self, heights: np.ndarray, note: dict, **changes) -> HeightMap:
        """The same grid with other heights; ``note`` is merged into :attr:`source`."""
        kw = {"filled": self.filled, "periodic": self.periodic, "lengths": self.lengths}
        kw.update(changes)
        return HeightMap(heights, source={**self.source, **note}, **kw)

    # -- processing ---------------------------------------------------------------------
    def detrended(self, mode: MapDetrend = "mean") -> HeightMap:
        """Remove nothing, the mean, or the least-squares plane of the measured points.

        A plane is fitted to the measured points only; on a periodic map it would add a
        seam jump, so ``"plane"`` is refused there (a periodic map has no tilt to remove).
        What is left within round-off of the heights (a constant or a tilted plane) is the
        flat map, zero heights, which the solvers refuse in one line.
        """
        if mode not in ("none", "mean", "plane"):
            raise InputError(f"detrend: expected 'none', 'mean' or 'plane', got {mode!r}")
        z = self.heights
        m = self.measured
        if mode == "none":
            return self
        if mode == "mean":
            return self.replace(_flat_at_roundoff(z - z[m].mean(), z), {"detrend": "mean"})
        if self.periodic:
            raise InputError("detrend: 'plane' on a periodic map would open a seam; use 'mean'")
        yy, xx = np.meshgrid(self.y, self.x, indexing="ij")
        a = np.column_stack([np.ones(m.sum()), xx[m], yy[m]])
        coef, *_ = np.linalg.lstsq(a, z[m], rcond=None)
        plane = coef[0] + coef[1] * xx + coef[2] * yy
        return self.replace(_flat_at_roundoff(z - plane, z),
                            {"detrend": "plane", "tilt_x": float(coef[1]),
                             "tilt_y": float(coef[2])})

    def periodized(self, method: Literal["mirror", "none"] = "mirror") -> HeightMap:
        """One period of a periodic surface made of this map (module docstring).

        ``"mirror"``: even reflection about the last row and column, shape
        ``(2(ny − 1), 2(nx − 1))``, lengths doubled less one pixel; ``"none"``: the map is
        declared one period as it is (its seam jumps become slopes: only for maps that are
        periodic already). A periodic map is returned unchanged.
        """
        if method not in ("mirror", "none"):
            raise InputError(f"periodize: expected 'mirror' or 'none', got {method!r}")
        if self.periodic:
            return self
        if method == "none":
            return self.replace(self.heights, {"periodize": "none (taken as one period)"},
                                periodic=True)
        z = _mirror(self.heights)
        filled = None if self.filled is None else _mirror(self.filled)
        lengths = (z.shape[0] * self.dy, z.shape[1] * self.dx)
        return self.replace(z, {"periodize": "mirror"}, periodic=True, filled=filled,
                            lengths=lengths)

    def resampled(self, shape: tuple[int, int]) -> HeightMap:
        """The periodic map's trigonometric polynomial sampled on ``shape = (ny, nx)`` points
        (Fourier interpolation, :func:`scipy.signal.resample`): the same surface on a finer
        (or, dropping its shortest modes, coarser) grid, for resolution studies."""
        from scipy.signal import resample

        if not self.periodic:
            raise InputError("resampled: Fourier interpolation needs a periodic map; use "
                             "map.periodized() first")
        if np.ndim(shape) != 1 or len(shape) != 2 or any(int(n) != n or n < MIN_MAP_POINTS
                                                          for n in shape):
            raise InputError(f"shape: expected (ny, nx), integers >= {MIN_MAP_POINTS}, "
                             f"got {shape!r}")
        z = resample(resample(self.heights, int(shape[0]), axis=0), int(shape[1]), axis=1)
        return HeightMap(z, self.lengths, periodic=True,
                         source={**self.source, "resampled_from": list(self.shape)})

    def profile(self) -> np.ndarray | None:
        """The common row if the map is uniform in ``y`` (every row equal), else ``None``."""
        z = self.heights
        return z[0].copy() if np.array_equal(z, np.broadcast_to(z[0], z.shape)) else None

    def to_dataset(self):
        """Heights (and the fill mask) as an :class:`xarray.Dataset`, dims ``(y, x)``."""
        import xarray as xr

        data = {"heights": (("y", "x"), self.heights, {"units": "mm",
                                                        "long_name": "surface height z"})}
        if self.filled is not None:
            data["filled"] = (("y", "x"), self.filled.astype(np.int8),
                              {"long_name": "1 where a dropout was filled"})
        import json

        return xr.Dataset(data, coords={"x": ("x", self.x, {"units": "mm"}),
                                        "y": ("y", self.y, {"units": "mm"})},
                          attrs={"periodic": int(self.periodic), "Lx_mm": self.lengths[1],
                                 "Ly_mm": self.lengths[0], "source": json.dumps(self.source)})


def _flat_at_roundoff(residual: np.ndarray, heights: np.ndarray) -> np.ndarray:
    """``residual``, or zeros when it is within round-off (1e-12) of the ``heights`` it was
    detrended from: a constant or planar map leaves round-off, not a roughness to solve."""
    scale = float(np.abs(heights).max())
    return np.zeros_like(residual) if np.abs(residual).max() <= 1e-12 * scale else residual


def _mirror(a: np.ndarray) -> np.ndarray:
    """Even reflection about the last row and column, without repeating them."""
    a = np.concatenate([a, a[-2:0:-1]], axis=0)
    return np.concatenate([a, a[:, -2:0:-1]], axis=1)


def harmonic_fill(z: np.ndarray) -> np.ndarray:
    """``z`` with its NaN replaced by the discrete harmonic function on the measured rim.

    Each NaN point takes the mean of its 4 neighbours inside the map (the 5-point Laplace
    equation, the map's edges free), solved as one sparse system.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import spsolve

    z = np.array(z, dtype=float)
    gaps = np.isnan(z)
    if gaps.all():
        raise InputError("heights: every point is NaN (no measured height)")
    ny, nx = z.shape
    index = -np.ones(z.shape, int)
    index[gaps] = np.arange(gaps.sum())
    rows, cols, vals = [], [], []
    rhs = np.zeros(gaps.sum())
    degree = np.zeros(gaps.sum())
    jj, ii = np.nonzero(gaps)
    for dj, di in ((1, 0), (-1, 0), (0, 1), (0, -1)):
        nj, ni = jj + dj, ii + di
        inside = (nj >= 0) & (nj < ny) & (ni >= 0) & (ni < nx)
        p, nj, ni = index[jj[inside], ii[inside]], nj[inside], ni[inside]
        degree[p] += 1
        unknown = gaps[nj, ni]
        rows += [p[unknown]]
        cols += [index[nj[unknown], ni[unknown]]]
        vals += [-np.ones(unknown.sum())]
        np.add.at(rhs, p[~unknown], z[nj[~unknown], ni[~unknown]])
    k = np.arange(gaps.sum())
    a = coo_matrix((np.concatenate([degree, *vals]), (np.concatenate([k, *rows]),
                                                      np.concatenate([k, *cols]))),
                   shape=(k.size, k.size)).tocsr()
    z[gaps] = spsolve(a, rhs)
    return z


def max_height(hmap: HeightMap, newton_steps: int = 20) -> float:
    """Highest point [mm] of a periodic map's trigonometric polynomial.

    The sampled maximum refined by Newton's method on the exact gradient of the
    polynomial (its nonzero Fourier modes); a flat direction (a map uniform in y) is
    handled by the least-squares step. A non-periodic map gives its sampled maximum.
    """
    z = hmap.heights
    j, i = np.unravel_index(int(np.argmax(z)), z.shape)
    if not hmap.periodic:
        return float(z[j, i])
    ck = np.fft.fft2(z) / z.size
    ky = 2 * np.pi * np.fft.fftfreq(z.shape[0], hmap.dy)
    kx = 2 * np.pi * np.fft.fftfreq(z.shape[1], hmap.dx)
    nz = np.abs(ck) > 1e-14 * np.abs(ck).max()
    kyy, kxx = np.meshgrid(ky, kx, indexing="ij")
    c, k = ck[nz], np.stack([kxx[nz], kyy[nz]])
    r = np.array([i * hmap.dx, j * hmap.dy])
    best = float(z[j, i])
    for _ in range(int(newton_steps)):
        e = c * np.exp(1j * (k.T @ r))
        grad = -(k * e.imag).sum(axis=1)
        hess = -(k[:, None, :] * k[None, :, :] * e.real).sum(axis=2)
        step = np.linalg.lstsq(hess, -grad, rcond=1e-10)[0]
        if np.linalg.norm(step) > max(hmap.dx, hmap.dy):
            break                   # left the sampled maximum's basin: keep the best point
        r = r + step
        best = max(best, float(np.sum(c * np.exp(1j * (k.T @ r))).real))
        if np.linalg.norm(step) < 1e-14 * max(hmap.lengths):
            break
    return best
