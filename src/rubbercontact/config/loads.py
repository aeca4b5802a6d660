"""The run's loads and sliding speeds: ``[loads]`` and ``velocities``."""

from __future__ import annotations

import difflib
from typing import Annotated

import numpy as np
from pydantic import Field, model_validator

from ..inputs import PositiveFloat
from ..inputs import Strict as _Strict

#: Most speeds of a ``velocities`` range.
MAX_SPEED_POINTS = 400


class LoadConfig(_Strict):
    """Applied loads: mean pressures, or target normal contact areas (pressures solved for)."""

    pressures: list[PositiveFloat] | None = Field(None, description="mean pressures σ0 [MPa]")
    contact_areas: list[Annotated[float, Field(gt=0, le=1)]] | None = Field(
        None, description="target normalized contact areas A_c/A_0 in (0, 1]")
    sweep_points: int | None = Field(
        None, ge=2, le=200, description="pressures of the sweep that brackets the target "
                                        "areas (default: max(6, areas + 2))")

    @model_validator(mode="after")
    def _one_kind(self) -> LoadConfig:
        if (self.pressures is None) == (self.contact_areas is None):
            raise ValueError("give exactly one of 'pressures' and 'contact_areas'")
        if self.sweep_points is not None and self.contact_areas is None:
            raise ValueError("'sweep_points' applies to 'contact_areas' only")
        return self



def _speed_range(value):
    """``{from, to, points}`` [mm/s] → log-spaced speeds (endpoints exact); lists pass."""
    if not isinstance(value, dict):
        return value
    keys = ("from", "to", "points")
    unknown = [k for k in value if k not in keys]
    if unknown:
        guess = difflib.get_close_matches(str(unknown[0]), keys, n=1)
        raise ValueError(f"unknown key '{unknown[0]}' in the range"
                         + (f"; did you mean '{guess[0]}'?" if guess else "")
                         + "; give from, to [mm/s] and points")
    missing = [k for k in keys if k not in value]
    if missing:
        raise ValueError(f"a range needs from, to [mm/s] and points; missing {missing}")
    lo, hi, n = value["from"], value["to"], value["points"]
    if not all(isinstance(x, int | float) and not isinstance(x, bool) for x in (lo, hi)):
        raise ValueError(f"from and to must be numbers [mm/s], got {lo!r}, {hi!r}")
    if not 0 < lo < hi or not np.isfinite(hi):
        raise ValueError(f"a log range needs 0 < from < to [mm/s], got from = {lo}, to = {hi}")
    if isinstance(n, bool) or not isinstance(n, int) or not 2 <= n <= MAX_SPEED_POINTS:
        raise ValueError(f"points must be an integer in [2, {MAX_SPEED_POINTS}], got {n!r}")
    return [float(x) for x in np.geomspace(float(lo), float(hi), n)]

