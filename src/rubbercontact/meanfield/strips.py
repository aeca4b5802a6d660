r"""The 1D contact of a sine series as a cascade of Westergaard strips (the model
``meanfield-strips``, :class:`~.options.StripOptions`).

Persson's diffusion (:mod:`.contact`) gives every mode a Gaussian pressure step. In 1D the
exact answer for one wave is known (Westergaard; :mod:`.patches`): a sine ``Δ cos qx`` under
the mean pressure ``p̄ < p* = qΔE_r/2`` touches on strips of the fraction
``r = (2/π) arcsin √(p̄/p*)`` of its wavelength, with the pressure

.. math:: p(θ) = 2p^*\cos(θ/2)\sqrt{\sin^2(α/2) − \sin^2(θ/2)},\qquad α = πr.

This module builds the contact of a sine series from these strips (one sliding sine's,
:mod:`.sine`: their pressure variance and their stiffening at the contact time), longest wave
first, and takes the area, the pressure and the friction from the same strips. No constant
is fitted.

The cascade
-----------
The contact is carried as weighted samples of the local pressure (weight: the share of the
nominal length), each with the half-width ``a`` and the crest curvature ``κ`` of the strip it
lies in (none before any strip forms). A wave ``i`` (``κ_i = q_i²Δ_i``, random phase ``φ``
at the crest) acts on a strip in two ways:

* it bends the crest (:mod:`.crests`). A line contact of half-width ``a`` on the gap
  ``h = κx²/2 − Δ_i cos(q_i x + φ)`` sits where it is in moment balance, on the highest
  compound crest: its centre ``c`` minimises ``κc²/2 − Δ_i J0(q_i a) cos(q_i c + φ)``
  (:func:`~.crests.crest_phase`; ``ψ = q_i c + φ``), and it carries the load
  ``(E_r/2)∫ ξ h'(c + ξ)/√(a² − ξ²) dξ = (πE_r a²/4) κ_eff`` (Johnson, *Contact
  Mechanics*, §2.8) with ``κ_eff = κ + κ_i cos ψ · 2J1(q_i a)/(q_i a)``
  (:func:`~.crests.bending_share`: 1 for a strip much narrower than the wave, 0 for a wide
  one; taken as 0 beyond its first zero). A sliding strip's modulus is that of its contact
  time (:class:`~.crests.StripModulus`), and the wave's part of the load is carried at the
  wave's own frequency where the strip is wider than it, so at its load the half-width
  solves ``a'² κ_eff(a') |E_r(a')| = a² κ |E_r(a)|`` and the (Hertzian) pressures scale by
  ``a/a'`` (:func:`_bend`); the change in the pressure variance dissipates at the
  strip's own harmonics, those of its period, with the spectrum of the change of width
  (:class:`~.patches.WidthLoss`). Where the wave's next crest is nearly as high as the
  strip's, the rubber droops onto it and the two share the load, each a Hertzian strip of
  the same curvature (:func:`~.crests.neighbour_share`, :func:`_share_load`). Where
  ``κ_eff ≤ 0`` nonetheless, the crest splits, and the
  whole wave forms strips as below (docs/validation/meanfield.md compares this with a strip
  kept on the parent's crest);
* the rest of the wave, of amplitude ``(1 − 2J1(q_i a)/(q_i a)) Δ_i``, forms its own strips
  at the local pressure, Westergaard's (scale separation, Archard's picture with the exact
  sine at each step); its pressure variance is added at the loss of the strips' harmonics
  (:func:`~.patches.patch_loss` at the strips' fraction);
* those strips lift the rubber (Westergaard's mean gap), and the wave's crests just outside
  the strip, where the strip's own separation is small, come into contact and take a share
  of its load (:mod:`.outer`, :func:`_outer_crests`): the contact leaves the longer wave's
  strip, as in the BEM on octave ladders.

The bending is what a mean-field theory driven by ``G`` alone cannot have: waves an
octave apart make compound crests whose area depends on the spectrum's breadth.

The shorter waves' strips are a compliant layer
-----------------------------------------------
Where a wave forms strips inside a strip, the longer strip no longer presses on a smooth
half-space but on the wave's partial contact, a compliant layer: one sine under the mean
pressure ``p̄ = x p*`` keeps the mean gap ``ū = Δ(1 − x + x ln x)`` (Westergaard; exact, the
BEM's to its grid, tests/test_meanfield_strips.py), so its tangent compliance is
``C = −dū/dp̄ = 2 ln(1/x)/(q E_r)`` [mm/MPa], ``E_r`` the modulus of its sliding strips. A
line contact of half-width ``a`` on curvature ``κ`` needs ``p0 = E_r a κ/2`` on the
half-space and ``κa²/(2C)`` on a Winkler layer; in series, at its load,
``W = (π/4) E_r a² κ/(1 + L E_r/a)`` with ``L`` the layers' compliance summed over the
waves formed inside the strip (exact on the half-space; where the layer dominates it gives
``π a³κ/(4C)`` against the Winkler layer's exact ``2a³κ/(3C)``). The strip widens at fixed
load (:func:`_soften`, at most to its period);
its pressures scale by ``a/a'``, and the variance it loses comes off its own harmonics
(:class:`~.patches.WidthLoss`).
The longer strips then carry less of the variance in their own bands, as in the BEM
(docs/validation/meanfield.md measures it on two waves and on the ladders).

Exact limits: in full contact every sample stays in contact, each wave adds ``p*²/2`` at the
mode's loss, ``μ = Σ q²Δ² Im E_r(qv)/(4σ0)``; an elastic rubber has no loss, ``μ = 0``; one
wave is Westergaard's sine. The small-load area of a line contact is not linear in load
(for one sine it grows as ``√p̄``), so this geometry applies to sine series, where it is the
exact 1D limit; continuous spectra keep the diffusion (:mod:`.contact`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.special import j0

from ..materials.protocol import Material
from .crests import (
    PHASES,
    SMALLEST_FRACTION,
    StripModulus,
    bending_share,
    crest_cosine,
    neighbour_crest,
    neighbour_share,
)
from .outer import outer_load
from .patches import LossFilter, WidthLoss
from .sine import WaveTables, wave_tables, westergaard_variance

#: Samples across a strip (midpoint rule in the strip's angle).
STRIP_SAMPLES = 32
#: Rebinning of the samples after each wave: log bins in pressure and in half-width.
PRESSURE_BINS = 200
WIDTH_BINS = 30
#: Fixed-point iterations of a bent or widened strip's half-width.
FIXED_POINT_ITERATIONS = 8
#: Half-width standing for "no strip yet" [mm].
NO_STRIP = 1e9


@dataclass(frozen=True)
class Samples:
    """The contact as weighted samples (all arrays of one length).

    Attributes
    ----------
    pressure
        Local pressure [MPa].
    weight
        Share of the nominal length [-] (their sum is the contact fraction).
    half_width
        Half-width ``a`` [mm] of the strip the sample lies in (:data:`NO_STRIP`: none yet).
    curvature
        Curvature ``κ`` [1/mm] of that strip's crest.
    wavenumber
        Wavenumber [rad/mm] of the wave that formed the strip (its modulus is read at
        ``max(πv/(2a), qv)``, :class:`~.crests.StripModulus`).
    layer
        Compliance ``L`` [mm/MPa] of the shorter waves' strips under the strip (0 before any
        formed there; module docstring).
    """

    pressure: np.ndarray
    weight: np.ndarray
    half_width: np.ndarray
    curvature: np.ndarray
    wavenumber: np.ndarray
    layer: np.ndarray

    def subset(self, mask: np.ndarray) -> Samples:
        return Samples(*(getattr(self, name)[mask] for name in FIELDS))


FIELDS = ("pressure", "weight", "half_width", "curvature", "wavenumber", "layer")


def _join(parts: list[Samples]) -> Samples:
    return Samples(*(np.concatenate([getattr(p, name) for p in parts]) for name in FIELDS))


@dataclass(frozen=True)
class WaveStep:
    """The contact after one wave and the friction stress [MPa] that wave added."""

    samples: Samples
    friction_stress: float


def _westergaard_samples(p_star: np.ndarray, fraction: np.ndarray, weight: np.ndarray,
                         wave: WaveTables, curvature: np.ndarray) -> Samples:
    """Strips of ``wave`` in partial contact (fractions ``r < 1``, ``p*`` [MPa] at their
    modulus): :data:`STRIP_SAMPLES` pressures across each, their weights ``weight · r``."""
    t = (np.arange(STRIP_SAMPLES) + 0.5) / STRIP_SAMPLES
    alpha = np.pi * fraction[:, None]
    theta = alpha * t
    pressure = 2 * p_star[:, None] * np.cos(theta / 2) * np.sqrt(
        np.maximum(np.sin(alpha / 2) ** 2 - np.sin(theta / 2) ** 2, 0.0))
    rep = np.ones(STRIP_SAMPLES)
    return Samples(pressure.ravel(), np.outer(weight * fraction, rep / STRIP_SAMPLES).ravel(),
                   np.outer(fraction * np.pi / wave.wavenumber, rep).ravel(),
                   np.outer(curvature, rep).ravel(), np.full(pressure.size, wave.wavenumber),
                   np.zeros(pressure.size))


def _form_strips(s: Samples, wave: WaveTables, residual: np.ndarray) -> WaveStep:
    """The wave, of amplitude ``residual · Δ_i`` here, forms its strips at each sample's
    local pressure (module docstring)."""
    p_star0 = wave.p_star * np.maximum(residual, 1e-300)
    st = wave.at(s.pressure / p_star0)
    p_star = p_star0 * st.stiffening
    var = westergaard_variance(s.pressure / p_star) * p_star**2
    fstress = float(np.sum(s.weight * var * wave.loss_at(st.fraction)))
    full = st.fraction >= 1.0
    t = (np.arange(STRIP_SAMPLES) + 0.5) / STRIP_SAMPLES
    rep = np.ones(STRIP_SAMPLES)
    p_full = s.pressure[full, None] + p_star[full, None] * np.cos(np.pi * t)
    kept = Samples(p_full.ravel(), np.outer(s.weight[full], rep / STRIP_SAMPLES).ravel(),
                   *(np.outer(getattr(s, name)[full], rep).ravel() for name in FIELDS[2:]))
    formed = _westergaard_samples(p_star[~full], st.fraction[~full], s.weight[~full], wave,
                                  wave.curvature * residual[~full])
    return WaveStep(_join([kept, formed]), fstress)


def _outer_crests(s: Samples, wave: WaveTables, residual: np.ndarray, modulus: StripModulus,
                  width_loss: WidthLoss) -> OuterStep:
    """The wave's crests just outside the strips take a share ``F`` of their load
    (:func:`~.outer.outer_load`): the strips' pressures scale by ``1 − F``, the variance they
    lose coming off their own harmonics, and the outer crests carry the load as strips of
    the whole wave at the mean load ratio ``x̄``, their variance at the wave's strips' loss.
    Returns the strips and, as ``outer``, the outer crests' strips."""
    none = OuterStep.untouched(s)
    stripped = s.half_width < NO_STRIP
    if not stripped.any():
        return none
    a = np.where(stripped, s.half_width, 1.0)
    fraction = np.clip(a * s.wavenumber / np.pi, SMALLEST_FRACTION, 1.0)
    amp = s.curvature / s.wavenumber**2
    # the strip's mean contact pressure (Westergaard at its fraction, its contact-time modulus)
    contact = (np.sin(np.pi * fraction / 2) ** 2 * s.wavenumber * amp * modulus(a, s.wavenumber)
               / (2 * fraction))
    load = outer_load(a, s.wavenumber, amp, contact, wave.wavenumber, wave.amplitude,
                      np.where(stripped, residual, 0.0), wave.p_star)
    share = np.where(stripped, load.share, 0.0)
    touch = share > 0
    if not touch.any():
        return none
    kept = Samples(s.pressure * (1 - share), *(getattr(s, name) for name in FIELDS[1:]))
    d_var = s.weight[touch] * s.pressure[touch] ** 2 * ((1 - share[touch]) ** 2 - 1)
    fstress = float(np.sum(d_var * width_loss(s.wavenumber[touch], a[touch], a[touch])))
    st = wave.at(load.ratio[touch])
    p_star = wave.p_star * st.stiffening
    # contact per unit load of a strip at x̄: r/(x̄ p*)
    moved = s.weight[touch] * s.pressure[touch] * share[touch]
    outer = _westergaard_samples(p_star, st.fraction, moved / (load.ratio[touch] * wave.p_star),
                                 wave, np.full(st.fraction.size, wave.curvature))
    fstress += float(np.sum(outer.weight * outer.pressure**2
                            * wave.loss_at(np.repeat(st.fraction, STRIP_SAMPLES))))
    return OuterStep(kept, outer, fstress)


@dataclass(frozen=True)
class OuterStep:
    """The strips, their load less the outer crests' (``strips``), the outer crests' strips
    (``outer``) and the friction stress [MPa] of the move."""

    strips: Samples
    outer: Samples
    friction_stress: float

    @classmethod
    def untouched(cls, s: Samples) -> OuterStep:
        """The strips ``s`` as they are, no outer crests."""
        return cls(s, s.subset(np.zeros(s.weight.size, bool)), 0.0)


def _wave_on(s: Samples, wave: WaveTables, residual: np.ndarray, modulus: StripModulus,
             width_loss: WidthLoss, outer_crests: bool) -> WaveStep:
    """A wave (its share ``residual`` not bending the strips) on the samples: the strips
    widen on its layer (:func:`_soften`), its crests outside them take their share
    (:func:`_outer_crests`, if ``outer_crests``), and it forms its strips inside
    (:func:`_form_strips`)."""
    soft = _soften(s, wave, residual, modulus, width_loss)
    outer = (_outer_crests(soft.samples, wave, residual, modulus, width_loss) if outer_crests
             else OuterStep.untouched(soft.samples))
    formed = _form_strips(outer.strips, wave, residual)
    return WaveStep(_join([formed.samples, outer.outer]), soft.friction_stress
                    + outer.friction_stress + formed.friction_stress)


@dataclass(frozen=True)
class Bending:
    """The crests a wave bends, and the samples on which the crest splits instead."""

    bent: Samples
    split: Samples
    friction_stress: float


def _share_load(s: Samples, share: np.ndarray, width_loss: WidthLoss
                ) -> tuple[Samples, float]:
    """Strips whose neighbouring crest takes the load share ``share`` become two strips
    (:func:`~.crests.neighbour_share`) of half-widths ``a√(1 − share)`` and ``a√share``, at
    the same curvature; the friction stress [MPa] of the variance the split removes."""
    parts, fstress = [], 0.0
    for frac in (1.0 - share, share):
        keep = frac > 0
        r = np.sqrt(frac[keep])
        d_var = s.weight[keep] * s.pressure[keep] ** 2 * (frac[keep] ** 1.5 - frac[keep])
        moved = share[keep] > 0
        fstress += float(np.sum(d_var[moved] * width_loss(
            s.wavenumber[keep][moved], s.half_width[keep][moved],
            (s.half_width[keep] * r)[moved])))
        parts.append(Samples(s.pressure[keep] * r, s.weight[keep] * r,
                             s.half_width[keep] * r, s.curvature[keep], s.wavenumber[keep],
                             s.layer[keep]))
    return _join(parts), fstress


def _bend(s: Samples, wave: WaveTables, modulus: StripModulus, width_loss: WidthLoss
          ) -> Bending:
    """The wave bends the crests of the strips (module docstring): at each crest phase the
    half-width solves ``a'² κ_eff(a') |E_r(a')| = a² κ |E_r(a)|``, ``κ_eff = κ + κ_i cos ψ ·
    bending_share(q_i, a') · |E_r(q_i, a')|/|E_r(a')|``, ``ψ`` the wave's phase on the
    compound crest and the moduli at the contact times (:mod:`.crests`). The variance the
    narrowing adds dissipates at the strip's own harmonics (:class:`~.patches.WidthLoss`).
    Where the wave's neighbouring crest touches, the two share the load
    (:func:`_share_load`)."""
    kappa0, a0, q0 = s.curvature[:, None], s.half_width[:, None], s.wavenumber[:, None]
    stiff0 = kappa0 * modulus(a0, q0)
    half = np.broadcast_to(a0, (a0.size, PHASES))
    for _ in range(FIXED_POINT_ITERATIONS):
        e_strip = modulus(half, q0)
        rel = modulus(half, wave.wavenumber) / e_strip
        cos_psi = crest_cosine(kappa0, wave.amplitude * j0(wave.wavenumber * half) * rel,
                               wave.wavenumber)
        kappa = kappa0 + wave.curvature * cos_psi * bending_share(wave.wavenumber, half) * rel
        ok = kappa > 0
        half = a0 * np.sqrt(stiff0 / np.where(ok, kappa, kappa0) / e_strip)
    scale = half / a0
    weight = s.weight[:, None] / PHASES
    d_var = weight * s.pressure[:, None] ** 2 * (1.0 / scale - 1.0)
    q_strip = np.broadcast_to(q0, half.shape)
    fstress = float(np.sum(d_var[ok] * width_loss(q_strip[ok], np.broadcast_to(
        a0, half.shape)[ok], half[ok])))
    nb = neighbour_crest(kappa0, wave.amplitude * j0(wave.wavenumber * half) * rel,
                         wave.wavenumber)
    share = np.where(ok, neighbour_share(nb.height, nb.distance, half, kappa), 0.0)
    strips = Samples((s.pressure[:, None] / scale)[ok], (weight * scale)[ok], half[ok],
                     kappa[ok], q_strip[ok], np.broadcast_to(s.layer[:, None], half.shape)[ok])
    bent, d_stress = _share_load(strips, share[ok], width_loss)
    split = Samples(s.pressure, s.weight * np.mean(~ok, axis=1), s.half_width, s.curvature,
                    s.wavenumber, s.layer)
    return Bending(bent, split, fstress + d_stress)


def layer_compliance(pressure_ratio, wavenumber: float, modulus) -> np.ndarray:
    """Tangent compliance ``2 ln(1/x)/(q E_r)`` [mm/MPa] of one sine's strips at
    ``x = p̄/p*`` (``p*`` at the strips' modulus ``E_r`` [MPa]; 0 in full contact, module
    docstring)."""
    x = np.clip(np.asarray(pressure_ratio, float), 1e-300, 1.0)
    return 2.0 * np.log(1.0 / x) / (wavenumber * np.asarray(modulus, float))


def _soften(s: Samples, wave: WaveTables, residual: np.ndarray, modulus: StripModulus,
            width_loss: WidthLoss) -> WaveStep:
    """The strips ``s`` widen on the layer the wave's strips (amplitude ``residual · Δ_i``)
    form under them: at fixed load ``E(a) a²/(1 + L E(a)/a)``, ``L`` the summed layer
    compliance (module docstring); the variance they lose comes off their own harmonics
    (:class:`~.patches.WidthLoss`)."""
    stripped = s.half_width < NO_STRIP
    if not stripped.any():
        return WaveStep(s, 0.0)
    a0 = np.where(stripped, s.half_width, 1.0)
    e0 = modulus(a0, s.wavenumber)
    load = e0 * a0**2 / (1.0 + s.layer * e0 / a0)
    widest = np.maximum(a0, np.pi / s.wavenumber)            # the strip fills its period
    p_star = wave.p_star * np.maximum(residual, 1e-300)
    lam = 2 * np.pi / wave.wavenumber
    half, layer = a0, s.layer
    for _ in range(FIXED_POINT_ITERATIONS):
        st = wave.at(s.pressure * a0 / half / p_star)
        e_wave = modulus(np.maximum(st.fraction * lam / 2, 1e-300), wave.wavenumber)
        add = layer_compliance(s.pressure * a0 / half / (p_star * st.stiffening),
                               wave.wavenumber, e_wave)
        layer = s.layer + np.where(stripped & (residual > 0) & (st.fraction < 1.0), add, 0.0)
        e = modulus(half, s.wavenumber)
        half = np.clip(np.sqrt(load * (1.0 + layer * e / half) / e), a0, widest)
    scale = np.where(stripped, half / a0, 1.0)
    d_var = s.weight * s.pressure**2 * (1.0 / scale - 1.0)
    m = stripped & (scale > 1.0)
    fstress = float(np.sum(d_var[m] * width_loss(s.wavenumber[m], a0[m], half[m])))
    widened = Samples(s.pressure / scale, s.weight * scale, np.where(stripped, half, NO_STRIP),
                      s.curvature, s.wavenumber, np.where(stripped, layer, 0.0))
    return WaveStep(widened, fstress)


def _rebin(s: Samples) -> Samples:
    """Merge samples on a log grid of pressure × half-width (load and weight conserved);
    the samples in no strip yet get a width bin of their own."""
    s = s.subset((s.weight > 0) & (s.pressure > 0))
    top = s.pressure.max()
    ip = np.clip(np.searchsorted(np.geomspace(top * 1e-9, top * (1 + 1e-9), PRESSURE_BINS + 1),
                                 s.pressure) - 1, 0, PRESSURE_BINS - 1)
    la = np.log(s.half_width)
    stripped = s.half_width < NO_STRIP
    ia = np.full(la.shape, WIDTH_BINS)
    if stripped.any():
        edges = np.linspace(la[stripped].min() - 1e-9, la[stripped].max() + 1e-9,
                            WIDTH_BINS + 1)
        ia[stripped] = np.clip(np.searchsorted(edges, la[stripped]) - 1, 0, WIDTH_BINS - 1)
    idx = ip * (WIDTH_BINS + 1) + ia
    n = PRESSURE_BINS * (WIDTH_BINS + 1)
    w = np.bincount(idx, s.weight, n)
    m = w > 0

    def mean(values):
        return np.bincount(idx, s.weight * values, n)[m] / w[m]

    return Samples(mean(s.pressure), w[m], np.exp(mean(la)), np.exp(mean(np.log(s.curvature))),
                   np.exp(mean(np.log(s.wavenumber))), mean(s.layer))


@dataclass(frozen=True)
class StripContact:
    """Contact and friction of a sine series by the strip cascade.

    Attributes
    ----------
    contact_fraction
        ``A/A0`` [-] after every wave (longest first), shape ``(n_waves,)``.
    friction_stress
        Each wave's part of ``μσ0`` [MPa], shape ``(n_waves,)``.
    samples
        The final contact (local pressures and their weights).
    """

    contact_fraction: np.ndarray
    friction_stress: np.ndarray
    samples: Samples


def strip_contact(wavenumbers, amplitudes, material: Material, velocity: float,
                  mean_pressure: float, nu: float = 0.5, outer_crests: bool = True,
                  loss_filter: LossFilter | None = None) -> StripContact:
    """The strip cascade (module docstring) of the waves ``Δ_i cos(q_i x + φ_i)``.

    Parameters
    ----------
    wavenumbers, amplitudes
        ``q_i`` [rad/mm] and ``Δ_i`` [mm]; taken longest wave first.
    material, velocity, mean_pressure, nu
        Rubber, speed [mm/s], ``σ0`` [MPa] and Poisson's ratio.
    outer_crests
        Whether a wave's crests just outside a strip take their share of its load
        (:func:`_outer_crests`); without, every wave's contact stays inside the longer
        waves' strips (the previous cascade, kept for comparison).
    loss_filter
        Read in place of the loss ``−2 Im[1/E_r(ω)]`` wherever the cascade dissipates
        (:data:`~.patches.LossFilter`; the geometry reads ``|E_r|`` only and is unchanged);
        None: the loss itself.
    """
    q, amp = np.asarray(wavenumbers, float), np.asarray(amplitudes, float)
    order = np.argsort(q)
    s = Samples(np.array([float(mean_pressure)]), np.ones(1), np.full(1, NO_STRIP), np.ones(1),
                np.ones(1), np.zeros(1))
    modulus = StripModulus(material, velocity, nu, q.min(), q.max())
    width_loss = WidthLoss(material, velocity, nu, q.min(), q.max(), loss_filter)
    area, fstress = [], []
    for i in order:
        wave = wave_tables(q[i], amp[i], material, velocity, nu, loss_filter)
        stripped = s.half_width < NO_STRIP
        bend = _bend(s.subset(stripped), wave, modulus, width_loss)
        bent = _rebin(bend.bent) if bend.bent.weight.size else bend.bent
        rest = _join([s.subset(~stripped), bend.split])
        residual = 1.0 - bending_share(q[i], bent.half_width)
        steps = [_wave_on(group, wave, share, modulus, width_loss, outer_crests)
                 for group, share in ((bent, residual), (rest, np.ones(rest.weight.size)))]
        s = _rebin(_join([st.samples for st in steps]))
        area.append(float(s.weight.sum()))
        fstress.append(bend.friction_stress + sum(st.friction_stress for st in steps))
    inverse = np.argsort(order)
    return StripContact(np.array(area)[inverse], np.array(fstress)[inverse], s)
