"""rubbercontact.meanfield.bands: a 1D contact split by wavenumber band.

References: Parseval (the bands of a pressure add up to its variance, a pure harmonic
lands in its own band whole), the periodic count of contact intervals, and the linearity
of the strip cascade's friction in the loss (its bands add up to its friction).
"""

from types import SimpleNamespace

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.meanfield.bands import (
    band_power,
    contact_patches,
    pressure_power,
    strip_bands,
)
from rubbercontact.meanfield.strips import strip_contact
from rubbercontact.roughness import random_ladder


def test_contact_patches_counts_intervals_across_the_period_edge():
    # intervals of p > 0 on a periodic grid; one that wraps around the period's edge is one
    # patch, full and no contact are limits
    p = np.zeros(100)
    p[10:20] = 1.0          # 10 cells
    p[50:53] = 2.0          # 3 cells
    p[95:] = p[:2] = 1.0    # 5 + 2 cells across the edge
    widths = np.sort(contact_patches(p, 10.0))
    np.testing.assert_allclose(widths, [0.3, 0.7, 1.0])
    np.testing.assert_allclose(contact_patches(np.ones(8), 2.0), [2.0])
    assert contact_patches(np.zeros(8), 2.0).size == 0


def test_band_power_splits_the_pressure_variance_by_wavenumber():
    # Parseval: the bands add up to the variance of the pressure (mean over the solves),
    # and a pure harmonic lands in its own band whole
    period, n = 8.0, 1024
    x = np.arange(n) * period / n
    k3 = 2 * np.pi * 3 / period
    solves = [SimpleNamespace(pressure=1.0 + 0.5 * np.cos(k3 * x + ph) + 0.2 * np.sin(
        2 * np.pi * 40 * x / period)) for ph in (0.0, 1.0)]
    edges = np.array([0.0, 0.5 * k3, 2 * k3, np.inf])
    bands = band_power(solves, period, edges)
    assert bands.sum() == pytest.approx(np.mean([np.var(s.pressure) for s in solves]),
                                        rel=1e-12)
    np.testing.assert_allclose(bands, [0.0, 0.125, 0.02], atol=1e-12)
    # a weight per wavenumber multiplies each mode's power; arrays work as the solves
    assert band_power([s.pressure for s in solves], period, edges,
                      lambda k: 2.0 * (k > 0))[1] == pytest.approx(0.25, rel=1e-12)
    with pytest.raises(InputError, match="ascending"):
        band_power(solves, period, np.array([1.0, 0.5]))


def test_pressure_power_of_an_odd_and_an_even_grid_is_the_variance():
    rng = np.random.default_rng(2)
    for n in (255, 256):
        p = rng.random(n)
        k, power = pressure_power(p, 3.0)
        assert power[0] == 0.0 and power.sum() == pytest.approx(np.var(p), rel=1e-12)
        assert k[1] == pytest.approx(2 * np.pi / 3.0)


def test_the_strip_cascades_bands_add_up_to_its_friction():
    # the friction is linear in the loss: one cascade per band with the loss kept in that
    # band only adds up to the cascade with the whole loss. Not to round-off: the width
    # loss is tabulated as a log and interpolated, which a band's edge cuts (measured
    # +0.1 % on this ladder at 1 mm/s, +0.7 % at 500 mm/s)
    sbr = rc.materials.sbr()
    surf = random_ladder(8, 3)
    q = np.sort(surf.wavenumbers)
    edges = np.concatenate([[0.0], q * 2**-0.5, q[-1] * 2**0.5 * 2.0 ** np.arange(6),
                            [np.inf]])
    for v in (1.0, 500.0):
        mu = strip_bands(surf, sbr, v, 0.4, edges)
        whole = strip_contact(surf.wavenumbers, surf.amplitudes, sbr, v, 0.4)
        assert np.all(mu >= 0)
        assert mu.sum() == pytest.approx(float(whole.friction_stress.sum()) / 0.4, rel=0.02)
    # one band holding every wavenumber is the cascade itself, exactly
    assert strip_bands(surf, sbr, 500.0, 0.4, np.array([0.0, np.inf]))[0] == \
        float(whole.friction_stress.sum()) / 0.4
