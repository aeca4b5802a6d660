"""Figures (matplotlib, Agg backend: files only, no display; :func:`show` for scripts)."""

from .materials import plot_dma_fit
from .output import show
from .roughness import plot_hdc

__all__ = ["plot_hdc", "plot_dma_fit", "show"]
