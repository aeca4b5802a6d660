"""The law's extension in ``run --check``'s estimate (:mod:`.cost`): one round priced at
its worst, from the per-task costs of :mod:`.costmodel`."""

from __future__ import annotations

import math

from ..models.planning import PER_REALIZATION
from ..models.registry import needs_law, planning
from .cost import Stage
from .costmodel import (
    LAW_TABLE_SPEED_S,
    halfspace_solve_seconds,
    law_task_seconds,
    meanfield_point_seconds,
    quasi_static_seconds,
)
from .setup import RunSetup


def extension_rungs(setup: RunSetup, top: float) -> list[float]:
    """The pressures [MPa] the law's extension (:mod:`.lawcover`) may add above the law's
    ``top``: the rungs of its ladder up to E∞ and ``law.max_pressure`` (it adds no point
    above them); empty when ``law.extend`` is off."""
    from .lawcover import ladder_above

    cfg = setup.config
    cap = min(setup.material.equilibrium_modulus, cfg.law.max_pressure or math.inf)
    if not cfg.law.extend or top >= cap:
        return []
    return [p for p in ladder_above(top, cap) if p <= cap]


def extension_stages(setup: RunSetup, top: float, loads: int) -> list[Stage]:
    """One round of the law's extension, priced as its worst case: FEM points at every rung
    of :func:`extension_rungs` at every computed speed, their quasi-static points (in the
    same sweep), the law's tables and the law models once more. A run whose local pressures
    stay inside the law, or whose cell would shear as a whole at the rung, does none of it
    (examples/asphalt.toml), and one that needs it pays it all (examples/dma_compound.toml,
    benchmarks/examples.md)."""
    from .lawstage import uses_continuation

    rungs = extension_rungs(setup, top)
    if not rungs:
        return []
    cfg, e_inf = setup.config, setup.material.equilibrium_modulus
    opts = cfg.fem.options(setup.material)
    speeds = setup.speeds.computed.size
    if uses_continuation(cfg, speeds):
        fem = tuple(law_task_seconds(opts, setup.hs0, p, e_inf, speeds, True)
                    for p in rungs[::-1])
    else:
        fem = tuple(law_task_seconds(opts, setup.hs0, p, e_inf) for p in rungs
                    for _ in range(speeds))
    n = len(rungs) * speeds
    at = ", ".join(f"{p:.3g}" for p in rungs)
    out = [Stage(f"law extension, if the local pressures pass the law (worst case: every "
                 f"speed at {at} MPa): FEM points", n, sum(fem) / n, fem)]
    if cfg.law.quasi_static_check:
        qs = tuple(quasi_static_seconds(opts, setup.hs0, p, e_inf) for p in rungs[::-1])
        out.append(Stage("law extension: quasi-static check", len(qs), sum(qs) / len(qs),
                         qs, same_sweep=True))
    out.append(Stage("law extension: law tables again", speeds, LAW_TABLE_SPEED_S))
    solves = [(speeds * len(setup.realizations) * loads,
               halfspace_solve_seconds(cfg.halfspace.n)) if planning(m).per == PER_REALIZATION
              else (speeds * loads, meanfield_point_seconds(m))
              for m in setup.models if needs_law(m)]
    count = sum(c for c, _ in solves)
    if count:
        out.append(Stage("law extension: the law models again", count,
                         sum(c * t for c, t in solves) / count))
    return out
