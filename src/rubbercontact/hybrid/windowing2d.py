"""The high-slope law read at the low-slope pressure averaged over one high-slope cell (maps).

The 2D form of :mod:`rubbercontact.hybrid.windowing`: on a map the law's averaging cell is a
box of one high-slope period ``λ_c`` in x and in y (the period of the cell the map's law is
computed on, :mod:`rubbercontact.roughness.mapsplit`; a cell of several periods is a larger
sample of the same crests, the window stays one period), so::

    μ_hs = <Δτ_hs(σ̄(x, y))>/σ0,   A_c = <α_hs(σ̄(x, y))>,   σ̄ = box_{λc×λc} * σ_ls.

A patch smaller than the cell then carries its force on one cell of high-slope asperities.
Each axis is averaged as the 1D window does (odd number of whole grid cells, periodic), so a
pressure uniform in y gives the 1D windowed terms exactly.
"""

from __future__ import annotations

import numpy as np
from scipy.ndimage import uniform_filter

from .._validation import finite_array
from ..errors import InputError
from .windowing import law_in_pressure


def _cells(window: float, period: float, n: int) -> int:
    """Odd number of grid cells of the 1D rule (:func:`.windowing.window_average`); a window
    longer than the period covers the period (a periodic field repeats beyond it)."""
    if not 0 < window:
        raise InputError(f"window: must be > 0 mm, got {window!r}")
    return min(2 * int(round(min(window, period) / period * n / 2 - 0.5)) + 1, n)


def window_average_2d(field: np.ndarray, lengths: tuple[float, float],
                      window: float) -> np.ndarray:
    """Periodic centred box average of a map over ``window × window`` [mm].

    Parameters
    ----------
    field
        Values ``(ny, nx)`` on a uniform periodic grid.
    lengths
        ``(Ly, Lx)`` [mm].
    window
        Box side [mm], > 0; per axis rounded to an odd number of grid cells (one cell: that
        axis unchanged; a window of the axis' period or longer: the axis' mean).
    """
    f = finite_array("field", field, ndim=2)
    wy = _cells(window, lengths[0], f.shape[0])
    wx = _cells(window, lengths[1], f.shape[1])
    out = uniform_filter(f, size=(wy, wx), mode="wrap")
    # a box spanning a whole axis is that axis' mean (uniform_filter's even-size rule aside)
    if wy >= f.shape[0]:
        out = np.broadcast_to(out.mean(axis=0), f.shape).copy()
    if wx >= f.shape[1]:
        out = np.broadcast_to(out.mean(axis=1, keepdims=True), f.shape).copy()
    return out


def windowed_hs_terms_2d(pressure: np.ndarray, lengths: tuple[float, float], window: float,
                         table: dict, mean_pressure: float) -> dict:
    """``μ_hs``, ``μ_hs,y`` and ``A_c`` of the hybrid on a map, the law read at the box-averaged
    low-slope pressure.

    Parameters
    ----------
    pressure
        Low-slope pressure ``σ_ls(x, y)`` [MPa], ``(ny, nx)``.
    lengths
        ``(Ly, Lx)`` [mm].
    window
        Cell side ``λ_c`` [mm].
    table
        The map's law at the solve's speed (keys ``separation``, ``pressure``,
        ``contact_fraction``, ``shear_stress``, optionally ``shear_stress_y``).
    mean_pressure
        ``σ0`` [MPa] > 0.

    Returns
    -------
    dict
        ``friction_hs``, ``friction_hs_y`` [-] and ``contact_fraction`` [-].
    """
    pbar = np.maximum(window_average_2d(pressure, lengths, window), 0.0)
    sig, alpha, tau = law_in_pressure(table)
    out = {"friction_hs": float(np.mean(np.interp(pbar, sig, tau))) / mean_pressure,
           "contact_fraction": float(np.mean(np.interp(pbar, sig, alpha))),
           "friction_hs_y": 0.0}
    if "shear_stress_y" in table:
        sig_y, _, tau_y = law_in_pressure(lateral_table(table))
        out["friction_hs_y"] = float(np.mean(np.interp(pbar, sig_y, tau_y))) / mean_pressure
    return out


def lateral_table(table: dict) -> dict:
    """The law ``table`` with its lateral stress ``Δτ_hs,y`` (``shear_stress_y``) in place of
    ``Δτ_hs``: read through it, ``Δτ_hs,y`` is interpolated as ``Δτ_hs`` is (the same
    separations, pressures and interpolant)."""
    return {**table, "shear_stress": table["shear_stress_y"]}
