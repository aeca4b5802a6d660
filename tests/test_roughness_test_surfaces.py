"""The synthetic 1D test surfaces (rubbercontact.roughness.random_ladder and
self_affine_profile) against their definitions: Parseval for the profile, the octave
wavelengths and the slope range for the ladder."""

from __future__ import annotations

import numpy as np
import pytest

from rubbercontact.errors import InputError
from rubbercontact.roughness import random_ladder, self_affine_profile

PROFILE = dict(length=10.0, lam_min=0.1, hurst=0.8, rolloff=4, slope=0.5)


def test_the_profile_has_its_spectrum_exactly():
    z, psd = self_affine_profile(n=1024, seed=1, **PROFILE)
    n, length = z.size, PROFILE["length"]
    # the periodogram of z: one-sided power 2|ẑ_k|² per harmonic is the spectrum's v_k
    zk = np.fft.rfft(z) / n
    power = 2 * np.abs(zk[1:101]) ** 2
    np.testing.assert_allclose(power, psd.variances, rtol=1e-10)
    assert np.all(np.abs(zk[101:]) < 1e-14) and abs(zk[0]) < 1e-14      # band-limited, mean 0
    np.testing.assert_allclose(psd.wavenumbers, 2 * np.pi * np.arange(1, 101) / length)
    # the rms slope by spectral differentiation is the one asked for
    slope = np.fft.irfft(1j * 2 * np.pi * np.arange(zk.size) / length * zk * n, n)
    assert np.sqrt(np.mean(slope**2)) == pytest.approx(PROFILE["slope"], rel=1e-12)
    # the self-affine law above the roll-off: v_k ∝ k^−(1+2H)
    k = np.arange(4, 101)
    ratio = psd.variances[3:] * k ** (1 + 2 * PROFILE["hurst"])
    np.testing.assert_allclose(ratio, ratio[0], rtol=1e-12)


def test_the_profile_spectrum_is_the_same_for_every_seed_and_needs_4_points_per_wave():
    (za, a), (zb, b) = (self_affine_profile(n=512, seed=s, **PROFILE) for s in (1, 2))
    np.testing.assert_array_equal(a.variances, b.variances)
    assert not np.allclose(za, zb)
    with pytest.raises(InputError, match="4 per shortest wavelength"):
        self_affine_profile(n=399, seed=1, **PROFILE)


def test_the_ladder_is_an_octave_series_with_slopes_in_range():
    surf = random_ladder(8, 3)
    np.testing.assert_allclose(np.sort(surf.wavelengths), np.sort(8.0 / 2.0 ** np.arange(8)))
    m2 = surf.amplitudes * surf.wavenumbers / np.sqrt(2)        # rms slope of each wave
    assert np.all((m2 >= 0.1) & (m2 < 0.6))
    assert random_ladder(8, 3) == surf and random_ladder(8, 4) != surf
    with pytest.raises(InputError, match="waves"):
        random_ladder(0, 3)
