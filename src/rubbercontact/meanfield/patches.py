r"""Where a mode in partial contact dissipates: the patch spectrum (1D).

The exact identity of :mod:`.friction`, ``μσ0 = Σ_k var σ_k · (−k Im M(k))``, weighs the
pressure power at each wavenumber ``k`` with the half-space's loss at *that* wavenumber;
in 1D ``−k Im M(k) = −2 Im[1/E_r(kv)]``. Persson's friction puts all the pressure power of a
mode ``q`` at ``k = q``. That is exact in full contact, but a mode whose pressure is confined
to contact patches narrower than its wavelength carries its power at the harmonics of the
patches, which dissipate at the higher frequencies ``n q v``.

The exact 1D limit: one sine
----------------------------
A sine ``Δ cos qx`` pressed on an elastic half-space (plane strain) to the mean pressure
``p̄ < p* = qΔE_r/2`` touches on ``|qx| < α`` with (Westergaard; Johnson, *Contact
Mechanics*, §13.2)

.. math:: p̄ = p^* \sin^2(α/2),\qquad
          p(θ) = 2p^*\cos(θ/2)\sqrt{\sin^2(α/2) − \sin^2(θ/2)},\quad θ = qx,

so the contact fraction is ``r = α/π = (2/π) arcsin √(p̄/p*)`` (:func:`westergaard_fraction`;
Persson's ``erf(p̄/p*)`` lies below it at small loads; the BEM reproduces it,
tests/test_meanfield_patches.py). Its harmonics ``n = 1, 2, …`` carry the fractions
``h_n(r)`` of the pressure variance
(:func:`harmonic_fractions`, an FFT of ``p(θ)``; in full contact ``h_1 = 1``). To first order
in the loss, the pressure keeps this elastic shape, and the friction of the sliding sine is

.. math:: μσ_0 = \mathrm{var}\,p · Σ_n h_n(r)\,(−2\,\mathrm{Im}[1/E_r(n q v)]),

which the BEM confirms at 1 mm/s (tests/test_meanfield_patches.py; at higher speeds the
sliding patch is asymmetric and stiffer than this shape, and the estimate is low).

In the mean-field theory
------------------------
Mode ``i`` carries the pressure power ``(A S)_i s_i`` (:mod:`.friction`); the patch spectrum
spreads it over the harmonics of a sine at the *local contact fraction* ``r_i``, i.e. replaces
the mode's friction stress ``f_i = s_i (−2 Im[1/E_r(q_i v)])`` by
``s_i Σ_n h_n(r_i) (−2 Im[1/E_r(n q_i v)])``. What ``r_i`` is depends on how the patches of
mode ``i`` sit (``MeanFieldOptions.dissipation``):

* ``"patch"``: one patch per wavelength of the mode, ``r_i = A(ζ_i)`` — the picture of a dense
  spectrum, where the contact resolved at ``ζ_i`` is made of the asperities of that scale;
* ``"cascade"``: the wave forms its patches inside those of the longer waves,
  ``r_i = A(ζ_i)/A(ζ_{i−1})`` — scale separation, the picture of a sine series;
* ``"mode"``: no spreading (Persson's, ``h_1 = 1``).

docs/validation/meanfield.md compares them against the BEM. The harmonics are tabulated for
``r ≥`` :data:`R_MIN`; below, the patch is a Hertzian line contact whose spectrum is a
function of ``n r`` alone, so the table's last row is reused with ``n`` scaled by
``R_MIN/r``.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import lru_cache

import numpy as np
from scipy.special import j1

from ..materials.protocol import Material

#: Smallest tabulated contact fraction (below it the Hertzian scaling in ``n r``).
R_MIN = 1e-3
#: Contact fractions of the table (log-spaced) and FFT samples per period.
TABLE_ROWS = 41
SAMPLES = 2**15
#: Harmonics 1..EXACT_HARMONICS kept one by one; above, log bins of this width (factor).
EXACT_HARMONICS = 4
BIN_FACTOR = 2**0.5
#: Points per decade of frequency on which the loss is tabulated (:func:`patch_loss`).
LOSS_PER_DECADE = 200
#: :class:`WidthLoss` tables: points per decade in ``qa`` and in ``q``, the smallest ``qa``,
#: and the harmonics summed (one by one up to the first, then log-spaced to the last).
WIDTH_PER_DECADE, WAVENUMBER_PER_DECADE, SMALLEST_QA = 40, 20, 1e-6
COMB_EXACT, COMB_LAST, COMB_PER_DECADE = 32, 1e8, 40


def westergaard_fraction(pressure_ratio) -> np.ndarray:
    """Contact fraction ``(2/π) arcsin √x`` of one elastic sine at ``x = p̄/p*`` [-] (1 at
    ``x ≥ 1``: full contact)."""
    x = np.clip(np.asarray(pressure_ratio, float), 0.0, 1.0)
    return 2.0 / np.pi * np.arcsin(np.sqrt(x))


def westergaard_pressure(theta: np.ndarray, fraction: float) -> np.ndarray:
    """``p(θ)/p*`` of one sine at the contact fraction ``r = α/π`` (module docstring)."""
    s2 = np.sin(np.pi * fraction / 2) ** 2
    return 2.0 * np.cos(theta / 2) * np.sqrt(np.maximum(s2 - np.sin(theta / 2) ** 2, 0.0))


def harmonic_fractions(fraction: float, samples: int = SAMPLES) -> np.ndarray:
    """``h_n``, ``n = 1 … samples/2``: the share of the pressure variance in harmonic ``n``
    of one sine at the contact fraction ``fraction`` (sums to 1)."""
    theta = 2 * np.pi * (np.arange(samples) / samples)
    theta = np.where(theta > np.pi, theta - 2 * np.pi, theta)
    c = np.fft.rfft(westergaard_pressure(theta, min(float(fraction), 1.0)))[1:]
    power = np.abs(c) ** 2
    if fraction >= 1.0:                       # full contact: the fundamental only
        power = np.zeros_like(power)
        power[0] = 1.0
    return power / power.sum()


def _bins(n_max: int) -> list[np.ndarray]:
    edges = [float(EXACT_HARMONICS) + 0.5]
    while edges[-1] < n_max:
        edges.append(edges[-1] * BIN_FACTOR)
    n = np.arange(1, n_max + 1)
    out = [np.array([k - 1]) for k in range(1, EXACT_HARMONICS + 1)]
    for lo, hi in zip(edges[:-1], edges[1:], strict=False):
        idx = np.nonzero((n > lo) & (n <= hi))[0]
        if idx.size:
            out.append(idx)
    return out


@lru_cache(maxsize=1)
def harmonic_table() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(r, n_b, h_b)``: contact fractions ``(R,)``, the binned harmonics' power-weighted
    numbers ``(R, B)`` and variance shares ``(R, B)``, computed once per process (its
    resolution is checked in docs/validation/meanfield.md, "Cost")."""
    rs = np.geomspace(R_MIN, 1.0, TABLE_ROWS)
    bins = _bins(SAMPLES // 2)
    n = np.arange(1, SAMPLES // 2 + 1, dtype=float)
    nb, hb = np.ones((rs.size, len(bins))), np.zeros((rs.size, len(bins)))
    for j, r in enumerate(rs):
        h = harmonic_fractions(r)
        for b, idx in enumerate(bins):
            hb[j, b] = h[idx].sum()
            nb[j, b] = np.sum(h[idx] * n[idx]) / hb[j, b] if hb[j, b] > 0 else n[idx].mean()
    return rs, nb, hb


def _rows(fraction: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Harmonic numbers and shares at the fractions (log-linear between table rows)."""
    rs, nb, hb = harmonic_table()
    r = np.clip(fraction, 0.0, 1.0)
    x = np.log(np.maximum(r, R_MIN))
    k = np.clip(np.searchsorted(np.log(rs), x) - 1, 0, rs.size - 2)
    t = ((x - np.log(rs[k])) / (np.log(rs[k + 1]) - np.log(rs[k])))[..., None]
    n = np.exp((1 - t) * np.log(nb[k]) + t * np.log(nb[k + 1]))
    h = (1 - t) * hb[k] + t * hb[k + 1]
    n = n * (R_MIN / np.maximum(r, 1e-12))[..., None] ** (r < R_MIN)[..., None]
    return n, h / h.sum(axis=-1, keepdims=True)


#: A filter of the loss: ``(ω [rad/s], −2 Im[1/E_r(ω)] [1/MPa]) -> loss [1/MPa]`` read in
#: its place (:func:`rubbercontact.meanfield.bands.strip_bands`: the friction is linear in
#: the loss, so a band's indicator splits it by frequency band); None is the loss itself.
LossFilter = Callable[[np.ndarray, np.ndarray], np.ndarray]


def patch_loss(fraction, wavenumbers, material: Material, velocity,
               nu: float, loss_filter: LossFilter | None = None) -> np.ndarray:
    """``Σ_n h_n(r) (−2 Im[1/E_r(n q v)])`` [1/MPa] for each node (shape of ``fraction``,
    ``(..., n_q)``; ``velocity`` broadcast over the leading axes). At ``r = 1`` it is the
    mode's own loss ``−2 Im[1/E_r(qv)]``, so ``f_i = s_i ·`` this in full contact.
    ``loss_filter`` (:data:`LossFilter`) replaces the loss by its filtered value."""
    fraction = np.asarray(fraction, float)
    if fraction.ndim > 1:       # one speed at a time: (speeds, nodes, bins) would not fit
        v = np.broadcast_to(np.asarray(velocity, float), fraction.shape[:-1])
        return np.stack([patch_loss(f, wavenumbers, material, vi, nu, loss_filter)
                         for f, vi in zip(fraction, v, strict=True)])
    n, h = _rows(fraction)
    v = np.asarray(velocity, float)[..., None, None]
    omega = n * np.asarray(wavenumbers, float)[:, None] * np.abs(v)
    loss = (_loss_interpolant(material, nu, omega, loss_filter)
            * np.sign(v))                                          # E(−ω) = conj E(ω)
    return np.sum(h * loss, axis=-1)


def _loss_interpolant(material: Material, nu: float, omega: np.ndarray,
                      loss_filter: LossFilter | None = None) -> np.ndarray:
    """``−2 Im[1/E_r(ω)]`` [1/MPa] at ``omega`` [rad/s], read off a log grid of
    :data:`LOSS_PER_DECADE` points per decade (the loss is smooth in ``log ω``, and a speed
    sweep would otherwise evaluate the modulus at every harmonic of every node and speed),
    then through ``loss_filter`` if given."""
    if loss_filter is not None:
        return loss_filter(omega, _loss_interpolant(material, nu, omega))
    pos = omega[omega > 0]
    if pos.size == 0:
        return np.zeros_like(omega)
    # grid nodes at fixed multiples of 1/LOSS_PER_DECADE: every call reads the same nodes
    lo = np.floor(np.log10(pos.min()) * LOSS_PER_DECADE)
    hi = np.ceil(np.log10(pos.max()) * LOSS_PER_DECADE)
    grid = np.arange(lo, hi + 2) / LOSS_PER_DECADE
    e_r = material.complex_modulus(10.0**grid) / (1.0 - nu**2)
    table = -2.0 * np.imag(1.0 / e_r)
    out = np.interp(np.log10(np.maximum(omega, 10.0**grid[0])), grid, table)
    return np.where(omega > 0, out, 0.0)


def hertz_spectrum(z) -> np.ndarray:
    """``(2J1(z)/z)²``: the power of an elliptical (Hertzian) line-contact pressure at
    ``z = ka`` relative to ``k = 0`` [-]."""
    z = np.asarray(z, float)
    safe = np.where(z > 1e-8, z, 1.0)
    return np.where(z > 1e-8, (2.0 * j1(safe) / safe) ** 2, 1.0)


class WidthLoss:
    r"""Loss [1/MPa] of the pressure variance a strip gains (or loses) when its half-width
    changes from ``a`` to ``a'`` at fixed load.

    A strip of half-width ``a`` formed by the wave ``q`` recurs once per period ``2π/q``;
    its Hertzian pressure carries at the harmonics ``k_n = n q`` the power
    ``∝ F(k_n a) = (2J1(k_n a)/(k_n a))²``. At fixed load a change of width changes the power
    at each harmonic by ``F(k_n a') − F(k_n a)`` (nothing at ``k → 0``: the load stays where
    it is), so the variance it adds dissipates at

    .. math:: \frac{Σ_n [F(nqa') − F(nqa)]\,(−2\,\mathrm{Im}[1/E_r(nqv)])}
                    {Σ_n [F(nqa') − F(nqa)]}.

    (docs/validation/meanfield.md compares it with booking it at the harmonics of the wave
    that bends the strip.) Tabulated once per cascade on a grid of ``qa`` and ``q``; the
    harmonic sum is log-binned above :data:`COMB_EXACT`. ``loss_filter``
    (:data:`LossFilter`) replaces the loss by its filtered value.
    """

    def __init__(self, material: Material, velocity: float, nu: float,
                 q_min: float, q_max: float, loss_filter: LossFilter | None = None):
        v = float(velocity)
        n = np.concatenate([np.arange(1.0, COMB_EXACT + 1),
                            np.geomspace(COMB_EXACT + 1, COMB_LAST, int(
                                np.log10(COMB_LAST / COMB_EXACT) * COMB_PER_DECADE))])
        dn = np.gradient(n)
        dn[:COMB_EXACT] = 1.0
        lo, hi = np.log10(q_min) - 0.1, np.log10(q_max) + 0.1
        self.log_q = np.linspace(lo, hi, max(2, int((hi - lo) * WAVENUMBER_PER_DECADE) + 2))
        self.log_z = np.linspace(np.log10(SMALLEST_QA), np.log10(np.pi),
                                 int((np.log10(np.pi / SMALLEST_QA)) * WIDTH_PER_DECADE) + 2)
        f = hertz_spectrum(10.0 ** self.log_z[:, None] * n[None, :]) * dn     # (Z, N)
        omega = n[None, :] * 10.0 ** self.log_q[:, None] * abs(v)               # (Q, N)
        loss = _loss_interpolant(material, nu, omega, loss_filter)              # ≥ 0
        self.sign = float(np.sign(v))                        # E(−ω) = conj E(ω)
        self.power = np.log(f.sum(axis=1))                                      # (Z,)
        # both sums are smooth in log qa and log q: interpolated as logs
        self.dissipation = np.log(np.maximum(f @ loss.T, 1e-300))               # (Z, Q)
        self.loss_range = (float(loss.min()), float(loss.max()))

    def _tables(self, z: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        lz = np.clip(np.log10(np.maximum(z, SMALLEST_QA)), self.log_z[0], self.log_z[-1])
        lq = np.clip(np.log10(q), self.log_q[0], self.log_q[-1])
        # uniform grids: the cell index is arithmetic
        fz = (lz - self.log_z[0]) / (self.log_z[1] - self.log_z[0])
        fq = (lq - self.log_q[0]) / (self.log_q[1] - self.log_q[0])
        iz = np.clip(fz.astype(int), 0, self.log_z.size - 2)
        iq = np.clip(fq.astype(int), 0, self.log_q.size - 2)
        tz, tq = fz - iz, fq - iq
        d = self.dissipation
        diss = np.exp((1 - tz) * ((1 - tq) * d[iz, iq] + tq * d[iz, iq + 1])
                      + tz * ((1 - tq) * d[iz + 1, iq] + tq * d[iz + 1, iq + 1]))
        power = np.exp((1 - tz) * self.power[iz] + tz * self.power[iz + 1])
        return power, diss

    def __call__(self, wavenumber, half_width, new_half_width) -> np.ndarray:
        """The loss [1/MPa] for strips of the waves ``wavenumber`` [rad/mm] going from
        ``half_width`` to ``new_half_width`` [mm] (arrays of one shape)."""
        q = np.asarray(wavenumber, float)
        p0, d0 = self._tables(q * np.asarray(half_width, float), q)
        p1, d1 = self._tables(q * np.asarray(new_half_width, float), q)
        dp = p1 - p0
        tiny = np.abs(dp) <= 1e-9 * np.maximum(p0, p1)
        loss = np.where(tiny, d1 / p1, (d1 - d0) / np.where(tiny, 1.0, dp))
        return self.sign * np.clip(loss, *self.loss_range)
