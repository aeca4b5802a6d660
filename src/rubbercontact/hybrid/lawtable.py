"""A law table screened and read per speed, as the half-space solver applies it.

:func:`screen_impaled` excludes the FEM points whose rubber face was impaled,
:func:`screen_monotone` the FEM points that break the law's monotonicity,
:func:`law_at_velocity` gives the law at one speed as plain data (with the zero-load
anchor at :func:`max_height`), :func:`tabulated_law_from_dict` turns that into the
solver's :class:`~rubbercontact.halfspace.TabulatedLaw`, and :func:`check_coverage` warns
when the low-slope solve loaded the law beyond its FEM points.
"""

from __future__ import annotations

import warnings

import numpy as np
import xarray as xr

from ..errors import InputError
from ..roughness import SineSeries


class LawWarning(UserWarning):
    """The law table has failed, unsteady, impaled or non-monotone points, or is being
    extrapolated."""


#: Status of a law point whose FEM test reported an impaled face (:func:`screen_impaled`).
IMPALED_STATUS = ("excluded: impaled (the surface passes through the rubber face between "
                  "nodes; its friction and contact fraction are not meaningful)")

#: Status of a law grid point that was not computed (a run's speed did not need the
#: pressure, or its path stopped before it: the run's coverage line says why).
NOT_COMPUTED = "not computed"


def max_height(surface: SineSeries, n: int = 8192) -> float:
    """Highest point of ``surface`` [mm] (a sampled maximum refined by the exact slope root)."""
    from scipy.optimize import brentq

    if surface.size == 0:
        return 0.0
    x, z = surface.grid(n)
    k = int(np.argmax(z))
    dx = x[1] - x[0]
    a, b = x[k] - dx, x[k] + dx
    if surface.slopes(a) > 0 > surface.slopes(b):
        return float(surface.heights(brentq(surface.slopes, a, b, xtol=1e-14)))
    return float(z[k])


def screen_impaled(law: xr.Dataset, stacklevel: int = 2) -> xr.Dataset:
    """Exclude the FEM points whose rubber face was impaled, and say which.

    An impaled face (:attr:`rubbercontact.fem.SolverStats.impaled`: an asperity passed
    through it between two nodes) keeps the status ``"ok"`` in the FEM result, but its
    friction and contact fraction are not meaningful, so it must not enter the law. Each
    such point that is still ``"ok"`` gets the status :data:`IMPALED_STATUS` (which every
    reader of the law skips, as the failed and non-monotone points) and keeps its numbers
    and its ``impaled`` flag in the table; one :class:`LawWarning` names them.

    Parameters
    ----------
    law
        Law table (dims ``velocity, pressure``). FEM results cached before the flag
        existed have no ``impaled`` value; of those, a point with a contact fraction above
        1 (the old count on a folded face) is excluded too.
    stacklevel
        Of the warning, as for :func:`warnings.warn`.

    Returns
    -------
    xarray.Dataset
        ``law``, a copy with the updated ``status`` when a point was excluded.
    """
    status = law["status"].values.astype(object)
    # A contact fraction above 1 is what the count before f64f81b gave on a folded
    # (impaled) face; such a result, cached before the flag existed, is caught by it.
    flagged = law["impaled"].values == 1 if "impaled" in law else np.zeros(status.shape, bool)
    hit = (flagged | (law["contact_fraction"].values > 1.0)) & (status == "ok")
    if not hit.any():
        return law
    law = law.copy(deep=True)
    status[hit] = IMPALED_STATUS
    law["status"] = (law["status"].dims, status.astype(str))
    v, p = law["velocity"].values, law["pressure"].values
    where = "; ".join(f"p={p[j]:g} MPa, v={v[i]:g} mm/s" for i, j in np.argwhere(hit))
    warnings.warn(f"law: FEM point(s) {where} dropped from the law: the rubber face is "
                  f"impaled there, so friction and contact fraction are not meaningful (kept "
                  f"in the table, status 'excluded: impaled'); refine the cell (fem.mesh) or "
                  f"lower the load (law.pressures)", LawWarning, stacklevel=stacklevel + 1)
    return law


def screen_monotone(law: xr.Dataset) -> xr.Dataset:
    """Exclude the FEM points that break the law's monotonicity, and say which.

    Physically ``ū`` decreases strictly as ``p̄`` grows. Per speed, among the successful
    points ordered by pressure, the largest subset with strictly decreasing ``ū`` is
    kept (ties: the subset with the lower pressures, where the FEM is most reliable);
    every other point keeps its numbers in the table but gets the status
    ``"excluded: non-monotone ..."`` and is named in a :class:`LawWarning`. Typical
    cause: mean pressures near or beyond the rubber's equilibrium modulus, where the
    friction stress ``μp̄`` shears the cell as a whole by ``3μp̄/E∞`` of order 1 and that
    finite shear lifts the face off, so that the settled ``ū`` rises with ``p̄``
    (docs/validation/fem_steadiness.md, docs/validation/material_model.md).

    Returns a copy of ``law`` with the updated ``status``.
    """
    law = law.copy(deep=True)
    status = law["status"].values.astype(object)
    pressures = law["pressure"].values
    order = np.argsort(pressures)
    excluded = []                                 # (speed, [pressures]) per speed with drops
    for iv, v in enumerate(law["velocity"].values):
        u = law["mean_separation"].values[iv]
        idx = [j for j in order if status[iv, j] == "ok" and np.isfinite(u[j])]
        keep = _longest_decreasing(u[idx])
        dropped = [j for k, j in enumerate(idx) if k not in keep]
        for j in dropped:
            status[iv, j] = (f"excluded: non-monotone (u = {u[j]:.6g} mm at p = "
                             f"{pressures[j]:g} MPa breaks the decrease of u with p)")
        if dropped:
            excluded.append((float(v), [float(pressures[j]) for j in dropped]))
    if excluded:
        # one warning for the whole table: a speed sweep would otherwise print one per speed
        where = "; ".join(f"v={v:g} mm/s: p={ps}" for v, ps in excluded)
        warnings.warn(
            f"law: {sum(len(ps) for _, ps in excluded)} FEM points excluded, their mean "
            f"separation breaks the strict decrease of u with p ({where} MPa; near the "
            f"equilibrium modulus the sheared cell's face lifts off; the law's 'status' "
            f"names each, see screen_monotone)", LawWarning, stacklevel=2)
    law["status"] = (law["status"].dims, status.astype(str))
    return law


def _longest_decreasing(values: np.ndarray) -> set[int]:
    """Indices of the longest strictly decreasing subsequence, preferring early entries."""
    n = len(values)
    length, prev = [1] * n, [-1] * n
    for i in range(n):
        for j in range(i):
            if values[j] > values[i] and length[j] + 1 > length[i]:
                length[i], prev[i] = length[j] + 1, j
    if n == 0:
        return set()
    # the first index reaching the maximal length ends the subsequence with the lowest loads
    i = int(np.argmax(length))
    out = set()
    while i >= 0:
        out.add(i)
        i = prev[i]
    return out


def law_at_velocity(law: xr.Dataset, velocity: float) -> dict:
    """The law at one speed as plain data: ``u`` [mm] ascending, ``sigma``, ``alpha``, ``tau``.

    Failed FEM points are dropped and reported (:class:`LawWarning`); the zero-load
    anchor ``(ū = max z_hs, σ = α = Δτ = 0)`` is added — at vanishing load the rubber
    touches only the highest peak, so its mean height equals that peak's height.
    A table that is still not monotone (pressure not decreasing with ``ū``; run
    :func:`screen_monotone` first to exclude such points explicitly) is an error: the FEM
    points disagree with each other and must be inspected, not smoothed.
    """
    speeds = law["velocity"].values
    match = np.flatnonzero(np.isclose(speeds, velocity, rtol=1e-9, atol=1e-12))
    if match.size == 0:
        raise InputError(f"velocity: {velocity} mm/s is not in the law table "
                         f"(available: {speeds.tolist()} mm/s)")
    row = law.isel(velocity=int(match[0]))
    status = row["status"].values.astype(str)
    ok = (status == "ok") & np.isfinite(row["mean_separation"].values)
    # excluded points were named by screen_impaled or screen_monotone already, and the
    # points a run did not compute by the run's coverage line
    failed = ~ok & ~np.char.startswith(status, "excluded") & (status != NOT_COMPUTED)
    if failed.any():
        bad = row["pressure"].values[failed].tolist()
        warnings.warn(f"law at v={velocity} mm/s: FEM points at p={bad} MPa failed and are "
                      f"left out", LawWarning, stacklevel=2)
    if ok.sum() < 2:
        raise InputError(f"law at v={velocity} mm/s: fewer than 2 successful FEM points")
    u = row["mean_separation"].values[ok]
    sigma = row["pressure"].values[ok]
    alpha = row["contact_fraction"].values[ok]
    tau = row["shear_stress"].values[ok]
    order = np.argsort(u)
    u, sigma, alpha, tau = u[order], sigma[order], alpha[order], tau[order]
    if np.any(np.diff(sigma) >= 0):
        raise InputError(f"law at v={velocity} mm/s: pressure does not decrease with mean "
                         f"separation (u={u.tolist()} mm, p={sigma.tolist()} MPa); the FEM "
                         f"points are inconsistent (check convergence and averaging)")
    u0 = float(law.attrs["hs_max_height_mm"])
    if u0 > u[-1]:
        u = np.append(u, u0)
        sigma, alpha, tau = (np.append(a, 0.0) for a in (sigma, alpha, tau))
    return {"separation": u.tolist(), "pressure": sigma.tolist(),
            "contact_fraction": alpha.tolist(), "shear_stress": tau.tolist()}


def tabulated_law_from_dict(table: dict):
    """Build the half-space solver's tabulated law from :func:`law_at_velocity` output."""
    from ..halfspace import TabulatedLaw

    return TabulatedLaw(np.asarray(table["separation"]), np.asarray(table["pressure"]),
                        contact_fraction=np.asarray(table["contact_fraction"]),
                        shear_stress=np.asarray(table["shear_stress"]))


def law_top(law: xr.Dataset, velocity: float) -> float:
    """Highest pressure [MPa] of the law's successful FEM points at ``velocity`` (0 if none)."""
    row = law.sel(velocity=velocity, method="nearest")
    ok = row["status"].values == "ok"
    return float(row["pressure"].values[ok].max()) if ok.any() else 0.0


def check_coverage(law: xr.Dataset, reached: dict[float, float]) -> None:
    """Warn once when the low-slope solve reached pressures beyond the law's successful
    FEM range: ``reached`` maps each speed [mm/s] to the highest local pressure [MPa]."""
    tops = {v: law_top(law, v) for v in reached}
    over = {v: (p, tops[v]) for v, p in reached.items() if p > tops[v]}
    if not over:
        return
    vs = sorted(over)
    where = (f"v={vs[0]:g} mm/s" if len(vs) == 1 else
             f"{len(vs)} of {len(reached)} speeds ({vs[0]:.3g} … {vs[-1]:.3g} mm/s)")
    top = max(p for p, _ in over.values())
    ends = sorted({t for _, t in over.values()})
    end_text = f"{ends[0]:.3g}" if len(ends) == 1 else f"{ends[0]:.3g}–{ends[-1]:.3g}"
    warnings.warn(f"law at {where} is extrapolated: local low-slope pressure reaches "
                  f"{top:.3g} MPa, the FEM table ends at {end_text} MPa (beyond, the law "
                  f"follows the linear law's shape anchored at the last FEM point); add "
                  f"higher law pressures", LawWarning, stacklevel=2)
