"""The readers' result: :class:`Profiles`, line scans sharing one sampling step."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..._validation import positive_scalar
from ...errors import InputError
from .cleaning import _cut, _step, _window_points


@dataclass(frozen=True, eq=False)
class Profiles:
    """Line scans sharing one sampling step.

    Attributes
    ----------
    profiles
        Read-only 1D height arrays [mm], NaN-free.
    dx
        Sampling step [mm].
    sources
        One dict per file: ``path``, ``sha256``, ``format``, ``unit`` and what was done
        (plates trimmed, dropouts, spikes replaced, scans kept).

    Raises
    ------
    InputError
        If there is no scan, ``dx`` is not a positive number, or a scan is not 1D, has
        fewer than 2 points or contains NaN.
    """

    profiles: tuple[np.ndarray, ...]
    dx: float
    sources: tuple[dict[str, Any], ...] = field(default_factory=tuple)

    def __post_init__(self) -> None:
        dx = positive_scalar("dx", self.dx, unit="mm")
        if not self.profiles:
            raise InputError("profiles: no scan left (empty input, or every window had "
                             "a dropout)")
        frozen = []
        for i, z in enumerate(self.profiles):
            arr = np.array(z, dtype=float)
            label = f"profiles[{i}]"
            if arr.ndim != 1:
                raise InputError(f"{label}: expected a 1D scan, got shape {arr.shape}")
            if arr.size < 2:
                raise InputError(f"{label}: needs at least 2 points, got {arr.size}"
                                 + (" (empty profile)" if arr.size == 0 else ""))
            if not np.all(np.isfinite(arr)):
                raise InputError(f"{label}: contains NaN heights; choose nan='windows' "
                                 "or 'interpolate'")
            arr.setflags(write=False)
            frozen.append(arr)
        object.__setattr__(self, "profiles", tuple(frozen))
        object.__setattr__(self, "dx", dx)
        object.__setattr__(self, "sources", tuple(dict(s) for s in self.sources))

    def __len__(self) -> int:
        return len(self.profiles)

    def __iter__(self) -> Iterator[np.ndarray]:
        return iter(self.profiles)

    @property
    def lengths(self) -> np.ndarray:
        """Length of each scan [mm] (``points × dx``)."""
        return np.array([z.size for z in self.profiles]) * self.dx

    @property
    def n_points(self) -> int:
        """Total number of heights over all scans."""
        return int(sum(z.size for z in self.profiles))

    def as_array(self) -> np.ndarray:
        """Scans stacked as rows.

        Returns
        -------
        numpy.ndarray
            Shape ``(scans, points)``.

        Raises
        ------
        InputError
            If the scans have different lengths.
        """
        sizes = {z.size for z in self.profiles}
        if len(sizes) != 1:
            raise InputError(f"profiles: scans have different lengths {sorted(sizes)}; "
                             "cut windows (nan='windows') for equal lengths")
        return np.stack(self.profiles)

    def windows(self, length: float, overlap: float = 0.5) -> Profiles:
        """Cut every scan into windows, e.g. to compare statistics at one scale.

        Parameters
        ----------
        length
            Window length [mm] (rounded to whole points, at least 2).
        overlap
            Fraction of a window shared by consecutive ones, in [0, 1).

        Returns
        -------
        Profiles
            The windows, with the same step and sources.
        """
        n = _window_points(length, self.dx)
        out = [w for z in self.profiles for w in _cut(z, n, _step(n, overlap))]
        return Profiles(tuple(out), self.dx, self.sources)

    def __repr__(self) -> str:
        lens = self.lengths
        return (f"Profiles({len(self)} scans, dx={self.dx:g} mm, length "
                f"{lens.min():g}–{lens.max():g} mm, from {len(self.sources)} source(s))")
