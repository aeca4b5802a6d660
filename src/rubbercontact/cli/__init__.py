"""Command-line interface: ``rubbercontact COMMAND ...``.

Each command group lives in its own module and is registered here. User errors
print one line ``error: ...`` to stderr and exit with code 2; ``--debug`` shows
the traceback.
"""

from __future__ import annotations

import importlib
import sys

import typer

from .. import __version__
from ..errors import ConvergenceError, InputError

app = typer.Typer(
    name="rubbercontact",
    help="Hybrid multiscale rubber friction and contact area on rough surfaces "
         "(units: mm, MPa, s, mm/s).",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    # Plain help text: rich markup would swallow the unit brackets like "[mm]".
    rich_markup_mode=None,
)

_STATE = {"debug": False}

# (module, name, help): sub-apps (command groups) or single commands, registered if present.
_GROUPS = [
    ("roughness", "roughness", "Analyse measured roughness and fit sine series (paper §2.2)."),
    ("halfspace", "halfspace", "Viscoelastic half-space steady sliding contact (paper §2.3)."),
    ("fem", "fem", "Finite-strain FEM micromechanical sliding test (paper §2.4)."),
    ("material", "material", "Read DMA data, fit Prony series, shift to temperatures."),
    ("run", "run", "Run the hybrid multiscale pipeline from a TOML config (paper §2.1)."),
    ("plot", "plot", "Redraw figures from a results NetCDF file."),
    ("summary", "summary", "Print the summary of a results NetCDF file (curves and peaks)."),
    ("cache", "cache", "Inspect or clear the result cache."),
]


def _version_callback(value: bool) -> None:
    if value:
        typer.echo(f"rubbercontact {__version__}")
        raise typer.Exit()


@app.callback()
def _main(
    debug: bool = typer.Option(False, "--debug", help="Show full tracebacks on errors."),
    version: bool = typer.Option(False, "--version", callback=_version_callback,
                                 is_eager=True, help="Print the version and exit."),
) -> None:
    _STATE["debug"] = debug


def _register() -> None:
    for module_name, name, help_text in _GROUPS:
        try:
            module = importlib.import_module(f".{module_name}", __name__)
        except ModuleNotFoundError as exc:
            if exc.name == f"{__name__}.{module_name}":
                continue  # command group not built yet
            raise
        if hasattr(module, "app"):
            app.add_typer(module.app, name=name, help=help_text)
        else:
            app.command(name=name, help=help_text)(module.command)


_register()


def _write_crash_report(exc: BaseException) -> str:
    """Save the traceback of an internal failure; return where it went."""
    import tempfile
    import traceback

    fd, path = tempfile.mkstemp(prefix="rubbercontact-crash-", suffix=".log")
    with open(fd, "w") as fh:
        fh.write("".join(traceback.format_exception(exc)))
    return path


def main(argv: list[str] | None = None) -> int:
    """Console-script entry point; returns the process exit code."""
    debug = "--debug" in (argv if argv is not None else sys.argv[1:])
    try:
        # without standalone mode click *returns* a command's typer.Exit code
        code = app(args=argv, standalone_mode=False)
        if isinstance(code, int) and not isinstance(code, bool):
            return code
    except (InputError, FileNotFoundError, FileExistsError) as exc:
        if debug:
            raise
        typer.echo(f"error: {exc}", err=True)
        return 2
    except ConvergenceError as exc:
        if debug:
            raise
        typer.echo(f"error: solver did not converge: {exc}", err=True)
        return 1
    except SystemExit as exc:  # typer.Exit inside commands
        return int(exc.code or 0)
    except KeyboardInterrupt:
        typer.echo("interrupted", err=True)
        return 130
    except Exception as exc:  # noqa: BLE001 - usage errors and internal failures
        # typer vendors its own click: recognise its exceptions by behaviour, not by class.
        if type(exc).__name__ == "Exit" and hasattr(exc, "exit_code"):
            return int(exc.exit_code)
        if hasattr(exc, "show") and hasattr(exc, "exit_code"):
            exc.show()
            return int(exc.exit_code)
        if type(exc).__name__ == "Abort":
            return 1
        if debug:
            raise
        log = _write_crash_report(exc)
        typer.echo(f"error: internal failure: {type(exc).__name__}: {exc} (details: {log}; "
                   f"re-run with --debug for the traceback)", err=True)
        return 1
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
