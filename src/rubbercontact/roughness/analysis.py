"""Roughness analysis as a job: fit, Table-2-like table, HDC figure, JSON record.

:func:`analyse_default` is the built-in default job (``make run`` until the hybrid
pipeline exists): the paper's Table 2 surface sampled as 30 noisy line scans of
16 mm, fitted back with the well-conditioned method.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from .fit import HDCFit, fit_hdc_details, octave_wavelengths
from .presets import TABLE2, asphalt_ac8
from .sines import SineSeries
from .synthetic import DEFAULT_NOISE, synthetic_line_scans

#: The default data set: Table 2, 30 scans of 16 mm at 0.005 mm, seed 0.
DEFAULT_DATASET = {"n_scans": 30, "length": 16.0, "dx": 0.005, "noise": DEFAULT_NOISE,
                   "seed": 0}


def format_table(fit: HDCFit, m2_threshold: float = 1.0, *,
                 reference: np.ndarray | None = None, source: str = "") -> str:
    """Plain-text table like the paper's Table 2, with a summary of the fit.

    ``reference``: amplitudes to print beside the fitted ones (e.g. Table 2's).
    """
    rows = fit.table(m2_threshold)
    head = f"{'wave':>4}  {'wavelength [mm]':>15}  {'amplitude [mm]':>14}  {'m2':>7}"
    if reference is not None:
        head += f"  {'reference [mm]':>14}  {'ratio':>6}"
    head += "  scale"
    lines = []
    if source:
        lines.append(source)
    lines += [head, "-" * len(head)]
    for i, r in enumerate(rows):
        line = (f"{i + 1:>4}  {r['wavelength']:>15.5g}  {r['amplitude']:>14.5f}  "
                f"{r['m2']:>7.4f}")
        if reference is not None:
            ref = float(reference[i])
            ratio = r["amplitude"] / ref if ref > 0 else float("nan")
            line += f"  {ref:>14.5f}  {ratio:>6.3f}"
        line += "  " + ("high-slope" if r["high_slope"] else "low-slope")
        lines.append(line)
    s = fit.series
    hs = [r["wavelength"] for r in rows if r["high_slope"]]
    lines += [
        "-" * len(head),
        f"method {fit.method}; HDC fit error (rms of log10 R_zz) {fit.log10_rms_error:.4f} "
        f"over {fit.lags.size} lags {fit.lags.min():.4g}–{fit.lags.max():.4g} mm",
        f"rms height {s.rms_height:.4f} mm; rms slope sqrt(sum m2^2) {s.rms_slope:.4f}",
        f"high-slope scale (m2 > {m2_threshold:g}): "
        + (", ".join(f"{w:g} mm" for w in hs) if hs else "none"),
    ]
    return "\n".join(lines)


def write_outputs(fit: HDCFit, output_dir: str | Path, *, stem: str = "roughness_fit",
                  m2_threshold: float = 1.0, extra: dict | None = None) -> dict[str, Path]:
    """Write ``<stem>.png`` (HDC figure) and ``<stem>.json`` into ``output_dir``."""
    from ..plotting.roughness import plot_hdc

    out = Path(output_dir)
    out.mkdir(parents=True, exist_ok=True)
    png, js = out / f"{stem}.png", out / f"{stem}.json"
    fig = plot_hdc(fit, png, m2_threshold=m2_threshold)
    import matplotlib.pyplot as plt

    plt.close(fig)
    record = fit.as_dict(m2_threshold)
    record["series"] = fit.series.as_dict()
    record.update(extra or {})
    js.write_text(json.dumps(record, indent=2))
    return {"figure": png, "json": js}


def analyse_default(output_dir: str | Path, *, echo=print,
                    method: str = "wellconditioned") -> SineSeries:
    """The built-in default roughness job; returns the fitted :class:`SineSeries`.

    Generates Table 2's surface as :data:`DEFAULT_DATASET` (random phases per scan, white
    noise), fits the 8 octaves 0.0625 … 8 mm to the scans' mean HDC, prints the table
    (with Table 2's amplitudes beside) through ``echo`` and writes ``roughness_fit.png``
    (Fig. 6 style) and ``roughness_fit.json`` into ``output_dir``.
    """
    scans = synthetic_line_scans(asphalt_ac8(), **DEFAULT_DATASET)
    wavelengths = octave_wavelengths(0.0625, 8.0)
    fit = fit_hdc_details(scans, DEFAULT_DATASET["dx"], wavelengths, method)
    d = DEFAULT_DATASET
    echo(format_table(
        fit, reference=TABLE2[:, 1],
        source=(f"Built-in data set: Table 2 surface, {d['n_scans']} line scans of "
                f"{d['length']:g} mm at dx = {d['dx']:g} mm, random phases, noise "
                f"{d['noise'] * 1e3:g} um (seed {d['seed']})")))
    files = write_outputs(fit, output_dir, extra={"dataset": dict(DEFAULT_DATASET),
                                                  "reference": "paper Table 2"})
    echo(f"wrote {files['figure']} and {files['json']}")
    return fit.series
