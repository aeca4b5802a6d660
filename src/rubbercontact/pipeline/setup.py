"""A run's set-up, resolved before any task runs: surfaces, material, speeds, checks.

:func:`resolve` builds what the config describes (the material, the base surface and its
random-phase realizations, their high-/low-slope parts, the speeds and temperatures) and
checks what would otherwise fail only inside the tasks, with the cause named: FEM meshes
too coarse for the cells they mesh, temperatures without a shift law, pressures beyond
the rubber's range (:mod:`.limits`).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from ..config import RunConfig
from ..errors import InputError
from ..inputs import SurfaceInput, build_material, build_surface
from ..materials import GeneralizedMaxwell
from ..models.registry import needs_law
from ..roughness import SineSeries
from .limits import check_pressures
from .speeds import SpeedPlan, plan_speeds


@dataclass(frozen=True)
class Parts:
    """A realization split at ``surface.m2_threshold``: high- and low-slope waves."""

    high: SineSeries
    low: SineSeries


@dataclass(frozen=True)
class RunSetup:
    """Everything a run builds from its config before the first task.

    Attributes
    ----------
    config
        The validated config.
    material
        The rubber at its reference temperature.
    surface
        The base sine series and its provenance.
    realizations
        ``config.realizations`` random-phase copies of the base series (``config.seed``).
    parts
        Their high- and low-slope parts.
    hs0
        The high-slope part of the first realization translated to zero phase: the law's
        cell (the law is a property of the high-slope scale up to a translation).
    speeds
        Speeds, temperatures and the reduced speeds computed.
    models
        The models, in config order, without repeats.
    n_fem
        Realizations the full FEM runs on (the first ``n_fem``).
    """

    config: RunConfig
    material: GeneralizedMaxwell
    surface: SurfaceInput
    realizations: list[SineSeries]
    parts: list[Parts]
    hs0: SineSeries
    speeds: SpeedPlan
    models: list[str]
    n_fem: int

    @property
    def base(self) -> SineSeries:
        return self.surface.series

    @property
    def period(self) -> float:
        return self.base.period

    @property
    def needs_law(self) -> bool:
        """Whether a model reads the high-slope law and the surface has a high-slope scale."""
        return any(map(needs_law, self.models)) and self.hs0.size > 0


def resolve(cfg: RunConfig) -> RunSetup:
    """Build and check a run's set-up (raises :class:`InputError` naming the cause)."""
    material = build_material(cfg.material)
    for key, pressures in (("loads.pressures", cfg.loads.pressures),
                           ("law.pressures", cfg.law.pressures)):
        check_pressures(pressures or [], material, key)
    surface = build_surface(cfg.surface)
    # the law cell's crests rounded to what the measurement resolves (fem.crest_radius)
    cfg = cfg.model_copy(update={"fem": cfg.fem.with_sampling(surface.info.get("dx_mm"))})
    realizations = surface.series.realizations(cfg.realizations, seed=cfg.seed)
    parts = [Parts(*r.partition(cfg.surface.m2_threshold)) for r in realizations]
    setup = RunSetup(config=cfg, material=material, surface=surface,
                     realizations=realizations, parts=parts,
                     hs0=translated_to_zero_phase(parts[0].high),
                     speeds=plan_speeds(cfg.velocities, cfg.temperatures, material),
                     models=list(dict.fromkeys(cfg.models)),
                     n_fem=cfg.fem.realizations or cfg.realizations)
    check_fem_meshes(setup)
    return setup


def check_fem_meshes(setup: RunSetup) -> None:
    """Check each FEM cell the run will mesh (the law's, the full surface's) as the FEM
    task would (:func:`rubbercontact.fem.sliding.check_test`), naming the config key."""
    cfg = setup.config
    cells = []
    if setup.needs_law and cfg.law.file is None:
        cells.append(("fem.mesh", "the law cell (the high-slope waves)", setup.hs0,
                      cfg.fem.options(setup.material)))
    if "fem" in setup.models:
        cells.append(("fem.full_mesh (default: fem.mesh)", "the full-surface FEM cell",
                      translated_to_zero_phase(setup.realizations[0]),
                      cfg.fem.options(setup.material, full=True)))
    for key, what, surface, options in cells:
        check_fem_cell(surface, setup.material, options, key, what)


def check_fem_cell(surface: SineSeries, material: GeneralizedMaxwell, options, key: str,
                   what: str) -> None:
    """:func:`~rubbercontact.fem.sliding.check_test` on one cell; its error names ``key``."""
    from ..fem.sliding import check_test

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")     # a load warning belongs to the tasks, not here
        try:
            check_test(surface, material, material.equilibrium_modulus / 2, 1.0, options)
        except InputError as exc:
            raise InputError(f"{key}: {what}, period {surface.period:g} mm, shortest "
                             f"wavelength {float(surface.wavelengths[0]):g} mm: {exc}"
                             ) from None


def translated_to_zero_phase(surface: SineSeries) -> SineSeries:
    """``surface(x + x0)`` with ``x0`` chosen so that its shortest wave has phase 0."""
    if surface.size == 0:
        return surface
    x0 = -surface.phases[0] / surface.wavenumbers[0]
    return surface.with_phases(surface.phases + surface.wavenumbers * x0)


def task_material(material: GeneralizedMaxwell) -> dict:
    """The material as a task argument: the Prony series only.

    Its shift law and provenance do not change a solve at the reference temperature, so
    they stay out of the cache key (a material without them keys as before they existed).
    """
    out = material.as_dict(provenance=False)
    out.pop("shift", None)
    return out


def task_surface(surface: SineSeries) -> dict:
    """A sine series as a task argument (plain data)."""
    return surface.as_dict()


def static_series(surface: SineSeries) -> SineSeries:
    """The waves of ``surface`` without phases (what a statistical model sees)."""
    return SineSeries(surface.wavelengths, surface.amplitudes)


def pressure_array(values) -> np.ndarray:
    return np.sort(np.asarray(values, float))
