"""The discretised half-space problem: grid, heights, compliance and its operators.

A periodic surface is sampled on a uniform grid (1D ``(n,)`` or 2D ``(ny, nx)``, sliding along
the last axis ``x``). Every operator is applied with one ``rfftn``/``irfftn`` pair on a
precomputed kernel (:mod:`~rubbercontact.halfspace.kernels`); :class:`Problem` counts these
applications (``matvecs``). The multilevel starts use the same problem on every 4th point of a
1D grid, or on every 2nd point of each axis of a map: same period, and the lowest
wavenumbers of the fine rfft grid, hence the same ``M(q)`` there. Every algorithm returns a
:class:`Solution`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._validation import finite_array, positive_scalar
from ..errors import InputError
from ..roughness.protocol import check_surface
from . import kernels as kn
from .options import COARSE_FACTOR, SolverOptions

__all__ = ["MIN_POINTS", "Grid", "Problem", "Solution", "sample_surface"]

#: Smallest number of grid points per axis accepted.
MIN_POINTS = 8
#: Relative tolerance for "period is a multiple of every wavelength".
_PERIOD_RTOL = 1e-9


@dataclass(frozen=True, eq=False)
class Grid:
    """A surface sampled on the solver's grid.

    Attributes
    ----------
    shape, lengths
        Grid shape and periodic lengths [mm] per axis (``x`` last).
    heights
        ``z`` [mm] on the grid (the mean of a sampled surface removed).
    slope
        Exact ``∂z/∂x`` on the grid (a profile's own ``sampled`` slope, spectral otherwise).
    x, y
        Coordinates [mm] (``y`` is ``None`` in 1D).
    """

    shape: tuple[int, ...]
    lengths: tuple[float, ...]
    heights: np.ndarray
    slope: np.ndarray
    x: np.ndarray
    y: np.ndarray | None


@dataclass(frozen=True, eq=False)
class Solution:
    """What every algorithm returns: a state on the (flat) grid and how it was reached.

    Attributes
    ----------
    sigma, u, w
        Pressure [MPa], separation ``u = ū + w − z`` [mm] and displacement [mm], flat.
    ubar
        The mean-separation unknown [mm] (the multiplier of ``<σ> = σ0``; restarts use it).
    iterations
        Outer iterations of the algorithm (and of the stages before it).
    residual
        Final residual (per algorithm, see its docstring).
    converged
        Whether the tolerance was met.
    info
        Diagnostics (iteration histories, stage counts); ends up in ``SlidingResult.info``.
    """

    sigma: np.ndarray
    u: np.ndarray
    w: np.ndarray
    ubar: float
    iterations: int
    residual: float
    converged: bool
    info: dict = field(default_factory=dict)


@dataclass(eq=False)
class Problem:
    """One discretised contact problem (flat arrays) with its FFT operators.

    Mutable only in its counter ``matvecs`` (FFT-pair operator applications) and caches.
    """

    shape: tuple[int, ...]
    lengths: tuple[float, ...]
    z: np.ndarray  # flat, zero mean
    slope: np.ndarray  # flat dz/dx (exact)
    compliance: np.ndarray  # M on the rfft half-grid
    sigma0: float
    options: SolverOptions
    matvecs: int = 0
    _pre: np.ndarray | None = None
    _column: np.ndarray | None = None
    #: ``(set's index bytes, float32 LU factor)`` of the last dense contact-set solve
    _dense_lu: tuple | None = None
    _compliance32: np.ndarray | None = None
    _krylov: dict | None = None
    _cache: dict | None = None

    @property
    def size(self) -> int:
        return int(np.prod(self.shape))

    @property
    def compliance_diagonal(self) -> float:
        """``m_d``: the diagonal of ``M`` in real space [mm/MPa]."""
        return float(np.real(self.compliance).sum() * 2 / self.size)

    def apply(self, kernel: np.ndarray, flat: np.ndarray) -> np.ndarray:
        self.matvecs += 1
        return kn.apply_kernel(kernel, flat.reshape(self.shape),
                               split=self.options.split_inverse_fft_2d).ravel()

    def apply_single(self, kernel: np.ndarray, flat: np.ndarray) -> np.ndarray:
        """:meth:`apply` in single precision: float32 field, ``kernel`` complex64 or float32
        (:func:`~.kernels.single`); one FFT pair in ``matvecs``, float32 result."""
        self.matvecs += 1
        return kn.apply_kernel(kernel, flat.reshape(self.shape).astype(np.float32, copy=False),
                               split=self.options.split_inverse_fft_2d).ravel()

    def compliance_single(self) -> np.ndarray:
        """``M`` in single precision (cached)."""
        if self._compliance32 is None:
            self._compliance32 = kn.single(self.compliance)
        return self._compliance32

    def krylov_workspace(self) -> dict | None:
        """The GMRES bases kept between this problem's contact-set solves
        (``options.krylov_workspace_2d``; see :func:`~.krylov.gmres`), else ``None``."""
        if not self.options.krylov_workspace_2d:
            return None
        if self._krylov is None:
            self._krylov = {}
        return self._krylov

    def cache(self) -> dict:
        """A dict for quantities derived from the kernel alone (kept with the problem)."""
        if self._cache is None:
            self._cache = {}
        return self._cache

    def displacement(self, sigma: np.ndarray) -> np.ndarray:
        return self.apply(self.compliance, sigma)

    def column(self) -> np.ndarray:
        """Response of ``M`` to a unit pressure at point 0 (1D; cached): the circulant's
        first column, ``(M σ)_i = Σ_j col[(i − j) mod n] σ_j``."""
        return self._doubled_column()[self.size:]

    def _doubled_column(self) -> np.ndarray:
        # the column twice over: col2[n + i − j] = col[(i − j) mod n] for 0 <= i, j < n
        # without a modulo (a wrapping ``take`` costs four times a plain gather)
        if self._column is None:
            col = kn.inverse(self.compliance, self.shape).ravel()
            self._column = np.concatenate([col, col])
        return self._column

    def restricted(self, idx: np.ndarray) -> np.ndarray:
        """Dense matrix of ``M`` between the 1D grid points ``idx`` (``M[idx][:, idx]``),
        gathered from :meth:`column`."""
        return self._doubled_column().take(np.subtract.outer(idx + self.size, idx))

    def preconditioner(self) -> np.ndarray:
        """Hard-wall preconditioner kernel ``1/M`` (or ``1/Re M``, see the options; cached)."""
        if self._pre is None:
            self._pre = kn.stiffness_kernel(self.compliance,
                                            hermitian=not self.options.complex_preconditioner)
        return self._pre

    def with_compliance(self, compliance: np.ndarray) -> Problem:
        """The same surface and load with another compliance kernel (e.g. ``Re M``)."""
        return Problem(self.shape, self.lengths, self.z, self.slope, compliance, self.sigma0,
                       self.options)

    def can_coarsen(self, min_points: int | None, min_side: int | None = None) -> bool:
        """Whether a multilevel start applies: 1D, ``N`` divisible by 4, ``N/4 >= min_points``;
        a map, both sides even and halved at least ``min_side`` (``None``:
        ``options.coarse_min_side_2d``), and ``min_points``, the 1D switch, not ``None``."""
        if min_points is None:
            return False
        if len(self.shape) == 1:
            n = self.size
            return n % COARSE_FACTOR == 0 and n // COARSE_FACTOR >= min_points
        side = self.options.coarse_min_side_2d
        if side is not None and min_side is not None:
            side = min_side
        return side is not None and all(n % 2 == 0 and n // 2 >= max(side, MIN_POINTS)
                                        for n in self.shape)

    def coarse(self) -> Problem:
        """The same problem on every 4th grid point (1D) or every 2nd point per axis (map):
        same period, same kernel."""
        if len(self.shape) == 2:
            return self._coarse_map()
        nc = self.size // COARSE_FACTOR
        # the coarse rfft grid holds the first nc/2 + 1 wavenumbers of the fine one: same M(q)
        zc = self.z[::COARSE_FACTOR]
        return Problem((nc,), self.lengths, zc - zc.mean(), self.slope[::COARSE_FACTOR],
                       self.compliance[:nc // 2 + 1].copy(), self.sigma0, self.options)

    def _coarse_map(self) -> Problem:
        ny, nx = self.shape
        cy, cx = ny // 2, nx // 2
        # the coarse grid's wavenumbers are the fine grid's lowest: along y (full FFT axis)
        # the first cy/2 and the last cy/2 rows (the coarse Nyquist row is the fine row
        # −cy/2, whose M equals that of +cy/2), along x the first cx/2 + 1 columns
        rows = np.r_[0:cy // 2, ny - cy // 2:ny]
        comp = self.compliance[rows, :cx // 2 + 1].copy()
        zc = self.z.reshape(self.shape)[::2, ::2]
        sc = self.slope.reshape(self.shape)[::2, ::2]
        return Problem((cy, cx), self.lengths, (zc - zc.mean()).ravel(), sc.ravel(), comp,
                       self.sigma0, self.options)

    def refine(self, coarse_sigma: np.ndarray) -> np.ndarray:
        """A pressure of :meth:`coarse` interpolated (periodic, linear; bilinear on a map),
        ``<σ> = σ0`` restored."""
        n = self.size
        if len(self.shape) == 2:
            sigma = _bilinear_double(coarse_sigma.reshape(self.shape[0] // 2,
                                                          self.shape[1] // 2)).ravel()
        else:
            sigma = np.interp(np.arange(n), np.arange(n // COARSE_FACTOR) * COARSE_FACTOR,
                              coarse_sigma, period=n)
        sigma *= self.sigma0 * n / sigma.sum()
        return sigma


def _bilinear_double(coarse: np.ndarray) -> np.ndarray:
    """Periodic bilinear interpolation of a 2D field onto the grid of twice its points per
    axis (the coarse points are the fine grid's even points)."""
    cy, cx = coarse.shape
    fine = np.empty((2 * cy, 2 * cx))
    right = np.roll(coarse, -1, axis=1)
    fine[::2, ::2] = coarse
    fine[::2, 1::2] = 0.5 * (coarse + right)
    below = np.roll(fine[::2], -1, axis=0)
    fine[1::2] = 0.5 * (fine[::2] + below)
    return fine


def _commensurate(name: str, period: float, wavelengths: np.ndarray) -> None:
    ratio = period / wavelengths
    bad = np.abs(ratio - np.round(ratio)) > _PERIOD_RTOL * np.maximum(ratio, 1)
    if np.any(bad) or np.any(np.round(ratio) < 1):
        offending = (wavelengths[bad] if np.any(bad) else wavelengths).tolist()
        raise InputError(f"{name}: non-periodic length mismatch: period {period} mm is not an "
                         f"integer multiple of the wavelengths {offending} mm")


def sample_surface(surface, period, n: int) -> Grid:
    """Sample a surface on ``n`` points, or check sampled heights; see ``solve_sliding``.

    Dispatch on what the surface declares (:mod:`rubbercontact.roughness.protocol`), not
    on its class: a profile (``dimension`` 1) is sampled by its own ``sampled``, a map
    (``dimension`` 2) is taken on its grid; an array is heights.
    """
    if not hasattr(surface, "dimension") and (isinstance(surface, np.ndarray | list | tuple)
                                              or hasattr(surface, "__array__")):
        return _heights_grid(surface, period)
    if check_surface(surface) == 2:
        return _map_grid(surface, period)
    if int(n) != n or n < MIN_POINTS:
        raise InputError(f"n: number of grid points must be an integer >= {MIN_POINTS}, "
                         f"got {n}")
    n = int(n)
    own = float(surface.period)
    if not own > 0:
        raise InputError(f"surface: its period must be > 0 mm, got {own} (an empty SineSeries?)")
    length = own if period is None else positive_scalar("period", period, unit="mm")
    # a surface that declares its waves is checked against each (the message names the
    # offending ones) and must be resolved; otherwise against its period
    waves = getattr(surface, "wavelengths", None)
    waves = np.array([own]) if waves is None else np.asarray(waves, dtype=float)
    _commensurate("period", length, waves)
    # need at least 4 points per shortest wavelength to resolve its slope
    if n * float(np.min(waves)) / length < 4:
        raise InputError(f"n: {n} points over {length} mm give fewer than 4 points per "
                         f"shortest wavelength {float(np.min(waves))} mm")
    x = np.arange(n) * (length / n)
    heights, slopes = surface.sampled(length, n)
    heights = finite_array("surface.sampled heights", heights, ndim=1)
    slopes = finite_array("surface.sampled slopes", slopes, ndim=1)
    if heights.shape != (n,) or slopes.shape != (n,):
        raise InputError(f"surface.sampled: expected heights and slopes of shape ({n},), got "
                         f"{heights.shape} and {slopes.shape}")
    return Grid((n,), (length,), heights, slopes, x, None)


def _map_grid(surface, period) -> Grid:
    """A map (``dimension`` 2) on its own grid; ``period`` None or its lengths."""
    if getattr(surface, "periodic", True) is False:
        raise InputError("surface: the half-space solve takes the map as one period; use "
                         "map.periodized() first")
    lengths = finite_array("surface.lengths", surface.lengths, ndim=1)
    if lengths.size != 2 or np.any(lengths <= 0):
        raise InputError(f"surface.lengths: expected (Ly, Lx) > 0 mm, got {surface.lengths}")
    if period is not None and not _same_lengths(period, lengths):
        raise InputError(f"period: a map's lengths are its own, (Ly, Lx) = "
                         f"{tuple(lengths.tolist())} mm; pass None, got {period}")
    z = finite_array("surface.heights", surface.heights, ndim=2, min_size=MIN_POINTS)
    return _heights_grid(z, (float(lengths[0]), float(lengths[1])))


def _same_lengths(period, lengths: np.ndarray) -> bool:
    try:
        return bool(np.array_equal(np.broadcast_to(np.asarray(period, dtype=float), 2), lengths))
    except (TypeError, ValueError):
        return False


def _heights_grid(surface, period) -> Grid:
    """Sampled heights ``(n,)`` or ``(ny, nx)`` over ``period`` (a map: scalar or (Ly, Lx))."""
    z = finite_array("surface", surface, ndim=(1, 2), min_size=MIN_POINTS)
    if min(z.shape) < MIN_POINTS:
        raise InputError(f"surface: needs at least {MIN_POINTS} points per axis, got {z.shape}")
    if period is None:
        raise InputError("period: required for a sampled surface (length of the x axis [mm], "
                         "or (Ly, Lx) for a 2D map)")
    if z.ndim == 1:
        lengths = (positive_scalar("period", period, unit="mm"),)
    elif np.ndim(period) == 0:
        lx = positive_scalar("period", period, unit="mm")
        lengths = (lx * z.shape[0] / z.shape[1], lx)  # square pixels
    else:
        per = finite_array("period", period, ndim=1)
        if per.size != 2 or np.any(per <= 0):
            raise InputError(f"period: expected (Ly, Lx) > 0 for a 2D map, got {period}")
        lengths = (float(per[0]), float(per[1]))
    zx = kn.derivative_x(z, lengths[-1])
    x = np.arange(z.shape[-1]) * (lengths[-1] / z.shape[-1])
    y = np.arange(z.shape[0]) * (lengths[0] / z.shape[0]) if z.ndim == 2 else None
    return Grid(z.shape, lengths, z - z.mean(), zx, x, y)
