"""``rubbercontact halfspace``: one viscoelastic half-space steady-sliding solve (paper §2.3).

Options or a TOML file (options override the file). TOML keys::

    surface = "section3"            # preset: asphalt_ac8, section3, high_slope_wave
    # or: [surface] wavelengths = [...], amplitudes = [...], phases = [...]
    material = "sbr"                # or "elastic" with modulus = 10.0 (MPa), or a Prony file
    velocity = 10.0                 # mm/s (or velocities = [1, 10, 100] to sweep)
    pressure = 0.3                  # MPa
    law = "lennard-jones"           # (default) or "hard-wall", as halfspace.law in a run
    n = 4096
    nu = 0.5
    period = 0.25                   # mm, optional
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import typer

from ..errors import InputError
from ..inputs import SURFACE_PRESETS

#: The wall laws, by their config names (halfspace.law), and the older spellings.
_LAWS = {"lennard-jones": "lennard-jones", "lj": "lennard-jones", "hard-wall": "hard-wall",
         "hardwall": "hard-wall", "none": "hard-wall"}


def _floats(name: str, text: str | None) -> list[float] | None:
    if text is None:
        return None
    try:
        vals = [float(t) for t in str(text).replace(";", ",").split(",") if t.strip()]
    except ValueError:
        raise InputError(f"{name}: expected comma-separated numbers, got {text!r}") from None
    if not vals:
        raise InputError(f"{name}: no numbers in {text!r}")
    return vals


def _load_toml(path: Path) -> dict:
    import tomllib
    if not path.exists():
        raise FileNotFoundError(f"config: file not found: {path}")
    try:
        with open(path, "rb") as fh:
            data = tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"config: {path} is not valid TOML ({exc})") from None
    data = data.get("halfspace", data)
    known = {"surface", "material", "modulus", "velocity", "velocities", "pressure", "law", "n",
             "nu", "period", "phases"}
    unknown = set(data) - known
    if unknown:
        raise InputError(f"config: unknown key(s) {sorted(unknown)}; known: {sorted(known)}")
    return data


def _surface(spec, wavelengths, amplitudes, phases):
    from ..inputs import surface_from_value

    if wavelengths is not None or amplitudes is not None:
        if wavelengths is None or amplitudes is None:
            raise InputError("surface: give both --wavelengths and --amplitudes")
        spec = {"wavelengths": wavelengths, "amplitudes": amplitudes}
    return surface_from_value(spec, default="section3", phases=phases)


def _material(name, modulus: float | None, base_dir=None):
    from ..inputs import material_from_value

    return material_from_value(name, modulus=modulus, base_dir=base_dir)


def _law(name: str):
    from ..halfspace import LennardJonesRepulsion

    if name not in _LAWS:
        raise InputError(f"law: expected 'lennard-jones' or 'hard-wall', got {name!r}")
    return LennardJonesRepulsion() if _LAWS[name] == "lennard-jones" else None


def _summary(res) -> dict:
    return {"velocity": res.velocity, "mean_pressure": res.mean_pressure,
            "friction": res.friction, "friction_ls": res.friction_ls,
            "friction_hs": res.friction_hs, "contact_fraction": res.contact_fraction,
            "mean_separation": res.mean_separation, "iterations": res.iterations,
            "residual": res.residual, "converged": res.converged, "method": res.method,
            "elapsed_s": res.elapsed}


def _plot_profile(res, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if res.y is not None:      # a map: its contact pressure
        from ..plotting.maps import contact_title, draw_contact_map

        draw_contact_map(res.x, res.y, res.pressure, contact_title(
            res.velocity, res.mean_pressure, res.friction, res.contact_fraction), path)
        return
    fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
    ax1.plot(res.x, res.pressure, color="C3")
    ax1.set_ylabel("pressure σ [MPa]")
    ax1.set_title(f"v = {res.velocity:g} mm/s, σ0 = {res.mean_pressure:g} MPa, "
                  f"μ = {res.friction:.4f}, A/A0 = {res.contact_fraction:.3f}")
    ax2.plot(res.x, res.heights, color="k", label="rigid surface z")
    ax2.plot(res.x, res.heights + res.separation, color="C0", label="rubber surface z + u")
    ax2.set_xlabel("x [mm]")
    ax2.set_ylabel("height [mm]")
    ax2.legend(loc="best", fontsize="small")
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)


def _plot_sweep(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    v = [r["velocity"] for r in rows]
    mu = [r["friction"] for r in rows]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(v, mu, "o-")
    ax.set_xscale("log")
    if all(m > 0 for m in mu):
        ax.set_yscale("log")
    ax.set_xlabel("sliding speed v [mm/s]")
    ax.set_ylabel("friction μ [-]")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)


def command(
    config: Path | None = typer.Option(None, "--config", help="TOML file with the case."),
    surface: str | None = typer.Option(None, "--surface",
                                       help=f"Preset surface: {', '.join(SURFACE_PRESETS)}."),
    wavelengths: str | None = typer.Option(None, "--wavelengths",
                                           help="Comma-separated wavelengths [mm]."),
    amplitudes: str | None = typer.Option(None, "--amplitudes",
                                          help="Comma-separated amplitudes [mm]."),
    phases: str | None = typer.Option(None, "--phases", help="Comma-separated phases [rad]."),
    period: float | None = typer.Option(None, "--period",
                                        help="Periodic length [mm] (default: longest λ)."),
    material: str | None = typer.Option(None, "--material", help="sbr (Table 1), elastic "
                                        "(with --modulus), or a Prony TOML/CSV file."),
    modulus: float | None = typer.Option(None, "--modulus", help="Young's modulus E [MPa] "
                                         "of an elastic material."),
    velocity: float | None = typer.Option(None, "--velocity", help="Sliding speed [mm/s]."),
    velocities: str | None = typer.Option(None, "--velocities",
                                          help="Sweep: comma-separated speeds [mm/s]."),
    pressure: float | None = typer.Option(None, "--pressure", help="Mean pressure σ0 [MPa]."),
    law: str | None = typer.Option(None, "--law", help="lennard-jones (default) or "
                                   "hard-wall."),
    n: int | None = typer.Option(None, "--n", help="Grid points (default 4096)."),
    nu: float | None = typer.Option(None, "--nu", help="Poisson's ratio (default 0.5)."),
    as_json: bool = typer.Option(False, "--json", help="Machine-readable output."),
    plot: Path | None = typer.Option(None, "--plot", help="Write a PNG: pressure and "
                                     "deformed profile, the contact map of a map (or μ(v) "
                                     "for a sweep)."),
    map_file: Path | None = typer.Option(None, "--map", help="Solve on a height map file "
                                         "(text grid, .npy, x3p, ...) instead of a sine "
                                         "series; sliding along its x."),
    map_dx: float | None = typer.Option(None, "--map-dx", help="Pixel size [mm] of a map "
                                        "file that does not state it (.npy)."),
    periodize: str = typer.Option("mirror", "--periodize", help="Map: mirror (a measured "
                                  "map) or none (one period already, e.g. synthetic)."),
    map_nan: str = typer.Option("error", "--map-nan", help="Map dropouts (NaN): error or "
                                "fill (harmonic fill, as roughness map --nan)."),
) -> None:
    """Solve steady sliding of a rigid sine-series surface (or a height map) on the
    viscoelastic half-space."""
    from ..halfspace import solve_sliding

    cfg = _load_toml(config) if config is not None else {}
    if map_file is not None:
        from .mapcli import check_no_sine_options, load_map

        check_no_sine_options(surface=surface, wavelengths=wavelengths,
                              amplitudes=amplitudes, phases=phases, period=period, n=n)
        if periodize not in ("mirror", "none"):
            raise InputError(f"--periodize: expected 'mirror' or 'none', got {periodize!r}")
        if map_nan not in ("error", "fill"):
            raise InputError(f"--map-nan: expected 'error' or 'fill', got {map_nan!r}")
        hmap = load_map(map_file, dx=map_dx, nan=map_nan, periodize=periodize)[1]
    ph = _floats("phases", phases) if phases is not None else cfg.get("phases")
    surf = None if map_file is not None else _surface(
        surface or cfg.get("surface"), _floats("wavelengths", wavelengths),
        _floats("amplitudes", amplitudes), ph)
    mat = _material(material or cfg.get("material", "sbr"),
                    modulus if modulus is not None else cfg.get("modulus"),
                    base_dir=config.parent if config is not None else None)
    the_law = _law(law or cfg.get("law", "lennard-jones"))
    p0 = pressure if pressure is not None else cfg.get("pressure")
    if p0 is None:
        raise InputError("pressure: give --pressure σ0 [MPa] (or 'pressure' in the config)")
    sweep = _floats("velocities", velocities) if velocities is not None else cfg.get("velocities")
    if sweep is None:
        v = velocity if velocity is not None else cfg.get("velocity")
        if v is None:
            raise InputError("velocity: give --velocity [mm/s] or --velocities for a sweep")
        sweep_list = [float(v)]
    else:
        sweep_list = [float(s) for s in sweep]
    from ..pipeline.limits import check_pressures, check_velocity

    check_pressures([p0], mat, "mean_pressure")
    for v in sweep_list:
        check_velocity(v, "velocity")
    kw = {"period": period if period is not None else cfg.get("period"),
          "n": n if n is not None else cfg.get("n", 4096),
          "nu": nu if nu is not None else cfg.get("nu", 0.5)}
    if map_file is not None:
        from ..hybrid.maps import solve_map

        results = [solve_map(hmap, mat, v, p0, the_law, nu=kw["nu"]) for v in sweep_list]
    else:
        results = [solve_sliding(surf, kw["period"], mat, v, p0, law=the_law, n=kw["n"],
                                 nu=kw["nu"]) for v in sweep_list]
    rows = [_summary(r) for r in results]
    from ..validity.halfspace import resolution_note

    notes = [resolution_note(r) for r in results]
    for row, note in zip(rows, notes, strict=True):
        row["validity"] = "" if note is None else note.text
    if as_json:
        typer.echo(json.dumps(rows[0] if len(rows) == 1 and sweep is None else rows, indent=2))
    else:
        typer.echo(f"{'v [mm/s]':>12} {'sigma0 [MPa]':>12} {'mu':>10} {'A/A0':>8} "
                   f"{'u_mean [mm]':>12} {'its':>5}")
        for r in rows:
            typer.echo(f"{r['velocity']:12.4g} {r['mean_pressure']:12.4g} {r['friction']:10.5f} "
                       f"{r['contact_fraction']:8.4f} {r['mean_separation']:12.4e} "
                       f"{r['iterations']:5d}")
        for note in notes:
            if note is not None:
                typer.echo(f"note: {note.text}")
    if plot is not None:
        if len(results) > 1:
            _plot_sweep(rows, plot)
        else:
            _plot_profile(results[0], plot)
        if not as_json:
            typer.echo(f"plot written to {plot}")
    if any(not math.isfinite(r["friction"]) for r in rows):  # pragma: no cover - defensive
        raise typer.Exit(1)
