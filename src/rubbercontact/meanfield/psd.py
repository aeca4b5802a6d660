r"""The roughness power spectrum as the mean-field theory reads it.

Representation
--------------
A :class:`PSD` is a list of nodes ``q_i`` [rad/mm] (ascending) each carrying the part
``v_i`` [mm²] of the height variance that lies in its cell. Every integral of the theory
is then a sum over nodes, exact for a sine series and a quadrature for a continuous
spectrum:

* 1D profile, one-sided density ``C1(q)`` [mm³] (the convention of
  :func:`rubbercontact.roughness.psd`): ``v_i = C1(q_i) Δq_i``,
  ``Σ v_i = <z²>`` (rms height squared), ``Σ q_i² v_i = <z'²> = m2²`` (rms slope squared). A
  sine ``Δ sin(qx + φ)`` is one node ``(q, Δ²/2)``: its ``m2 = qΔ/√2`` is the project's.
* 2D isotropic surface, two-sided density ``C(q)`` [mm⁴] of the paper's eq. 11,
  ``<z²> = ∫ d²q C = 2π ∫ q C(q) dq``: ``v_i = 2π q_i C(q_i) Δq_i``; ``Σ v_i = <z²>`` and
  ``Σ q_i² v_i = <|∇z|²>`` (rms *gradient* squared); a line scan of the surface along any
  direction has the rms slope ``sqrt(<|∇z|²>/2)``.

The roughness statistics themselves (periodogram, detrending, HDC) are those of
:mod:`rubbercontact.roughness.statistics`; this module only changes their representation.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validation import finite_array, positive_scalar
from ..errors import InputError
from ..roughness.protocol import WaveProfile, check_waves
from ..roughness.sines import SineSeries
from ..roughness.statistics import psd as profile_psd

#: Nodes per decade of a continuous spectrum (self-affine or binned measured spectra).
NODES_PER_DECADE = 32


@dataclass(frozen=True, eq=False)
class PSD:
    """Roughness power spectrum as nodes ``(q_i, v_i)`` (module docstring).

    Attributes
    ----------
    wavenumbers
        ``q_i`` [rad/mm], ascending, > 0.
    variances
        ``v_i`` [mm²], >= 0: the height variance each node carries.
    dimension
        1 (profile, plane strain) or 2 (isotropic surface).
    waves
        The sine series the spectrum was built from (1D only), else ``None``; its waves
        are the nodes, so :meth:`partition` splits exactly as the hybrid does.
    source
        How the spectrum was made (for results and reports).
    """

    wavenumbers: np.ndarray
    variances: np.ndarray
    dimension: int = 1
    waves: SineSeries | None = None
    source: str = ""

    def __post_init__(self) -> None:
        q = finite_array("wavenumbers", self.wavenumbers, ndim=1)
        v = finite_array("variances", self.variances, ndim=1)
        if q.shape != v.shape:
            raise InputError(f"wavenumbers and variances: lengths differ ({q.size} vs {v.size})")
        if np.any(q <= 0):
            raise InputError(f"wavenumbers: must be > 0 rad/mm, got min {q.min():g}")
        if np.any(v < 0):
            raise InputError(f"variances: must be >= 0 mm², got min {v.min():g}")
        if np.any(np.diff(q) <= 0):
            raise InputError("wavenumbers: must be strictly increasing (one node per q)")
        if self.dimension not in (1, 2):
            raise InputError(f"dimension: expected 1 (profile) or 2 (isotropic surface), "
                             f"got {self.dimension!r}")
        if not np.any(v > 0):
            raise InputError("variances: all zero (a flat surface has no spectrum)")
        if self.waves is not None and self.dimension != 1:
            raise InputError("waves: a sine series is a 1D profile (dimension=1)")
        for name, arr in (("wavenumbers", q), ("variances", v)):
            arr = np.ascontiguousarray(arr, dtype=float)
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)

    # -- moments ------------------------------------------------------------------------
    @property
    def size(self) -> int:
        return int(self.wavenumbers.size)

    @property
    def rms_height(self) -> float:
        """``sqrt(Σ v_i)`` [mm]."""
        return float(np.sqrt(self.variances.sum()))

    @property
    def rms_gradient(self) -> float:
        """``sqrt(Σ q_i² v_i)`` [-]: the rms slope of a profile, the rms gradient in 2D."""
        return float(np.sqrt(np.sum(self.wavenumbers**2 * self.variances)))

    @property
    def rms_slope(self) -> float:
        """rms slope of a line scan [-]: ``rms_gradient`` in 1D, ``rms_gradient/√2`` in 2D."""
        return self.rms_gradient / (1.0 if self.dimension == 1 else np.sqrt(2.0))

    @property
    def density(self) -> np.ndarray:
        """``C1(q_i)`` [mm³] (1D) or ``C(q_i)`` [mm⁴] (2D) from the node variances.

        Cell widths are the geometric midpoints between nodes (for a sine series the
        density is a sum of deltas; this is its spread over the cells, for plots).
        """
        q = self.wavenumbers
        if q.size == 1:
            return np.array([np.nan])
        edges = np.concatenate([[q[0] ** 1.5 / q[1] ** 0.5], np.sqrt(q[1:] * q[:-1]),
                                [q[-1] ** 1.5 / q[-2] ** 0.5]])
        dq = np.diff(edges)
        return self.variances / dq / (1.0 if self.dimension == 1 else 2 * np.pi * q)

    def band_slopes(self, edges) -> np.ndarray:
        """rms slope of a line scan [-] carried by each band ``edges[k] <= q < edges[k+1]``."""
        e = finite_array("edges", edges, ndim=1, min_size=2)
        idx = np.digitize(self.wavenumbers, e) - 1
        m2sq = np.zeros(e.size - 1)
        ok = (idx >= 0) & (idx < e.size - 1)
        np.add.at(m2sq, idx[ok], (self.wavenumbers**2 * self.variances)[ok])
        return np.sqrt(m2sq / (1.0 if self.dimension == 1 else 2.0))

    # -- splitting ----------------------------------------------------------------------
    def partition(self, m2_threshold: float = 1.0) -> tuple[PSD | None, PSD | None]:
        """Split into ``(high_slope, low_slope)`` as the hybrid splits a surface.

        A spectrum made from a sine series splits wave by wave
        (:meth:`rubbercontact.roughness.SineSeries.partition`). A continuous 1D spectrum
        splits by octave bands counted down from its largest wavenumber: a band whose rms
        slope exceeds ``m2_threshold`` is high-slope. Either part may be ``None`` (empty).
        """
        thr = positive_scalar("m2_threshold", m2_threshold)
        if self.dimension != 1:
            raise InputError("partition: the high-slope law is a plane-strain FEM result; "
                             "split 1D spectra only")
        if self.waves is not None:
            hs, ls = self.waves.partition(thr)
            return (PSD.from_sines(hs) if hs.size else None,
                    PSD.from_sines(ls) if ls.size else None)
        q = self.wavenumbers
        n_oct = int(np.ceil(np.log2(q[-1] / q[0]) + 1e-9)) + 1
        edges = q[-1] * 1.000001 / 2.0 ** np.arange(n_oct, -1, -1)
        band = np.digitize(q, edges) - 1
        high = np.isin(band, np.flatnonzero(self.band_slopes(edges) > thr))
        return self._subset(high, "high-slope"), self._subset(~high, "low-slope")

    def _subset(self, mask: np.ndarray, label: str) -> PSD | None:
        if not np.any(mask & (self.variances > 0)):
            return None
        return PSD(self.wavenumbers[mask], self.variances[mask], self.dimension,
                   source=f"{label} part of {self.source or 'a spectrum'}")

    def as_dict(self) -> dict:
        """Plain data (tasks, cache keys): nodes, dimension and source."""
        return {"wavenumbers": self.wavenumbers.tolist(), "variances": self.variances.tolist(),
                "dimension": self.dimension, "source": self.source}

    @classmethod
    def from_dict(cls, data: dict) -> PSD:
        """Inverse of :meth:`as_dict`; a SineSeries dict (``wavelengths``, ``amplitudes``)
        is read as :meth:`from_sines`."""
        if not isinstance(data, dict):
            raise InputError(f"surface: expected a dict, got {type(data).__name__}")
        if "wavelengths" in data:
            return cls.from_sines(SineSeries(data["wavelengths"], data["amplitudes"],
                                             data.get("phases")))
        missing = [k for k in ("wavenumbers", "variances") if k not in data]
        if missing:
            raise InputError(f"surface: a spectrum needs the keys wavenumbers and variances "
                             f"(or a sine series: wavelengths, amplitudes); missing {missing}")
        return cls(data["wavenumbers"], data["variances"], int(data.get("dimension", 1)),
                   source=str(data.get("source", "")))

    # -- constructors -------------------------------------------------------------------
    @classmethod
    def from_sines(cls, surface: WaveProfile) -> PSD:
        """The exact spectrum of a sine series: one node ``(q_i, Δ_i²/2)`` per wave (1D).

        Phases do not enter: the mean-field theory sees the surface's statistics only.
        ``surface`` is a :class:`~rubbercontact.roughness.SineSeries` or any profile that
        declares its waves (:class:`~rubbercontact.roughness.WaveProfile`), kept as a
        SineSeries of them (:attr:`waves`, which :meth:`partition` splits).
        """
        check_waves(surface, needs="PSD.from_sines")
        # a SineSeries of the declared waves (and phases, if declared): partition() splits
        # it; for a SineSeries an equal one (its arrays are already sorted and reduced)
        surface = SineSeries(surface.wavelengths, surface.amplitudes,
                             getattr(surface, "phases", None))
        if surface.size == 0 or not np.any(surface.amplitudes > 0):
            raise InputError("surface: no wave with a non-zero amplitude")
        order = np.argsort(surface.wavenumbers)
        return cls(surface.wavenumbers[order], surface.amplitudes[order] ** 2 / 2, 1,
                   waves=surface, source=f"{surface.size} sine waves")

    @classmethod
    def from_profiles(cls, profiles, dx: float | None = None, *, detrend: str = "mean",
                      nodes_per_decade: int | None = NODES_PER_DECADE) -> PSD:
        """The mean periodogram of equal-length line scans (1D), by
        :func:`rubbercontact.roughness.psd` (its normalisation: ``Σ C1 Δq`` = variance).

        ``nodes_per_decade``: the periodogram's harmonics are pooled into log-spaced cells
        (variance summed, node at the cell's slope-weighted wavenumber
        ``sqrt(Σ q² v / Σ v)``), which keeps ``<z²>`` and ``<z'²>`` exact and smooths the
        periodogram's scatter; ``None`` keeps every harmonic. Scans of different lengths:
        cut them first (``Profiles.windows``).
        """
        q, c1 = profile_psd(profiles, dx, detrend=detrend)
        dq = q[0]                                   # harmonics k·2π/L: Δq = 2π/L
        v = c1 * dq
        src = f"periodogram of line scans (L = {2 * np.pi / dq:g} mm)"
        if nodes_per_decade is None:
            keep = v > 0
            return cls(q[keep], v[keep], 1, source=src)
        return cls(*_pool(q, v, nodes_per_decade), 1, source=src)

    @classmethod
    def from_map(cls, heights, lengths, *, nodes_per_decade: int | None = NODES_PER_DECADE
                 ) -> PSD:
        """The radially pooled periodogram of a periodic 2D height map (isotropic, 2D).

        ``heights`` [mm], shape ``(ny, nx)``; ``lengths = (Ly, Lx)`` [mm] or one length for
        square pixels along x. Each Fourier mode ``k`` carries ``|ẑ_k|²`` of the variance
        (Parseval, mean removed); modes are pooled by ``|k|`` into log cells as in
        :meth:`from_profiles`. For the map the 2D BEM solves this is its exact spectrum up
        to the pooling.
        """
        z = finite_array("heights", heights, ndim=2, min_size=16)
        if np.ndim(lengths) == 0:
            lx = positive_scalar("lengths", lengths, unit="mm")
            ly = lx * z.shape[0] / z.shape[1]
        else:
            ly, lx = (positive_scalar("lengths", x, unit="mm") for x in lengths)
        ny, nx = z.shape
        zk = np.fft.fft2(z - z.mean()) / z.size
        kx = 2 * np.pi * np.fft.fftfreq(nx, lx / nx)
        ky = 2 * np.pi * np.fft.fftfreq(ny, ly / ny)
        k = np.hypot(*np.meshgrid(ky, kx, indexing="ij")).ravel()
        v = (np.abs(zk) ** 2).ravel()
        keep = (k > 0) & (v > 1e-15 * v.sum())   # modes with round-off power only: dropped
        k, v = k[keep], v[keep]
        src = f"periodogram of a {ny}x{nx} map ({ly:g} x {lx:g} mm)"
        if nodes_per_decade is None:
            uq, inv = np.unique(k, return_inverse=True)
            return cls(uq, np.bincount(inv, weights=v), 2, source=src)
        return cls(*_pool(k, v, nodes_per_decade), 2, source=src)

    @classmethod
    def self_affine(cls, *, hurst: float, q1: float, qr: float | None = None,
                    q0: float | None = None, rms_height: float | None = None,
                    rms_slope: float | None = None, dimension: int = 1,
                    nodes_per_decade: int = NODES_PER_DECADE) -> PSD:
        r"""Self-affine spectrum with a roll-off: flat on ``[q0, qr)``, ``∝ q^-(2H+d)`` on
        ``[qr, q1]`` (``d`` the dimension: ``C1 ∝ q^-(1+2H)``, ``C ∝ q^-2(1+H)``), 0 outside.

        Parameters
        ----------
        hurst
            Hurst exponent ``H``, ``0 < H < 1``.
        q1
            Upper cut-off [rad/mm].
        qr
            Roll-off wavenumber [rad/mm] (default ``q0``: no roll-off).
        q0
            Lower cut-off [rad/mm] (default ``qr``); ``q0 <= qr < q1``.
        rms_height, rms_slope
            Exactly one: the rms height [mm], or the rms slope of a line scan [-] (the
            rms gradient is ``√2`` times larger in 2D).
        dimension
            1 or 2.
        nodes_per_decade
            Cells per decade; each cell's variance and slope moment are integrated
            exactly, so both rms values are exact whatever the resolution.
        """
        h = positive_scalar("hurst", hurst)
        if not h < 1:
            raise InputError(f"hurst: must lie in (0, 1), got {hurst}")
        q1 = positive_scalar("q1", q1, unit="rad/mm")
        if qr is None and q0 is None:
            raise InputError("self_affine: give qr (roll-off) and/or q0 (lower cut-off)")
        qr = positive_scalar("qr", qr if qr is not None else q0, unit="rad/mm")
        q0 = positive_scalar("q0", q0 if q0 is not None else qr, unit="rad/mm")
        if not q0 <= qr < q1:
            raise InputError(f"self_affine: need q0 <= qr < q1, got q0={q0:g}, qr={qr:g}, "
                             f"q1={q1:g} rad/mm")
        if dimension not in (1, 2):
            raise InputError(f"dimension: expected 1 or 2, got {dimension!r}")
        if (rms_height is None) == (rms_slope is None):
            raise InputError("self_affine: give exactly one of rms_height and rms_slope")
        if int(nodes_per_decade) != nodes_per_decade or nodes_per_decade < 2:
            raise InputError(f"nodes_per_decade: must be an integer >= 2, got "
                             f"{nodes_per_decade!r}")
        n = max(2, int(np.ceil(np.log10(q1 / q0) * nodes_per_decade)))
        edges = np.unique(np.concatenate([np.geomspace(q0, q1, n + 1), [qr]]))
        # cell moments of q^(d-1) C(q) (variance) and q^(d+1) C(q) (slope), C = 1 at qr
        m0 = _cell_moment(edges, qr, h, dimension, 0)
        m2 = _cell_moment(edges, qr, h, dimension, 2)
        if rms_height is not None:
            scale = positive_scalar("rms_height", rms_height, unit="mm") ** 2 / m0.sum()
        else:
            grad = positive_scalar("rms_slope", rms_slope) * (1.0 if dimension == 1
                                                             else np.sqrt(2.0))
            scale = grad**2 / m2.sum()
        q = np.sqrt(m2 / m0)
        return cls(q, scale * m0, dimension,
                   source=f"self-affine H={h:g}, q0={q0:g}, qr={qr:g}, q1={q1:g} rad/mm, "
                          f"{dimension}D")


def _pool(q: np.ndarray, v: np.ndarray, per_decade: int) -> tuple[np.ndarray, np.ndarray]:
    """Pool modes into log cells: summed variance at the slope-weighted wavenumber."""
    if int(per_decade) != per_decade or per_decade < 1:
        raise InputError(f"nodes_per_decade: must be a positive integer or None, got "
                         f"{per_decade!r}")
    qlo, qhi = float(q.min()), float(q.max())
    n = max(1, int(np.ceil(np.log10(qhi / qlo) * per_decade + 1e-9)))
    edges = np.geomspace(qlo, qhi * (1 + 1e-9), n + 1)
    idx = np.clip(np.digitize(q, edges) - 1, 0, n - 1)
    s0 = np.bincount(idx, weights=v, minlength=n)
    s2 = np.bincount(idx, weights=q**2 * v, minlength=n)
    keep = s0 > 0
    return np.sqrt(s2[keep] / s0[keep]), s0[keep]


def _cell_moment(edges: np.ndarray, qr: float, h: float, dim: int, k: int) -> np.ndarray:
    """``∫ q^(k) · (2π q)^(d-1) C(q) dq`` over each cell, ``C = 1`` on ``[q0, qr)``,
    ``(q/qr)^-(2H+d)`` above (the node variance for k = 0, its slope moment for k = 2)."""
    lo, hi = edges[:-1], edges[1:]
    pref = (2 * np.pi) ** (dim - 1)
    flat = pref * (hi ** (k + dim) - lo ** (k + dim)) / (k + dim)
    e = k + dim - (2 * h + dim)            # exponent of q in q^(k+d-1) q^-(2H+d), plus 1
    power = pref * qr ** (2 * h + dim) * (hi**e - lo**e) / e
    return np.where(hi <= qr * (1 + 1e-12), flat, power)
