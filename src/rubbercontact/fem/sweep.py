"""Sweeps of steady sliding tests by continuation: each solution starts the next.

A friction-versus-speed curve over decades, or a load sweep at one speed, is a path
through neighbouring steady problems: the first point is solved from the press, every
further one by a homotopy from its predecessor's solution on the same mesh
(:func:`~rubbercontact.fem.steady_sliding`'s ``start``), which costs a fraction of a
fresh solve. A point whose continuation fails is solved afresh (and, failing that, by
the transient fallback), so a sweep never stops at one bad point.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .._validation import finite_array
from ..errors import InputError
from .options import FemOptions
from .result import SlidingTestResult
from .sliding import make_options, steady_sliding


def steady_sweep(surface, material, mean_pressures: Sequence[float] | float,
                 velocities: Sequence[float] | float, *, options: FemOptions | None = None,
                 **changes) -> list[SlidingTestResult]:
    """Steady tests along a path of loads and speeds, each started from the last.

    Parameters
    ----------
    surface, material
        As for :func:`~rubbercontact.fem.steady_sliding`.
    mean_pressures, velocities
        ``p̄`` [MPa] and ``v`` [mm/s]: one value and a sequence (a speed or a load sweep),
        or two sequences of equal length (the path itself). The path is followed in the
        order given; sort it (e.g. by speed) so that neighbours are close.
    options, **changes
        The FEM options (``solver`` must be ``"steady"``).

    Returns
    -------
    list of SlidingTestResult
        One per point, in path order.
    """
    opts = make_options(options, **changes)
    if opts.solver != "steady":
        raise InputError("steady_sweep: continuation is the steady solver's; solver must be "
                         "'steady'")
    p = np.atleast_1d(finite_array("mean_pressures", mean_pressures, ndim=None))
    v = np.atleast_1d(finite_array("velocities", velocities, ndim=None))
    if p.ndim != 1 or v.ndim != 1:
        raise InputError("mean_pressures, velocities: expected numbers or 1-D sequences")
    if p.size == 1:
        p = np.full(v.size, p[0])
    if v.size == 1:
        v = np.full(p.size, v[0])
    if p.size != v.size:
        raise InputError(f"mean_pressures ({p.size}) and velocities ({v.size}): give one "
                         f"value and a sequence, or two sequences of equal length")
    out: list[SlidingTestResult] = []
    state = None
    for pi, vi in zip(p, v, strict=True):
        res = steady_sliding(surface, material, float(pi), float(vi), options=opts,
                             start=state)
        out.append(res)
        state = res.state        # None after a transient fallback: the next starts afresh
    return out
