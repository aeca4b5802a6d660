"""Generalized Maxwell material against its closed forms and limits."""

import numpy as np
import pytest
from scipy.integrate import quad

import rubbercontact as rc
from rubbercontact.errors import InputError


@pytest.fixture
def sbr():
    return rc.materials.sbr()


def test_table1_values(sbr):
    # Paper Table 1, transcribed independently here.
    assert sbr.equilibrium_modulus == 4.17
    np.testing.assert_array_equal(sbr.moduli, [1.72, 7.36, 70.98, 505.87, 1125.85, 1185.94])
    np.testing.assert_array_equal(sbr.relaxation_times,
                                  [1.134e-02, 2.628e-04, 1.316e-05, 1.295e-06, 7.708e-08, 4.2e-10])


def test_static_and_glassy_limits(sbr):
    # E(0) = E_inf exactly; E(omega) -> E_inf + sum E_i as omega*tau_min -> inf.
    assert sbr.complex_modulus(0.0) == pytest.approx(4.17, rel=0, abs=1e-12)
    e_glassy = 4.17 + 1.72 + 7.36 + 70.98 + 505.87 + 1125.85 + 1185.94
    assert sbr.glassy_modulus == pytest.approx(e_glassy, rel=1e-12)
    # At omega = 1e16 rad/s, omega*tau_min = 4.2e6: relative deviation ~ 1/(omega tau)^2.
    assert sbr.complex_modulus(1e16).real == pytest.approx(e_glassy, rel=1e-9)


def test_loss_modulus_nonnegative_and_conjugate_symmetry(sbr):
    w = np.logspace(-3, 12, 400)
    assert np.all(sbr.loss_modulus(w) >= 0)
    # Storage modulus increases monotonically with frequency for a Prony series.
    assert np.all(np.diff(sbr.storage_modulus(w)) >= 0)
    np.testing.assert_allclose(sbr.complex_modulus(-w), np.conj(sbr.complex_modulus(w)))


def test_single_branch_closed_form():
    # One Maxwell element: E'' peaks at omega*tau = 1 with value E1/2, E' = Einf + E1/2 there.
    m = rc.materials.GeneralizedMaxwell(2.0, [6.0], [1e-3])
    e = m.complex_modulus(1e3)
    assert e.real == pytest.approx(5.0, rel=1e-14)
    assert e.imag == pytest.approx(3.0, rel=1e-14)
    assert m.loss_tangent(1e3) == pytest.approx(0.6, rel=1e-14)


def test_creep_of_standard_linear_solid_closed_form():
    # E_inf + one branch (E1, tau): creep retardation time tau (E_inf + E1)/E_inf and
    # J(t) = 1/E_inf - (1/E_inf - 1/(E_inf + E1)) exp(-t/lambda). Exact up to root finding.
    m = rc.materials.GeneralizedMaxwell(2.0, [6.0], [1e-3])
    lam = 1e-3 * 8.0 / 2.0
    np.testing.assert_allclose(m.retardation_times(), [lam], rtol=1e-12)
    t = np.array([0.0, 1e-3, 4e-3, 2e-2])
    np.testing.assert_allclose(m.creep_compliance(t),
                               0.5 - (0.5 - 1 / 8.0) * np.exp(-t / lam), rtol=1e-12)


def test_creep_compliance_inverts_relaxation(sbr):
    # Hold a unit stress: Boltzmann superposition of the creep strain through E(t) must give
    # back sigma = E(t) J(0) + int_0^t E(t - s) J'(s) ds = 1 at every t. Checked on a
    # three-branch series: J' by central difference (h = 1e-9 s: rounding ~ eps J/h ~ 1e-7)
    # and quad (default tolerance ~1.5e-8), so 1e-6 bounds the numerics (measured <= 1e-8).
    # Then the limits and interlacing on SBR (Table 1, times over eight decades).
    m = rc.materials.GeneralizedMaxwell(1.0, [3.0, 10.0, 30.0], [1e-1, 1e-2, 1e-3])
    lam = m.retardation_times()
    h = 1e-9
    for t in (5e-4, 5e-3, 0.05, 0.5):
        def integrand(s, t=t):
            dj = (m.creep_compliance(s + h) - m.creep_compliance(max(s - h, 0.0))) / (
                s + h - max(s - h, 0.0))
            return float(m.relaxation_modulus(t - s) * dj)
        stress = float(m.relaxation_modulus(t) * m.creep_compliance(0.0)) + quad(
            integrand, 0.0, t, points=[x for x in lam if x < t], limit=400)[0]
        assert stress == pytest.approx(1.0, abs=1e-6)
    lam = sbr.retardation_times()
    tau = np.sort(sbr.relaxation_times)
    assert lam.size == tau.size
    assert np.all(tau < lam) and np.all(lam[:-1] < tau[1:])        # interlacing
    assert sbr.creep_compliance(0.0) == pytest.approx(1 / sbr.glassy_modulus, rel=1e-10)
    assert sbr.creep_compliance(10.0) == pytest.approx(1 / 4.17, rel=1e-10)
    assert np.all(np.diff(sbr.creep_compliance(np.logspace(-11, 0, 200))) >= -1e-15)
    assert rc.materials.GeneralizedMaxwell(3.0).retardation_times().size == 0
    assert rc.materials.GeneralizedMaxwell(3.0).creep_compliance(1.0) == pytest.approx(1 / 3)


def test_relaxation_modulus_limits_and_kramers_kronig(sbr):
    # E(t=0) = glassy modulus, E(t -> inf) = E_inf.
    assert sbr.relaxation_modulus(0.0) == pytest.approx(sbr.glassy_modulus, rel=1e-14)
    assert sbr.relaxation_modulus(10.0) == pytest.approx(4.17, rel=1e-12)
    # E(w) = E_inf + i w * int_0^inf (E(t) - E_inf) e^{-i w t} dt: the complex modulus is
    # the Fourier transform of the relaxation function. Check at two frequencies by quadrature.
    m = rc.materials.GeneralizedMaxwell(4.17, [1.72, 7.36], [1.134e-2, 2.628e-4])
    def excess(t):
        return m.relaxation_modulus(t) - 4.17

    for w in (30.0, 3000.0):
        re = quad(excess, 0, 1.0, weight="cos", wvar=w, limit=400)[0]
        im = quad(excess, 0, 1.0, weight="sin", wvar=w, limit=400)[0]
        e = 4.17 + 1j * w * (re - 1j * im)
        # quadrature truncated at t=1 s = 88 tau_max: tail below 1e-30; quad accurate to ~1e-8.
        np.testing.assert_allclose(e, m.complex_modulus(w), rtol=1e-6)


def test_reduced_modulus(sbr):
    w = 1e4
    np.testing.assert_allclose(sbr.reduced_modulus(w, nu=0.5), sbr.complex_modulus(w) / 0.75)
    with pytest.raises(InputError, match="nu"):
        sbr.reduced_modulus(w, nu=0.7)


def test_elastic_material_has_no_loss():
    m = rc.materials.GeneralizedMaxwell.elastic(10.0)
    assert m.is_elastic
    assert np.all(m.loss_modulus(np.logspace(-2, 9, 20)) == 0)


@pytest.mark.parametrize("kwargs, field", [
    (dict(equilibrium_modulus=-1.0), "equilibrium_modulus"),
    (dict(equilibrium_modulus=float("nan")), "equilibrium_modulus"),
    (dict(equilibrium_modulus=1.0, moduli=[1.0, -2.0], relaxation_times=[1.0, 2.0]),
     r"moduli\[1\]"),
    (dict(equilibrium_modulus=1.0, moduli=[1.0], relaxation_times=[0.0]), r"relaxation_times\[0\]"),
    (dict(equilibrium_modulus=1.0, moduli=[1.0, 2.0], relaxation_times=[1.0]), "lengths differ"),
    (dict(equilibrium_modulus=1.0, moduli=[1.0, np.nan], relaxation_times=[1.0, 2.0]), "moduli"),
    (dict(equilibrium_modulus=1.0, moduli=[1.0, 2.0], relaxation_times=[1.0, 1.0]), "duplicate"),
])
def test_bad_material_input(kwargs, field):
    with pytest.raises(InputError, match=field):
        rc.materials.GeneralizedMaxwell(**kwargs)


def test_from_toml_and_csv(tmp_path, sbr):
    toml = tmp_path / "m.toml"
    toml.write_text("equilibrium_modulus = 4.17\nmoduli = [1.72, 7.36, 70.98, 505.87, 1125.85, "
                    "1185.94]\nrelaxation_times = [1.134e-02, 2.628e-04, 1.316e-05, 1.295e-06, "
                    "7.708e-08, 4.200e-10]\n")
    assert rc.materials.GeneralizedMaxwell.from_file(toml) == sbr
    csv = tmp_path / "m.csv"
    csv.write_text("E_MPa,tau_s\n4.17,\n1.72,1.134e-02\n7.36,2.628e-04\n70.98,1.316e-05\n"
                   "505.87,1.295e-06\n1125.85,7.708e-08\n1185.94,4.200e-10\n")
    assert rc.materials.GeneralizedMaxwell.from_file(csv) == sbr
    bad = tmp_path / "bad.csv"
    bad.write_text("E,tau\n4.17,\n1.0,abc\n")
    with pytest.raises(InputError, match="line 3"):
        rc.materials.GeneralizedMaxwell.from_file(bad)
    with pytest.raises(InputError, match="not found"):
        rc.materials.GeneralizedMaxwell.from_file(tmp_path / "missing.toml")
    unknown = tmp_path / "u.toml"
    unknown.write_text("equilibrium_modulus = 1.0\nmodulii = [1.0]\n")
    with pytest.raises(InputError, match="modulii"):
        rc.materials.GeneralizedMaxwell.from_file(unknown)
