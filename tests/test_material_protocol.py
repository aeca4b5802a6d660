"""Solvers take any material with the members of ``Material`` and route laws by their kind.

A Cole–Cole (fractional Zener) solid, written in closed form and not a Prony series, goes
through the half-space solver and the mean-field theory: in full contact of a sine both must
give the closed form ``μ = q²Δ² Im E_r(qv)/(4σ0)``; with exponent 1 it *is* the standard
linear solid, i.e. a one-branch :class:`GeneralizedMaxwell`, whose answers it must reproduce in
partial contact. A stiff wall law of a new class (a 12th-power wall) declaring
``kind = "wall"`` must be solved by the wall + soft algorithm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact import meanfield as mf
from rubbercontact.errors import InputError
from rubbercontact.halfspace import (
    InteractionLaw,
    LennardJonesRepulsion,
    TabulatedLaw,
    solve_sliding,
)
from rubbercontact.halfspace.walls import split_law
from rubbercontact.materials import GeneralizedMaxwell, Material, check_material
from rubbercontact.roughness import SineSeries


@dataclass(frozen=True)
class ColeCole:
    """``E(ω) = E_r + (E_u − E_r) (iωτ)^a / (1 + (iωτ)^a)`` [MPa]: no finite Prony series
    for ``a < 1``; ``a = 1`` is the standard linear solid."""

    relaxed: float = 3.0
    unrelaxed: float = 300.0
    tau: float = 1e-4
    exponent: float = 0.4
    name: str = "Cole-Cole"
    is_elastic: bool = False

    def complex_modulus(self, omega) -> np.ndarray:
        # principal branch of the power: (−iy)^a = conj((iy)^a), so E(−ω) = conj E(ω)
        x = (1j * np.asarray(omega, dtype=float) * self.tau) ** self.exponent
        return self.relaxed + (self.unrelaxed - self.relaxed) * x / (1.0 + x)


COLE: Material = ColeCole()


def _er(material, omega):
    return complex(material.complex_modulus(omega)) / 0.75      # ν = 0.5


def test_cole_cole_is_causal_and_not_a_prony_series():
    w = np.array([1e-2, 1.0, 1e4, 1e8])
    e = COLE.complex_modulus(w)
    np.testing.assert_allclose(COLE.complex_modulus(-w), np.conj(e), rtol=1e-15)
    assert np.all(e.imag > 0)
    # the loss peak of a Cole–Cole solid is broader than any single Maxwell branch's:
    # at 100× the peak frequency tan δ of the SLS has fallen far more
    sls = ColeCole(exponent=1.0)
    peak = 1.0 / COLE.tau
    assert COLE.complex_modulus(100 * peak).imag / COLE.complex_modulus(peak).imag > \
        5 * sls.complex_modulus(100 * peak).imag / sls.complex_modulus(peak).imag


@pytest.mark.parametrize("velocity", [1e-2, 10.0, 1e4])
def test_full_contact_friction_of_a_sine_in_the_halfspace(velocity):
    lam, delta = 0.125, 0.002
    q = 2 * np.pi / lam
    er = _er(COLE, q * velocity)
    sigma0 = 1.5 * abs(er) * q * delta / 2          # full contact: σ0 > |E_r| qΔ/2
    res = solve_sliding(SineSeries([lam], [delta]), None, COLE, velocity, sigma0, n=256)
    assert res.contact_fraction == 1.0
    # one Fourier mode is exact on the grid: only the solver tolerance (1e-8) remains
    assert res.friction == pytest.approx(q**2 * delta**2 * er.imag / (4 * sigma0), rel=1e-7)


@pytest.mark.parametrize("velocity", [1e-2, 10.0, 1e4])
def test_full_contact_friction_of_sines_in_the_meanfield(velocity):
    surf = rc.roughness.section3()
    q, d = surf.wavenumbers, surf.amplitudes
    er = COLE.complex_modulus(q * velocity) / 0.75
    sigma0 = 1e4 * float(np.max(q * d * np.abs(er)))   # G ~ 1e-8: A = 1 to round-off
    res = mf.solve(mf.PSD.from_sines(surf), COLE, velocity, sigma0)
    assert res.contact_fraction == 1.0
    # a sum in closed form: round-off only
    assert res.friction == pytest.approx(float(np.sum(q**2 * d**2 * er.imag)) / (4 * sigma0),
                                         rel=1e-12)


def test_standard_linear_solid_in_closed_form_is_the_one_branch_prony_series():
    sls = ColeCole(unrelaxed=30.0, tau=1e-3, exponent=1.0)
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
