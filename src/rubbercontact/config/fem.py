"""The ``[fem]`` table: the FEM sliding test of the law's cell and of the full surface."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import Field, field_validator, model_validator

from .._optionfields import option_field
from ..errors import InputError
from ..fem.options import (
    SOLVERS,
    VISCOUS_MODELS,
    FemOptions,
    SteadyOptions,
    TransientOptions,
)
from ..inputs import PositiveFloat
from ..inputs import Strict as _Strict

#: Elements (nx, ny) of a FEM mesh; its limits are :class:`rubbercontact.fem.FemOptions`'s
#: (checked by :meth:`FemConfig._meshes`), so the config and the CLI state the same ones.
Mesh = tuple[int, int]


def _mesh(mesh: Mesh | str) -> Mesh | str:
    """A config mesh as :class:`~rubbercontact.fem.FemOptions` takes it."""
    return mesh if mesh == "auto" else tuple(mesh)


#: FemConfig fields that only the time-stepped (transient) solver uses.
TRANSIENT_ONLY = ("periods", "steps_per_period", "full_periods", "full_steps_per_period",
                  "min_creep_times")


#: Sliding periods of the transient test that a steady solve falls back to in a run
#: (``FemOptions.steady.fallback``). A run's steady FEM tasks have carried 4 since before
#: ``fem.periods`` took the library's 6 (issue 38): the transient options are part of every
#: FEM task's arguments, so 4 keeps the keys of every steady run's cached FEM, the reference
#: cache behind VALIDATION.md among them. No steady run of the validation fell back.
STEADY_FALLBACK_PERIODS = 4


class FemConfig(_Strict):
    """FEM sliding test (paper §2.4): used for the law and for the full-surface model.
    Defaults (and, where the config has nothing to add, help) are those of
    :class:`rubbercontact.fem.FemOptions` and :class:`~rubbercontact.fem.TransientOptions`,
    except ``mesh`` ("auto" here: a run's law cell follows its surface)."""

    solver: Literal[SOLVERS] = option_field(
        FemOptions, "solver", description="steady: the steady state solved directly (settled by "
                              "construction); transient: time-stepped press/settle/slide")
    mesh: Mesh | Literal["auto"] = Field(
        "auto", description="elements (nx, ny) of the high-slope cell, or 'auto': from the "
                            "cell's shortest wave (columns_per_wave), rows and grading from "
                            "its height; each law point checks its narrowest contact patch "
                            "and refines once where it is too narrow "
                            "(docs/validation/mesh_resolution.md)")
    columns_per_wave: int = option_field(
        FemOptions, "columns_per_wave", ge=8, le=256,
        description="mesh = 'auto': columns per shortest wave of the law cell")
    full_mesh: Mesh | None = Field(
        None, description="elements (nx, ny) of the full-surface FEM model (default: mesh if "
                          "given, else 120 x 90)")
    height_ratio: PositiveFloat = option_field(FemOptions, "height_ratio")
    crest_radius: PositiveFloat | Literal["sampling", "none"] = Field(
        "sampling", description="law cell: round the high-slope band's crests to this radius "
                                "[mm] before the FEM (a steep sine band's crests are sharper "
                                "than a measured profile resolves); 'sampling': the measured "
                                "profiles' sampling interval (none for a sine table or "
                                "preset); 'none': the band as fitted "
                                "(docs/validation/steep_cells.md)")
    periods: int = option_field(TransientOptions, "periods", ge=1, le=100,
                                prefix="transient: ")
    steps_per_period: int | None = option_field(TransientOptions, "steps_per_period", ge=4,
                                                prefix="transient: ")
    contact_points: int = option_field(FemOptions, "contact_points", ge=1, le=64)
    history_order: Literal[1, 2] = option_field(
        FemOptions, "history_order",
        description="time interpolation of the viscous history: 2 quadratic (second order in "
                    "dt), 1 piecewise linear (first order for fast branches)")
    viscous_model: Literal[VISCOUS_MODELS] = option_field(
        FemOptions, "viscous_model",
        description="finite-strain viscoelasticity: simo (stress-like internal variables) or "
                    "reese-govindjee (the paper's; multiplicative split, first order in dt; "
                    "transient solver only)")
    grading: PositiveFloat = option_field(
        FemOptions, "grading", le=100,
        description="top/bottom element height ratio of the law cell's mesh (> 1 refines "
                    "toward the contact face; set by mesh = 'auto')")
    full_grading: PositiveFloat = option_field(
        FemOptions, "grading", le=100,
        description="top/bottom element height ratio of the full-surface FEM mesh (> 1 "
                    "refines toward the contact face)")
    full_steps_per_period: int | None = Field(
        None, ge=4, description="transient: time steps per period of the full-surface FEM "
                                "(default: steps_per_period)")
    full_periods: int | None = Field(
        None, ge=1, le=100, description="transient: maximum sliding distance of the "
                                        "full-surface FEM in its (longer) periods (default: "
                                        "periods)")
    realizations: int | None = Field(
        None, ge=1, le=10_000,
        description="run the full-surface FEM on the first this many realizations only "
                    "(default: all); the other models run on all of them, and the FEM's "
                    "phase average is estimated with the VHS as control variate, "
                    "mean_N(VHS) + mean_R(FEM - VHS) (needs the vhs model)")
    min_creep_times: float | None = Field(
        None, gt=0, le=50,
        description="transient: slide every FEM test at least this many of the material's "
                    "longest retardation time before its steadiness check (the bulk creeps "
                    "on that time)")
    steady: dict[str, Any] = Field(
        default_factory=dict, description="controls of the steady solver "
                                          "(rubbercontact.fem.SteadyOptions fields)")
    numerics: dict[str, Any] = Field(
        default_factory=dict, description="the FEM's own numerics by name "
                                          "(rubbercontact.fem.FemOptions fields not set "
                                          "above: penalty_factor, contact, bulk_modulus, "
                                          "newton_tol, ...)")

    @field_validator("mesh", "full_mesh")
    @classmethod
    def _meshes(cls, mesh: Mesh | None) -> Mesh | None:
        if mesh is not None and mesh != "auto":
            try:
                FemOptions(mesh=mesh)
            except InputError as exc:
                # the formatter adds the value given
                raise ValueError(str(exc).removeprefix("mesh: ").split(", got")[0]) from None
        return mesh

    @model_validator(mode="after")
    def _solver_options(self) -> FemConfig:
        if self.solver == "steady":
            # by value, not by whether the key was written: a dumped config re-parses
            given = [k for k in TRANSIENT_ONLY
                     if getattr(self, k) != type(self).model_fields[k].default]
            if given:
                raise ValueError(f"{', '.join(given)} apply to solver = 'transient' only "
                                 f"(the steady solver has no time steps or sliding distance)")
            if self.viscous_model != "simo":
                raise ValueError("viscous_model = 'reese-govindjee' needs solver = 'transient'")
        if self.mesh == "auto" and self.grading != 1.0:
            raise ValueError("grading: mesh = 'auto' sets the law cell's grading; give an "
                             "explicit mesh = [nx, ny] to set it")
        unknown = set(self.steady) - set(SteadyOptions.__dataclass_fields__)
        if unknown:
            raise ValueError(f"steady: unknown key(s) {sorted(unknown)}; allowed: "
                             f"{', '.join(SteadyOptions.__dataclass_fields__)}")
        SteadyOptions(**self.steady).validate()
        self._numerics()
        return self

    def _numerics(self) -> None:
        """``numerics`` holds FemOptions fields that have no key of their own here."""
        allowed = set(FemOptions.__dataclass_fields__) - set(type(self).model_fields) - {
            "transient"}
        unknown = set(self.numerics) - allowed
        if unknown:
            raise ValueError(f"numerics: unknown or set elsewhere {sorted(unknown)}; "
                             f"allowed: {', '.join(sorted(allowed))}")
        try:
            FemOptions(**self.numerics)
        except InputError as exc:
            raise ValueError(f"numerics: {exc}") from None

    @property
    def full_mesh_or_default(self) -> tuple[int, int]:
        """The full-surface FEM's mesh: ``full_mesh``, else ``mesh`` if given, else 120 x 90
        (the automatic rule would put tens of thousands of columns on a whole surface)."""
        if self.full_mesh is not None:
            return tuple(self.full_mesh)
        return (120, 90) if self.mesh == "auto" else tuple(self.mesh)

    def with_sampling(self, dx: float | None) -> FemConfig:
        """This table with ``crest_radius = "sampling"`` made the surface's sampling
        interval ``dx`` [mm] (``"none"`` when the surface was not measured)."""
        if self.crest_radius != "sampling":
            return self
        return self.model_copy(update={"crest_radius": "none" if dx is None else float(dx)})

    def options(self, material, full: bool = False):
        """The :class:`~rubbercontact.fem.FemOptions` of the law cell, or of the full-surface
        model (``full=True``), for ``material`` (whose retardation time sizes
        ``min_creep_times``)."""
        times = material.retardation_times()
        min_time = (float(self.min_creep_times * times.max())
                    if self.min_creep_times is not None and times.size else 0.0)
        periods = (self.full_periods or self.periods) if full else self.periods
        transient = TransientOptions(
            periods=STEADY_FALLBACK_PERIODS if self.solver == "steady" else periods,
            steps_per_period=((self.full_steps_per_period or self.steps_per_period) if full
                              else self.steps_per_period),
            min_sliding_time=min_time)
        return FemOptions(
            mesh=self.full_mesh_or_default if full else _mesh(self.mesh),
            columns_per_wave=self.columns_per_wave,
            height_ratio=self.height_ratio,
            grading=self.full_grading if full else self.grading,
            contact_points=self.contact_points, history_order=self.history_order,
            viscous_model=self.viscous_model, solver=self.solver,
            crest_radius=(self.crest_radius if isinstance(self.crest_radius, float) and not full
                          else None),
            steady=SteadyOptions(**self.steady), transient=transient, **self.numerics)

