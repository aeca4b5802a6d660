"""The ``[halfspace]`` table: the half-space solves' options."""

from __future__ import annotations

from typing import Literal

from pydantic import Field

from .._optionfields import option_field
from ..inputs import PositiveFloat
from ..inputs import Strict as _Strict
from ..models.halfspace import LAWS, HalfspaceOptions


class HalfSpaceConfig(_Strict):
    """The half-space solves (:class:`rubbercontact.models.HalfspaceOptions`: defaults and
    help are its own)."""

    n: int = option_field(HalfspaceOptions, "n", ge=64, le=2**22)
    hybrid_n: int | None = Field(
        None, ge=64, le=2**22,
        description="grid points per period of the hybrid's low-slope solve (default: n "
                    "halved while z_ls's shortest wave keeps the points per wave n gives "
                    "z's shortest; rubbercontact.hybrid.grid)")
    law: Literal[LAWS] = option_field(HalfspaceOptions, "law")
    tol: PositiveFloat = option_field(HalfspaceOptions, "tol", lt=1)

