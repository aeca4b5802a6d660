"""``rubbercontact material ...``: read DMA data and fit a Prony series."""

from __future__ import annotations

import json
import warnings
from pathlib import Path
from typing import Literal

import typer

from ..errors import InputError

app = typer.Typer(no_args_is_help=True, add_completion=False,
                  pretty_exceptions_enable=False)


@app.callback()
def _group() -> None:
    """Read DMA data, fit Prony series, shift to temperatures."""


def _shift_law(wlf: str | None, arrhenius: float | None, temperature: float | None):
    from ..materials import WLF, Arrhenius

    if wlf is None and arrhenius is None:
        return None
    if wlf is not None and arrhenius is not None:
        raise InputError("give one of --wlf and --arrhenius")
    if temperature is None:
        raise InputError("--wlf/--arrhenius refer to the reference temperature: give "
                         "--temperature")
    if arrhenius is not None:
        return Arrhenius(arrhenius, temperature)
    parts = wlf.replace(";", ",").split(",")
    try:
        c1, c2 = (float(p) for p in parts)
    except ValueError:
        raise InputError(f"--wlf: expected 'C1,C2' (e.g. 8.86,101.6), got {wlf!r}") from None
    return WLF(c1, c2, temperature)


def _table(mat) -> str:
    rows = [f"  {'branch':>6}  {'E_i [MPa]':>12}  {'tau_i [s]':>12}",
            f"  {'inf':>6}  {mat.equilibrium_modulus:12.5g}  {'-':>12}"]
    for i, (e, t) in enumerate(zip(mat.moduli, mat.relaxation_times, strict=True), start=1):
        rows.append(f"  {i:>6}  {e:12.5g}  {t:12.5g}")
    return "\n".join(rows)


@app.command("fit")
def fit(
    dma_file: Path = typer.Argument(..., help="DMA CSV with a header naming the columns, "
                                    "e.g. 'frequency [Hz], E_storage [MPa], E_loss [MPa]'."),
    frequency_unit: str | None = typer.Option(None, "--frequency-unit", help="Hz or rad/s, "
                                              "when the header states none."),
    modulus_unit: str | None = typer.Option(None, "--modulus-unit", help="Pa, kPa, MPa or "
                                            "GPa, when the header states none."),
    temperature: float | None = typer.Option(None, "--temperature", help="Reference "
                                             "temperature of the curve [°C]."),
    terms: int | None = typer.Option(None, "--terms", help="Relaxation times of the NNLS "
                                     "grid (default: the fewest per decade reaching "
                                     "--tolerance or the noise floor)."),
    tolerance: float = typer.Option(0.01, "--tolerance", help="Target rms relative "
                                    "residual of E' and E'' [-]."),
    wlf: str | None = typer.Option(None, "--wlf", help="WLF 'C1,C2' (C2 in K) of the "
                                   "master curve, referred to --temperature."),
    arrhenius: float | None = typer.Option(None, "--arrhenius", help="Arrhenius activation "
                                           "energy [J/mol], referred to --temperature."),
    law: Literal["WLF", "Arrhenius"] = typer.Option("WLF", "--law", help="Shift law fitted "
                                                    "to isothermal sweeps (files with a "
                                                    "temperature column)."),
    output: Path | None = typer.Option(None, "-o", "--output", help="Write the fitted "
                                       "material to this TOML file."),
    plot: Path | None = typer.Option(None, "--plot", help="Write the data-against-fit "
                                     "figure to this file (.png, .pdf, .svg)."),
    as_json: bool = typer.Option(False, "--json", help="Print the result as JSON."),
) -> None:
    """Fit a generalized Maxwell series to DMA data; print the table and its fit error."""
    from ..materials import fit_prony, master_curve, read_dma

    if output is not None and output.suffix.lower() != ".toml":
        raise InputError(f"--output {output}: expected a .toml file")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        dma = read_dma(dma_file, frequency_unit, temperature, modulus_unit=modulus_unit,
                       shift=_shift_law(wlf, arrhenius, temperature))
        master = None
        if not dma.is_isothermal:
            if wlf is not None or arrhenius is not None:
                raise InputError(f"{dma_file}: isothermal sweeps get their shift law fitted "
                                 f"(--law); drop --wlf/--arrhenius")
            master = master_curve(dma, law=law)
            dma = master.data
        result = fit_prony(dma, terms, tolerance=tolerance, report=True)
    for w in caught:
        typer.echo(f"warning: {w.message}", err=True)
    mat, rep = result.material, result.report
    if output is not None:
        mat.to_toml(output)
    if plot is not None:
        import matplotlib.pyplot as plt

        from ..plotting.materials import plot_dma_fit

        plt.close(plot_dma_fit(dma, mat, plot))
    if as_json:
        record = {"material": mat.as_dict(provenance=False), "report": rep.as_dict()}
        if master is not None:
            record["master_curve"] = {"temperatures": master.temperatures.tolist(),
                                      "log10_shifts": master.log10_shifts.tolist(),
                                      "law_rms_error": master.law_rms_error}
        for key, value in (("output", output), ("figure", plot)):
            if value is not None:
                record[key] = str(value)
        typer.echo(json.dumps(record, indent=2))
        return
    typer.echo(f"{dma_file}: {dma.n_points} points, {dma.frequency.min():.4g}–"
               f"{dma.frequency.max():.4g} rad/s"
               + ("" if dma.temperature is None else f", reference {dma.temperature:g} °C"))
    if master is not None:
        shifts = ", ".join(f"{t:g} °C: {a:+.3f}" for t, a in
                           zip(master.temperatures, master.log10_shifts, strict=True))
        typer.echo(f"master curve: log10 a_T {shifts} (law rms "
                   f"{master.law_rms_error:.3g} decades)")
    if mat.shift is not None:
        typer.echo(f"shift law: {mat.shift.as_dict()}")
    typer.echo(f"fit: {rep.summary()}")
    typer.echo(_table(mat))
    for key, value in (("wrote", output), ("wrote", plot)):
        if value is not None:
            typer.echo(f"{key} {value}")
