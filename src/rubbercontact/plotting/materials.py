"""DMA data against a Prony fit: E′ and E″, tan δ and the relative error against frequency."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..materials import DMAData, GeneralizedMaxwell
from .roughness import _pyplot


def plot_dma_fit(dma: DMAData, material: GeneralizedMaxwell, path: str | Path | None = None,
                 *, title: str | None = None, dpi: int = 150):
    """Draw measured E′, E″ and tan δ with the fitted series, and the fit's relative error.

    The frequency axis is in the unit the data came in (Hz or rad/s). Returns the
    matplotlib Figure; writes it to ``path`` (format from the extension) when given.
    """
    plt = _pyplot()
    to_axis = 2 * np.pi if dma.frequency_unit == "Hz" else 1.0
    f = dma.frequency / to_axis
    dense = np.geomspace(f.min(), f.max(), 400)
    model = material.complex_modulus(dense * to_axis)
    at_data = material.complex_modulus(dma.frequency)
    fig, axes = plt.subplots(3, 1, figsize=(6.4, 8.0), sharex=True, layout="constrained",
                             gridspec_kw={"height_ratios": [2.2, 1.3, 1.0]})
    ax = axes[0]
    ax.loglog(f, dma.storage, "o", ms=3, mfc="none", color="tab:blue", label="E′ data")
    ax.loglog(f, dma.loss, "s", ms=3, mfc="none", color="tab:red", label="E″ data")
    ax.loglog(dense, model.real, color="tab:blue", lw=1.5, label="E′ fit")
    ax.loglog(dense, model.imag, color="tab:red", lw=1.5, label="E″ fit")
    ax.set_ylabel("modulus [MPa]")
    ax.legend(fontsize=8)
    axes[1].loglog(f, dma.loss_tangent, "o", ms=3, mfc="none", color="tab:green",
                   label="tan δ data")
    axes[1].loglog(dense, model.imag / model.real, color="tab:green", lw=1.5,
                   label="tan δ fit")
    axes[1].set_ylabel("tan δ [-]")
    axes[1].legend(fontsize=8)
    axes[2].semilogx(f, 100 * (at_data.real / dma.storage - 1), "o", ms=3, color="tab:blue",
                     label="E′")
    axes[2].semilogx(f, 100 * (at_data.imag / dma.loss - 1), "s", ms=3, color="tab:red",
                     label="E″")
    axes[2].axhline(0.0, color="black", lw=0.6)
    axes[2].set_ylabel("fit / data − 1 [%]")
    axes[2].set_xlabel(f"frequency [{dma.frequency_unit}]")
    axes[2].legend(fontsize=8)
    for a in axes:
        a.grid(True, which="both", lw=0.3, alpha=0.5)
    t_ref = "" if dma.temperature is None else f" at {dma.temperature:g} °C"
    axes[0].set_title(title or f"{material.name}: {material.n_branches} Maxwell branches"
                               f"{t_ref}", fontsize=10)
    if path is not None:
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=dpi)
    return fig
