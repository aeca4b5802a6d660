"""Interaction laws: LJ wall, tabulated (monotone interpolation, out-of-table), sums, and solves."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.halfspace import (
    LennardJonesRepulsion,
    SolverOptions,
    SumLaw,
    TabulatedLaw,
    solve_sliding,
)
from rubbercontact.roughness import SineSeries

SBR = rc.materials.sbr()


def fd_stiffness(law, u, h):
    return -(law.pressure(u + h) - law.pressure(u - h)) / (2 * h)


# --- Lennard-Jones ------------------------------------------------------------------------------
def test_lj_power_law_and_stiffness():
    law = LennardJonesRepulsion(1e-4, 0.5)
    u = np.array([0.5e-4, 1e-4, 2e-4, 1e-3])
    np.testing.assert_allclose(law.pressure(u), 0.5 * (1e-4 / u) ** 9)
    np.testing.assert_allclose(law.stiffness(u), fd_stiffness(law, u, 1e-9), rtol=1e-5)
    assert law.in_contact(np.array([1.9e-4, 2.1e-4])).tolist() == [True, False]


def test_lj_continuation_is_finite_and_monotone():
    law = LennardJonesRepulsion(1e-4, 0.5)
    u = np.linspace(-1e-4, 1e-3, 2001)
    s = law.pressure(u)
    assert np.all(np.isfinite(s)) and np.all(np.diff(s) <= 0)
    # C1 at u_min = ℓ/4
    umin = 0.25e-4
    assert law.pressure(umin - 1e-12) == pytest.approx(law.pressure(umin + 1e-12), rel=1e-6)


def test_lj_unresolved_and_resolution():
    with pytest.raises(InputError, match="unresolved"):
        LennardJonesRepulsion().pressure(np.array([1.0]))
    law = LennardJonesRepulsion(relative_length=1e-3).resolve(0.02, 0.4)
    assert law.length == pytest.approx(2e-5) and law.reference_pressure == 0.4
    with pytest.raises(InputError, match="length"):
        LennardJonesRepulsion(length=-1.0)


# --- tabulated ------------------------------------------------------------------------------------
def test_tabulated_exponential_is_reproduced_exactly():
    u = np.linspace(0.0, 0.05, 6)
    law = TabulatedLaw(u, 2.0 * np.exp(-u / 0.01))
    uu = np.linspace(0.0, 0.05, 101)
    # log-PCHIP of log-linear data is exactly linear in log σ
    np.testing.assert_allclose(law.pressure(uu), 2.0 * np.exp(-uu / 0.01), rtol=1e-12)
    np.testing.assert_allclose(law.stiffness(uu), 200.0 * np.exp(-uu / 0.01), rtol=1e-10)


def test_tabulated_inside_the_table_is_the_log_pchip_of_scipy():
    """Inside the table the law is ``exp`` of SciPy's PCHIP through ``(u_j, log σ_j)`` and
    ``k = −σ (log σ)'`` (the law's own piecewise-cubic evaluation against the peer's)."""
    from scipy.interpolate import PchipInterpolator

    u = np.array([0.0, 0.003, 0.007, 0.012, 0.02, 0.031, 0.05])
    s = np.array([6.0, 3.1, 1.2, 0.55, 0.2, 0.04, 0.002])
    ref = PchipInterpolator(u, np.log(s))
    uu = np.concatenate([u, np.random.default_rng(1).uniform(0.0, 0.05, 200)])
    law = TabulatedLaw(u, s)
    np.testing.assert_allclose(law.pressure(uu), np.exp(ref(uu)), rtol=1e-13)
    np.testing.assert_allclose(law.stiffness(uu), -ref.derivative()(uu) * np.exp(ref(uu)),
                               rtol=1e-12)


def test_tabulated_out_of_table_behaviour():
    u = np.array([0.01, 0.02, 0.03, 0.04])
    s = np.array([1.0, 0.3, 0.05, 0.0])
    law = TabulatedLaw(u, s, contact_fraction=[0.9, 0.5, 0.2, 0.0],
                       shear_stress=[0.2, 0.1, 0.02, 0.0])
    # zero beyond the first zero sample, together with α and Δτ
    assert law.pressure(np.array([0.04, 0.1])).tolist() == [0.0, 0.0]
    assert law.stiffness(np.array([0.05])).tolist() == [0.0]
    assert law.contact_fraction(np.array([0.05]))[0] == 0.0
    assert law.shear_stress(np.array([0.05]))[0] == 0.0
    # stiff continuation below the table: keeps rising, at least as steep (in log) as the
    # first secant
    below = law.pressure(np.array([0.0, 0.005, 0.01]))
    assert below[0] > below[1] > below[2] == pytest.approx(1.0)
    secant = np.log(0.3 / 1.0) / 0.01
    assert np.log(below[1] / below[2]) >= -secant * 0.005 * (1 - 1e-12)
    # companions held at the first value below the table
    assert law.contact_fraction(np.array([-1.0]))[0] == 0.9
    # samples are reproduced
    np.testing.assert_allclose(law.pressure(u), s, atol=1e-15)
    np.testing.assert_allclose(law.contact_fraction(u), [0.9, 0.5, 0.2, 0.0], atol=1e-15)


def test_tabulated_far_continuation_stays_finite():
    # steep first secant (found by hypothesis): exp overflow far below the table before the fix
    law = TabulatedLaw([0.0, 0.002, 1.0, 2.0], [1.0, 0.5, 0.5, 0.5])
    u = np.linspace(-3.0, 0.0, 301)
    p = law.pressure(u)
    assert np.all(np.isfinite(p)) and np.all(np.diff(p) < 0)
    assert np.all(np.isfinite(law.stiffness(u)))


def test_tabulated_decaying_tail_when_table_never_reaches_zero():
    law = TabulatedLaw([0.0, 0.01, 0.02], [1.0, 0.5, 0.25])
    assert law.pressure(np.array([0.03]))[0] == pytest.approx(0.125)  # exponential decay
    assert law.pressure(np.array([1.0]))[0] < 1e-20


@pytest.mark.parametrize("args, field", [
    (([0.0, 0.0, 1.0], [1.0, 0.5, 0.1]), "separation"),
    (([0.0, 0.5, 1.0], [1.0, 1.5, 0.1]), "pressure"),
    (([0.0, 0.5, 1.0], [1.0, -0.5, -1.0]), "pressure"),
    (([0.0, 0.5, 1.0], [1.0, np.nan, 0.1]), "pressure"),
    (([0.0, 0.5, 1.0], [1.0, 0.5]), "pressure"),
    (([0.0], [1.0]), "separation"),
])
def test_tabulated_bad_tables(args, field):
    with pytest.raises(InputError, match=field):
        TabulatedLaw(*args)
    with pytest.raises(InputError, match="contact_fraction"):
        TabulatedLaw([0.0, 1.0], [1.0, 0.0], contact_fraction=[1.5, 0.0])


@st.composite
def monotone_tables(draw):
    n = draw(st.integers(2, 12))
    steps = draw(st.lists(st.floats(1e-4, 1.0), min_size=n - 1, max_size=n - 1))
    u = np.concatenate([[draw(st.floats(-0.1, 0.1))], np.cumsum(steps)])
    u[1:] += u[0]
    drops = draw(st.lists(st.floats(0.0, 0.9), min_size=n - 1, max_size=n - 1))
    s = np.concatenate([[draw(st.floats(1e-3, 1e3))], np.zeros(n - 1)])
    for i, d in enumerate(drops):
        s[i + 1] = s[i] * (1 - d)
    if draw(st.booleans()):
        s[draw(st.integers(1, n - 1)):] = 0.0  # table reaching zero
    return u, s


@settings(max_examples=60, deadline=None)
@given(monotone_tables())
def test_tabulated_interpolation_is_monotone(table):
    u, s = table
    law = TabulatedLaw(u, s)
    span = u[-1] - u[0]
    uu = np.linspace(u[0] - 0.5 * span, u[-1] + 0.5 * span, 3001)
    p = law.pressure(uu)
    k = law.stiffness(uu)
    assert np.all(np.isfinite(p)) and np.all(p >= 0) and np.all(k >= 0)
    assert np.all(np.diff(p) <= 1e-12 * p.max())  # non-increasing everywhere
    np.testing.assert_allclose(law.pressure(u), s, rtol=1e-9, atol=1e-300)


# --- sum ----------------------------------------------------------------------------------------
def test_sum_law():
    lj = LennardJonesRepulsion(1e-4, 1.0)
    tab = TabulatedLaw([0.0, 0.01, 0.02], [1.0, 0.5, 0.0], contact_fraction=[1.0, 0.4, 0.0],
                       shear_stress=[0.3, 0.1, 0.0])
    law = lj + tab
    assert isinstance(law, SumLaw)
    u = np.array([5e-5, 0.005, 0.015, 0.5])
    np.testing.assert_allclose(law.pressure(u), lj.pressure(u) + tab.pressure(u))
    np.testing.assert_allclose(law.stiffness(u), lj.stiffness(u) + tab.stiffness(u))
    np.testing.assert_allclose(law.contact_fraction(u), tab.contact_fraction(u))
    np.testing.assert_allclose(law.shear_stress(u), tab.shear_stress(u))
    assert len((law + lj).laws) == 3  # flattened
    with pytest.raises(InputError, match="contact_fraction"):
        SumLaw(tab, tab)
    assert LennardJonesRepulsion().resolve(1.0, 1.0).contact_fraction(u) is None


# --- solves with laws against closed forms ------------------------------------------------------
def test_linear_tabulated_law_full_contact_closed_form():
    """Linear spring layer σ = κ(u_c − u) in series with the half-space: σ(q) = κz(q)/(1 + κM)."""
    lam, delta, v = 0.125, 0.001, 10.0
    q = 2 * np.pi / lam
    kappa, uc = 200.0, 0.02  # MPa/mm, mm
    law = TabulatedLaw([0.0, uc], [kappa * uc, 0.0])
    sigma0 = kappa * uc / 2  # keeps u inside the linear table range
    res = solve_sliding(SineSeries([lam], [delta]), None, SBR, v, sigma0, n=256, law=law,
                        tol=1e-12)
    m = 2 / (q * complex(SBR.reduced_modulus(q * v)))
    expected = q * delta**2 / 2 * (kappa / (1 + kappa * m)).imag / sigma0
    assert res.friction == pytest.approx(expected, rel=1e-8)
    assert res.mean_separation == pytest.approx(uc / 2, rel=1e-10)


def test_companion_tables_enter_results():
    lam, delta = 0.125, 0.002
    tau0, alpha0 = 0.05, 0.5
    tab = TabulatedLaw([0.0, 0.01, 1.0], [1.0, 0.1, 0.0], contact_fraction=[alpha0] * 3,
                       shear_stress=[tau0] * 3)
    law = LennardJonesRepulsion() + tab
    res = solve_sliding(SineSeries([lam], [delta]), None, SBR, 10.0, 0.2, n=512, law=law)
    # constant tables: <Δτ>/σ0 and <H(σ) α> are known (LJ keeps σ > 0 everywhere)
    assert res.friction_hs == pytest.approx(tau0 / 0.2, rel=1e-12)
    assert res.contact_fraction == pytest.approx(alpha0, rel=1e-12)
    assert res.friction == pytest.approx(res.friction_ls + res.friction_hs)


def test_steep_law_converges_to_hard_wall():
    surf = rc.roughness.section3(phases=[0.3, 1.2, 2.5])
    hard = solve_sliding(surf, None, SBR, 10.0, 0.3, n=2048)
    errs = []
    for rel in (1e-3, 1e-4, 1e-5):
        soft = solve_sliding(surf, None, SBR, 10.0, 0.3, n=2048,
                             law=LennardJonesRepulsion(relative_length=rel))
        errs.append(abs(soft.friction - hard.friction) / hard.friction)
    # the wall thickness ℓ → 0 recovers the exact complementarity solution
    assert errs[0] > errs[1] > errs[2] and errs[2] < 1e-3


def _hs_law(u0=0.005, pa=5.0):
    u = np.linspace(0.0, 0.04, 21)
    sig = pa * np.exp(-u / u0)
    sig[-1] = 0.0
    return TabulatedLaw(u, sig, contact_fraction=np.exp(-u / u0), shear_stress=0.3 * sig)


def test_wall_plus_soft_law_equals_soft_law_when_wall_is_idle():
    ls = rc.roughness.section3(phases=[0.3, 1.2, 2.5]).partition(1.0)[1]
    tab = _hs_law()
    both = solve_sliding(ls, None, SBR, 10.0, 0.05, n=1024, law=LennardJonesRepulsion() + tab)
    soft = solve_sliding(ls, None, SBR, 10.0, 0.05, n=1024, law=tab)
    # u stays ≫ ℓ, so the wall adds nothing: the two solves must agree
    assert both.separation.min() > 100 * 1e-5 * np.std(both.heights)
    assert both.friction == pytest.approx(soft.friction, rel=1e-8)
    assert both.contact_fraction == pytest.approx(soft.contact_fraction, rel=1e-8)


def test_wall_plus_soft_law_sharing_the_load():
    ls = rc.roughness.section3(phases=[0.3, 1.2, 2.5]).partition(1.0)[1]
    tab = _hs_law(u0=0.002, pa=2.0)
    wall = LennardJonesRepulsion()
    res = solve_sliding(ls, None, SBR, 10.0, 1.0, n=1024, law=wall + tab)
    assert res.info["wall_soft_method"] == "active-set"  # no continuation needed
    assert res.converged
    resolved = wall.resolve(np.std(res.heights), 1.0)
    p_wall = resolved.pressure(res.separation)
    p_soft = tab.pressure(res.separation)
    # both members carry a finite share; the pressure is the law at the solved separation
    assert 0.05 < np.mean(p_wall) < 0.95 and 0.05 < np.mean(p_soft) < 0.95
    np.testing.assert_allclose(res.pressure, p_wall + p_soft, rtol=1e-5, atol=1e-8)
    # eq. 6 with the companion table at the solved separation (linear-space PCHIP, so only
    # close to 0.3·<σ_soft>)
    assert res.friction_hs == pytest.approx(np.mean(tab.shear_stress(res.separation)), rel=1e-12)
    assert res.friction_hs == pytest.approx(0.3 * np.mean(p_soft), rel=0.02)


#: The continuation path only (``wall + s·soft``, s: 0 → 1), the method before the active set.
CONTINUATION = SolverOptions(wall_soft_active_set=False)


@pytest.mark.parametrize("case", ["shared", "fem-like"])
def test_wall_soft_active_set_matches_continuation(case):
    """The active-set path (hard wall + soft law, then Newton on the LJ law) gives the answer
    of the previous continuation path (``stiff + s·soft``, s: 0 → 1) within the tolerance."""
    if case == "shared":  # the wall carries ~half the load: continuation needed 11 stages
        ls = rc.roughness.section3(phases=[0.3, 1.2, 2.5]).partition(1.0)[1]
        tab, sigma0 = _hs_law(u0=0.002, pa=2.0), 0.3
    else:  # the shape of the FEM high-slope law (decreasing, zero beyond 0.01867 mm)
        ls = rc.roughness.section3(phases=[2.0, 0.4, 5.1]).partition(1.0)[1]
        tab = TabulatedLaw(separation=[0.004, 0.008, 0.012, 0.016, 0.01867],
                           pressure=[8, 3, 1, 0.3, 0], contact_fraction=[0.6, 0.4, 0.25, 0.1, 0],
                           shear_stress=[2.5, 1.2, 0.4, 0.08, 0])
        sigma0 = 1.0
    law = LennardJonesRepulsion() + tab
    fast = solve_sliding(ls, None, SBR, 10.0, sigma0, n=1024, law=law)
    assert fast.info["wall_soft_method"] == "active-set"
    ref = solve_sliding(ls, None, SBR, 10.0, sigma0, n=1024, law=law, options=CONTINUATION)
    assert "wall_soft_method" not in ref.info
    assert fast.residual <= 1e-8 and ref.residual <= 1e-8
    assert fast.friction == pytest.approx(ref.friction, rel=1e-6)
    assert fast.contact_fraction == pytest.approx(ref.contact_fraction, rel=1e-6)
    assert fast.mean_separation == pytest.approx(ref.mean_separation, rel=1e-6)
    np.testing.assert_allclose(fast.pressure, ref.pressure, rtol=0,
                               atol=1e-5 * fast.pressure.max())


def test_wall_soft_steep_soft_law_matches_continuation():
    """A soft law steep on the scale of the roughness (AC-8 low-slope part, law decaying over
    2 µm): the soft Newton needs the hard-wall start; same answer as the continuation path."""
    ls = rc.roughness.asphalt_ac8(phases=np.linspace(0, 6, 8)).partition(1.0)[1]
    law = LennardJonesRepulsion() + _hs_law(u0=0.002, pa=2.0)
    fast = solve_sliding(ls, None, SBR, 10.0, 0.5, n=2048, law=law)
    assert fast.info["wall_soft_method"] == "active-set"
    ref = solve_sliding(ls, None, SBR, 10.0, 0.5, n=2048, law=law, options=CONTINUATION)
    assert fast.friction == pytest.approx(ref.friction, rel=1e-6)
    assert fast.contact_fraction == pytest.approx(ref.contact_fraction, rel=1e-6)
    assert fast.mean_separation == pytest.approx(ref.mean_separation, rel=1e-6)


def test_wall_soft_coarse_grid_start_gives_the_single_grid_answer():
    """N = 8192: hard wall + soft law started from 4× coarser grids = started on the grid."""
    ls = rc.roughness.section3(phases=[0.3, 1.2, 2.5]).partition(1.0)[1]
    law = LennardJonesRepulsion() + _hs_law(u0=0.002, pa=2.0)
    fast = solve_sliding(ls, None, SBR, 10.0, 1.0, n=8192, law=law)
    assert fast.info["coarse_levels"] >= 1
    ref = solve_sliding(ls, None, SBR, 10.0, 1.0, n=8192, law=law,
                        options=SolverOptions(wall_soft_coarse_min_points=None))
    assert ref.info["coarse_levels"] == 0
    assert fast.friction == pytest.approx(ref.friction, rel=1e-7)
    assert fast.contact_fraction == pytest.approx(ref.contact_fraction, rel=1e-7)
    assert fast.mean_separation == pytest.approx(ref.mean_separation, rel=1e-7)
    rel = np.linalg.norm(fast.pressure - ref.pressure) / np.linalg.norm(ref.pressure)
    assert rel < 1e-7


def test_pressure_and_stiffness_in_one_pass_are_the_separate_ones():
    # the solver's combined evaluation (one pass of a table) returns bitwise the arrays of
    # pressure() and stiffness(), for a table, the wall, their sum and a protocol law
    table = TabulatedLaw([0.001, 0.002, 0.004, 0.006], [5.0, 2.0, 0.4, 0.0])
    wall = LennardJonesRepulsion(length=1e-4, reference_pressure=1.0)

    class Linear:
        kind = "soft"

        def pressure(self, u):
            return np.maximum(1.0 - u, 0.0)

        def stiffness(self, u):
            return (u < 1.0).astype(float)

    u = np.linspace(-0.001, 0.008, 401)
    for law in (table, wall, wall + table, wall + Linear()):
        f, k = law.pressure_and_stiffness(u)
        np.testing.assert_array_equal(f, law.pressure(u))
        np.testing.assert_array_equal(k, law.stiffness(u))
