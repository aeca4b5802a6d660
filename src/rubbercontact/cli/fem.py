"""``rubbercontact fem``: one FEM micromechanical sliding test (paper §2.4, Fig. 4).

Options or a TOML file (``--config``) with the keys ``surface`` (a preset name,
default ``"high_slope_wave"``, or a table ``{wavelengths, amplitudes, phases}``),
``material`` (``"sbr"``, a Prony file path, or a ``[material]`` table as in a run config;
both parsed by :mod:`rubbercontact.inputs`), ``mean_pressure``, ``velocity``,
``mesh = [nx, ny]``,
``solver``, ``height_ratio``, ``grading``, ``contact_points``, ``history_order``, and for
the transient solver ``periods``, ``steps_per_period``, ``viscous_model``.
Command-line options override
the file.
"""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import numpy as np
import typer

from ..errors import InputError

_KEYS = {"surface", "material", "mean_pressure", "velocity", "mesh", "solver", "height_ratio",
         "periods", "steps_per_period", "grading", "contact_points", "history_order",
         "viscous_model"}


def _surface(spec):
    from ..inputs import surface_from_value

    return surface_from_value(spec, default="high_slope_wave")


def _material(spec):
    from ..inputs import material_from_value

    return material_from_value(spec)


def _mesh(text):
    if isinstance(text, list | tuple):
        return tuple(text)
    if str(text).lower() == "auto":        # from the surface (rubbercontact.fem.resolution)
        return "auto"
    try:
        nx, ny = (int(v) for v in str(text).lower().split("x"))
    except ValueError:
        raise InputError(f"mesh: expected NXxNY such as 120x90, or auto, got "
                         f"{text!r}") from None
    return nx, ny


def command(
    config: Path | None = typer.Option(None, "--config", "-c", help="TOML file with the "
                                       "test parameters (options override it)."),
    pressure: float | None = typer.Option(None, "--pressure", "-p",
                                          help="Mean pressure p̄ (MPa) [1.0]."),
    velocity: float | None = typer.Option(None, "--velocity", "-v",
                                          help="Sliding speed v (mm/s) [10.0]; 0 = static."),
    surface: str | None = typer.Option(None, "--surface", help="Preset: high_slope_wave "
                                       "(default), section3, asphalt_ac8."),
    wavelength: list[float] | None = typer.Option(None, "--wavelength", help="Sine "
                                                  "wavelength (mm), repeatable."),
    amplitude: list[float] | None = typer.Option(None, "--amplitude", help="Sine amplitude "
                                                 "(mm), one per --wavelength."),
    material: str | None = typer.Option(None, "--material", help="'sbr' (Table 1, default) "
                                        "or a Prony TOML/CSV file."),
    mesh: str | None = typer.Option(None, "--mesh", help="Elements NXxNY, or 'auto' (from "
                                    "the surface's shortest wave) [120x90]."),
    solver: str | None = typer.Option(None, "--solver", help="steady (the steady state "
                                      "directly) or transient (time-stepped) [steady]."),
    height_ratio: float | None = typer.Option(None, "--height-ratio",
                                              help="Cell height / width [0.75]."),
    periods: int | None = typer.Option(None, "--periods", help="Transient: maximum sliding "
                                       "periods [6]."),
    steps_per_period: int | None = typer.Option(None, "--steps-per-period",
                                                help="Transient: steps per period [NX]."),
    grading: float | None = typer.Option(None, "--grading", help="Top/bottom element height "
                                         "ratio (> 1 refines toward the contact face) [1]."),
    contact_points: int | None = typer.Option(None, "--contact-points", help="Contact points "
                                              "per face segment (1: node-to-surface) [4]."),
    history_order: int | None = typer.Option(None, "--history-order", help="Time "
                                             "interpolation of the viscous history: 2 "
                                             "quadratic, 1 linear [2]."),
    viscous_model: str | None = typer.Option(None, "--viscous-model", help="Finite-strain "
                                             "viscoelasticity: simo or reese-govindjee "
                                             "[simo]."),
    plot: Path | None = typer.Option(None, "--plot", help="Write a figure (PNG/PDF/SVG): "
                                     "deformed mesh, contact pressure, time histories."),
    netcdf: Path | None = typer.Option(None, "--netcdf", help="Write the result dataset."),
    as_json: bool = typer.Option(False, "--json", help="Print the result as JSON."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="No progress output."),
) -> None:
    """Run one FEM sliding test and print friction, contact fraction and separation."""
    from .. import fem

    cfg: dict = {}
    if config is not None:
        if not config.is_file():
            raise InputError(f"--config {config}: file not found")
        try:
            cfg = tomllib.loads(config.read_text())
        except tomllib.TOMLDecodeError as exc:
            raise InputError(f"--config {config}: not valid TOML ({exc})") from None
        cfg = cfg.get("fem", cfg)
        unknown = set(cfg) - _KEYS
        if unknown:
            raise InputError(f"--config {config}: unknown key(s) {sorted(unknown)}; "
                             f"allowed: {sorted(_KEYS)}")
    if wavelength or amplitude:
        if len(wavelength or []) != len(amplitude or []):
            raise InputError("--wavelength/--amplitude: give one amplitude per wavelength")
        surf = _surface({"wavelengths": list(wavelength), "amplitudes": list(amplitude)})
    else:
        surf = _surface(surface if surface is not None else cfg.get("surface"))
    mat = _material(material if material is not None else cfg.get("material"))
    kw = {"mesh": _mesh(mesh if mesh is not None else cfg.get("mesh", "120x90"))}
    for name, val in (("solver", solver), ("height_ratio", height_ratio), ("periods", periods),
                      ("steps_per_period", steps_per_period), ("grading", grading),
                      ("contact_points", contact_points), ("history_order", history_order),
                      ("viscous_model", viscous_model)):
        val = val if val is not None else cfg.get(name)
        if val is not None:
            kw[name] = val
    p = pressure if pressure is not None else cfg.get("mean_pressure", 1.0)
    v = velocity if velocity is not None else cfg.get("velocity", 10.0)

    def progress(phase, step, t, mu):
        if step % 20 == 0:
            typer.echo(f"  step {step:5d}  {phase:6s}  t = {t:.4e} s  μ = {mu:+.4f}", err=True)

    from ..pipeline.limits import check_pressures, check_velocity

    check_pressures([p], mat, "mean_pressure")
    check_velocity(v, "velocity")
    opts = fem.make_options(**kw)
    res = fem.sliding_test(surf, mat, p, v, options=opts,
                           progress=None if quiet or as_json else progress)
    s = res.stats
    if as_json:
        typer.echo(json.dumps({
            "friction": res.friction, "shear_stress_MPa": res.shear_stress,
            "contact_fraction": res.contact_fraction,
            "mean_separation_mm": res.mean_separation, "mean_pressure_MPa": res.mean_pressure,
            "velocity_mm_s": res.velocity, "mesh": list(res.mesh), "stats": s.as_dict()},
            indent=1))
    else:
        typer.echo(f"FEM sliding test  p̄ = {res.mean_pressure:g} MPa  v = {res.velocity:g} mm/s"
                   f"  L0 = {res.width:g} mm  mesh {res.mesh[0]}x{res.mesh[1]}")
        typer.echo(f"  friction coefficient μ   {res.friction:.5f}")
        typer.echo(f"  shear stress Δτ = μ p̄    {res.shear_stress:.5f} MPa")
        typer.echo(f"  contact fraction α       {res.contact_fraction:.5f}")
        typer.echo(f"  mean separation ū        {res.mean_separation:.6g} mm")
        typer.echo(f"  cell shear (face lag/H)  {s.bulk_shear:.4g}"
                   + (f" ({s.bulk_shear_change:+.3g} over the last period)"
                      if np.isfinite(s.bulk_shear_change) else ""))
        typer.echo(f"  solver {s.solver}" + ("" if s.status == "ok" else f" ({s.status})"))
        if s.solver == "steady":
            typer.echo(f"  narrowest contact patch  {s.patch_columns:.1f} columns"
                       + (" (under-resolved)" if s.under_resolved else "")
                       + (" (refined)" if s.refined else ""))
            typer.echo(f"  Newton iterations {s.newton_iterations}, GMRES iterations "
                       f"{s.krylov_iterations}, factorizations {s.factorizations}, "
                       f"continuation steps {s.continuation_steps}; "
                       f"{'; '.join(s.tried)}")
        else:
            typer.echo(f"  steps {s.steps}, Newton iterations {s.newton_iterations} "
                       f"({s.newton_iterations / max(s.steps, 1):.1f}/step), factorizations "
                       f"{s.factorizations}, cut-backs {s.cutbacks}, periods {s.periods}"
                       f"{'' if s.steady else ' (NOT steady)'}"
                       + (f", friction change over the last period {100 * s.period_change:.2f} %"
                          if np.isfinite(s.period_change) else ""))
        typer.echo(f"  max penetration {s.max_penetration:.3g} mm (between nodes "
                   f"{s.max_segment_penetration:.3g} mm), wall time "
                   f"{s.wall_time:.1f} s (assembly {s.assembly_time:.1f} s, "
                   f"solve {s.solve_time:.1f} s)")
    if netcdf is not None:
        res.to_dataset().to_netcdf(netcdf)
    if plot is not None:
        plot_result(res, plot)
        if not as_json:
            typer.echo(f"  figure written to {plot}")


def plot_result(res, path: Path) -> None:
    """Deformed cell coloured by the in-plane max shear stress, surface, contact pressure,
    and time histories of friction, contact fraction and mean separation."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection

    from ..roughness.sines import SineSeries

    surf = SineSeries(**res.surface)
    transient = bool(res.history)     # the steady solver has no time history
    fig = plt.figure(figsize=(11, 8 if transient else 6.5), layout="constrained")
    gs = fig.add_gridspec(3 if transient else 2, 2,
                          height_ratios=[2.2, 1, 1] if transient else [2.2, 1])
    ax = fig.add_subplot(gs[0, :])
    xy = res.element_coordinates
    sig = res.element_stress
    tau = np.sqrt(((sig[:, 0] - sig[:, 1]) / 2) ** 2 + sig[:, 2] ** 2)
    # the lower part of the cell, where the action is
    # periodic copies left and right so the window [0, L0] is always filled
    tiles = [xy + [k * res.width, 0.0] for k in (-1, 0, 1)]
    pc = PolyCollection(np.concatenate(tiles), array=np.tile(tau, 3), cmap="viridis",
                        edgecolors="face", linewidths=0.05)
    ax.add_collection(pc)
    fig.colorbar(pc, ax=ax, label="in-plane max shear stress (MPa)", shrink=0.8)
    xs = np.linspace(-res.width, 2 * res.width, 2400)
    zs = surf.heights(xs + res.sliding_distance)
    bottom = float(zs.min()) - 0.1 * res.width
    ax.fill_between(xs, zs, bottom, color="0.6", label="rigid surface", zorder=0)
    face = res.pressure_profile
    ax.set_xlim(0.0, res.width)
    ax.set_ylim(float(zs.min()) - 0.03 * res.width, float(zs.max()) + 0.45 * res.height)
    ax.set_aspect("equal", adjustable="datalim")  # widen the periodic view, keep shapes
    ax.set_xlabel("x (mm, rubber frame)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"deformed cell ({res.stats.solver}): p̄ = {res.mean_pressure:g} MPa, "
                 f"v = {res.velocity:g} mm/s (rubber moves +x)\nμ = {res.friction:.4f}, "
                 f"α = {res.contact_fraction:.3f}")
    ax.legend(loc="upper right")

    axp = fig.add_subplot(gs[1, :])
    axp.plot(face.x, face.pressure, "-", color="C3", label="contact pressure")
    axp.set_xlabel("x (mm, surface frame)")
    axp.set_ylabel("pressure (MPa)", color="C3")
    axz = axp.twinx()
    axz.plot(face.x, face.surface_height, color="0.5", lw=1, label="z(x)")
    axz.set_ylabel("z (mm)", color="0.5")
    axp.set_title("contact pressure along the surface (v > 0: higher on dz/dx > 0 flanks)")

    h = res.history
    if not transient:
        fig.savefig(path, dpi=150)
        plt.close(fig)
        return
    slide = h["phase"] == 2
    xh = h["sliding_distance"] / res.width
    ax1 = fig.add_subplot(gs[2, 0])
    ax1.plot(xh[slide], h["friction"][slide], label="μ (contact force)")
    ax1.axhline(res.friction, color="k", ls="--", lw=0.8, label="time average")
    ax1.set_xlabel("sliding distance / L0")
    ax1.set_ylabel("friction μ")
    ax1.legend(fontsize=8)
    ax2 = fig.add_subplot(gs[2, 1])
    ax2.plot(xh[slide], h["contact_fraction"][slide], color="C1", label="α")
    ax2.set_xlabel("sliding distance / L0")
    ax2.set_ylabel("contact fraction α", color="C1")
    ax3 = ax2.twinx()
    ax3.plot(xh[slide], h["mean_separation"][slide] * 1e3, color="C2", label="ū")
    ax3.set_ylabel("mean separation ū (µm)", color="C2")
    fig.savefig(path, dpi=150)
    plt.close(fig)
