"""What a solver needs of a surface: the :class:`Surface` protocol.

A rigid surface slides along ``x`` over the rubber. Every surface declares its
``dimension``: 1 for a profile ``z(x)`` (plane strain, per unit width), 2 for a map
``z(y, x)``. The solvers dispatch on that declaration and look up the members they use,
never the class, so a user's own surface works wherever it has them:

* the half-space solver (:func:`rubbercontact.halfspace.solve_sliding`) samples a
  :class:`Profile` on its grid (``period``, ``sampled(length, n)``) and takes a
  :class:`SurfaceMap` on the map's own grid (``lengths``, ``heights``);
* the sine-series tools of the mean-field theory
  (:meth:`rubbercontact.meanfield.PSD.from_sines`,
  :func:`rubbercontact.meanfield.bands.strip_bands`) need the waves of a
  :class:`WaveProfile`, and the FEM cell (:func:`rubbercontact.fem.sliding_test`) its
  analytic heights, slopes and curvatures too: it meshes the cell by the shortest
  wavelength and bounds the surface's slope and curvature by ``Σ q_i Δ_i`` and
  ``Σ q_i² Δ_i``.

:class:`~rubbercontact.roughness.SineSeries` is a :class:`WaveProfile`,
:class:`~rubbercontact.roughness.HeightMap` a :class:`SurfaceMap`. The checks
(:func:`check_surface`, :func:`check_waves`) are structural like
:func:`rubbercontact.materials.check_material`: one :class:`~rubbercontact.errors.InputError`
line names what is missing.
"""

from __future__ import annotations

from collections.abc import Collection
from typing import Protocol

import numpy as np

from .._validation import require_members
from ..errors import InputError

__all__ = ["Surface", "Profile", "SurfaceMap", "WaveProfile", "check_surface", "check_waves"]

#: What every surface declares, and what it should be.
_SURFACE = {"dimension": "1 for a profile z(x), 2 for a map z(y, x) (sliding along x)"}
#: What a profile (dimension 1) needs for the half-space solver.
_PROFILE = {
    "period": "its period [mm] along x",
    "sampled": "a method (length [mm], n) -> (z [mm], dz/dx [-]) at x_j = j*length/n",
}
#: What a map (dimension 2) needs for the half-space solver.
_MAP = {
    "lengths": "(Ly, Lx) [mm], one period along each axis",
    "heights": "z [mm] on the map's grid, shape (ny, nx), x along the last axis",
}
#: What a profile made of sine waves has (the mean-field's sine tools).
_WAVES = {
    "wavelengths": "the waves' wavelengths lambda_i [mm]",
    "wavenumbers": "q_i = 2 pi / lambda_i [rad/mm]",
    "amplitudes": "Delta_i [mm], one per wave",
}
#: What the FEM cell needs besides the waves: the analytic profile.
_ANALYTIC = {
    "period": "its period [mm] along x",
    "heights": "a method x [mm] -> z [mm]",
    "slopes": "a method x [mm] -> dz/dx [-]",
    "curvatures": "a method x [mm] -> d2z/dx2 [1/mm]",
    "as_dict": "a method -> plain data recorded with the result",
}
_ANALYTIC_METHODS = ("heights", "slopes", "curvatures", "as_dict")
_HINT = "use rubbercontact.roughness.SineSeries or HeightMap, or any object with these members"
_KINDS = {1: "a profile (dimension 1)", 2: "a map (dimension 2)"}


class Surface(Protocol):
    """A rigid surface sliding along ``x``, as every solver sees it first."""

    @property
    def dimension(self) -> int:
        """1: a profile ``z(x)`` (plane strain); 2: a map ``z(y, x)``."""
        ...


class Profile(Surface, Protocol):
    """A periodic profile ``z(x)``, as the half-space solver samples it."""

    @property
    def period(self) -> float:
        """Its period [mm]; the solver's grid spans it (or an integer multiple)."""
        ...

    def sampled(self, length: float, n: int) -> tuple[np.ndarray, np.ndarray]:
        """``(z, dz/dx)`` [mm, -] at ``x_j = j·length/n``, ``j = 0 … n−1``, each shape
        ``(n,)``. The slope is the exact one: it is the friction's lever (``<σ dz/dx>``)."""
        ...


class SurfaceMap(Surface, Protocol):
    """One period of a map ``z(y, x)`` on its own uniform grid.

    A map may also declare ``periodic``; the half-space solver refuses one that declares
    ``False`` (a measured map's seams are cliffs it does not have), and takes one that
    does not declare it as periodic, as it takes an array of heights.
    """

    @property
    def lengths(self) -> tuple[float, float]:
        """``(Ly, Lx)`` [mm]: the period along each axis."""
        ...

    @property
    def heights(self) -> np.ndarray:
        """``z`` [mm], shape ``(ny, nx)``, ``heights[j, i] = z(i·Lx/nx, j·Ly/ny)``."""
        ...


class WaveProfile(Surface, Protocol):
    """A periodic profile ``z(x) = Σ_i Δ_i sin(q_i x + φ_i)`` as the FEM and the
    mean-field's sine tools see it: its waves and its analytic derivatives."""

    period: float
    wavelengths: np.ndarray
    wavenumbers: np.ndarray
    amplitudes: np.ndarray

    def heights(self, x) -> np.ndarray:
        """``z(x)`` [mm] at positions ``x`` [mm], any shape."""
        ...

    def slopes(self, x) -> np.ndarray:
        """``dz/dx`` [-] at ``x`` [mm]."""
        ...

    def curvatures(self, x) -> np.ndarray:
        """``d²z/dx²`` [1/mm] at ``x`` [mm]."""
        ...

    def as_dict(self) -> dict:
        """Plain data of the surface, recorded with a result."""
        ...


def check_surface(surface: object, *, what: str = "surface",
                  dimensions: Collection[int] = (1, 2), needs: str = "the half-space solver"
                  ) -> int:
    """The declared dimension of ``surface`` once it has what a half-space solve needs.

    Parameters
    ----------
    surface
        Any object; its members are looked up, its class is not.
    what
        The argument's name, the start of the error message.
    dimensions
        The dimensions the caller takes (a map solver: ``(2,)``).
    needs
        Who needs it, for the message when the dimension is not taken.

    Returns
    -------
    int
        1 (a :class:`Profile`) or 2 (a :class:`SurfaceMap`).

    Raises
    ------
    InputError
        One line naming the missing members, or the dimension that is not taken.
    """
    require_members(surface, _SURFACE, what=what, kind="a surface", hint=_HINT)
    dim = surface.dimension
    if isinstance(dim, bool) or dim not in _KINDS:
        raise InputError(f"{what}: dimension must be 1 (a profile) or 2 (a map), got {dim!r}")
    if dim not in dimensions:
        wanted = " or ".join(_KINDS[d] for d in sorted(dimensions))
        raise InputError(f"{what}: {needs} takes {wanted}, got {_KINDS[dim]}")
    if dim == 1:
        require_members(surface, _PROFILE, methods=("sampled",), what=what,
                        kind="a profile for the half-space solver", hint=_HINT)
    else:
        require_members(surface, _MAP, what=what, kind="a map for the half-space solver",
                        hint=_HINT)
    return int(dim)


def check_waves(surface: object, *, what: str = "surface", analytic: bool = False,
                needs: str = "the sine-series tools") -> WaveProfile:
    """Return ``surface`` if it is a profile that declares its sine waves, else raise.

    Parameters
    ----------
    surface
        Any object; its members are looked up, its class is not.
    what
        The argument's name, the start of the error message.
    analytic
        Also require the analytic profile the FEM cell needs (``period``, ``heights(x)``,
        ``slopes(x)``, ``curvatures(x)``, ``as_dict()``).
    needs
        Who needs it, for the messages.

    Raises
    ------
    InputError
        One line naming the missing members, or a map given for a profile.
    """
    hint = "use rubbercontact.roughness.SineSeries or any object with these members"
    require_members(surface, _SURFACE, what=what, kind="a surface", hint=hint)
    if surface.dimension != 1:
        raise InputError(f"{what}: {needs} needs a profile of sine waves (dimension 1), got "
                         f"dimension {surface.dimension!r}")
    members = {**_WAVES, **_ANALYTIC} if analytic else _WAVES
    require_members(surface, members, methods=_ANALYTIC_METHODS if analytic else (),
                    what=what, kind=f"a profile of sine waves for {needs}", hint=hint)
    return surface
