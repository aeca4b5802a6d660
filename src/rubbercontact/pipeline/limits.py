"""The physical range of a run's loads and speeds, checked where the user's input enters.

The solvers take any number; these checks refuse, with one line that states the bound,
inputs outside the range the models describe, before anything runs: a mean pressure at
or above the rubber's glassy modulus (the rubber would be squeezed by more than its own
size at any rate, far beyond the small strains of the half-space and the contact of the
FEM cell), and a negative sliding speed (the friction of ``-v`` is that of the mirrored
surface: the models slide the rubber in ``+x``).
"""

from __future__ import annotations

import math
from collections.abc import Iterable

from ..errors import InputError
from ..materials import GeneralizedMaxwell


def check_pressures(pressures: Iterable[float], material: GeneralizedMaxwell,
                    key: str) -> None:
    """Refuse mean pressures [MPa] that are not below the glassy modulus of ``material``.

    Parameters
    ----------
    pressures
        Mean (nominal) pressures σ0 [MPa].
    material
        The rubber; its glassy (instantaneous) modulus ``E_g`` [MPa] is the bound.
    key
        The config key or option named in the error.
    """
    bound = float(material.glassy_modulus)
    for value in pressures:
        p = _number(value, key, "MPa")
        if not (math.isfinite(p) and 0 < p < bound):
            raise InputError(f"{key}: mean pressure {p:g} MPa out of range: it must lie in "
                             f"(0, {bound:.4g}) MPa, below the rubber's glassy modulus E_g")


def _number(value, key: str, unit: str) -> float:
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InputError(f"{key}: expected a number [{unit}], got {value!r}") from None


def check_velocity(velocity: float, key: str, static: bool = True) -> None:
    """Refuse a negative (or non-finite) sliding speed [mm/s]; ``static``: 0 is allowed."""
    velocity = _number(velocity, key, "mm/s")
    ok = math.isfinite(velocity) and (velocity >= 0 if static else velocity > 0)
    if not ok:
        allowed = ">= 0 mm/s (0 is static contact)" if static else "> 0 mm/s"
        raise InputError(f"{key}: sliding speed {velocity:g} mm/s: must be {allowed}; the "
                         f"rubber slides in +x: for -v, mirror the surface")
