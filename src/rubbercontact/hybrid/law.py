"""The effective interface law of the high-slope scale (paper eqs. 1–3).

FEM sliding tests on the high-slope surface ``z_hs`` over a grid of mean pressures
``p̄`` and speeds ``v`` give, per test, the mean separation ``ū``, the contact
fraction ``α_hs`` and the viscoelastic shear stress ``Δτ_hs = μ_hs p̄``. Read at a
fixed speed as functions of ``ū`` they are the law ``σ_hs(ū)``, ``α_hs(ū)``,
``Δτ_hs(ū)`` that the half-space solver applies locally to the low-slope scale.

The law table is an ``xarray.Dataset`` (dims ``velocity``, ``pressure``). Computing it
is the expensive part of the method; once saved it serves any surface that shares
the same high-slope scale and material.
"""

from __future__ import annotations

import json
import warnings
from collections.abc import Sequence

import numpy as np
import xarray as xr

from .._validation import finite_array
from ..errors import InputError
from ..fem.result import BULK_SHEAR_LIMIT, BULK_SHEAR_STUDY
from ..materials import GeneralizedMaxwell
from ..roughness import SineSeries


class LawWarning(UserWarning):
    """The law table has failed, unsteady or non-monotone points, or is being extrapolated."""


#: Steadiness diagnostics of an FEM sliding test kept in the law and results tables.
STEADINESS_VARIABLES = {
    "steady": "successive sliding periods agreed within the steadiness tolerance "
              "(1/0; NaN: failed or not recorded)",
    "period_change": "relative change of the friction over the last sliding period",
    "period_area_change": "relative change of the contact fraction over the last sliding "
                          "period",
    "sliding_time": "sliding time of the test (NaN: not recorded)",
    "bulk_shear": "mean shear strain of the cell at the end of the test, |mean face "
                  "x-displacement| / H (NaN: not recorded)",
}
#: Units of ``STEADINESS_VARIABLES`` other than "1".
STEADINESS_UNITS = {"sliding_time": "s"}
#: Sliding, in longest retardation times, below which a test is called creep-unsettled.
CREEP_SETTLED_TIMES = 3.0


def creep_unsettled_message(diag: dict, material: GeneralizedMaxwell, label, what: str,
                            times: float = CREEP_SETTLED_TIMES) -> str | None:
    """One warning naming the FEM tests of ``diag`` that slid less than ``times`` longest
    retardation times of ``material`` (shortest first, at most 6 named), or None.

    The period rule (two successive period averages within 1 %) can pass while the cell
    still creeps in shear under the friction stress on that time, which is slower than a
    period at high speed (docs/validation/creep_settled.md). Tests whose sliding time was
    not recorded (NaN) or that did not slide (0) are not counted; an elastic material does
    not creep.
    """
    lam = material.retardation_times()
    t = np.asarray(diag.get("sliding_time", np.nan), float)
    if lam.size == 0 or not np.any(np.isfinite(t)):
        return None
    short = sorted(map(tuple, np.argwhere(np.isfinite(t) & (t > 0) & (t < times * lam.max()))),
                   key=lambda idx: t[idx])
    if not short:
        return None
    where = ", ".join(f"{label(*idx)} ({1e3 * t[idx]:.1f} ms)" for idx in short[:6])
    ran = int(np.isfinite(t).sum())
    return (f"{what}: {len(short)} of {ran} time-stepped FEM tests (fem.solver = "
            f"'transient', or fallbacks of the steady solver) slid less than {times:g} "
            f"retardation times ({1e3 * lam.max():.1f} ms), shortest first: {where}"
            f"{', ...' if len(short) > 6 else ''}; the bulk may still creep although periods "
            f"agree: fem.min_creep_times slides them longer (docs/validation/creep_settled.md)")


def sheared_cells_message(diag: dict, label, what: str,
                          limit: float = BULK_SHEAR_LIMIT) -> str | None:
    """One warning naming the FEM tests of ``diag`` whose cell sheared as a whole by more
    than ``limit`` (largest first, at most 6 named), or None.

    Under a friction stress above the relaxed shear modulus the cell's bulk shear exceeds
    1, it creeps for several retardation times, and until it has settled the result
    depends on the cell height, which the paper fixes at H/L0 = 0.75
    (docs/validation/cell_creep.md). Tests cached before the shear was recorded (NaN) are
    not counted.
    """
    g = np.asarray(diag.get("bulk_shear", np.nan), float)
    big = sorted(map(tuple, np.argwhere(np.isfinite(g) & (g > limit))), key=lambda i: -g[i])
    if not big:
        return None
    where = ", ".join(f"{label(*idx)} ({g[idx]:.2f})" for idx in big[:6])
    return (f"{what}: {len(big)} of {int(np.isfinite(g).sum())} FEM tests sheared as a whole "
            f"by more than {limit:g} (mean face displacement / cell height), largest first: "
            f"{where}{', ...' if len(big) > 6 else ''}: the friction stress exceeds E∞/3 there "
            f"({BULK_SHEAR_STUDY})")


def describe_unsteady(diag: dict, label) -> tuple[int, str, bool]:
    """The FEM tests of ``diag`` (arrays of ``STEADINESS_VARIABLES``) that were not steady.

    Returns their number, ``"label (μ 1.2 %, A 7.0 %), ..."`` with ``label(*index)`` naming
    each and its changes over the last period where recorded, and whether any was recorded
    (results cached before the changes existed have only the flag).
    """
    items, recorded = [], False
    bad = np.argwhere(diag["steady"] == 0)
    for idx in map(tuple, bad):
        parts = [f"{name} {100 * diag[k][idx]:.1f} %"
                 for name, k in (("μ", "period_change"), ("A", "period_area_change"))
                 if np.isfinite(diag[k][idx])]
        recorded |= bool(parts)
        items.append(label(*idx) + (f" ({', '.join(parts)})" if parts else ""))
    return len(bad), ", ".join(items), recorded


def effective_law(hs_surface: SineSeries, material: GeneralizedMaxwell,
                  pressures: Sequence[float], velocities: Sequence[float], *,
                  options=None, runner=None, **changes) -> xr.Dataset:
    """Run the FEM sliding test over ``pressures × velocities`` and tabulate the law.

    Parameters
    ----------
    hs_surface
        High-slope surface ``z_hs`` (cell width = its longest wavelength).
    material
        Rubber.
    pressures
        Mean pressures ``p̄`` [MPa], > 0. They should span the local pressures of the
        low-slope solve (checked later by :func:`check_coverage`).
    velocities
        Sliding speeds ``v`` [mm/s], >= 0.
    options
        The FEM test (:class:`rubbercontact.fem.FemOptions`; default: the steady solver
        on 120 × 90).
    runner
        Callable ``runner(tasks) -> list`` executing :class:`~rubbercontact.sweep.Task`
        objects, returning per task an ``xr.Dataset`` or a failure record;
        default: the package's sweep executor without cache.
    **changes
        Fields of the options by name (``mesh=``, ``grading=``, ``solver=``, ...; see
        :func:`rubbercontact.fem.make_options`).

    Returns
    -------
    xarray.Dataset
        Variables ``mean_separation`` [mm], ``contact_fraction`` [-], ``shear_stress``
        [MPa], ``friction`` [-], ``status`` (``"ok"`` or the failure message), dims
        ``(velocity, pressure)``; the surface, material and FEM options in ``attrs``.
    """
    from ..fem import make_options

    p = np.sort(finite_array("pressures", pressures, ndim=1))
    v = np.sort(finite_array("velocities", velocities, ndim=1))
    if np.any(p <= 0):
        raise InputError(f"pressures: must be > 0 MPa, got {p.tolist()}")
    if np.any(v < 0):
        raise InputError(f"velocities: must be >= 0 mm/s, got {v.tolist()}")
    if hs_surface.size == 0:
        raise InputError("hs_surface: the high-slope surface is empty; no law is needed")
    opts = make_options(options, **changes)      # fails here, not in every FEM task
    from ..sweep import Task

    fem_opts = opts.to_dict()
    tasks = [Task(function="rubbercontact.hybrid.tasks:fem_task",
                  kwargs={"surface": hs_surface.as_dict(), "material": material.as_dict(),
                          "velocity": float(vi), "mean_pressure": float(pi),
                          "options": fem_opts},
                  label=f"law FEM v={vi:g} mm/s p={pi:g} MPa")
             for vi in v for pi in p]
    results = (runner or _default_runner)(tasks)
    return assemble_law(results, p, v, hs_surface, material, fem_opts)


def _default_runner(tasks):
    from ..sweep import run_sweep

    return run_sweep(tasks, cache=None).results


def assemble_law(results, pressures, velocities, hs_surface: SineSeries,
                 material: GeneralizedMaxwell, fem_options: dict) -> xr.Dataset:
    """Stack per-test datasets (row-major over velocity, pressure) into the law table."""
    names = ("mean_separation", "contact_fraction", "shear_stress", "friction", "wall_time")
    shape = (len(velocities), len(pressures))
    data = {k: np.full(shape, np.nan) for k in names}
    status = np.full(shape, "ok", dtype=object)
    diag = {k: np.full(shape, np.nan) for k in STEADINESS_VARIABLES}
    for idx, ds in enumerate(results):
        i, j = divmod(idx, len(pressures))
        if not isinstance(ds, xr.Dataset):
            status[i, j] = "missing result" if ds is None else str(ds)
            continue
        for k in names:
            data[k][i, j] = float(ds[k])
        for k in diag:
            if k in ds:     # results cached before the period changes existed lack them
                diag[k][i, j] = float(ds[k])
    units = {"mean_separation": "mm", "contact_fraction": "1", "shear_stress": "MPa",
             "friction": "1", "wall_time": "s"}
    law = xr.Dataset(
        {k: (("velocity", "pressure"), data[k], {"units": units[k]}) for k in names},
        coords={"velocity": ("velocity", np.asarray(velocities, float), {"units": "mm/s"}),
                "pressure": ("pressure", np.asarray(pressures, float), {"units": "MPa"})},
    )
    law["status"] = (("velocity", "pressure"), status.astype(str))
    for k, text in STEADINESS_VARIABLES.items():
        law[k] = (("velocity", "pressure"), diag[k],
                  {"units": STEADINESS_UNITS.get(k, "1"), "long_name": text})
    def label(i, j):
        return f"v={velocities[i]:g} p={pressures[j]:g}"

    n_bad, where, recorded = describe_unsteady(diag, label)
    if n_bad:
        # Kept in the table (the last period's averages): in the law cell the friction
        # settles within a few periods, the contact fraction can keep swinging by several
        # per cent from one period to the next.
        brackets = " (change over the last period in brackets)" if recorded else ""
        warnings.warn(f"law: {n_bad} of {diag['steady'].size} FEM points did not reach "
                      f"steady sliding within fem.periods{brackets}: {where}; they are kept "
                      f"(last period's averages); use fem.solver = 'steady' or more periods",
                      LawWarning, stacklevel=3)
    creep = creep_unsettled_message(diag, material, label, "law")
    if creep:
        warnings.warn(creep, LawWarning, stacklevel=3)
    sheared = sheared_cells_message(diag, label, "law")
    if sheared:
        warnings.warn(sheared, LawWarning, stacklevel=3)
    law.attrs.update({
        "title": "effective interface law of the high-slope scale (paper eqs. 1-3)",
        "hs_wavelengths_mm": hs_surface.wavelengths.tolist(),
        "hs_amplitudes_mm": hs_surface.amplitudes.tolist(),
        "hs_phases_rad": hs_surface.phases.tolist(),
        "hs_max_height_mm": float(max_height(hs_surface)),
        "material": json.dumps(material.as_dict()),
        "fem_options": json.dumps(fem_options),
    })
    return law


#: Variables of a law table as :func:`effective_law` and the pipeline build it; a results
#: file carries each as ``law_<name>`` on the dims ``(velocity, law_pressure)``.
LAW_VARIABLES = ("mean_separation", "contact_fraction", "shear_stress", "friction", "status",
                 "wall_time", *STEADINESS_VARIABLES, "vhs_friction", "vhs_contact_fraction")
_LAW_REQUIRED = ("mean_separation", "contact_fraction", "shear_stress", "status")
_LAW_PROVENANCE = ("hs_wavelengths_mm", "hs_amplitudes_mm", "hs_phases_rad",
                   "hs_max_height_mm", "material")


def law_from_results(ds: xr.Dataset, source: str = "results") -> xr.Dataset:
    """The law table a results dataset carries, in the form :func:`effective_law` returns.

    Raises :class:`~rubbercontact.errors.InputError` when the run had no law (no hybrid
    model, or no high-slope scale) or its file predates the law's provenance attributes.
    """
    if "law_pressure" not in ds.coords:
        raise InputError(f"{source}: carries no law (no hybrid model ran on a high-slope "
                         f"scale)")
    if "law_attrs" not in ds.attrs:
        raise InputError(f"{source}: its law has no provenance (written before "
                         f"rubbercontact stored it); rerun the law or use a law.nc")
    # a run with temperatures keeps its law on the reduced speeds, dim law_velocity
    names = {"law_pressure": "pressure", "law_velocity": "velocity"}
    law = xr.Dataset({k: ds[f"law_{k}"].rename({d: names[d] for d in ds[f"law_{k}"].dims
                                                if d in names})
                      for k in LAW_VARIABLES if f"law_{k}" in ds})
    law.attrs.update(json.loads(ds.attrs["law_attrs"]))
    return law


def as_law(ds: xr.Dataset, source: str = "law") -> xr.Dataset:
    """A law table from a law dataset or from a run's results; checked for completeness."""
    if "law_pressure" in ds.coords or "model" in ds.dims:   # a run's results
        return law_from_results(ds, source)
    missing = [k for k in _LAW_REQUIRED if k not in ds]
    if missing or set(ds["mean_separation"].dims) != {"velocity", "pressure"}:
        raise InputError(f"{source}: not a law table (needs variables {list(_LAW_REQUIRED)} "
                         f"on dims (velocity, pressure); missing {missing}); use the law.nc "
                         f"or results.nc a rubbercontact run wrote")
    absent = [k for k in _LAW_PROVENANCE if k not in ds.attrs]
    if absent:
        raise InputError(f"{source}: no {absent} attribute(s): cannot check that the law "
                         f"belongs to this surface and rubber")
    return ds


def check_law_matches(law: xr.Dataset, hs_surface: SineSeries, material: GeneralizedMaxwell,
                      velocities: Sequence[float], source: str = "law") -> None:
    """Fail unless a reused law was built for this high-slope scale, rubber and speeds.

    The law is a property of the high-slope waves (up to a translation: compare
    ``hs_surface`` at zero phase) and of the rubber; the FEM options it was built with
    (mesh, sliding) are the user's choice and are not checked. Tolerance: relative
    ``1e-9``, i.e. the same numbers up to their round trip through a file.
    """
    attrs = law.attrs

    def vec(key):
        return np.atleast_1d(np.asarray(attrs[key], float))   # NetCDF stores [x] as x

    wl, amp, ph = vec("hs_wavelengths_mm"), vec("hs_amplitudes_mm"), vec("hs_phases_rad")
    same = (wl.size == hs_surface.size
            and np.allclose(wl, hs_surface.wavelengths, rtol=1e-9, atol=0)
            and np.allclose(amp, hs_surface.amplitudes, rtol=1e-9, atol=0)
            and np.allclose(np.angle(np.exp(1j * (ph - hs_surface.phases))), 0, atol=1e-9))
    if not same:
        raise InputError(f"{source}: built for the high-slope waves wavelengths {wl.tolist()} "
                         f"mm, amplitudes {amp.tolist()} mm, phases {ph.tolist()} rad; this "
                         f"run's high-slope scale is {hs_surface.wavelengths.tolist()} mm, "
                         f"{hs_surface.amplitudes.tolist()} mm, "
                         f"{hs_surface.phases.tolist()} rad")
    built = json.loads(attrs["material"])
    mine = material.as_dict()
    same = (np.isclose(built["equilibrium_modulus"], mine["equilibrium_modulus"], rtol=1e-9)
            and len(built["moduli"]) == len(mine["moduli"])
            and np.allclose(built["moduli"], mine["moduli"], rtol=1e-9, atol=0)
            and np.allclose(built["relaxation_times"], mine["relaxation_times"], rtol=1e-9,
                            atol=0))
    if not same:
        raise InputError(f"{source}: built for the rubber {built.get('name')!r} (E_inf = "
                         f"{built['equilibrium_modulus']:g} MPa, {len(built['moduli'])} "
                         f"branches), not this run's {mine['name']!r} (E_inf = "
                         f"{mine['equilibrium_modulus']:g} MPa, {len(mine['moduli'])} branches)")
    speeds = law["velocity"].values
    absent = [float(v) for v in velocities
              if not np.any(np.isclose(speeds, v, rtol=1e-9, atol=1e-12))]
    if absent:
        raise InputError(f"{source}: has no FEM points at {absent} mm/s (it has "
                         f"{speeds.tolist()} mm/s); build the law at those speeds or drop "
                         f"them from velocities")


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
    # excluded points were named by screen_monotone already
    failed = ~ok & ~np.char.startswith(status, "excluded")
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


def linear_law(hs_surface: SineSeries, material: GeneralizedMaxwell, velocity: float, *,
               n: int = 2048, nu: float = 0.5, points: int = 80) -> dict:
    """The VHS (linear) law of the high-slope wave alone, as a table like :func:`law_at_velocity`.

    Hard-wall VHS solves at ``points`` pressures from 1e-3 to 50 MPa (geometric), up to
    full contact, plus the zero-load anchor ``(max z_hs, 0, 0, 0)``. With it in place of
    the FEM law the hybrid's remaining error is its scale split alone.
    """
    from .. import halfspace

    rows = []
    for p in np.geomspace(1e-3, 50.0, int(points)):
        r = halfspace.solve_sliding(hs_surface, hs_surface.period, material, velocity,
                                    float(p), n=n, nu=nu)
        if r.contact_fraction >= 0.999:   # full contact: u stops changing
            break
        rows.append((r.mean_separation, p, r.contact_fraction, r.friction * p))
    u, sig, alpha, tau = (np.array(c) for c in zip(*sorted(rows), strict=True))
    return {"separation": [*u, max_height(hs_surface)], "pressure": [*sig, 0.0],
            "contact_fraction": [*alpha, 0.0], "shear_stress": [*tau, 0.0]}


def continue_with_linear_shape(table: dict, hs_surface: SineSeries,
                               material: GeneralizedMaxwell, velocity: float, *,
                               n: int = 2048, nu: float = 0.5, factor: float = 1.25,
                               max_rows: int = 40) -> dict:
    """Continue a law table past its highest FEM pressure with the shape of the linear law.

    The FEM cell of a steep wave is crushed beyond ~1.5 E∞, while the low-slope solve may
    load the high-slope scale locally to several times that. Beyond the last FEM point
    ``(σ₀, ū₀, α₀, Δτ₀)`` the rows follow the viscoelastic half-space (VHS) law of the same
    wave, anchored multiplicatively at that point::

        ū(σ) = ū₀ ū_V(σ)/ū_V(σ₀),  α(σ) = min(1, α₀ α_V(σ)/α_V(σ₀)),
        Δτ(σ) = Δτ₀ Δτ_V(σ)/Δτ_V(σ₀),

    at ``σ = σ₀ factor^k`` until the VHS reaches 99 % contact (``max_rows`` at most). The
    continuation is exact when the FEM law equals the VHS law, keeps ``ū > 0`` and
    decreasing, and reaches the linear theory's full-contact behaviour (``Δτ`` independent
    of ``σ``) instead of holding ``Δτ`` or ``Δτ/σ`` at the last FEM value. It is an
    extrapolation all the same: :func:`check_coverage` still warns when it is used.

    Parameters
    ----------
    table
        Output of :func:`law_at_velocity` (``u`` ascending, highest pressure first).
    hs_surface, material, velocity
        The high-slope wave, the rubber and the speed [mm/s] of the table.
    n, nu
        Grid points and Poisson ratio of the VHS solves (hard wall).
    factor
        Pressure ratio between continuation rows (> 1).
    max_rows
        Most rows added.

    Returns
    -------
    dict
        The table with the continuation rows prepended (same keys).
    """
    from .. import halfspace

    u = np.asarray(table["separation"], float)
    sig = np.asarray(table["pressure"], float)
    alpha = np.asarray(table["contact_fraction"], float)
    tau = np.asarray(table["shear_stress"], float)
    if not factor > 1:
        raise InputError(f"factor: must be > 1, got {factor}")

    def vhs(p):
        r = halfspace.solve_sliding(hs_surface, hs_surface.period, material, velocity, p,
                                    law=None, n=n, nu=nu)
        return r.mean_separation, r.contact_fraction, r.friction * p

    if material.is_elastic:
        return table        # no hysteresis: no shear stress to borrow the shape of
    s0 = float(sig[0])
    ref = vhs(s0)
    if not (ref[0] > 0 and ref[1] > 0 and ref[2] > 0 and tau[0] > 0):
        return table        # no shape to borrow (full contact at σ₀)
    rows = []
    p, u_last = s0, ref[0]
    for _ in range(int(max_rows)):
        p *= factor
        uv, av, tv = vhs(p)
        # stop at (near) full contact, where the VHS separation stops decreasing
        if av >= 0.99 or not 0 < uv < u_last:
            break
        u_last = uv
        rows.append((u[0] * uv / ref[0], p, min(1.0, alpha[0] * av / ref[1]),
                     tau[0] * tv / ref[2]))
    ext = np.array(rows[::-1]).reshape(-1, 4)   # ascending in u
    return {"separation": [*ext[:, 0], *u], "pressure": [*ext[:, 1], *sig],
            "contact_fraction": [*ext[:, 2], *alpha], "shear_stress": [*ext[:, 3], *tau]}


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
