"""The ``[meanfield]`` table: the options of the mean-field models."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import Field, model_validator

from .._optionfields import option_default
from ..inputs import Strict as _Strict
from ..meanfield.options import (
    DISSIPATIONS,
    INTERFACES,
    WEIGHTINGS,
    Dissipation,
    SCorrection,
    StripOptions,
    Weighting,
)
from ..meanfield.psd import NODES_PER_DECADE


class MeanFieldConfig(_Strict):
    """Options of the mean-field models (:mod:`rubbercontact.meanfield.options`):
    ``meanfield`` (Persson's theory with S(q)), ``meanfield-hybrid`` (the same with the
    high-slope law) and ``meanfield-strips`` (the strip cascade of a 1D sine series). A key
    left out is the model's default; a key for a model the run does not include is refused.
    """

    # None is "the model's default": the defaults named in the help are the option
    # objects' own (meanfield/options.py), so they cannot drift from what runs
    gamma: float | None = Field(
        None, gt=0, le=1, description=f"Persson's S = gamma + (1 - gamma) A^2 (meanfield, "
                                      f"meanfield-hybrid; default "
                                      f"{option_default(SCorrection, 'gamma'):g}, chosen "
                                      f"against the BEM; 1: S = 1, Persson 2001) [-]")
    weighting: Literal[WEIGHTINGS] | None = Field(
        None, description=f"contact fraction weighing a node's friction: cell (the mean over "
                          f"its cell, Persson's integral) or after (after the wave, sine "
                          f"series); default {option_default(Weighting, 'kind')}; meanfield, "
                          f"meanfield-hybrid")
    dissipation: Literal[DISSIPATIONS] | None = Field(
        None, description=f"where a mode in partial contact dissipates: at its own "
                          f"wavenumber (mode, Persson's) or at the harmonics of its contact "
                          f"patches (patch, cascade; 1D; use gamma = 1 with them); default "
                          f"{option_default(Dissipation, 'kind')}; meanfield, "
                          f"meanfield-hybrid")
    interface: Literal[INTERFACES] | None = Field(
        None, description="meanfield-hybrid: the law's compliance in series with the "
                          "half-space (law, default), or a rigid low-slope contact (rigid)")
    outer_crests: bool | None = Field(
        None, description=f"meanfield-strips: a wave's crests just outside a longer wave's "
                          f"strip come into contact (default "
                          f"{str(option_default(StripOptions, 'outer_crests')).lower()}; "
                          f"false: the nested strips)")
    spectrum: Literal["sines", "profiles"] | None = Field(
        None, description="meanfield: the spectrum the theory reads, the sine series of the "
                          "surface (default) or the periodogram of the measured profiles")
    nodes_per_decade: int | None = Field(
        None, ge=2, le=1000, description=f"spectrum = 'profiles': log cells per decade of "
                                         f"the periodogram (default {NODES_PER_DECADE})")

    @model_validator(mode="before")
    @classmethod
    def _removed(cls, data: Any) -> Any:
        if isinstance(data, dict):
            for key, why in REMOVED_MEANFIELD_KEYS.items():
                if key in data:
                    raise ValueError(f"meanfield.{key} was removed (issue 38): {why}")
        return data

    @model_validator(mode="after")
    def _profiles_only(self) -> MeanFieldConfig:
        if self.nodes_per_decade is not None and self.spectrum != "profiles":
            raise ValueError("'nodes_per_decade' applies to spectrum = 'profiles' only")
        return self

    def check_models(self, models) -> None:
        """Refuse (ValueError, one line) a key set for models the run does not include."""
        for key, users in MEANFIELD_KEYS.items():
            if getattr(self, key) is not None and not set(users) & set(models):
                raise ValueError(f"meanfield.{key} applies to {' or '.join(users)}, which "
                                 "the run does not include; add the model or drop the key")

    def options(self, model: str):
        """The options object of ``model`` (defaults where a key is left out)."""
        from ..meanfield import MeanFieldOptions, StripOptions

        if model == "meanfield-strips":
            return StripOptions() if self.outer_crests is None else StripOptions(
                self.outer_crests)
        given = {"correction": self.gamma, "weighting": self.weighting,
                 "dissipation": self.dissipation,
                 "interface": self.interface if model == "meanfield-hybrid" else None}
        return MeanFieldOptions(**{k: v for k, v in given.items() if v is not None})


#: The ``[meanfield]`` keys and the models that read them (the rest are refused).
MEANFIELD_KEYS = {"gamma": ("meanfield", "meanfield-hybrid"),
                  "weighting": ("meanfield", "meanfield-hybrid"),
                  "dissipation": ("meanfield", "meanfield-hybrid"),
                  "interface": ("meanfield-hybrid",),
                  "outer_crests": ("meanfield-strips",),
                  "spectrum": ("meanfield",)}
#: Keys of the options before the mean-field models were split (issue 38), and the way now.
REMOVED_MEANFIELD_KEYS = {
    "correction": "Persson's S(q) is always on; set gamma (gamma = 1 is S = 1)",
    "geometry": "the strip cascade is the model 'meanfield-strips', Persson's diffusion the "
                "model 'meanfield'"}

