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
