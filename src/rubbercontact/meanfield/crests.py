r"""A strip's crest under a wave: the compound crest and the modulus of a sliding strip.

Used by the strip cascade (:mod:`.strips`). A line contact of half-width ``a`` centred at
``c`` on the gap ``g(x)`` (plane strain, modulus ``E_r``) has bounded pressure at both edges
when it is in moment balance and then carries the load (Johnson, *Contact Mechanics*, §2.8)

.. math:: ∫_{−a}^{a} \frac{g'(c + ξ)}{\sqrt{a^2 − ξ^2}} dξ = 0,\qquad
          W = \frac{E_r}{2}∫_{−a}^{a} \frac{ξ\, g'(c + ξ)}{\sqrt{a^2 − ξ^2}} dξ.

For the crest of a strip, ``g = κx²/2 − Δ cos(qx + φ)`` (the parent's parabola and a
shorter wave), with ``ψ = qc + φ``:

* moment balance: ``κc + qΔ J0(qa) sin ψ = 0``, i.e. ``c`` is a stationary point of
  ``G(c) = κc²/2 − Δ J0(qa) cos(qc + φ)``, the gap seen through the Chebyshev weight
  (at ``a → 0`` the compound gap itself). The contact sits on the highest compound crest:
  the lowest minimum of ``G`` (:func:`crest_phase`, among the crests nearest the parent's,
  where the parabola stands for the parent);
* load: ``W = (πE_r a²/4) κ_eff``, ``κ_eff = κ + q²Δ cos ψ · 2J1(qa)/(qa)``
  (:func:`bending_share`).

The neighbouring crest. Where ``q²Δ J0(qa) > κ`` the compound gap ``G`` has more than one
minimum; the strip sits on the lowest, and the next one, a height ``ΔG`` higher and ``d``
away (:func:`neighbour_crest`), comes into contact when the rubber droops onto it. Outside a
Hertzian line contact of half-width ``a`` on a parabola ``κ`` (plane strain) the separation
is ``(κ/2)[x√(x² − a²) − a² arccosh(x/a)]``, of slope ``κ√(x² − a²)``, i.e.
``κx²/2 − (a²κ/2)(ln(2x/a) + ½)`` at ``x ≫ a`` (tests/test_meanfield_crests.py): the
rubber droops at ``d`` by ``(2W/πE_r)(ln(2d/a) + ½)``, ``2W/πE_r = a²κ/2``. Two contacts
sharing the load ``W₁ + W₂ = W`` (half-widths ``a_j = a√(W_j/W)``) are compatible when the
droops differ by the crests' heights,

.. math:: \frac{a^2κ}{2}\Big[\frac{W_1}{W}\Big(\ln\frac{2d}{a_1} + \tfrac12\Big)
          − \frac{W_2}{W}\Big(\ln\frac{2d}{a_2} + \tfrac12\Big)\Big] = ΔG,

which gives the neighbour's share ``W₂/W`` (:func:`neighbour_share`; 0 if even the whole
load leaves a gap). Two line contacts carry the load on more area than one (each ``a_j ∝
√W_j``): this is the area a single compound crest misses at small loads.

A sliding strip is loaded in the time ``2a/v``; its modulus is ``|E_r|`` at
``ω = max(πv/(2a), qv)`` (:class:`StripModulus`, the rule of
:func:`~.sine.sliding_fraction`). The wave's part of the gap is pressed at its own
frequency where the strip is wider than the wave, so its term in ``κ_eff`` carries the ratio
of the two moduli (1 for a strip narrower than the wave).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.special import j1, jn_zeros

from ..materials.protocol import Material

#: Crest phases ``φ`` of a wave against a strip (midpoints of equal steps); the cascade's.
PHASES = 16
#: Smallest strip fraction of the cascade (the modulus table reaches its frequency).
SMALLEST_FRACTION = 1e-7
#: First zero of J1.
BESSEL_ZERO = float(jn_zeros(1, 1)[0])
#: The compound crest (:func:`crest_cosine`): Newton steps, range and points of its table.
CREST_NEWTON = 8
CREST_RANGE = (1e-4, 1e4)
CREST_POINTS = 2000
#: Points per decade of frequency of a strip's modulus table (:class:`StripModulus`).
MODULUS_PER_DECADE = 100
#: Crests searched either side of the parent's for the two lowest minima of ``G``
#: (:func:`compound_minima`), and the bisection steps of :func:`neighbour_share`.
NEIGHBOUR_CRESTS, SHARE_BISECTIONS = 2, 40


class StripModulus:
    """``|E_r|`` [MPa] of a sliding strip at the frequency of its contact time,
    ``ω = max(πv/(2a), qv)`` (``q`` the wave that formed it; :func:`sliding_fraction`), read
    off a log grid in ``ω`` (:data:`MODULUS_PER_DECADE` points per decade)."""

    def __init__(self, material: Material, velocity: float, nu: float,
                 q_min: float, q_max: float):
        self.speed = abs(float(velocity))
        if self.speed == 0.0:
            return
        # from the longest wave's own frequency to that of its narrowest strip,
        # a = SMALLEST_FRACTION · π/q_max: ω = q_max v/(2 SMALLEST_FRACTION)
        lo = np.log10(q_min * self.speed) - 1.0
        hi = np.log10(q_max * self.speed / (2 * SMALLEST_FRACTION)) + 1.0
        self.grid = np.linspace(lo, hi, int((hi - lo) * MODULUS_PER_DECADE) + 2)
        self.table = np.abs(material.complex_modulus(10.0**self.grid)) / (1.0 - nu**2)

    def __call__(self, half_width, wavenumber) -> np.ndarray:
        """``|E_r(max(πv/(2a), qv))|`` at the half-widths ``a`` [mm] of strips formed by
        waves of wavenumber ``q`` [rad/mm] (1 at ``v = 0``: only ratios are used)."""
        if self.speed == 0.0:
            return np.ones(np.broadcast(half_width, wavenumber).shape)
        omega = np.maximum(np.pi * self.speed / (2 * np.asarray(half_width)),
                           np.asarray(wavenumber) * self.speed)
        return np.interp(np.log10(omega), self.grid, self.table)


def bending_share(wavenumber: float, half_width) -> np.ndarray:
    """``2J1(qa)/(qa)`` up to its first zero, 0 beyond [-]: the share of a wave that bends a
    strip of half-width ``a`` [mm] (module docstring)."""
    z = wavenumber * np.asarray(half_width, float)
    safe = np.where((z > 0) & (z < BESSEL_ZERO), z, 1.0)
    return np.where(z < BESSEL_ZERO, np.where(z > 0, 2 * j1(safe) / safe, 1.0), 0.0)


@dataclass(frozen=True)
class CompoundMinima:
    """The two lowest local minima of ``G/A = u²/(2b) − cos(u + φ)`` (``u = qc``, ``b =
    q²A/κ > 0``): values ``g`` and positions ``u``; the second ``inf``/NaN where there is one
    only."""

    g1: np.ndarray
    u1: np.ndarray
    g2: np.ndarray
    u2: np.ndarray


def compound_minima(b, phase) -> CompoundMinima:
    """Newton from the crests ``k = −``:data:`NEIGHBOUR_CRESTS` ``…`` of the cosine (the
    parent's and its neighbours); a start that does not end on a minimum is dropped, and the
    second minimum is the lowest one away from the first (Newton may land twice on one)."""
    b, phase = np.broadcast_arrays(np.asarray(b, float), np.asarray(phase, float))
    gs, us = [], []
    for k in range(-NEIGHBOUR_CRESTS, NEIGHBOUR_CRESTS + 1):
        u = 2 * np.pi * k - phase
        for _ in range(CREST_NEWTON):
            g1 = u / b + np.sin(u + phase)
            g2 = 1 / b + np.cos(u + phase)
            u = u - np.where(g2 > 0, g1 / np.where(g2 > 0, g2, 1.0), 0.0)
        minimum = ((1 / b + np.cos(u + phase) > 0)
                   & (np.abs(u / b + np.sin(u + phase)) < 1e-8 * (1 + np.abs(u) / b)))
        gs.append(np.where(minimum, 0.5 * u**2 / b - np.cos(u + phase), np.inf))
        us.append(u)
    gs, us = np.array(gs), np.array(us)
    first = np.argmin(gs, axis=0)[None]
    g1, u1 = np.take_along_axis(gs, first, 0)[0], np.take_along_axis(us, first, 0)[0]
    others = np.where(np.abs(us - u1) > 0.1, gs, np.inf)
    second = np.argmin(others, axis=0)[None]
    g2 = np.take_along_axis(others, second, 0)[0]
    u2 = np.where(np.isfinite(g2), np.take_along_axis(us, second, 0)[0], np.nan)
    return CompoundMinima(g1, u1, g2, u2)


def crest_phase(curvature, amplitude, wavenumber: float, phase) -> np.ndarray:
    """The wave's phase ``ψ = qc + φ`` at the centre ``c`` of a strip on the compound crest.

    ``c`` minimises ``G(c) = κc²/2 − A cos(qc + φ)`` (the gap seen through the strip's
    Chebyshev weight, ``A = Δ J0(qa)``: ``G'(c) = 0`` is the strip's moment balance, module
    docstring) among the crests of ``A cos`` nearest the parent's (:func:`compound_minima`;
    ``A < 0`` is ``|A|`` with the phase shifted by ``π``). ``curvature`` ``κ`` [1/mm],
    ``amplitude`` ``A`` [mm], ``wavenumber`` [rad/mm], ``phase`` ``φ`` [rad]; arrays
    broadcast.
    """
    kappa, amp, phase = np.broadcast_arrays(np.asarray(curvature, float),
                                            np.asarray(amplitude, float),
                                            np.asarray(phase, float))
    b = wavenumber**2 * np.abs(amp) / kappa
    flat = b <= 0                                   # no wave: the parent's crest
    m = compound_minima(np.where(flat, 1.0, b), phase + np.where(amp < 0, np.pi, 0.0))
    return np.where(flat | ~np.isfinite(m.g1), phase, m.u1 + phase)


@dataclass(frozen=True)
class CrestTables:
    """On a log grid ``ln b`` (:data:`CREST_RANGE`, :data:`CREST_POINTS`) × the
    :data:`PHASES` crest phases: ``cos ψ`` of the strip's crest, and the neighbouring
    crest's height ``ΔG/A`` and distance ``q d`` (NaN: none)."""

    log_b: np.ndarray
    cos_psi: np.ndarray
    height: np.ndarray
    distance: np.ndarray


@lru_cache(maxsize=1)
def crest_tables() -> CrestTables:
    """:class:`CrestTables`, computed once per process (``G/A`` depends on ``b`` and ``φ``
    alone)."""
    lb = np.linspace(np.log(CREST_RANGE[0]), np.log(CREST_RANGE[1]), CREST_POINTS)
    phi = 2 * np.pi * (np.arange(PHASES) + 0.5) / PHASES
    m = compound_minima(np.exp(lb)[:, None], phi[None, :])
    found = np.isfinite(m.g2)
    return CrestTables(lb, np.cos(m.u1 + phi[None, :]), np.where(found, m.g2 - m.g1, np.nan),
                       np.where(found, np.abs(m.u2 - m.u1), np.nan))


@dataclass(frozen=True)
class PhaseCell:
    """Where ``b = q²A/κ`` falls on a table's uniform grid in ``ln b``, at every crest phase:
    the lower row ``row``, the weight ``t`` of the next and the phase column ``column``
    (shifted by ``π`` where ``A < 0``); ``b`` itself, shape ``(samples, PHASES)``."""

    row: np.ndarray
    t: np.ndarray
    column: np.ndarray
    b: np.ndarray

    @classmethod
    def locate(cls, lb: np.ndarray, curvature, amplitude, wavenumber: float) -> PhaseCell:
        b = wavenumber**2 * np.asarray(amplitude, float) / np.asarray(curvature, float)
        b = np.broadcast_to(b, np.broadcast(b, np.empty(PHASES)).shape)
        x = np.log(np.clip(np.abs(b), np.exp(lb[0]), np.exp(lb[-1])))
        # one linear interpolation on the uniform grid for every phase column at once
        # (the same numbers as np.interp column by column)
        step = lb[1] - lb[0]
        k = np.clip(((x - lb[0]) / step).astype(int), 0, lb.size - 2)
        col = np.broadcast_to(np.arange(PHASES), b.shape)
        col = np.where(b >= 0, col, (col + PHASES // 2) % PHASES)   # A < 0: shifted by π
        return cls(k, (x - lb[k]) / step, col, b)


def crest_cosine(curvature, amplitude, wavenumber: float) -> np.ndarray:
    """``cos ψ`` of :func:`crest_phase` at the :data:`PHASES` crest phases, read off
    :func:`crest_tables`. ``curvature`` [1/mm] and ``amplitude`` [mm] broadcast to
    ``(samples, PHASES)``, the last axis the phases; for ``A < 0`` the phase is shifted by
    ``π`` and ``cos ψ`` changes sign."""
    tables = crest_tables()
    c = PhaseCell.locate(tables.log_b, curvature, amplitude, wavenumber)
    table = tables.cos_psi
    value = (1 - c.t) * table[c.row, c.column] + c.t * table[c.row + 1, c.column]
    return np.where(c.b >= 0, value, -value)


@dataclass(frozen=True)
class NeighbourCrest:
    """The next crest of the compound gap, at each crest phase (NaN: none).

    Attributes
    ----------
    height
        ``ΔG`` [mm]: how much lower it lies than the strip's crest.
    distance
        ``d`` [mm] from the strip's centre.
    """

    height: np.ndarray
    distance: np.ndarray


def neighbour_crest(curvature, amplitude, wavenumber: float) -> NeighbourCrest:
    """The neighbouring crest (module docstring) at the :data:`PHASES` crest phases, as
    :func:`crest_cosine` reads the strip's own: ``curvature`` [1/mm] and ``amplitude``
    (``Δ J0(qa)``, [mm]) broadcast to ``(samples, PHASES)``."""
    tables = crest_tables()
    c = PhaseCell.locate(tables.log_b, curvature, amplitude, wavenumber)

    def read(table):
        lo, hi = table[c.row, c.column], table[c.row + 1, c.column]
        # where the second minimum appears between two grid points, the one that has it
        return np.where(np.isnan(lo), hi, np.where(np.isnan(hi), lo, (1 - c.t) * lo + c.t * hi))

    amp = np.abs(np.broadcast_to(np.asarray(amplitude, float), c.b.shape))
    return NeighbourCrest(amp * read(tables.height), read(tables.distance) / wavenumber)


def neighbour_share(height, distance, half_width, curvature) -> np.ndarray:
    """``W₂/W`` in ``[0, ½]``: the load the neighbouring crest ``height`` [mm] lower and
    ``distance`` [mm] away takes from a strip of half-width ``a`` [mm] on the curvature
    ``κ`` [1/mm] (module docstring; 0 where it stays out of contact or is none)."""
    shape = np.broadcast(half_width, curvature, height, distance).shape
    a, kappa, height, distance = (np.array(x, float).reshape(-1) for x in
                                  np.broadcast_arrays(half_width, curvature, height, distance))
    scale = a**2 * kappa / 2                                    # 2W/(πE_r) [mm]
    with np.errstate(invalid="ignore"):                          # NaN: no neighbour
        idx = np.flatnonzero((scale > 0) & (distance > 2 * a) & np.isfinite(height))
    sc, dg, log2d = scale[idx], height[idx], np.log(2 * distance[idx] / a[idx])

    def excess(w2):
        w1 = 1 - w2
        return sc * (w1 * (log2d - 0.5 * np.log(w1) + 0.5)
                     - w2 * (log2d - 0.5 * np.log(w2) + 0.5)) - dg

    lo, hi = np.full(sc.shape, 1e-12), np.full(sc.shape, 0.5)
    touches = excess(lo) > 0            # else the whole load on the strip leaves a gap
    for _ in range(SHARE_BISECTIONS):
        mid = 0.5 * (lo + hi)
        up = excess(mid) > 0
        lo, hi = np.where(up, mid, lo), np.where(up, hi, mid)
    out = np.zeros(a.shape)
    out[idx] = np.where(touches, 0.5 * (lo + hi), 0.0)
    return out.reshape(shape)
