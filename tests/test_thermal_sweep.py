"""The accelerated flash of a half-space contact against the plain search, and over sweeps
(thermal/contact.py's secant search, thermal/sweep.py).

The reference is the plain search (bracket + false position) of the same fixed point: both
stop when ``|F(T) − T|`` is below their tolerance ε, and ``F`` decreases with ``T`` on
this profile at the roots (a hotter rubber is a slower one, and slides with a smaller
contact: checked below), so ``|1 − F'| ≥ 1`` and the two roots differ by at most
``ε_plain + ε_secant``; where ``F`` jumps over the diagonal (the grid's contact set
changes) both stop in a bracket of width ε around the jump, so the bound holds there too.
"""

from __future__ import annotations

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.thermal import FlashSearch, FlashStart, flash_contact, flash_sweep
from rubbercontact.thermal.contact import start_pressure
from rubbercontact.thermal.sweep import predicted_start

SBR = rc.materials.sbr()
WLF = rc.materials.WLF(8.86, 101.6, 20.0)
SINES = rc.roughness.SineSeries([1.0, 0.1, 0.01], [0.02, 0.002, 0.0002])
PLAIN = FlashSearch(method="bracket")
SPEEDS = np.logspace(-1, 4, 6)


def _solve(pressure: float = 0.1, n: int = 2048):
    return lambda u: rc.halfspace.solve_sliding(SINES, None, SBR, u, pressure, n=n)


def _eps(out) -> float:
    """The stopping tolerance the search used at its root [K]."""
    rise = out.contact_temperature - out.background_temperature
    return out.inputs["tolerance_K"] + out.inputs["relative_tolerance"] * rise


def _rise(out) -> float:
    return out.contact_temperature - out.background_temperature


@pytest.fixture(scope="module")
def sweeps():
    solve = _solve()
    plain = [flash_contact(solve, v, WLF, search=PLAIN) for v in SPEEDS]
    return plain, flash_sweep(solve, SPEEDS, WLF)


def test_the_secant_search_finds_the_plain_root(sweeps):
    plain, _ = sweeps
    solve = _solve()
    for v, ref in zip(SPEEDS, plain, strict=True):
        out = flash_contact(solve, v, WLF)
        if out.residual > _eps(out):          # F jumps (the grid's contact set): both
            assert ref.residual > ref.inputs["tolerance_K"]     # stop at the jump
        assert abs(_rise(out) - _rise(ref)) <= _eps(out) + ref.inputs["tolerance_K"]


def test_the_sweep_finds_the_plain_roots(sweeps):
    plain, sweep = sweeps
    assert not sweep.failures
    for ref, out in zip(plain, sweep.flashes, strict=True):
        assert abs(_rise(out) - _rise(ref)) <= _eps(out) + ref.inputs["tolerance_K"]
        # |ΔT| ≤ 0.06 K here moves a WLF shift by ≤ 0.004 decades
        assert out.result.friction == pytest.approx(ref.result.friction, rel=2e-3)
        if _rise(ref) == 0.0:              # cold: the isothermal solve, once, bit for bit
            assert len(out.evaluations) == 1 and _rise(out) == 0.0
            assert out.result.friction == ref.result.friction


def test_warm_started_solves_find_the_plain_roots(sweeps):
    """Each heated solve polished from the nearest one solved: the same roots to the
    tolerance, and the cold speeds' isothermal solves bit for bit."""
    plain, _ = sweeps

    def solve(u, start=None):
        return rc.halfspace.solve_sliding(SINES, None, SBR, u, 0.1, n=2048,
                                          start=None if start is None
                                          else start_pressure(start))

    warm = flash_sweep(solve, SPEEDS, WLF, search=FlashSearch(warm_start=True))
    assert any(f.result.info.get("warm_start") for f in warm.flashes)
    for ref, out in zip(plain, warm.flashes, strict=True):
        assert abs(_rise(out) - _rise(ref)) <= _eps(out) + ref.inputs["tolerance_K"]
        if _rise(ref) == 0.0:
            assert out.result.friction == ref.result.friction


def test_a_sweep_guided_by_another_realization_finds_the_plain_roots(sweeps):
    """Started at the roots of another realization (the same waves in other phases):
    the same roots to the tolerance, the cold speeds' isothermal solves bit for bit; a
    guide over other speeds is refused."""
    plain, _ = sweeps
    other = rc.roughness.SineSeries(SINES.wavelengths, SINES.amplitudes, [1.0, 2.0, 3.0])
    guide = flash_sweep(lambda u: rc.halfspace.solve_sliding(other, None, SBR, u, 0.1,
                                                             n=2048), SPEEDS, WLF)
    guided = flash_sweep(_solve(), SPEEDS, WLF, guide=guide)
    assert not guided.failures
    for ref, out in zip(plain, guided.flashes, strict=True):
        assert abs(_rise(out) - _rise(ref)) <= _eps(out) + ref.inputs["tolerance_K"]
        if _rise(ref) == 0.0:
            assert out.result.friction == ref.result.friction
    with pytest.raises(InputError, match="guide"):
        flash_sweep(_solve(), SPEEDS[:3], WLF, guide=guide)


def test_the_fixed_point_map_falls_with_the_temperature_at_the_root(sweeps):
    """The premise of the bound in the module docstring: F' ≤ 0 at the plain root (the
    slope between its two evaluations closest to it)."""
    plain, _ = sweeps
    slopes = [out.log_slope for out in plain if out.log_slope is not None]
    assert slopes and max(slopes) <= 0


def test_a_temperature_independent_rubber_keeps_its_isothermal_friction_at_every_speed():
    law = rc.materials.Arrhenius(1e-6, 20.0)        # a_T = 1 to 1e-9
    solve = _solve()
    sweep = flash_sweep(solve, [300.0, 1e3, 1e4], law)
    for v, out in zip(sweep.velocities, sweep.flashes, strict=True):
        assert _rise(out) > 0.1
        assert out.result.friction == pytest.approx(solve(v).friction, rel=1e-8)


def test_an_infinitely_conducting_rubber_sweeps_isothermally():
    solve = _solve()
    hot = rc.thermal.ThermalProperties(conductivity=1e20)
    sweep = flash_sweep(solve, [1.0, 1e4], WLF, thermal=hot)
    for v, out in zip(sweep.velocities, sweep.flashes, strict=True):
        assert _rise(out) == 0.0 and len(out.evaluations) == 1
        assert out.result.friction == solve(v).friction


class _Done:
    """A converged flash with only what :func:`predicted_start` reads."""

    def __init__(self, rise: float):
        self.contact_temperature, self.background_temperature = 20.0 + rise, 20.0
        self.evaluations = ((rise, rise * 1.1), (rise * 1.2, rise * 0.9))

    log_slope = property(lambda self: -0.5)
    result = None


def test_the_prediction_is_exact_on_power_laws_and_quadratics_in_log_log():
    v = [1.0, 10.0, 100.0]
    power = [(x, _Done(0.3 * x**0.7)) for x in v]
    assert predicted_start(power[:2], 1e3, 1e-2).rise == pytest.approx(0.3 * 1e3**0.7)
    assert predicted_start(power, 1e3, 1e-2).rise == pytest.approx(0.3 * 1e3**0.7)
    assert predicted_start(power, 1e3, 1e-2).log_slope == -0.5
    # one heated speed: the moving source's T ∝ v^(1/2)
    assert predicted_start(power[-1:], 1e4, 1e-2).rise == pytest.approx(
        0.3 * 100.0**0.7 * 10.0)
    quad = [(x, _Done(np.exp(0.1 + 0.4 * np.log(x) - 0.02 * np.log(x) ** 2))) for x in v]
    expected = np.exp(0.1 + 0.4 * np.log(1e3) - 0.02 * np.log(1e3) ** 2)
    assert predicted_start(quad, 1e3, 1e-2).rise == pytest.approx(expected)
    # cold last speed: start at the isothermal solve
    assert predicted_start([(1.0, _Done(0.0))], 10.0, 1e-2) is None
    # the exponent is kept in [0, 3/2]
    steep = [(1.0, _Done(1e-2 * 1.01)), (10.0, _Done(10.0))]
    assert predicted_start(steep, 100.0, 1e-3).rise == pytest.approx(10.0 * 10**1.5)


def test_bad_search():
    with pytest.raises(InputError, match="method"):
        FlashSearch(method="newton")
    with pytest.raises(InputError, match="max_solves"):
        FlashSearch(max_solves=0)
    with pytest.raises(InputError, match="rise"):
        FlashSearch(start=FlashStart(-1.0))
    with pytest.raises(InputError, match="velocities"):
        flash_sweep(_solve(), [1.0, -1.0], WLF)
