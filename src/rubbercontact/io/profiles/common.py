"""Shared pieces of the profile readers: units, the sampling-step check, file hashes and
the plausibility warning.

Every reader converts lengths to mm with :func:`unit_factor`, checks position columns
with :func:`uniform_step`, records :func:`sha256_file` of its input and warns through
:func:`check_plausible` when the heights look like the wrong unit.
"""

from __future__ import annotations

import hashlib
import math
import warnings
from collections.abc import Iterable
from pathlib import Path
from typing import Literal

import numpy as np

from ...errors import InputError
from ...roughness.fit import RoughnessWarning

NanPolicy = Literal["windows", "interpolate", "error"]
Format = Literal["auto", "text", "captif", "topography"]

#: Length units accepted in files, in mm.
UNITS_MM = {"mm": 1.0, "um": 1e-3, "µm": 1e-3, "μm": 1e-3, "micron": 1e-3, "nm": 1e-6,
            "m": 1e3, "cm": 10.0, "in": 25.4}
#: Largest deviation of the positions from a uniform grid, as a fraction of dx (the
#: CAPTIF files round x to 1 µm at dx = 37.5 µm: 1.3 %).
SPACING_RTOL = 0.1
_SPACING_HINT = "resample the scan to a uniform grid first"


def sha256_file(path: str | Path) -> str:
    """SHA-256 of a file's bytes.

    Parameters
    ----------
    path
        The file, read in chunks of 1 MiB.

    Returns
    -------
    str
        The hexadecimal digest.
    """
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def unit_factor(unit: str, name: str = "unit") -> float:
    """Factor that converts ``unit`` to mm.

    Parameters
    ----------
    unit
        A key of :data:`UNITS_MM` (surrounding blanks ignored).
    name
        The argument's name in the error message.

    Returns
    -------
    float
        Millimetres per ``unit``.

    Raises
    ------
    InputError
        If ``unit`` is not a known length unit.
    """
    key = str(unit).strip()
    if key not in UNITS_MM:
        raise InputError(f"{name}: unknown length unit {unit!r}; use one of "
                         f"{', '.join(sorted(set(UNITS_MM) - {'μm', 'micron'}))}")
    return UNITS_MM[key]


def uniform_step(x: np.ndarray, name: str = "x") -> float:
    """The sampling step of positions ``x``, checked to be uniform.

    Parameters
    ----------
    x
        Increasing, finite positions (at least 2).
    name
        The positions' name in error messages.

    Returns
    -------
    float
        The mean step, in the unit of ``x``.

    Raises
    ------
    InputError
        If ``x`` has fewer than 2 points, NaN, does not increase, or is off a uniform
        grid by more than :data:`SPACING_RTOL` of a step.
    """
    x = np.asarray(x, dtype=float)
    if x.size < 2:
        raise InputError(f"{name}: needs at least 2 positions, got {x.size}")
    if not np.all(np.isfinite(x)):
        raise InputError(f"{name}: contains NaN positions (first at index "
                         f"{int(np.argmax(~np.isfinite(x)))})")
    steps = np.diff(x)
    if np.any(steps <= 0):
        i = int(np.argmax(steps <= 0))
        raise InputError(f"{name}: positions must increase, but x[{i + 1}] = {x[i + 1]:g} "
                         f"<= x[{i}] = {x[i]:g}")
    dx = (x[-1] - x[0]) / (x.size - 1)
    dev = np.abs(x - (x[0] + dx * np.arange(x.size)))
    if dev.max() > SPACING_RTOL * dx:
        raise InputError(f"{name}: non-uniform spacing (steps from {steps.min():g} to "
                         f"{steps.max():g}, positions off a uniform grid by up to "
                         f"{dev.max() / dx:.0%} of the mean step {dx:g}); {_SPACING_HINT}")
    return float(dx)


def check_plausible(profiles: Iterable[np.ndarray], source: str, unit: str) -> None:
    """Warn when the rms height is implausible for mm.

    Parameters
    ----------
    profiles
        Height arrays [mm]; empty ones are ignored.
    source
        The data's name in the warning.
    unit
        The unit the numbers were read in, suggested in the warning.

    Warns
    -----
    RoughnessWarning
        If the pooled rms height exceeds 100 mm or is below 1 nm (but not 0).
    """
    zs = [z for z in profiles if z.size]
    if not zs:
        return
    total = sum(float(np.sum((z - z.mean()) ** 2)) for z in zs)
    rms = math.sqrt(total / sum(z.size for z in zs))
    if rms > 100.0:
        warnings.warn(f"{source}: rms height {rms:g} mm (> 100 mm) is implausible for a "
                      f"rough surface: are the heights in {unit}? (did you give mm as µm, "
                      f"or pass unit='{unit}' for data in µm?)", RoughnessWarning, stacklevel=3)
    elif 0 < rms < 1e-6:
        warnings.warn(f"{source}: rms height {rms:g} mm (< 1 nm) is implausibly small: did "
                      f"you give metres as mm? Pass the file's unit (unit='m').",
                      RoughnessWarning, stacklevel=3)
