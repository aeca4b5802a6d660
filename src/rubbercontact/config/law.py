"""The ``[law]`` table: the effective interface law of the high-slope scale."""

from __future__ import annotations

from pathlib import Path
from typing import Literal

from pydantic import Field

from ..inputs import PositiveFloat
from ..inputs import Strict as _Strict


class LawConfig(_Strict):
    """Effective interface law of the high-slope scale (paper eqs. 1–3)."""

    pressures: list[PositiveFloat] | None = Field(
        None, min_length=2, description="FEM pressure grid [MPa] (at least 2); default: 8 "
                                        "from half the smallest to 8x the largest load, "
                                        "extended (law.extend) to the local pressures")
    file: Path | None = Field(None, description="reuse a saved law (NetCDF) instead of running FEM")
    speed_path: Literal["auto", "points", "continuation"] = Field(
        "auto", description="FEM law points: 'points' one task per (speed, pressure); "
                            "'continuation' one task per pressure following the speeds "
                            "(steady solver); 'auto': continuation from 3 speeds on")
    extend: bool = Field(
        True, description="add FEM pressures (half-decade steps) until the law covers the "
                          "local pressures of the low-slope solve at every speed")
    max_pressure: PositiveFloat | None = Field(
        None, description="highest pressure the law is extended to [MPa] (default: below "
                          "the rubber's glassy modulus)")
    quasi_static_check: bool = Field(
        True, description="one FEM point per law pressure at the quasi-static speed, where "
                          "the law's friction must vanish on a resolved cell (the run warns "
                          "where it does not)")
