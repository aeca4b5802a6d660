"""``rubbercontact roughness ...``: fit sine series to measured line scans (``fit``); a height
map's statistics (``map``, :mod:`.mapcli`)."""

from __future__ import annotations

import json
import warnings
from pathlib import Path
from typing import Literal

import typer

from ..errors import InputError
from .mapcli import stats_command

app = typer.Typer(no_args_is_help=True, add_completion=False,
                  pretty_exceptions_enable=False)
app.command("map")(stats_command)


@app.callback()
def _group() -> None:
    """Analyse measured roughness and fit sine series (paper section 2.2)."""


def _wavelengths(dx: float, shortest: float, waves: int | None, lower: float | None,
                 upper: float | None):
    from ..roughness.fit import default_wavelengths, octave_wavelengths

    if waves is not None and lower is not None and upper is not None:
        lam = octave_wavelengths(upper_cutoff=upper, n_waves=waves)
        if abs(lam.min() - lower) > 1e-9 * upper:
            raise InputError(f"--waves {waves} octaves down from --upper-cutoff {upper:g} "
                             f"end at {lam.min():g} mm, not --lower-cutoff {lower:g}: "
                             "give two of the three")
        return lam
    if waves is not None and upper is None and lower is not None:
        return octave_wavelengths(lower_cutoff=lower, n_waves=waves)
    return default_wavelengths(dx, shortest, waves, lower, upper)


@app.command("fit")
def fit(
    files: list[Path] = typer.Argument(..., help="Profile files (text/CSV, CAPTIF, or "
                                       "instrument formats with the topography extra)."),
    dx: float | None = typer.Option(None, "--dx", help="Sampling step (mm) for text files "
                                    "without a position column."),
    waves: int | None = typer.Option(None, "--waves", help="Number of octave-spaced waves "
                                     "M (default: from the cut-offs)."),
    lower_cutoff: float | None = typer.Option(None, "--lower-cutoff", help="Shortest "
                                              "wavelength (mm) (default 4·dx)."),
    upper_cutoff: float | None = typer.Option(None, "--upper-cutoff", help="Longest "
                                              "wavelength (mm) (default half the "
                                              "shortest scan)."),
    method: Literal["wellconditioned", "paper"] = typer.Option("wellconditioned", "--method",
                                        help="wellconditioned: NNLS on the exact "
                                        "one-wave HDC; paper: eqs. 29-30 as printed."),
    fmt: Literal["auto", "text", "captif", "topography"] = typer.Option(
        "auto", "--format", help="File format."),
    unit: str | None = typer.Option(None, "--unit", help="Unit of the numbers in the "
                                    "files: mm (default), um, nm or m."),
    nan: Literal["windows", "interpolate", "error"] = typer.Option(
        "windows", "--nan", help="Dropouts: NaN-free "
                                  "windows, linear interpolation, or error."),
    window: float = typer.Option(16.0, "--window", help="Length of the NaN-free windows "
                                 "[mm]."),
    despike: bool = typer.Option(False, "--despike", help="Replace spikes (Hampel filter)."),
    m2_threshold: float = typer.Option(1.0, "--m2-threshold", help="Waves with m2 above "
                                       "this form the high-slope scale."),
    plot: Path | None = typer.Option(None, "--plot", help="Write the HDC figure (Fig. 6 "
                                     "style) to this file (.png, .pdf, .svg)."),
    as_json: bool = typer.Option(False, "--json", help="Print the result as JSON."),
) -> None:
    """Fit a sine series to the mean HDC of line scans and print a Table-2-like table."""
    from ..io.profiles import read_profiles
    from ..roughness.analysis import format_table
    from ..roughness.fit import fit_hdc_details

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        profiles = read_profiles(files, format=fmt, unit=unit, dx=dx, nan=nan,
                                 window=window, despike=despike)
        shortest = float(profiles.lengths.min())
        lam = _wavelengths(profiles.dx, shortest, waves, lower_cutoff, upper_cutoff)
        result = fit_hdc_details(profiles, None, lam, method)
    for w in caught:
        typer.echo(f"warning: {w.message}", err=True)
    source = (f"{len(files)} file(s), {len(profiles)} scans of "
              f"{profiles.lengths.min():.4g}–{profiles.lengths.max():.4g} mm, "
              f"dx = {profiles.dx:.5g} mm")
    if plot is not None:
        import matplotlib.pyplot as plt

        from ..plotting.roughness import plot_hdc

        plt.close(plot_hdc(result, plot, m2_threshold=m2_threshold))
    if as_json:
        record = result.as_dict(m2_threshold)
        record["series"] = result.series.as_dict()
        record["sources"] = [{k: s.get(k) for k in ("path", "sha256", "format", "unit")}
                             for s in profiles.sources]
        record["n_scans"] = len(profiles)
        if plot is not None:
            record["figure"] = str(plot)
        typer.echo(json.dumps(record, indent=2))
    else:
        typer.echo(format_table(result, m2_threshold, source=source))
        if plot is not None:
            typer.echo(f"wrote {plot}")


def analyse_default(output_dir: Path, *, echo=typer.echo):
    """The roughness part of the built-in default run: :func:`~rubbercontact.roughness.
    analysis.fit_default`, its table (with Table 2's amplitudes beside) through ``echo``,
    and ``roughness_fit.png`` (Fig. 6 style) + ``roughness_fit.json`` in ``output_dir``.
    Returns the fitted sine series."""
    from ..plotting.roughness import write_fit_outputs
    from ..roughness.analysis import DEFAULT_DATASET, default_source, fit_default, format_table
    from ..roughness.presets import TABLE2

    fit = fit_default()
    echo(format_table(fit, reference=TABLE2[:, 1], source=default_source()))
    files = write_fit_outputs(fit, output_dir, extra={"dataset": dict(DEFAULT_DATASET),
                                                      "reference": "paper Table 2"})
    echo(f"wrote {files['figure']} and {files['json']}")
    return fit.series
