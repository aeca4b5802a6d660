"""Speed and temperature sweeps of the run pipeline, adhesion and the mean-field models.

Each test compares the pipeline against something it did not produce: a material whose
relaxation times were shifted by hand (time–temperature superposition), the closed form of
full contact, the formula of the adhesive term, the points of a speed path solved one by
one.
"""

import json

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.cli import main
from rubbercontact.errors import InputError

WLF = {"law": "WLF", "c1": 8.86, "c2": 101.6}
#: Newton/contact tolerances of the solvers: two runs of the same reduced problem in
#: different variables (τ a_T at v, or τ at a_T v) agree to this [relative].
SOLVER_RTOL = 1e-6


def _config(tmp_path, **over):
    cfg = {"surface": {"wavelengths": [0.125, 0.25], "amplitudes": [0.02648, 0.02939]},
           "material": {"preset": "sbr", "reference_temperature": 20.0, "shift": WLF},
           "loads": {"pressures": [0.3, 1.0]}, "velocities": [10.0], "realizations": 2,
           "seed": 3, "models": ["vhs"], "halfspace": {"n": 1024},
           "execution": {"workers": 1, "cache": str(tmp_path / "cache")},
           "output": {"directory": str(tmp_path / "out")}}
    cfg.update(over)
    return cfg


def _shifted_material(temperature: float) -> dict:
    """The SBR at ``temperature`` as an inline table: relaxation times × a_T, by hand."""
    a_t = 10 ** (-WLF["c1"] * (temperature - 20.0) / (WLF["c2"] + temperature - 20.0))
    m = rc.materials.sbr()
    return {"equilibrium_modulus": m.equilibrium_modulus, "moduli": m.moduli.tolist(),
            "relaxation_times": (m.relaxation_times * a_t).tolist()}


def test_a_log_range_of_speeds_is_log_spaced_with_exact_endpoints(tmp_path):
    cfg = rc.config.parse_config(_config(tmp_path, velocities={"from": 1e-3, "to": 1e4,
                                                               "points": 15}))
    v = np.asarray(cfg.velocities)
    assert v.size == 15 and v[0] == 1e-3 and v[-1] == 1e4
    np.testing.assert_allclose(np.diff(np.log10(v)), 0.5, rtol=1e-12)
    for bad, match in (({"from": 10.0, "to": 1.0, "points": 5}, "0 < from < to"),
                       ({"from": 1.0, "to": 10.0}, "missing"),
                       ({"from": 1.0, "to": 10.0, "points": 1}, "points"),
                       ({"from": 1.0, "too": 10.0, "points": 3}, "did you mean 'to'")):
        with pytest.raises(InputError, match=match):
            rc.config.parse_config(_config(tmp_path, velocities=bad))


@pytest.mark.parametrize("temperature", [0.0, 35.0])
def test_vhs_at_a_temperature_is_the_hand_shifted_material_at_the_same_speed(tmp_path,
                                                                             temperature):
    # TTS: at T the relaxation times are a_T τ_i; the run computes the reduced speed a_T v at
    # T_ref instead. Both are the same linear problem, so they agree to the solver tolerance.
    speeds = [1.0, 30.0]
    ds = rc.pipeline.run(_config(tmp_path / "t", velocities=speeds,
                                 temperatures=[20.0, temperature]), progress=False)
    ref = rc.pipeline.run(_config(tmp_path / "r", velocities=speeds,
                                  material=_shifted_material(temperature)), progress=False)
    assert ds["friction"].dims[:3] == ("model", "temperature", "velocity")
    at_t = ds.sel(temperature=temperature)
    for k in ("friction", "contact_fraction", "mean_separation"):
        np.testing.assert_allclose(at_t[k].values, ref[k].values, rtol=SOLVER_RTOL)
    # the reference temperature is the isothermal run of the unshifted material, exactly
    iso = rc.pipeline.run(_config(tmp_path / "i", velocities=speeds,
                                  material={"preset": "sbr"}), progress=False)
    np.testing.assert_array_equal(ds["friction"].sel(temperature=20.0).values,
                                  iso["friction"].values)
    a_t = float(ds["shift_factor"].sel(temperature=temperature))
    np.testing.assert_allclose(ds["reduced_velocity"].sel(temperature=temperature),
                               a_t * np.asarray(speeds), rtol=1e-14)


def test_hybrid_at_a_temperature_is_the_hand_shifted_material_at_the_same_speed(tmp_path):
    # The same identity through the FEM law (steady solver) and the hybrid solve.
    over = {"surface": {"preset": "section3"}, "models": ["hybrid"], "realizations": 1,
            "loads": {"pressures": [0.3]}, "fem": {"mesh": [40, 30]},
            "law": {"pressures": [0.2, 0.6, 2.0], "extend": False}}
    ds = rc.pipeline.run(_config(tmp_path / "t", temperatures=[20.0, 30.0], **over),
                         progress=False)
    ref = rc.pipeline.run(_config(tmp_path / "r", **{**over, "material": _shifted_material(30.0)}),
                          progress=False)
    at_t = ds.sel(temperature=30.0)
    assert float(at_t["friction_hs"].max()) > 0.01          # the law really contributes
    for k in ("friction", "friction_hs", "contact_fraction"):
        np.testing.assert_allclose(at_t[k].values, ref[k].values, rtol=SOLVER_RTOL)


def test_temperatures_need_a_shift_law(tmp_path):
    with pytest.raises(InputError, match="no time-temperature shift law"):
        rc.pipeline.run(_config(tmp_path, material={"preset": "sbr"}, temperatures=[20.0, 40.0]),
                        progress=False)


def test_adhesion_is_tau_times_area_over_pressure_at_the_reduced_speed(tmp_path):
    tau0, v0, c = 0.4, 3.0, 1.5
    speeds = [0.3, 3.0, 30.0]
    ds = rc.pipeline.run(_config(tmp_path, velocities=speeds, temperatures=[20.0, 10.0],
                                 friction={"adhesion": {"law": "gaussian", "shear_strength": tau0,
                                                        "peak_velocity": v0, "width": c}}),
                         progress=False)
    a_t = ds["shift_factor"].values[:, None] * np.asarray(speeds)[None, :]
    tau = tau0 * np.exp(-np.log10(a_t / v0) ** 2 / (2 * c**2))        # by hand, (T, v)
    expected = (ds["contact_fraction"] / ds["pressure"]
                * ds["reduced_velocity"].copy(data=tau))
    np.testing.assert_allclose(ds["friction_adhesion"].values,
                               expected.transpose(*ds["friction_adhesion"].dims).values,
                               rtol=1e-12)
    np.testing.assert_allclose(ds["friction_total"], ds["friction"] + ds["friction_adhesion"],
                               rtol=1e-14)
    # at T_ref the gaussian peaks at v0: tau_f = tau0 there
    at_ref = ds.sel(temperature=20.0, velocity=v0)
    np.testing.assert_allclose(at_ref["friction_adhesion"],
                               tau0 * at_ref["contact_fraction"] / at_ref["pressure"], rtol=1e-12)
    assert json.loads(ds.attrs["adhesion"])["law"] == "gaussian"


def test_adhesion_parameters_are_checked(tmp_path):
    with pytest.raises(InputError, match="peak_velocity"):
        rc.config.parse_config(_config(tmp_path, friction={"adhesion": {
            "law": "gaussian", "shear_strength": 0.4}}))


def test_full_contact_friction_of_vhs_and_meanfield_is_the_closed_form(tmp_path, closed_forms):
    # In full contact the linear problem superposes: μ = Σ q²Δ² Im E_r(qv)/(4σ0) (plane
    # strain). The BEM represents the sines exactly; the mean-field theory was derived
    # from this limit, and at 200 MPa its P(q) differs from 1 by < 1e-6.
    sbr = rc.materials.sbr()
    p, v = 200.0, 10.0
    ds = rc.pipeline.run(_config(tmp_path, loads={"pressures": [p]}, velocities=[v],
                                 models=["vhs", "meanfield"], material={"preset": "sbr"}),
                         progress=False)
    exact = sum(closed_forms.full_contact_friction(sbr, lam, amp, v, p)
                for lam, amp in ((0.125, 0.02648), (0.25, 0.02939)))
    for m in ("vhs", "meanfield"):
        sel = ds.sel(model=m)
        np.testing.assert_allclose(sel["contact_fraction"], 1.0, atol=1e-6)
        np.testing.assert_allclose(sel["friction"], exact, rtol=1e-4)


def test_friction_vanishes_at_both_ends_of_the_speed_range(tmp_path):
    # E(ω) is real as ω → 0 (E∞) and ω → ∞ (glassy): no hysteresis at either end.
    ds = rc.pipeline.run(_config(tmp_path, velocities=[1e-9, 10.0, 1e12],
                                 models=["vhs", "meanfield"], material={"preset": "sbr"}),
                         progress=False)
    mu = ds["friction"].mean("realization")
    for m in ("vhs", "meanfield"):
        ends = mu.sel(model=m).isel(velocity=[0, 2])
        assert float(ends.max()) < 1e-3 * float(mu.sel(model=m, velocity=10.0).min())


def test_the_law_by_continuation_in_speed_equals_the_points_solved_one_by_one(tmp_path):
    over = {"surface": {"preset": "section3"}, "models": ["hybrid"], "realizations": 1,
            "loads": {"pressures": [0.3]}, "velocities": [3.0, 10.0, 30.0],
            "fem": {"mesh": [40, 30]}, "material": {"preset": "sbr"}}
    path = rc.pipeline.run(_config(tmp_path / "c", law={"pressures": [0.2, 0.6], "extend": False,
                                                        "speed_path": "continuation"},
                                   **over),
                           progress=False)
    points = rc.pipeline.run(_config(tmp_path / "p", law={"pressures": [0.2, 0.6],
                                                          "extend": False,
                                                          "speed_path": "points"}, **over),
                             progress=False)
    for k in ("law_friction", "law_contact_fraction", "law_mean_separation"):
        np.testing.assert_allclose(path[k].values, points[k].values, rtol=SOLVER_RTOL)


def test_cli_summary_prints_the_curve_and_its_peak(tmp_path, capsys):
    cfg = _config(tmp_path, velocities={"from": 0.1, "to": 1000.0, "points": 9},
                  material={"preset": "sbr"})
    ds = rc.pipeline.run(cfg, progress=False)
    path = tmp_path / "results.nc"
    rc.io.results.write_results(ds, path)
    assert main(["summary", str(path)]) == 0
    assert "peak of vhs" in capsys.readouterr().out
    peak = rc.pipeline.friction_peak(ds["velocity"].values,
                                     ds["friction"].sel(model="vhs", pressure=0.3)
                                     .mean("realization").values)
    assert peak is not None and peak.interior and 0.1 < peak.velocity < 1000.0


def test_cli_rejects_a_bad_speed_range_in_one_line(tmp_path, capsys):
    toml = tmp_path / "bad.toml"
    toml.write_text('velocities = {from = 10.0, to = 1.0, points = 5}\nmodels = ["vhs"]\n'
                    "[surface]\npreset = 'section3'\n[loads]\npressures = [0.3]\n")
    assert main(["run", str(toml), "--check"]) == 2
    err = capsys.readouterr().err
    assert "0 < from < to" in err and len(err.strip().splitlines()) == 1


def test_cli_check_prints_the_plan_and_runs_nothing(tmp_path, capsys):
    toml = tmp_path / "sweep.toml"
    toml.write_text("velocities = {from = 1.0, to = 100.0, points = 5}\n"
                    "temperatures = [0.0, 20.0, 40.0]\nmodels = ['vhs', 'hybrid']\n"
                    f"[execution]\ncache = '{tmp_path / 'cache'}'\n"
                    "[surface]\npreset = 'section3'\n[loads]\npressures = [0.3]\n"
                    "[material]\npreset = 'sbr'\nreference_temperature = 20.0\n"
                    "[material.shift]\nlaw = 'WLF'\nc1 = 8.86\nc2 = 101.6\n")
    assert main(["run", str(toml), "--check"]) == 0
    assert "15 distinct reduced speeds" in capsys.readouterr().out
    assert not (tmp_path / "cache").exists()


def test_speed_and_temperature_figures_are_drawn(tmp_path):
    ds = rc.pipeline.run(_config(tmp_path, velocities={"from": 0.1, "to": 100.0, "points": 4},
                                 temperatures=[0.0, 20.0]), progress=False)
    from rubbercontact.plotting.figures import plot_all

    written = {p.name for p in plot_all(ds, tmp_path / "fig") if p}
    assert {"friction_vs_speed.png", "contact_vs_speed.png",
            "friction_vs_temperature.png"} <= written
    assert all((tmp_path / "fig" / n).stat().st_size > 10_000 for n in written)


def test_a_law_mesh_too_coarse_is_named_before_any_task_runs(tmp_path, capsys):
    # section 3's law cell is one 0.0625 mm wave: 4 columns cannot mesh it. The run must
    # say so, naming the config key, before it computes (or caches) anything.
    cfg = _config(tmp_path, surface={"preset": "section3"}, models=["hybrid"],
                  material={"preset": "sbr"}, fem={"mesh": [4, 4]})
    with pytest.raises(InputError, match=r"fem\.mesh: the law cell.*elements per shortest"):
        rc.pipeline.run(cfg, progress=False)
    assert not (tmp_path / "cache").exists()
