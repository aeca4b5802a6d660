"""``rubbercontact cache info|prune|clear|copy``: inspect, prune or empty the result cache."""

from __future__ import annotations

from pathlib import Path

import typer

app = typer.Typer(no_args_is_help=True, add_completion=False,
                  help="Inspect, prune or clear the result cache.")

_CACHE_HELP = ("Cache directory (default: $RUBBERCONTACT_CACHE, else the user cache "
               "directory).")


def _cache(directory: Path | None):
    from ..sweep.cache import ResultCache

    return ResultCache(directory)


@app.command("info")
def info(cache: Path | None = typer.Option(None, "--cache", help=_CACHE_HELP)) -> None:
    """Location, number of entries (ok / failed; of the current or other code), size on
    disk, interrupted writes."""
    store = _cache(cache)
    typer.echo(str(store.info()))
    typer.echo(str(store.code_report()))


@app.command("prune")
def prune(cache: Path | None = typer.Option(None, "--cache", help=_CACHE_HELP)) -> None:
    """Delete the entries computed by other code than this installation's.

    The code a task runs is part of its key, so such entries are never hit again; they
    only take space.
    """
    store = _cache(cache)
    n = store.prune()
    typer.echo(f"deleted {n} entries of other or unknown code from {store.directory}")


@app.command("clear")
def clear(cache: Path | None = typer.Option(None, "--cache", help=_CACHE_HELP),
          failed_only: bool = typer.Option(False, "--failed-only",
                                           help="Delete only recorded failures, so that the "
                                                "next run recomputes them."),
          yes: bool = typer.Option(False, "--yes", "-y", help="Do not ask for confirmation.")
          ) -> None:
    """Delete cached results (all, or only failed ones) and interrupted writes."""
    store = _cache(cache)
    info = store.info()
    n = info.n_failed if failed_only else info.n_entries
    what = "failed entries" if failed_only else "entries"
    if n == 0 and info.n_temporary == 0:
        typer.echo(f"nothing to delete in {store.directory}")
        return
    if not yes and not typer.confirm(f"delete {n} {what} from {store.directory}?"):
        typer.echo("aborted; nothing deleted")
        raise typer.Exit(1)
    deleted = store.clear(failed_only=failed_only)
    typer.echo(f"deleted {deleted} {what} from {store.directory}")


@app.command("copy")
def copy(source: Path = typer.Argument(..., help="Cache directory to copy from."),
         destination: Path = typer.Argument(..., help="Cache directory to copy into."),
         function: list[str] = typer.Option(
             [], "--function", help="Only tasks whose function name ends with this, e.g. "
                                     "fem_task (repeatable; default: every task)."),
         include_failed: bool = typer.Option(False, "--include-failed",
                                             help="Also copy recorded failures.")) -> None:
    """Copy the valid entries DESTINATION lacks from SOURCE (checked, atomic).

    Keeps expensive results (e.g. the FEM solves behind a validation report) in a
    directory of their own, and seeds a fresh cache from it.
    """
    from ..errors import InputError

    if not source.is_dir():
        raise InputError(f"cache copy: source {str(source)!r} is not a directory")
    report = _cache(source).copy_to(_cache(destination), tuple(function) or None,
                                    include_failed=include_failed)
    typer.echo(f"{source} -> {destination}: {report}")
