"""Newton–Krylov for the steady cell, and the homotopy that carries a solution along a path.

Newton's linear systems have the exact Jacobian (local tangent + upstream memory, see
:mod:`.steady`) applied matrix-free and are solved by right-preconditioned GMRES with
the factorized local tangent — the transient test's own tangent — as preconditioner.
Inexact Newton: GMRES stops at ``η = min(η_max, 0.1 ‖r‖/‖r₀‖)`` (Eisenstat–Walker type).

Globalisation: backtracking on the *preconditioned* residual ``‖K⁻¹ r‖`` with the
factorization frozen. The force residual is dominated by the penalty forces of the few
face nodes at the contact edges, where a good step that moves the contact set raises
``‖r‖`` at first; the preconditioned residual is that residual turned into
displacements, which the Newton direction decreases.

The homotopy (:func:`follow`) blends two problems — history kernels and loads — with a
parameter ``λ`` from 0 to 1 in adaptive steps: a step that Newton does not converge is
halved and retried from the last converged state, a quick one grows the next
(:data:`STEP_GROWTH`).
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass, field

import numpy as np

from ..halfspace.krylov import GmresResult, gmres
from .options import SteadyOptions
from .steady import SteadyCell, SteadyEvaluation
from .streamline import StreamlineKernel

log = logging.getLogger(__name__)



@dataclass
class Counters:
    """Work done by the steady solver (summed over every Newton solve)."""

    newton_iterations: int = 0
    krylov_iterations: int = 0
    factorizations: int = 0
    residual_evaluations: int = 0
    assembly_time: float = 0.0
    factorization_time: float = 0.0
    krylov_time: float = 0.0
    continuation_steps: int = 0
    cut_steps: int = 0
    tried: list = field(default_factory=list)   # one line per path: what was tried


class BudgetSpent(Exception):
    """The steady solve spent its Newton budget (:attr:`~.options.SteadyOptions.newton_budget`);
    raised out of every stage at once, so a stop costs no more than the budget."""

    def __init__(self, budget: int) -> None:
        super().__init__(f"Newton budget spent ({budget} iterations, steady.newton_budget)")
        self.budget = budget


@dataclass
class NewtonOutcome:
    """One Newton–Krylov solve: its last iterate, whether it converged, and why not."""

    U: np.ndarray
    ev: SteadyEvaluation
    converged: bool
    residuals: list[float]
    reason: str = ""


def _evaluate(cell: SteadyCell, U, shift, load, gauge, counters: Counters) -> SteadyEvaluation:
    t0 = time.perf_counter()
    ev = cell.evaluate(U, shift, load, gauge)
    counters.assembly_time += time.perf_counter() - t0
    counters.residual_evaluations += 1
    return ev


def newton_krylov(cell: SteadyCell, U0: np.ndarray, shift: float, load: float, gauge: str,
                  atol: float, options: SteadyOptions, counters: Counters) -> NewtonOutcome:
    """Solve the steady cell from ``U0``; never raises on non-convergence."""
    U = U0.copy()
    ev = _evaluate(cell, U, shift, load, gauge, counters)
    hist = [ev.norm]
    if not ev.admissible:
        return NewtonOutcome(U, ev, False, hist, "inadmissible start (inverted element)")
    pre, fresh = None, False
    for _ in range(options.newton_per_step):
        if hist[-1] <= atol:
            return NewtonOutcome(U, ev, True, hist)
        if counters.newton_iterations >= options.newton_budget:
            raise BudgetSpent(options.newton_budget)
        if pre is None:
            pre = _factor(cell, ev, counters)
            if pre is None:
                return NewtonOutcome(U, ev, False, hist, "factorization failed")
            fresh = True
        eta = min(options.krylov_rtol, max(1e-10, 0.1 * hist[-1] / hist[0]))
        step = _newton_step(cell, ev, pre, gauge, eta, options, counters)
        if isinstance(step, str) and not fresh:
            # the preconditioner is from an earlier iterate: refresh it and retry
            pre = _factor(cell, ev, counters)
            if pre is None:
                return NewtonOutcome(U, ev, False, hist, "factorization failed")
            fresh = True
            step = _newton_step(cell, ev, pre, gauge, eta, options, counters)
        if step == LINE_SEARCH_FAILED and eta > 1e-6:
            # an inexact direction need not decrease the merit: solve more accurately
            # (not after a stagnated GMRES: a tighter tolerance cannot help it)
            step = _newton_step(cell, ev, pre, gauge, 1e-6, options, counters)
        if isinstance(step, str):
            return NewtonOutcome(U, ev, False, hist, step)
        fresh = False
        if step.lin.iterations > options.refactor_krylov:
            pre = None     # the factorization has drifted too far from the Jacobian
        U = U + step.alpha * step.lin.x
        ev = step.trial
        hist.append(ev.norm)
        log.debug("newton: |r| %.2e -> %.2e, alpha %.3g, GMRES %d (%.1e)", hist[-2], hist[-1],
                  step.alpha, step.lin.iterations, step.lin.residual)
    if hist[-1] <= 30 * atol:
        # Stagnation just above the tolerance (a face point flickering in and out of
        # contact at round-off level): the force error is still <= 30 × atol, as the
        # transient test accepts.
        return NewtonOutcome(U, ev, True, hist, "loose")
    return NewtonOutcome(U, ev, False, hist, f"no convergence in {options.newton_per_step} Newton "
                                             f"iterations (|r| {hist[-1]:.2e}, tolerance "
                                             f"{atol:.2e})")


def _factor(cell: SteadyCell, ev: SteadyEvaluation, counters: Counters):
    t0 = time.perf_counter()
    try:
        pre = cell.factor(ev)
    except RuntimeError:   # singular tangent
        return None
    counters.factorization_time += time.perf_counter() - t0
    counters.factorizations += 1
    return pre


def _touches(ev: SteadyEvaluation) -> bool:
    """Whether the surface pushes on the face at ``ev`` (any contact force)."""
    return bool(np.any(ev.contact.force))


@dataclass(frozen=True, eq=False)
class NewtonStep:
    """An accepted damped Newton step: ``U + alpha · lin.x`` evaluated as ``trial``."""

    alpha: float
    lin: GmresResult
    trial: SteadyEvaluation


#: Why a Newton step was not taken (:func:`_newton_step`).
LINE_SEARCH_FAILED = "line search failed"
GMRES_STAGNATED = "GMRES stagnated"

#: GMRES goes on past its first restart cycle only if that cycle brought the relative
#: residual below this. Where the tangent is nearly singular (an iterate that lost its
#: last contact points leaves the cell floating) GMRES stalls at 0.1–1: measured on the
#: section 3 press (120 × 45, 2 MPa), 200 iterations ended at 0.12–2e4, twice per cut
#: step (the accurate retry too), 4–5 s each, and the step was cut anyway.
STAGNATION = 0.1


def _direction(cell: SteadyCell, ev: SteadyEvaluation, pre, gauge: str, eta: float,
               options: SteadyOptions) -> GmresResult | None:
    """The inexact Newton direction by GMRES to ``eta``; None if GMRES stagnated."""
    restart = min(60, options.max_krylov)

    def matvec(x):
        return cell.jvp(ev, x)

    def psolve(b):
        return pre.solve(b, gauge)

    lin = gmres(matvec, psolve, -ev.r, rtol=eta, restart=restart, maxiter=restart)
    if lin.residual <= eta or lin.iterations >= options.max_krylov:
        return lin
    if lin.residual > STAGNATION:
        return None
    more = gmres(matvec, psolve, -ev.r, x0=lin.x, rtol=eta, restart=restart,
                 maxiter=options.max_krylov - lin.iterations)
    return GmresResult(more.x, lin.iterations + more.iterations, more.residual)


def _newton_step(cell: SteadyCell, ev: SteadyEvaluation, pre, gauge: str, eta: float,
                 options: SteadyOptions, counters: Counters) -> NewtonStep | str:
    """GMRES to ``eta`` and a backtracking search on the preconditioned residual; the
    reason (:data:`GMRES_STAGNATED`, :data:`LINE_SEARCH_FAILED`) if no step is taken."""
    t0 = time.perf_counter()
    lin = _direction(cell, ev, pre, gauge, eta, options)
    counters.krylov_time += time.perf_counter() - t0
    counters.newton_iterations += 1
    if lin is None:
        counters.krylov_iterations += min(60, options.max_krylov)
        return GMRES_STAGNATED
    counters.krylov_iterations += lin.iterations
    if not np.all(np.isfinite(lin.x)):
        return LINE_SEARCH_FAILED
    merit0 = float(np.linalg.norm(pre.solve(ev.r, gauge)))
    carried = _touches(ev)
    # barrier contact: start where no contact point has crossed the surface on the way
    # (the penalty's 1); the halvings below keep it so
    alpha = cell.model.feasible_step(ev.U, lin.x, ev.shift)
    if alpha <= 0.0:
        return LINE_SEARCH_FAILED
    rejected = []
    barrier = cell.model.barrier is not None
    for _ in range(12):
        trial = _evaluate(cell, ev.U + alpha * lin.x, ev.shift, ev.load, gauge, counters)
        # A step must not lift the cell off the surface: without contact the plate's load
        # has no reaction and the next tangent is singular (GMRES stagnates and the whole
        # load step is cut). The linearized penalty overshoots exactly so when only one or
        # two face points touch (the first steps of a press).
        if trial.admissible and (_touches(trial) or not carried):
            merit = float(np.linalg.norm(pre.solve(trial.r, gauge)))
            # Also bound the growth of the force residual: a step that lowers the merit
            # while moving face points deep into the surface costs several damped
            # iterations afterwards (measured: half the Newton iterations with the bound).
            decrease = merit < (1.0 - 1e-4 * alpha) * merit0
            if decrease and (barrier or trial.norm <= 3.0 * ev.norm):
                return NewtonStep(alpha, lin, trial)
            # Barrier contact: its stiffness grows like 1/g² at the contact points, so the
            # frozen factorization's merit weighs the soft modes the step leaves: measured
            # on the steep cells, full steps that cut ‖r‖ 200-fold raised it by 1-20 % and
            # were refused to the last halving. A filter: a step that halves the force
            # residual is taken too (a penalty step that moves the contact set raises it).
            # The bound on the growth of ‖r‖ is the penalty's: a barrier point brought
            # close to the surface multiplies its force while the merit falls.
            if barrier and trial.norm <= 0.5 * ev.norm and merit < 2.0 * merit0:
                return NewtonStep(alpha, lin, trial)
            rejected.append(f"{alpha:.2g}: merit {merit / merit0:.3g}, |r| "
                            f"{trial.norm / ev.norm:.3g}")
        else:
            rejected.append(f"{alpha:.2g}: " + ("lifted" if trial.admissible else "inadmissible"))
        alpha *= 0.5
    log.debug("line search failed: %s", "; ".join(rejected))
    return LINE_SEARCH_FAILED


@dataclass(frozen=True, eq=False)
class Endpoint:
    """One end of a homotopy: the history kernel, the plate load [N/mm] and a residual
    bias [N/mm] (None: zero; see :class:`~.steady.SteadyCell`)."""

    kernel: StreamlineKernel
    load: float
    bias: np.ndarray | None = None


def blend(a: Endpoint, b: Endpoint, lam: float) -> Endpoint:
    """The problem at ``λ`` between ``a`` (0) and ``b`` (1); the preconditioner's diagonal
    is ``b``'s (it only changes the splitting, not the Jacobian)."""
    parts = [w * e.bias for e, w in ((a, 1.0 - lam), (b, lam)) if e.bias is not None]
    bias = sum(parts) if parts else None
    return Endpoint(a.kernel.blended(b.kernel, lam), (1.0 - lam) * a.load + lam * b.load, bias)


@dataclass
class PathResult:
    """The end of a homotopy, or how far it got."""

    U: np.ndarray
    ev: SteadyEvaluation | None
    reached: float            # λ of the last converged state
    converged: bool
    reason: str
    steps: list = field(default_factory=list)   # (λ, Newton iterations) per converged step


#: Newton tolerance of the intermediate steps of a path, as a multiple of its end's (1000:
#: 1e-3 of the plate load with ``newton_tol = 1e-6``; see :func:`follow`). A constant, not
#: a :class:`~.options.SteadyOptions` field: every option is in the result cache's key, and
#: the end of a path is converged to the same tolerance either way.
PATH_TOL_FACTOR = 1000.0


#: How a continuation step grows after one that converged in ``n`` Newton iterations: the
#: factor of the first row with ``n <= limit`` (none: the step is kept). The 1.5 after 6-8
#: iterations lets the steep cells' presses leave the 1/32 they settle at after two cuts,
#: where every step took 6-9 (doubling only after <= 5 kept it there). Measured on the
#: issue 41 cells (benchmarks/steady.md): 1284 -> 1236 Newton iterations over seven cells,
#: -6 to -13 % on four, +1 and +4 % on two (their larger steps are cut more often).
STEP_GROWTH = ((5, 2.0), (8, 1.5))


def growth(newton: int) -> float:
    """The factor of the next continuation step after one of ``newton`` iterations."""
    return next((f for n, f in STEP_GROWTH if newton <= n), 1.0)


def follow(cell: SteadyCell, U0: np.ndarray, start: Endpoint, end: Endpoint, shift: float,
           gauge: str, atol: float, options: SteadyOptions, counters: Counters,
           label: str, first_step: float | None = None,
           path_tol_factor: float = PATH_TOL_FACTOR) -> PathResult:
    """Carry the solution ``U0`` of ``start`` to ``end`` by adaptive steps in ``λ``.

    A state inside the path only starts the next step, whose Newton corrects it: the
    intermediate steps are converged to ``path_tol_factor × atol`` [N/mm] only, and the
    end (``λ = 1``) to ``atol``. That saves the last one or two quadratic iterations of
    every step, and a step that needs fewer iterations lets the next one grow (section 3,
    240 × 45, 2 MPa: 231 -> 189 Newton iterations, μ equal to 1e-12).
    """
    lam, step = 0.0, min(1.0, first_step or options.first_step)
    U = U0
    out = PathResult(U0, None, 0.0, False, "")
    reason = ""
    for _ in range(options.max_steps):
        target = min(1.0, lam + step)
        # The last converged state is the predictor: a secant extrapolation in λ moves the
        # face nodes into the surface, where the penalty makes its residual larger than
        # the plain start's (measured: 30x on the high-slope wave; on the section 3 press
        # at 2 MPa 13 of 28 secant-predicted steps failed and were redone from the plain
        # start, 85 s against 72 s).
        prob = blend(start, end, target)
        try:
            res = newton_krylov(cell.with_kernel(prob.kernel, prob.bias), U, shift, prob.load,
                                gauge, atol if target >= 1.0 else path_tol_factor * atol,
                                options, counters)
        except BudgetSpent as spent:
            counters.tried.append(f"{label}: {len(out.steps)} steps to λ = {out.reached:.4g} "
                                  f"({spent})")
            raise
        counters.continuation_steps += 1
        log.debug("%s: λ %.4g %s after %d Newton %s", label, target,
                  "converged" if res.converged else "cut", len(res.residuals) - 1, res.reason)
        if res.converged:
            U, lam = res.U, target
            out.U, out.ev, out.reached = U, res.ev, lam
            out.steps.append((lam, len(res.residuals) - 1))
            if lam >= 1.0:
                out.converged = True
                break
            step = min(step * growth(len(res.residuals) - 1), 1.0)
        else:
            reason = res.reason
            counters.cut_steps += 1
            step *= 0.5
            if step < options.min_step:
                break
    else:
        reason = reason or f"{options.max_steps} continuation steps"
    out.reason = "" if out.converged else (
        f"{label}: stopped at λ = {out.reached:.4g} (step {step:.2g}): {reason}")
    counters.tried.append(f"{label}: {len(out.steps)} steps to λ = {out.reached:.4g}"
                          + ("" if out.converged else f" ({reason})"))
    return out
