"""Figures of a results dataset, after the paper's Figs. 2, 5, 7, 8 and 9."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from ..hybrid.pipeline import mean_of

_COLORS = {"vhs": "tab:red", "hybrid": "tab:blue", "hybrid-windowed": "tab:green",
           "fem": "black"}
_LABELS = {"vhs": "VHS (half-space only)", "hybrid": "hybrid multiscale",
           "hybrid-windowed": "hybrid, law at λ_hs-averaged pressure", "fem": "FEM (full)"}


def _plt():
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path: Path) -> Path:
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    _plt().close(fig)
    return path


def plot_law(ds: xr.Dataset, path: Path) -> Path | None:
    """Fig. 2: the effective law σ_hs(ū), with α_hs(ū) and Δτ_hs(ū), per speed."""
    if "law_mean_separation" not in ds:
        return None
    plt = _plt()
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.8))
    for v in ds["velocity"].values:
        u = ds["law_mean_separation"].sel(velocity=v).values * 1e3
        p = ds["law_pressure"].values
        ok = (ds["law_status"].sel(velocity=v).values == "ok" if "law_status" in ds
              else np.ones(p.size, bool))
        lbl = f"v = {v:g} mm/s"
        for ax, y in zip(axes, (p, ds["law_contact_fraction"].sel(velocity=v).values,
                                ds["law_shear_stress"].sel(velocity=v).values), strict=True):
            line, = ax.plot(u[ok], y[ok], "o-", label=lbl)
            # failed or excluded (non-monotone) FEM points: shown, not connected
            ax.plot(u[~ok], y[~ok], "x", color=line.get_color(), ms=8,
                    label="excluded" if (ax is axes[0] and (~ok).any()) else None)
    axes[0].set_yscale("log")
    for ax, yl in zip(axes, ("σ_hs [MPa]", "α_hs [-]", "Δτ_hs [MPa]"), strict=True):
        ax.set_xlabel("mean separation ū [µm]")
        ax.set_ylabel(yl)
        ax.grid(alpha=0.3)
    axes[0].legend()
    fig.suptitle("Effective interface law of the high-slope scale (FEM)")
    return _save(fig, path)


def _label(ds: xr.Dataset, m: str) -> str:
    label = _LABELS.get(m, m)
    if m == "fem" and "fem_realizations" in ds.attrs:
        label += (f", {ds.attrs['fem_realizations']} of {ds.sizes['realization']} "
                  "realizations + VHS control variate")
    return label


def _friction_panels(ds: xr.Dataset, path: Path, x_of, xlabel: str, xlog: bool) -> Path:
    """One panel per speed: mean friction ± sd over realizations, one curve per model.

    With the FEM on a subset of the realizations its points are the control-variate
    estimates of its phase average (``*_phase_mean``), the error bars its own spread.
    """
    plt = _plt()
    nv = ds.sizes["velocity"]
    fig, axes = plt.subplots(1, nv, figsize=(5.2 * nv, 4), squeeze=False)
    mu = mean_of(ds, "friction")
    for iv, v in enumerate(ds["velocity"].values):
        ax = axes[0, iv]
        for m in ds["model"].values:
            sel = ds.sel(model=m, velocity=v)
            ax.errorbar(x_of(ds, m, v), mu.sel(model=m, velocity=v).values,
                        yerr=sel["friction_std"].values, fmt="o-", color=_COLORS.get(m),
                        label=_label(ds, m), capsize=3)
        if xlog:
            ax.set_xscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("friction coefficient μ [-]")
        title = f"v = {v:g} mm/s"
        if "error_vs_fem" in ds:
            parts = [f"e({m}) = {100 * float(ds['error_vs_fem'].sel(compared_model=m)[iv]):.1f} %"
                     for m in ds["compared_model"].values]
            title += "\n" + ", ".join(parts) + _error_basis(ds)
        ax.set_title(title, fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    return _save(fig, path)


def plot_friction_vs_area(ds: xr.Dataset, path: Path) -> Path:
    """Fig. 5: friction vs normalized contact area, all models, one panel per speed."""
    area = mean_of(ds, "contact_fraction")
    return _friction_panels(ds, path, lambda ds, m, v: area.sel(model=m, velocity=v).values,
                            "normalized contact area A_c/A_0 [-]", xlog=False)


def _error_basis(ds: xr.Dataset) -> str:
    """``" at equal σ0"`` / ``" at equal A_c"``: what ``error_vs_fem`` compares over
    (empty for files written before the attribute existed)."""
    over = ds["error_vs_fem"].attrs.get("compared_over")
    return {"pressure": " at equal σ0", "contact_area": " at equal A_c"}.get(over, "")


def plot_friction_vs_pressure(ds: xr.Dataset, path: Path) -> Path:
    """Fig. 9: friction vs mean pressure, all models (mean ± sd over realizations)."""
    return _friction_panels(ds, path, lambda ds, m, v: ds["pressure"].values,
                            "mean pressure σ0 [MPa]", xlog=True)


def plot_high_slope_friction(ds: xr.Dataset, path: Path) -> Path | None:
    """Fig. 7: friction vs pressure on the high-slope scale alone, VHS vs FEM."""
    if "law_friction" not in ds:
        return None
    plt = _plt()
    nv = ds.sizes["velocity"]
    fig, axes = plt.subplots(1, nv, figsize=(5.2 * nv, 4), squeeze=False)
    for iv, v in enumerate(ds["velocity"].values):
        ax = axes[0, iv]
        p = ds["law_pressure"].values
        ax.plot(p, ds["law_friction"].sel(velocity=v), "o-", color="black", label="FEM")
        if "law_vhs_friction" in ds:
            ax.plot(p, ds["law_vhs_friction"].sel(velocity=v), "s--", color="tab:red",
                    label="VHS")
        ax.set_xscale("log")
        ax.set_xlabel("mean pressure p̄ [MPa]")
        ax.set_ylabel("friction coefficient μ_hs [-]")
        ax.set_title(f"high-slope scale, v = {v:g} mm/s")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    return _save(fig, path)


def plot_pressure_profiles(ds: xr.Dataset, path: Path) -> Path | None:
    """Fig. 8: contact pressure along the surface (realization 0), hybrid and VHS."""
    keys = [k for k in ("pressure_profile_hybrid", "pressure_profile_vhs") if k in ds]
    if not keys:
        return None
    plt = _plt()
    nv = ds.sizes["velocity"]
    fig, axes = plt.subplots(nv, 1, figsize=(9, 3.2 * nv), squeeze=False)
    x = ds["x"].values
    period = x[-1] + (x[1] - x[0])
    ip = ds.sizes["pressure"] // 2
    for iv, v in enumerate(ds["velocity"].values):
        ax = axes[iv, 0]
        for k in keys:
            m = k.rsplit("_", 1)[-1]
            ax.plot(x / period, ds[k].isel(velocity=iv, pressure=ip), color=_COLORS.get(m),
                    lw=0.8, label=_LABELS.get(m, m))
        ax.set_xlabel("x / L0 [-]")
        ax.set_ylabel("contact pressure [MPa]")
        ax.set_title(f"v = {v:g} mm/s, σ0 = {float(ds['pressure'][ip]):.3g} MPa")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        if "heights" in ds:
            ax2 = ax.twinx()
            ax2.plot(x / period, ds["heights"].values * 1e3, color="0.6", lw=0.6)
            ax2.set_ylabel("surface height [µm]", color="0.5")
    return _save(fig, path)


def plot_all(ds: xr.Dataset, directory: str | Path) -> list[Path]:
    """Write every figure that the dataset supports into ``directory``; return their paths."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    out = [
        plot_law(ds, directory / "fig2_law.png"),
        plot_friction_vs_area(ds, directory / "fig5_friction_vs_area.png"),
        plot_high_slope_friction(ds, directory / "fig7_high_slope_friction.png"),
        plot_pressure_profiles(ds, directory / "fig8_pressure_profiles.png"),
        plot_friction_vs_pressure(ds, directory / "fig9_friction_vs_pressure.png"),
    ]
    return [p for p in out if p is not None]


def summary_table(ds: xr.Dataset) -> str:
    """Plain-text summary: mean friction and area per model, speed and load; eq. 28 errors."""
    lines = []
    has_area = "friction_at_area_mean" in ds
    mu, area = mean_of(ds, "friction"), mean_of(ds, "contact_fraction")
    if "fem_realizations" in ds.attrs:
        lines.append(f"fem ran on {ds.attrs['fem_realizations']} of {ds.sizes['realization']} "
                     "realizations: its mu and A are phase averages estimated with the VHS "
                     "as control variate, mean_N(vhs) + mean_R(fem - vhs)")
    for v in ds["velocity"].values:
        lines.append(f"v = {v:g} mm/s")
        wid = {m: max(10, len(m) + 3) for m in ds["model"].values}
        lines.append(f"  {'sigma0 [MPa]':>12} " + " ".join(
            f"{m + ' mu':>{wid[m]}} {m + ' A':>{wid[m] - 1}}" for m in ds["model"].values))
        for p in ds["pressure"].values:
            row = [f"  {p:12.4g}"]
            for m in ds["model"].values:
                at = {"model": m, "velocity": v, "pressure": p}
                row.append(f"{float(mu.sel(at)):{wid[m]}.4f} "
                           f"{float(area.sel(at)):{wid[m] - 1}.4f}")
            lines.append(" ".join(row))
        if has_area:
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
                lines.append(f"  eq. 28 error of {m} vs FEM{_error_basis(ds)}: "
                             f"{'n/a' if np.isnan(e) else f'{100 * e:.1f} %'}")
    return "\n".join(lines)
