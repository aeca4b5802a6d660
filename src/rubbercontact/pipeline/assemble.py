"""Task results into one dataset: dims ``model, velocity, realization, pressure``.

``velocity`` is here the computed speed of each task (the reduced speed of a run with
temperatures; :mod:`.temperature` spreads the dataset over ``temperature, velocity``).
"""

from __future__ import annotations

import warnings

import numpy as np
import xarray as xr

from ..fem.loadrange import LOAD_RANGE_STUDY, held
from ..hybrid.law import (
    STEADINESS_UNITS,
    STEADINESS_VARIABLES,
    creep_unsettled_message,
    describe_unsteady,
    sheared_cells_message,
)
from ..hybrid.steadiness import impaled_tests
from ..materials import GeneralizedMaxwell
from ..models.registry import splits
from .plan import Slot

#: Status of a solve skipped by design (the FEM beyond ``fem.realizations``): not a failure.
NOT_RUN = "not run"

#: Result variables produced per (model, velocity, realization, pressure).
RESULT_VARIABLES = {
    "friction": ("1", "total hysteretic friction coefficient mu"),
    "friction_ls": ("1", "low-slope part mu_ls (eq. 7); equals mu for vhs, fem and meanfield"),
    "friction_hs": ("1", "high-slope part mu_hs (eq. 6); 0 for vhs, fem and meanfield"),
    "contact_fraction": ("1", "normalized real contact area A_c/A_0 (eq. 8 for hybrid)"),
    "mean_separation": ("mm", "mean interface separation"),
    "wall_time": ("s", "wall time of the solve"),
}
DIMS = ("model", "velocity", "realization", "pressure")


def failed_solves(status) -> np.ndarray:
    """Boolean mask of the solves that failed: status neither ``"ok"`` nor :data:`NOT_RUN`."""
    s = np.asarray(status).astype(str)
    return (s != "ok") & ~np.char.startswith(s, NOT_RUN)


def failure_message(res) -> str | None:
    """``None`` for a successful task result, else why it failed (one line)."""
    if isinstance(res, xr.Dataset):
        return None
    return "missing result" if res is None else str(res)


def model_times(slots: list[Slot], results: list) -> dict[str, float]:
    """Summed wall time of each model's tasks [s] (a mean-field task counted once)."""
    out: dict[str, float] = {}
    for slot, res in zip(slots, results, strict=True):
        t = (float(np.nansum(res["wall_time"].values))
             if failure_message(res) is None and "wall_time" in res else 0.0)
        out[slot.model] = out.get(slot.model, 0.0) + t
    return out


def assemble(models: list[str], velocities: np.ndarray, n_real: int, pressures: np.ndarray,
             slots: list[Slot], results: list, material: GeneralizedMaxwell,
             n_fem: int) -> xr.Dataset:
    """Stack the task results; warn about failures and unsteady full-FEM tests."""
    shape = (len(models), len(velocities), n_real, len(pressures))
    names = list(RESULT_VARIABLES) + ["max_local_pressure"]
    data = {k: np.full(shape, np.nan) for k in names}
    status = np.full(shape, "ok", dtype=object)
    if "fem" in models and n_fem < n_real:
        status[models.index("fem"), :, n_fem:] = f"{NOT_RUN} (fem.realizations = {n_fem})"
    if "fem" in models:
        fem_above_range(status[models.index("fem")], pressures, material)
    # full-FEM steadiness (1/0; NaN where failed or not recorded)
    fem_diag = {k: np.full(shape[1:], np.nan) for k in STEADINESS_VARIABLES}
    for slot, res in zip(slots, results, strict=True):
        im = models.index(slot.model)
        at = (im, slot.iv, slice(None) if slot.ir is None else slot.ir,
              slice(None) if slot.ip is None else slot.ip)
        msg = failure_message(res)
        if msg is not None:
            status[at] = msg
            continue
        if slot.ip is None:
            _store_loads(data, status, at, res, split=splits(slot.model))
            continue
        if slot.model == "fem":
            for k, arr in fem_diag.items():
                if k in res:     # results cached before a diagnostic existed lack it
                    arr[at[1:]] = float(res[k])
        for k in names:
            if k in res:
                data[k][at] = float(res[k])
        if not splits(slot.model):
            data["friction_ls"][at] = float(res["friction"])
            data["friction_hs"][at] = 0.0
    ds = xr.Dataset(
        {k: (DIMS, data[k], {"units": RESULT_VARIABLES.get(k, ("MPa", ""))[0],
                             "long_name": RESULT_VARIABLES.get(k, ("", "max local pressure"))[1]})
         for k in names},
        coords={"model": list(models),
                "velocity": ("velocity", np.asarray(velocities, float), {"units": "mm/s"}),
                "realization": np.arange(n_real),
                "pressure": ("pressure", pressures, {"units": "MPa",
                                                     "long_name": "mean pressure sigma0"})},
    )
    ds["status"] = (DIMS, status.astype(str))
    n_run = int((~np.char.startswith(status.astype(str), NOT_RUN)).sum())
    n_failed = int(failed_solves(status).sum())
    if n_failed:
        warnings.warn(f"{n_failed} of {n_run} solves failed; see the 'status' variable",
                      RuntimeWarning, stacklevel=3)
    if "fem" in models:
        ds = add_fem_steadiness(ds, fem_diag, material, stacklevel=4)
    return ds


def fem_above_range(status: np.ndarray, pressures: np.ndarray,
                    material: GeneralizedMaxwell) -> None:
    """Mark the full FEM's loads above the rubber's E∞ as not run (``status`` the model's,
    by velocity, realization, pressure) and say so in one line: the run does not try them
    (:func:`~.plan.run_loads`, :mod:`rubbercontact.fem.loadrange`)."""
    e_inf = float(material.equilibrium_modulus)
    above = ~held(pressures, e_inf)
    if not above.any():
        return
    status[..., above] = f"{NOT_RUN} (above E∞ = {e_inf:.3g} MPa)"
    loads = ", ".join(f"{p:.3g}" for p in np.asarray(pressures)[above])
    warnings.warn(f"full FEM not run at {loads} MPa: above the rubber's E∞ ({e_inf:.3g} MPa), "
                  f"outside the FEM cell's range ({LOAD_RANGE_STUDY})", RuntimeWarning,
                  stacklevel=4)


def _store_loads(data: dict, status: np.ndarray, at: tuple, res: xr.Dataset,
                 split: bool) -> None:
    """A task's result over every load (a ``pressure`` dimension) into its slot; ``split``:
    the model reports ``μ_ls`` and ``μ_hs`` (else ``μ_ls = μ``, ``μ_hs = 0``)."""
    status[at] = res["status"].values.astype(str)
    for k, arr in data.items():
        if k in res:
            arr[at] = res[k].values
    if not split:
        data["friction_ls"][at] = res["friction"].values
        data["friction_hs"][at] = np.where(np.isfinite(res["friction"].values), 0.0, np.nan)


def add_fem_steadiness(ds: xr.Dataset, diag: dict, material: GeneralizedMaxwell,
                       stacklevel: int = 2) -> xr.Dataset:
    """Store the full-FEM tests' diagnostics, and name those that did not reach steady
    sliding, crept, sheared as a whole or had their face impaled.

    An unsteady test keeps its result (the last period's averages), as the FEM itself
    does, but the run says so instead of leaving the warning in a worker's log.
    """
    dims = ("velocity", "realization", "pressure")
    for k, text in STEADINESS_VARIABLES.items():
        ds[f"fem_{k}"] = (dims, diag[k], {"units": STEADINESS_UNITS.get(k, "1"),
                                           "long_name": f"full FEM: {text}"})
    v, p = ds["velocity"].values, ds["pressure"].values

    def label(iv, ir, ip):
        return f"v={v[iv]:g} σ0={p[ip]:g} r={ir}"

    n_bad, where, recorded = describe_unsteady(diag, label)
    if n_bad:
        brackets = ("; change of friction / contact fraction over the last period in "
                    "brackets" if recorded else "")
        warnings.warn(f"{n_bad} of {int(np.isfinite(diag['steady']).sum())} full-FEM tests "
                      f"did not reach "
                      f"steady sliding in the periods allowed (fem.full_periods, else "
                      f"fem.periods){brackets}: {where}. Their results are the last period's "
                      f"averages (see 'fem_steady'); more periods, or fem.min_creep_times, would "
                      f"settle them",
                      RuntimeWarning, stacklevel=stacklevel)
    creep = creep_unsettled_message(diag, material, label, "full FEM")
    if creep:
        warnings.warn(creep, RuntimeWarning, stacklevel=stacklevel)
    sheared = sheared_cells_message(diag, label, "full FEM")
    if sheared:
        warnings.warn(sheared, RuntimeWarning, stacklevel=stacklevel)
    # an under-resolved test is said once by the run's validity note of the FEM
    # (rubbercontact.validity.run), not here
    n_impaled, where = impaled_tests(diag, label)
    if n_impaled:
        # kept (nothing is lost) and still "ok": the run names them instead
        warnings.warn(f"{n_impaled} full-FEM test(s) had the rubber face impaled ({where}): "
                      f"their friction and contact fraction are not meaningful (see "
                      f"'fem_impaled'); refine the cell (fem.mesh) or lower the load",
                      RuntimeWarning, stacklevel=stacklevel)
    return ds


def add_profiles(ds: xr.Dataset, slots: list[Slot], results: list) -> xr.Dataset:
    """Pressure along the surface for realization 0 (paper Fig. 8).

    The profiles share the finest half-space grid (the VHS's): a solve on a coarser grid
    (the hybrid's low-slope solve, :mod:`rubbercontact.hybrid.grid`) is interpolated to it
    linearly and periodically (its own points are among the fine ones when its size
    divides the fine grid's, and keep their values); ``grid_points`` in the variable's
    attributes is the size of the grid it was solved on.
    """
    rows: dict[str, list] = {}
    fine = None
    for slot, res in zip(slots, results, strict=True):
        if (failure_message(res) or slot.ir != 0 or "pressure_profile" not in res
                or slot.model == "fem"):
            continue
        rows.setdefault(slot.model, []).append((slot, res["x"].values,
                                                res["pressure_profile"].values))
        if fine is None or res.sizes["x"] > fine.size:
            fine = res["x"].values
        if "heights" not in ds and slot.model == "vhs":
            ds = ds.assign_coords(x=("x", res["x"].values, {"units": "mm"}))
            ds["heights"] = ("x", res["heights_profile"].values, {"units": "mm"})
    if fine is None:
        return ds
    if "x" not in ds.coords:
        ds = ds.assign_coords(x=("x", fine, {"units": "mm"}))
    fine = ds["x"].values
    for m, items in rows.items():
        arr = np.full((ds.sizes["velocity"], ds.sizes["pressure"], fine.size), np.nan)
        points = items[0][1].size
        for slot, x, prof in items:
            if x.size != fine.size:
                length = (x[1] - x[0]) * x.size          # uniform grid from x = 0
                prof = np.stack([np.interp(fine, x, row, period=length)
                                 for row in np.atleast_2d(prof)]).reshape(
                    prof.shape[:-1] + (fine.size,))
            arr[slot.iv, slice(None) if slot.ip is None else slot.ip] = prof
        ds[f"pressure_profile_{m}"] = (("velocity", "pressure", "x"), arr,
                                       {"units": "MPa", "grid_points": points,
                                        "long_name": f"{m} contact pressure, realization 0"})
    return ds


def add_law(ds: xr.Dataset, law: xr.Dataset, on: str = "velocity") -> xr.Dataset:
    """Carry the law table as ``law_<name>`` variables on ``(on, law_pressure)``, with what
    :func:`~rubbercontact.hybrid.law.law_from_results` needs to give it back."""
    import json

    from ..hybrid.law import LAW_VARIABLES

    for k in LAW_VARIABLES:
        if k in law:
            var = law[k].rename(pressure="law_pressure")
            ds[f"law_{k}"] = var.rename(velocity=on) if on != "velocity" else var
    coords = {"law_pressure": ("law_pressure", law["pressure"].values, {"units": "MPa"})}
    if on != "velocity":
        coords[on] = (on, law["velocity"].values, {"units": "mm/s",
                                                    "long_name": "speeds of the law at T_ref"})
    ds = ds.assign_coords(coords)
    ds.attrs["law_attrs"] = json.dumps({k: np.asarray(v).tolist() if not isinstance(v, str)
                                        else v for k, v in law.attrs.items()})
    return ds
