"""The whole run's table (:class:`RunConfig`): its models and the checks across tables."""

from __future__ import annotations

from typing import Annotated, Literal

import numpy as np
from pydantic import Field, field_validator, model_validator

from ..inputs import MaterialSpec, SurfaceSpec
from ..inputs import Strict as _Strict
from ..models.registry import plannable
from .execution import ExecutionConfig, OutputConfig
from .fem import FemConfig
from .friction import FrictionConfig
from .halfspace import HalfSpaceConfig
from .law import LawConfig
from .loads import LoadConfig, _speed_range
from .meanfield import MeanFieldConfig

#: The ``[surface]`` and ``[material]`` tables (:mod:`rubbercontact.inputs`, shared with the CLI).
SurfaceConfig = SurfaceSpec
MaterialConfig = MaterialSpec
#: Models a run can compare: the registered ones a run can plan
#: (:func:`rubbercontact.models.registry.plannable`).
MODELS = plannable()
#: The models a run without ``models`` runs: the half-space alone, the hybrid as the docs
#: recommend it (the law read at the λ_hs-averaged pressure) and the mean-field theory, all
#: seconds once the law exists; ``fem`` is the reference, too costly to run unasked.
DEFAULT_MODELS = ("vhs", "hybrid-windowed", "meanfield")
#: Models a run on a height map (``[surface.map]``, :mod:`rubbercontact.pipeline.maprun`)
#: can compare (the hybrids with the linear law of the map's high-slope cell), and its
#: default.
MAP_MODELS = ("vhs", "meanfield", "hybrid", "hybrid-windowed")
MAP_DEFAULT_MODELS = ("vhs", "meanfield")


class RunConfig(_Strict):
    """The whole run (see ``examples/*.toml``)."""

    surface: SurfaceConfig
    material: MaterialConfig = MaterialConfig()
    loads: LoadConfig
    velocities: list[float] = Field(
        min_length=1, description="sliding speeds [mm/s]: a list, or a log range "
                                  "{from, to, points}")
    temperatures: list[Annotated[float, Field(gt=-273.15)]] | None = Field(
        None, min_length=1, description="temperatures [°C] (default: isothermal at the "
                                        "material's reference temperature); needs a shift "
                                        "law")
    realizations: int = Field(1, ge=1, le=10_000)
    seed: int = Field(0, ge=0)
    models: list[Literal[MODELS]] = Field(
        default_factory=lambda: list(DEFAULT_MODELS), min_length=1,
        description="models to run (default: the ones to run first; the full FEM, hours on "
                    "a real surface, only when named)")
    halfspace: HalfSpaceConfig = HalfSpaceConfig()
    fem: FemConfig = FemConfig()
    law: LawConfig = LawConfig()
    meanfield: MeanFieldConfig = MeanFieldConfig()
    friction: FrictionConfig = FrictionConfig()
    execution: ExecutionConfig = ExecutionConfig()
    output: OutputConfig = OutputConfig()

    @field_validator("velocities", mode="before")
    @classmethod
    def _velocity_range(cls, value):
        return _speed_range(value)

    @field_validator("velocities")
    @classmethod
    def _sliding(cls, value: list[float]) -> list[float]:
        # v = 0 is static contact (no hysteretic friction) and v < 0 the mirrored surface:
        # neither is a sliding speed, and v = 0 would cost a full FEM run for a zero.
        bad = [v for v in value if not (np.isfinite(v) and v > 0)]
        if bad:
            raise ValueError("sliding speeds must be finite and > 0 mm/s (v = 0 is static "
                             "contact, without hysteretic friction)")
        return value

    @model_validator(mode="after")
    def _fem_subset(self) -> RunConfig:
        r = self.fem.realizations
        if r is not None and r > self.realizations:
            raise ValueError(f"fem.realizations ({r}) exceeds realizations "
                             f"({self.realizations})")
        if (r is not None and r < self.realizations and "fem" in self.models
                and "vhs" not in self.models):
            raise ValueError("fem.realizations below realizations needs the 'vhs' model: the "
                             "VHS on every realization is the control variate that carries "
                             "the FEM on a subset to the phase average")
        return self

    @model_validator(mode="after")
    def _map_run(self) -> RunConfig:
        if self.surface.map is None:
            return self
        models = self.models if "models" in self.model_fields_set else MAP_DEFAULT_MODELS
        bad = [m for m in models if m not in MAP_MODELS]
        unsupported = {"models " + ", ".join(bad): bool(bad),
                       "[law] (a map's hybrid uses the linear law of its cell)":
                           self.law != LawConfig(),
                       # by value, not by whether the key was written: a dump re-parses
                       "halfspace.n, hybrid_n (a map is solved on its own grid)":
                           (self.halfspace.n, self.halfspace.hybrid_n)
                           != (HalfSpaceConfig().n, HalfSpaceConfig().hybrid_n),
                       "loads.contact_areas": self.loads.contact_areas is not None,
                       "realizations > 1": self.realizations > 1,
                       "temperatures": self.temperatures is not None,
                       "friction.adhesion": self.friction.adhesion is not None,
                       "friction.flash_temperature": self.friction.flash_temperature.enabled}
        given = [k for k, v in unsupported.items() if v]
        if given:
            raise ValueError(f"a run on [surface.map] supports models {', '.join(MAP_MODELS)} "
                             f"at given pressures, one map, isothermal; not {'; '.join(given)}")
        return self

    @model_validator(mode="after")
    def _meanfield_spectrum(self) -> RunConfig:
        models = self.models
        if self.surface.map is not None and "models" not in self.model_fields_set:
            models = list(MAP_DEFAULT_MODELS)
        self.meanfield.check_models(models)
        if self.meanfield.spectrum == "profiles":
            if self.surface.profiles is None:
                raise ValueError("meanfield.spectrum = 'profiles' needs [surface.profiles]")
            if "meanfield-hybrid" in self.models:
                raise ValueError("meanfield-hybrid reads the sine series (its law belongs to "
                                 "the fit's high-slope waves): use meanfield.spectrum = "
                                 "'sines', or the model meanfield")
        return self

