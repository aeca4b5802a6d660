r"""The paper's scale split on a height map: octave bands, ``z = z_ls + z_hs``, the cell.

Octave bands of the map's spectrum are centred on ``q_c = 2^k q_f``, ``q_f = 2π/Lx`` (the
map's fundamental along the sliding direction), band ``k`` holding the modes with
``q_c/√2 <= |q| < √2 q_c``; a wave of wavelength ``Lx/2^k`` sits at the centre of band ``k``,
so a map made of the paper's octave ladder splits wave by wave as the 1D
:meth:`rubbercontact.roughness.SineSeries.partition` does. A band is **high-slope** when its
rms slope along the sliding direction, ``sqrt(Σ_band q_x² P_k)``, exceeds the threshold (the
paper's ``m2 > 1``, eq. 16, read along x; SPEC.md "Maps").

``z_hs`` is the inverse FFT of the high-slope modes, ``z_ls`` of the others (with the mean):
``z = z_ls + z_hs`` to round-off, on the map's lattice.

The high-slope law is computed on a *cell*: one period ``λ_c = 2π/q_c`` of the longest
high-slope band in x and in y (the 1D cell is one period of the longest high-slope wave), or
``cell_periods`` such periods. The high-slope spectrum is carried onto the cell's lattice
``K = (2π/side)(m, n)``: each high-slope mode of the map gives its variance to the nearest
cell mode of the same band (the direction of the power is kept as well as the lattice
allows; the band's variance exactly), and the cell's surface is the trigonometric
polynomial with those variances and random (seeded) phases. When every high-slope mode of
the map lies on the cell's lattice (the map's ``z_hs`` is periodic on the cell), the cell
keeps the map's amplitudes and phases: it is ``z_hs`` itself. A map uniform in y with a wave
of wavelength ``λ_c`` gives the cell ``Δ sin(2πx/λ_c + φ)``: the 1D cell.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from .._validation import positive_scalar
from ..errors import InputError
from .maps import HeightMap
from .mapstats import mode_power
from .mapsynth import realize

#: Default points per side of the cell's realization.
CELL_POINTS = 64


@dataclass(frozen=True, eq=False)
class MapSplit:
    """The split of a periodic map (module docstring).

    Attributes
    ----------
    low, high
        ``z_ls`` (with the map's mean) and ``z_hs`` on the map's lattice [mm].
    bands
        Per octave band (dim ``band``): ``q_center`` [rad/mm], ``wavelength`` [mm],
        ``variance`` [mm²], ``rms_slope_x``, ``rms_slope_y``, ``rms_gradient`` [-], ``modes``,
        ``high_slope`` (1/0); ``threshold`` in attrs.
    cell
        The high-slope band on the cell's lattice (side ``cell_periods × λ_c``), or ``None``
        when no band is high-slope.
    cell_modes
        The cell's modes (dim ``mode``, one of each ``±K`` pair): ``kx``, ``ky`` [rad/mm],
        ``variance`` [mm²] (both members of the pair together), or ``None``.
    """

    low: HeightMap
    high: HeightMap
    bands: xr.Dataset
    cell: HeightMap | None
    cell_modes: xr.Dataset | None

    @property
    def cell_period(self) -> float:
        """``λ_c`` [mm], the period of the longest high-slope band (0 without one)."""
        return 0.0 if self.cell is None else self.cell.source["cell_period_mm"]

    @property
    def cell_side(self) -> float:
        """The cell's side [mm] (``cell_periods × λ_c``; 0 without a high-slope band)."""
        return 0.0 if self.cell is None else self.cell.lengths[1]


def _band_index(hmap: HeightMap) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, float]:
    """``(qx, qy, P, band)`` per FFT mode (band −1 for the mean) and ``q_f``."""
    qx, qy, p = mode_power(hmap)
    qf = 2 * np.pi / hmap.lengths[1]
    q = np.hypot(qx, qy)
    with np.errstate(divide="ignore"):
        band = np.where(q > 0, np.floor(np.log2(q / qf) + 0.5 + 1e-12), -1).astype(int)
    # q_c/√2 <= |q| < √2 q_c: log2(q/q_f) in [k − ½, k + ½); modes below q_f/√2 join band 0
    band = np.where(q > 0, np.maximum(band, 0), -1)
    return qx, qy, p, band, qf


def octave_bands(hmap: HeightMap, m2_threshold: float = 1.0) -> xr.Dataset:
    """The octave-band table of a map (module docstring); see :class:`MapSplit.bands`."""
    thr = positive_scalar("m2_threshold", m2_threshold)
    qx, qy, p, band, qf = _band_index(hmap)
    nb = int(band.max()) + 1
    ok = band >= 0

    def per_band(w):
        return np.bincount(band[ok], weights=w[ok], minlength=nb)

    sx, sy = np.sqrt(per_band(qx**2 * p)), np.sqrt(per_band(qy**2 * p))
    qc = qf * 2.0 ** np.arange(nb)
    data = {"q_center": ("band", qc, {"units": "rad/mm"}),
            "wavelength": ("band", 2 * np.pi / qc, {"units": "mm"}),
            "variance": ("band", per_band(p), {"units": "mm^2"}),
            "rms_slope_x": ("band", sx, {"units": "1"}),
            "rms_slope_y": ("band", sy, {"units": "1"}),
            "rms_gradient": ("band", np.hypot(sx, sy), {"units": "1"}),
            "modes": ("band", per_band(np.ones_like(p)).astype(int)),
            "high_slope": ("band", (sx > thr).astype(int))}
    return xr.Dataset(data, coords={"band": np.arange(nb)},
                      attrs={"threshold": thr, "criterion": "rms slope along x > threshold"})


def split_map(hmap: HeightMap, m2_threshold: float = 1.0, *, cell_points: int = CELL_POINTS,
              cell_periods: int = 1, seed: int | None = 0) -> MapSplit:
    """Split a periodic map into ``z_ls`` and ``z_hs`` and realize ``z_hs`` on its cell.

    Parameters
    ----------
    hmap
        A periodic :class:`HeightMap` (:meth:`HeightMap.periodized` for a measured one).
    m2_threshold
        A band whose rms slope along x exceeds it is high-slope [-].
    cell_points
        Points per side of the cell's realization (even, enough for its highest mode).
    cell_periods
        Cell side in periods ``λ_c`` of the longest high-slope band (1, 2, 4, …): a larger
        cell holds more of the band's modes.
    seed
        Of the cell's phases (unused when the map's high-slope modes all lie on the cell's
        lattice: the cell then takes the map's own amplitudes and phases, and is ``z_hs``
        itself up to the period).
    """
    if not isinstance(hmap, HeightMap):
        raise InputError(f"map: expected a HeightMap, got {type(hmap).__name__}")
    if not hmap.periodic:
        raise InputError("map: the split is spectral and needs a periodic map; use "
                         "map.periodized() first")
    bands = octave_bands(hmap, m2_threshold)
    qx, qy, p, band, _ = _band_index(hmap)
    high_bands = np.flatnonzero(bands["high_slope"].values)
    is_high = np.isin(band, high_bands)
    zk = np.fft.fft2(hmap.heights)
    z_hs = np.fft.ifft2(np.where(is_high, zk, 0.0)).real
    z_ls = np.fft.ifft2(np.where(is_high, 0.0, zk)).real
    note = {"split": f"m2 > {bands.attrs['threshold']:g} along x, high-slope bands "
                     f"{high_bands.tolist()}"}
    low = hmap.replace(z_ls, {**note, "part": "low-slope"})
    high = hmap.replace(z_hs, {**note, "part": "high-slope"})
    if high_bands.size == 0:
        return MapSplit(low, high, bands, None, None)
    if int(cell_periods) != cell_periods or cell_periods < 1 \
            or int(cell_periods) & (int(cell_periods) - 1):
        raise InputError(f"cell_periods: expected a power of 2 (1, 2, 4, …), got "
                         f"{cell_periods!r}")
    lam = float(bands["wavelength"].values[high_bands.min()])
    modes = (qx[is_high], qy[is_high], zk[is_high] / zk.size, band[is_high])
    cell, table = _cell(modes, lam, int(cell_periods), int(cell_points), seed, note)
    return MapSplit(low, high, bands, cell, table)


def _cell(modes, lam: float, periods: int, n: int, seed, note: dict
          ) -> tuple[HeightMap, xr.Dataset]:
    """The high-slope modes ``(qx, qy, ẑ, band)`` carried to the cell lattice and realized
    (module docstring)."""
    if n % 2 or n < 8:
        raise InputError(f"cell_points: expected an even number >= 8, got {n}")
    qx, qy, zc, band = modes
    power = np.abs(zc) ** 2
    live = power > 1e-15 * power.sum()      # modes with round-off power only carry nothing
    qx, qy, zc, band = qx[live], qy[live], zc[live], band[live]
    side = periods * lam
    k0, qc = 2 * np.pi / side, 2 * np.pi / lam
    mm, nn = np.meshgrid(np.arange(-n // 2 + 1, n // 2), np.arange(-n // 2 + 1, n // 2))
    kx, ky = (k0 * mm).ravel(), (k0 * nn).ravel()
    kq = np.hypot(kx, ky)
    with np.errstate(divide="ignore"):     # band 0 is λ_c's; longer cell modes are unused
        kband = np.where(kq > 0, np.floor(np.log2(kq / qc) + 0.5 + 1e-12), -1)
    offset = int(np.min(band))     # the map's band of λ_c
    target = np.zeros(band.size, int)
    for b in np.unique(band):
        cand = np.flatnonzero(kband == b - offset)
        if cand.size == 0:
            raise InputError(f"cell_points: {n} points per cell cannot hold band {b} "
                             f"(wavelength {lam / 2 ** (b - offset):.4g} mm); use more")
        sel = np.flatnonzero(band == b)
        d = (qx[sel, None] - kx[None, cand]) ** 2 + (qy[sel, None] - ky[None, cand]) ** 2
        target[sel] = cand[np.argmin(d, axis=1)]
    on_lattice = (np.allclose(kx[target], qx, rtol=0, atol=1e-9 * k0)
                  and np.allclose(ky[target], qy, rtol=0, atol=1e-9 * k0)
                  and np.unique(target).size == target.size)
    rows, cols = nn.ravel()[target] % n, mm.ravel()[target] % n
    if on_lattice:       # the map's high-slope part is periodic on the cell: keep it
        spec = np.zeros((n, n), complex)
        spec[rows, cols] = zc * n * n
        z = np.fft.ifft2(spec).real
        grid = np.zeros((n, n))
        grid[rows, cols] = np.abs(zc) ** 2
    else:
        grid = np.zeros((n, n))
        np.add.at(grid, (rows, cols), np.abs(zc) ** 2)
        grid = 0.5 * (grid + np.roll(grid[::-1, ::-1], 1, axis=(0, 1)))   # P(−K) = P(K)
        z = realize(grid, seed)
    cell = HeightMap(z, (side, side), periodic=True,
                     source={**note, "part": "high-slope cell", "cell_period_mm": lam,
                             "cell_side_mm": side,
                             "phases": "the map's" if on_lattice else f"random, seed {seed}"})
    half = (ky > 0) | ((ky == 0) & (kx > 0))
    power = grid[nn.ravel() % n, mm.ravel() % n]
    keep = half & (power > 0)
    table = xr.Dataset({"kx": ("mode", kx[keep], {"units": "rad/mm"}),
                        "ky": ("mode", ky[keep], {"units": "rad/mm"}),
                        "variance": ("mode", 2 * power[keep], {"units": "mm^2"})})
    return cell, table
