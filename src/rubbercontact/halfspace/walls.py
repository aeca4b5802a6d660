r"""Lennard-Jones wall + soft law: ``LennardJonesRepulsion() + TabulatedLaw(...)``, the hybrid's.

*Active-set path* (``options.wall_soft_active_set``): the stiff wall is first replaced by a hard
wall, which turns the problem into "hard wall + soft law": ``u >= 0``, ``λ = σ − f(u) >= 0``,
``u λ = 0`` with ``f`` the soft member. Steps: (1) Winkler-foundation pressure, ``ū`` shifted so
that ``<f(u)> = σ0`` (no linear solve); (2) the soft law alone by Newton from it (if it fails,
as for a soft law steep on the scale of the roughness, from the hard wall of ``Re M`` instead);
(3) the hard wall + soft law by a semismooth (primal–dual active-set) Newton on
``C = min(u, W λ)`` (:func:`wall_soft_active_set`): on the contact set ``A = {W λ > u}`` the
equation is ``u = 0``, off it ``σ = f(u)`` linearised, i.e. the Newton system of
:mod:`~rubbercontact.halfspace.newton` with ``c = 0`` on ``A``; the soft law is evaluated at
``u₊`` (penetration is the wall's business), line search on ``|C|₂``; (4) Newton on the full law
from that state, ``ū`` shifted so that ``<f(u)> = σ0``. On 1D grids with ``N`` divisible by 4
and at least four times ``options.wall_soft_coarse_min_points`` (maps: even sides at least
twice ``options.coarse_min_side_2d``, every 2nd point per axis), steps 1–3 are done on a 4×
coarser grid first (recursively) and step 3 restarts from the interpolated result: the active
set changes by a few points per step where ``u`` and ``λ`` are both small (the soft law's
pressure at contact close to what the wall carries), so from a poor start its step count grows
with N. μ, contact fraction and ``ū`` equal those of the continuation path below (tested).

*Continuation path* (if any step fails, or ``wall_soft_active_set=False``): the wall alone from
the hard-wall state, then the soft member switched on as ``wall + s·soft``, ``s: 0 → 1``, each
stage by Newton from the previous one (step doubled after a success, quartered after a
failure). Many stages are needed when the wall carries much of the load: Newton with a linear
update in ``σ`` opens a wall contact by only a fraction of ``ℓ`` per step. Step counts and
timings of both paths are measured in ``benchmarks/halfspace.md``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import partial

import numpy as np

from ..errors import InputError
from .contact_set import contact_solve, shifted_preconditioner, step_displacement
from .hardwall import hard_wall_active_set, winkler_guess
from .laws import LAW_KINDS, InteractionLaw, SumLaw
from .newton import _step, newton_from, newton_law, shift_for_law
from .problem import Problem, Solution

__all__ = ["LawParts", "solve_wall_soft", "split_law", "wall_soft_active_set"]


@dataclass(frozen=True)
class LawParts:
    """A law split into its stiff wall (members of kind ``"wall"``) and its soft remainder."""

    stiff: InteractionLaw | None
    soft: InteractionLaw | None


def split_law(law: InteractionLaw) -> LawParts:
    """(stiff wall part, soft remainder) of a law; either may be ``None``.

    Each member is routed by the :attr:`~.laws.InteractionLaw.kind` it declares.
    """
    members = law.members
    for m in members:
        if getattr(m, "kind", None) not in LAW_KINDS:
            raise InputError(f"law: {type(m).__name__} declares kind "
                             f"{getattr(m, 'kind', None)!r}; expected one of {LAW_KINDS}")
    stiff = [m for m in members if m.kind == "wall"]
    soft = [m for m in members if m.kind == "soft"]

    def pack(ms):
        return None if not ms else ms[0] if len(ms) == 1 else SumLaw(*ms)

    return LawParts(pack(stiff), pack(soft))


def wall_soft_active_set(prob: Problem, soft: InteractionLaw, tol: float, max_iter: int,
                         sigma: np.ndarray, ubar: float,
                         active: np.ndarray | None = None) -> Solution:
    """Hard wall + soft law: ``u >= 0``, ``λ = σ − f(u) >= 0``, ``u λ = 0`` (semismooth Newton).

    Semismooth Newton on the complementarity function ``C = min(u, W λ)`` with
    ``W = 1/(k + 1/m_d)`` (``k = −f'``, ``m_d`` the diagonal of ``M``): on the contact set
    ``A = {W λ > u}`` the equation is ``u = 0`` (the wall multiplier is free), off it ``σ = f(u)``
    linearised. Each step is one contact-set linear solve with ``c = 0`` on ``A`` and ``c = 1/k``
    where the soft law is stiff (same system and preconditioner as the Newton solver); points
    where ``f`` is flat are updated explicitly. Backtracking line search on ``|C|₂`` (``W`` frozen
    during the search). The soft law is evaluated at ``u₊``: penetration is left to the wall, and
    the law's steep extrapolation below ``u = 0`` would otherwise wreck the merit. Converged when
    the rms of ``C`` falls below ``tol × max|z|``.
    """
    n = prob.size
    z = prob.z
    m_diag = prob.compliance_diagonal
    zscale = float(np.abs(z).max()) or 1.0
    w = prob.displacement(sigma)
    u = ubar + w - z
    # the soft law is only evaluated at u >= 0: penetration is the wall's business (it
    # enters the set at the next update); its steep extrapolation below u = 0 would
    # otherwise dominate the line-search merit
    f, k = soft.pressure_and_stiffness(np.maximum(u, 0.0))
    if active is None:
        active = (sigma - f) / (k + 1.0 / m_diag) > u
    lin_its = 0
    history = []
    res = np.inf

    def merit(sig, uu, ff, wgt):
        # semismooth complementarity residual min(u, W λ), λ = σ − f(u₊), as a displacement
        return np.minimum(uu, wgt * (sig - ff))

    moving = True    # the set changed by more than _MOVING_SET of its points at the last update
    # the merit's weights and value at the current state, carried from the last update's
    # test (the same numbers, not computed twice)
    wgt = 1.0 / (k + 1.0 / m_diag)
    phi0 = float(np.linalg.norm(merit(sigma, u, f, wgt)))
    for it in range(1, max_iter + 1):
        stiff = active | (k * m_diag > 1e-8)
        idx = np.flatnonzero(stiff)
        free = ~stiff
        # whole-grid passes, not masked ones (a masked gather or scatter of most of a map's
        # points costs several whole-grid passes); the same values and sums
        dsig = np.where(free, f - sigma, 0.0)
        total = prob.sigma0 * n - sigma.sum() - np.compress(free, dsig).sum()
        on_a = active[idx]
        c = np.zeros(idx.size)
        kk = k[idx]
        c[~on_a] = 1.0 / kk[~on_a]
        w_free = prob.displacement(dsig) if np.any(dsig) else np.zeros(n)   # 0 off free
        rhs = np.where(on_a, -u[idx], c * (f[idx] - sigma[idx])) - w_free[idx]
        contact = c < m_diag
        precond = partial(shifted_preconditioner, prob, c, contact)   # if used
        lin = contact_solve(prob, idx, rhs, total, precond,
                            c=c, rtol=_linear_rtol(prob, moving), extra_diag=~contact,
                            soft_shifts=prob.options.wall_soft_shifts_2d)
        lin_its += lin.iterations
        dsig[idx] = lin.x
        dw = step_displacement(prob, dsig, w_free, lin)
        du = lin.multiplier + dw
        t = 1.0
        k_t = None
        for _ in range(30):
            s_t = _step(sigma, t, dsig)
            u_t = _step(u, t, du)
            if t == 1.0:   # the full step, nearly always taken: its stiffness in the same pass
                f_t, k_t = soft.pressure_and_stiffness(np.maximum(u_t, 0.0))
            else:
                f_t, k_t = soft.pressure(np.maximum(u_t, 0.0)), None
            phi = float(np.linalg.norm(merit(s_t, u_t, f_t, wgt)))
            if phi <= (1 - 1e-4 * t) * phi0 or phi <= 1e-3 * tol * zscale:
                break
            t *= 0.5
        sigma, ubar, u, w = s_t, ubar + t * lin.multiplier, u_t, _step(w, t, dw)
        if k_t is None:
            k_t = soft.stiffness(np.maximum(u, 0.0))
        wgt = 1.0 / (k_t + 1.0 / m_diag)
        scaled = wgt * (sigma - f_t)     # W λ
        phi0 = float(np.linalg.norm(np.minimum(u, scaled)))     # merit(sigma, u, f_t, wgt)
        res = phi0 / zscale / np.sqrt(n)
        new = scaled > u
        changed = int(np.count_nonzero(new != active))
        moving = changed > _MOVING_SET * max(int(new.sum()), 1)
        history.append((int(active.sum()), changed, lin.iterations, lin.residual, t, res))
        if res <= tol:
            return Solution(sigma, u, w, ubar, it, res, True,
                            {"linear_iterations": lin_its, "history": history, "active": active})
        active = new
        f, k = f_t, k_t       # the law at the accepted u, for the next step
    return Solution(sigma, u, w, ubar, max_iter, res, False,
                    {"linear_iterations": lin_its, "history": history, "active": active})


#: A hard wall + soft law update that changes more than this fraction of the contact set
#: leaves the next step's system to ``options.wall_soft_moving_rtol_2d`` on maps.
_MOVING_SET = 0.01


def _linear_rtol(prob: Problem, moving: bool = False) -> float:
    """GMRES tolerance of a hard wall + soft law step: ``options.wall_soft_linear_rtol``, on
    maps ``options.wall_soft_linear_rtol_2d``, or ``options.wall_soft_moving_rtol_2d``
    while the set still ``moving`` (the first step, and after an update that changed more
    than ``_MOVING_SET`` of it)."""
    opts = prob.options
    if moving and len(prob.shape) == 2 and opts.wall_soft_moving_rtol_2d is not None:
        return max(opts.wall_soft_moving_rtol_2d, opts.wall_soft_linear_rtol_2d)
    return opts.wall_soft_linear_rtol_2d if len(prob.shape) == 2 else opts.wall_soft_linear_rtol


def _coarse_tol(prob: Problem, tol: float) -> float:
    """Tolerance of the coarser grids' hard wall + soft law: ``tol``; on maps at least
    ``options.wall_soft_coarse_tol_2d`` (their answer is only the finer grid's start)."""
    if len(prob.shape) == 2 and prob.options.wall_soft_coarse_tol_2d is not None:
        return max(tol, prob.options.wall_soft_coarse_tol_2d)
    return tol


def _with_soft_start(act: Solution, soft_newton_iterations: int, linear_iterations: int,
                     **extra) -> Solution:
    """``act`` with the soft Newton's (and coarser grids') counts added to its info."""
    info = {**act.info, "soft_newton_iterations": soft_newton_iterations, **extra,
            "linear_iterations": act.info["linear_iterations"] + linear_iterations}
    return replace(act, info=info)


def _hard_wall_soft(prob: Problem, soft: InteractionLaw, tol: float,
                    max_iter: int, finest: bool = True) -> Solution | None:
    """Hard wall + soft law (steps 1–3 of the active-set path); ``None`` on failure.

    On grids that can be coarsened (``options.wall_soft_coarse_min_points``) it starts from
    the interpolated solution on a 4× coarser grid (recursively), as the viscoelastic hard wall.
    On a map the ``finest`` grid starts from the grid 4× coarser per axis where that one
    exists (``options.wall_soft_skip_level_2d``; :func:`_start_grid`).
    """
    min_points = prob.options.wall_soft_coarse_min_points
    min_side = prob.options.wall_soft_coarse_min_side_2d
    if prob.can_coarsen(min_points, min_side):
        levels = _start_grid(prob, finest)
        coarse = levels[-1]
        out_c = _hard_wall_soft(coarse, soft, _coarse_tol(prob, tol), max_iter, finest=False)
        prob.matvecs += coarse.matvecs
        if out_c is not None:
            start = out_c.sigma
            for level in reversed([prob, *levels[:-1]]):
                start = level.refine(start)
            act = wall_soft_active_set(prob, soft, tol, min(max_iter, 100), start,
                                       out_c.ubar)
            if act.converged:
                return _with_soft_start(act, out_c.info.get("soft_newton_iterations", 0),
                                        out_c.info["linear_iterations"],
                                        coarse_levels=out_c.info.get("coarse_levels", 0) + 1)
    sigma = winkler_guess(prob, prob.z)
    w = prob.displacement(sigma)
    shift = shift_for_law(soft, w - prob.z, prob.sigma0)
    so = newton_law(prob, soft, tol, max_iter, sigma, shift)
    if not so.converged:
        # a soft law that is steep on the scale of the roughness (observed: AC-8 low-slope
        # part, 0.5 mm waves, law decaying over 2 µm) needs a hard-wall start, as the
        # Lennard-Jones wall does: the symmetric (Re M) one is cheap and enough
        sym = prob.with_compliance(np.real(prob.compliance))
        hw = hard_wall_active_set(sym, tol, max_iter)
        prob.matvecs += sym.matvecs
        if not hw.converged:
            return None
        so = newton_from(prob, soft, hw, tol, max_iter, loose=True, mixed=False)
        if not so.converged:
            return None
    act = wall_soft_active_set(prob, soft, tol, min(max_iter, 100), so.sigma, so.ubar)
    if not act.converged:
        return None
    return _with_soft_start(act, so.iterations, so.info["linear_iterations"])


def _start_grid(prob: Problem, finest: bool) -> list[Problem]:
    """The coarser grids from ``prob`` down to the one its hard wall + soft law starts
    from: ``[prob.coarse()]``, or on the ``finest`` grid of a map with
    ``options.wall_soft_skip_level_2d`` ``[prob.coarse(), prob.coarse().coarse()]`` when
    the first can itself be coarsened: the finest grid then starts from the grid 4× coarser
    per axis. On the 1024² linear-law case of ``benchmarks/maps.md`` the 512² stage took 8
    updates (0.5 s) to spare the 1024² grid one (0.25–0.35 s); from 256² it takes 10
    instead of 9. Coarser levels keep halving: skipping there too (1024² from 256² from
    64²) cost the 1024² grid more updates than it saved.
    """
    coarse = prob.coarse()
    opts = prob.options
    if finest and len(prob.shape) == 2 and opts.wall_soft_skip_level_2d \
            and coarse.can_coarsen(opts.wall_soft_coarse_min_points,
                                   opts.wall_soft_coarse_min_side_2d):
        return [coarse, coarse.coarse()]
    return [coarse]


def _active_set_path(prob: Problem, law: InteractionLaw, soft: InteractionLaw, tol: float,
                     max_iter: int) -> Solution | None:
    """Steps 1–4 of the active-set path (module docstring); ``None`` if a stage fails.

    Step 2 (the soft law alone by Newton from the Winkler pressure) is as good a start as the
    symmetric hard-wall solution at a fraction of its cost; step 4 replaces ``u = 0`` on the
    contact set by the wall gap ``u ≈ ℓ``.
    """
    act = _hard_wall_soft(prob, soft, max(tol, 1e-8), max_iter)
    if act is None:
        return None
    out = _full_law_newton(prob, law, soft, act, tol, max_iter)
    if not out.converged:
        return None
    info = {**out.info, "continuation": [1.0], "wall_soft_active_set_iterations": act.iterations,
            "soft_newton_iterations": act.info["soft_newton_iterations"],
            "coarse_levels": act.info.get("coarse_levels", 0),
            "linear_iterations": out.info["linear_iterations"] + act.info["linear_iterations"],
            "wall_soft_history": act.info["history"], "wall_soft_method": "active-set"}
    return replace(out, iterations=out.iterations + act.iterations
                   + info["soft_newton_iterations"], info=info)


def _full_law_newton(prob: Problem, law: InteractionLaw, soft: InteractionLaw, act: Solution,
                     tol: float, max_iter: int) -> Solution:
    """Step 4: Newton on the full law from the hard wall + soft law state ``act``.

    On a map (``options.wall_soft_mixed_newton_2d``) the wall's contact rows are linearised
    in the wall's inverse form (:func:`~.newton.newton_law` with ``soft``): the plain Newton
    creeps there as it does for the Lennard-Jones wall alone (10 steps against 4 on the
    maps of ``benchmarks/maps.md``). The plain Newton is the fallback.
    """
    walls = [m for m in law.members if m.kind == "wall"]
    inverse = walls[0].inverse() if len(walls) == 1 else None
    if len(prob.shape) == 2 and prob.options.wall_soft_mixed_newton_2d and inverse is not None:
        shift = shift_for_law(law, act.w - prob.z, prob.sigma0, guess=act.ubar)
        out = newton_law(prob, law, tol, max_iter, act.sigma, shift, loose=True,
                         inverse=inverse, soft=soft)
        if out.converged:
            return out
    return newton_from(prob, law, act, tol, max_iter, loose=True, mixed=False)


class _Blend(InteractionLaw):
    """``stiff + s·soft`` (pressure and stiffness only): a continuation stage."""

    def __init__(self, stiff: InteractionLaw, soft: InteractionLaw, s: float) -> None:
        self.stiff, self.soft, self.s = stiff, soft, s

    def pressure(self, u):
        return self.stiff.pressure(u) + self.s * self.soft.pressure(u)

    def stiffness(self, u):
        return self.stiff.stiffness(u) + self.s * self.soft.stiffness(u)


def _continuation(prob: Problem, law: InteractionLaw, parts: LawParts, tol: float,
                  max_iter: int, hard_wall: Solution) -> Solution:
    """The wall alone from the hard wall, then ``wall + s·soft`` with ``s`` stepping to 1."""
    mixed = prob.options.mixed_newton

    def newton(stage_law, start, final):
        return newton_from(prob, stage_law, start, tol if final else max(tol, 1e-6),
                           max_iter if final else min(max_iter, 40), loose=False, mixed=mixed)

    out = newton(parts.stiff, hard_wall, False)
    total_its = out.iterations
    lin = out.info["linear_iterations"]
    if not out.converged:
        return out
    stages = []
    s_prev, step = 0.0, 1.0
    while s_prev < 1.0:
        s = min(1.0, s_prev + step)
        final = s == 1.0
        trial = newton(law if final else _Blend(parts.stiff, parts.soft, s), out, final)
        total_its += trial.iterations
        lin += trial.info["linear_iterations"]
        if trial.converged:
            stages.append(s)
            s_prev, out = s, trial
            step *= 2.0
        else:
            step *= 0.25
            if step < 1e-4:
                out = trial
                break
    return replace(out, iterations=total_its,
                   info={**out.info, "linear_iterations": lin, "continuation": stages})


def solve_wall_soft(prob: Problem, law: InteractionLaw, parts: LawParts, tol: float,
                    max_iter: int, hard_wall: Callable[[], Solution]) -> Solution:
    """Wall + soft law: the active-set path, else the continuation path from ``hard_wall()``
    (a callable, so that the hard-wall solution is computed only when needed)."""
    if prob.options.wall_soft_active_set:
        fast = _active_set_path(prob, law, parts.soft, tol, max_iter)
        if fast is not None:
            return fast
    return _continuation(prob, law, parts, tol, max_iter, hard_wall())
