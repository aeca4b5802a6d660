"""Figures of a results dataset, after the paper's Figs. 2, 5, 7, 8 and 9.

The per-speed figures draw at most :data:`MAX_PANELS` speeds (spread over the range); in a
run with temperatures they show the temperature nearest the reference one (the speed and
temperature curves are :mod:`.speed`'s).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from ..io.results import mean_of
from .summary import _error_basis, summary_table

__all__ = ["plot_all", "summary_table", "plot_law", "plot_friction_vs_area",
           "plot_friction_vs_pressure", "plot_high_slope_friction", "plot_pressure_profiles"]

_COLORS = {"vhs": "tab:red", "hybrid": "tab:blue", "hybrid-windowed": "tab:green",
           "fem": "black", "meanfield": "tab:purple", "meanfield-hybrid": "tab:orange",
           "meanfield-strips": "tab:brown"}
_LABELS = {"vhs": "VHS (half-space only)", "hybrid": "hybrid multiscale",
           "hybrid-windowed": "hybrid, law at λ_hs-averaged pressure", "fem": "FEM (full)",
           "meanfield": "mean-field (Persson, S(q))", "meanfield-hybrid": "mean-field + FEM law",
           "meanfield-strips": "Westergaard strip cascade"}
#: Most speeds a per-speed figure draws.
MAX_PANELS = 4


def panel_indices(n: int, most: int = MAX_PANELS) -> list[int]:
    """At most ``most`` indices of ``range(n)``, spread evenly, first and last included."""
    if n <= most:
        return list(range(n))
    return sorted({int(round(x)) for x in np.linspace(0, n - 1, most)})


def panel_grid(n: int, size: tuple[float, float]):
    """A figure of ``n`` panels of ``size`` [in]: one row up to two, else a near-square
    grid (four panels in a row made a 2704 x 520 strip); the axes in reading order, the
    grid's spare cells hidden."""
    plt = _plt()
    cols = n if n <= 2 else int(np.ceil(np.sqrt(n)))
    rows = int(np.ceil(n / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(size[0] * cols, size[1] * rows),
                             squeeze=False)
    for ax in axes.flat[n:]:
        ax.set_visible(False)
    return fig, list(axes.flat[:n])


def law_speeds(ds: xr.Dataset) -> tuple[str, np.ndarray]:
    """The dimension of the law's speeds (``law_velocity`` in a run with temperatures) and
    the speeds to draw (at most :data:`MAX_PANELS`)."""
    dim = "law_velocity" if "law_velocity" in ds.dims else "velocity"
    v = ds[dim].values
    return dim, v[panel_indices(v.size)]


def isothermal_view(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` at the temperature nearest the reference one (a scalar ``temperature``
    coordinate remains), or ``ds`` itself for an isothermal run."""
    if "temperature" not in ds.dims:
        return ds
    t = ds["temperature"].values
    ref = ds.attrs.get("reference_temperature_C")
    k = int(np.argmin(np.abs(t - float(ref)))) if ref is not None else 0
    return ds.isel(temperature=k)


def _at_temperature(ds: xr.Dataset) -> str:
    return f", T = {float(ds['temperature']):g} °C" if "temperature" in ds.coords else ""


def _plt():
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path: Path, legends=(), **legend_kw) -> Path:
    """Lay out, place the legends of the axes ``legends`` clear of their data
    (:func:`~.layout.legend_clear_of_data`, once the panels have their final size), write."""
    from .layout import legend_clear_of_data

    fig.tight_layout()
    for ax in legends:
        legend_clear_of_data(ax, **({"fontsize": 8} | legend_kw))
    fig.savefig(path, dpi=130)
    _plt().close(fig)
    return path


def speed_text(v: float) -> str:
    """A speed [mm/s] for a title: three significant digits (a log range's 0.316228 is
    0.316)."""
    return f"{float(f'{float(v):.3g}'):g} mm/s"       # 1000, not 1e+03


def plot_law(ds: xr.Dataset, path: Path) -> Path | None:
    """Fig. 2: the effective law σ_hs(ū), with α_hs(ū) and Δτ_hs(ū), per speed."""
    if "law_mean_separation" not in ds:
        return None
    plt = _plt()
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.8))
    dim, speeds = law_speeds(ds)
    for v in speeds:
        at = {dim: v}
        u = ds["law_mean_separation"].sel(at).values
        p = ds["law_pressure"].values
        ok = _law_kept(ds, at, p.size)
        lbl = f"v = {speed_text(v)}" + (" (T_ref)" if dim == "law_velocity" else "")
        for ax, y in zip(axes, (p, ds["law_contact_fraction"].sel(at).values,
                                ds["law_shear_stress"].sel(at).values), strict=True):
            line, = ax.plot(u[ok], y[ok], "o-", label=lbl)
            # failed or excluded (non-monotone) FEM points: shown, not connected
            ax.plot(u[~ok], y[~ok], "x", color=line.get_color(), ms=8,
                    label="excluded" if (ax is axes[0] and (~ok).any()) else None)
    axes[0].set_yscale("log")
    for ax, yl in zip(axes, ("σ_hs [MPa]", "α_hs [-]", "Δτ_hs [MPa]"), strict=True):
        ax.set_xlabel("mean separation ū [mm]")
        ax.set_ylabel(yl)
        ax.grid(alpha=0.3)
    fig.suptitle("Effective interface law of the high-slope scale (FEM)")
    return _save(fig, path, legends=[axes[0]])


def _law_kept(ds: xr.Dataset, at: dict, n: int) -> np.ndarray:
    """Which FEM points of the law the law kept (failed and non-monotone ones are not)."""
    if "law_status" not in ds:
        return np.ones(n, bool)
    return ds["law_status"].sel(at).values == "ok"


def _label(ds: xr.Dataset, m: str, iv: int | None = None) -> str:
    """The model's name as the config spells it; the FEM's realizations when it ran on a
    subset; its eq. 28 error against the FEM at speed ``iv``."""
    label = str(m)
    if m == "fem" and "fem_realizations" in ds.attrs:
        label += f" ({ds.attrs['fem_realizations']} of {ds.sizes['realization']} + vhs CV)"
    if iv is not None and "error_vs_fem" in ds and m in ds["compared_model"].values:
        e = float(ds["error_vs_fem"].sel(compared_model=m)[iv])
        label += "" if np.isnan(e) else f", e = {100 * e:.1f} %"
    return label


def _friction_panels(ds: xr.Dataset, path: Path, x_of, xlabel: str, xlog: bool) -> Path:
    """One panel per speed: mean friction ± sd over realizations, one curve per model.

    With the FEM on a subset of the realizations its points are the control-variate
    estimates of its phase average (``*_phase_mean``), the error bars its own spread.
    """
    ds = isothermal_view(ds)
    if ds.sizes["pressure"] == 1:
        return _one_load_panel(ds, path, x_of, xlabel, xlog)
    shown = panel_indices(ds.sizes["velocity"])
    fig, axes = panel_grid(len(shown), (5.2, 4.4))
    mu = mean_of(ds, "friction")
    for ax, iv in zip(axes, shown, strict=True):
        v = ds["velocity"].values[iv]
        for m in ds["model"].values:
            sel = ds.sel(model=m, velocity=v)
            ax.errorbar(x_of(ds, m, v), mu.sel(model=m, velocity=v).values,
                        yerr=sel["friction_std"].values, fmt="o-", color=_COLORS.get(m),
                        label=_label(ds, m, iv), capsize=3)
        if xlog:
            ax.set_xscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("friction coefficient μ [-]")
        title = f"v = {speed_text(v)}{_at_temperature(ds)}"
        if "error_vs_fem" in ds:
            title += f"\ne: eq. 28 error vs fem{_error_basis(ds)}"
        ax.set_title(title, fontsize=9)
        ax.grid(alpha=0.3)
    return _save(fig, path, legends=axes)


#: Markers of the speeds in a one-load figure.
_SPEED_MARKERS = ("o", "s", "^", "D")


def _one_load_panel(ds: xr.Dataset, path: Path, x_of, xlabel: str, xlog: bool) -> Path:
    """A run at one load: every speed in one panel (one point per model and speed, the
    speed by its marker) instead of one-point panels."""
    from matplotlib.lines import Line2D

    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    mu = mean_of(ds, "friction")
    shown = panel_indices(ds.sizes["velocity"])
    for k, iv in enumerate(shown):
        v = ds["velocity"].values[iv]
        for m in ds["model"].values:
            ax.errorbar(x_of(ds, m, v), mu.sel(model=m, velocity=v).values,
                        yerr=ds["friction_std"].sel(model=m, velocity=v).values,
                        fmt=_SPEED_MARKERS[k], color=_COLORS.get(m), capsize=3)
    handles = [Line2D([], [], color=_COLORS.get(m), marker="o", ls="",
                      label=_label(ds, m, shown[0] if len(shown) == 1 else None))
               for m in ds["model"].values]
    handles += [Line2D([], [], color="0.4", marker=_SPEED_MARKERS[k], ls="",
                       label=f"v = {speed_text(ds['velocity'].values[iv])}")
                for k, iv in enumerate(shown)]
    if xlog:
        ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("friction coefficient μ [-]")
    ax.set_title(f"σ0 = {float(ds['pressure'][0]):.3g} MPa{_at_temperature(ds)}", fontsize=9)
    ax.grid(alpha=0.3)
    return _save(fig, path, legends=[ax], handles=handles)


def plot_friction_vs_area(ds: xr.Dataset, path: Path) -> Path:
    """Fig. 5: friction vs normalized contact area, all models, one panel per speed."""
    area = mean_of(isothermal_view(ds), "contact_fraction")
    return _friction_panels(ds, path, lambda ds, m, v: area.sel(model=m, velocity=v).values,
                            "normalized contact area A_c/A_0 [-]", xlog=False)


def plot_friction_vs_pressure(ds: xr.Dataset, path: Path) -> Path:
    """Fig. 9: friction vs mean pressure, all models (mean ± sd over realizations)."""
    return _friction_panels(ds, path, lambda ds, m, v: ds["pressure"].values,
                            "mean pressure σ0 [MPa]", xlog=True)


def plot_high_slope_friction(ds: xr.Dataset, path: Path) -> Path | None:
    """Fig. 7: friction vs pressure on the high-slope scale alone, VHS vs FEM."""
    if "law_friction" not in ds:
        return None
    dim, speeds = law_speeds(ds)
    fig, axes = panel_grid(len(speeds), (5.2, 4.0))
    for ax, v in zip(axes, speeds, strict=True):
        p = ds["law_pressure"].values
        mu = ds["law_friction"].sel({dim: v}).values
        kept = _law_kept(ds, {dim: v}, p.size)
        ax.plot(p[kept], mu[kept], "o-", color="black", label="FEM (the law)")
        if (~kept).any():
            ax.plot(p[~kept], mu[~kept], "x", color="black", ms=9,
                    label="FEM, excluded from the law")
        if "law_vhs_friction" in ds:
            ax.plot(p, ds["law_vhs_friction"].sel({dim: v}), "s--", color="tab:red",
                    label="VHS")
        if (np.nan_to_num(mu) < 0).any():
            ax.axhline(0.0, color="0.3", lw=0.8)
            ax.plot(p[mu < 0], mu[mu < 0], "v", color="tab:orange", ms=9, ls="",
                    label="μ_hs < 0 (the wave pushes)")
        ax.set_xscale("log")
        ax.set_xlabel("mean pressure p̄ [MPa]")
        ax.set_ylabel("friction coefficient μ_hs [-]")
        ax.set_title(f"high-slope scale, v = {speed_text(v)}", fontsize=10)
        ax.grid(alpha=0.3)
    return _save(fig, path, legends=axes)


def plot_pressure_profiles(ds: xr.Dataset, path: Path) -> Path | None:
    """Fig. 8: contact pressure along the surface (realization 0), every model of the run
    that stores a profile (the half-space ones)."""
    keys = {m: f"pressure_profile_{m}" for m in ds["model"].values
            if f"pressure_profile_{m}" in ds}
    if not keys:
        return None
    plt = _plt()
    ds = isothermal_view(ds)
    shown = panel_indices(ds.sizes["velocity"])
    fig, axes = plt.subplots(len(shown), 1, figsize=(9, 3.2 * len(shown)), squeeze=False)
    x = ds["x"].values
    period = x[-1] + (x[1] - x[0])
    ip = ds.sizes["pressure"] // 2
    for ax, iv in zip(axes[:, 0], shown, strict=True):
        v = ds["velocity"].values[iv]
        # dashes: the hybrids share one low-slope solve, and their profiles coincide
        for (m, k), ls in zip(keys.items(), ("-", "--", "-.", ":", "-", "--"), strict=False):
            ax.plot(x / period, ds[k].isel(velocity=iv, pressure=ip), color=_COLORS.get(m),
                    lw=0.8, ls=ls, label=m)
        ax.set_xlabel("x / L0 [-]")
        ax.set_ylabel("contact pressure [MPa]")
        ax.set_title(f"v = {speed_text(v)}, σ0 = {float(ds['pressure'][ip]):.3g} MPa"
                     f"{_at_temperature(ds)}", fontsize=10)
        ax.grid(alpha=0.3)
        if "heights" in ds:
            ax2 = ax.twinx()
            ax2.plot(x / period, ds["heights"].values, color="0.6", lw=0.6)
            ax2.set_ylabel("surface height [mm]", color="0.5")
            ax.set_zorder(ax2.get_zorder() + 1)     # the pressures and legend over the surface
            ax.patch.set_visible(False)
    return _save(fig, path, legends=list(axes[:, 0]))


def plot_all(ds: xr.Dataset, directory: str | Path) -> list[Path]:
    """Write every figure that the dataset supports into ``directory``; return their paths."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    from .speed import plot_contact_vs_speed, plot_friction_vs_speed, plot_friction_vs_temperature

    out = [
        plot_law(ds, directory / "fig2_law.png"),
        plot_friction_vs_area(ds, directory / "fig5_friction_vs_area.png"),
        plot_high_slope_friction(ds, directory / "fig7_high_slope_friction.png"),
        plot_pressure_profiles(ds, directory / "fig8_pressure_profiles.png"),
        plot_friction_vs_pressure(ds, directory / "fig9_friction_vs_pressure.png"),
        plot_friction_vs_speed(ds, directory / "friction_vs_speed.png"),
        plot_contact_vs_speed(ds, directory / "contact_vs_speed.png"),
        plot_friction_vs_temperature(ds, directory / "friction_vs_temperature.png"),
    ]
    return [p for p in out if p is not None]
