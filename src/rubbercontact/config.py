"""Run configuration: a TOML file validated with pydantic.

Every field carries its unit and allowed range; unknown keys are rejected with a
did-you-mean suggestion, and every error names the file and the key. Paths in the
file are resolved relative to the file itself.
"""

from __future__ import annotations

import difflib
import tomllib
from pathlib import Path
from typing import Annotated, Any, Literal

import numpy as np
from pydantic import BaseModel, Field, ValidationError, field_validator, model_validator

from ._optionfields import option_default, option_field
from .errors import InputError
from .fem.options import (
    SOLVERS,
    VISCOUS_MODELS,
    FemOptions,
    SteadyOptions,
    TransientOptions,
)
from .inputs import (
    MaterialSpec,
    PositiveFloat,
    ProfileInput,  # noqa: F401  (re-exported: config.ProfileInput)
    SurfaceSpec,
)
from .inputs import Strict as _Strict
from .meanfield.options import (
    DISSIPATIONS,
    INTERFACES,
    WEIGHTINGS,
    Dissipation,
    SCorrection,
    StripOptions,
    Weighting,
)
from .meanfield.psd import NODES_PER_DECADE
from .models.halfspace import LAWS, HalfspaceOptions
from .models.registry import plannable

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
            steady=SteadyOptions(**self.steady), transient=transient, **self.numerics)


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
        from .meanfield import MeanFieldOptions, StripOptions

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


class AdhesionConfig(_Strict):
    """Adhesive friction ``μ_adh = τ_f(v) A_c/σ0`` (paper §2.1 after eq. 8), a model whose
    parameters the user supplies: ``τ_f`` constant, or a Gaussian in ``log10 v``,
    ``τ_f = τ_0 exp(−(log10(v/v_0))²/(2c²))``, evaluated at the reduced speed ``a_T v``."""

    law: Literal["constant", "gaussian"] = Field(
        "constant", description="constant tau_0, or gaussian in log10 v")
    shear_strength: PositiveFloat = Field(description="tau_0, interfacial shear strength [MPa]")
    peak_velocity: PositiveFloat | None = Field(
        None, description="v_0, speed of the gaussian's peak at the reference temperature "
                          "[mm/s]")
    width: PositiveFloat | None = Field(
        None, description="c, standard deviation of the gaussian in decades of speed [-]")

    @model_validator(mode="after")
    def _parameters(self) -> AdhesionConfig:
        shape = [k for k in ("peak_velocity", "width") if getattr(self, k) is not None]
        if self.law == "gaussian" and len(shape) != 2:
            raise ValueError("law = 'gaussian' needs peak_velocity [mm/s] and width [decades]")
        if self.law == "constant" and shape:
            raise ValueError(f"{', '.join(shape)} apply to law = 'gaussian' only")
        return self


class FlashTemperatureConfig(_Strict):
    """The flash temperature of the contact spots, self-consistent with the friction
    (:mod:`rubbercontact.meanfield.flash`; the compound's ``[material.thermal]``)."""

    enabled: bool = Field(False, description="compute mu(v) with the flash temperature beside "
                                             "the isothermal one (mean-field models)")
    contact_time: PositiveFloat | None = Field(
        None, description="time the rubber slides in nominal contact [s]: the tread's "
                          "background heating (default: none, the run's temperature)")
    spot_radius: PositiveFloat = Field(
        float(np.pi / 2), description="q R of a contact spot at the wavenumber q [-]")
    tolerance: PositiveFloat = Field(1e-3, description="fixed point's tolerance [K]")
    max_iterations: int = Field(500, ge=1, le=100_000, description="fixed-point steps")


class FrictionConfig(_Strict):
    """Contributions to friction beyond the hysteresis the models compute."""

    adhesion: AdhesionConfig | None = None
    flash_temperature: FlashTemperatureConfig = FlashTemperatureConfig()


class ExecutionConfig(_Strict):
    workers: int = Field(1, ge=1, le=4096)
    threads_per_worker: int = Field(1, ge=1, le=256)
    scheduler: str | None = Field(None, pattern=r"^(tcp|tls|inproc)://.+",
                                  description="address of an existing Dask scheduler")
    cache: Path | None = Field(None, description="result cache directory")


class OutputConfig(_Strict):
    directory: Path = Path("results")
    figures: bool = True
    overwrite: bool = False


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


def _field_names(model: type[BaseModel], loc: tuple) -> list[str]:
    """Valid keys at the location of an error (for did-you-mean)."""
    for part in loc[:-1]:
        if isinstance(part, int):
            continue
        field = model.model_fields.get(part)
        if field is None:
            return []
        ann = field.annotation
        for cand in getattr(ann, "__args__", (ann,)):
            if isinstance(cand, type) and issubclass(cand, BaseModel):
                model = cand
                break
        else:
            return []
    return list(model.model_fields)


def _format_error(err: dict, source: str) -> str:
    loc = tuple(err["loc"])
    key = ".".join(str(p) for p in loc) or "(top level)"
    if err["type"] == "extra_forbidden":
        names = _field_names(RunConfig, loc)
        guess = difflib.get_close_matches(str(loc[-1]), names, n=1)
        hint = f"; did you mean '{guess[0]}'?" if guess else (
            f"; allowed: {', '.join(names)}" if names else "")
        return f"{source}: unknown key '{key}'{hint}"
    msg = err["msg"].removeprefix("Value error, ")
    field_desc = ""
    try:
        names = RunConfig
        for part in loc:
            if isinstance(part, int):
                continue
            f = names.model_fields[part]
            field_desc = f.description or ""
            ann = f.annotation
            nxt = [c for c in getattr(ann, "__args__", (ann,))
                   if isinstance(c, type) and issubclass(c, BaseModel)]
            names = nxt[0] if nxt else names
    except (KeyError, AttributeError):
        field_desc = ""
    unit = f" ({field_desc})" if field_desc else ""
    got = f", got {err['input']!r}" if "input" in err and not isinstance(err["input"], dict) else ""
    return f"{source}: key '{key}'{unit}: {msg}{got}"


def _resolve_paths(cfg: RunConfig, base: Path) -> RunConfig:
    def fix(p: Path | None) -> Path | None:
        return None if p is None else (p if p.is_absolute() else (base / p).resolve())

    upd: dict[str, Any] = {}
    if cfg.surface.profiles is not None:
        prof = cfg.surface.profiles.model_copy(update={"files": [fix(f) for f in
                                                                 cfg.surface.profiles.files]})
        missing = [str(f) for f in prof.files if not f.is_file()]
        if missing:
            raise InputError(f"surface.profiles.files: file(s) not found: {', '.join(missing)}")
        upd["surface"] = cfg.surface.model_copy(update={"profiles": prof})
    if cfg.surface.map is not None and cfg.surface.map.file is not None:
        path = fix(cfg.surface.map.file)
        if not path.is_file():
            raise InputError(f"surface.map.file: not found: {path}")
        upd["surface"] = cfg.surface.model_copy(
            update={"map": cfg.surface.map.model_copy(update={"file": path})})
    for key in ("file", "dma"):
        path = getattr(cfg.material, key)
        if path is not None:
            if not fix(path).is_file():
                raise InputError(f"material.{key}: not found: {fix(path)}")
            upd["material"] = upd.get("material", cfg.material).model_copy(
                update={key: fix(path)})
    if cfg.law.file is not None:
        if not fix(cfg.law.file).is_file():
            raise InputError(f"law.file: not found: {fix(cfg.law.file)}")
        upd["law"] = cfg.law.model_copy(update={"file": fix(cfg.law.file)})
    upd["output"] = cfg.output.model_copy(update={"directory": fix(cfg.output.directory)})
    if cfg.execution.cache is not None:
        upd["execution"] = cfg.execution.model_copy(update={"cache": fix(cfg.execution.cache)})
    return cfg.model_copy(update=upd)


def parse_config(data: dict, source: str = "<config>", base_dir: Path | None = None) -> RunConfig:
    """Validate a config mapping; raise :class:`InputError` with one line per problem."""
    if not isinstance(data, dict):
        raise InputError(f"{source}: expected a table of keys, got {type(data).__name__}")
    try:
        cfg = RunConfig.model_validate(data)
    except ValidationError as exc:
        lines = [_format_error(e, source) for e in exc.errors()]
        raise InputError("; ".join(lines)) from None
    return _resolve_paths(cfg, base_dir or Path.cwd())


def load_config(path: str | Path) -> RunConfig:
    """Read and validate a TOML run configuration."""
    path = Path(path)
    if not path.is_file():
        raise InputError(f"config file {path}: not found")
    try:
        text = path.read_text(encoding="utf-8")
        data = tomllib.loads(text)
    except UnicodeDecodeError:
        raise InputError(f"{path}: not a UTF-8 text file") from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{path}: invalid TOML: {exc}") from None
    return parse_config(data, source=str(path), base_dir=path.resolve().parent)


def default_config() -> RunConfig:
    """Built-in default of ``rubbercontact run``: a reduced paper §3 case at the paper's two
    speeds, by the VHS, both hybrids and the full FEM."""
    return parse_config(DEFAULT_CONFIG, source="<built-in default>")


#: Reduced section 3 validation (paper §3): three waves, coarse FEM, sized for 2 cores and
#: an empty result cache. Both FEM uses (the law cell and the full cell) solve the steady
#: state directly (fem.solver = "steady"): creep-settled by construction. The law stops at
#: 2 MPa: at 4 MPa its cell sheared as a whole (a friction stress above E∞/3) and the points
#: were excluded as non-monotone, so the table ended at 2 MPa anyway. The full FEM runs on
#: one realization, the cheap models on eight: the FEM's phase average is estimated with
#: the VHS as control variate (fem.realizations),
#: the workflow that makes the FEM comparison affordable. The eq. 28 figures the default
#: prints are a demonstration (one FEM realization, three loads), not the validation
#: (VALIDATION.md).
DEFAULT_CONFIG: dict = {
    "surface": {"preset": "section3"},
    "material": {"preset": "sbr"},
    "loads": {"pressures": [0.15, 0.25, 0.35]},
    "velocities": [10.0, 50.0],          # the paper's two speeds
    "realizations": 8,
    "seed": 2021,
    "models": ["vhs", "hybrid", "hybrid-windowed", "fem"],
    "halfspace": {"n": 2048},
    # law: 40 elements per 0.0625 mm wavelength; full FEM: 16 per 0.0625 mm wavelength
    "fem": {"mesh": [40, 30], "full_mesh": [64, 48], "realizations": 1},
    "law": {"pressures": [0.05, 0.1, 0.2, 0.5, 1.0, 2.0]},
    "execution": {"workers": 2},
    "output": {"directory": "results"},
}
