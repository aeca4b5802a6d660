"""Figures (matplotlib, Agg backend: files only, no display)."""

from .materials import plot_dma_fit
from .roughness import plot_hdc

__all__ = ["plot_hdc", "plot_dma_fit"]
