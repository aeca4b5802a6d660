"""Roughness as a finite sum of sine waves (paper eq. 17).

``z(x) = Σ_i Δ_i sin(q_i x + φ_i)`` with ``q_i = 2π/λ_i``. Lengths in mm, phases
in rad. The paper uses the octave ladder ``q_i = 2^i q_0``; any wavelengths are
accepted as long as the fundamental period (the longest wavelength) is an integer
multiple of every other wavelength, which keeps the profile periodic.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from .._validation import finite_array, positive_scalar
from ..errors import InputError

#: Relative tolerance when checking that wavelengths divide the period.
_COMMENSURATE_RTOL = 1e-9


@dataclass(frozen=True, eq=False)
class SineSeries:
    """A periodic profile made of sine waves.

    Parameters
    ----------
    wavelengths
        ``λ_i`` [mm], each > 0. Stored sorted from shortest to longest.
    amplitudes
        ``Δ_i`` [mm], each >= 0.
    phases
        ``φ_i`` [rad]; zeros when omitted.
    """

    #: a profile z(x): what the solvers dispatch on (:mod:`~rubbercontact.roughness.protocol`)
    dimension: ClassVar[int] = 1
    wavelengths: np.ndarray
    amplitudes: np.ndarray
    phases: np.ndarray | None = None
    #: :meth:`sampled` grids of this series, by ``(length, n)`` (the series is immutable)
    _samples: dict = field(default_factory=dict, init=False, repr=False)

    def __post_init__(self) -> None:
        lam = finite_array("wavelengths", self.wavelengths, ndim=1, min_size=0)
        amp = finite_array("amplitudes", self.amplitudes, ndim=1, min_size=0)
        if lam.shape != amp.shape:
            raise InputError(f"wavelengths and amplitudes: lengths differ ({lam.size} vs "
                             f"{amp.size})")
        phi = (np.zeros_like(lam) if self.phases is None
               else finite_array("phases", self.phases, ndim=1, min_size=0))
        if phi.shape != lam.shape:
            raise InputError(f"phases: expected {lam.size} values, got {phi.size}")
        if np.any(lam <= 0):
            i = int(np.argmax(lam <= 0))
            raise InputError(f"wavelengths[{i}]: must be > 0 mm, got {lam[i]}")
        if np.any(amp < 0):
            i = int(np.argmax(amp < 0))
            raise InputError(f"amplitudes[{i}]: must be >= 0 mm, got {amp[i]}")
        if np.unique(lam).size != lam.size:
            raise InputError("wavelengths: duplicate values (merge them into one wave)")
        order = np.argsort(lam, kind="stable")
        lam, amp, phi = lam[order], amp[order], np.mod(phi[order], 2 * np.pi)
        if lam.size:
            ratio = lam[-1] / lam
            if np.any(np.abs(ratio - np.round(ratio)) > _COMMENSURATE_RTOL * ratio):
                raise InputError("wavelengths: the longest wavelength must be an integer "
                                 f"multiple of all others for a periodic profile, got {lam}")
        for name, arr in (("wavelengths", lam), ("amplitudes", amp), ("phases", phi)):
            arr = np.ascontiguousarray(arr, dtype=float)
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)

    # -- constructors -----------------------------------------------------------------
    @classmethod
    def ladder(cls, period: float, amplitudes, phases=None) -> SineSeries:
        """Octave ladder of the paper: ``λ_i = period / 2^i``, ``i = 0 … M−1``.

        ``amplitudes[i]`` belongs to ``λ_i`` (longest first).
        """
        period = positive_scalar("period", period, unit="mm")
        amp = finite_array("amplitudes", amplitudes, ndim=1)
        return cls(period / 2.0 ** np.arange(amp.size), amp, phases)

    def with_phases(self, phases) -> SineSeries:
        """Same waves with other phases [rad] (one per wave, shortest wavelength first)."""
        return SineSeries(self.wavelengths, self.amplitudes, phases)

    def realizations(self, n: int, seed: int | None = None) -> list[SineSeries]:
        """``n`` copies with independent uniform phases ``φ ~ U(0, 2π)`` (seeded)."""
        if int(n) != n or n < 1:
            raise InputError(f"n: number of realizations must be a positive integer, got {n}")
        rng = np.random.default_rng(seed)
        return [self.with_phases(rng.uniform(0.0, 2 * np.pi, self.size)) for _ in range(int(n))]

    # -- basic properties -------------------------------------------------------------
    @property
    def size(self) -> int:
        return int(self.wavelengths.size)

    def __len__(self) -> int:
        return self.size

    @property
    def wavenumbers(self) -> np.ndarray:
        """``q_i = 2π/λ_i`` [rad/mm]."""
        return 2 * np.pi / self.wavelengths

    @property
    def period(self) -> float:
        """Fundamental period = longest wavelength [mm] (0 for an empty series)."""
        return float(self.wavelengths[-1]) if self.size else 0.0

    def rms_slopes(self) -> np.ndarray:
        """``m2_i = q_i Δ_i / √2`` per wave [-] (paper eq. 16 for one sine)."""
        return self.wavenumbers * self.amplitudes / np.sqrt(2.0)

    @property
    def rms_height(self) -> float:
        """``sqrt(Σ Δ_i²/2)`` [mm], exact over one period for distinct wavelengths."""
        return float(np.sqrt(np.sum(self.amplitudes**2) / 2))

    @property
    def rms_slope(self) -> float:
        """``sqrt(Σ m2_i²)`` [-]."""
        return float(np.sqrt(np.sum(self.rms_slopes() ** 2)))

    def partition(self, m2_threshold: float = 1.0) -> tuple[SineSeries, SineSeries]:
        """Split into ``(high_slope, low_slope)``: waves with ``m2 > m2_threshold`` first."""
        thr = positive_scalar("m2_threshold", m2_threshold)
        hs = self.rms_slopes() > thr
        return self.subset(hs), self.subset(~hs)

    def subset(self, mask) -> SineSeries:
        """The waves selected by a boolean mask or index array."""
        return SineSeries(self.wavelengths[mask], self.amplitudes[mask], self.phases[mask])

    def __add__(self, other: SineSeries) -> SineSeries:
        return SineSeries(np.concatenate([self.wavelengths, other.wavelengths]),
                          np.concatenate([self.amplitudes, other.amplitudes]),
                          np.concatenate([self.phases, other.phases]))

    # -- evaluation -------------------------------------------------------------------
    def heights(self, x) -> np.ndarray:
        """``z(x)`` [mm] at positions ``x`` [mm] (any shape)."""
        x = np.asarray(x, dtype=float)
        arg = x[..., None] * self.wavenumbers + self.phases
        return (self.amplitudes * np.sin(arg)).sum(axis=-1)

    def slopes(self, x) -> np.ndarray:
        """Exact ``dz/dx`` [-] at ``x`` [mm]."""
        x = np.asarray(x, dtype=float)
        arg = x[..., None] * self.wavenumbers + self.phases
        return (self.amplitudes * self.wavenumbers * np.cos(arg)).sum(axis=-1)

    def sampled(self, length: float, n: int) -> tuple[np.ndarray, np.ndarray]:
        """``(z, dz/dx)`` on ``n`` uniform points ``x_j = j length / n`` [mm], read-only.

        Kept on the series: a half-space task solves one surface at several loads, and
        evaluating every wave at every grid point each time would repeat the same work.
        """
        key = (float(length), int(n))
        if key not in self._samples:
            x = np.arange(int(n)) * (float(length) / int(n))
            z, dz = self.heights(x), self.slopes(x)
            z.setflags(write=False)
            dz.setflags(write=False)
            self._samples[key] = (z, dz)
        return self._samples[key]

    def curvatures(self, x) -> np.ndarray:
        """Exact ``d²z/dx²`` [1/mm] at ``x`` [mm]."""
        x = np.asarray(x, dtype=float)
        arg = x[..., None] * self.wavenumbers + self.phases
        return -(self.amplitudes * self.wavenumbers**2 * np.sin(arg)).sum(axis=-1)

    def grid(self, n: int, period: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Sample ``n`` equally spaced points over one period: ``(x, z)`` [mm]."""
        if int(n) != n or n < 2:
            raise InputError(f"n: number of grid points must be an integer >= 2, got {n}")
        length = self.period if period is None else positive_scalar("period", period, unit="mm")
        if length <= 0:
            raise InputError("period: an empty SineSeries has no period; pass period=")
        x = np.arange(int(n)) * (length / int(n))
        return x, self.heights(x)

    def hdc(self, lag) -> np.ndarray:
        """Exact spatially averaged HDC ``R_zz(λ) = Σ 2Δ_i² sin²(q_i λ/2)`` [mm²] (eq. 14)."""
        lag = np.asarray(lag, dtype=float)
        return (2 * self.amplitudes**2 * np.sin(self.wavenumbers * lag[..., None] / 2) ** 2
                ).sum(axis=-1)

    def as_dict(self) -> dict:
        return {"wavelengths": self.wavelengths.tolist(), "amplitudes": self.amplitudes.tolist(),
                "phases": self.phases.tolist()}

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, SineSeries):
            return NotImplemented
        return all(np.array_equal(getattr(self, k), getattr(other, k))
                   for k in ("wavelengths", "amplitudes", "phases"))

    def __hash__(self) -> int:
        return hash((self.wavelengths.tobytes(), self.amplitudes.tobytes(), self.phases.tobytes()))

    def __repr__(self) -> str:
        phases = np.round(self.phases, 4).tolist()
        return (f"SineSeries(wavelengths={self.wavelengths.tolist()}, "
                f"amplitudes={self.amplitudes.tolist()}, phases={phases})")
