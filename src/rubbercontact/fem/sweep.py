"""Sweeps of steady sliding tests by continuation: each solution starts the next.

A friction-versus-speed curve over decades, or a load sweep at one speed, is a path
through neighbouring steady problems: one point is solved from the press, every further
one by a homotopy from its neighbour's solution on the same mesh
(:func:`~rubbercontact.fem.steady_sliding`'s ``start``), which costs a fraction of a
fresh solve. The press runs at the middle of the path and the continuation goes outwards
both ways (:func:`continuation_order`): the press is the dear part, and at the ends of a
speed range over decades (rubbery or glassy) it costs several times what it costs in the
middle (BENCHMARKS.md, "Steady FEM"). A point whose continuation fails is solved afresh
(and, failing that, by the transient fallback), so a sweep never stops at one bad point.
"""

from __future__ import annotations

import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from .._validation import finite_array
from ..errors import InputError
from .options import FemOptions
from .result import SlidingTestResult
from .sliding import make_options, steady_sliding


def continuation_order(n: int, first: int | None = None) -> list[tuple[int, int | None]]:
    """The order in which a path of ``n`` points is solved: ``(point, neighbour)`` pairs,
    the neighbour being the point whose solution starts it (None: from the press).

    ``first`` (default the middle, ``n // 2``) is solved from the press; then the points
    after it in turn, each from its predecessor; then those before it, each from its
    successor.
    """
    if n <= 0:
        return []
    k = n // 2 if first is None else int(first)
    if not 0 <= k < n:
        raise InputError(f"first: expected an index in [0, {n}), got {first}")
    return ([(k, None)] + [(i, i - 1) for i in range(k + 1, n)]
            + [(i, i + 1) for i in range(k - 1, -1, -1)])


def steady_sweep(surface, material, mean_pressures: Sequence[float] | float,
                 velocities: Sequence[float] | float, *, first: int | None = None,
                 options: FemOptions | None = None, **changes) -> list[SlidingTestResult]:
    """Steady tests along a path of loads and speeds, each started from the last.

    Parameters
    ----------
    surface, material
        As for :func:`~rubbercontact.fem.steady_sliding`.
    mean_pressures, velocities
        ``p̄`` [MPa] and ``v`` [mm/s]: one value and a sequence (a speed or a load sweep),
        or two sequences of equal length (the path itself). Neighbours in the sequence
        start each other; sort it (e.g. by speed) so that they are close.
    first
        Index of the point solved from the press (default: the middle of the path; see
        :func:`continuation_order`).
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
    out: list[SlidingTestResult | None] = [None] * p.size
    for point in sweep_points(surface, material, p, v, opts, first):
        out[point.index] = point.result
    return out


@dataclass(frozen=True)
class SweepPoint:
    """One point of :func:`sweep_points`: its ``index`` in the path, its ``result`` (None
    if it failed), the ``error`` it failed with, and its ``wall`` time [s]."""

    index: int
    result: SlidingTestResult | None
    error: Exception | None
    wall: float


def sweep_points(surface, material, p: np.ndarray, v: np.ndarray, options: FemOptions,
                 first: int | None = None, errors: tuple[type[Exception], ...] = ()
                 ) -> Iterator[SweepPoint]:
    """The steady tests of a path ``(p[i], v[i])`` in :func:`continuation_order`, each
    started from its neighbour's state. A point failing with one of ``errors`` is yielded
    with its error and passes its neighbour's state on (the solver presses afresh when the
    continuation from it fails); other errors propagate."""
    states: list = [None] * len(p)
    for i, j in continuation_order(len(p), first):
        start = None if j is None else states[j]     # None after a transient fallback
        t0 = time.perf_counter()
        try:
            res = steady_sliding(surface, material, float(p[i]), float(v[i]),
                                 options=options, start=start)
        except errors as exc:
            states[i] = start
            yield SweepPoint(i, None, exc, time.perf_counter() - t0)
            continue
        states[i] = res.state
        yield SweepPoint(i, res, None, time.perf_counter() - t0)
