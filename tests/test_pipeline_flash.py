"""A run with ``[friction.flash_temperature]``: the mean-field μ(v) with the flash beside
the isothermal one (:mod:`rubbercontact.pipeline.flash`).

Checked against what the flash did not produce: the run's own isothermal friction, which
an infinitely conducting rubber must reproduce (no temperature rise, so the same theory at
the same speeds), a run without the table (identical), and the physics of frictional
heating (the heat ``μσ0v`` grows with the speed, and so does the flash).
"""

import json

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.cli import main
from rubbercontact.errors import InputError
from rubbercontact.pipeline.statistics import friction_peak
from rubbercontact.plotting.summary import summary_table

WLF = {"law": "WLF", "c1": 8.86, "c2": 101.6}
#: The isothermal theory the flash solver reads off its modulus tables agrees with the
#: direct solve to 1e-8 (meanfield/flash.py, tests/test_meanfield_flash.py); with a rise of
#: ~1e-11 K the shift moves ω by ~1e-12: both well below this [relative].
SOLVER_RTOL = 1e-6
#: A conductivity [W/(m·K)] 4e12 × the filled SBR's: the spots' rise scales as 1/K, so the
#: 30 K flash of the default compound at 10 m/s becomes ~1e-11 K.
INFINITE_K = 1e12


def _config(tmp_path, flash: dict | None = None, **over) -> dict:
    cfg = {"surface": {"wavelengths": [0.125, 0.25, 0.5, 1.0],
                       "amplitudes": [0.005, 0.01, 0.02, 0.04]},
           "material": {"preset": "sbr", "reference_temperature": 20.0, "shift": WLF},
           "loads": {"pressures": [0.3, 1.0]},
           "velocities": {"from": 1e-2, "to": 1e4, "points": 7},
           "models": ["meanfield"],
           "execution": {"workers": 1, "cache": str(tmp_path / "cache")},
           "output": {"directory": str(tmp_path / "out")}}
    if flash is not None:
        cfg["friction"] = {"flash_temperature": flash}
    cfg.update(over)
    return cfg


def _run(cfg: dict):
    return rc.pipeline.run(cfg, progress=False)


def test_an_infinitely_conducting_rubber_has_the_isothermal_friction(tmp_path):
    mat = {"preset": "sbr", "reference_temperature": 20.0, "shift": WLF,
           "thermal": {"conductivity": INFINITE_K}}
    ds = _run(_config(tmp_path, {"enabled": True}, material=mat))
    assert ds["friction_flash"].dims == ("model", "velocity", "pressure")
    iso = ds["friction"].isel(realization=0)
    np.testing.assert_allclose(ds["friction_flash"], iso, rtol=SOLVER_RTOL)
    np.testing.assert_allclose(ds["contact_fraction_flash"],
                               ds["contact_fraction"].isel(realization=0), rtol=SOLVER_RTOL)
    assert np.all(np.abs(ds["flash_temperature"].values) < 1e-6)
    thermal = json.loads(ds.attrs["flash_thermal"])
    assert thermal["conductivity"] == INFINITE_K and thermal["source"] == "given"


def test_with_temperatures_each_temperature_is_its_isothermal_run_at_infinite_conductivity(
        tmp_path):
    # the flash is computed at the true speeds at each T; the run's isothermal friction at
    # the reduced speeds a_T v: the same theory by time-temperature superposition
    mat = {"preset": "sbr", "reference_temperature": 20.0, "shift": WLF,
           "thermal": {"conductivity": INFINITE_K}}
    ds = _run(_config(tmp_path, {"enabled": True}, material=mat, temperatures=[0.0, 40.0],
                      loads={"pressures": [0.3]}))
    assert ds["friction_flash"].dims == ("model", "temperature", "velocity", "pressure")
    np.testing.assert_allclose(ds["friction_flash"], ds["friction"].isel(realization=0),
                               rtol=SOLVER_RTOL)


def test_the_flash_grows_with_speed_and_vanishes_with_it(tmp_path):
    ds = _run(_config(tmp_path, {"enabled": True}))
    rise = ds["flash_temperature"].sel(model="meanfield").values        # (speed, load)
    assert np.all(np.diff(rise, axis=0) > 0) and np.all(rise > 0)
    # v -> 0: no heat, the isothermal theory; at 1e-2 mm/s the rise is ~1e-5 K, which
    # moves the WLF shift by ~1e-6 decades, far below this tolerance
    mu, mu_iso = ds["friction_flash"].values[0], ds["friction"].values[0, :, 0]
    assert np.all(rise[0] < 1e-3)
    np.testing.assert_allclose(mu[0], mu_iso[0], rtol=1e-4)
    assert json.loads(ds.attrs["timings_s"])["flash"] > 0


def test_the_summary_prints_both_peaks_and_the_compound(tmp_path):
    ds = _run(_config(tmp_path, {"enabled": True}, loads={"pressures": [0.3]},
                      velocities={"from": 1.0, "to": 1e4, "points": 9}))
    text = summary_table(ds)
    assert "Mark, Physical Properties of Polymers" in text and "meanfield mu flash" in text
    lines = text.splitlines()
    flash = [x for x in lines if x.startswith("  peak of meanfield with flash")]
    iso = [x for x in lines if x.startswith("  peak of meanfield:")]
    assert len(flash) == len(iso) == 1
    v = ds["velocity"].values
    peak = friction_peak(v, ds["friction_flash"].sel(model="meanfield").values[:, 0])
    assert f"mu = {peak.friction:.4f} at v = {peak.velocity:.4g} mm/s" in flash[0]
    # the flash lowers the maximum of μ(v) (Persson, J. Phys.: Condens. Matter 18, 7789,
    # 2006): the scales that dissipate most are the hottest, moved to their rubbery side
    iso_peak = friction_peak(v, ds["friction"].sel(model="meanfield").values[:, 0, 0])
    assert peak.friction < iso_peak.friction


def test_per_scale_the_finer_spots_are_hotter_and_the_tread_heats_them_all(tmp_path):
    # ΔT_i = Σ_{l ≤ i} (1/A_l − 1/A_{l−1}) Γ_l W_l (+ the tread's rise): a sum of terms
    # ≥ 0 over the coarser levels, so non-decreasing towards the finer nodes, its last
    # node the finest spots' flash_temperature
    cold = _run(_config(tmp_path / "a", {"enabled": True}, loads={"pressures": [0.3]}))
    rise = cold["flash_scale_temperature"].sel(model="meanfield", pressure=0.3).values
    assert cold["flash_scale_temperature"].dims[-1] == "flash_wavenumber"
    assert np.all(np.diff(cold["flash_wavenumber"].values) > 0)
    assert np.all(np.diff(rise, axis=-1) >= -1e-12)
    np.testing.assert_array_equal(rise[:, -1], cold["flash_temperature"].values[0, :, 0])
    # a tread sliding 10 ms in the footprint is heated as a whole besides its spots
    warm = _run(_config(tmp_path / "b", {"enabled": True, "contact_time": 0.01},
                        loads={"pressures": [0.3]}))
    fast = warm["velocity"].values > 10.0
    assert np.all(warm["flash_temperature"].values[0, fast, 0]
                  > cold["flash_temperature"].values[0, fast, 0])
    assert json.loads(warm.attrs["flash_options"])["contact_time"] == 0.01


def test_flash_off_is_the_run_without_the_table(tmp_path):
    off = _run(_config(tmp_path / "off", {"enabled": False}))
    none = _run(_config(tmp_path / "none"))
    assert set(off.data_vars) == set(none.data_vars) and set(off.coords) == set(none.coords)
    assert not any("flash" in k for k in (*off.data_vars, *off.attrs))
    for k in none.data_vars:
        if k != "wall_time":
            np.testing.assert_array_equal(off[k].values, none[k].values)


def test_models_without_the_flash_are_named_in_a_note_and_left_nan(tmp_path):
    cfg = _config(tmp_path, {"enabled": True}, models=["meanfield-strips", "meanfield"],
                  velocities=[1.0, 100.0], loads={"pressures": [0.3]})
    ds = _run(cfg)
    note = ds.attrs["flash_note"]
    assert note.count("\n") == 0 and "not yet for meanfield-strips" in note
    assert np.all(np.isnan(ds["friction_flash"].sel(model="meanfield-strips")))
    assert np.all(np.isfinite(ds["friction_flash"].sel(model="meanfield")))


#: The VHS runs: two realizations on 512 points, 1 – 1e4 mm/s.
VHS = {"models": ["vhs"], "halfspace": {"n": 512}, "realizations": 2,
       "velocities": {"from": 1.0, "to": 1e4, "points": 5}, "loads": {"pressures": [0.3]}}


@pytest.mark.parametrize("conductivity, searched", [(INFINITE_K, False), (5e4, True)])
def test_vhs_with_an_infinitely_conducting_rubber_is_its_isothermal_run(tmp_path,
                                                                        conductivity,
                                                                        searched):
    """No rise: at 1e12 W/(m·K) the heat's bound (thermal.rise_bound) is below the
    tolerance at every speed, so no speed is searched and the run's own isothermal answer
    is taken; at 5e4 W/(m·K) (a rise of ~5e-3 K at 1e4 mm/s, below the search's
    tolerance 1e-2 K, a bound of ~2e-2 K above it) the fastest speed is searched and ends
    at its isothermal solve: the same solve as the run's own task, bit for bit."""
    mat = {"preset": "sbr", "reference_temperature": 20.0, "shift": WLF,
           "thermal": {"conductivity": conductivity}}
    ds = _run(_config(tmp_path, {"enabled": True}, material=mat, **VHS))
    np.testing.assert_array_equal(ds["friction_flash"].sel(model="vhs"),
                                  ds["friction_mean"].sel(model="vhs"))
    np.testing.assert_array_equal(ds["contact_fraction_flash"].sel(model="vhs"),
                                  ds["contact_fraction_mean"].sel(model="vhs"))
    assert np.all(ds["flash_temperature"].values == 0.0)
    assert (ds.attrs["flash_halfspace_solves"] > 0) == searched


def test_vhs_of_a_temperature_independent_rubber_heats_but_keeps_its_friction(tmp_path):
    """WLF with C1 = 1e-300: a_T = 1 exactly at every temperature, so each solve is the
    isothermal one whatever the rise; the rise itself is the heat's (> 0, growing)."""
    mat = {"preset": "sbr", "reference_temperature": 20.0,
           "shift": {"law": "WLF", "c1": 1e-300, "c2": 101.6}}
    ds = _run(_config(tmp_path, {"enabled": True}, material=mat, temperatures=[0.0, 40.0],
                      **VHS))
    np.testing.assert_array_equal(ds["friction_flash"].sel(model="vhs"),
                                  ds["friction_mean"].sel(model="vhs"))
    rise = ds["flash_temperature"].sel(model="vhs", pressure=0.3).values
    assert np.all(rise[:, -1] > 1.0) and np.all(np.diff(rise, axis=-1) > 0)


def test_vhs_flash_variables_energy_balance_and_summary(tmp_path):
    """The heat into the rubber is μ σ0 v (the solver's pressure, averaged over the
    realizations: to its load balance, tol 1e-8); the flash rises with the speed; units;
    the summary prints the VHS's two peaks."""
    ds = _run(_config(tmp_path, {"enabled": True}, **VHS))
    vhs = ds.sel(model="vhs", pressure=0.3)
    v = ds["velocity"].values
    np.testing.assert_allclose(vhs["flash_heat_flux"], vhs["friction_flash"] * 0.3 * v,
                               rtol=1e-7)
    rise = vhs["flash_temperature"].values
    assert rise[0] < 0.1 and rise[-1] > 1.0 and np.all(np.diff(rise[1:]) > 0)
    units = {k: ds[k].attrs["units"] for k in ("friction_flash", "contact_fraction_flash",
                                                 "flash_temperature", "flash_heat_flux")}
    assert units == {"friction_flash": "1", "contact_fraction_flash": "1",
                     "flash_temperature": "K", "flash_heat_flux": "mW/mm^2"}
    assert ds.attrs["flash_note"] == "" and ds.attrs["flash_residual_K"] < 1.0
    assert json.loads(ds.attrs["flash_halfspace_search"])["method"] == "secant"
    text = summary_table(ds)
    assert "vhs mu flash" in text and "peak of vhs with flash temperature" in text


@pytest.mark.parametrize("over, match", [
    ({"material": {"preset": "sbr", "thermal": {"conductivity": -1.0}}}, "conductivity"),
    ({"material": {"preset": "sbr", "thermal": {"conduct": 0.2}}}, "unknown key"),
    ({"friction": {"flash_temperature": {"enabled": True, "contact_time": 0.0}}},
     "contact_time"),
    ({"friction": {"flash_temperature": {"enabled": True}},
      "material": {"preset": "sbr"}}, "shift law"),
    ({"friction": {"flash_temperature": {"enabled": True}},
      "meanfield": {"geometry": "diffusion"}}, "meanfield-strips"),
])
def test_bad_flash_input_is_one_line(tmp_path, over, match):
    with pytest.raises(InputError, match=match) as err:
        _run(_config(tmp_path, **over))
    assert "\n" not in str(err.value)


def test_cli_exits_2_on_bad_thermal_input(tmp_path, capsys):
    path = tmp_path / "run.toml"
    path.write_text('velocities = [1.0]\nmodels = ["meanfield"]\n'
                    '[surface]\nwavelengths = [0.5]\namplitudes = [0.01]\n'
                    '[loads]\npressures = [0.3]\n'
                    '[material]\npreset = "sbr"\n[material.thermal]\ndensity = 0\n')
    assert main(["run", str(path), "--check"]) == 2
    assert "density" in capsys.readouterr().err


def test_the_speed_figure_draws_the_flash_curve_dashed_beside_the_isothermal_one(
        tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rubbercontact.plotting import speed

    figs = []
    monkeypatch.setattr(speed, "_save", lambda fig, path, **kw: figs.append(fig) or path)
    ds = _run(_config(tmp_path, {"enabled": True}, loads={"pressures": [0.3]},
                      temperatures=[20.0, 60.0], velocities=[1.0, 100.0, 1e4]))
    speed.plot_friction_vs_speed(ds, tmp_path / "mu.png")
    for ax, t in zip(figs[0].axes, (20.0, 60.0), strict=True):
        lines = {line.get_label(): line for line in ax.lines}
        dashed = lines["meanfield: with flash temperature"]
        assert dashed.get_linestyle() == "--" and lines["meanfield"].get_linestyle() == "-"
        np.testing.assert_array_equal(
            dashed.get_ydata(), ds["friction_flash"].sel(model="meanfield", temperature=t,
                                                         pressure=0.3).values)
    plt.close("all")


def test_the_plan_names_the_flash_and_check_catches_its_inputs(tmp_path, capsys):
    from rubbercontact.cli.run import describe_plan

    cfg = rc.config.parse_config(_config(tmp_path, {"enabled": True},
                                         models=["vhs", "meanfield"]))
    line = [x for x in describe_plan(cfg).splitlines() if x.startswith("flash")]
    assert len(line) == 1 and "vhs, meanfield" in line[0] and "not yet" not in line[0]
    path = tmp_path / "run.toml"
    path.write_text('velocities = [1.0]\nmodels = ["meanfield"]\n'
                    '[surface]\nwavelengths = [0.5]\namplitudes = [0.01]\n'
                    '[loads]\npressures = [0.3]\n[material]\npreset = "sbr"\n'
                    '[friction.flash_temperature]\nenabled = true\n')
    assert main(["run", str(path), "--check"]) == 2
    assert "shift law" in capsys.readouterr().err


def test_the_fem_in_a_flash_run_says_in_one_line_that_it_is_isothermal(tmp_path):
    """The FEM has no flash: the plan's one flash line (run --check) says so, and the same
    note goes into attrs["flash_note"] (plan_flash's, printed by summary); meanfield-hybrid
    is computed with the flash (pipeline/flash_meanfield.py), not named."""
    from rubbercontact.cli.run import describe_plan
    from rubbercontact.pipeline.flash import plan_flash
    from rubbercontact.pipeline.setup import resolve

    cfg = rc.config.parse_config(_config(tmp_path, {"enabled": True},
                                         models=["meanfield", "meanfield-hybrid", "fem"],
                                         surface={"wavelengths": [0.125, 1.0],
                                                  "amplitudes": [0.02, 0.04]}))
    line = [x for x in describe_plan(cfg).splitlines() if x.startswith("flash")]
    assert len(line) == 1 and line[0].endswith("not yet for fem (isothermal)")
    plan = plan_flash(resolve(cfg))
    assert plan.models == ("meanfield", "meanfield-hybrid") and plan.skipped == ("fem",)
    assert plan.note == "flash temperature computed for meanfield, meanfield-hybrid only; " \
                        "not yet for fem (isothermal)"


def test_a_fixed_point_that_does_not_converge_is_a_note_and_nan_not_a_crash(tmp_path):
    # one step cannot meet 1e-3 K where the rubber heats at all (here ~0.02 K at 1 mm/s)
    ds = _run(_config(tmp_path, {"enabled": True, "max_iterations": 1},
                      loads={"pressures": [0.3]}, velocities=[1.0, 1e4]))
    note = ds.attrs["flash_note"]
    assert "did not converge" in note and "max_iterations" in note and "\n" not in note
    assert np.all(np.isnan(ds["friction_flash"].values))
    assert np.all(np.isfinite(ds["friction"].values))
