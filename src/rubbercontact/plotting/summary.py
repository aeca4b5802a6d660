"""Plain-text summary of a results dataset (``rubbercontact run``, ``plot``, ``summary``).

A run with a handful of speeds prints, per speed, each model's mean friction and contact
area at every load and the eq. 28 errors. A speed sweep (:data:`CURVE_SPEEDS` speeds or
more) or a run with temperatures prints, per temperature and load, the friction curve
against speed and where each model's curve peaks (:func:`rubbercontact.pipeline.friction_peak`).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..io.results import mean_of

#: From this many speeds on, the summary prints curves against speed.
CURVE_SPEEDS = 3


def _error_basis(ds: xr.Dataset) -> str:
    """``" at equal σ0"`` / ``" at equal A_c"``: what ``error_vs_fem`` compares over
    (empty for files written before the attribute existed)."""
    over = ds["error_vs_fem"].attrs.get("compared_over")
    return {"pressure": " at equal σ0", "contact_area": " at equal A_c"}.get(over, "")


def summary_table(ds: xr.Dataset) -> str:
    """Plain-text summary: friction and area per model, speed and load; eq. 28 errors;
    for speed sweeps the curves and their peaks (module docstring)."""
    lines = []
    if "fem_realizations" in ds.attrs:
        lines.append(f"fem ran on {ds.attrs['fem_realizations']} of {ds.sizes['realization']} "
                     "realizations: its mu and A are phase averages estimated with the VHS "
                     "as control variate, mean_N(vhs) + mean_R(fem - vhs)")
    if "adhesion" in ds.attrs:
        import json

        lines.append("adhesion: mu_adh = tau_f A_c/sigma0 with "
                     + json.loads(ds.attrs["adhesion"])["formula"]
                     + "; 'mu+adh' is the hysteretic mu plus mu_adh")
    lines += _flash_heading(ds)
    if "temperature" in ds.dims or ds.sizes["velocity"] >= CURVE_SPEEDS:
        lines += _curves(ds)
    else:
        for v in ds["velocity"].values:
            lines += _per_speed(ds, v)
    coverage = [f"law: {ds.attrs['law_coverage']}"] if ds.attrs.get("law_coverage") else []
    cell = [ds.attrs["law_cell_note"]] if ds.attrs.get("law_cell_note") else []
    if ds.attrs.get("law_quasi_static"):
        cell.append(f"law cell: {ds.attrs['law_quasi_static']}")
    return "\n".join(lines + cell + coverage + _validity(ds))


def _validity(ds: xr.Dataset) -> list[str]:
    """The run's notes where a model left the class it was validated on (one line a
    model)."""
    notes = [line for k, v in ds.attrs.items() if k.startswith("validity_")
             for line in str(v).splitlines() if line]
    if not notes:
        return []
    return ["", "outside the validated class (docs/guide/models.md, 'Where each model was "
                "validated'):", *(f"  {n}" for n in notes)]


def _columns(ds: xr.Dataset) -> list[tuple[str, str, xr.DataArray, int]]:
    """(model, heading, mean, width) of each printed column."""
    mu, area = mean_of(ds, "friction"), mean_of(ds, "contact_fraction")
    total = mean_of(ds, "friction_total") if "friction_total_mean" in ds else None
    cols = []
    for m in ds["model"].values:
        w = max(10, len(m) + 3)
        cols += [(m, f"{m} mu", mu, w), (m, f"{m} A", area, w - 1)]
        if total is not None:
            cols.append((m, f"{m} mu+adh", total, max(w, len(m) + 7)))
        if m in _flash_models(ds):
            cols += [(m, f"{m} mu flash", ds["friction_flash"], max(w, len(m) + 9)),
                     (m, f"{m} dT [K]", ds["flash_temperature"], max(w, len(m) + 7))]
    return cols


def _flash_models(ds: xr.Dataset) -> list[str]:
    """The models with a friction computed with the flash temperature."""
    if "friction_flash" not in ds:
        return []
    return [m for m in ds["model"].values
            if bool(ds["friction_flash"].sel(model=m).notnull().any())]


def _flash_heading(ds: xr.Dataset) -> list[str]:
    """What 'mu flash' and 'dT' are, the compound's thermal properties, the run's note."""
    if "flash_thermal" not in ds.attrs:
        return []
    import json

    th = json.loads(ds.attrs["flash_thermal"])
    lines = [f"flash temperature: 'mu flash' with the contact spots heated by the friction, "
             f"'dT' their rise [K]; K = {th['conductivity']:g} W/(m K), rho = "
             f"{th['density']:g} kg/m3, c = {th['specific_heat']:g} J/(kg K) "
             f"({th['source']})"]
    if ds.attrs.get("flash_note"):
        lines.append(ds.attrs["flash_note"])
    return lines


def _flash_peak(at_t: xr.Dataset, m: str, p: float) -> str | None:
    """The line of the peak of ``m``'s μ(v) with the flash temperature (None without)."""
    from ..pipeline.statistics import friction_peak

    if m not in _flash_models(at_t):
        return None
    peak = friction_peak(at_t["velocity"].values,
                         at_t["friction_flash"].sel(model=m, pressure=p).values)
    if peak is None:
        return f"  peak of {m} with flash temperature: n/a (fewer than two finite points)"
    where = "" if peak.interior else " (at the end of the range)"
    return (f"  peak of {m} with flash temperature: mu = {peak.friction:.4f} at v = "
            f"{peak.velocity:.4g} mm/s{where}")


def _spread(ds: xr.Dataset, k: str) -> xr.DataArray:
    """Standard deviation of ``k`` over the realizations that ran (NaN below two)."""
    n = ds[k].notnull().sum("realization")
    return ds[k].std("realization").where(n > 1)


def _with_spread(mean, sd) -> str:
    """``0.5157 ±0.071``: the mean to four decimals, the spread to two digits (none when
    fewer than two realizations ran)."""
    sd = float(sd)
    return f"{float(mean):.4f} " + ("" if np.isnan(sd) else f"±{sd:.2g}")


def _per_speed(ds: xr.Dataset, v: float) -> list[str]:
    """One row per load and model (a table as narrow as a terminal, whatever the models):
    the phase average of μ and A, each ± its spread between realizations."""
    lines = [f"v = {v:g} mm/s: phase average over {ds.sizes['realization']} realizations "
             f"± the spread between them (standard deviation)"]
    mu, area = mean_of(ds, "friction"), mean_of(ds, "contact_fraction")
    sd_mu, sd_area = _spread(ds, "friction"), _spread(ds, "contact_fraction")
    total = mean_of(ds, "friction_total") if "friction_total_mean" in ds else None
    width = max(len(str(m)) for m in ds["model"].values)
    head = f"  {'sigma0 [MPa]':>12}  {'model':<{width}}  {'mu':<15}  {'A_c/A_0':<16}"
    lines.append(head + "  mu+adh" if total is not None else head.rstrip())
    for p in ds["pressure"].values:
        for k, m in enumerate(ds["model"].values):
            at = {"model": m, "velocity": v, "pressure": p}
            row = (f"  {f'{p:.4g}' if k == 0 else '':>12}  {m:<{width}}  "
                   f"{_with_spread(mu.sel(at), sd_mu.sel(at)):<15}  "
                   f"{_with_spread(area.sel(at), sd_area.sel(at)):<16}")
            if total is not None:
                row += f"  {float(total.sel(at)):.4f}"
            lines.append(row.rstrip())
    for m in _flash_models(ds):
        for p in ds["pressure"].values:
            at = {"model": m, "velocity": v, "pressure": p}
            lines.append(f"  {m} with flash temperature at {p:.4g} MPa: mu = "
                         f"{float(ds['friction_flash'].sel(at)):.4f}, dT = "
                         f"{float(ds['flash_temperature'].sel(at)):.3g} K")
    if "friction_at_area_mean" in ds:
        wid = {m: max(10, len(m) + 3) for m in ds["model"].values}
        lines.append(f"  {'A_c/A_0':>12} " + " ".join(f"{m + ' mu':>{wid[m]}}"
                                                      for m in ds["model"].values))
        mu_at = mean_of(ds, "friction_at_area")
        for a in ds["contact_area"].values:
            vals = [(m, float(mu_at.sel(model=m, velocity=v, contact_area=a)))
                    for m in ds["model"].values]
            lines.append(f"  {a:12.3g} " + " ".join(f"{x:{wid[m]}.4f}" for m, x in vals))
    if "error_vs_fem" in ds:
        for m in ds["compared_model"].values:
            e = float(ds["error_vs_fem"].sel(compared_model=m, velocity=v))
            text = (f"  eq. 28 error of {m} vs FEM{_error_basis(ds)}: "
                    f"{'n/a' if np.isnan(e) else f'{100 * e:.1f} %'}")
            if "error_vs_fem_at_area" in ds:
                a = float(ds["error_vs_fem_at_area"].sel(compared_model=m, velocity=v))
                text += f", at equal A_c: {'n/a' if np.isnan(a) else f'{100 * a:.1f} %'}"
            lines.append(text)
    return lines


def _curves(ds: xr.Dataset) -> list[str]:
    """Per temperature and load: μ (and A) against speed, and each model's peak."""
    from ..pipeline.statistics import friction_peak

    temps = ds["temperature"].values if "temperature" in ds.dims else [None]
    lines = []
    for t in temps:
        at_t = ds if t is None else ds.sel(temperature=t)
        heading = "" if t is None else f"T = {t:g} °C"
        if t is not None and "shift_factor" in at_t.coords:
            heading += f" (a_T = {float(at_t['shift_factor']):.4g})"
        cols = _columns(at_t)
        for p in at_t["pressure"].values:
            lines.append(", ".join(x for x in (heading, f"sigma0 = {p:g} MPa") if x))
            lines.append(f"  {'v [mm/s]':>12} " + " ".join(f"{h:>{w}}" for _, h, _, w in cols))
            for v in at_t["velocity"].values:
                lines.append(f"  {v:12.4g} " + " ".join(
                    f"{float(a.sel(model=m, velocity=v, pressure=p)):{w}.4f}"
                    for m, _, a, w in cols))
            mu = mean_of(at_t, "friction")
            for m in at_t["model"].values:
                peak = friction_peak(at_t["velocity"].values,
                                     mu.sel(model=m, pressure=p).values)
                if peak is None:
                    lines.append(f"  peak of {m}: n/a (fewer than two finite points)")
                    continue
                where = "" if peak.interior else " (at the end of the range: the peak may " \
                                                 "lie beyond)"
                lines.append(f"  peak of {m}: mu = {peak.friction:.4f} at v = "
                             f"{peak.velocity:.4g} mm/s{where}")
                flash = _flash_peak(at_t, m, p)
                if flash is not None:
                    lines.append(flash)
    return lines
