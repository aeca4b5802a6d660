r"""Hard-wall contact: ``u >= 0``, ``σ >= 0``, ``u σ = 0`` with ``<σ> = σ0`` imposed.

*Active set* (``method="active-set"``, the default for an elastic material): primal–dual
active-set (semismooth Newton) iteration on the complementarity problem. Given the set ``A``:
solve ``u_A = 0``, ``σ = 0`` off ``A``, ``<σ> = σ0``
(:func:`~rubbercontact.halfspace.contact_set.contact_solve`); then
``A ← {σ > 0 on A} ∪ {u < −ε off A}`` (``ε = 1e-12 max|z|``). Stops when ``A`` no longer
changes; the result then satisfies ``σ >= 0``, ``u >= −ε`` and ``σ u = 0`` up to the linear
tolerance. Start: the contact set of a Winkler foundation ``σ = k_W (z − h)₊`` with the
spectrum-weighted half-space stiffness ``k_W`` (:func:`winkler_guess`).

*Viscoelastic* (the default when ``M`` is complex): the active-set iteration alone can cycle
for the non-symmetric operator (observed). Globally convergent outer loop: the projection
method for the variational inequality in the metric of the Hermitian part ``M_s = Re M``,
``σ_{k+1} = argmin_{σ >= 0, <σ> = σ0} ½ σ·M_s σ − σ·(M_s σ_k + γ (z − M σ_k))``, each step a
symmetric contact problem solved by the warm-started active-set method. With
``θ = max_q |Im M|/Re M = max tan δ`` and ``γ = 1/(1 + θ²)`` the map contracts at rate
``θ/√(1 + θ²) < 1`` in the ``M_s`` norm whatever the contact set (``M`` strongly monotone with
modulus 1 and Lipschitz constant ``√(1 + θ²)`` in that norm). Once the pressure changes by less
than 10 % (then 3 %, 1 %, ...) per step, the active-set iteration on the full operator is tried
(at most 5 updates) from the current set; it then converges in a few updates and gives exact
complementarity. Each projection step is itself inexact: a single active-set update (one
contact-set linear solve) of the symmetric subproblem, warm-started; a fixed point of this
fused iteration has ``u = 0`` on the set and ``u >= 0`` off it for the full operator. Anderson
acceleration of the projection map was tried and was slower (the map is only piecewise smooth).

*Viscoelastic, coarse-grid start* (1D, ``N`` divisible by 4 and at least four times
``options.coarse_min_points``; maps of even sides at least twice
``options.coarse_min_side_2d``, on every 2nd point per axis): the problem is first solved
exactly on the coarse grid (same
period, the same ``M(q)`` on the coarser rfft grid; recursively, the coarsest level by the
projection method, with dense linear solves on at most ``options.dense_max_points`` points),
the pressure interpolated (periodic, linear or bilinear) and polished by at most
``options.coarse_polish_updates`` active-set updates on the full operator, which converge
because the set is right up to a few points per contact edge; up to 4× more while each
update changes at most 4 points and no set repeats (an unresolved odd–even leading edge
moving 2 points per update: :func:`_polish`). Result: the same exact
complementarity solution (tested against the fine-grid projection method: same contact
set, μ, area and ``ū``). If the polish fails, the projection method runs on that grid.
``matvecs`` then counts FFT pairs on all grids. Update counts and timings are measured in
``benchmarks/halfspace.md``.

*Polonsky–Keer* (``method="pk"``, elastic only): the classic constrained conjugate gradient of
Polonsky & Keer (Wear 231, 1999) with the mean-pressure constraint, stopping when the relative
l1 change of the pressure in one iteration falls below ``tol``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from . import kernels as kn
from .contact_set import contact_solve
from .problem import Problem, Solution

__all__ = ["hard_wall_active_set", "hard_wall_elastic", "hard_wall_pk", "hard_wall_projection",
           "hard_wall_viscoelastic", "winkler_guess"]

_SET_EPS = 1e-12


def winkler_guess(prob: Problem, z: np.ndarray) -> np.ndarray:
    """Initial pressure from a Winkler foundation ``σ = k_W (z − h)₊`` with ``<σ> = σ0``.

    ``k_W = Σ|z_q|² / Σ|z_q|² Re M(q)``: the half-space stiffness seen by the roughness
    spectrum. Gives the active-set iteration a contact set of about the right size, instead of
    shrinking from full contact by a boundary layer per update.
    """
    spec = np.abs(kn.forward(z.reshape(prob.shape))) ** 2
    weight = float(np.sum(spec * np.real(prob.compliance)))
    if weight <= 0:
        return np.full(prob.size, prob.sigma0)
    k_w = float(np.sum(spec)) / weight
    zs = np.sort(z)[::-1]
    # mean of k_W (z − h)₊ with h between consecutive sorted heights: pick the first h that
    # reaches σ0 (cumulative sums), then solve the linear piece exactly
    csum = np.cumsum(zs)
    m = np.arange(1, zs.size + 1)
    mean_p = k_w * (csum - m * zs) / zs.size  # σ mean when h = zs[m-1]
    j = int(np.searchsorted(mean_p, prob.sigma0))
    if j >= zs.size:
        return np.full(prob.size, prob.sigma0)  # full contact
    m_act = j if j > 0 else 1
    h = (csum[m_act - 1] - prob.sigma0 * zs.size / k_w) / m_act
    sigma = k_w * np.maximum(z - h, 0.0)
    total = sigma.sum()
    return sigma * (prob.sigma0 * prob.size / total) if total > 0 else np.full(prob.size,
                                                                               prob.sigma0)


def hard_wall_active_set(prob: Problem, tol: float, max_iter: int,
                         sigma_init: np.ndarray | None = None, z: np.ndarray | None = None,
                         active_init: np.ndarray | None = None) -> Solution:
    """Primal–dual active-set iteration (module docstring) against the heights ``z``.

    Starts from the Winkler guess, or from ``sigma_init`` with the set ``active_init``
    (default ``σ > 0``). ``info["active"]`` is the final set.
    """
    n = prob.size
    z = prob.z if z is None else z
    k_pre = prob.preconditioner()
    zscale = float(np.abs(z).max()) or 1.0
    eps = _SET_EPS * zscale
    eps_p = _SET_EPS * prob.sigma0
    if sigma_init is None:
        sigma = winkler_guess(prob, z)
        active = sigma > 0
    else:
        sigma = sigma_init.copy()
        active = sigma > 0 if active_init is None else active_init.copy()
    history = []
    lin_its = 0
    u = w = None
    ubar = 0.0
    for it in range(1, max_iter + 1):
        idx = np.flatnonzero(active)
        if idx.size == 0:
            active[np.argmax(z)] = True
            idx = np.flatnonzero(active)
        lin = contact_solve(prob, idx, z[idx], prob.sigma0 * n, k_pre, x0=sigma[idx],
                            rtol=min(tol, 1e-8))
        ubar = lin.multiplier
        lin_its += lin.iterations
        sigma = np.zeros(n)
        sigma[idx] = lin.x
        w = prob.displacement(sigma)
        u = ubar + w - z
        new = (active & (sigma > -eps_p)) | (~active & (u < -eps))
        changed = int(np.count_nonzero(new != active))
        history.append((idx.size, changed, lin.iterations, lin.residual))
        if changed == 0:
            res = max(lin.residual,
                      float(np.abs(u[active]).max()) / zscale if idx.size else 0.0)
            return Solution(sigma, u, w, ubar, it, res, True,
                            {"linear_iterations": lin_its, "history": history, "active": new})
        active = new
    return Solution(sigma, u, w, ubar, max_iter, float("nan"), False,
                    {"linear_iterations": lin_its, "history": history, "active": active})


def hard_wall_elastic(prob: Problem, tol: float, max_iter: int) -> Solution:
    """Elastic active set; on a map started from the solution on the coarse grid.

    A map that can be coarsened (:meth:`~.problem.Problem.can_coarsen` with
    ``options.coarse_min_points``) is first solved on every 2nd point per axis
    (recursively); the interpolated pressure and its support start the active set, which
    then needs fewer updates on the fine grid than from the Winkler guess (the coarse grid
    misses the finest asperities, so the set still changes by thousands of points at first;
    starting from the set where the interpolated state penetrates instead was no better,
    measured). 1D grids: the active set from the Winkler guess, as before.
    """
    if len(prob.shape) == 2 and prob.can_coarsen(prob.options.coarse_min_points):
        coarse = prob.coarse()
        out_c = hard_wall_elastic(coarse, tol, max_iter)
        prob.matvecs += coarse.matvecs
        if out_c.converged:
            out = hard_wall_active_set(prob, tol, max_iter, sigma_init=prob.refine(out_c.sigma))
            info = {**out.info, "coarse_levels": out_c.info.get("coarse_levels", 0) + 1,
                    "fine_iterations": out.iterations}
            return replace(out, iterations=out.iterations + out_c.iterations, info=info)
    return hard_wall_active_set(prob, tol, max_iter)


def hard_wall_projection(prob: Problem, tol: float, max_iter: int,
                         polish: bool = True) -> Solution:
    """Exact hard-wall solution for the non-symmetric (viscoelastic) operator.

    Projection method in the metric of the Hermitian part ``M_s = Re M`` (module docstring),
    each step one warm-started active-set update of the symmetric subproblem; when it has
    (nearly) converged, a few active-set iterations on the full operator polish the
    complementarity.
    """
    comp = prob.compliance
    ms = np.real(comp)
    nz = ms > 0
    theta = float(np.max(np.abs(np.imag(comp[nz])) / ms[nz])) if nz.any() else 0.0
    gamma = 1.0 / (1.0 + theta**2)
    sym = prob.with_compliance(ms)
    comb = ms - gamma * comp  # kernel of M_s − γ M
    out = hard_wall_active_set(sym, tol, max_iter)
    sigma = out.sigma
    hist = []
    inner = out.iterations
    ok = False
    diff = np.inf
    it = 0
    next_try = 1e-1
    info = {"theta": theta, "gamma": gamma}
    active = out.info["active"]
    polish_mv = 0
    for it in range(1, 50 * max_iter + 1):
        # one active-set update of the projection subproblem per step (inexact projection):
        # the fixed point has u = 0 on the set and u >= 0 off it for the full operator M;
        # the linear tolerance follows the progress of the outer iteration
        z_eff = gamma * prob.z + sym.apply(comb, sigma)
        lin_tol = max(min(tol, 1e-10), min(1e-3, 1e-2 * diff))
        out = hard_wall_active_set(sym, lin_tol, 1, sigma_init=sigma, z=z_eff,
                                   active_init=active)
        inner += 1
        active = out.info["active"]
        diff = float(np.linalg.norm(out.sigma - sigma) / np.linalg.norm(out.sigma))
        sigma = out.sigma
        hist.append(diff)
        if polish and (diff < next_try or diff < tol):
            # close enough for the active set to be (nearly) right: try exact polishing
            next_try *= 0.3
            before = prob.matvecs
            pol = hard_wall_active_set(prob, tol, 5, sigma_init=np.maximum(sigma, 0.0),
                                       active_init=active)
            polish_mv += prob.matvecs - before
            if pol.converged:
                prob.matvecs += sym.matvecs
                info.update(projection_iterations=it, inner_active_set_iterations=inner,
                            history=hist, polish_iterations=pol.iterations,
                            polish_matvecs=polish_mv)
                return replace(pol, iterations=it, info=info)
        if diff < tol:
            ok = True
            break
    prob.matvecs += sym.matvecs
    info.update(projection_iterations=it, inner_active_set_iterations=inner, history=hist)
    w = prob.displacement(sigma)
    u0 = w - prob.z
    ubar = -float(u0[sigma > 0].mean())
    return Solution(sigma, ubar + u0, w, ubar, it, diff, ok, info)


def hard_wall_viscoelastic(prob: Problem, tol: float, max_iter: int,
                           start: np.ndarray | None = None) -> Solution:
    """Exact viscoelastic hard wall, started from the solution on a 4× coarser grid.

    With ``start`` (a pressure on this grid, e.g. a nearby speed's solution) the same
    polish is tried from it first (``info["warm_start"]``); if it does not converge, the
    usual path runs.

    The coarse solution (recursively, down to ``options.coarse_min_points``) is interpolated
    to the grid and polished by ``options.coarse_polish_updates`` active-set updates
    (extended while a contact edge still advances, :func:`_polish`) on the full operator
    (exact complementarity, as the polishing step of :func:`hard_wall_projection`). If the
    polish does not converge, or the grid is not coarsened, the projection method runs on
    this grid.
    """
    opts = prob.options
    if start is not None:
        pol = _polish(prob, tol, start, opts.coarse_polish_updates)
        if pol.converged:
            return replace(pol, info={**pol.info, "warm_start": True})
    if prob.can_coarsen(opts.coarse_min_points):
        coarse = prob.coarse()
        out_c = hard_wall_viscoelastic(coarse, tol, max_iter)
        prob.matvecs += coarse.matvecs
        if out_c.converged:
            pol = _polish(prob, tol, prob.refine(out_c.sigma), opts.coarse_polish_updates)
            if pol.converged:
                info = {"coarse_levels": out_c.info.get("coarse_levels", 0) + 1,
                        "polish_iterations": pol.iterations, "coarse_info": out_c.info}
                return replace(pol, iterations=pol.iterations + out_c.iterations, info=info)
    return hard_wall_projection(prob, tol, max_iter)


#: A polish still moving a contact edge (at most this many points changed per update) may
#: take up to this many times ``options.coarse_polish_updates`` updates in all.
_FRONT_CHANGES = 4
_FRONT_BUDGET = 4


def _polish(prob: Problem, tol: float, sigma: np.ndarray, budget: int) -> Solution:
    """Active-set polish of an interpolated coarse-grid pressure, extended while it advances.

    An unresolved leading edge (odd–even pressure, module docstring of
    :mod:`~rubbercontact.halfspace.solver`) can need one update per pair of grid points it
    moves: the set then changes by a couple of points per update and never repeats
    (observed: benchmarks/bench_flash.py's profile at 14.552 mm/s, 23 updates, 12 of them
    moving one edge by 2 points). Restarting the
    projection method on the fine grid costs ~6× more matvecs, so after ``budget`` updates
    the same iteration continues one update at a time while each update changes at most
    ``_FRONT_CHANGES`` points and revisits no set (a cycle), up to ``_FRONT_BUDGET × budget``.
    """
    pol = hard_wall_active_set(prob, tol, budget, sigma_init=sigma)
    seen: set[bytes] = set()
    history = list(pol.info["history"])
    lin_its = pol.info["linear_iterations"]
    its = pol.iterations
    while (not pol.converged and its < _FRONT_BUDGET * budget
           and history[-1][1] <= _FRONT_CHANGES):
        key = np.packbits(pol.info["active"]).tobytes()
        if key in seen:
            break  # a cycle: leave it to the projection method
        seen.add(key)
        pol = hard_wall_active_set(prob, tol, 1, sigma_init=pol.sigma,
                                   active_init=pol.info["active"])
        history += pol.info["history"]
        lin_its += pol.info["linear_iterations"]
        its += 1
    info = {**pol.info, "history": history, "linear_iterations": lin_its}
    return replace(pol, iterations=its, info=info)


def hard_wall_pk(prob: Problem, tol: float, max_iter: int) -> Solution:
    """Polonsky & Keer (1999) constrained conjugate gradient, elastic (symmetric) operator."""
    n = prob.size
    z = prob.z
    kern = prob.compliance
    total = prob.sigma0 * n
    p = np.full(n, prob.sigma0)
    t = np.zeros(n)
    delta = 0.0
    g_old = 1.0
    err = np.inf
    it = 0
    while it < max_iter:
        it += 1
        gap = prob.apply(kern, p) - z
        s = p > 0
        gap -= gap[s].mean()
        gs = gap[s]
        g_norm = float(gs @ gs)
        t[s] = gs + (delta * g_norm / g_old) * t[s]
        t[~s] = 0.0
        g_old = g_norm
        r = prob.apply(kern, t)
        r -= r[s].mean()
        denom = float(r[s] @ t[s])
        tau = float(gs @ t[s]) / denom if denom != 0 else 0.0
        p_old = p.copy()
        p[s] -= tau * t[s]
        np.maximum(p, 0.0, out=p)
        overlap = (p == 0) & (gap < 0)
        if overlap.any():
            delta = 0.0
            p[overlap] -= tau * gap[overlap]
        else:
            delta = 1.0
        p *= total / p.sum()
        err = float(np.abs(p - p_old).sum() / total)
        if err < tol:
            break
    w = prob.apply(kern, p)
    u0 = w - z
    s = p > 0
    ubar = -float(u0[s].mean()) if s.any() else 0.0
    return Solution(p, ubar + u0, w, ubar, it, err, err < tol, {})
