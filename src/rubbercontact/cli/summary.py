"""``rubbercontact summary RESULTS.nc``: the summary table of a results file."""

from __future__ import annotations

from pathlib import Path

import typer


def command(
    results: Path = typer.Argument(..., help="Results NetCDF written by 'rubbercontact run'."),
) -> None:
    """Print each model's friction and contact area; for speed sweeps the curves and peaks."""
    from ..io.results import read_results
    from ..plotting.summary import summary_table

    ds = read_results(results)
    if ds.attrs.get("surface_kind") == "map":         # a run on a height map
        from ..pipeline.maprun import map_summary

        typer.echo(map_summary(ds))
    else:
        typer.echo(summary_table(ds))
