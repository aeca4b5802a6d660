"""What a run will cost, before it runs: its solves counted from the set-up and priced
by :mod:`.costmodel` (``rubbercontact run --check``).

The counts are exact (they follow :mod:`.plan` and :mod:`.lawstage`); each solve is priced
by :mod:`.costmodel`'s per-point costs, measured on one core. The wall time: each stage's
tasks in rounds of ``workers`` (a law by continuation has one task per pressure, so 5
pressures on 2 workers take 3 rounds), plus the set-up. The law's extension when the local
pressures go past its FEM points (:mod:`.lawcover`) is priced as one round at its worst:
every speed at every pressure it may add (:mod:`.costext`).

Not foreseen: further rounds of the extension (up to three), a steady solve that stops and
runs the barrier rescue or the transient fallback (minutes a point, the fallback at most
``steady.fallback_budget`` Newton iterations), the steepness of a law
cell (docs/validation/steep_cells.md), a steady point that needs many more Newton
iterations than its neighbours, and a loaded machine (the wall time then grows with the
load, the CPU time much less). The FEM's cost varies by up to 10× with speed and load: the
estimate is meant to a factor of 2 (``benchmarks/examples.md`` compares it with each
example's measured time).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..models.planning import PER_LOAD, PER_REALIZATION
from ..models.registry import planning
from ..sweep.progress import scheduled
from .costmodel import (
    FLASH_SOLVE_FACTOR,
    FULL_FEM_FACTOR,
    LAW_TABLE_SPEED_S,
    MEANFIELD_FLASH_CURVE_S,
    OVERHEAD_S,
    fem_point_seconds,
    halfspace_solve_seconds,
    law_point_seconds_on,
    law_task_seconds,
    meanfield_point_seconds,
    quasi_static_seconds,
)
from .setup import RunSetup


@dataclass(frozen=True)
class Stage:
    """One kind of solve of a run: how many, and the expected cost of each [s].

    Attributes
    ----------
    name
        What the solves are, as ``run --check`` prints it.
    count
        How many solves.
    each_s
        Expected cost of one (the mean) [s].
    tasks
        Expected cost of each task [s], in the order the run hands them to the workers,
        when the solves run as fewer tasks than solves (a law by continuation: one task per
        pressure); empty: one task per solve.
    same_sweep
        Its tasks go to the workers in the previous stage's sweep, after that stage's.
    """

    name: str
    count: int
    each_s: float
    tasks: tuple[float, ...] = ()
    same_sweep: bool = False

    @property
    def total_s(self) -> float:
        """Expected CPU time of the stage [s]."""
        return self.count * self.each_s

    @property
    def task_s(self) -> tuple[float, ...]:
        """Expected cost of each of its tasks [s], in the order they are sent."""
        return self.tasks or (self.each_s,) * self.count

    def wall_s(self, workers: int) -> float:
        """Expected wall time of the stage on ``workers`` [s]: each task to the first free
        worker, in order."""
        return scheduled(self.task_s, workers)


@dataclass(frozen=True)
class CostEstimate:
    """The solves of a run and their expected cost.

    Attributes
    ----------
    stages
        The kinds of solve (only those the run has).
    workers
        Parallel workers the solves share (``execution.workers``).
    notes
        What the estimate leaves out (a cost it cannot price, a test the run does not
        try), one line each as ``run --check`` prints it.
    """

    stages: tuple[Stage, ...]
    workers: int
    notes: tuple[str, ...] = ()

    @property
    def compute_s(self) -> float:
        """Expected CPU time of the solves [s]."""
        return sum(s.total_s for s in self.stages)

    @property
    def wall_s(self) -> float:
        """Expected wall time [s]: each sweep's tasks (a stage's, or several stages' sent
        together) in rounds of the workers, plus set-up."""
        sweeps: list[tuple[float, ...]] = []
        for s in self.stages:
            if s.same_sweep and sweeps:
                sweeps[-1] += s.task_s
            else:
                sweeps.append(s.task_s)
        return sum(scheduled(t, self.workers) for t in sweeps) + OVERHEAD_S

    @property
    def cpu_s(self) -> float:
        """Expected CPU time of the run [s]: the solves plus set-up."""
        return self.compute_s + OVERHEAD_S

    def describe(self) -> str:
        """The estimate as the lines ``run --check`` prints."""
        lines = [f"cost: {s.name}: {s.count} x ~{_duration(s.each_s)} = "
                 f"{_duration(s.total_s)}" for s in self.stages if s.count]
        lines.append(f"cost: about {_duration(self.wall_s)} on {self.workers} worker(s) "
                     f"from an empty cache, {_duration(self.cpu_s)} of CPU (to a factor of "
                     f"2 on a quiet machine; per-point costs measured on one core, "
                     f"rubbercontact.pipeline.costmodel)")
        lines += [f"cost: {note}" for note in self.notes]
        return "\n".join(lines)


def _duration(seconds: float) -> str:
    if seconds < 1:
        return f"{seconds:.2g} s"
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


def law_mesh(setup: RunSetup) -> tuple[int, int]:
    """The law cell's mesh: ``fem.mesh``, or the automatic one of the high-slope cell
    (:meth:`rubbercontact.fem.FemOptions.resolved`)."""
    return tuple(setup.config.fem.options(setup.material).resolved(setup.hs0).mesh)


def law_refined_mesh(setup: RunSetup) -> tuple[int, int]:
    """The mesh an automatic law cell's point is re-solved on when its narrowest contact
    patch is too narrow (:func:`rubbercontact.fem.resolution.refined_mesh`: ``nx``
    doubled, and the rows of the rule for twice the columns, at least the first mesh's)."""
    from ..fem.resolution import refined_mesh

    opts = setup.config.fem.options(setup.material)
    m = refined_mesh(setup.hs0, opts.height_ratio, opts.columns_per_wave)
    return (m.nx, m.ny)


def law_point_seconds(setup: RunSetup, pressure: float) -> float:
    """Expected cost of one fresh law FEM point at ``pressure`` [MPa] [s]: on the law
    cell's mesh, and on an automatic mesh the share of points re-solved on the refined
    mesh (:func:`law_refined_mesh`)."""
    return law_point_seconds_on(setup.config.fem.options(setup.material), setup.hs0,
                                pressure, setup.material.equilibrium_modulus)


def full_fem_seconds(setup: RunSetup, pressure: float) -> float:
    """Expected cost of one full FEM test at ``pressure`` [MPa] [s] (``FULL_FEM_FACTOR``
    times a point of the full mesh)."""
    cfg = setup.config
    return FULL_FEM_FACTOR * fem_point_seconds(cfg.fem.full_mesh_or_default, cfg.fem.solver,
                                               pressure, setup.material.equilibrium_modulus)


def model_task_seconds(setup: RunSetup, model: str, pressures) -> float:
    """Expected cost of one model task at ``pressures`` [MPa] [s], as the model's planning
    (:mod:`rubbercontact.models.planning`) runs it: half-space solves over its loads, a
    mean-field point, or a full FEM test."""
    per = planning(model).per
    if per == PER_REALIZATION:
        return len(pressures) * halfspace_solve_seconds(setup.config.halfspace.n)
    if per == PER_LOAD:
        return len(pressures) * meanfield_point_seconds(model)
    return sum(full_fem_seconds(setup, float(p)) for p in pressures)


def estimate_cost(setup: RunSetup) -> CostEstimate:
    """Count the solves of a resolved run (:func:`~.setup.resolve`) and price them."""
    import numpy as np

    from .costext import extension_stages
    from .lawstage import law_pressures, uses_continuation
    from .loads import load_count

    cfg = setup.config
    speeds = setup.speeds.computed.size
    loads = load_count(cfg)
    n_real = len(setup.realizations)
    e_inf = setup.material.equilibrium_modulus
    stages, notes = [], []
    if setup.needs_law and cfg.law.file is None:
        pressures = np.sort(law_pressures(cfg, np.ones(1)))
        mesh = law_mesh(setup)
        opts = cfg.fem.options(setup.material)
        each = np.array([law_point_seconds(setup, p) for p in pressures])
        how = " (auto)" if cfg.fem.mesh == "auto" else ""
        if uses_continuation(cfg, speeds):
            # one task per pressure, highest first (lawstage.law_batch)
            how = f"{how}, by continuation in speed"
            tasks = tuple(law_task_seconds(opts, setup.hs0, p, e_inf, speeds, True)
                          for p in pressures[::-1])
        else:
            tasks = tuple(np.tile(each, speeds).tolist())
        stages.append(Stage(f"law FEM points ({mesh[0]} x {mesh[1]}{how})",
                            len(pressures) * speeds, sum(tasks) / (len(pressures) * speeds),
                            tasks))
        if cfg.law.quasi_static_check:
            # one fresh point per law pressure at the quasi-static speed (.lawcheck), sent
            # in the law's sweep after its own tasks
            qs = np.array([quasi_static_seconds(opts, setup.hs0, p, e_inf) for p in pressures])
            stages.append(Stage("law cell quasi-static check (one point per law pressure)",
                                len(pressures), float(qs.mean()), tuple(qs[::-1].tolist()),
                                same_sweep=True))
        above = pressures[pressures > e_inf]
        if above.size:
            fate = ("not tried on the automatic mesh: outside the cell's range" if opts.auto
                    else "may stop and run the barrier rescue or the transient fallback, "
                         "minutes a point")
            notes.append(f"not budgeted: law FEM points at "
                         f"{', '.join(f'{p:g}' for p in above)} MPa, "
                         f"above the rubber's E∞ ({e_inf:.3g} MPa), {fate}")
        # one task per computed speed on the workers (.lawstage.law_tables)
        stages.append(Stage("law tables past the top FEM pressure (linear-law shape, one "
                            "task per speed)", speeds, LAW_TABLE_SPEED_S))
        stages.append(Stage("half-space solves of the high-slope waves (Fig. 7)",
                            len(pressures) * speeds,
                            halfspace_solve_seconds(min(cfg.halfspace.n, 4096))))
        stages += extension_stages(setup, float(pressures.max()), loads)
    if "fem" in setup.models:
        stage, note = full_fem_stage(setup)
        stages.append(stage)
        notes += [note] if note else []
    hs_models = [m for m in setup.models if planning(m).per == PER_REALIZATION]
    if hs_models:
        stages.append(Stage(f"half-space solves ({', '.join(hs_models)}; "
                            f"{cfg.halfspace.n} points)",
                            len(hs_models) * speeds * n_real * loads,
                            halfspace_solve_seconds(cfg.halfspace.n)))
    for m in (m for m in setup.models if planning(m).per == PER_LOAD):
        stages.append(Stage(f"mean-field points ({m})", speeds * loads,
                            meanfield_point_seconds(m)))
    if cfg.friction.flash_temperature.enabled:
        stages += flash_stages(setup, loads)
    return CostEstimate(tuple(stages), cfg.execution.workers, tuple(notes))


def full_fem_stage(setup: RunSetup) -> tuple[Stage, str | None]:
    """The full FEM's tests at the run's own loads (:func:`~.loads.run_pressures`: for
    target contact areas the VHS grid the run will sweep), each priced at its pressure,
    and the note for the loads above the rubber's E∞, which the run does not try
    (:func:`~.plan.run_loads`, :mod:`rubbercontact.fem.loadrange`)."""
    from ..fem.loadrange import held
    from .loads import run_pressures

    cfg = setup.config
    mesh = cfg.fem.full_mesh_or_default
    pressures = run_pressures(setup)
    e_inf = setup.material.equilibrium_modulus
    inside = pressures[held(pressures, e_inf)]
    runs = setup.speeds.computed.size * setup.n_fem
    each = [full_fem_seconds(setup, float(p)) for p in inside]
    stage = Stage(f"full FEM tests ({mesh[0]} x {mesh[1]})", runs * inside.size,
                  sum(each) / max(inside.size, 1))
    above = pressures[~held(pressures, e_inf)]
    if not above.size:
        return stage, None
    return stage, (f"full FEM not run at {', '.join(f'{p:.3g}' for p in above)} MPa: above "
                   f"the rubber's E∞ ({e_inf:.3g} MPa), outside the FEM cell's range")


def flash_stages(setup: RunSetup, loads: int) -> list[Stage]:
    """The flash temperature's solves (:mod:`.flash`): per half-space model, run
    temperature and load one task of its realizations' heated solves, priced as
    ``FLASH_SOLVE_FACTOR`` times their isothermal solves; ``meanfield-hybrid``'s μ(v) one
    task per run temperature and load, ``meanfield``'s in the run's own process,
    ``MEANFIELD_FLASH_CURVE_S`` each."""
    from .flash_halfspace import HALFSPACE_FLASH_MODELS
    from .flash_meanfield import MODEL as MEANFIELD_HYBRID

    temps = 1 if setup.speeds.temperatures is None else len(setup.speeds.temperatures)
    speeds, n_real = setup.speeds.velocities.size, len(setup.realizations)
    hs = [m for m in setup.models if m in HALFSPACE_FLASH_MODELS]
    out = []
    if hs:
        each = FLASH_SOLVE_FACTOR * halfspace_solve_seconds(setup.config.halfspace.n)
        tasks = len(hs) * temps * loads
        out.append(Stage(f"flash temperature: half-space solves ({', '.join(hs)}; "
                         f"{tasks} tasks)", tasks * n_real * speeds, each,
                         (n_real * speeds * each,) * tasks))
    if MEANFIELD_HYBRID in setup.models:
        out.append(Stage(f"flash temperature: {MEANFIELD_HYBRID} curves (one task each)",
                         temps * loads, MEANFIELD_FLASH_CURVE_S))
    if "meanfield" in setup.models:
        out.append(Stage("flash temperature: meanfield curves (in the run's own process)",
                         temps * loads, MEANFIELD_FLASH_CURVE_S,
                         (temps * loads * MEANFIELD_FLASH_CURVE_S,)))
    return out
