"""The hybrids with the flash temperature (:mod:`rubbercontact.pipeline.flash_hybrid`) and
the law read between its speeds (:mod:`rubbercontact.hybrid.lawspeed`).

Checked against what the flash did not produce: the run's own isothermal hybrid, which an
infinitely conducting rubber and a temperature-independent one must reproduce bit for bit
(no shift of the speed, so the run's own solve with the run's own law table); the heat
``μ σ0 v`` of the friction the flash reports (energy balance); the growth of the rise with
the speed; a law tabulated alike at two speeds read between them is that law. The law is
the linear (VHS) law of the high-slope wave on a coarse grid, the speeds few, and the
run's continuation of the law past its highest point by the linear law's shape (VHS
solves on 2048 points near full contact, ~40 s of a run here, and the identity for a
linear law) is left out, so that a run takes seconds.
"""

import json

import numpy as np
import pytest
import xarray as xr

import rubbercontact as rc
from rubbercontact.hybrid.lawspeed import LawSpeeds, blend_tables
from rubbercontact.hybrid.lawtable import tabulated_law_from_dict
from rubbercontact.hybrid.linearlaw import linear_law_table
from rubbercontact.materials import GeneralizedMaxwell
from rubbercontact.pipeline.setup import resolve, task_material

WLF = {"law": "WLF", "c1": 8.86, "c2": 101.6}
#: A conductivity [W/(m·K)] 4e12 × the filled SBR's: a rise of ~1e-11 K, below the
#: search's tolerance, so every speed ends at its isothermal solve.
INFINITE_K = 1e12
HYBRIDS = ("hybrid", "hybrid-windowed")


def _config(tmp_path, speeds=(1.0, 100.0, 1e4), material=None, **over) -> dict:
    # a moderate wave counted as high-slope (m2_threshold 0.1), so that the linear law is
    # its law; two low-slope waves
    cfg = {"surface": {"wavelengths": [0.125, 1.0, 2.0], "amplitudes": [0.004, 0.02, 0.04],
                       "m2_threshold": 0.1},
           "material": material or {"preset": "sbr", "reference_temperature": 20.0,
                                    "shift": WLF},
           "loads": {"pressures": [0.3]}, "velocities": list(speeds),
           "models": list(HYBRIDS), "realizations": 1,
           "halfspace": {"n": 256, "hybrid_n": 256},
           "friction": {"flash_temperature": {"enabled": True}},
           "execution": {"workers": 1, "cache": str(tmp_path / "cache")},
           "output": {"directory": str(tmp_path / "out")}}
    cfg.update(over)
    return cfg


def _linear_law(cfg: dict) -> xr.Dataset:
    """The VHS law of the run's high-slope waves at its computed speeds, as a law table
    (the points in (near) full contact excluded)."""
    setup = resolve(rc.config.parse_config(cfg))
    mat = GeneralizedMaxwell(**task_material(setup.material))
    return linear_law_table(setup.hs0, mat, setup.speeds.computed,
                            np.geomspace(0.01, 100.0, 9), n=128)


@pytest.fixture(autouse=True)
def _no_continuation(monkeypatch):
    monkeypatch.setattr("rubbercontact.hybrid.lawtask.continue_with_linear_shape",
                        lambda table, *args, **kwargs: table)


def _run(cfg: dict) -> xr.Dataset:
    return rc.pipeline.run(cfg, law=_linear_law(cfg), progress=False)


@pytest.mark.parametrize("conductivity, searched", [(INFINITE_K, False), (3e5, True)])
def test_hybrids_of_an_infinitely_conducting_rubber_are_their_isothermal_run(
        tmp_path, conductivity, searched):
    """No rise. At 1e12 W/(m·K) no speed is searched (the heat's bound is below the
    tolerance: the run's own answer is taken); at 3e5 W/(m·K) (both scales' rises below
    the search's tolerance, their bound above it) the fastest speed is searched, and its
    search ends at its isothermal solve, the run's own task's solve with the run's own law
    table, bit for bit. (At 1e5 W/(m·K) the high-slope spots, 1 % of the area at 1e4 mm/s,
    still rise by 0.02 K: their Γ falls only as ln(D)/K at low Péclet number.)"""
    mat = {"preset": "sbr", "reference_temperature": 20.0, "shift": WLF,
           "thermal": {"conductivity": conductivity}}
    ds = _run(_config(tmp_path, material=mat))
    for m in HYBRIDS:
        np.testing.assert_array_equal(ds["friction_flash"].sel(model=m),
                                      ds["friction_mean"].sel(model=m))
        np.testing.assert_array_equal(ds["contact_fraction_flash"].sel(model=m),
                                      ds["contact_fraction_mean"].sel(model=m))
    assert np.all(ds["flash_temperature"].values == 0.0)
    assert (ds.attrs["flash_halfspace_solves"] > 0) == searched
    assert json.loads(ds.attrs["flash_models"]) == list(HYBRIDS)
    assert "not yet" not in ds.attrs["flash_note"]


def test_with_temperatures_the_hybrids_read_the_law_at_their_reduced_speeds(tmp_path):
    """At each run temperature T the flash reads the law at a_T(T + T_c) v: with no rise,
    at the run's own reduced speed, the table the run's task read; so each temperature
    is its isothermal hybrid (to the rounding of a_T v computed twice)."""
    mat = {"preset": "sbr", "reference_temperature": 20.0, "shift": WLF,
           "thermal": {"conductivity": INFINITE_K}}
    ds = _run(_config(tmp_path, speeds=(1.0, 1e3), material=mat, temperatures=[0.0, 40.0]))
    assert ds["friction_flash"].dims == ("model", "temperature", "velocity", "pressure")
    for m in HYBRIDS:
        np.testing.assert_allclose(ds["friction_flash"].sel(model=m),
                                   ds["friction_mean"].sel(model=m), rtol=1e-12)
    assert ds.attrs["flash_note"] == ""


def test_hybrids_of_a_temperature_independent_rubber_heat_but_keep_their_friction(tmp_path):
    """WLF with C1 = 1e-300: a_T = 1 exactly, so every solve is at the run's own speed,
    with the run's own law table, whatever the rise — its high-slope spots' too, hotter
    than the contact; the rise is the heat's (growing with the speed; at 1 mm/s below the
    search's tolerance, so 0)."""
    mat = {"preset": "sbr", "reference_temperature": 20.0,
           "shift": {"law": "WLF", "c1": 1e-300, "c2": 101.6}}
    ds = _run(_config(tmp_path, material=mat))
    for m in HYBRIDS:
        np.testing.assert_array_equal(ds["friction_flash"].sel(model=m),
                                      ds["friction_mean"].sel(model=m))
        rise = ds["flash_temperature"].sel(model=m, pressure=0.3).values
        assert rise[0] < 1e-2 and np.all(np.diff(rise) > 0) and rise[-1] > 1.0
        spots = ds["flash_temperature_hs"].sel(model=m, pressure=0.3).values
        assert np.all(spots >= rise) and spots[-1] > rise[-1] + 1.0
    assert ds.attrs["flash_note"] == ""


def test_hybrid_flash_energy_balance_growth_and_a_clamped_law_said_once(tmp_path):
    """The heat into the rubber is μ σ0 v (the solver's load balance, tol 1e-8); the rise
    grows with the speed; the flash moves μ where the rubber heats (past 1 K) and not at
    the slowest speed (no rise); where the slowest speed heats, the law is read at it and
    the note says so in one line."""
    ds = _run(_config(tmp_path))
    v = ds["velocity"].values
    for m in HYBRIDS:
        h = ds.sel(model=m, pressure=0.3)
        np.testing.assert_allclose(h["flash_heat_flux"], h["friction_flash"] * 0.3 * v,
                                   rtol=1e-7)
        rise = h["flash_temperature"].values
        assert rise[0] < 1e-2 and rise[-1] > 1.0 and np.all(np.diff(rise) > 0)
        mu, iso = h["friction_flash"].values, h["friction_mean"].values
        assert mu[0] == pytest.approx(iso[0], rel=1e-3)
        assert abs(mu[-1] / iso[-1] - 1) > 0.05
    assert ds.attrs["flash_note"] == "" and ds.attrs["flash_residual_K"] < 1.0

    hot = _run(_config(tmp_path / "hot", speeds=(1e3, 1e4)))
    note = hot.attrs["flash_note"]
    assert "\n" not in note and "clamped, not extrapolated" in note
    assert "tabulated from 1000 mm/s" in note
    assert np.all(np.isfinite(hot["friction_flash"].sel(model="hybrid").values))


def test_the_law_at_a_tabulated_speed_is_its_table_and_outside_is_clamped(hand_made_law):
    a = hand_made_law(11)
    b = {**a, "shear_stress": [2.0 * t for t in a["shear_stress"]]}
    laws = LawSpeeds({1.0: a, 100.0: b})
    assert laws.at(1.0).table is a and laws.at(100.0 * (1 + 1e-12)).table is b
    slow = laws.at(0.5)
    assert slow.clamped and slow.table is a and slow.read_at == 1.0
    fast = laws.at(200.0)
    assert fast.clamped and fast.table is b
    mid = laws.at(10.0)              # halfway in ln v: the geometric mean of a and b
    assert not mid.clamped and mid.weight == pytest.approx(0.5)
    pos = np.asarray(a["pressure"]) > 0
    np.testing.assert_allclose(np.asarray(mid.table["shear_stress"])[pos],
                               np.sqrt(2.0) * np.asarray(a["shear_stress"])[pos],
                               rtol=1e-12)
    np.testing.assert_allclose(mid.table["separation"], a["separation"], rtol=1e-12)


def test_a_law_tabulated_alike_at_two_speeds_is_that_law_between_them(hand_made_law):
    """The same table at two speeds: the same law between them (to rounding); tables on
    other pressures (11 against 31 nodes): a law (u strictly decreasing in σ) on the union
    of their pressures, between the two tables' own interpolants."""
    table = hand_made_law(11)
    for w in (0.0, 0.3, 1.0):
        mid = blend_tables(table, table, w)
        for k in table:
            np.testing.assert_allclose(mid[k], table[k], rtol=1e-12, atol=1e-15)
    coarse, fine = hand_made_law(11), hand_made_law(31)
    mid = blend_tables(coarse, fine, 0.3)
    assert np.all(np.diff(mid["separation"]) > 0) and np.all(np.diff(mid["pressure"]) < 0)
    assert len(mid["pressure"]) == 31        # the coarse pressures are among the fine ones
    u = np.asarray(mid["separation"])
    lc, lf = tabulated_law_from_dict(coarse), tabulated_law_from_dict(fine)
    lo, hi = np.minimum(lc.pressure(u), lf.pressure(u)), np.maximum(lc.pressure(u),
                                                                     lf.pressure(u))
    sig = np.asarray(mid["pressure"])
    assert np.all(lo <= sig * (1 + 1e-9) + 1e-12) and np.all(sig <= hi * (1 + 1e-9) + 1e-12)
    with pytest.raises(rc.errors.InputError, match="weight"):
        blend_tables(coarse, fine, 1.5)
