"""What a run will cost, before it runs: solves counted from the set-up, times from
measured per-point costs (``rubbercontact run --check``).

The counts are exact (they follow :mod:`.plan` and :mod:`.lawstage`); the times are the
counts times per-point costs measured on one core of the 2-core development machine, in
the built-in default's run (``make run`` from an empty cache, 2026-12-03, commit 5ebb528;
the load average was 3-4, so the figures are on the high side of a quiet machine's):

- steady FEM: 3.6 s per point on the 40 × 30 law cell (mean of 14 points at 0.05-4 MPa,
  10 and 50 mm/s; single points range from 1 to 18 s) and 14 s per point on the 64 × 48
  full cell; in between, and beyond, as the unknowns to the power 1.5 (the two sizes give
  1.5; the 24 × 12 cell of the README's quick start, 0.2 s measured, 0.4 s by the law);
- a law path by continuation in speed costs a quarter of a fresh point per speed
  (BENCHMARKS, "Steady FEM": 13 speeds at 1 MPa on the 120 × 23 cell in 23 s, 2.1× the
  fresh 1 mm/s point); the time-stepped solver costs 20-200× the steady one (BENCHMARKS),
  counted as 50×;
- half-space: 0.05 s per load at 2048 points (96 solves of the default in 5.0 s), scaled
  as ``n log n``;
- mean-field, per point and model (CPU time of the tasks of the default's three loads at
  10 and 50 mm/s on the section 3 and asphalt AC8 presets, 2026-12-03, load 2.5):
  ``meanfield`` (Persson's theory) about 1 ms, ``meanfield-hybrid`` about 4 ms (the law's
  compliance in series), ``meanfield-strips`` 0.06-0.27 s (the strip cascade; 0.17 s in
  BENCHMARKS, "strip cascade"); a model not listed is priced as the strips.

A run's wall time is about the sum over the workers plus some 40 s of set-up (Dask, the
roughness analysis of the default, the figures): the estimate is good to a factor of 2,
the FEM's per-point cost varying by up to 10× with speed and load.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..models.planning import PER_LOAD, PER_REALIZATION
from ..models.registry import planning
from .setup import RunSetup

#: Measured per-point costs [s] (module docstring).
FEM_POINT_S = 3.6
FEM_POINT_UNKNOWNS = 2 * 41 * 31          # the 40 x 30 cell's nodes, two components each
FEM_EXPONENT = 1.5
TRANSIENT_FACTOR = 50.0
CONTINUATION_FACTOR = 0.25
HALFSPACE_SOLVE_S = 0.05
HALFSPACE_POINTS = 2048
#: Per-point cost of each mean-field model [s] (module docstring).
MEANFIELD_POINT_S = {"meanfield": 0.001, "meanfield-hybrid": 0.004, "meanfield-strips": 0.17}
#: Set-up outside the solves (Dask's start, the figures) [s].
OVERHEAD_S = 40.0


def fem_point_seconds(mesh: tuple[int, int], solver: str = "steady") -> float:
    """Expected cost of one FEM sliding test on ``mesh`` (nx, ny elements) [s]."""
    unknowns = 2 * (mesh[0] + 1) * (mesh[1] + 1)
    t = FEM_POINT_S * (unknowns / FEM_POINT_UNKNOWNS) ** FEM_EXPONENT
    return t * (TRANSIENT_FACTOR if solver == "transient" else 1.0)


def halfspace_solve_seconds(n: int) -> float:
    """Expected cost of one half-space solve (one load) on ``n`` points [s]."""
    ref = HALFSPACE_POINTS * math.log(HALFSPACE_POINTS)
    return HALFSPACE_SOLVE_S * n * math.log(n) / ref


@dataclass(frozen=True)
class Stage:
    """One kind of solve of a run: how many, and the expected cost of each [s]."""

    name: str
    count: int
    each_s: float

    @property
    def total_s(self) -> float:
        return self.count * self.each_s


@dataclass(frozen=True)
class CostEstimate:
    """The solves of a run and their expected cost.

    Attributes
    ----------
    stages
        The kinds of solve (only those the run has).
    workers
        Parallel workers the solves share (``execution.workers``).
    """

    stages: tuple[Stage, ...]
    workers: int

    @property
    def compute_s(self) -> float:
        """Expected CPU time of the solves [s]."""
        return sum(s.total_s for s in self.stages)

    @property
    def wall_s(self) -> float:
        """Expected wall time [s]: the solves shared by the workers, plus set-up."""
        return self.compute_s / self.workers + OVERHEAD_S

    def describe(self) -> str:
        """The estimate as the lines ``run --check`` prints."""
        lines = [f"cost: {s.name}: {s.count} x ~{_duration(s.each_s)} = "
                 f"{_duration(s.total_s)}" for s in self.stages if s.count]
        lines.append(f"cost: about {_duration(self.wall_s)} on {self.workers} worker(s) "
                     f"from an empty cache (to a factor of 2; per-point costs measured on "
                     f"one core, rubbercontact.pipeline.cost)")
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
    (:meth:`rubbercontact.fem.FemOptions.resolved`; a point refined by its resolution check
    costs more, which the estimate does not foresee)."""
    return tuple(setup.config.fem.options(setup.material).resolved(setup.hs0).mesh)


def estimate_cost(setup: RunSetup) -> CostEstimate:
    """Count the solves of a resolved run (:func:`~.setup.resolve`) and price them."""
    from .lawstage import law_pressures, uses_continuation

    cfg = setup.config
    speeds = setup.speeds.computed.size
    loads = (len(cfg.loads.pressures) if cfg.loads.pressures is not None
             else cfg.loads.sweep_points or max(6, len(cfg.loads.contact_areas) + 2))
    n_real = len(setup.realizations)
    stages = []
    if setup.needs_law and cfg.law.file is None:
        import numpy as np

        n_law = len(law_pressures(cfg, np.ones(1)))
        mesh = law_mesh(setup)
        each = fem_point_seconds(mesh, cfg.fem.solver)
        how = " (auto)" if cfg.fem.mesh == "auto" else ""
        if uses_continuation(cfg, speeds):
            each, how = each * CONTINUATION_FACTOR, f"{how}, by continuation in speed"
        stages.append(Stage(f"law FEM points ({mesh[0]} x {mesh[1]}{how})",
                            n_law * speeds, each))
        stages.append(Stage("half-space solves of the high-slope waves (Fig. 7)",
                            n_law * speeds,
                            halfspace_solve_seconds(min(cfg.halfspace.n, 4096))))
    if "fem" in setup.models:
        mesh = cfg.fem.full_mesh_or_default
        stages.append(Stage(f"full FEM tests ({mesh[0]} x {mesh[1]})",
                            speeds * setup.n_fem * loads,
                            fem_point_seconds(mesh, cfg.fem.solver)))
    hs_models = [m for m in setup.models if planning(m).per == PER_REALIZATION]
    if hs_models:
        stages.append(Stage(f"half-space solves ({', '.join(hs_models)}; "
                            f"{cfg.halfspace.n} points)",
                            len(hs_models) * speeds * n_real * loads,
                            halfspace_solve_seconds(cfg.halfspace.n)))
    for m in (m for m in setup.models if planning(m).per == PER_LOAD):
        stages.append(Stage(f"mean-field points ({m})", speeds * loads,
                            MEANFIELD_POINT_S.get(m, MEANFIELD_POINT_S["meanfield-strips"])))
    return CostEstimate(tuple(stages), cfg.execution.workers)
