"""HDC figure like the paper's Fig. 6: measured vs fitted HDC and each wave's HDC, log–log."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..roughness.fit import HDCFit


def _pyplot():
    import matplotlib

    if matplotlib.get_backend().lower() not in ("agg", "pdf", "svg", "ps", "cairo"):
        matplotlib.use("Agg")  # no display on compute machines; files only
    import matplotlib.pyplot as plt

    return plt


def plot_hdc(fit: HDCFit, path: str | Path | None = None, *, title: str | None = None,
             m2_threshold: float = 1.0, dpi: int = 150):
    """Draw the measured HDC, the fitted sum and each wave's HDC on log–log axes.

    Each wave is drawn bold up to half its wavelength and faint beyond; high-slope waves
    (``m2 > m2_threshold``) are dashed. Returns the matplotlib Figure;
    writes it to ``path`` (format from the extension) when given.
    """
    plt = _pyplot()
    lo = float(fit.lags.min())
    hi = float(fit.lags.max())
    dense = np.geomspace(lo, hi, 400)
    waves = fit.wave_hdcs(dense)
    model = waves.sum(axis=1)
    fig, ax = plt.subplots(figsize=(6.4, 4.8), layout="constrained")
    cmap = plt.get_cmap("viridis")
    m2 = fit.series.rms_slopes()
    n = fit.series.size
    floor = float(fit.measured.min()) / 30
    for i in range(n):
        y = np.where(waves[:, i] > floor, waves[:, i], np.nan)
        if np.all(np.isnan(y)):
            continue
        style = {"ls": "--" if m2[i] > m2_threshold else "-",
                 "color": cmap(i / max(n - 1, 1))}
        rising = dense <= fit.series.wavelengths[i] / 2
        ax.loglog(dense, np.where(rising, y, np.nan), lw=1.0, **style,
                  label=f"λ = {fit.series.wavelengths[i]:g} mm, m2 = {m2[i]:.3g}")
        # beyond λ/2 the exact one-wave HDC oscillates (eq. 14), the clipped one is flat
        # (eq. 15): drawn faint so that the sum stays readable
        ax.loglog(dense, np.where(rising, np.nan, y), lw=0.6, alpha=0.35, **style)
    ax.loglog(fit.lags, fit.measured, "o", ms=3.5, mfc="none", color="tab:red",
              label="measured (mean of scans)")
    ax.loglog(dense, model, color="black", lw=2,
              label=f"fit, {fit.method} (log10 rms error {fit.log10_rms_error:.3f})")
    ax.set_xlabel("lag λ [mm]")
    ax.set_ylabel("HDC  R_zz(λ) [mm²]")
    ax.set_ylim(floor, float(max(fit.measured.max(), model.max())) * 2)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    ax.set_title(title or f"HDC fit with {n} sine waves "
                          f"(rms height {fit.series.rms_height:.3g} mm)")
    ax.legend(fontsize=7, loc="upper left")
    if path is not None:
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=dpi)
    return fig


def write_fit_outputs(fit: HDCFit, output_dir: str | Path, *, stem: str = "roughness_fit",
                      m2_threshold: float = 1.0, extra: dict | None = None) -> dict[str, Path]:
    """Write ``<stem>.png`` (the HDC figure) and ``<stem>.json`` (the fit's record, its
    series and ``extra``) into ``output_dir``; returns ``{"figure": ..., "json": ...}``."""
    out = Path(output_dir)
    out.mkdir(parents=True, exist_ok=True)
    png, js = out / f"{stem}.png", out / f"{stem}.json"
    fig = plot_hdc(fit, png, m2_threshold=m2_threshold)
    _pyplot().close(fig)
    record = fit.as_dict(m2_threshold)
    record["series"] = fit.series.as_dict()
    record.update(extra or {})
    js.write_text(json.dumps(record, indent=2))
    return {"figure": png, "json": js}
