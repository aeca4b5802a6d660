"""Friction and contact area against sliding speed and temperature (speed sweeps).

One panel per load (at most :data:`MAX_LOADS`, spread over the loads) and, with
temperatures, one row per temperature (at most :data:`MAX_TEMPERATURES`): each model's
mean friction over log v, the hybrid models' ``μ_ls`` (dashed) and ``μ_hs`` (dotted), and
with ``[friction.adhesion]`` the adhesive ``μ_adh`` (dash-dot) and the sum (thin), with
``[friction.flash_temperature]`` the friction with the flash temperature (dashed, thick).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from ..io.results import mean_of
from .figures import _COLORS, _plt, _save, panel_indices, speed_text

#: Most loads, temperatures and speeds drawn as panels or curves.
MAX_LOADS = 4
MAX_TEMPERATURES = 4
#: Speeds needed for a curve against speed; temperatures for one against temperature.
CURVE_POINTS = 3
_SPLIT = ("hybrid", "hybrid-windowed", "meanfield-hybrid")


def _grid(ds: xr.Dataset, rows: int, cols: int, size=(4.8, 3.6)):
    plt = _plt()
    return plt.subplots(rows, cols, figsize=(size[0] * cols, size[1] * rows), squeeze=False)


def _temperature_rows(ds: xr.Dataset) -> list:
    if "temperature" not in ds.dims:
        return [None]
    t = ds["temperature"].values
    return [t[i] for i in panel_indices(t.size, MAX_TEMPERATURES)]


def _loads(ds: xr.Dataset) -> np.ndarray:
    p = ds["pressure"].values
    return p[panel_indices(p.size, MAX_LOADS)]


def _speed_axes(ds: xr.Dataset, path: Path, draw, ylabel: str, title: str) -> Path | None:
    if ds.sizes["velocity"] < CURVE_POINTS:
        return None
    temps, loads = _temperature_rows(ds), _loads(ds)
    fig, axes = _grid(ds, len(temps), len(loads))
    v = ds["velocity"].values
    for r, t in enumerate(temps):
        at_t = ds if t is None else ds.sel(temperature=t)
        for c, p in enumerate(loads):
            ax = axes[r, c]
            draw(ax, at_t, v, p)
            ax.set_xscale("log")
            ax.set_xlabel("sliding speed v [mm/s]")
            ax.set_ylabel(ylabel)
            ax.set_title(f"σ0 = {p:.3g} MPa" + ("" if t is None else f", T = {t:.3g} °C"),
                         fontsize=9)
            ax.grid(alpha=0.3, which="both")
    fig.suptitle(title)
    return _save(fig, path, legends=[axes[0, 0]], fontsize=7)


def plot_friction_vs_speed(ds: xr.Dataset, path: Path) -> Path | None:
    """μ against log v per model, with the split models' μ_ls / μ_hs (and μ_adh)."""
    mu = mean_of(ds, "friction")
    split = {k: ds[f"{k}_mean"] for k in ("friction_ls", "friction_hs") if f"{k}_mean" in ds}
    if not split:
        split = {k: ds[k].mean("realization") for k in ("friction_ls", "friction_hs")}
    adh = mean_of(ds, "friction_adhesion") if "friction_adhesion_mean" in ds else None
    total = mean_of(ds, "friction_total") if "friction_total_mean" in ds else None
    flash = ds["friction_flash"] if "friction_flash" in ds else None

    def draw(ax, at_t, v, p):
        sel = {"pressure": p}
        if "temperature" in at_t.coords and "temperature" in mu.dims:
            sel["temperature"] = float(at_t["temperature"])
        for m in ds["model"].values:
            col = _COLORS.get(m)
            ax.plot(v, mu.sel(model=m, **sel), "o-", ms=3, color=col, label=m)
            if m in _SPLIT:
                ax.plot(v, split["friction_ls"].sel(model=m, **sel), "--", color=col, lw=1,
                        label=f"{m}: μ_ls")
                ax.plot(v, split["friction_hs"].sel(model=m, **sel), ":", color=col, lw=1,
                        label=f"{m}: μ_hs")
            if adh is not None:
                ax.plot(v, adh.sel(model=m, **sel), "-.", color=col, lw=1, label=f"{m}: μ_adh")
                ax.plot(v, total.sel(model=m, **sel), "-", color=col, lw=0.6,
                        label=f"{m}: μ + μ_adh")
            if flash is not None and bool(flash.sel(model=m).notnull().any()):
                ax.plot(v, flash.sel(model=m, **sel), "--", color=col, lw=1.8,
                        label=f"{m}: with flash temperature")

    return _speed_axes(ds, path, draw, "friction coefficient μ [-]",
                       "Friction against sliding speed (mean over realizations)")


def plot_contact_vs_speed(ds: xr.Dataset, path: Path) -> Path | None:
    """Real contact area A_c/A_0 against log v per model."""
    area = mean_of(ds, "contact_fraction")

    def draw(ax, at_t, v, p):
        sel = {"pressure": p}
        if "temperature" in at_t.coords and "temperature" in area.dims:
            sel["temperature"] = float(at_t["temperature"])
        for m in ds["model"].values:
            ax.plot(v, area.sel(model=m, **sel), "o-", ms=3, color=_COLORS.get(m),
                    label=m)
        ax.set_yscale("log")

    return _speed_axes(ds, path, draw, "contact area A_c/A_0 [-]",
                       "Real contact area against sliding speed")


def plot_friction_vs_temperature(ds: xr.Dataset, path: Path) -> Path | None:
    """μ against temperature per model: one panel per load (rows) and speed (columns, at
    most :data:`MAX_LOADS` speeds spread over the range)."""
    if "temperature" not in ds.dims or ds.sizes["temperature"] < 2:
        return None
    mu = mean_of(ds, "friction")
    loads = _loads(ds)
    v_all = ds["velocity"].values
    speeds = v_all[panel_indices(v_all.size, MAX_LOADS)]
    panels = [(p, v) for p in loads for v in speeds]
    # wrapped into a near-square grid: one row of 4 panels was a 2496 x 468 strip
    cols = int(np.ceil(np.sqrt(len(panels))))
    rows = int(np.ceil(len(panels) / cols))
    fig, axes = _grid(ds, rows, cols)
    t = ds["temperature"].values
    for ax, (p, v) in zip(axes.flat, panels, strict=False):
        for m in ds["model"].values:
            ax.plot(t, mu.sel(model=m, pressure=p, velocity=v), "o-", ms=3,
                    color=_COLORS.get(m), label=m)
        ax.set_xlabel("temperature T [°C]")
        ax.set_ylabel("friction coefficient μ [-]")
        ax.set_title(f"σ0 = {p:.3g} MPa, v = {speed_text(v)}", fontsize=9)
        ax.grid(alpha=0.3)
    for ax in axes.flat[len(panels):]:
        ax.set_visible(False)
    fig.suptitle("Friction against temperature (time-temperature superposition)")
    return _save(fig, path, legends=[axes[0, 0]], fontsize=7)
