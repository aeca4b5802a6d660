"""Legends that leave the data visible.

matplotlib's ``loc="best"`` only minimises the overlap: with four curves and error bars
in a small panel it still covers points. :func:`legend_clear_of_data` keeps the legend
where ``"best"`` puts it when it covers no data point, and otherwise raises the y-axis's
upper limit until the points fit below a legend in the panel's top left corner.
"""

from __future__ import annotations

import numpy as np

#: Gap between the highest data point and the legend, in axes fractions.
PAD = 0.03


def data_points(ax) -> np.ndarray:
    """Every drawn data point of ``ax`` (lines' vertices, error bars' ends), ``(n, 2)``
    in data coordinates."""
    pts = [np.asarray(line.get_xydata(), float).reshape(-1, 2) for line in ax.lines]
    for coll in ax.collections:
        for seg in getattr(coll, "get_segments", lambda: [])():
            pts.append(np.asarray(seg, float).reshape(-1, 2))
    pts = [p for p in pts if p.size]
    if not pts:
        return np.empty((0, 2))
    allp = np.concatenate(pts)
    return allp[np.isfinite(allp).all(axis=1)]


def _covered(ax, legend) -> bool:
    """Whether the legend's box covers a data point of ``ax``."""
    box = legend.get_window_extent()
    xy = ax.transData.transform(data_points(ax))
    inside = ((xy[:, 0] >= box.x0) & (xy[:, 0] <= box.x1)
              & (xy[:, 1] >= box.y0) & (xy[:, 1] <= box.y1))
    return bool(inside.any())


def legend_clear_of_data(ax, **kwargs):
    """A legend inside ``ax`` that covers none of its data points (module docstring);
    ``kwargs`` go to :meth:`matplotlib.axes.Axes.legend`. Call it once the figure's
    layout is final (after ``tight_layout``): it measures the legend in the panel."""
    fig = ax.figure
    legend = ax.legend(loc="best", **kwargs)
    fig.canvas.draw()
    if not _covered(ax, legend):
        return legend
    legend = ax.legend(loc="upper left", **kwargs)
    fig.canvas.draw()
    height = legend.get_window_extent().transformed(ax.transAxes.inverted()).height
    room = 1.0 - height - PAD
    pts = data_points(ax)
    if room < 0.25 or pts.size == 0:
        return legend                         # too tall to fit above: leave it to "best"
    scale = ax.yaxis.get_transform()
    lo, hi = scale.transform(np.asarray(ax.get_ylim(), float))
    top = float(np.max(ax.transAxes.inverted().transform(ax.transData.transform(pts))[:, 1]))
    data_top = lo + top * (hi - lo)
    new_hi = max(hi, lo + (data_top - lo) / room)
    ax.set_ylim(*scale.inverted().transform(np.array([lo, new_hi])))
    return legend
