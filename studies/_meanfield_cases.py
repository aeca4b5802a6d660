"""Cases of studies/meanfield.py: surfaces, loads and the modelling variants compared."""

from __future__ import annotations

import numpy as np
from scipy.optimize import brentq

from rubbercontact import meanfield as mf
from rubbercontact.roughness import (  # noqa: F401 - the studies read them from here
    SineSeries,
    random_ladder,
    self_affine_profile,
)

SPEEDS = (1.0, 10.0, 50.0, 500.0)      # mm/s: the paper's two and a decade either side
AREAS = (0.02, 0.06, 0.2, 0.45)        # the theory's contact fraction at the chosen loads
HYBRID_AREAS = (0.02, 0.06, 0.2)
#: One sine (the exact 1D limit): wavelength [mm], rms slope, speeds [mm/s] (0: the relaxed
#: elastic half-space) and loads as fractions of Westergaard's full-contact pressure.
SINE = {"wavelength": 1.0, "m2": 0.4}
SINE_SPEEDS = (0.0, 1.0, 10.0, 50.0, 500.0)
SINE_LOADS = (0.01, 0.03, 0.1, 0.3, 0.6)
#: The modelling choices compared (label, options); the first is the issue's naive
#: transcription of the 2D theory, the last two the strip cascade (``meanfield-strips``).
#: Persson's diffusion with S = 1 as the study's earlier default resolved it on a sine
#: series (after the wave, own-wavenumber dissipation; before issue 38's named models).
DIFFUSION = mf.MeanFieldOptions(correction=1.0, weighting="after")
#: The strip cascade (model ``meanfield-strips``) and without the outer crests.
STRIPS = mf.StripOptions()
NESTED = mf.StripOptions(outer_crests=False)
VARIANTS = (
    ("naive: S = ½ + ½A², cell mean", mf.MeanFieldOptions(correction=0.5)),
    ("S = 1, cell mean", mf.MeanFieldOptions(correction=1.0)),
    ("S = ½ + ½A², after the wave", mf.MeanFieldOptions(correction=0.5, weighting="after")),
    ("S = 1, after the wave (default of the diffusion before issue 38)", DIFFUSION),
    ("S = 1, after the wave, patch spectrum r = A_i/A_(i−1) (cascade)",
     mf.MeanFieldOptions(correction=1.0, weighting="after", dissipation="cascade")),
    ("S = 1, after the wave, patch spectrum r = A_i",
     mf.MeanFieldOptions(correction=1.0, weighting="after", dissipation="patch")),
    (f"S = {mf.DEFAULT_GAMMA:g} + {1 - mf.DEFAULT_GAMMA:g}A², cell mean (meanfield: Persson, "
     "the default)", mf.MeanFieldOptions()),
    ("Westergaard strips, without outer crests (the strips before them)", NESTED),
    ("Westergaard strips (meanfield-strips)", STRIPS),
)


def diffusion(psd) -> mf.MeanFieldOptions:
    """Persson's diffusion with S = 1 as the study's defaults resolved it before issue 38:
    :data:`DIFFUSION` on a sine series, the cell mean with the patch spectrum on a
    continuous 1D spectrum, the cell mean with Persson's dissipation in 2D."""
    if psd.waves is not None:
        return DIFFUSION
    return mf.MeanFieldOptions(correction=1.0,
                               dissipation="patch" if psd.dimension == 1 else "mode")


def previous_default(psd):
    """The options the study's "default" columns show: the strips on a 1D sine series
    (``meanfield-strips``), :func:`diffusion` otherwise."""
    return STRIPS if psd.dimension == 1 and psd.waves is not None else diffusion(psd)


#: Elastic two- and four-wave profiles (rms slope 0.3 per wave): is Persson's area low in 1D
#: because the scales are not separated? (name, wavelengths [mm], grid points)
SEPARATION = (("2 waves, ratio 16", (4.0, 0.25), 16384), ("2 waves, ratio 2", (4.0, 2.0), 8192),
              ("4 waves, ratio 2", (4.0, 2.0, 1.0, 0.5), 8192))


def separation_series(wavelengths) -> SineSeries:
    """Waves of rms slope 0.3 each at ``wavelengths`` [mm]."""
    lam = np.asarray(wavelengths, float)
    return SineSeries(lam, 0.3 * np.sqrt(2) * lam / (2 * np.pi))


def one_sine() -> SineSeries:
    """The single wave of :data:`SINE` (``Δ = m2 √2 λ/(2π)``)."""
    lam = SINE["wavelength"]
    return SineSeries([lam], [SINE["m2"] * np.sqrt(2) * lam / (2 * np.pi)])


def westergaard_p_star(surface: SineSeries, material, velocity: float, nu: float = 0.5
                       ) -> float:
    """Full-contact pressure amplitude ``qΔ|E_r(qv)|/2`` [MPa] of a one-wave series."""
    q, d = float(surface.wavenumbers[0]), float(surface.amplitudes[0])
    return q * d * abs(complex(material.complex_modulus(q * abs(velocity)))) / (1 - nu**2) / 2


def separated_hybrid() -> SineSeries:
    """Three low-slope waves (4, 2, 1 mm; m2 = 0.3, 0.4, 0.4) and a high-slope wave 16 times
    shorter than the shortest (m2 = 1.2): the hybrid's scale separation holds."""
    lam = np.array([4.0, 2.0, 1.0, 1.0 / 16])
    m2 = np.array([0.3, 0.4, 0.4, 1.2])
    return SineSeries(lam, m2 * np.sqrt(2) * lam / (2 * np.pi))


def load_for_area(psd, material, velocity: float, area: float) -> float:
    """The mean pressure [MPa] at which the diffusion's (Persson's) contact fraction is
    ``area`` (4 significant digits; the loads of the cached rows)."""
    def gap(logp):
        return mf.solve(psd, material, velocity, float(np.exp(logp)),
                        options=DIFFUSION).contact_fraction - area

    return float(f"{np.exp(brentq(gap, np.log(1e-6), np.log(1e5), xtol=1e-6)):.4g}")


def make_map(*, n: int, length: float, hurst: float, rolloff: int, kmax: int, slope: float,
             seed: int) -> np.ndarray:
    """A periodic random-phase 2D map with an isotropic self-affine spectrum (rms gradient
    ``slope``), modes ``1 <= |k| <= kmax`` of the period."""
    rng = np.random.default_rng(seed)
    kx = np.fft.fftfreq(n, 1.0 / n)
    k = np.hypot(*np.meshgrid(kx, kx, indexing="ij"))
    c = np.zeros_like(k)
    band = (k >= 1) & (k <= kmax)
    c[band] = np.where(k[band] < rolloff, 1.0, (k[band] / rolloff) ** (-2 * (1 + hurst)))
    z = np.real(np.fft.ifft2(np.sqrt(c) * np.exp(2j * np.pi * rng.random((n, n)))))
    z -= z.mean()
    grad2 = np.sum(np.abs(np.fft.fft2(z) / z.size) ** 2 * (2 * np.pi * k / length) ** 2)
    return z * slope / np.sqrt(grad2)
