"""``rubbercontact plot RESULTS.nc``: redraw the figures of a results file."""

from __future__ import annotations

from pathlib import Path

import typer


def command(
    results: Path = typer.Argument(..., help="Results NetCDF written by 'rubbercontact run'."),
    output: Path = typer.Option(None, "--output", "-o",
                                help="Figure directory (default: next to the results file)."),
) -> None:
    """Redraw every figure of a results file and print its summary table."""
    from ..io.results import read_results
    from ..plotting.figures import plot_all, summary_table

    ds = read_results(results)
    if ds.attrs.get("surface_kind") == "map":         # a run on a height map
        from ..pipeline.maprun import map_summary
        from ..plotting.maps import plot_map_run

        summary, plot = map_summary, plot_map_run
    else:
        summary, plot = summary_table, plot_all
    typer.echo(summary(ds))
    for p in plot(ds, output if output is not None else results.parent):
        typer.echo(f"figure: {p}")
