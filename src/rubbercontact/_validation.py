"""Boundary checks: turn bad user input into one clear :class:`InputError`.

Physics kernels assume clean arrays; these helpers are called where data enter
(public constructors, solvers' entry points, readers, config).
"""

from __future__ import annotations

import numbers
from collections.abc import Collection, Mapping

import numpy as np

from .errors import InputError


def finite_array(name: str, value, *, ndim: int | tuple[int, ...] | None = None,
                 min_size: int = 1, dtype=float) -> np.ndarray:
    """Return ``value`` as a finite ndarray, or raise :class:`InputError` naming ``name``."""
    try:
        arr = np.asarray(value, dtype=dtype)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name}: cannot be read as an array of numbers ({exc})") from None
    if ndim is not None:
        allowed = (ndim,) if isinstance(ndim, int) else ndim
        if arr.ndim not in allowed:
            raise InputError(f"{name}: expected {' or '.join(map(str, allowed))}-dimensional "
                             f"data, got shape {arr.shape}")
    if arr.size < min_size:
        raise InputError(f"{name}: needs at least {min_size} value(s), got {arr.size}")
    bad = ~np.isfinite(arr)
    if bad.any():
        idx = np.argwhere(bad)[0]
        where = tuple(int(i) for i in idx) if arr.ndim > 1 else int(idx[0])
        raise InputError(f"{name}: contains NaN or infinite values ({int(bad.sum())} of "
                         f"{arr.size}, first at index {where})")
    return arr


def positive_scalar(name: str, value, *, allow_zero: bool = False, unit: str = "") -> float:
    """Return ``value`` as a float that is > 0 (or >= 0), else raise :class:`InputError`."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real | np.ndarray):
        raise InputError(f"{name}: expected a number{f' in {unit}' if unit else ''}, got {value!r}")
    v = float(np.asarray(value))
    u = f" {unit}" if unit else ""
    if not np.isfinite(v):
        raise InputError(f"{name}: must be finite, got {v}{u}")
    if v < 0 or (v == 0 and not allow_zero):
        rel = ">= 0" if allow_zero else "> 0"
        raise InputError(f"{name}: must be {rel}, got {v}{u}")
    return v


def missing_members(obj: object, members: Mapping[str, str],
                    methods: Collection[str] = ()) -> list[str]:
    """The names of ``members`` that ``obj`` lacks, or has but cannot call (``methods``).

    The structural check of a protocol (a material, a law): members are looked up, the
    class is not, so any object that has them passes.
    """
    return [m for m in members
            if not hasattr(obj, m) or (m in methods and not callable(getattr(obj, m)))]


def require_members(obj: object, members: Mapping[str, str], *, what: str, kind: str,
                    hint: str, methods: Collection[str] = ()) -> None:
    """Raise :class:`InputError` unless ``obj`` has every member (:func:`missing_members`).

    Parameters
    ----------
    members
        Name -> what it should be; the message lists the missing ones with these words.
    what, kind, hint
        The message reads ``"{what}: {class} is not {kind} (missing ...); {hint}"``, one line.
    methods
        The members that must be callable.
    """
    missing = missing_members(obj, members, methods)
    if missing:
        wants = "; ".join(f"{m}: {members[m]}" for m in missing)
        raise InputError(f"{what}: {type(obj).__name__} is not {kind} (missing {wants}); "
                         f"{hint}")
