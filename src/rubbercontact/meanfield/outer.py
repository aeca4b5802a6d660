r"""The wave's crests outside a strip: where the rubber, lifted by the wave's contact inside
the strip, comes down onto them (used by the strip cascade, :mod:`.strips`).

Outside a Westergaard strip
---------------------------
A sine ``Δ cos θ`` (``θ = qx``) in contact over ``|θ| < α`` carries the pressure
``2p* cos(θ/2)√(sin²(α/2) − sin²(θ/2))``; the same analytic function continued outside the
contact is the slope of the separation, ``ds/dθ = 2Δ cos(θ/2)√(sin²(θ/2) − sin²(α/2))``, so
with ``σ = sin(θ/2)``, ``σ_α = sin(α/2)``

.. math:: s(θ) = 2Δ\,\big[σ\sqrt{σ^2 − σ_α^2} − σ_α^2 \operatorname{arccosh}(σ/σ_α)\big],
          \qquad |θ| ≥ α

(:func:`westergaard_separation`): ``Δ(1 − cos θ)`` with no load, 0 in full contact, the
elastic BEM's to its grid (tests/test_meanfield_outer.py).

The rubber rises
----------------
A shorter wave ``Δ_w cos(q_w x + φ)`` forms strips inside a strip of half-width ``a`` at the
strip's mean contact pressure ``x p*_w`` (its residual amplitude ``Δ_r``, the part that does not
bend the strip, :mod:`.strips`). On its crests the rubber's mean surface stands Westergaard's
mean gap ``ū = Δ_r(1 − x + x ln x)`` above the strip's wave, i.e. it is lifted by ``ū`` and
stands ``Δ_r(x − x ln x)`` (:func:`penetration`) below the wave's crest tops. A crest of the
wave outside the strip, at ``θ_k`` of the strip's wave, is as high above that wave as those
inside (the bent part of the wave raises the strip's crest as much), so it interferes by

.. math:: I_k = Δ_r(x − x \ln x) − s(θ_k),

where ``s`` is the strip's separation at the load it keeps. Where ``I_k > 0`` the crest (of
curvature ``q_w²Δ_w``) carries the load ``W_k`` of a line contact of half-width ``a_k`` that
sinks by ``(2W_k/πE)(ln(2d_k/a_k) + ½)`` relative to the strip ``d_k`` away — the
compatibility of two line contacts (:mod:`.crests`), here ``= I_k`` (:func:`crest_load`),
``E = 2p*_w/(q_wΔ_w)``. That load comes off the strip, which lowers ``x`` and narrows the
strip (Westergaard: ``sin²(πr/2)`` in proportion to its load), so the share ``F`` of the
strip's load ``W`` on its outer crests solves ``F = Σ_k W_k(F)/W`` (:func:`outer_load`, false
position; the right side falls as ``F`` grows). The crests are the first
:data:`OUTER_CRESTS` beyond each edge, at :data:`OFFSETS` uniform offsets, within the strip
wave's period; they then form strips of the whole wave at the load-weighted mean
``x_k = W_k/(p*_w λ_w)`` (:mod:`.strips`).

This is where the BEM's contact leaves a strip of the longer wave: on octave ladders the
shorter waves' crests just outside it touch (docs/validation/meanfield.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Crests of the wave considered beyond each edge of a strip, and their uniform offsets
#: (their convergence: docs/validation/meanfield.md, "Cost").
OUTER_CRESTS, OFFSETS = 2, 8
#: False-position steps of the outer crests' load share.
SHARE_ITERATIONS = 6
#: ``u ≥ ½`` against ``ln(u e^{1−2u})``, on which :func:`crest_load` inverts ``u e^{1−2u} = y``
#: (the lower real branch of Lambert's W; the grid reaches contacts ``e^{-40}`` of the
#: distance).
_U = np.concatenate([0.5 + np.geomspace(1e-6, 0.5, 200), np.linspace(1.0 + 1e-3, 40.0, 800)])
_LOG_Y = np.log(_U) + 1 - 2 * _U


def westergaard_separation(theta, fraction) -> np.ndarray:
    """Separation [in units of the sine's amplitude ``Δ``] at the phase ``theta`` [rad] of a
    sine in contact over the share ``fraction`` of its period (module docstring; 0 inside
    the contact). Arrays broadcast."""
    return _separation(np.abs(np.sin(np.asarray(theta, float) / 2)),
                       np.sin(np.pi * np.clip(np.asarray(fraction, float), 0.0, 1.0) / 2))


def _separation(sig, sa) -> np.ndarray:
    """:func:`westergaard_separation` in ``σ = |sin(θ/2)|`` and ``σ_α = sin(α/2)``."""
    out = sig > sa
    safe = np.where(out & (sa > 0), sa, 1.0)
    ratio = np.where(out & (sa > 0), sig / safe, 1.0)
    value = 2 * (sig * np.sqrt(np.maximum(sig**2 - sa**2, 0.0)) - sa**2 * np.arccosh(ratio))
    return np.where(out, np.where(sa > 0, value, 2 * sig**2), 0.0)


def penetration(ratio) -> np.ndarray:
    """``x − x ln x`` [-]: how far the crest tops of a sine under ``x = p̄/p*`` stand above the
    rubber's mean surface, in units of its amplitude (1 in full contact)."""
    x = np.clip(np.asarray(ratio, float), 1e-300, 1.0)
    return x - x * np.log(x)


@dataclass(frozen=True)
class OuterLoad:
    """The load a strip's outer crests take (arrays over the strips).

    Attributes
    ----------
    share
        ``F`` [-]: share of the strip's load on its outer crests.
    ratio
        Load-weighted mean ``x_k`` [-] of the outer crests' strips (0 where none touches).
    """

    share: np.ndarray
    ratio: np.ndarray


def crest_load(interference, distance, curvature, modulus) -> np.ndarray:
    """Load [N/mm] of a crest of curvature ``κ`` [1/mm] whose top interferes by
    ``interference`` [mm] with the rubber, ``distance`` [mm] from the strip that holds the
    rubber down (plane-strain modulus ``E`` [MPa]): a line contact of half-width ``a_f``,
    ``W = πEκa_f²/4``, sinks by ``(2W/πE)(ln(2d/a_f) + ½)`` relative to the strip (the
    compatibility of :mod:`.crests`' line contacts), solved with Lambert's W (0 where
    ``interference ≤ 0``; at most the contact of half-width ``2d``)."""
    i, d, k, e = np.broadcast_arrays(*(np.asarray(v, float) for v in
                                       (interference, distance, curvature, modulus)))
    # with t = ln(2d/a_f): e^{-2t}(t + 1/2) = I/(2κd²) =: y, u = t + 1/2: u e^{1-2u} = y
    y = np.clip(i / (2 * k * d**2), 1e-300, 0.5)
    u = np.interp(-np.log(y), -_LOG_Y, _U)          # −ln y rises with u
    half = 2 * d * np.exp(0.5 - u)
    return np.where(i > 0, np.pi * e * k * half**2 / 4, 0.0)


def outer_load(half_width, strip_wavenumber, strip_amplitude, contact_pressure,
               wavenumber: float, amplitude: float, residual, p_star: float) -> OuterLoad:
    """The outer crests' load (module docstring).

    Parameters
    ----------
    half_width, strip_wavenumber, strip_amplitude, contact_pressure
        The strips: ``a`` [mm], the wavenumber [rad/mm] and amplitude ``κ/q_s²`` [mm] of the
        wave whose strips they are, and their mean contact pressure [MPa] (arrays of one
        shape).
    wavenumber, amplitude, residual, p_star
        The shorter wave: ``q_w`` [rad/mm], ``Δ_w`` [mm], the share of it that forms strips
        inside the strip (array) and ``p*_w`` [MPa].
    """
    n = np.asarray(half_width).size
    share, ratio = np.zeros(n), np.zeros(n)
    a, qs, amp_s, pc, res = (np.asarray(v, float).reshape(-1)[:, None, None] for v in
                             (half_width, strip_wavenumber, strip_amplitude, contact_pressure,
                              np.broadcast_to(residual, (n,))))
    lam = 2 * np.pi / wavenumber
    offset = (np.arange(OFFSETS) + 0.5) / OFFSETS
    dist = a + lam * (np.arange(OUTER_CRESTS)[None, None, :] + offset[None, :, None])
    inside = dist < np.pi / qs                       # within the strip wave's period
    sig = np.abs(np.sin(qs * np.minimum(dist, np.pi / qs) / 2))
    edge = np.sin(np.pi * np.clip(a * qs / np.pi, 0.0, 1.0) / 2)
    modulus = 2 * p_star / (wavenumber * amplitude)

    def crest_loads(left, arrays):
        """The outer crests' loads of strips holding the share ``left`` of their load, and
        their share of it (``arrays``: the strips' ``a, pc, res, amp_s, edge, sig, dist,
        inside``)."""
        a, pc, res, amp_s, edge, sig, dist, inside = arrays
        x = np.clip(pc * left / np.maximum(res * p_star, 1e-300), 0.0, 1.0)
        # Westergaard: the strip at the load W(1 − F) keeps sin²(πr/2) ∝ its load
        gap = amp_s * _separation(sig, edge * np.sqrt(left))
        interference = np.where(inside, res * amplitude * penetration(x) - gap, 0.0)
        w = crest_load(interference, dist, wavenumber**2 * amplitude, modulus)
        # both edges, averaged over the offsets; over the strip's load per period
        return w, 2 * np.mean(np.sum(w, axis=2), axis=1) / (pc * 2 * a)[:, 0, 0]

    arrays = (a, pc, res, amp_s, edge, sig, dist, inside)
    # the outer crests interfere most with the whole load on the strip: only the strips
    # whose crests do then are solved for, g(F) = F_k(F) − F = 0 on [0, F_k(0)] (g falls)
    first = crest_loads(np.ones((n, 1, 1)), arrays)[1]
    m = np.flatnonzero(first > 0)
    arrays = tuple(v[m] for v in arrays)
    lo, hi = np.zeros(m.size), np.minimum(first[m], 1.0)
    g_lo = first[m] - lo
    g_hi = crest_loads(1 - hi[:, None, None], arrays)[1] - hi
    for _ in range(SHARE_ITERATIONS):
        # false position, the kept end's value halved at every step (Illinois-like: neither
        # end sticks, so the bracket shrinks from both sides)
        mid = np.clip(hi - g_hi * (hi - lo) / np.where(g_hi != g_lo, g_hi - g_lo, 1.0), lo, hi)
        g_mid = crest_loads(1 - mid[:, None, None], arrays)[1] - mid
        up = g_mid > 0
        g_hi = np.where(up, 0.5 * g_hi, g_mid)
        g_lo = np.where(up, g_mid, 0.5 * g_lo)
        lo, hi = np.where(up, mid, lo), np.where(up, hi, mid)
    root = np.where(np.abs(g_lo) < np.abs(g_hi), lo, hi)
    w, _ = crest_loads(1 - root[:, None, None], arrays)
    total = np.sum(w, axis=(1, 2))
    share[m] = np.where(total > 0, root, 0.0)
    # the load-weighted mean load ratio x_k = W_k/(p* λ)
    ratio[m] = np.sum(w**2, axis=(1, 2)) / np.maximum(total, 1e-300) / (p_star * lam)
    shape = np.shape(half_width)
    return OuterLoad(share.reshape(shape), ratio.reshape(shape))
