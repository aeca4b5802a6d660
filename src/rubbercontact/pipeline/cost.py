"""What a run will cost, before it runs: solves counted from the set-up, times from
measured per-point costs (``rubbercontact run --check``).

The counts are exact (they follow :mod:`.plan` and :mod:`.lawstage`); the times are the
counts times per-point costs measured on one core of the 2-core development machine. The
measured constants are all in the block "Measured costs" below, each with where it was
measured. The model, kept simple:

- a steady FEM point costs ``FEM_POINT_S`` on the reference law cell (120 × 23 elements),
  times the elements to the power ``FEM_ELEMENT_EXPONENT``, times ``1 + FEM_PRESSURE_SLOPE
  p / E∞`` (more Newton iterations as the load approaches the rubber's relaxed modulus);
  the time-stepped solver ``TRANSIENT_FACTOR`` times that; a full FEM test
  ``FULL_FEM_FACTOR`` times a law point of its mesh and load; along a path of speeds by
  continuation ``CONTINUATION_FACTOR`` of a fresh point per speed; on an automatic mesh
  a point whose narrowest contact patch is too narrow is re-solved on twice the columns
  (:mod:`rubbercontact.fem`), budgeted as ``AUTO_REFINED_SHARE`` of the points;
- a half-space solve ``HALFSPACE_SOLVE_S`` at ``HALFSPACE_POINTS``, as ``n log n``;
- the law's tables, continued past the top FEM pressure with the linear law's shape,
  ``LAW_TABLE_SPEED_S`` per computed speed, one task each on the workers;
- mean-field points per model, ``MEANFIELD_POINT_S``;
- the law cell's quasi-static check, one point per law pressure, ``QS_POINT_FACTOR``
  times a law point, ``QS_GRADED_FACTOR`` on an explicit mesh graded toward its face;
- with the flash temperature, per half-space model, run temperature and load one task of
  ``FLASH_SOLVE_FACTOR`` times its isothermal solves; per mean-field model, temperature
  and load one μ(v), ``MEANFIELD_FLASH_CURVE_S`` (``meanfield-hybrid``'s a task,
  ``meanfield``'s in the run's own process);
- the wall time: each stage's tasks in rounds of ``workers`` (a law by continuation has one
  task per pressure, so 5 pressures on 2 workers take 3 rounds), plus ``OVERHEAD_S``.

The law's extension when the local pressures go past its FEM points (:mod:`.lawcover`) is
priced as one round at its worst: every speed at every pressure it may add.
Not foreseen: further rounds of the extension (up to three), a steady
solve that stops and runs the barrier rescue or the transient fallback (minutes a point),
the steepness of a law cell (steep cells' points cost several times what this model
gives at the same p / E∞: docs/validation/steep_cells.md), a steady point that needs many
more Newton iterations than its neighbours (benchmarks/examples.md), and a loaded machine
(the wall time then grows with the load, the CPU time much less).
The FEM's cost varies by up to 10× with speed (the rubbery end, 1e-3 mm/s, costs the most)
and load: the estimate is meant to a factor of 2 (``benchmarks/examples.md`` compares it
with each example's measured time).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..models.planning import PER_LOAD, PER_REALIZATION
from ..models.registry import planning
from ..sweep.progress import scheduled
from .setup import RunSetup

# --- Measured costs: the one place ------------------------------------------------------
# CPU seconds of one process, one thread, on the 2-core x86_64 development machine. "Timed
# 2026-12-04": single law points of the examples timed in process (fem_task, one worker,
# 04:20-04:32 UTC, commit ee0af7b, load 9-11: CPU seconds, the wall was 4-5x that);
# "BENCHMARKS": BENCHMARKS.md, "Steady FEM against the time-stepped test".
#: Steady FEM point on the reference mesh, load far below E∞, 10-50 mm/s [s]. Timed
#: 2026-12-04 on examples/asphalt.toml's cell: 1.39 s at 0.1 MPa / 10 mm/s, 1.20 s at
#: 0.5 MPa / 50 mm/s.
FEM_POINT_S = 1.3
#: A law cell's quasi-static point (:mod:`.lawcheck`) against a law point at the same
#: pressure: the relaxed rubber indents deeper, in more continuation steps. Measured on the
#: built-in default (2026-12-06, load 15): its 6 quasi-static points took 113 s of wall
#: against 72 s for its 12 law points, about 3x a point; examples/captif_road.toml's
#: automatic cell (128 x 16, graded 9.9 by the rule), in process at 0.3 MPa (2026-12-06,
#: load 2, the FEM of 632bec3): 7.9 s of CPU against 3.1 s, 2.5x.
QS_POINT_FACTOR = 3.0
#: The same on an explicit mesh graded toward the face by more than ``QS_GRADING`` (the
#: section 3 law cell, 120 x 23, ``fem.grading = 8``): the grading, not the cell's size,
#: multiplies the relaxed press's iterations; the automatic mesh's grading does not.
#: Calibrated on examples/asphalt.toml's check continued from ``lawcheck.TAIL_FROM``
#: (benchmarks/qs_tail.md, benchmarks/examples.md).
QS_GRADED_FACTOR = 8.5
QS_GRADING = 2.0

#: The reference mesh (nx, ny): the law cell of examples/asphalt.toml and section3.toml.
FEM_REFERENCE_MESH = (120, 23)
#: Cost against the elements ``nx ny``. BENCHMARKS (quiet, 2298ddb): the section 3 full
#: cell, 240 × 45, 30.9 s at 0.35 MPa and 40.9 s at 2 MPa, where this model gives 19 and
#: 39 s; the default 120 × 90 cell at 1 MPa / 10 mm/s 9.2 s, where it gives 27 s (its rows
#: deep in the rubber are cheap): the exponent sits between the two.
FEM_ELEMENT_EXPONENT = 1.75
#: Cost against load: ``1 + FEM_PRESSURE_SLOPE p / E∞``. Timed 2026-12-04: 3.59 s at
#: 2 MPa / 10 mm/s on the asphalt cell (p / E∞ = 0.48), 2.8x the light points; BENCHMARKS:
#: 8 MPa / 10 mm/s (p / E∞ = 1.9) 14-17 s on the loaded machine, where this gives 10.5 s.
FEM_PRESSURE_SLOPE = 3.7
#: Time-stepped against steady solver: 22-196x (BENCHMARKS), taken as 50x.
TRANSIENT_FACTOR = 50.0
#: One speed of a path by continuation against a fresh point at 10-50 mm/s: BENCHMARKS
#: (quiet) 13 speeds at 1 MPa in 23 s, 0.7x; examples/dma_compound.toml (2026-12-04, load
#: 10) its paths at 0.1-3 MPa, 132 speeds in 135 s, 0.4x. (Fresh points at the rubbery end
#: cost far more: 62 s at 1e-3 mm/s, 1 MPa, BENCHMARKS.)
CONTINUATION_FACTOR = 0.5
#: Share of an automatic mesh's points re-solved on twice the columns (the narrowest
#: contact patch under ``fem.patch_columns`` columns), on the law cells as runs build them
#: since their crests are rounded to the profiles' sampling (``fem.crest_radius``): 38 of
#: the 135 law points of examples/speed_sweep.toml (2026-12-06 04:29 UTC, ab0117d), 0 of
#: the 3 of examples/captif_road.toml (twice, 03:49 and 06:09 UTC); 0.28. With sharp
#: crests it had been 2 of 3 and 106 of 135 (2026-12-04). The re-solve is priced as a fresh
#: point on the refined mesh (nx doubled, and the rows of the rule for twice the columns:
#: 256 x 19 after 128 x 16 on captif_road's cell); the solver presses it nested, on nx
#: columns first, and carries it over.
AUTO_REFINED_SHARE = 0.28
#: The full FEM's tests (the whole surface's cell, several waves) against a law point of the
#: same mesh and load: more contact patches to settle, more Newton iterations as the load
#: grows. examples/section3.toml reduced to 10 mm/s and the FEM on one realization
#: (61d4682, 2026-12-06, benchmarks/examples.md): its 240 x 45 tests took 25-45 Newton
#: iterations below 0.1 MPa, 88-185 at 0.2-0.45 MPa and 416-730 at 0.3-1 MPa, 0.23-0.25 s
#: of CPU an iteration (the same counts and CPU at e729684); its 1.5 and 2.3 MPa tests
#: together more than 13 min of CPU: in all at least 4x what the model gives the 12 at the
#: E∞/4 it prices target areas at. At 50 mm/s the BENCHMARKS rows (0.35 and 2 MPa, 103 and
#: 165 iterations) are 1.6x and 1.05x the model. Taken as 3 for runs of both speeds.
FULL_FEM_FACTOR = 3.0
#: One half-space solve (one load) [s] on ``HALFSPACE_POINTS`` points, scaled as n log n:
#: the examples from an empty cache on the quiet machine (2026-12-04 05:21 UTC, load
#: 0.3-2.4, benchmarks/examples.md), by the solves' own clocks: asphalt 120 solves in 4 s,
#: dma_compound 594 in 11 s, speed_sweep 540 in 9 s (0.017-0.033 s each; 0.2 s had been
#: read off a run at load 9).
HALFSPACE_SOLVE_S = 0.03
HALFSPACE_POINTS = 16384
#: The law's table at one computed speed [s]: its continuation past the top FEM pressure
#: with the linear law's shape (hybrid.linearlaw.continue_with_linear_shape: up to 41 VHS
#: solves of the high-slope waves at 2048 points), one cached task per speed on the
#: workers, one BLAS thread (hybrid/lawtask.py, since 3286531). 0.6 s on one thread
#: (asphalt's cell, 2026-12-06); examples/speed_sweep.toml from an empty cache (2026-12-06
#: 15:45 UTC, e45e668, load 4.4-5 with two workers on 2 cores): 69 tables, 124 s by their
#: own clocks, 1.8 s each, about 0.7 s of CPU at the core share the load left them. The
#: 3.5 s it had been was read off the runs' own-process CPU when the tables ran there on
#: every BLAS thread beside the workers (25 s a table had been seen there under load).
LAW_TABLE_SPEED_S = 1.0
#: Per-point cost of each mean-field model [s] (CPU time of the tasks of the default's
#: three loads at 10 and 50 mm/s on the section 3 and asphalt AC8 presets, 2026-12-03,
#: load 2.5; the strips: BENCHMARKS.md, "strip cascade"); a model not listed is priced as
#: the strips.
MEANFIELD_POINT_S = {"meanfield": 0.001, "meanfield-hybrid": 0.004, "meanfield-strips": 0.17}
#: A half-space model's flash (``[friction.flash_temperature]``) against its isothermal
#: solves, per speed, realization and load: the heated solves of the search, each warm
#: started from the nearest one solved (benchmarks/flash_run.md, 2026-12-03, load 3: the
#: guided flash's CPU 3.9 s against the isothermal model tasks' 2.7 s, 1.4x, on
#: speed_sweep made small, 8 speeds from 1e-3 mm/s of which the cold ones cost none;
#: benchmarks/flash.md, the Lennard-Jones wall over speed_sweep's 15 speeds: 2.2x).
FLASH_SOLVE_FACTOR = 1.8
#: One mean-field flash μ(v) per model, run temperature and load, in the run's own process
#: [s] (meanfield-hybrid 0.8-1.1 s for 2 loads of 13 speeds, 2026-12-04; meanfield under
#: 2 s over 201 speeds, benchmarks/flash.md).
MEANFIELD_FLASH_CURVE_S = 0.5
#: Set-up outside the solves (Python and the Dask workers' start, the surface, the law's
#: tables, the figures) [s]: the 2026-12-03 quiet asphalt run's 0.4 min wall less its solves.
OVERHEAD_S = 15.0
# ------------------------------------------------------------------------------------------


def fem_point_seconds(mesh: tuple[int, int], solver: str = "steady",
                      pressure: float = 0.0, modulus: float = math.inf) -> float:
    """Expected cost of one FEM sliding test [s].

    Parameters
    ----------
    mesh
        Elements (nx, ny) of the cell.
    solver
        ``"steady"`` or ``"transient"`` (``fem.solver``).
    pressure
        Mean pressure of the test [MPa]; 0 (the default) prices a light load.
    modulus
        The rubber's relaxed modulus E∞ [MPa] that ``pressure`` is measured against.

    Returns
    -------
    float
        ``FEM_POINT_S (elements / reference elements)^FEM_ELEMENT_EXPONENT
        (1 + FEM_PRESSURE_SLOPE pressure / modulus)``, times ``TRANSIENT_FACTOR`` for the
        time-stepped solver.
    """
    elements = mesh[0] * mesh[1] / (FEM_REFERENCE_MESH[0] * FEM_REFERENCE_MESH[1])
    t = FEM_POINT_S * elements ** FEM_ELEMENT_EXPONENT
    t *= 1.0 + FEM_PRESSURE_SLOPE * pressure / modulus
    return t * (TRANSIENT_FACTOR if solver == "transient" else 1.0)


def halfspace_solve_seconds(n: int) -> float:
    """Expected cost of one half-space solve (one load) on ``n`` points [s]."""
    ref = HALFSPACE_POINTS * math.log(HALFSPACE_POINTS)
    return HALFSPACE_SOLVE_S * n * math.log(n) / ref


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
        What the run may cost beyond the estimate, as ``run --check`` prints it.
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
                     f"rubbercontact.pipeline.cost)")
        lines += [f"cost: not budgeted: {note}" for note in self.notes]
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


# --- Per task: what run --check adds up, and each sweep task's cost hint (Task.cost) ----
def law_point_seconds_on(options, surface, pressure: float, modulus: float) -> float:
    """:func:`law_point_seconds` from the law cell's own terms: its
    :class:`~rubbercontact.fem.FemOptions`, its surface (the high-slope waves), the
    point's pressure [MPa] and the rubber's E∞ [MPa]. Zero for a pressure the automatic
    mesh does not try (:mod:`rubbercontact.fem.loadrange`)."""
    from ..fem.loadrange import outside_range
    from ..fem.resolution import refined_mesh

    if options.auto and outside_range(pressure, modulus):
        return 0.0
    mesh = tuple(options.resolved(surface).mesh)
    t = fem_point_seconds(mesh, options.solver, pressure, modulus)
    if options.auto:
        m = refined_mesh(surface, options.height_ratio, options.columns_per_wave)
        t += AUTO_REFINED_SHARE * fem_point_seconds((m.nx, m.ny), options.solver, pressure,
                                                    modulus)
    return t


def law_task_seconds(options, surface, pressure: float, modulus: float, speeds: int = 1,
                     continuation: bool = False) -> float:
    """Expected cost of one law FEM task [s]: a fresh point, or a path of ``speeds`` by
    continuation (``CONTINUATION_FACTOR`` of a fresh point per speed)."""
    fresh = law_point_seconds_on(options, surface, pressure, modulus)
    return fresh * CONTINUATION_FACTOR * speeds if continuation else fresh


def quasi_static_seconds(options, surface, pressure: float, modulus: float) -> float:
    """Expected cost of the law cell's quasi-static point at ``pressure`` [s]:
    ``QS_POINT_FACTOR`` times a law point, ``QS_GRADED_FACTOR`` on an explicit mesh graded
    by more than ``QS_GRADING``."""
    graded = not options.auto and options.grading > QS_GRADING
    factor = QS_GRADED_FACTOR if graded else QS_POINT_FACTOR
    return factor * law_point_seconds_on(options, surface, pressure, modulus)


def full_fem_seconds(setup: RunSetup, pressure: float) -> float:
    """Expected cost of one full FEM test at ``pressure`` [MPa] [s] (``FULL_FEM_FACTOR``
    times a point of the full mesh)."""
    cfg = setup.config
    return FULL_FEM_FACTOR * fem_point_seconds(cfg.fem.full_mesh_or_default, cfg.fem.solver,
                                               pressure, setup.material.equilibrium_modulus)


def meanfield_point_seconds(model: str) -> float:
    """Expected cost of one mean-field point of ``model`` [s] (``MEANFIELD_POINT_S``; a
    model not listed priced as the strips)."""
    return MEANFIELD_POINT_S.get(model, MEANFIELD_POINT_S["meanfield-strips"])


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

    cfg = setup.config
    speeds = setup.speeds.computed.size
    loads = (len(cfg.loads.pressures) if cfg.loads.pressures is not None
             else cfg.loads.sweep_points or max(6, len(cfg.loads.contact_areas) + 2))
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
            notes.append(f"law FEM points at {', '.join(f'{p:g}' for p in above)} MPa, "
                         f"above the rubber's E∞ ({e_inf:.3g} MPa), {fate}")
        # one task per computed speed on the workers (.lawstage.law_tables)
        stages.append(Stage("law tables past the top FEM pressure (linear-law shape, one "
                            "task per speed)", speeds, LAW_TABLE_SPEED_S))
        stages.append(Stage("half-space solves of the high-slope waves (Fig. 7)",
                            len(pressures) * speeds,
                            halfspace_solve_seconds(min(cfg.halfspace.n, 4096))))
        stages += extension_stages(setup, float(pressures.max()), loads)
    if "fem" in setup.models:
        mesh = cfg.fem.full_mesh_or_default
        # loads given as contact areas: priced at E∞/4, about 1 MPa for the SBR, inside
        # the 0.03-2.3 MPa of the section 3 areas 0.01-0.1's load grid
        load = (float(np.mean(cfg.loads.pressures)) if cfg.loads.pressures is not None
                else e_inf / 4)
        stages.append(Stage(f"full FEM tests ({mesh[0]} x {mesh[1]})",
                            speeds * setup.n_fem * loads, full_fem_seconds(setup, load)))
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
