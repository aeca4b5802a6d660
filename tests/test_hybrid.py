"""Hybrid pipeline: consistency limits and the law table's contract."""

import numpy as np
import pytest
import xarray as xr

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.hybrid.law import (
    LawWarning,
    assemble_law,
    law_at_velocity,
    max_height,
    screen_monotone,
)


def _config(tmp_path, **over):
    cfg = {"surface": {"wavelengths": [0.125, 0.25], "amplitudes": [0.02648, 0.02939]},
           "loads": {"pressures": [0.3, 1.0]}, "velocities": [10.0], "realizations": 2,
           "seed": 3, "models": ["vhs", "hybrid"], "halfspace": {"n": 1024},
           "execution": {"workers": 1, "cache": str(tmp_path / "cache")},
           "output": {"directory": str(tmp_path / "out")}}
    cfg.update(over)
    return cfg


def test_empty_high_slope_set_hybrid_equals_vhs(tmp_path):
    # Both waves have m2 < 1: the hybrid has no law and must reproduce the VHS exactly;
    # so must the windowed hybrid (no law to read).
    ds = rc.pipeline.run(_config(tmp_path, models=["vhs", "hybrid", "hybrid-windowed"]),
                       progress=False)
    assert "law_mean_separation" not in ds
    for m in ("hybrid", "hybrid-windowed"):
        for k in ("friction", "contact_fraction", "mean_separation"):
            np.testing.assert_array_equal(ds[k].sel(model=m).values,
                                          ds[k].sel(model="vhs").values)
        assert np.all(ds["friction_hs"].sel(model=m) == 0)
    assert np.all(ds["status"].values == "ok")
    # The two realizations carry independent random phases.
    assert not np.allclose(ds["phase"].isel(realization=0), ds["phase"].isel(realization=1))


def _fake_fem_result(u, alpha, tau, p):
    # A per-test result as fem_task returns it (scalars), built by hand for the table logic.
    return xr.Dataset({"mean_separation": u, "contact_fraction": alpha, "shear_stress": tau,
                       "friction": tau / p, "wall_time": 1.0})


def _law(points, velocities=(10.0,)):
    hs = rc.roughness.high_slope_wave()
    p = np.array([pt[3] for pt in points])
    res = [_fake_fem_result(*pt) if pt[0] is not None else None
           for _ in velocities for pt in points]
    return assemble_law(res, p, np.array(velocities), hs, rc.materials.sbr(), {})


def test_law_table_anchor_and_order():
    law = _law([(0.012, 0.3, 0.2, 1.0), (0.016, 0.1, 0.02, 0.3), (0.008, 0.6, 0.9, 3.0)])
    t = law_at_velocity(law, 10.0)
    u = np.array(t["separation"])
    assert np.all(np.diff(u) > 0)
    assert np.all(np.diff(t["pressure"]) < 0)
    # Zero-load anchor: the flat rubber rests on the peak, u = Delta = 0.01867 mm, sigma = 0.
    assert u[-1] == pytest.approx(0.01867, rel=1e-9)
    assert t["pressure"][-1] == 0 and t["shear_stress"][-1] == 0
    assert max_height(rc.roughness.section3(phases=[0.3, 1.0, 2.0])) <= (
        0.01867 + 0.02648 + 0.02939)


def test_law_table_reports_failures_and_rejects_nonmonotone():
    law = _law([(0.012, 0.3, 0.2, 1.0), (None, 0, 0, 0.3), (0.008, 0.6, 0.9, 3.0)])
    with pytest.warns(LawWarning, match=r"p=\[0.3\] MPa failed"):
        law_at_velocity(law, 10.0)
    bad = _law([(0.012, 0.3, 0.2, 1.0), (0.010, 0.1, 0.02, 0.3), (0.008, 0.6, 0.9, 3.0)])
    with pytest.raises(InputError, match="does not decrease"):
        law_at_velocity(bad, 10.0)
    with pytest.raises(InputError, match=r"50.0 mm/s is not in the law table"):
        law_at_velocity(law, 50.0)
    # a point a run did not compute (its speed did not need it) is not a failure
    import warnings

    skipped = law.copy(deep=True)
    skipped["status"].values[0, 1] = "not computed"
    with warnings.catch_warnings():
        warnings.simplefilter("error", LawWarning)
        assert law_at_velocity(skipped, 10.0)["pressure"] == [3.0, 1.0, 0.0]  # the anchor


def test_law_table_flags_unsteady_points_and_keeps_them():
    hs = rc.roughness.high_slope_wave()
    res = [_fake_fem_result(0.012, 0.3, 0.2, 1.0), _fake_fem_result(0.008, 0.6, 0.9, 3.0)]
    res[0] = res[0].assign(steady=1.0, period_change=0.002, period_area_change=0.004)
    res[1] = res[1].assign(steady=0.0, period_change=0.003, period_area_change=0.07)
    with pytest.warns(LawWarning, match=r"1 of 2 FEM points did not reach steady sliding.*"
                                        r"v=10 p=3 \(μ 0.3 %, A 7.0 %\)"):
        law = assemble_law(res, np.array([1.0, 3.0]), np.array([10.0]), hs,
                           rc.materials.sbr(), {})
    assert list(law["steady"].values[0]) == [1.0, 0.0]
    assert law["period_area_change"].values[0, 1] == pytest.approx(0.07)
    assert np.all(law["status"].values == "ok")       # kept in the table
    # results cached before the diagnostics existed: NaN, no warning
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        old = _law([(0.012, 0.3, 0.2, 1.0)])
    assert np.isnan(old["steady"].values).all()


def test_screen_monotone_excludes_and_names_the_offending_points():
    # u must fall strictly as p rises. Top point crushed (u rises again at 8 MPa, as the FEM
    # does beyond E_inf): only it goes. A lone outlier in the middle: only it goes, not
    # every point above it.
    top = _law([(0.018, 0.05, 0.01, 0.1), (0.013, 0.15, 0.2, 1.0), (0.009, 0.4, 0.9, 4.0),
                (0.010, 0.5, 1.5, 8.0)])
    with pytest.warns(LawWarning, match=r"1 FEM points excluded.*v=10 mm/s: p=\[8.0\]"):
        screened = screen_monotone(top)
    assert screened["status"].values[0, 3].startswith("excluded: non-monotone")
    assert list(screened["status"].values[0, :3]) == ["ok"] * 3
    # the FEM numbers stay in the table for inspection
    assert float(screened["mean_separation"][0, 3]) == 0.010
    t = law_at_velocity(screened, 10.0)
    assert t["pressure"][:3] == [4.0, 1.0, 0.1]
    mid = _law([(0.018, 0.05, 0.01, 0.1), (0.0195, 0.1, 0.1, 0.3), (0.013, 0.15, 0.2, 1.0),
                (0.009, 0.4, 0.9, 4.0)])
    with pytest.warns(LawWarning, match=r"p=\[0.3\] MPa"):
        screened = screen_monotone(mid)
    # two speeds with exclusions: one warning naming both
    pts = [(0.018, 0.05, 0.01, 0.1), (0.013, 0.15, 0.2, 1.0), (0.009, 0.4, 0.9, 4.0),
           (0.010, 0.5, 1.5, 8.0)]
    both = _law(pts, velocities=(10.0, 50.0))
    with pytest.warns(LawWarning) as caught:
        screen_monotone(both)
    msgs = [str(w.message) for w in caught if issubclass(w.category, LawWarning)]
    assert len(msgs) == 1 and "2 FEM points" in msgs[0] and "v=50 mm/s: p=[8.0]" in msgs[0]
    assert list(screened["status"].values[0] == "ok") == [True, False, True, True]
    # a monotone table passes untouched and silently
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        same = screen_monotone(_law([(0.018, 0.05, 0.01, 0.1), (0.013, 0.15, 0.2, 1.0)]))
    assert np.all(same["status"].values == "ok")


def test_impaled_law_point_is_dropped_with_a_warning_and_kept_in_the_table():
    # An impaled face says "ok" but its friction and contact fraction are meaningless (the
    # 10 MPa steep cell: A = 1.07, mu = 1.98): the law must leave it out, say which point
    # and what to do in one line, and keep its numbers and flag in the table.
    import warnings

    from rubbercontact.hybrid.law import IMPALED_STATUS, law_top

    hs = rc.roughness.high_slope_wave()
    pts = [(0.016, 0.1, 0.02, 0.3), (0.012, 0.3, 0.2, 1.0), (0.011, 1.07, 19.8, 10.0)]
    res = [_fake_fem_result(*pt).assign(impaled=float(pt[3] == 10.0)) for pt in pts]
    with pytest.warns(LawWarning) as caught:
        law = assemble_law(res, np.array([pt[3] for pt in pts]), np.array([10.0]), hs,
                           rc.materials.sbr(), {})
    msgs = [str(w.message) for w in caught if issubclass(w.category, LawWarning)]
    assert len(msgs) == 1 and "\n" not in msgs[0]
    assert msgs[0].startswith("law: FEM point(s) p=10 MPa, v=10 mm/s dropped from the law: "
                              "the rubber face is impaled")
    assert "refine the cell (fem.mesh) or lower the load (law.pressures)" in msgs[0]
    assert list(law["status"].values[0]) == ["ok", "ok", IMPALED_STATUS]
    np.testing.assert_array_equal(law["impaled"].values[0], [0, 0, 1])
    assert float(law["contact_fraction"][0, 2]) == 1.07     # kept for inspection
    # the readers of the law skip it silently (it was named once, above)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        t = law_at_velocity(screen_monotone(law), 10.0)
    assert t["pressure"][:2] == [1.0, 0.3]
    assert law_top(law, 10.0) == 1.0


def test_law_point_cached_before_the_flag_with_contact_above_one_is_dropped():
    # A result cached before the impaled flag existed has no flag; the old count gave a
    # contact fraction above 1 only on a folded (impaled) face, and the current count
    # cannot exceed 1, so such a point is excluded too; points at or below 1 are kept.
    from rubbercontact.hybrid.law import IMPALED_STATUS

    hs = rc.roughness.high_slope_wave()
    pts = [(0.016, 0.1, 0.02, 0.3), (0.012, 1.0, 0.2, 1.0), (0.011, 1.07, 19.8, 10.0)]
    res = [_fake_fem_result(*pt) for pt in pts]
    with pytest.warns(LawWarning, match=r"p=10 MPa, v=10 mm/s dropped"):
        law = assemble_law(res, np.array([pt[3] for pt in pts]), np.array([10.0]), hs,
                           rc.materials.sbr(), {})
    assert list(law["status"].values[0]) == ["ok", "ok", IMPALED_STATUS]


def test_impaled_point_of_a_speed_path_is_dropped_and_its_flag_reaches_the_results(tmp_path):
    # The pipeline's law by continuation in speed takes the same exclusion, and the flag
    # is carried into the results (law_impaled) and back (law_from_results).
    from rubbercontact.hybrid.law import IMPALED_STATUS, law_from_results
    from rubbercontact.pipeline.assemble import add_law
    from rubbercontact.pipeline.lawstage import fem_law

    cfg = rc.config.parse_config(_config(tmp_path, velocities=[1.0, 10.0],
                                         law={"pressures": [0.3, 1.0],
                                              "speed_path": "continuation"}))
    v = [1.0, 10.0]

    def path(p):
        u = {0.3: 0.016, 1.0: 0.012}[p]
        return xr.Dataset({"mean_separation": ("velocity", [u, u]),
                           "contact_fraction": ("velocity", [0.1, 0.3]),
                           "shear_stress": ("velocity", [0.02 * p, 0.2 * p]),
                           "friction": ("velocity", [0.02, 0.2]),
                           "wall_time": ("velocity", [1.0, 1.0]),
                           "impaled": ("velocity", [0, int(p == 1.0)]),
                           "status": ("velocity", ["ok", "ok"])},
                          coords={"velocity": v})

    def runner(tasks, **kw):
        return [path(t.kwargs["mean_pressure"]) for t in tasks]

    with pytest.warns(LawWarning, match=r"p=1 MPa, v=10 mm/s dropped from the law"):
        law = fem_law(cfg, rc.roughness.high_slope_wave(), rc.materials.sbr(),
                      np.array([0.3, 1.0]), np.array(v), runner)
    assert law["status"].values.tolist() == [["ok", "ok"], ["ok", IMPALED_STATUS]]
    ds = add_law(xr.Dataset(), law)
    np.testing.assert_array_equal(ds["law_impaled"].values, [[0, 0], [0, 1]])
    back = law_from_results(ds)
    assert back["status"].values[1, 1] == IMPALED_STATUS and back["impaled"].values[1, 1] == 1


def test_elastic_high_slope_law_gives_zero_mu_hs(tmp_path):
    # Elastic rubber: no hysteresis at any scale, so the FEM law carries dtau_hs = 0 (FEM
    # symmetry gives a round-off of ~1e-9 of the load, dtau/p < 1e-8) and
    # mu_hs = <dtau_hs(u)>/sigma0 must vanish; the elastic half-space gives mu_ls = 0 up to
    # the sampling of the contact edges (~1e-5 at n = 1024).
    cfg = _config(tmp_path, surface={"preset": "section3"},
                  models=["hybrid", "hybrid-windowed"],
                  material={"preset": None, "equilibrium_modulus": 4.17},
                  realizations=1, fem={"mesh": [16, 12]},
                  law={"pressures": [0.1, 0.3, 1.0], "extend": False})
    ds = rc.pipeline.run(cfg, progress=False)
    assert np.all(ds["status"].values == "ok")
    assert np.nanmax(np.abs(ds["law_shear_stress"] / ds["law_pressure"]).values) < 1e-8
    for m in ("hybrid", "hybrid-windowed"):
        mu_hs = ds["friction_hs"].sel(model=m).values
        assert np.all(np.abs(mu_hs) < 1e-8)
        assert np.all(np.abs(ds["friction"].sel(model=m).values) < 1e-4)
        a = ds["contact_fraction"].sel(model=m).values
        assert np.all((a > 0) & (a < 1))
    # Same low-slope solve: μ_ls and ū agree exactly; only the law's reading differs.
    for k in ("friction_ls", "mean_separation", "max_local_pressure"):
        np.testing.assert_array_equal(ds[k].sel(model="hybrid").values,
                                      ds[k].sel(model="hybrid-windowed").values)


def test_small_slope_hybrid_agrees_with_vhs(tmp_path):
    # Both scales have small slope (m2 = 0.10 and 0.07, the threshold is lowered to 0.08 so
    # the short wave goes through the FEM law): both models are linear here and must agree.
    # Tolerances: the FEM matches the BEM within 5 % on one small-slope wave in partial
    # contact (test_fem), plus the hybrid's scale-separation error (wavelength ratio 4);
    # measured 2.5-3.6 % on friction and 1-3 % on area at these loads.
    cfg = _config(tmp_path, surface={"wavelengths": [0.0625, 0.25],
                                     "amplitudes": [0.0014, 0.004], "m2_threshold": 0.08},
                  loads={"pressures": [0.1, 0.2, 0.4]}, realizations=1,
                  halfspace={"n": 2048}, fem={"mesh": [32, 24]},
                  law={"pressures": [0.02, 0.05, 0.1, 0.2, 0.4, 0.8],
                       "extend": False})
    ds = rc.pipeline.run(cfg, progress=False)
    vhs, hyb = ds.sel(model="vhs"), ds.sel(model="hybrid")
    np.testing.assert_allclose(hyb["friction"], vhs["friction"], rtol=0.08)
    np.testing.assert_allclose(hyb["contact_fraction"], vhs["contact_fraction"], rtol=0.05)
    # The law carries a real share of the friction: mu_hs is a sizeable part of mu.
    assert np.all(hyb["friction_hs"].values > 0.2 * hyb["friction"].values)


def _first_sweep(cfg) -> list:
    """The tasks of the run's first sweep (a recording runner stops the run there)."""
    class Stop(Exception):
        pass

    seen = []

    def runner(tasks, description="sweep"):
        seen.extend(tasks)
        raise Stop

    with pytest.raises(Stop):
        rc.pipeline.run(cfg, runner=runner, progress=False)
    return seen


def test_full_fem_options_reach_the_fem_task(tmp_path):
    # The full-surface FEM gets its own mesh, grading and (transient) time step; the contact
    # sampling and the history order are shared with the law. One options object carries
    # them all into the task (and into its cache key).
    seen = _first_sweep(_config(
        tmp_path, models=["fem"], surface={"preset": "section3"},
        fem={"solver": "transient", "mesh": [40, 30], "full_mesh": [96, 40],
             "full_grading": 4.0, "full_steps_per_period": 48, "contact_points": 3,
             "history_order": 1, "periods": 12, "full_periods": 3}))
    assert seen[0].function.endswith(":fem_task")
    opts = rc.fem.FemOptions.from_dict(seen[0].kwargs["options"])
    assert (opts.mesh, opts.grading, opts.transient.steps_per_period, opts.contact_points,
            opts.history_order, opts.transient.periods, opts.solver) == (
        (96, 40), 4.0, 48, 3, 1, 3, "transient")
    # without full_periods the full FEM runs the law's number of periods
    seen = _first_sweep(_config(tmp_path, models=["fem"], surface={"preset": "section3"},
                                fem={"solver": "transient", "mesh": [40, 30], "periods": 5}))
    assert seen[0].kwargs["options"]["transient"]["periods"] == 5
    with pytest.raises(rc.errors.InputError, match="full_periods"):
        rc.config.parse_config(_config(tmp_path, fem={"solver": "transient",
                                                      "full_periods": 0}))


def test_the_steady_solver_is_the_default_and_rejects_transient_options(tmp_path):
    seen = _first_sweep(_config(tmp_path, models=["hybrid"], surface={"preset": "section3"},
                                fem={"mesh": [40, 30], "steady": {"coarse_elements": 0}}))
    assert seen and all(t.kwargs["options"]["solver"] == "steady" for t in seen)
    assert all(t.kwargs["options"]["steady"]["coarse_elements"] == 0 for t in seen)
    for key, value in (("periods", 5), ("steps_per_period", 64), ("min_creep_times", 5.0),
                       ("viscous_model", "reese-govindjee")):
        with pytest.raises(rc.errors.InputError, match=f"{key}.*transient|transient.*{key}"):
            rc.config.parse_config(_config(tmp_path, fem={key: value}))
    with pytest.raises(rc.errors.InputError, match="unknown key"):
        rc.config.parse_config(_config(tmp_path, fem={"steady": {"coarse": 3}}))


@pytest.mark.parametrize("field, values", [
    ("history_order", (1, 2)), ("grading", (1.0, 4.0)), ("contact_points", (2, 4))])
def test_fem_options_reach_every_task_and_its_cache_key(tmp_path, field, values):
    keys = []
    for value in values:
        for models in (["hybrid"], ["fem"]):
            fem = {"mesh": [40, 30], field: value}
            if field == "grading" and models == ["fem"]:
                fem = {"mesh": [40, 30], "full_grading": value}
            seen = _first_sweep(_config(tmp_path, models=models,
                                        surface={"preset": "section3"}, fem=fem))
            assert seen and all(t.kwargs["options"][field] == value for t in seen)
            keys.append(seen[0].key())
    assert len(set(keys)) == len(keys)       # every option value is its own cache entry
    with pytest.raises(rc.errors.InputError, match=field):
        rc.config.parse_config(_config(tmp_path, fem={field: 0}))


def test_min_creep_times_reach_every_transient_fem_task(tmp_path):
    # fem.min_creep_times k: every transient test slides at least k longest retardation
    # times of the material (SBR: 16.3 ms) before its steadiness check.
    lam = float(rc.materials.sbr().retardation_times().max())
    assert 0.015 < lam < 0.018            # measured 16.3 ms (tests/test_materials.py)
    for k, models in ((None, ["hybrid"]), (None, ["fem"]), (5.0, ["hybrid"]), (5.0, ["fem"])):
        fem = {"solver": "transient", "mesh": [40, 30]} | (
            {} if k is None else {"min_creep_times": k})
        seen = _first_sweep(_config(tmp_path, models=models, surface={"preset": "section3"},
                                    fem=fem))
        assert seen
        for t in seen:
            got = t.kwargs["options"]["transient"]["min_sliding_time"]
            assert got == (0.0 if k is None else pytest.approx(k * lam, rel=1e-12))
    for bad in (0.0, -1.0, 100.0):
        with pytest.raises(rc.errors.InputError, match="min_creep_times"):
            rc.config.parse_config(_config(tmp_path, fem={"solver": "transient",
                                                          "min_creep_times": bad}))
    # an elastic material does not creep: no minimum
    cfg = rc.config.parse_config(_config(tmp_path, fem={"solver": "transient",
                                                        "min_creep_times": 5.0}))
    elastic = rc.materials.GeneralizedMaxwell.elastic(4.0)
    assert cfg.fem.options(elastic).transient.min_sliding_time == 0.0
    assert cfg.fem.options(rc.materials.sbr()).transient.min_sliding_time == pytest.approx(
        5 * lam, rel=1e-12)


def _runner_with_stand_in_fem(diagnostics):
    """A sweep runner that runs every task but the full FEM, which it replaces by a fixed
    result with ``diagnostics(mean_pressure)`` (a dict of steadiness variables) added."""
    import importlib

    def runner(tasks, description="sweep"):
        out = []
        for t in tasks:
            if t.function.endswith(":fem_task"):
                out.append(xr.Dataset({"friction": 0.5, "contact_fraction": 0.05,
                                       "mean_separation": 0.01, "wall_time": 1.0,
                                       **diagnostics(t.kwargs["mean_pressure"])}))
            else:
                module, name = t.function.split(":")
                out.append(getattr(importlib.import_module(module), name)(**t.kwargs))
        return out

    return runner


def test_unsteady_full_fem_tests_are_flagged_in_the_results(tmp_path):
    # A full-FEM test that has not settled keeps its numbers (the last period's averages)
    # but must not pass as "ok" silently: the results say which loads, and by how much the
    # friction still moved, and the run warns in the calling process (a worker's warning
    # only reaches its log).
    runner = _runner_with_stand_in_fem(lambda p: {
        "steady": 0.0 if p == 1.0 else 1.0, "period_change": 0.034, "period_area_change": 0.05})

    cfg = rc.config.parse_config(_config(tmp_path, models=["vhs", "fem"], realizations=1))
    with pytest.warns(RuntimeWarning, match=r"1 of 2 full-FEM tests did not reach steady "
                                            r"sliding.*v=10 σ0=1 r=0 \(μ 3.4 %, A 5.0 %\)"):
        ds = rc.pipeline.run(cfg, runner=runner, progress=False)
    np.testing.assert_array_equal(ds["fem_steady"].sel(velocity=10.0, realization=0), [1, 0])
    assert float(ds["fem_period_change"].sel(velocity=10.0, realization=0, pressure=1.0)) \
        == pytest.approx(0.034)
    assert set(ds["status"].values.ravel()) == {"ok"}      # kept, not failed


def test_target_areas_are_bracketed_at_every_speed(tmp_path):
    # The pressure sweep behind target areas is shared by all speeds; at 1 mm/s the
    # rubber is ~4x softer than at 1000 mm/s, so a grid sized at one speed misses the
    # targets at the other. Every target must be reached (no NaN) at both speeds, and
    # the interpolated VHS area there equals the target (log-linear interpolation
    # along a sweep of 8 points: within 15 %).
    cfg = _config(tmp_path, velocities=[1.0, 1000.0], realizations=1, models=["vhs"],
                  loads={"contact_areas": [0.05, 0.2], "sweep_points": 8})
    ds = rc.pipeline.run(cfg, progress=False)
    mu = ds["friction_at_area"].sel(model="vhs").values
    assert np.all(np.isfinite(mu)), mu
    from rubbercontact.hybrid.metrics import interpolate_at_areas

    for iv in range(2):
        a = ds["contact_fraction"].sel(model="vhs").isel(velocity=iv, realization=0).values
        p = ds["pressure"].values
        p_at = np.exp(np.interp(np.log([0.05, 0.2]), np.log(a), np.log(p)))
        assert np.all((p_at > p.min()) & (p_at < p.max()))
        assert interpolate_at_areas(a, a, [0.05, 0.2]) == pytest.approx([0.05, 0.2], rel=0.15)


def _vhs_table(hs, mat, v, pressures):
    rows = sorted((r.mean_separation, p, r.contact_fraction, r.friction * p) for p in pressures
                  for r in [rc.halfspace.solve_sliding(hs, hs.period, mat, v, p, n=2048)])
    return {k: [r[i] for r in rows] for i, k in enumerate(
        ("separation", "pressure", "contact_fraction", "shear_stress"))}


def test_continuation_past_the_fem_table_follows_the_linear_law():
    from rubbercontact.hybrid.law import continue_with_linear_shape, tabulated_law_from_dict

    hs, mat, v = rc.roughness.high_slope_wave(), rc.materials.sbr(), 10.0
    table = _vhs_table(hs, mat, v, [0.1, 0.5, 1.0, 2.0])
    # A law equal to the VHS law is continued by the VHS law itself (anchor ratios 1):
    # the rows must be the VHS solutions at those pressures (same solver, n = 2048).
    ext = continue_with_linear_shape(table, hs, mat, v)
    added = len(ext["pressure"]) - len(table["pressure"])
    assert added >= 3 and ext["pressure"][added] == 2.0 and min(ext["pressure"][:added]) > 2.4
    direct = _vhs_table(hs, mat, v, ext["pressure"][:added])
    for k in table:
        np.testing.assert_allclose(ext[k][:added], direct[k], rtol=1e-9)
    # A law 20 % below the VHS in shear stress and 10 % in separation keeps those ratios
    # in the continuation; u stays positive and increasing, alpha <= 1, and the table
    # builds a valid law (continuous at the anchor by construction).
    scaled = {**table, "separation": [0.9 * u for u in table["separation"]],
              "shear_stress": [0.8 * t for t in table["shear_stress"]]}
    ext2 = continue_with_linear_shape(scaled, hs, mat, v)
    np.testing.assert_allclose(ext2["shear_stress"][:added], 0.8 * np.array(direct["shear_stress"]),
                               rtol=1e-9)
    np.testing.assert_allclose(ext2["separation"][:added], 0.9 * np.array(direct["separation"]),
                               rtol=1e-9)
    assert np.all(np.diff(ext2["separation"]) > 0) and ext2["separation"][0] > 0
    assert max(ext2["contact_fraction"]) <= 1.0
    law = tabulated_law_from_dict(ext2)
    assert law.pressure(np.array([ext2["separation"][0]]))[0] == pytest.approx(
        max(ext2["pressure"]), rel=1e-9)
    # an elastic rubber has no shear stress to borrow the shape of: table unchanged
    elastic = rc.materials.GeneralizedMaxwell(4.17, [], [])
    assert continue_with_linear_shape(table, hs, elastic, v) == table


def test_linear_law_hybrid_reproduces_the_vhs_when_scales_separate():
    # With the VHS law of the high-slope wave as its law, the hybrid's only approximation
    # is the scale split. For a low-slope wave 16 times longer than the 0.0625 mm wave the
    # split must vanish: measured <= 1 % in friction and area (benchmarks/
    # scale_separation.py; at a ratio of 2 it is +10 to +42 %). 3 % allows for the two
    # discretizations (n = 4096 on each period) and the law's interpolation.
    from rubbercontact.hybrid.law import linear_law
    from rubbercontact.hybrid.tasks import halfspace_task

    mat, v = rc.materials.sbr(), 10.0
    hs = rc.roughness.SineSeries([0.0625], [0.01867])
    lam = 1.0
    amp = 0.3 * np.sqrt(2) * lam / (2 * np.pi)            # m2 = 0.3
    ls = rc.roughness.SineSeries([lam], [amp], [0.7])
    full = rc.roughness.SineSeries([0.0625, lam], [0.01867, amp], [2.1, 0.7])
    table = linear_law(hs, mat, v)
    for p in (0.15, 0.35):
        vhs = rc.halfspace.solve_sliding(full, lam, mat, v, p, n=4096)
        hyb = halfspace_task(ls.as_dict(), lam, mat.as_dict(), v, p, n=4096,
                             interface_law=table)
        assert float(hyb["friction"]) == pytest.approx(vhs.friction, rel=0.03)
        assert float(hyb["contact_fraction"]) == pytest.approx(vhs.contact_fraction, rel=0.03)


def test_tests_that_slid_less_than_three_retardation_times_are_named(tmp_path):
    # The period rule can pass while the bulk still creeps on the longest retardation time
    # (SBR: 16.3 ms), so a law whose FEM tests slid less than 3 of those says so, naming
    # the shortest; static (0 s) and unrecorded (NaN) tests are not counted.
    from rubbercontact.hybrid.law import assemble_law, creep_unsettled_message

    mat = rc.materials.sbr()
    lam = float(mat.retardation_times().max())
    diag = {"sliding_time": np.array([[0.2 * lam, 3.5 * lam, np.nan, 0.0, 2.9 * lam]])}
    msg = creep_unsettled_message(diag, mat, lambda i, j: f"p{j}", "law")
    assert msg.startswith("law: 2 of 4 time-stepped FEM tests")
    assert "first: p0 (3.3 ms), p4 (" in msg
    assert creep_unsettled_message(diag, rc.materials.GeneralizedMaxwell.elastic(4.0),
                                   lambda i, j: "", "law") is None
    assert creep_unsettled_message({"sliding_time": np.array([4 * lam])}, mat,
                                   lambda i: "", "law") is None

    def res(t):
        return xr.Dataset({"mean_separation": 0.01, "contact_fraction": 0.1,
                           "shear_stress": 0.05, "friction": 0.5, "wall_time": 1.0,
                           "steady": 1.0, "period_change": 0.0, "period_area_change": 0.0,
                           "sliding_time": t})

    hs = rc.roughness.high_slope_wave()
    with pytest.warns(rc.hybrid.LawWarning, match=r"law: 1 of 2 time-stepped FEM tests .*slid "
                                                  r"less than 3 retardation times \(16.3 ms\)"
                                                  r".*v=50 p=1"):
        law = assemble_law([res(10 * lam), res(0.5 * lam)], [0.5, 1.0], [50.0], hs, mat, {})
    assert law["sliding_time"].attrs["units"] == "s"


def test_cells_in_bulk_shear_are_named_in_the_law_and_the_results(tmp_path):
    # Above a mean shear of 1 the FEM result depends on the cell height
    # (docs/validation/cell_height.md); the run must say which tests got there, largest
    # first, in the calling process, and keep the values. Unrecorded (NaN) are not counted.
    from rubbercontact.hybrid.law import sheared_cells_message

    diag = {"bulk_shear": np.array([[0.4, 1.3, np.nan, 2.1]])}
    msg = sheared_cells_message(diag, lambda i, j: f"p{j}", "law")
    assert msg.startswith("law: 2 of 3 FEM tests sheared as a whole by more than 1 ")
    assert "largest first: p3 (2.10), p1 (1.30):" in msg
    assert sheared_cells_message({"bulk_shear": np.array([0.99, np.nan])},
                                 lambda i: "", "law") is None
    assert sheared_cells_message({}, lambda i: "", "law") is None     # old cache entries

    runner = _runner_with_stand_in_fem(lambda p: {"steady": 1.0,
                                                  "bulk_shear": 1.4 if p == 1.0 else 0.3})

    cfg = rc.config.parse_config(_config(tmp_path, models=["vhs", "fem"], realizations=1))
    with pytest.warns(RuntimeWarning, match=r"full FEM: 1 of 2 FEM tests sheared as a whole "
                                            r"by more than 1 .*v=10 σ0=1 r=0 \(1.40\)"):
        ds = rc.pipeline.run(cfg, runner=runner, progress=False)
    np.testing.assert_allclose(ds["fem_bulk_shear"].sel(velocity=10.0, realization=0),
                               [0.3, 1.4])
    assert set(ds["status"].values.ravel()) == {"ok"}      # kept, not failed


def test_friction_at_area_uses_only_loads_whose_area_grows(tmp_path):
    # A full FEM whose area stops growing with the load (settled at 50 mm/s above ~1 MPa
    # the cell shears beyond 1 and its contact shrinks): interpolating μ at a target area
    # across the fold would mix two branches. Stand-in FEM: area rises with the load up to
    # the third-highest load and falls above it, μ = 0.5 on the rising branch and 0.9 on
    # the falling one; the friction at every reachable target must be exactly 0.5, the
    # targets beyond the peak NaN, and the run must name the loads left out.
    import importlib

    def runner(tasks, description="sweep"):
        fem_p = sorted({t.kwargs["mean_pressure"] for t in tasks
                        if t.function.endswith(":fem_task")})
        out = []
        for t in tasks:
            if t.function.endswith(":fem_task"):
                k = fem_p.index(t.kwargs["mean_pressure"])
                peak = len(fem_p) - 3
                rising = k <= peak
                area = 0.01 + 0.2 * k / peak if rising else 0.1 - 0.01 * (k - peak)
                out.append(xr.Dataset({"friction": 0.5 if rising else 0.9,
                                       "contact_fraction": area, "mean_separation": 0.01,
                                       "wall_time": 1.0, "steady": 1.0}))
            else:
                module, name = t.function.split(":")
                out.append(getattr(importlib.import_module(module), name)(**t.kwargs))
        return out

    cfg = rc.config.parse_config(_config(
        tmp_path, models=["vhs", "fem"], realizations=1,
        loads={"contact_areas": [0.05, 0.15, 0.3], "sweep_points": 8}))
    with pytest.warns(RuntimeWarning, match=r"friction at contact area: 1 load sweep has .*"
                                            r"left out.*fem v=10 r=0: σ0="):
        ds = rc.pipeline.run(cfg, runner=runner, progress=False)
    mu = ds["friction_at_area"].sel(model="fem", realization=0).values
    np.testing.assert_array_equal(mu[:, :2], 0.5)
    assert np.all(np.isnan(mu[:, 2]))


def test_fem_task_records_what_it_would_warn_and_the_law_says_it_once():
    # The paper's high-slope wave at 3 MPa on 16 x 8: the friction stress exceeds E∞/3 and
    # the cell shears as a whole by more than 1 (3μp̄/E∞ with μ ≈ 0.5: about 1.1). The
    # library's test warns; the pipeline's task records the shear instead, and the law
    # built from such tests says it once (assemble_law).
    import warnings

    from rubbercontact.hybrid.law import assemble_law
    from rubbercontact.hybrid.tasks import fem_task

    surf, mat = rc.roughness.high_slope_wave(), rc.materials.sbr()
    with pytest.warns(RuntimeWarning, match="sheared as a whole"):
        rc.fem.steady_sliding(surf, mat, 3.0, 10.0, mesh=(16, 8))
    with warnings.catch_warnings():
        warnings.simplefilter("error")           # any warning out of the task fails
        out = fem_task(surf.as_dict(), mat.as_dict(), 10.0, 3.0, options={"mesh": [16, 8]})
    assert float(out["bulk_shear"]) > 1.0
    with pytest.warns(LawWarning, match=r"1 of 1 FEM tests sheared as a whole"):
        assemble_law([out], [3.0], [10.0], surf, mat, {"mesh": [16, 8]})


def test_fem_task_records_its_sliding_time():
    # Transient: 2 periods of the 0.0625 mm cell at 10 mm/s: 12.5 ms (an elastic cell is
    # steady after the minimum of 2 periods). Steady: settled by construction (inf).
    from rubbercontact.hybrid.tasks import fem_task

    surf = rc.roughness.SineSeries([0.0625], [0.003])
    mat = rc.materials.GeneralizedMaxwell.elastic(4.17).as_dict()
    opts = rc.fem.make_options(mesh=(16, 8), solver="transient", periods=2,
                               steps_per_period=8)
    out = fem_task(surf.as_dict(), mat, 10.0, 0.3, options=opts.to_dict())
    assert float(out["sliding_time"]) == pytest.approx(2 * 0.0625 / 10.0, rel=1e-12)
    assert out["sliding_time"].attrs["units"] == "s" and out.attrs["solver"] == "transient"
    out = fem_task(surf.as_dict(), mat, 10.0, 0.3, options={"mesh": [16, 8]})
    assert np.isinf(float(out["sliding_time"])) and out.attrs["solver"] == "steady"
    assert float(out["impaled"]) == 0          # the flag the law screens on (screen_impaled)


def _law_run_config(tmp_path, name, **over):
    # The paper's high-slope wave alone on a coarse cell: a cheap viscoelastic law.
    cfg = _config(tmp_path, surface={"preset": "high_slope_wave"}, models=["hybrid"],
                  realizations=1, loads={"pressures": [0.3, 1.0]},
                  fem={"mesh": [30, 23]}, law={"pressures": [0.3, 1.0], "extend": False},
                  execution={"workers": 1, "cache": str(tmp_path / f"cache-{name}")})
    cfg.update(over)
    return cfg


def _recording_runner(cfg, seen):
    from rubbercontact.pipeline import make_runner

    inner = make_runner(rc.config.parse_config(cfg), progress=False)

    def runner(tasks, **kw):
        seen.extend(tasks)
        return inner(tasks, **kw)
    return runner


def test_saved_law_is_reused_without_fem_on_a_surface_sharing_its_high_slope_wave(tmp_path):
    from rubbercontact.hybrid.law import law_from_results
    from rubbercontact.io.results import read_law, write_law, write_results

    built = rc.pipeline.run(_law_run_config(tmp_path, "built"), progress=False)
    # the law cell checked its quasi-static limit at each of its pressures: a lone sine is
    # symmetric, so its relaxed friction vanishes on any mesh (within the check's tolerance)
    qs = built["law_quasi_static_friction"]
    assert qs["law_pressure"].values.tolist() == [0.3, 1.0]
    assert np.all(np.abs(qs.values) <= qs.attrs["tolerance"])
    assert built.attrs["law_quasi_static"].endswith("2 of 2 law pressures pass")
    law_nc = write_law(law_from_results(built), tmp_path / "law.nc")
    results_nc = write_results(built, tmp_path / "results.nc")
    # The file round trip keeps the table and its provenance.
    law = read_law(law_nc)
    np.testing.assert_array_equal(law["mean_separation"], built["law_mean_separation"])
    assert float(law.attrs["hs_max_height_mm"]) > 0 and "fem_options" in law.attrs

    # Reused from either file (fresh caches, so nothing comes from a cache): no FEM task
    # runs and the hybrid is bit-identical, since it reads the same table.
    for name, path in (("law", law_nc), ("results", results_nc)):
        cfg = _law_run_config(tmp_path, name, law={"file": str(path)})
        seen = []
        ds = rc.pipeline.run(cfg, runner=_recording_runner(cfg, seen), progress=False)
        assert seen and not [t for t in seen if t.function.endswith(":fem_task")]
        for k in ("friction", "contact_fraction", "mean_separation"):
            np.testing.assert_array_equal(ds[k].values, built[k].values)
        assert "law_quasi_static" not in ds.attrs      # no FEM, nothing checked

    # The section 3 surface carries the same high-slope wave (plus two low-slope ones in
    # random phase): the law applies to it as it is.
    cfg = _law_run_config(tmp_path, "s3", surface={"preset": "section3"},
                          models=["hybrid", "hybrid-windowed"], law={"file": str(law_nc)})
    seen = []
    ds = rc.pipeline.run(cfg, runner=_recording_runner(cfg, seen), progress=False)
    assert not [t for t in seen if t.function.endswith(":fem_task")]
    assert np.all(ds["status"].values == "ok")


@pytest.mark.parametrize("over, message", [
    ({"material": {"preset": None, "equilibrium_modulus": 4.17}}, "rubber"),
    ({"velocities": [10.0, 50.0]}, r"no FEM points at \[50.0\] mm/s"),
    ({"surface": {"wavelengths": [0.0625], "amplitudes": [0.02]}}, "high-slope waves"),
])
def test_reused_law_built_for_another_wave_rubber_or_speed_is_rejected(tmp_path, over, message):
    from rubbercontact.hybrid.law import law_from_results
    from rubbercontact.io.results import write_law

    built = rc.pipeline.run(_law_run_config(tmp_path, "built"), progress=False)
    law_nc = write_law(law_from_results(built), tmp_path / "law.nc")
    seen = []
    cfg = _law_run_config(tmp_path, "other", law={"file": str(law_nc)}, **over)
    with pytest.raises(InputError, match=message):
        rc.pipeline.run(cfg, runner=_recording_runner(cfg, seen), progress=False)
    assert not seen     # rejected before any solve


def test_a_file_without_a_law_is_rejected_with_what_it_lacks(tmp_path):
    from rubbercontact.io.results import read_law, write_results

    vhs = rc.pipeline.run(_law_run_config(tmp_path, "vhs", models=["vhs"]), progress=False)
    write_results(vhs, tmp_path / "vhs.nc")
    with pytest.raises(InputError, match="carries no law"):
        read_law(tmp_path / "vhs.nc")
    xr.Dataset({"mean_separation": ("x", [1.0])}).to_netcdf(tmp_path / "other.nc")
    with pytest.raises(InputError, match="not a law table"):
        read_law(tmp_path / "other.nc")


def test_the_linear_law_as_a_table_is_the_linear_law_at_its_pressures():
    # linear_law_table (a run's law.nc layout) and linear_law (the table dict the hybrid
    # reads) are two readings of the same VHS solves: at linear_law's own pressures below
    # full contact they agree to round-off, and the zero-load anchor is the wave's height.
    from rubbercontact.hybrid.linearlaw import linear_law, linear_law_table

    hs, mat = rc.roughness.high_slope_wave(), rc.materials.sbr()
    ref = linear_law(hs, mat, 10.0, n=256, points=12)
    p = np.asarray(ref["pressure"][:-1])[:4]            # the anchor (p = 0) last
    law = linear_law_table(hs, mat, [10.0], p, n=256).isel(velocity=0)
    np.testing.assert_allclose(law["mean_separation"], ref["separation"][:4], rtol=1e-12)
    np.testing.assert_allclose(law["shear_stress"], ref["shear_stress"][:4], rtol=1e-12)
    assert np.all(law["status"] == "ok")
    assert law.attrs["hs_max_height_mm"] == ref["separation"][-1]
