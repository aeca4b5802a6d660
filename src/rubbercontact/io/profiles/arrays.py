"""In-memory heights as :class:`Profiles`: :func:`profiles_from_arrays`."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..._validation import positive_scalar
from ...errors import InputError
from .cleaning import _finish
from .common import SPACING_RTOL, NanPolicy, check_plausible, uniform_step, unit_factor
from .container import Profiles


def profiles_from_arrays(heights: np.ndarray | Sequence[Any], dx: float | None = None, *,
                         x: ArrayLike | None = None, unit: str = "mm",
                         nan: NanPolicy = "error", window: float = 16.0,
                         window_overlap: float = 0.5, despike: bool = False,
                         despike_window: int = 7, despike_k: float = 5.0,
                         source: str = "array") -> Profiles:
    """:class:`Profiles` from in-memory heights.

    Parameters
    ----------
    heights
        A 1D scan, a 2D array (one scan per row) or a list of 1D scans, in ``unit``.
    dx
        Sampling step [mm]; optional when ``x`` is given (then it must agree with it
        within :data:`SPACING_RTOL`).
    x
        Positions [``unit``] shared by all scans, uniform.
    unit
        Unit of ``heights`` and ``x`` (a key of :data:`UNITS_MM`).
    nan
        Dropout policy: ``"error"`` (default) refuses NaN; ``"windows"`` or
        ``"interpolate"`` as for the file readers.
    window, window_overlap
        Window length [mm] and overlap under ``nan="windows"``.
    despike, despike_window, despike_k
        Whether to apply the Hampel filter (:func:`despike`), and its settings.
    source
        The data's name in the metadata and warnings.

    Returns
    -------
    Profiles
        The scans [mm] with one source dict (``format="array"``).

    Raises
    ------
    InputError
        On unreadable, empty or non-1D scans, mismatched ``x``, a missing or
        disagreeing ``dx``, or NaN refused by ``nan``.
    """
    fac = unit_factor(unit)
    if isinstance(heights, np.ndarray) and heights.ndim == 2:
        scans = list(heights)
    elif isinstance(heights, np.ndarray) or (isinstance(heights, Sequence) and len(heights)
                                             and np.isscalar(heights[0])):
        scans = [heights]
    elif isinstance(heights, Sequence):
        scans = list(heights)
    else:
        raise InputError(f"heights: expected an array or a list of arrays, got "
                         f"{type(heights).__name__}")
    if not scans:
        raise InputError("heights: no profile given (empty list)")
    arrs = []
    for i, z in enumerate(scans):
        label = "heights" if len(scans) == 1 else f"heights[{i}]"
        try:
            a = np.asarray(z, dtype=float) * fac
        except (TypeError, ValueError) as exc:
            raise InputError(f"{label}: cannot be read as numbers ({exc})") from None
        if a.ndim != 1:
            raise InputError(f"{label}: expected a 1D scan, got shape {a.shape}")
        if a.size == 0:
            raise InputError(f"{label}: empty profile (no height values)")
        arrs.append(a)
    if x is not None:
        xs = np.asarray(x, dtype=float) * fac
        for i, a in enumerate(arrs):
            if a.size != xs.size:
                label = "heights" if len(arrs) == 1 else f"heights[{i}]"
                raise InputError(f"x and {label}: mismatched lengths ({xs.size} positions, "
                                 f"{a.size} heights)")
        step = uniform_step(xs, "x")
        if dx is not None and not math.isclose(step, positive_scalar("dx", dx, unit="mm"),
                                                rel_tol=SPACING_RTOL):
            raise InputError(f"dx: {dx} mm disagrees with the step of x ({step:g} mm)")
        dx = step
    elif dx is None:
        raise InputError("dx: give the sampling step [mm] or the positions x")
    dx = positive_scalar("dx", dx, unit="mm")
    cleaned = _finish(arrs, dx, label="heights" if len(arrs) == 1 else source, nan=nan,
                      window=window, window_overlap=window_overlap, despike_=despike,
                      despike_window=despike_window, despike_k=despike_k,
                      meta={"path": source, "format": "array", "unit": unit})
    check_plausible(cleaned.scans, source, unit)
    return Profiles(tuple(cleaned.scans), dx, (cleaned.meta,))
