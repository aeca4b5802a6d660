r"""The high-slope law read at any speed between the speeds it was tabulated at.

The law is an FEM table on ``velocity × pressure`` (:func:`~.law.effective_law`), read per
tabulated speed as plain data (:func:`~.lawtable.law_at_velocity`: ``separation``
ascending, ``pressure``, ``contact_fraction``, ``shear_stress``). A run evaluates it at its
own speeds; the flash temperature (:mod:`rubbercontact.pipeline.flash_hybrid`) needs it at
the reduced speed ``a_T(T) v`` of a heated contact, which falls between them.

Interpolation
-------------
Between the two tabulated speeds ``v_a < v < v_b`` around ``v``, at fixed mean pressure
``σ``, the logarithms linearly in ``ln v``: with ``w = ln(v/v_a)/ln(v_b/v_a)``,

.. math:: \ln u(σ, v) = (1 − w) \ln u_a(σ) + w \ln u_b(σ),

a local power law in the speed, and the same for ``α_hs`` and ``Δτ_hs``; a quantity with
a value ≤ 0 at a node (an FEM mean separation below the surface's mean plane, an elastic
law's ``Δτ = 0``) is blended linearly instead. Logarithms, because near full contact of
the high-slope cell ``u`` falls by decades over a small rise in ``σ`` (the linear law
reaches ``u ~ 1e-20`` mm): a linear blend there jumps by decades as soon as ``w < 1``, and
the interpolant ``σ(u)`` and the low-slope solve jump with it.

The nodes are the union of the two tables' pressures, each table read at the other's
pressures off its own interpolant (:class:`~rubbercontact.halfspace.TabulatedLaw`; beyond
its highest pressure by that interpolant's continuation, stiff in ``σ`` with ``α`` and
``Δτ`` held, as a solve at its speed reads it), so that the blend tends to each table as
``w`` tends to 0 or 1; the zero-load anchor ``σ = 0`` is at the higher of their
anchors' separations (the same high-slope peak). Both tables have ``u`` strictly
decreasing in ``σ``, so the blend has too (either way): it is a law. At a tabulated speed
(relative ``1e-9``) the table is returned as it is, so a solve there is the run's own.

The error is that of a power-law interpolant between the table's speeds (half-decade
apart in the examples): the law's quantities vary smoothly with the speed (the modulus
does), but not as power laws near the loss peak, and a table's rows near full contact
move with the speed. Measured on the linear (VHS) law of a moderate wave (λ = 0.125 mm,
the tests' and benchmarks' SBR, tables continued as a run continues them): the hybrid's μ
at the geometric midpoints between the table's speeds, against the law computed at those
speeds, is within 1–7 % (median 3.4 %) for half-decade steps and 8–15 % for decade
steps; its contact fraction within 0–5 % and 0–14 %. A three-point (quadratic in
``ln v``) rule did not do better at the worst midpoint. Tabulate the law at half-decade
speeds or closer where the flash matters.

Outside the tabulated speeds nothing is extrapolated: a speed below the slowest (above
the fastest) is read at the slowest (fastest) table and :attr:`LawAtSpeed.clamped` says so,
for the caller to report.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..errors import InputError

#: A speed within this relative distance of a tabulated one is that one [-].
SPEED_RTOL = 1e-9


@dataclass(frozen=True)
class SpeedBracket:
    """Where a speed falls among the tabulated ones (:meth:`LawSpeeds.where`).

    Attributes
    ----------
    speed
        The speed asked for [mm/s].
    read_at
        The speed the law is read at [mm/s]: ``speed``, or the tabulated end it is
        clamped to.
    lower, upper
        The tabulated speeds it is interpolated between [mm/s] (equal at a tabulated
        speed or when clamped).
    weight
        ``w`` of the module docstring [-] (0 at ``lower``).
    """

    speed: float
    read_at: float
    lower: float
    upper: float
    weight: float

    @property
    def clamped(self) -> bool:
        """Whether ``speed`` lies outside the tabulated speeds (read at the nearest end)."""
        return not np.isclose(self.read_at, self.speed, rtol=SPEED_RTOL, atol=0.0)


@dataclass(frozen=True)
class LawAtSpeed(SpeedBracket):
    """The law at one speed: where the speed falls (:class:`SpeedBracket`) and the table.

    Attributes
    ----------
    table
        The law as plain data (the keys of :func:`~.lawtable.law_at_velocity`).
    """

    table: dict


class LawSpeeds:
    """A law tabulated at several speeds, read at any speed (module docstring).

    Parameters
    ----------
    tables
        ``{speed [mm/s]: table}``, each table as :func:`~.lawtable.law_at_velocity` gives
        it (e.g. a run's :attr:`~rubbercontact.pipeline.lawstage.LawStage.tables`); at
        least one speed > 0.
    """

    def __init__(self, tables: Mapping[float, dict]) -> None:
        speeds = np.array(sorted(float(v) for v in tables), float)
        if speeds.size == 0 or not np.all(np.isfinite(speeds)) or speeds[0] <= 0:
            raise InputError(f"law tables: expected speeds > 0 mm/s, got {speeds.tolist()}")
        self.speeds = speeds
        self._tables = {float(v): tables[v] for v in tables}
        self._laws: dict[float, object] = {}
        self._pairs: dict[tuple[float, float], _Pair] = {}

    def _law(self, speed: float):
        """The interpolant of the table at a tabulated ``speed``, built once."""
        from .lawtable import tabulated_law_from_dict

        if speed not in self._laws:
            self._laws[speed] = tabulated_law_from_dict(self.table(speed))
        return self._laws[speed]

    def table(self, speed: float) -> dict:
        """The table at a tabulated ``speed`` [mm/s]."""
        return self._tables[float(speed)]

    def where(self, speed: float) -> SpeedBracket:
        """Where ``speed`` [mm/s] > 0 falls: at a tabulated speed, between two (their
        weight), or outside (``clamped`` to the nearest end)."""
        v = float(speed)
        if not (np.isfinite(v) and v > 0):
            raise InputError(f"speed: expected a finite speed > 0 mm/s, got {speed!r}")
        s = self.speeds
        near = np.flatnonzero(np.isclose(s, v, rtol=SPEED_RTOL, atol=0.0))
        if near.size:
            at = float(s[near[0]])
            return SpeedBracket(v, v, at, at, 0.0)
        if v < s[0] or v > s[-1]:
            end = float(s[0] if v < s[0] else s[-1])
            return SpeedBracket(v, end, end, end, 0.0)
        k = int(np.searchsorted(s, v))
        lo, hi = float(s[k - 1]), float(s[k])
        return SpeedBracket(v, v, lo, hi, float(np.log(v / lo) / np.log(hi / lo)))

    def at(self, speed: float) -> LawAtSpeed:
        """The law at ``speed`` [mm/s] > 0: a tabulated table, the interpolation between
        the two around it, or the nearest end's table (``clamped``)."""
        b = self.where(speed)
        lo, hi = b.lower, b.upper
        if lo == hi:
            table = self.table(lo)
        else:
            if (lo, hi) not in self._pairs:  # the same for every weight between them
                self._pairs[lo, hi] = _pair(self.table(lo), self.table(hi),
                                            (self._law(lo), self._law(hi)))
            table = _blend(self._pairs[lo, hi], b.weight)
        return LawAtSpeed(b.speed, b.read_at, lo, hi, b.weight, table=table)


def _in_pressure(table: dict, nodes: np.ndarray, law=None) -> dict:
    """``u``, ``α``, ``Δτ`` of ``table`` at the pressures ``nodes`` [MPa] (> 0), read off
    the law's own interpolant (:class:`~rubbercontact.halfspace.TabulatedLaw`: ``u`` by
    bisection on its ``σ(u)``, ``α`` and ``Δτ`` its companions at that ``u``); at the
    table's own pressures its own rows; beyond its highest pressure, the interpolant's
    continuation."""
    from .lawtable import tabulated_law_from_dict

    law = law if law is not None else tabulated_law_from_dict(table)
    u_tab = np.asarray(table["separation"], float)
    sig_tab = np.asarray(table["pressure"], float)
    span = u_tab[-1] - u_tab[0]
    lo = np.full(nodes.shape, u_tab[0])          # σ(lo) ≥ node: below the table's first
    for _ in range(_BISECTIONS):                 # row for a node beyond its pressures
        short = law.pressure(lo) <= nodes
        if not short.any():
            break
        lo = np.where(short, lo - span, lo)
        span *= 2.0
    hi = np.full(nodes.shape, u_tab[-1])         # σ(hi) = the lowest ≤ node
    for _ in range(_BISECTIONS):
        mid = 0.5 * (lo + hi)
        above = law.pressure(mid) > nodes
        lo, hi = np.where(above, mid, lo), np.where(above, hi, mid)
    u = 0.5 * (lo + hi)
    own = {float(sv): float(uv) for sv, uv in zip(sig_tab, u_tab, strict=True)}
    u = np.array([own.get(float(n), float(x)) for n, x in zip(nodes, u, strict=True)])
    return {"separation": u, "contact_fraction": np.asarray(law.contact_fraction(u), float),
            "shear_stress": np.asarray(law.shear_stress(u), float)}


#: Bisection steps of :func:`_in_pressure`: the bracket shrinks to 2^-60 of the table's
#: range of separations, below the float resolution.
_BISECTIONS = 60


def blend_tables(a: dict, b: dict, weight: float, laws: tuple | None = None) -> dict:
    """The law ``(1 − w) a + w b`` at fixed pressure (module docstring), as plain data.

    Parameters
    ----------
    a, b
        Law tables (:func:`~.lawtable.law_at_velocity`'s keys), ``separation`` ascending.
    weight
        ``w`` in [0, 1].
    laws
        Their :class:`~rubbercontact.halfspace.TabulatedLaw` if already built.
    """
    w = float(weight)
    if not 0.0 <= w <= 1.0:
        raise InputError(f"weight: expected a number in [0, 1], got {weight!r}")
    return _blend(_pair(a, b, laws), w)


@dataclass(frozen=True)
class _Pair:
    """Two tables read at the union of their pressures (what a blend of any weight needs).

    Attributes
    ----------
    nodes
        The union of their pressures > 0 [MPa], ascending.
    a, b
        Each table's ``separation``, ``contact_fraction``, ``shear_stress`` at ``nodes``.
    anchor
        The zero-load anchor's separation [mm] (None: a table without one).
    """

    nodes: np.ndarray
    a: dict
    b: dict
    anchor: float | None


def _pair(a: dict, b: dict, laws: tuple | None) -> _Pair:
    nodes = np.unique(np.concatenate([np.asarray(t["pressure"], float) for t in (a, b)]))
    nodes = nodes[nodes > 0]
    la, lb = laws if laws is not None else (None, None)
    anchors = [_anchor(t) for t in (a, b)]
    return _Pair(nodes, _in_pressure(a, nodes, la), _in_pressure(b, nodes, lb),
                 max(anchors) if all(u is not None for u in anchors) else None)


def _blend(pair: _Pair, w: float) -> dict:
    """The blend of weight ``w`` of a :class:`_Pair`, as plain data."""
    mixed = {k: blend(pair.a[k], pair.b[k], w) for k in pair.a}
    order = np.argsort(-pair.nodes)                          # separation ascending
    out = {"separation": mixed["separation"][order].tolist(),
           "pressure": pair.nodes[order].tolist(),
           "contact_fraction": mixed["contact_fraction"][order].tolist(),
           "shear_stress": mixed["shear_stress"][order].tolist()}
    if pair.anchor is not None and pair.anchor > out["separation"][-1]:
        for k, val in (("separation", pair.anchor), ("pressure", 0.0),
                       ("contact_fraction", 0.0), ("shear_stress", 0.0)):
            out[k].append(val)
    return out


def blend(a: np.ndarray, b: np.ndarray, w: float) -> np.ndarray:
    """A column of the law's table between two speeds at weight ``w`` (module docstring):
    ``a^(1−w) b^w`` where every value of both is > 0, else ``(1 − w) a + w b`` for the
    whole column — one rule per column keeps a monotone ``u(σ)`` monotone, which mixing
    the two rules node by node would not."""
    if np.all(a > 0) and np.all(b > 0):
        return np.exp((1.0 - w) * np.log(a) + w * np.log(b))
    return (1.0 - w) * a + w * b


def blend_values(a: np.ndarray, b: np.ndarray, w: float) -> np.ndarray:
    """The law's readings at given pressures between two speeds, value by value: as
    :func:`blend` where both values are > 0, linear elsewhere (e.g. the zero ``α`` and
    ``Δτ`` at zero pressure), each reading being a value on its own, not a table."""
    both = (a > 0) & (b > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        geo = np.exp((1.0 - w) * np.log(a) + w * np.log(b))
    return np.where(both, geo, (1.0 - w) * a + w * b)


def _anchor(table: dict) -> float | None:
    """The separation [mm] of the table's first zero-pressure row (its zero-load
    anchor), None without one."""
    sig = np.asarray(table["pressure"], float)
    zero = np.flatnonzero(sig <= 0)
    return float(np.asarray(table["separation"], float)[zero[0]]) if zero.size else None
