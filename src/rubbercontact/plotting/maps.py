"""Figures of a run on a height map (:mod:`rubbercontact.pipeline.maprun`), from its results:
the map, its spectrum with the scale split, the VHS contact map at one speed and load, and
μ and ``A_c/A_0`` against the load and against the speed, per model."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import xarray as xr

from .figures import _plt, _save, speed_text


def results_map(ds: xr.Dataset):
    """The periodic :class:`~rubbercontact.roughness.HeightMap` a map run's results hold."""
    from ..roughness import HeightMap

    info = json.loads(ds.attrs["surface"])
    return HeightMap(ds["heights"].values, tuple(info["lengths_mm"]), periodic=True,
                     source=info.get("map", {}))


def plot_height_map(ds: xr.Dataset, path: Path) -> Path:
    """The map's heights [µm] over x (sliding) and y [mm]."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5.6, 4.6))
    z = ds["heights"]
    im = ax.pcolormesh(ds["x"], ds["y"], 1e3 * (z - z.mean()), shading="auto", cmap="terrain")
    fig.colorbar(im, ax=ax, label="height z − <z> [µm]")
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm] (sliding)")
    ax.set_ylabel("y [mm]")
    info = json.loads(ds.attrs["surface"])
    ax.set_title(f"map {info['shape'][0]}×{info['shape'][1]}, rms gradient "
                 f"{info['rms_gradient']:.3g}", fontsize=10)
    return _save(fig, path)


def _binned_density(hmap, bins: int = 48) -> tuple[np.ndarray, np.ndarray]:
    """The isotropic average of the 2D PSD ``C(q)`` [mm⁴] in log bins of ``|q|`` [rad/mm]."""
    from ..roughness.mapstats import mode_power

    qx, qy, p = mode_power(hmap)
    q = np.hypot(qx, qy).ravel()
    c = (p / ((2 * np.pi) ** 2 / (hmap.lengths[0] * hmap.lengths[1]))).ravel()
    ok = q > 0
    edges = np.geomspace(q[ok].min(), q[ok].max() * 1.0001, bins + 1)
    idx = np.digitize(q[ok], edges) - 1
    n = np.bincount(idx, minlength=bins)[:bins]
    mean = np.bincount(idx, weights=c[ok], minlength=bins)[:bins] / np.maximum(n, 1)
    centre = np.sqrt(edges[:-1] * edges[1:])
    return centre[n > 0], mean[n > 0]


def plot_map_spectrum(ds: xr.Dataset, path: Path) -> Path:
    """The isotropic PSD with the high-slope octave bands shaded, and each band's rms slope
    along x against the threshold (the paper's split, :func:`~rubbercontact.roughness.
    octave_bands`)."""
    from ..roughness import octave_bands

    hmap = results_map(ds)
    thr = json.loads(ds.attrs["surface"])["m2_threshold"]
    bands = octave_bands(hmap, thr)
    plt = _plt()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    q, c = _binned_density(hmap)
    keep = c > 1e-12 * c.max()
    ax1.loglog(q[keep], c[keep], "k.-", ms=3, label="C(q), isotropic average")
    for qc, high in zip(bands["q_center"].values, bands["high_slope"].values, strict=True):
        if high:
            ax1.axvspan(qc / np.sqrt(2), qc * np.sqrt(2), color="C3", alpha=0.2, lw=0)
    ax1.set_xlabel("wavenumber |q| [rad/mm]")
    ax1.set_ylabel("C(q) [mm⁴]")
    ax1.set_title("spectrum (shaded: high-slope bands)", fontsize=10)
    colours = ["C3" if h else "C0" for h in bands["high_slope"].values]
    ax2.bar(np.arange(bands.sizes["band"]), bands["rms_slope_x"].values, color=colours)
    ax2.axhline(thr, color="k", ls="--", lw=1, label=f"threshold {thr:g}")
    ax2.set_xticks(np.arange(bands.sizes["band"]),
                   [f"{w:.3g}" for w in bands["wavelength"].values], rotation=45)
    ax2.set_xlabel("octave band: wavelength [mm]")
    ax2.set_ylabel("rms slope along x [-]")
    ax2.set_title("the split (red: high-slope)", fontsize=10)
    ax2.legend(fontsize=8)
    return _save(fig, path)


def draw_contact_map(x: np.ndarray, y: np.ndarray, pressure: np.ndarray, title: str,
                     path: Path) -> Path:
    """A contact pressure map [MPa] over ``x`` (sliding) and ``y`` [mm]."""
    plt = _plt()
    p = np.asarray(pressure)
    fig, ax = plt.subplots(figsize=(5.6, 4.6))
    im = ax.pcolormesh(x, y, np.where(p > 0, p, np.nan), shading="auto", cmap="magma_r")
    fig.colorbar(im, ax=ax, label="contact pressure σ [MPa]")
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm] (sliding)")
    ax.set_ylabel("y [mm]")
    ax.set_title(title, fontsize=9)
    return _save(fig, path)


def contact_title(velocity: float, mean_pressure: float, friction: float,
                  contact_fraction: float) -> str:
    """The title of a VHS contact map."""
    return (f"VHS, v = {speed_text(velocity)}, σ0 = {mean_pressure:g} MPa: "
            f"μ = {friction:.3f}, A/A0 = {contact_fraction:.3f}")


def plot_contact_map(ds: xr.Dataset, path: Path) -> Path | None:
    """The VHS contact pressure [MPa] at the kept speed and load (None without the VHS)."""
    if "contact_pressure" not in ds:
        return None
    a = ds["contact_pressure"].attrs
    return draw_contact_map(ds["x"], ds["y"], ds["contact_pressure"], contact_title(
        a["velocity"], a["mean_pressure"], a["friction"], a["contact_fraction"]), path)


def plot_map_friction(ds: xr.Dataset, path: Path) -> Path:
    """μ and ``A_c/A_0`` against the mean pressure, per model (colour) and speed (marker)."""
    return _against(ds, "pressure", "velocity", "mean pressure σ0 [MPa]",
                    lambda m, v: f"{m}, {speed_text(v)}", path, log=False)


def plot_map_speed(ds: xr.Dataset, path: Path) -> Path | None:
    """μ and ``A_c/A_0`` against the speed (log), per model (colour) and load (marker);
    None for a run at one speed."""
    if ds.sizes["velocity"] < 2:
        return None
    return _against(ds, "velocity", "pressure", "sliding speed v [mm/s]",
                    lambda m, p: f"{m}, σ0 = {p:g} MPa", path, log=True)


def _against(ds: xr.Dataset, along: str, per: str, xlabel: str, label, path: Path,
             log: bool) -> Path:
    """μ and ``A_c/A_0`` against ``along``, a curve per model (colour) and ``per`` value
    (marker); ``label(model, value)`` names a curve."""
    plt = _plt()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    marks = "osd^v<>p*h"
    for i, m in enumerate(ds["model"].values):
        for k, x in enumerate(ds[per].values):
            r = ds.sel({"model": m, per: x})
            kw = {"color": f"C{i}", "marker": marks[k % len(marks)], "ms": 4}
            ax1.plot(ds[along], r["friction"], label=label(m, x), **kw)
            ax2.plot(ds[along], r["contact_fraction"], **kw)
    ax1.set_ylabel("friction μ [-]")
    ax2.set_ylabel("contact area A_c/A_0 [-]")
    for ax in (ax1, ax2):
        if log:
            ax.set_xscale("log")
        ax.set_xlabel(xlabel)
        ax.grid(alpha=0.3, which="both" if log else "major")
    return _save(fig, path, legends=(ax1,))


def plot_map_run(ds: xr.Dataset, directory: str | Path) -> list[Path]:
    """Every figure of a map run into ``directory``; returns the files written."""
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    out = [plot_height_map(ds, d / "map.png"), plot_map_spectrum(ds, d / "map_spectrum.png"),
           plot_contact_map(ds, d / "contact_map.png"),
           plot_map_friction(ds, d / "map_friction.png"),
           plot_map_speed(ds, d / "map_speed.png")]
    return [p for p in out if p is not None]
