"""Figures (matplotlib, Agg backend: files only, no display)."""

from .roughness import plot_hdc

__all__ = ["plot_hdc"]
