"""The FEM sliding test with barrier contact against the closed forms the penalty contact
is held to: Westergaard's elastic sine at small slope, the linear full-contact friction
``μ = m2² Im E_r/(2 σ0)`` and zero friction of an elastic rubber (test_fem_contact,
test_fem_steady, where the full-contact friction runs with both contacts) — and no
penetration at all."""

import numpy as np
import pytest

import rubbercontact as rc

LAM = 0.0625


def test_westergaard_elastic_indentation_with_the_barrier():
    # Elastic sine (m2 = 0.044) at p̄ = 0.3 p_full, static: Westergaard
    # p̄/p_full = sin²(πa/λ), p(0) = 2 p̄ / sin(πa/λ). Tolerances as for the penalty
    # (test_fem_contact): edges to about one element (2 h/λ = 0.05), peak 5 %.
    E = 4.0
    lam, amp = 1.0, 0.01
    surf = rc.roughness.SineSeries([lam], [amp], [np.pi / 2])
    p_full = np.pi * (4 * E / 3) * amp / lam
    pbar = 0.3 * p_full
    out = rc.fem.sliding_test(surf, rc.materials.GeneralizedMaxwell.elastic(E), pbar, 0.0,
                              mesh=(40, 30), contact="barrier")
    a = lam / np.pi * np.arcsin(np.sqrt(pbar / p_full))
    assert out.contact_fraction == pytest.approx(2 * a / lam, abs=0.05)
    prof = out.pressure_profile
    dx = np.gradient(prof.x)
    assert np.sum(prof.pressure * dx) / lam == pytest.approx(pbar, rel=0.02)
    xs = np.mod(prof.x + lam / 2, lam) - lam / 2
    p0 = prof.pressure[np.argmin(np.abs(xs))]
    assert p0 == pytest.approx(2 * pbar / np.sin(np.pi * a / lam), rel=0.05)
    assert out.friction == pytest.approx(0.0, abs=1e-10)
    # impenetrable at the contact points; between two of them (h/4 apart) a straight
    # sub-chord can pass below the convex crest by at most its sag (h/4)² q² D / 8
    assert out.stats.max_penetration == 0.0
    h = lam / 40
    assert out.stats.max_segment_penetration <= (h / 4) ** 2 * (2 * np.pi / lam) ** 2 * amp / 8
    assert np.all(prof.y > prof.surface_height)


def test_elastic_material_has_no_friction_with_the_barrier():
    # No history: the steady problem is static and symmetric (crest on a node), μ = 0 to
    # round-off; contact fraction of the partial contact near Westergaard's (small slope
    # m2 = 0.36 here: within 0.1 of 2a/λ, the O(m2²) finite-slope correction and the edges).
    mat = rc.materials.GeneralizedMaxwell.elastic(4.17)
    amp = 0.005
    surf = rc.roughness.SineSeries([LAM], [amp])
    out = rc.fem.steady_sliding(surf, mat, 0.3, 10.0, mesh=(32, 24), contact="barrier")
    assert abs(out.friction) < 1e-8
    p_full = np.pi * (4 * 4.17 / 3) * amp / LAM
    a = LAM / np.pi * np.arcsin(np.sqrt(0.3 / p_full))
    assert out.contact_fraction == pytest.approx(2 * a / LAM, abs=0.1)
    assert out.stats.max_penetration == 0.0
