"""``meanfield-hybrid`` with the flash temperature (rubbercontact.pipeline.flash_meanfield).

Checked against what the flash did not produce: the run's own isothermal answer, which an
infinitely conducting rubber and a temperature-independent one must reproduce bit for bit
(no shift of the speed: the run's own solve with the run's own law table); the heat
``μ σ0 v``; and, on a one-node model of the solve, the Lambert-W root of the scalar
equation the search solves. The law is the linear (VHS) law of the high-slope wave, as in
tests/test_pipeline_flash_hybrid.py (whose run configuration this reuses).
"""

from __future__ import annotations

import json
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.special import lambertw
from test_pipeline_flash_hybrid import WLF, _config, _run

import rubbercontact as rc
from rubbercontact.meanfield.flash import FlashOptions
from rubbercontact.pipeline.flash_meanfield_task import contact_rise, meanfield_hybrid_flash
from rubbercontact.thermal import band_centre_temperature

MODEL = "meanfield-hybrid"
SPEEDS = (1.0, 100.0, 1e4, 1e5)


@pytest.fixture(autouse=True)
def _no_continuation(monkeypatch):
    monkeypatch.setattr("rubbercontact.hybrid.lawtask.continue_with_linear_shape",
                        lambda table, *args, **kwargs: table)


def _material(**over) -> dict:
    return {"preset": "sbr", "reference_temperature": 20.0, "shift": WLF, **over}


@pytest.mark.filterwarnings("ignore::rubbercontact.hybrid.lawtable.LawWarning")
def test_an_infinitely_conducting_rubber_is_the_isothermal_run(tmp_path):
    """1e12 W/(m·K): a rise ~1e-6 K at 1e5 mm/s, below the tolerance (1e-3 K), so every
    speed keeps its solve at a_T(T_ref) v = v, the run's own task's, bit for bit."""
    mat = _material(thermal={"conductivity": 1e12})
    ds = _run(_config(tmp_path, speeds=SPEEDS, material=mat, models=[MODEL]))
    h = ds.sel(model=MODEL)
    np.testing.assert_array_equal(h["friction_flash"], h["friction_mean"])
    np.testing.assert_array_equal(h["contact_fraction_flash"], h["contact_fraction_mean"])
    assert np.all(h["flash_temperature"].values == 0.0)
    assert json.loads(ds.attrs["flash_models"]) == [MODEL]
    assert "not yet" not in ds.attrs["flash_note"]


@pytest.mark.filterwarnings("ignore::rubbercontact.hybrid.lawtable.LawWarning")
def test_with_temperatures_each_is_its_isothermal_run_at_infinite_conductivity(tmp_path):
    """At each run temperature T the search solves at a_T(T + T_c) v with T_c = 0: the
    run's own reduced speed and law table, so each temperature is its isothermal answer
    (to the rounding of a_T v computed twice: 1e-12)."""
    mat = _material(thermal={"conductivity": 1e12})
    ds = _run(_config(tmp_path, speeds=(1.0, 1e3), material=mat, models=[MODEL],
                      temperatures=[0.0, 40.0]))
    h = ds.sel(model=MODEL)
    assert h["friction_flash"].dims == ("temperature", "velocity", "pressure")
    np.testing.assert_allclose(h["friction_flash"], h["friction_mean"], rtol=1e-12)
    assert np.all(h["flash_temperature"].values == 0.0)


@pytest.mark.filterwarnings("ignore::rubbercontact.hybrid.lawtable.LawWarning")
def test_a_temperature_independent_rubber_heats_but_keeps_its_friction(tmp_path):
    """WLF with C1 = 1e-300: a_T = 1 exactly, every solve is the run's own whatever the
    rise; the rise grows with the speed (1 mm/s: below 1e-2 K); the heat is μσ0v."""
    mat = _material(shift={"law": "WLF", "c1": 1e-300, "c2": 101.6})
    ds = _run(_config(tmp_path, speeds=SPEEDS, material=mat, models=[MODEL]))
    h = ds.sel(model=MODEL, pressure=0.3)
    np.testing.assert_array_equal(h["friction_flash"], h["friction_mean"])
    rise = h["flash_temperature"].values
    assert rise[0] < 1e-2 and np.all(np.diff(rise) > 0) and rise[-1] > 1.0
    np.testing.assert_allclose(h["flash_heat_flux"],
                               h["friction_flash"] * 0.3 * h["velocity"], rtol=1e-12)


@pytest.mark.filterwarnings("ignore::rubbercontact.hybrid.lawtable.LawWarning")
def test_the_heated_rubber_is_slower_and_the_search_converged(tmp_path):
    """With the SBR's WLF the rise grows with the speed and moves μ at the fast speeds
    (> 5 % at 1e4–1e5 mm/s, where it is 10–40 K; measured −34 %, −23 %), and at 1 mm/s
    only by its rise (3e-3 K there, μ moving ~2.5e-2 per K relative: 2e-4); the residual
    is within the tolerance's reach. The law's pressures (to 1 MPa here) do not cover the
    contact: the solves' warnings become one line of the note, not one warning each."""
    ds = _run(_config(tmp_path, speeds=SPEEDS, models=[MODEL]))
    h = ds.sel(model=MODEL, pressure=0.3)
    rise = h["flash_temperature"].values
    mu, iso = h["friction_flash"].values, h["friction_mean"].values
    assert rise[0] < 1e-2 and np.all(np.diff(rise) > 0) and rise[-1] > 10.0
    assert mu[0] == pytest.approx(iso[0], rel=2e-4)
    assert np.all(np.abs(mu[2:] / iso[2:] - 1) > 0.05)
    assert ds.attrs["flash_residual_K"] < 1.0
    note = ds.attrs["flash_note"]
    assert "\n" not in note and note.startswith(f"{MODEL} at 0.3 MPa: up to ")
    assert "beyond the law's highest pressure, where it is held; " in note


def test_the_search_solves_the_scalar_equation():
    """A one-node stand-in for the solve: area A fixed, μ = μ0 (u/v)^m shared between the
    node (μ_ls) and the law (μ_hs), both heating the finest spots. With the exponential
    shift log10 a_T = −sΔT the rise is ``ΔT = ΔT0 a^m = ΔT0 e^{−kΔT}``, ``k = m s ln 10``,
    ``ΔT0 = (1/A − 1) Γ μ0 σ0 v``: ``ΔT = W(kΔT0)/k``. To 1e-6 relative: the search
    stops within 1e-9 K, the WLF with C2 = 1e8 K is exponential to ΔT/C2 < 1e-6."""
    q, area, mu0, m, s, sigma0 = 2 * np.pi, 0.05, 0.4, 0.5, 0.02, 0.3
    law = rc.materials.WLF(s * 1e8, 1e8, 20.0)
    flash = FlashOptions(tolerance=1e-9)
    speeds = np.array([1e2, 1e4, 1e6])
    asked = {}

    def solve(u):
        v = asked["v"]
        mu = mu0 * (u / v) ** m
        return SimpleNamespace(friction=mu, friction_hs=0.25 * mu, contact_fraction=area,
                               friction_spectrum=(np.array([q]), np.array([0.75 * mu])),
                               area=SimpleNamespace(contact_fraction=np.array([area])))

    rises = []
    for v in speeds:
        asked["v"] = v
        out = meanfield_hybrid_flash(solve, np.array([v]), sigma0, law, None, flash)
        rises.append(out.rise[0])
        assert out.heat_flux[0] == pytest.approx(out.friction[0] * sigma0 * v, rel=1e-15)
        assert out.residual[0] < 1e-6
    gamma = band_centre_temperature(np.pi / 2 / q, speeds, flash.thermal)
    rise0 = (1 / area - 1) * gamma * mu0 * sigma0 * speeds
    k = m * s * np.log(10)
    np.testing.assert_allclose(rises, lambertw(k * rise0).real / k, rtol=1e-6)
    # contact_rise of the state without feedback is the cascade's one step
    asked["v"] = speeds[0]
    assert contact_rise(solve(speeds[0]), speeds[0], sigma0, flash) == pytest.approx(
        rise0[0], rel=1e-14)
