"""The high-slope law read at the low-slope pressure averaged over one high-slope period.

The law (paper eqs. 1–3) is a mean over one cell ``A_0,hs`` of the high-slope surface:
``Δτ_hs(σ̄)`` is the shear stress of a *periodic array* of high-slope asperities all
loaded to the mean pressure ``σ̄``. The paper's hybrid evaluates it point by point at
the local low-slope pressure ``σ_ls(x)`` (eqs. 6, 8). Where a low-slope contact patch
is narrower than the high-slope wavelength ``λ_hs`` that over-counts: the patch carries
its force on one high-slope crest, not on a whole array of crests at the patch's peak
pressure. With the steep law's friction rising with pressure (0.2 at 0.1 MPa to 0.66 at
4 MPa on the paper's wave), the hybrid then over-predicts friction and — with ``α_hs``
concave in pressure — under-predicts the contact area.

Here the law is read at ``σ̄(x)``, the low-slope pressure averaged over a window of one
high-slope period centred at ``x``::

    μ_hs = <Δτ_hs(σ̄(x))>/σ0,   A_c = <α_hs(σ̄(x))>,   σ̄ = box_λhs * σ_ls.

An isolated patch of force ``F`` (per unit depth) narrower than ``λ_hs`` then contributes
``λ_hs Δτ_hs(F/λ_hs)``: one high-slope period carrying the patch's force. Where the
low-slope pressure varies slowly on ``λ_hs`` (scale separation) ``σ̄ = σ_ls`` and the
paper's hybrid is recovered. The low-slope solve and ``μ_ls`` (eq. 7) are unchanged.
This is an extension of the paper's method, measured against the VHS on two-wave
surfaces without any FEM (``benchmarks/scale_separation.py``).
"""

from __future__ import annotations

import numpy as np
from scipy.ndimage import uniform_filter1d

from .._validation import finite_array
from ..errors import InputError


def window_average(field: np.ndarray, period: float, window: float) -> np.ndarray:
    """Periodic centred moving average of a 1-D field over ``window`` [same units as period].

    Parameters
    ----------
    field
        Values on ``n`` uniform points over one period.
    period
        Period ``L`` [mm].
    window
        Averaging length ``W`` [mm], ``0 < W <= L``. Rounded to whole grid cells (odd
        count, so the window is centred); one cell returns the field unchanged.

    Returns
    -------
    numpy.ndarray
        ``σ̄_i = mean of field over the cells within W/2 of i`` (mean of the field kept).
    """
    f = finite_array("field", field, ndim=1)
    if not 0 < window <= period:
        raise InputError(f"window: must be in (0, period = {period:g}] mm, got {window!r}")
    n = f.size
    w = 2 * int(round(window / period * n / 2 - 0.5)) + 1
    if w >= n:
        return np.full(n, f.mean())
    return uniform_filter1d(f, size=w, mode="wrap")


def law_in_pressure(table: dict, samples: int = 4096
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(σ, α, Δτ)`` of a law table, increasing in ``σ``, from the hybrid's own interpolant.

    The law is sampled through :func:`~rubbercontact.hybrid.law.tabulated_law_from_dict` (the
    interpolation the pointwise hybrid reads), on the table's separations plus ``samples``
    uniform ones, up to where its pressure reaches zero; so at a uniform low-slope pressure the
    windowed reading equals the pointwise one. Beyond the table's highest pressure
    :func:`windowed_hs_terms` holds ``α`` and ``Δτ``, as the tabulated law does below its
    smallest separation.
    """
    from .law import tabulated_law_from_dict

    law = tabulated_law_from_dict(table)
    u_tab = law.separation
    u = np.union1d(u_tab, np.linspace(u_tab[0], u_tab[-1], int(samples)))
    sig = law.pressure(u)
    keep = np.concatenate([[True], sig[1:] < sig[:-1]])   # strictly decreasing part
    u, sig = u[keep], sig[keep]
    order = slice(None, None, -1)                          # increasing in σ
    return sig[order], law.contact_fraction(u)[order], law.shear_stress(u)[order]


def windowed_hs_terms(pressure: np.ndarray, period: float, window: float, table: dict,
                      mean_pressure: float) -> tuple[float, float]:
    """``(μ_hs, A_c)`` of the hybrid with the law read at the window-averaged pressure.

    Parameters
    ----------
    pressure
        Low-slope contact pressure ``σ_ls(x)`` [MPa] on a uniform 1-D grid over ``period``.
    period
        Period of the low-slope solve [mm].
    window
        High-slope period ``λ_hs`` [mm] (the law's averaging cell).
    table
        Law table at the solve's speed (keys ``separation``, ``pressure``,
        ``contact_fraction``, ``shear_stress``; see
        :func:`~rubbercontact.hybrid.law.law_at_velocity`).
    mean_pressure
        ``σ0`` [MPa] > 0.
    """
    p = np.asarray(pressure, float)
    if p.ndim != 1:
        raise InputError("pressure: the windowed hybrid is implemented for 1-D profiles "
                         f"(the paper's plane-strain setting), got shape {p.shape}")
    pbar = np.maximum(window_average(p, period, window), 0.0)
    sig, alpha, tau = law_in_pressure(table)
    mu_hs = float(np.mean(np.interp(pbar, sig, tau))) / mean_pressure
    area = float(np.mean(np.interp(pbar, sig, alpha)))
    return mu_hs, area
