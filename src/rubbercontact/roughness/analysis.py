"""Roughness analysis: the Table-2-like table of a fit, and the built-in default fit.

:func:`fit_default` is the roughness part of the built-in default run (``make run``): the
paper's Table 2 surface sampled as 30 noisy line scans of 16 mm, fitted back with the
well-conditioned method. Figures and records are written by :mod:`rubbercontact.plotting`
(this package does not import it).
"""

from __future__ import annotations

import numpy as np

from .fit import HDCFit, fit_hdc_details, octave_wavelengths
from .presets import asphalt_ac8
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


def fit_default(method: str = "wellconditioned") -> HDCFit:
    """The built-in default roughness fit: Table 2's surface sampled as
    :data:`DEFAULT_DATASET` (random phases per scan, white noise), fitted with the 8 octaves
    0.0625 … 8 mm to the scans' mean HDC (the figure and the record are written by
    :func:`rubbercontact.plotting.roughness.write_fit_outputs`)."""
    scans = synthetic_line_scans(asphalt_ac8(), **DEFAULT_DATASET)
    return fit_hdc_details(scans, DEFAULT_DATASET["dx"], octave_wavelengths(0.0625, 8.0), method)


def default_source() -> str:
    """One line saying what :func:`fit_default` fitted."""
    d = DEFAULT_DATASET
    return (f"Built-in data set: Table 2 surface, {d['n_scans']} line scans of "
            f"{d['length']:g} mm at dx = {d['dx']:g} mm, random phases, noise "
            f"{d['noise'] * 1e3:g} um (seed {d['seed']})")
