r"""Newton's method for a local interaction law ``σ = f(u)`` (paper eq. 24).

*Newton* on ``r(σ, ū) = σ − f(ū + Mσ − z)`` with the mean pressure imposed exactly. The Newton
system ``(I + D M) δσ + D δū = −r`` (``D = diag k``, ``k = −f'``) is multiplied by
``D⁻¹ = diag c`` on the points where the law is stiff, which turns it into the contact-set form
of :mod:`~rubbercontact.halfspace.contact_set` (so the same preconditioner applies); where ``k``
is negligible the update is explicit (``δσ = f(u) − σ``). Inexact Newton: GMRES to
``0.1 √(|r|/|σ|)`` (capped at 1e-2; fewer GMRES iterations than ``1e-3 |r|/|σ|`` for the same
Newton steps). Backtracking (Armijo) line search on ``|W r|₂`` with ``W = 1/(k + 1/m_d)``
(``m_d`` the diagonal of ``M``), i.e. the residual converted to a displacement, frozen during
the search so the Newton direction is a descent direction. Initial guess for a single law: the
exact hard-wall solution, with ``ū`` shifted so that ``<f(u)> = σ0``; without it Newton on the
``u⁻⁹`` wall of the Lennard-Jones law overshoots into huge pressures and stalls (observed, even
with continuation in the wall stiffness). Converged when ``|r|₂/|σ|₂ <= tol``.

*Mixed Newton for the Lennard-Jones wall alone* (``options.mixed_newton``). Linearising the
steep ``f`` at the current ``u`` moves a point by at most ``u/9`` per step when ``u`` is too
small (``f`` convex), and the points just outside the hard-wall contact, which carry a small
pressure with the law, took many Newton steps to settle. Every row ``σ_i = f(u_i)`` may be
linearised at any point of the curve ``σ = f(u)`` (the iteration is still Newton's once the
state is consistent): where ``σ_i`` or ``f(u_i)`` is in the contact range (above ``f(2ℓ)``) the
tangent is taken at the geometric mean ``σ̃ = √(σ_i f(u_i))`` (both clipped below at
``f(2ℓ)``) of the inverse law ``u = g(σ) = ℓ (p_ref/σ)^(1/9)``; this gives the same linear
system with ``c = −g'(σ̃)`` and right-hand side ``g(σ̃) − c (σ − σ̃) − u``. The tangent at
``σ_i`` alone (pure inverse form) converges as slowly from the other side (points whose pressure
is too small); the geometric mean was the best of those tried. GMRES forcing ``0.3 |r|/|σ|``
(capped at 1e-2). Same line search and stopping test; if it fails, the plain Newton runs from
the same start (never observed). μ, contact fraction and ``ū`` agree with the plain Newton
(tested); steps, GMRES iterations and timings are measured in ``benchmarks/halfspace.md``.
"""

from __future__ import annotations

from dataclasses import replace
from functools import partial

import numpy as np
from scipy.optimize import brentq

from .contact_set import contact_solve, shifted_preconditioner
from .inverse import InverseWall
from .laws import InteractionLaw
from .problem import Problem, Solution

__all__ = ["InverseWall", "newton_from", "newton_law", "shift_for_law", "solve_single_law"]


def shift_for_law(law: InteractionLaw, u: np.ndarray, sigma0: float,
                  guess: float | None = None) -> float:
    """Scalar ``s`` with ``<f(u + s)> = σ0`` (bracketed root; ``f`` non-increasing).

    ``guess``: a shift near the root (the start state's ``ū``): the bracket then grows from
    ``guess ± 1e-6 span`` by factors of 8 (one pass per growth) instead of starting from
    ``±span``, ``span`` the range of ``u``; Brent's method then starts close to the root.
    The tolerance is the same either way (``1e-12 span``). Each shift is evaluated once
    (a pass of the law over the grid; the bracket's ends were passed again to Brent's
    method: 18 passes instead of 14 on the 1024² map of ``benchmarks/maps.md``).
    """
    seen: dict[float, float] = {}

    def mean_p(s):
        if s not in seen:
            seen[s] = float(np.mean(law.pressure(u + s)))
        return seen[s]
    span = float(np.ptp(u)) + 1e-12
    if guess is not None and np.isfinite(guess):
        lo, hi = _bracket_near(mean_p, sigma0, float(guess), span)
    else:
        lo, hi = -span, span
    p_lo = mean_p(lo)
    while p_lo < sigma0 and lo >= -1e6 * span:
        lo -= 2 * (hi - lo)
        p_lo = mean_p(lo)
    p_hi = mean_p(hi)
    while p_hi > sigma0 and hi <= 1e6 * span:
        hi += 2 * (hi - lo)
        p_hi = mean_p(hi)
    if p_lo < sigma0:
        return lo    # not bracketed within 1e6 spans: start from the end nearest the root
    if p_hi > sigma0:
        return hi
    # Brent's method on log <f>: each evaluation is a pass over the grid, and a wall's
    # power law is nearly linear in log, where bisection would halve the bracket per pass
    log_s0 = np.log(sigma0)
    return float(brentq(lambda s: np.log(max(mean_p(s), 1e-300)) - log_s0, lo, hi,
                        xtol=1e-12 * span, rtol=1e-12))


def _bracket_near(mean_p, sigma0: float, guess: float, span: float) -> tuple[float, float]:
    """``(lo, hi)`` around ``guess`` with ``<f> >= σ0`` at ``lo`` and ``<= σ0`` at ``hi``,
    grown by factors of 8 from ``1e-6 span`` (up to ``span``: then the caller widens it)."""
    d = 1e-6 * span
    p_g = mean_p(guess)
    if p_g >= sigma0:           # guess is on the low side of the root: search upwards
        lo, hi = guess, guess + d
        while mean_p(hi) > sigma0 and d < span:
            lo, d = hi, 8 * d
            hi = guess + d
        return lo, hi
    lo, hi = guess - d, guess
    while mean_p(lo) < sigma0 and d < span:
        hi, d = lo, 8 * d
        lo = guess - d
    return lo, hi


def _newton_rtol(tol: float, res: float, loose: bool = True, mixed: bool = False,
                 target: bool = False) -> float:
    """GMRES tolerance of a Newton step.

    ``loose``: ``0.1 √res`` capped at 1e-2 (inexact Newton, superlinear). Otherwise
    ``1e-3 res`` capped at 1e-3: the continuation fallback needs it (with the loose forcing a
    continuation stage was observed to stall). ``mixed`` (the inverse-law Newton, quadratic
    from its second step): ``0.3 res`` capped at 1e-2 (``0.1 √res`` stops one step short of
    ``tol``). Measured in ``benchmarks/halfspace.md``.

    ``target`` (maps, ``options.newton_forcing_target_2d``): the floor is ``0.01 tol/res``
    instead of ``tol``: the GMRES tolerance is relative to the step's residual, so a step
    from ``res`` near ``tol`` need not solve its system to ``tol`` itself. With the floor
    ``tol`` a last step from ``res = 3e-8`` (``tol`` 1e-8) solved its system to 1e-8: 83
    GMRES iterations where ~10 do (the 1024² linear-law case of ``benchmarks/maps.md``).
    A hundredth, not a tenth: the system's rows are scaled by ``c = 1/k``, so its residual
    understates that of ``σ − f(u)`` on the stiff rows (with ``0.1 tol/res`` a step from
    4e-5 ended at 1.4e-8 instead of 1.2e-9, and one more step was needed). The stopping
    test is unchanged.
    """
    floor = min(1e-2, 0.01 * tol / res) if target and res > 0 else tol
    if mixed:
        return min(1e-2, max(floor, 0.3 * res))
    if loose:
        return min(1e-2, max(floor, 0.1 * np.sqrt(res)))
    return min(1e-3, max(floor, 1e-3 * res))


def newton_law(prob: Problem, law: InteractionLaw, tol: float, max_iter: int,
               sigma: np.ndarray, ubar: float, loose: bool = True,
               inverse: InverseWall | None = None,
               soft: InteractionLaw | None = None) -> Solution:
    """Newton on ``σ = f(ū + Mσ − z)``, ``<σ> = σ0`` from ``(σ, ū)``; see the module docstring.

    ``inverse`` (the law's :meth:`~.laws.InteractionLaw.inverse`) switches the rows in the
    contact range to the inverse form ``u = g(σ)`` (mixed Newton): same linear system
    (``c = −g'(σ)``), but the nearly linear ``g`` is linearised instead of the steep ``f``.
    ``soft``: ``law`` is the wall of ``inverse`` plus this soft member ``f_s``; the wall's
    contact rows then read ``u = g(σ − f_s(u))`` (:func:`_wall_soft_rows`).
    """
    n = prob.size
    z = prob.z
    m_diag = prob.compliance_diagonal
    w = prob.displacement(sigma)
    u = ubar + w - z
    f, k_next = law.pressure_and_stiffness(u)
    r = sigma - f
    snorm = float(np.linalg.norm(sigma)) or 1.0
    rnorm = float(np.linalg.norm(r))
    history = [rnorm / snorm]
    lin_its = 0
    it = 0
    steps = []
    for it in range(1, max_iter + 1):
        if rnorm <= tol * snorm:
            it -= 1
            break
        # the stiffness at u, from the pass that computed f there (the full step's) if any
        k = law.stiffness(u) if k_next is None else k_next
        rhs_inv = None
        if inverse is not None and soft is not None:
            # the first step from the hard wall + soft law state: its pressure is close to
            # the answer, its separation (u = 0 on the wall contact) is not
            first = it == 1 and prob.options.wall_soft_first_tangent_2d
            inv, c_inv, rhs_inv = _wall_soft_rows(inverse, soft, sigma, f, u, first)
            k_inv = k.copy()
            k_inv[inv] = 1.0 / c_inv
        elif inverse is not None:
            # rows where σ or f(u) is in the contact range: tangent of g at σ̃ = max(σ, σ_c)
            s_c = inverse.threshold
            inv = np.maximum(sigma, f) > s_c
            s_lin = np.sqrt(np.maximum(sigma[inv], s_c) * np.maximum(f[inv], s_c))
            g_s = inverse.separation(s_lin)
            c_inv = inverse.compliance(s_lin, g_s)
            g_s = g_s - c_inv * (sigma[inv] - s_lin)
            k_inv = k.copy()
            k_inv[inv] = 1.0 / c_inv
        else:
            inv = None
            k_inv = k
        # points where the law is stiff enough to matter enter the linear system
        stiff = k_inv * m_diag > 1e-8
        if inv is not None:
            stiff |= inv
        idx = np.flatnonzero(stiff)
        free = ~stiff
        # k ≈ 0: explicit update (whole-grid passes, the same values and sums as masked ones)
        dsig = np.where(free, f - sigma, 0.0)
        total = prob.sigma0 * n - sigma.sum() - np.compress(free, dsig).sum()
        if _exact_load(prob) and abs(total) <= _LOAD_ROUNDOFF * prob.sigma0 * n:
            total = 0.0     # the load's round-off, not a correction (options.exact_load_2d)
        if idx.size:
            c = 1.0 / k_inv[idx]
            w_free = prob.displacement(dsig) if np.any(dsig) else np.zeros(n)  # 0 off free
            rhs = c * (f[idx] - sigma[idx])
            if inv is not None:
                # inverse rows: u + δu = g(σ) − c δσ  →  (M + c) δσ + δū = g(σ) − u
                rhs[inv[idx]] = g_s - u[inv] if rhs_inv is None else rhs_inv
            rhs -= w_free[idx]
            contact = c < m_diag
            precond = partial(shifted_preconditioner, prob, c, contact)   # if used
            lin = contact_solve(prob, idx, rhs, total, precond,
                                c=c, rtol=_newton_rtol(tol, rnorm / snorm, loose,
                                                       inverse is not None, _target(prob)),
                                extra_diag=~contact, multi_shift=_multi_shift(prob))
            lin_its += lin.iterations
            dsig[idx] = lin.x
            dubar = lin.multiplier
        else:
            dsig[free] += total / n
            dubar = 0.0
        # its own transform, not the solve's response (options.reuse_response_2d): on the
        # Lennard-Jones wall alone (512² map of benchmarks/maps.md) the summed one, 1e-23 mm
        # off, turned the first line search from t = 1 to 0.5, and 18 steps followed, not 5
        dw = prob.displacement(dsig)
        du = dubar + dw
        # merit: residual weighted to a displacement, W = 1/(k + 1/m_diag), frozen during the
        # line search so the Newton direction is a descent direction of |W r|
        wgt = 1.0 / (k + 1.0 / m_diag)
        phi0 = float(np.linalg.norm(wgt * r))
        t = 1.0
        for _ in range(40):
            s_t = _step(sigma, t, dsig)
            u_t = _step(u, t, du)
            if t == 1.0:
                f_t, k_next = law.pressure_and_stiffness(u_t)
            else:
                f_t, k_next = law.pressure(u_t), None
            r_t = s_t - f_t
            if float(np.linalg.norm(wgt * r_t)) <= (1 - 1e-4 * t) * phi0:
                break
            t *= 0.5
        else:
            break  # no decrease: stop, reported as not converged
        steps.append(t)
        rn_t = float(np.linalg.norm(r_t))
        sigma, ubar, u, w, f, r, rnorm = s_t, ubar + t * dubar, u_t, _step(w, t, dw), f_t, r_t, rn_t
        snorm = float(np.linalg.norm(sigma)) or 1.0
        history.append(rnorm / snorm)
    res = rnorm / snorm
    return Solution(sigma, u, w, ubar, it, res, res <= tol,
                    {"linear_iterations": lin_its, "history": history, "steps": steps})


def _step(x: np.ndarray, t: float, dx: np.ndarray) -> np.ndarray:
    """``x + t dx``; the full step (``t = 1``, nearly always taken) without the product,
    which is exact there: one whole-grid pass less."""
    return x + dx if t == 1.0 else x + t * dx


#: ``options.exact_load_2d``: a Newton step's load correction ``σ0 n − Σσ − Σ δσ_free`` of at
#: most this fraction of the load ``σ0 n`` is its round-off (an ulp of ``σ0 n`` is 1.1e-16
#: of it) and is dropped.
_LOAD_ROUNDOFF = 1e-13


def _exact_load(prob: Problem) -> bool:
    """Whether a Newton step drops a load correction at the load's round-off (maps,
    options)."""
    return len(prob.shape) == 2 and prob.options.exact_load_2d


def _target(prob: Problem) -> bool:
    """Whether the Newton forcing has the floor ``0.01 tol/res`` (maps, options)."""
    return len(prob.shape) == 2 and prob.options.newton_forcing_target_2d


def _multi_shift(prob: Problem) -> bool:
    """Whether the Newton systems use the multi-shift preconditioner (options)."""
    opts = prob.options
    return opts.multi_shift and (len(prob.shape) == 1 or opts.multi_shift_2d)


def _wall_soft_rows(inverse: InverseWall, soft: InteractionLaw, sigma: np.ndarray,
                    f: np.ndarray, u: np.ndarray, at_pressure: bool = False
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mixed-Newton rows of a wall + soft law ``f = f_w + f_s``: mask, ``c`` and right side.

    Rows where both the wall's share ``s = σ − f_s(u)`` and ``f_w(u)`` are in the contact
    range read ``u = g(σ − f_s(u))``, linearised at ``s̃ = √(s f_w(u))`` as for the wall
    alone: ``c_w δσ + (1 + c_w k_s) δu = G − u`` with ``G = g(s̃) − c_w (s − s̃)``,
    ``c_w = −g'(s̃)``, ``k_s = −f_s'(u)``; divided by ``1 + c_w k_s`` it is the contact-set
    row with ``c = c_w/(1 + c_w k_s)``. Both, not either as for the wall alone: from the hard
    wall + soft law state the points just off the wall contact carry the soft law's
    pressure, and taking them in made the line search damp the first four steps (measured:
    8 steps, against 4 with both and 10 for the plain Newton; ``benchmarks/maps.md``).

    ``at_pressure`` (the first step from the hard wall + soft law state,
    ``options.wall_soft_first_tangent_2d``): the tangent at ``s̃ = s`` instead. That state's
    wall share ``s`` is close to the answer while ``f_w(u)`` is nearly the same on every
    contact point (``u = 0`` there, shifted by ``ū``; on the 1024² linear-law case of
    ``benchmarks/maps.md`` ``s`` spans 2.5–10 MPa and ``f_w`` 1.96–2.15): the first step
    then takes the residual from 0.34 to 0.025–0.035 instead of 0.12, and the Newton ends
    in 4 steps instead of 5 (130 instead of 144 GMRES iterations). Later steps keep the
    geometric mean: with the tangent at ``s`` throughout the residual stalled at 1.5e-8
    (512²).
    """
    f_s = soft.pressure(u)
    s_w, f_w = sigma - f_s, f - f_s
    s_c = inverse.threshold
    inv = np.minimum(s_w, f_w) > s_c
    s_lin = s_w[inv] if at_pressure else np.sqrt(s_w[inv] * f_w[inv])
    g_s = inverse.separation(s_lin)
    c_w = inverse.compliance(s_lin, g_s)
    g_s = g_s - c_w * (s_w[inv] - s_lin)
    scale = 1.0 + c_w * soft.stiffness(u[inv])
    return inv, c_w / scale, (g_s - u[inv]) / scale


def newton_from(prob: Problem, law: InteractionLaw, start: Solution, tol: float,
                max_iter: int, loose: bool, mixed: bool) -> Solution:
    """Newton on ``law`` from the pressure of ``start``, ``ū`` shifted so ``<f(u)> = σ0``.

    ``mixed``: the inverse-law rows for a Lennard-Jones wall (no effect for other laws).
    """
    shift = shift_for_law(law, start.w - prob.z, prob.sigma0, guess=start.ubar)
    return newton_law(prob, law, tol, max_iter, start.sigma, shift, loose=loose,
                      inverse=law.inverse() if mixed else None)


def solve_single_law(prob: Problem, law: InteractionLaw, tol: float, max_iter: int,
                     hard_wall: Solution) -> Solution:
    """A law without a wall + soft split: Newton from the hard-wall solution.

    For a Lennard-Jones wall the mixed Newton (if the options allow it), with the plain Newton
    from the same start as a safety net.
    """
    mixed = prob.options.mixed_newton
    out = newton_from(prob, law, hard_wall, tol, max_iter, loose=True, mixed=mixed)
    if not out.converged and mixed and law.inverse() is not None:
        # safety net (not observed): the plain Newton from the same hard-wall start
        failed = out
        out = newton_from(prob, law, hard_wall, tol, max_iter, loose=True, mixed=False)
        out = replace(out, iterations=out.iterations + failed.iterations,
                      info={**out.info, "mixed_newton_failed": {
                          "iterations": failed.iterations, "residual": failed.residual}})
    return replace(out, info={**out.info, "continuation": [1.0]})
