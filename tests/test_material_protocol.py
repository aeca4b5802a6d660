"""Solvers take any material with the members of ``Material`` and route laws by their kind.

A Cole–Cole (fractional Zener) solid (the ``cole_cole`` fixture), written in closed form
and not a Prony series, goes through the half-space solver and the mean-field theory: in
full contact of a sine both must give the closed form ``μ = q²Δ² Im E_r(qv)/(4σ0)``; with
exponent 1 it *is* the standard linear solid, i.e. a one-branch :class:`GeneralizedMaxwell`,
whose answers it must reproduce in partial contact. A stiff wall law of a new class (a
12th-power wall) declaring ``kind = "wall"`` must be solved by the wall + soft algorithm.
A law need not be an ``InteractionLaw`` at all: classes of their own with only ``kind``,
``pressure`` and ``stiffness`` give the closed form of a linear spring layer on a sine and,
for an exponential, the answers of the built-in table of it; the mean-field theory reads a
high-slope law in pressure of its own class (``at``, ``compliance_at``, ``max_pressure``)
at a nearly uniform pressure as its closed form.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import SimpleNamespace
from typing import ClassVar

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact import meanfield as mf
from rubbercontact.errors import InputError
from rubbercontact.halfspace import (
    InteractionLaw,
    LennardJonesRepulsion,
    SumLaw,
    TabulatedLaw,
    solve_sliding,
)
from rubbercontact.halfspace.walls import split_law
from rubbercontact.materials import GeneralizedMaxwell, check_material
from rubbercontact.roughness import SineSeries


def _er(material, omega):
    return complex(material.complex_modulus(omega)) / 0.75      # ν = 0.5


def test_cole_cole_is_causal_and_not_a_prony_series(cole_cole):
    cole = cole_cole()
    w = np.array([1e-2, 1.0, 1e4, 1e8])
    e = cole.complex_modulus(w)
    np.testing.assert_allclose(cole.complex_modulus(-w), np.conj(e), rtol=1e-15)
    assert np.all(e.imag > 0)
    # the loss peak of a Cole–Cole solid is broader than any single Maxwell branch's:
    # at 100× the peak frequency tan δ of the SLS has fallen far more
    sls = cole_cole(exponent=1.0)
    peak = 1.0 / cole.tau
    assert cole.complex_modulus(100 * peak).imag / cole.complex_modulus(peak).imag > \
        5 * sls.complex_modulus(100 * peak).imag / sls.complex_modulus(peak).imag


@pytest.mark.parametrize("velocity", [1e-2, 10.0, 1e4])
def test_full_contact_friction_of_a_sine_in_the_halfspace(velocity, cole_cole):
    lam, delta = 0.125, 0.002
    q = 2 * np.pi / lam
    er = _er(cole_cole(), q * velocity)
    sigma0 = 1.5 * abs(er) * q * delta / 2          # full contact: σ0 > |E_r| qΔ/2
    res = solve_sliding(SineSeries([lam], [delta]), None, cole_cole(), velocity, sigma0, n=256)
    assert res.contact_fraction == 1.0
    # one Fourier mode is exact on the grid: only the solver tolerance (1e-8) remains
    assert res.friction == pytest.approx(q**2 * delta**2 * er.imag / (4 * sigma0), rel=1e-7)


@pytest.mark.parametrize("velocity", [1e-2, 10.0, 1e4])
def test_full_contact_friction_of_sines_in_the_meanfield(velocity, cole_cole):
    surf = rc.roughness.section3()
    q, d = surf.wavenumbers, surf.amplitudes
    er = cole_cole().complex_modulus(q * velocity) / 0.75
    sigma0 = 1e4 * float(np.max(q * d * np.abs(er)))   # G ~ 1e-8: A = 1 to round-off
    res = mf.solve(mf.PSD.from_sines(surf), cole_cole(), velocity, sigma0)
    assert res.contact_fraction == 1.0
    # a sum in closed form: round-off only
    assert res.friction == pytest.approx(float(np.sum(q**2 * d**2 * er.imag)) / (4 * sigma0),
                                         rel=1e-12)


def test_standard_linear_solid_in_closed_form_is_the_one_branch_prony_series(cole_cole):
    sls = cole_cole(unrelaxed=30.0, tau=1e-3, exponent=1.0)
    prony = GeneralizedMaxwell(sls.relaxed, [sls.unrelaxed - sls.relaxed], [sls.tau])
    surf = rc.roughness.section3(phases=[0.3, 1.2, 2.5])
    v, sigma0 = 10.0, 1.0                       # partial contact (A ~ 6 %), dissipative
    a = solve_sliding(surf, None, sls, v, sigma0, n=1024)
    b = solve_sliding(surf, None, prony, v, sigma0, n=1024)
    assert 0.02 < b.contact_fraction < 0.5 and b.friction > 0.1
    # the two moduli agree to round-off; the solves (tol 1e-8) then agree to far below it
    assert a.friction == pytest.approx(b.friction, rel=1e-8)
    assert a.contact_fraction == pytest.approx(b.contact_fraction, rel=1e-8)
    psd = mf.PSD.from_sines(surf)
    ma, mb = mf.solve(psd, sls, v, sigma0), mf.solve(psd, prony, v, sigma0)
    assert 0.02 < mb.contact_fraction < 0.5 and mb.friction > 0.1
    assert ma.friction == pytest.approx(mb.friction, rel=1e-8)
    assert ma.contact_fraction == pytest.approx(mb.contact_fraction, rel=1e-8)


def test_an_object_without_a_modulus_is_refused_in_one_line():
    @dataclass(frozen=True)
    class NoModulus:
        name: str = "steel?"
        is_elastic: bool = True

    with pytest.raises(InputError, match="missing complex_modulus") as err:
        solve_sliding(SineSeries([1.0], [0.01]), None, NoModulus(), 1.0, 0.1)
    assert "\n" not in str(err.value)
    with pytest.raises(InputError, match="missing complex_modulus"):
        mf.solve(mf.PSD.from_sines(SineSeries([1.0], [0.01])), NoModulus(), 1.0, 0.1)
    with pytest.raises(InputError, match="is_elastic"):
        check_material(object())
    # a modulus that is there but not a method is named beside what is missing
    with pytest.raises(InputError, match=r"missing complex_modulus: .*; name: a str"):
        check_material(SimpleNamespace(complex_modulus=3.0, is_elastic=True))
    assert check_material(rc.materials.sbr()) is not None


# --- laws: the declared kind ---------------------------------------------------------------------
@dataclass(frozen=True)
class TwelfthPowerWall(InteractionLaw):
    """``σ = p_ref (ℓ/u)¹²`` (linear below ``ℓ/2``), ``ℓ`` from the roughness: a new hard-wall
    stand-in that is not a :class:`LennardJonesRepulsion`."""

    kind: ClassVar[str] = "wall"
    length: float | None = None
    reference_pressure: float | None = None

    def resolve(self, length_scale, pressure_scale):
        return TwelfthPowerWall(self.length or 1e-5 * length_scale,
                                self.reference_pressure or pressure_scale)

    def pressure(self, u):
        u = np.asarray(u, dtype=float)
        us = np.maximum(u, 0.5 * self.length)
        sig = self.reference_pressure * (self.length / us) ** 12
        k_min = 12 * self.reference_pressure * 2.0**12 / (0.5 * self.length)
        return np.where(u < us, sig + k_min * (us - u), sig)

    def stiffness(self, u):
        us = np.maximum(np.asarray(u, dtype=float), 0.5 * self.length)
        return 12 * self.reference_pressure * (self.length / us) ** 12 / us

    def in_contact(self, u):
        return np.asarray(u) < 2 * self.length       # as the LJ wall: within 2ℓ


def _soft():
    u = np.linspace(0.0, 0.04, 21)
    sig = 2.0 * np.exp(-u / 0.002)
    sig[-1] = 0.0
    return TabulatedLaw(u, sig)


def test_a_new_wall_class_is_split_off_as_the_wall():
    wall, soft = TwelfthPowerWall(1e-6, 1.0), _soft()
    parts = split_law(wall + soft)
    assert parts.stiff is wall and parts.soft is soft
    assert split_law(soft).stiff is None and split_law(wall).soft is None


def test_a_new_wall_class_is_solved_by_the_wall_algorithm_like_the_lj_wall():
    ls = rc.roughness.section3(phases=[0.3, 1.2, 2.5]).partition(1.0)[1]
    sls = rc.materials.sbr()
    new = solve_sliding(ls, None, sls, 10.0, 1.0, n=1024, law=TwelfthPowerWall() + _soft())
    lj = solve_sliding(ls, None, sls, 10.0, 1.0, n=1024, law=LennardJonesRepulsion() + _soft())
    assert new.info["wall_soft_method"] == "active-set"
    # both walls sit at u ~ ℓ = 1e-5 h_rms, far inside the soft law's 2 µm decay: the two
    # answers differ by O(ℓ/2 µm) ~ 1e-4 at most
    assert new.friction == pytest.approx(lj.friction, rel=1e-3)
    assert new.contact_fraction == pytest.approx(lj.contact_fraction, rel=1e-3)


def test_a_law_of_unknown_kind_is_refused():
    class Sticky(TwelfthPowerWall):
        kind: ClassVar[str] = "adhesive"

    with pytest.raises(InputError, match="declares kind 'adhesive'"):
        split_law(Sticky(1e-6, 1.0) + _soft())


# --- laws: the protocol, not the class -----------------------------------------------------------
class LinearSpring:
    """``σ = k (u0 − u)`` for ``u < u0``, else 0: a soft law of its own class, not an
    :class:`InteractionLaw`, with only the members of the ``Law`` protocol."""

    kind = "soft"

    def __init__(self, k: float, u0: float) -> None:
        self.k, self.u0 = k, u0

    def pressure(self, u):
        return self.k * np.maximum(self.u0 - np.asarray(u, dtype=float), 0.0)

    def stiffness(self, u):
        return np.where(np.asarray(u, dtype=float) < self.u0, self.k, 0.0)


class FullLinearSpring(LinearSpring):
    """:class:`LinearSpring` with every optional member of the protocol but
    ``pressure_and_stiffness`` (added to the solvers' use after such classes were written):
    taken as it is, not wrapped, by ``check_law`` before that member was optional."""

    def contact_fraction(self, u):
        return None

    def shear_stress(self, u):
        return None

    def in_contact(self, u):
        return self.pressure(u) > 0

    def resolve(self, length_scale, pressure_scale):
        return self

    @property
    def members(self):
        return (self,)

    def inverse(self):
        return None

    def describe(self):
        return {"law": "FullLinearSpring"}


class Exponential:
    """``σ = p0 exp(−u/ℓ)``: the protocol's members only, as :class:`LinearSpring`."""

    kind = "soft"

    def __init__(self, p0: float, ell: float) -> None:
        self.p0, self.ell = p0, ell

    def pressure(self, u):
        return self.p0 * np.exp(-np.asarray(u, dtype=float) / self.ell)

    def stiffness(self, u):
        return self.pressure(u) / self.ell


@pytest.mark.parametrize("spring", [LinearSpring, FullLinearSpring])
@pytest.mark.parametrize("velocity", [1e-2, 10.0, 1e4])
def test_a_law_of_its_own_class_gives_the_closed_form_of_a_spring_layer(velocity, spring,
                                                                        cole_cole):
    # full contact of a sine on the half-space through a linear spring layer: the layer (k)
    # and the half-space (M = E_r q/2 per unit height of the mode) act in series, so the
    # pressure mode is Δ kM/(k+M) and μ = qΔ Im[kM/(k+M)]/(2σ0); ū = u0 − σ0/k
    lam, delta = 0.125, 0.002
    q = 2 * np.pi / lam
    m = _er(cole_cole(), q * velocity) * q / 2
    k = abs(m)                                   # the layer as stiff as the half-space
    p_mode = delta * k * m / (k + m)
    sigma0 = 1.5 * abs(p_mode)                   # σ > 0 everywhere: the law stays linear
    law = spring(k, 0.01)
    assert not isinstance(law, InteractionLaw)
    res = solve_sliding(SineSeries([lam], [delta]), None, cole_cole(), velocity, sigma0, n=256,
                        law=law)
    assert res.contact_fraction == 1.0
    # a linear law on one Fourier mode: Newton is exact in a step, so round-off only
    # (measured 3e-15)
    assert res.friction == pytest.approx(q * delta * p_mode.imag / (2 * sigma0), rel=1e-10)
    assert res.mean_separation == pytest.approx(0.01 - sigma0 / k, rel=1e-10)
    assert res.info["law"] == {"law": spring.__name__}


def test_a_law_of_its_own_class_equals_the_built_in_table_of_it():
    # the log-PCHIP of TabulatedLaw is exact for an exponential, continued below and above
    # the table with the same exponential: the two laws agree to round-off, and so do the
    # solves, alone (Newton) and behind a wall (wall + soft): measured 1.5e-12 at most
    ell, p0 = 0.002, 2.0
    u = np.linspace(0.0, 0.04, 41)
    table = TabulatedLaw(u, p0 * np.exp(-u / ell))
    own = Exponential(p0, ell)
    np.testing.assert_allclose(table.pressure(u[:-1] + 3e-4), own.pressure(u[:-1] + 3e-4),
                               rtol=1e-12)
    surf = rc.roughness.section3(phases=[0.3, 1.2, 2.5]).partition(1.0)[1]
    sbr = rc.materials.sbr()
    for mine, theirs in ((own, table), (LennardJonesRepulsion() + own,
                                        LennardJonesRepulsion() + table)):
        a = solve_sliding(surf, None, sbr, 10.0, 1.0, n=1024, law=mine)
        b = solve_sliding(surf, None, sbr, 10.0, 1.0, n=1024, law=theirs)
        assert a.method == b.method
        assert b.friction > 0.01                 # a dissipative, non-trivial solve
        # (an exponential is "in contact" everywhere: the contact fraction says nothing)
        assert a.info.get("wall_soft_method") == b.info.get("wall_soft_method")
        assert a.friction == pytest.approx(b.friction, rel=1e-10)
        assert a.mean_separation == pytest.approx(b.mean_separation, rel=1e-10)
        np.testing.assert_allclose(a.pressure, b.pressure, rtol=0,
                                   atol=1e-10 * b.pressure.max())
    # the wall routes the protocol law as the soft part, in either order of the sum
    parts = split_law(own + LennardJonesRepulsion())
    assert parts.stiff is not None and parts.soft.kind == "soft"


def test_an_object_that_is_not_a_law_is_refused_in_one_line(cole_cole):
    class NoStiffness:
        kind = "soft"

        def pressure(self, u):
            return np.zeros_like(u)

    with pytest.raises(InputError, match="missing stiffness") as err:
        solve_sliding(SineSeries([1.0], [0.01]), None, cole_cole(), 1.0, 0.1, law=NoStiffness())
    assert "\n" not in str(err.value)
    bad_kind = Exponential(1.0, 1e-3)
    bad_kind.kind = "sticky"
    with pytest.raises(InputError, match="declares kind 'sticky'"):
        solve_sliding(SineSeries([1.0], [0.01]), None, cole_cole(), 1.0, 0.1, law=bad_kind)
    with pytest.raises(InputError, match="missing kind"):
        SumLaw(LennardJonesRepulsion(), type("K", (), {"pressure": 0, "stiffness": 0})())


class ClosedFormPressureLaw:
    """A high-slope law in pressure of its own class (not a ``PressureLaw``):
    ``α = σ/(1+σ)``, ``Δτ = 0.3σ²``, a layer of constant compliance."""

    max_pressure = 10.0

    def __init__(self, compliance: float) -> None:
        self.compliance = compliance

    def at(self, sigma):
        s = np.asarray(sigma, dtype=float)
        return s / (1 + s), 0.3 * s**2

    def compliance_at(self, sigma):
        return np.full(np.shape(sigma), self.compliance)


@pytest.mark.parametrize("interface", ["rigid", "law"])
def test_a_pressure_law_of_its_own_class_is_read_at_the_nearly_uniform_pressure(interface):
    # a low-slope scale of negligible slope: P(σ) → δ(σ − σ0), so μ_hs → Δτ(σ0)/σ0 = 0.3σ0
    # and A → α(σ0); G ~ 1e-8 leaves a relative spread of 1e-4 in σ, which the law's
    # curvature turns into ~1e-8 at most (measured 1.4e-12)
    ls = mf.PSD.from_sines(SineSeries([8.0], [1e-6]))
    sigma0 = 1.3
    opts = mf.MeanFieldOptions(interface=interface)
    res = mf.solve(ls, rc.materials.sbr(), 10.0, sigma0, law=ClosedFormPressureLaw(0.05),
                   options=opts)
    assert res.friction_hs == pytest.approx(0.3 * sigma0, rel=1e-7)
    assert res.contact_fraction == pytest.approx(sigma0 / (1 + sigma0), rel=1e-7)
    if interface == "law":
        # a layer without compliance (NaN: a theory law's) is refused, in one line
        with pytest.raises(InputError, match="needs the law's separations"):
            mf.solve(ls, rc.materials.sbr(), 10.0, sigma0, law=ClosedFormPressureLaw(np.nan),
                     options=opts)
    with pytest.raises(InputError, match="missing at") as err:
        mf.solve(ls, rc.materials.sbr(), 10.0, sigma0, law=object(), options=opts)
    assert "\n" not in str(err.value)

