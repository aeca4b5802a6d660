"""Height maps on the command line: ``rubbercontact roughness map FILE`` and the map of
``rubbercontact halfspace --map FILE``.

A map file is read by :func:`rubbercontact.io.mapload.load_map` (the map runs' loader too:
text grids, ``.npy``, instrument files through SurfaceTopography), its mean or
least-squares plane removed, and made one period for the FFT (mirrored, or taken as one
period as it is for a map that is periodic already, e.g. a synthetic one). The statistics
are those of :mod:`rubbercontact.roughness.mapstats` and the octave bands of
:func:`rubbercontact.roughness.octave_bands`, on the periodized map.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Literal

import numpy as np
import typer

from ..errors import InputError
from ..io.mapload import load_map


def map_report(hmap, periodic, m2_threshold: float = 1.0) -> dict:
    """Statistics of a map (real space: ``hmap``; spectral bands: its ``periodic`` version).

    Keys: ``shape`` (ny, nx), ``lengths_mm`` (Ly, Lx), ``dx_mm``, ``dy_mm``, ``unit`` (of the
    file), ``rms_height_mm``, ``rms_gradient``, ``rms_slope_x``, ``anisotropy``,
    ``anisotropy_angle_deg``, ``periodized``, ``threshold`` and ``bands`` (per octave band:
    ``wavelength_mm``, ``rms_slope_x``, ``rms_gradient``, ``variance_mm2``, ``high_slope``).
    """
    from ..roughness.mapsplit import octave_bands
    from ..roughness.mapstats import anisotropy, rms_gradient, rms_height, rms_slope_x

    ratio, angle = anisotropy(hmap)
    bands = octave_bands(periodic, m2_threshold)
    rows = [{"wavelength_mm": float(bands["wavelength"][i]),
             "rms_slope_x": float(bands["rms_slope_x"][i]),
             "rms_gradient": float(bands["rms_gradient"][i]),
             "variance_mm2": float(bands["variance"][i]),
             "high_slope": bool(bands["high_slope"][i])} for i in range(bands.sizes["band"])]
    return {"source": {k: hmap.source.get(k) for k in ("path", "sha256", "format", "unit")},
            "shape": list(hmap.shape), "lengths_mm": list(hmap.lengths),
            "dx_mm": hmap.dx, "dy_mm": hmap.dy, "unit": hmap.source.get("unit", "mm"),
            "rms_height_mm": rms_height(hmap), "rms_gradient": rms_gradient(hmap),
            "rms_slope_x": rms_slope_x(hmap), "anisotropy": ratio,
            "anisotropy_angle_deg": float(np.degrees(angle)),
            "periodized": periodic.source.get("periodize", "periodic already"),
            "threshold": float(bands.attrs["threshold"]), "bands": rows}


def format_report(rep: dict) -> str:
    """The report of :func:`map_report` as text."""
    ny, nx = rep["shape"]
    ly, lx = rep["lengths_mm"]
    lines = [f"map {rep['source'].get('path')}: {ny} x {nx} points (y x x), "
             f"{ly:.5g} x {lx:.5g} mm, dx = {rep['dx_mm']:.5g} mm, dy = {rep['dy_mm']:.5g} mm "
             f"(file unit {rep['unit']})",
             f"rms height      {rep['rms_height_mm']:.5g} mm",
             f"rms gradient    {rep['rms_gradient']:.5g}",
             f"rms slope (x)   {rep['rms_slope_x']:.5g}   (x: sliding direction)",
             f"anisotropy      {rep['anisotropy']:.4g} (steepest at "
             f"{rep['anisotropy_angle_deg']:.0f} deg from x)",
             f"octave bands (periodized: {rep['periodized']}; high-slope: rms slope along x "
             f"> {rep['threshold']:g}):",
             f"{'band':>5} {'lambda [mm]':>12} {'slope x':>9} {'gradient':>9} "
             f"{'variance [mm2]':>15} {'high':>5}"]
    for i, b in enumerate(rep["bands"]):
        lines.append(f"{i:5d} {b['wavelength_mm']:12.5g} {b['rms_slope_x']:9.4f} "
                     f"{b['rms_gradient']:9.4f} {b['variance_mm2']:15.4e} "
                     f"{'yes' if b['high_slope'] else '':>5}")
    return "\n".join(lines)


def stats_command(
    file: Path = typer.Argument(..., help="Map file: text grid, .npy, or an instrument "
                                "file (x3p, sur, ...) with the topography extra."),
    fmt: Literal["auto", "text", "npy", "topography"] = typer.Option(
        "auto", "--format", help="File format (auto: by extension)."),
    unit: str | None = typer.Option(None, "--unit", help="Unit of heights and dx when the "
                                    "file does not state it: mm (default), um, nm or m."),
    dx: float | None = typer.Option(None, "--dx", help="Pixel size (in --unit) when the "
                                    "file does not state it (.npy)."),
    nan: Literal["error", "fill"] = typer.Option("error", "--nan", help="Dropouts: error "
                                                 "or harmonic fill."),
    detrend: Literal["plane", "mean", "none"] | None = typer.Option(
        None, "--detrend", help="plane, mean or none (default: plane when mirrored, mean "
        "for a map that is one period already)."),
    periodize: Literal["mirror", "none"] = typer.Option(
        "mirror", "--periodize", help="mirror (a measured map) or none (the map is one "
        "period already)."),
    m2_threshold: float = typer.Option(1.0, "--m2-threshold", help="A band whose rms "
                                       "slope along x exceeds this is high-slope."),
    as_json: bool = typer.Option(False, "--json", help="Print the report as JSON."),
) -> None:
    """Statistics of a height map: size, rms height and slopes, anisotropy, octave bands."""
    hmap, periodic = load_map(file, fmt=fmt, unit=unit, dx=dx, nan=nan, detrend=detrend,
                              periodize=periodize)
    # a map that is one period already gets its exact (spectral) slopes
    rep = map_report(periodic if periodize == "none" else hmap, periodic, m2_threshold)
    typer.echo(json.dumps(rep, indent=2) if as_json else format_report(rep))


def check_no_sine_options(**given) -> None:
    """One error line when a sine-series option is given together with ``--map``."""
    clash = [k for k, v in given.items() if v is not None]
    if clash:
        raise InputError(f"--map: a map replaces the sine-series surface; drop "
                         f"{', '.join('--' + k for k in clash)}")
