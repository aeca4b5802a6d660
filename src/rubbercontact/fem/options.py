"""Options of the FEM sliding test: one object from the config to the task.

:class:`FemOptions` holds what defines the cell and its numerics, and which solver runs
it; :class:`SteadyOptions` and :class:`TransientOptions` the controls of each solver.
All are frozen dataclasses of plain values, so a task carries them as a dict
(:meth:`FemOptions.to_dict`) and the result cache keys on every field.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field, fields, replace
from typing import Any

from .._validation import positive_scalar
from ..errors import InputError

#: ``"steady"`` solves the travelling-wave problem directly (:mod:`.steady_solver`);
#: ``"transient"`` time-steps the press / settle / slide protocol (:mod:`.transient`).
SOLVERS = ("steady", "transient")
#: Finite-strain viscoelastic models (see :mod:`.constitutive`).
VISCOUS_MODELS = ("simo", "reese-govindjee")
#: ``"penalty"``: the face may penetrate, force ``ε ⟨−g⟩`` (:mod:`.contact`);
#: ``"barrier"``: a C² log barrier, impenetrable by construction (:mod:`.barrier`).
CONTACTS = ("penalty", "barrier")


#: ``FemOptions.mesh`` that follows the surface (:mod:`.resolution`).
AUTO = "auto"


def _explicit_mesh(mesh: Any) -> tuple[int, int]:
    """``mesh`` as ``(nx, ny)``, checked."""
    try:
        if isinstance(mesh, str) or len(mesh) != 2 or any(int(m) != m for m in mesh):
            raise ValueError
        nx, ny = (int(m) for m in mesh)
    except (TypeError, ValueError):
        raise InputError(f"mesh: expected two integers (nx, ny) or 'auto', got "
                         f"{mesh!r}") from None
    if nx < 3 or ny < 1:
        raise InputError(f"mesh: need nx >= 3 and ny >= 1, got {mesh!r}")
    return nx, ny


def _integer(name: str, value: Any, low: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or int(value) != value \
            or value < low:
        raise InputError(f"{name}: must be an integer >= {low}, got {value!r}")
    return int(value)


#: Rescues of a failed (or impaled) penalty-contact steady solve (:attr:`SteadyOptions.rescue`).
RESCUES = ("barrier", "none")

#: Newton iterations per continuation step of the barrier rescue: a log barrier's Newton
#: takes many short steps near the surface; with 15 the barrier stopped where the penalty
#: did on the steep CAPTIF cells, with 60 it converged 3 of their 4 hard points
#: (docs/validation/steep_cells.md).
RESCUE_NEWTON = 60


@dataclass(frozen=True)
class SteadyOptions:
    """Controls of the steady solver (the defaults serve every case tested).

    Attributes
    ----------
    krylov_rtol
        Largest relative GMRES tolerance of an inexact Newton step.
    max_krylov
        GMRES iterations per Newton iteration.
    refactor_krylov
        Keep the factorized preconditioner for the next Newton iteration while GMRES needs
        at most this many iterations.
    newton_per_step
        Newton iterations per continuation step before the step is halved.
    first_step
        First continuation step in the homotopy parameter ``λ`` (0 … 1). Small: on the
        steep cells the larger first steps fail before this one converges, and the step
        grows after easy steps (benchmarks/steady.md, "The press's first step").
    min_step
        Smallest continuation step before the path is declared failed.
    max_steps
        Continuation steps (converged or halved) per path.
    coarse_elements, coarse_columns
        The coarsest mesh of the nested iteration (where the continuation runs) keeps at
        least ``coarse_elements`` elements per shortest wavelength and ``coarse_columns``
        columns (a contact patch must stay several columns wide for its solution to
        start the finer mesh); ``coarse_elements = 0`` switches nested iteration off.
    rescue
        If the steady solve with penalty contact fails, or converges with the face
        impaled on a crest: ``"barrier"`` solves it again with the barrier contact
        (:mod:`.barrier`, at least :data:`RESCUE_NEWTON` Newton iterations per
        continuation step) before any transient fallback (an impaled penalty solution
        stays, flagged, if the rescue fails); ``"none"``.
    fallback
        If the steady solve (and its rescue) fails, run the transient test and say so in
        the status.
    newton_budget
        Newton iterations one steady solve may spend on its mesh, its barrier rescue's
        included; past them it stops and says so (a stop then costs a bounded, machine-
        independent amount of work). The default is 1.5× the most any converged point of
        the steep-cell study needed (docs/validation/steep_cells.md).
    fallback_budget
        Newton iterations the transient fallback may spend, press and settle included;
        past them it stops and says how far it slid (None: no bound beyond its periods).
        The default, 2400, is twice ``newton_budget``'s (it does not follow a changed
        ``newton_budget``): a test that stops then costs at most about three steady budgets
        of Newton iterations, so a run's cost stays bounded.
    """

    krylov_rtol: float = 1e-2
    max_krylov: int = 200
    refactor_krylov: int = 0
    newton_per_step: int = 15
    first_step: float = 0.0625
    min_step: float = 1.0 / 512
    max_steps: int = 60
    coarse_elements: int = 16
    coarse_columns: int = 48
    rescue: str = "barrier"
    fallback: bool = True
    newton_budget: int = 1200
    fallback_budget: int | None = 2400

    def validate(self) -> SteadyOptions:
        positive_scalar("steady.krylov_rtol", self.krylov_rtol)
        if not self.krylov_rtol < 1:
            raise InputError(f"steady.krylov_rtol: must be < 1, got {self.krylov_rtol}")
        _integer("steady.max_krylov", self.max_krylov, 1)
        _integer("steady.refactor_krylov", self.refactor_krylov, 0)
        _integer("steady.newton_per_step", self.newton_per_step, 1)
        _integer("steady.max_steps", self.max_steps, 1)
        _integer("steady.coarse_elements", self.coarse_elements, 0)
        _integer("steady.coarse_columns", self.coarse_columns, 3)
        _integer("steady.newton_budget", self.newton_budget, 1)
        if self.fallback_budget is not None:
            _integer("steady.fallback_budget", self.fallback_budget, 1)
        if self.rescue not in RESCUES:
            raise InputError(f"steady.rescue: one of {', '.join(RESCUES)}, got {self.rescue!r}")
        for name in ("first_step", "min_step"):
            v = positive_scalar(f"steady.{name}", getattr(self, name))
            if v > 1:
                raise InputError(f"steady.{name}: must be in (0, 1], got {v}")
        return self


@dataclass(frozen=True)
class TransientOptions:
    """Controls of the time-stepped press / settle / slide protocol.

    Attributes
    ----------
    periods
        Maximum number of sliding periods (raised to cover ``min_sliding_time``).
    steps_per_period
        Steps per period of travel (None: ``nx``, one element of travel per step).
    min_periods
        Minimum sliding periods before steadiness is checked.
    min_sliding_time
        Minimum sliding time [s] before the steadiness check, in whole periods.
    steady_tol
        Relative agreement of successive period averages that ends the test.
    settle_time
        Hold time under load before sliding [s] (None: ``5 τ_max``; ``100 τ_max`` if v = 0).
    press_steps
        Load increments of the press phase.
    max_cutbacks
        Halvings of a failing step before the test gives up.
    newton_max_step
        Largest change of any unknown per Newton iteration, in smallest element sizes.
    slow_branch_start
        Start branches much slower than a period at their steady row-average state.
    surface_offset
        Sliding distance of the surface at the start [mm] (the steady solver reports the
        offset of its solution, ``stats.surface_offset``; a transient test started there
        reaches the same steady state).
    """

    periods: int = 6
    steps_per_period: int | None = None
    min_periods: int = 2
    min_sliding_time: float = 0.0
    steady_tol: float = 0.01
    settle_time: float | None = None
    press_steps: int = 4
    max_cutbacks: int = 6
    newton_max_step: float = 0.2
    slow_branch_start: bool = True
    surface_offset: float = 0.0

    def validate(self) -> TransientOptions:
        periods = _integer("periods", self.periods, 1)
        min_periods = _integer("min_periods", self.min_periods, 1)
        if min_periods > periods:
            raise InputError(f"min_periods: {min_periods} exceeds periods = {periods}")
        if self.steps_per_period is not None:
            _integer("steps_per_period", self.steps_per_period, 4)
        positive_scalar("min_sliding_time", self.min_sliding_time, allow_zero=True, unit="s")
        positive_scalar("steady_tol", self.steady_tol)
        if self.settle_time is not None:
            positive_scalar("settle_time", self.settle_time, allow_zero=True, unit="s")
        _integer("press_steps", self.press_steps, 1)
        _integer("max_cutbacks", self.max_cutbacks, 0)
        positive_scalar("newton_max_step", self.newton_max_step)
        positive_scalar("surface_offset", self.surface_offset, allow_zero=True, unit="mm")
        return self


@dataclass(frozen=True)
class FemOptions:
    """The FEM sliding test: cell, numerics, and which solver runs it.

    Attributes
    ----------
    mesh
        Elements ``(nx, ny)``; ``nx`` must give >= 8 elements per shortest wavelength.
        ``"auto"``: from the surface (:func:`~.resolution.auto_mesh`: ``columns_per_wave``
        columns on the shortest wave, rows and grading from the cell's height), resolved
        per test (:meth:`resolved`); a test whose narrowest contact patch is below
        ``patch_columns`` columns is then re-solved on a finer mesh (1.5x or 2x the columns).
    height_ratio
        Cell height / width (paper: 0.75).
    grading
        Ratio top-row / bottom-row element height (> 1 refines toward the contact face);
        set by ``mesh = "auto"`` (leave it at 1 there).
    columns_per_wave
        ``mesh = "auto"``: columns on the shortest wave (docs/validation/mesh_resolution.md).
    patch_columns
        Narrowest contact patch, in columns, of a resolved test (every test reports its
        own, ``stats.patch_columns``; docs/validation/mesh_resolution.md).
    contact_points
        Contact points per face segment (1: node-to-surface).
    penalty_factor
        Contact penalty ``ε = factor · E_alg/h`` (see :func:`~.contact.penalty_parameter`).
    contact_smoothing
        C¹ rounding of the penalty's kink over this fraction of the penetration under the
        mean pressure, ``p̄/ε`` (see :func:`~.contact.evaluate_contact`); 0 is the plain
        penalty. A contact point sitting at the kink makes Newton cycle; the rounding acts
        only where the local pressure is below a few per cent of ``p̄``.
    contact
        ``"penalty"`` or ``"barrier"`` (:data:`CONTACTS`). The barrier's Newton takes many
        short steps near the surface: give it ``steady.newton_per_step = 60``
        (docs/validation/steep_cells.md).
    barrier_distance
        The barrier's reach ``d̂`` as a fraction of the face's resolution: the smaller of
        the smallest element and the chord sag ``h² max|z''|/8`` of a face segment on the
        surface (barrier only; points within ``d̂`` count as contact).
    barrier_stiffness
        The barrier's stiffness: the gap is ``d̂/10`` under this multiple of ``p̄``
        (barrier only; see :func:`~.barrier.barrier_law`).
    bulk_modulus
        ``κ`` [MPa] (None: :data:`~.constitutive.DEFAULT_BULK_MODULUS`).
    history_order
        Time interpolation of the viscous history: 2 quadratic, 1 piecewise linear.
    viscous_model
        ``"simo"`` or ``"reese-govindjee"`` (transient solver only).
    newton_tol
        Convergence when ``‖r‖ <= newton_tol · p̄ L0``.
    max_newton
        Newton iterations per transient step (the steady solver's are in ``steady``).
    solver
        ``"steady"`` (default) or ``"transient"`` (:data:`SOLVERS`).
    crest_radius
        Round the surface's crests to at least this radius [mm] before the test
        (:func:`~rubbercontact.roughness.crests.round_crests`; None: the surface as given).
        A run's law cell of a measured road takes the profile's sampling interval: a
        sine band's crests are sharper than the measurement resolves, and the rubber
        crushed on them stops Newton (docs/validation/steep_cells.md).
    steady, transient
        The controls of each solver.
    """

    mesh: tuple[int, int] | str = (120, 90)
    height_ratio: float = 0.75
    grading: float = 1.0
    columns_per_wave: int = 64
    patch_columns: int = 4
    contact_points: int = 4
    penalty_factor: float = 100.0
    contact_smoothing: float = 0.1
    contact: str = "penalty"
    barrier_distance: float = 0.1
    barrier_stiffness: float = 1.0
    bulk_modulus: float | None = None
    history_order: int = 2
    viscous_model: str = "simo"
    newton_tol: float = 1e-6
    max_newton: int = 25
    solver: str = "steady"
    crest_radius: float | None = None
    steady: SteadyOptions = field(default_factory=SteadyOptions)
    transient: TransientOptions = field(default_factory=TransientOptions)

    def __post_init__(self) -> None:
        if not self.auto:
            object.__setattr__(self, "mesh", _explicit_mesh(self.mesh))
        positive_scalar("height_ratio", self.height_ratio)
        positive_scalar("grading", self.grading)
        if self.auto and self.grading != 1.0:
            raise InputError(f"grading: mesh = 'auto' sets the grading; give an explicit mesh "
                             f"to set it, got grading = {self.grading}")
        _integer("columns_per_wave", self.columns_per_wave, 8)
        _integer("patch_columns", self.patch_columns, 1)
        _integer("contact_points", self.contact_points, 1)
        positive_scalar("penalty_factor", self.penalty_factor)
        positive_scalar("contact_smoothing", self.contact_smoothing, allow_zero=True)
        if self.contact not in CONTACTS:
            raise InputError(f"contact: must be one of {', '.join(CONTACTS)}, got "
                             f"{self.contact!r}")
        positive_scalar("barrier_distance", self.barrier_distance)
        if not self.barrier_distance < 0.5:
            raise InputError(f"barrier_distance: must be < 0.5 (of the face's resolution), got "
                             f"{self.barrier_distance}")
        positive_scalar("barrier_stiffness", self.barrier_stiffness)
        if self.bulk_modulus is not None:
            positive_scalar("bulk_modulus", self.bulk_modulus, unit="MPa")
        if self.history_order not in (1, 2):
            raise InputError(f"history_order: must be 1 (linear) or 2 (quadratic), got "
                             f"{self.history_order!r}")
        if self.viscous_model not in VISCOUS_MODELS:
            raise InputError(f"viscous_model: must be one of {', '.join(VISCOUS_MODELS)}, got "
                             f"{self.viscous_model!r}")
        positive_scalar("newton_tol", self.newton_tol)
        _integer("max_newton", self.max_newton, 1)
        if self.crest_radius is not None:
            positive_scalar("crest_radius", self.crest_radius, unit="mm")
        if self.solver not in SOLVERS:
            raise InputError(f"solver: must be one of {', '.join(SOLVERS)}, got {self.solver!r}")
        if isinstance(self.steady, dict):
            object.__setattr__(self, "steady", SteadyOptions(**self.steady))
        if isinstance(self.transient, dict):
            object.__setattr__(self, "transient", TransientOptions(**self.transient))
        self.steady.validate()
        self.transient.validate()

    @property
    def auto(self) -> bool:
        """The mesh follows the surface (``mesh = "auto"``)."""
        return isinstance(self.mesh, str) and self.mesh == AUTO

    @property
    def steps_per_period(self) -> int:
        """The transient's steps per period (``nx`` unless set)."""
        return self.transient.steps_per_period or self.mesh[0]

    def resolved(self, surface) -> FemOptions:
        """These options on ``surface``'s cell: an automatic mesh made explicit
        (:func:`~.resolution.auto_mesh`), its nested iteration's coarsest mesh kept at
        ``columns_per_wave`` (the coarse press is then resolved too); others unchanged."""
        if not self.auto:
            return self
        from .resolution import auto_mesh

        m = auto_mesh(surface, self.height_ratio, self.columns_per_wave)
        coarse = self.steady.coarse_elements
        return self.with_(mesh=(m.nx, m.ny), grading=m.grading, steady={
            "coarse_elements": max(coarse, self.columns_per_wave) if coarse else 0})

    def to_dict(self) -> dict:
        """Plain data, e.g. for a task's arguments and its cache key: every field, except
        that the barrier's selector and parameters are written only when the contact is the
        barrier — so the penalty's tasks keep the arguments (and the cache keys) they had
        before the barrier existed, and the reference FEM solves stay reachable."""
        out = asdict(self)
        out["mesh"] = self.mesh if self.auto else list(self.mesh)
        if self.contact == "penalty":
            for name in ("contact", "barrier_distance", "barrier_stiffness"):
                del out[name]
        # likewise the automatic mesh's rule, on an explicit mesh at its defaults
        for name in ("columns_per_wave", "patch_columns"):
            if not self.auto and out[name] == _DEFAULTS[name]:
                del out[name]
        # and the steady solve's rescue and fallback budget at their defaults (the code
        # digest still tells apart the results computed before they existed)
        for name in ("rescue", "fallback_budget"):
            if out["steady"][name] == getattr(SteadyOptions, name):
                del out["steady"][name]
        # and the surface as given (crests not rounded)
        if out["crest_radius"] is None:
            del out["crest_radius"]
        return out

    @classmethod
    def from_dict(cls, data: dict) -> FemOptions:
        """Inverse of :meth:`to_dict`; unknown keys are an :class:`InputError`."""
        names = {f.name for f in fields(cls)}
        unknown = sorted(set(data) - names)
        if unknown:
            raise InputError(f"FEM options: unknown key(s) {unknown}")
        kw = dict(data)
        for key, sub in (("steady", SteadyOptions), ("transient", TransientOptions)):
            if isinstance(kw.get(key), dict):
                bad = sorted(set(kw[key]) - {f.name for f in fields(sub)})
                if bad:
                    raise InputError(f"FEM options: unknown key(s) {[f'{key}.{b}' for b in bad]}")
                kw[key] = sub(**kw[key])
        if "mesh" in kw and not isinstance(kw["mesh"], str):
            kw["mesh"] = tuple(kw["mesh"])
        return cls(**kw)

    def with_(self, **changes) -> FemOptions:
        """A copy with fields changed; ``steady=`` / ``transient=`` may be dicts of changes."""
        for key in ("steady", "transient"):
            if isinstance(changes.get(key), dict):
                changes[key] = replace(getattr(self, key), **changes[key])
        return replace(self, **changes)


#: Field defaults that :meth:`FemOptions.to_dict` leaves out.
_DEFAULTS = {f.name: f.default for f in fields(FemOptions)}
