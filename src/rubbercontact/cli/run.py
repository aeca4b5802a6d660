"""``rubbercontact run [CONFIG]``: the hybrid pipeline, reference models, results, figures."""

from __future__ import annotations

import warnings
from collections import Counter
from pathlib import Path

import numpy as np
import typer


def command(
    config: Path = typer.Argument(None, help="TOML config (default: built-in reduced §3 case).",
                                  show_default=False),
    output: Path = typer.Option(None, "--output", "-o",
                                help="Output directory (overrides output.directory)."),
    overwrite: bool = typer.Option(False, "--overwrite", help="Replace an existing results file."),
    workers: int = typer.Option(None, "--workers", min=1, help="Dask workers (local cluster)."),
    threads_per_worker: int = typer.Option(None, "--threads-per-worker", min=1,
                                           help="Threads per Dask worker (default 1)."),
    retry_failed: bool = typer.Option(False, "--retry-failed",
                                      help="Recompute tasks whose failure is cached."),
    scheduler: str = typer.Option(None, "--scheduler", envvar="RUBBERCONTACT_SCHEDULER",
                                  help="Address of an existing Dask scheduler (tcp://HOST:PORT)."),
    cache: Path = typer.Option(None, "--cache", envvar="RUBBERCONTACT_CACHE",
                               help="Result cache directory."),
    figures: bool = typer.Option(True, "--figures/--no-figures", help="Write the figures."),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="No progress output."),
    check: bool = typer.Option(False, "--check", help="Resolve and check the config "
                               "(surface, material, speeds, FEM meshes), print the plan, "
                               "run nothing."),
) -> None:
    """Run the hybrid multiscale pipeline (and VHS/FEM/mean-field models) from a config."""
    from ..config import default_config, load_config
    from ..io.results import write_law, write_results
    from ..pipeline import run
    from ..pipeline.assemble import failed_solves
    from ..plotting.figures import plot_all, summary_table

    cfg = load_config(config) if config is not None else default_config()
    upd_exec = {k: v for k, v in {"workers": workers, "threads_per_worker": threads_per_worker,
                                  "scheduler": scheduler, "cache": cache}.items()
                if v is not None}
    if upd_exec:
        cfg = cfg.model_copy(update={"execution": cfg.execution.model_copy(update=upd_exec)})
    if check:
        typer.echo(describe_plan(cfg))
        return
    if cfg.surface.map is not None:
        _run_map(cfg, output, overwrite, figures and cfg.output.figures)
        return
    overwrite = overwrite or cfg.output.overwrite
    results_path = _results_path(cfg, output, overwrite)
    outdir = results_path.parent

    if config is None:
        # The built-in default also shows the roughness analysis of paper §2.2/§4.1.
        from .roughness import analyse_default

        analyse_default(outdir, echo=typer.echo)
    if not quiet:
        # the whole run's expected time before the stages' own progress lines, whose ETA
        # covers only the stage under way
        typer.echo(run_estimate(cfg), err=True)

    ds = _saying_warnings(run, cfg, progress=False if quiet else "auto",
                          retry_failed=retry_failed)
    write_results(ds, results_path, overwrite=overwrite)
    typer.echo(summary_table(ds))
    if config is None:
        typer.echo(DEFAULT_RUN_NOTE)
    typer.echo(f"results: {results_path}")
    if "law_attrs" in ds.attrs:
        # The expensive part, on its own: reusable as law.file for any surface sharing
        # this high-slope scale and rubber.
        from ..hybrid.law import law_from_results

        typer.echo(f"law: {write_law(law_from_results(ds), outdir / 'law.nc')}")
    if figures and cfg.output.figures:
        for p in plot_all(ds, outdir):
            typer.echo(f"figure: {p}")
    mask = failed_solves(ds["status"].values)
    if mask.any():
        bad = np.argwhere(mask)
        typer.echo(f"error: {int(mask.sum())} solve(s) failed, e.g. "
                   f"{[str(ds['status'].values[tuple(b)]) for b in bad[:3]]}", err=True)
        raise typer.Exit(1)


def _results_path(cfg, output: Path | None, overwrite: bool) -> Path:
    """The run's ``results.nc`` in its output directory (created); refused if it exists
    and ``overwrite`` is off."""
    outdir = Path(output if output is not None else cfg.output.directory)
    path = outdir / "results.nc"
    if path.exists() and not overwrite:
        raise FileExistsError(f"{path} exists; pass --overwrite to replace it")
    outdir.mkdir(parents=True, exist_ok=True)
    return path


def _saying_warnings(solve, *args, **kwargs):
    """``solve(*args, **kwargs)``, its warnings printed after it, one line per distinct
    message with its count (the law's reading warns once per speed and solve)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        # Dask's local cluster leaves sockets to the garbage collector: not the user's concern
        warnings.simplefilter("ignore", ResourceWarning)
        out = solve(*args, **kwargs)
    for message, times in Counter(str(w.message) for w in caught).items():
        typer.echo(f"warning: {message}" + (f" (×{times})" if times > 1 else ""), err=True)
    return out


def _run_map(cfg, output: Path | None, overwrite: bool, figures: bool) -> None:
    """A run on ``[surface.map]`` (:mod:`rubbercontact.pipeline.maprun`): results and table."""
    from ..io.results import write_results
    from ..pipeline.maprun import map_summary, run_map

    overwrite = overwrite or cfg.output.overwrite
    results_path = _results_path(cfg, output, overwrite)
    outdir = results_path.parent
    ds = _saying_warnings(run_map, cfg)
    write_results(ds, results_path, overwrite=overwrite)
    typer.echo(map_summary(ds))
    typer.echo(f"results: {results_path}")
    if figures:
        from ..plotting.maps import plot_map_run

        for p in plot_map_run(ds, outdir):
            typer.echo(f"figure: {p}")
    if (ds["status"].values != "ok").any():
        typer.echo(f"error: {int((ds['status'].values != 'ok').sum())} solve(s) failed",
                   err=True)
        raise typer.Exit(1)


#: What the built-in default's numbers are, printed under them (one line).
DEFAULT_RUN_NOTE = ("built-in default: a reduced demonstration of the paper's §3 case (coarse "
                    "FEM meshes, the FEM on 1 realization, equal σ0), not the validation: the "
                    "validated eq. 28 errors are in README.md and VALIDATION.md")


def run_estimate(cfg) -> str:
    """The whole run's expected cost, one line (the last ``cost: about`` line of
    ``--check``; the progress lines that follow time one stage each)."""
    from ..pipeline import resolve
    from ..pipeline.cost import estimate_cost

    about = next(line for line in estimate_cost(resolve(cfg)).describe().splitlines()
                 if line.startswith("cost: about"))
    return f"run: {about.removeprefix('cost: ')}; `run --check` lists the stages"


def _flash_plan(setup) -> list[str]:
    """The flash temperature's line of the plan (checks its inputs; none when off)."""
    from ..pipeline.flash import plan_flash

    plan = plan_flash(setup)
    if plan is None:
        return []
    return [f"flash temperature: {', '.join(plan.models) or 'no model'}, one mu(v) per "
            f"temperature and load" + (f"; {plan.note}" if plan.note else "")]


def describe_plan(cfg) -> str:
    """What a run of ``cfg`` will compute (after :func:`rubbercontact.pipeline.resolve`)."""
    from ..pipeline import resolve
    from ..pipeline.cost import estimate_cost
    from ..pipeline.lawstage import uses_continuation

    if cfg.surface.map is not None:
        from ..pipeline.maprun import describe_map_plan

        return describe_map_plan(cfg)
    setup = resolve(cfg)
    sp = setup.speeds
    lines = [f"config ok: models {', '.join(setup.models)}",
             f"surface: {setup.surface.info.get('source')}, {setup.base.size} waves, "
             f"{int(setup.hs0.size)} high-slope; {len(setup.realizations)} realizations",
             f"material: {setup.material.name}"
             + ("" if sp.reference_temperature is None
                else f" (T_ref = {sp.reference_temperature:g} °C)"),
             f"speeds: {sp.velocities.size} from {sp.velocities.min():g} to "
             f"{sp.velocities.max():g} mm/s"]
    if not sp.isothermal:
        lines.append(f"temperatures: {', '.join(f'{t:g}' for t in sp.temperatures)} °C; "
                     f"{sp.computed.size} distinct reduced speeds computed at T_ref")
    loads = cfg.loads
    lines.append(f"loads: pressures {', '.join(f'{p:g}' for p in loads.pressures)} MPa"
                 if loads.pressures is not None
                 else f"loads: {len(loads.contact_areas)} target contact areas")
    lines += _flash_plan(setup)
    if setup.needs_law:
        if cfg.law.file is not None:
            lines.append(f"law: reused from {cfg.law.file}")
        else:
            n_p = len(cfg.law.pressures) if cfg.law.pressures is not None else 8
            how = ("by continuation in speed, one task per pressure"
                   if uses_continuation(cfg, sp.computed.size) else "one task per point")
            lines.append(f"law: {n_p} pressures x {sp.computed.size} speeds of FEM, {how}")
    lines.append(estimate_cost(setup).describe())
    return "\n".join(lines)
