"""``fem.realizations``: the full FEM on a subset, its phase average by control variate.

The FEM is replaced by a stand-in that returns the VHS result of the same realization and
load plus a known offset. For such a model the control-variate estimate
``mean_N(VHS) + mean_R(FEM − VHS)`` is *exactly* the stand-in's mean over all N
realizations, so the plumbing (which realizations run, which pair, what eq. 28 compares)
is checked to rounding error.
"""

import importlib
import re

import numpy as np
import pytest
import xarray as xr

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.hybrid.metrics import mean_relative_error
from rubbercontact.plotting.figures import plot_all, summary_table

OFFSET = {"friction": 0.05, "contact_fraction": 0.002, "mean_separation": -0.001}
LABEL = re.compile(r"^(\S+) v=(\S+) r=(\d+) p=(\S+)$")
HS_LABEL = re.compile(r"^(\S+) v=(\S+) r=(\d+)$")    # a half-space task: every load


def _config(tmp_path, **over):
    cfg = {"surface": {"wavelengths": [0.125, 0.25], "amplitudes": [0.02648, 0.02939]},
           "loads": {"pressures": [0.3, 1.0]}, "velocities": [10.0], "realizations": 6,
           "seed": 3, "models": ["vhs", "fem"], "halfspace": {"n": 1024},
           "fem": {"realizations": 2},
           "execution": {"workers": 1, "cache": str(tmp_path / "cache")},
           "output": {"directory": str(tmp_path / "out")}}
    cfg.update(over)
    return rc.config.parse_config(cfg)


def _offset_fem_runner(fail=None):
    """Runs the half-space tasks; answers each FEM task with its VHS twin + OFFSET.

    ``fail``: ``(r, p)`` of one FEM test that fails instead.
    """
    seen = []

    def runner(tasks, description="sweep"):
        seen.extend(tasks)
        out, vhs = [None] * len(tasks), {}
        for i, t in enumerate(tasks):
            if t.function.endswith(":fem_task"):
                continue
            module, name = t.function.split(":")
            out[i] = getattr(importlib.import_module(module), name)(**t.kwargs)
            m, v, r = HS_LABEL.match(t.label).groups()
            if m == "vhs":
                for p in out[i]["pressure"].values:
                    vhs[(v, r, f"{p:.4g}")] = out[i].sel(pressure=p)
        for i, t in enumerate(tasks):
            if t.function.endswith(":fem_task"):
                _, v, r, p = LABEL.match(t.label).groups()
                if fail is not None and (int(r), float(p)) == fail:
                    out[i] = "FEM did not converge (stand-in)"
                    continue
                twin = vhs[(v, r, p)]
                out[i] = xr.Dataset({k: float(twin[k]) + OFFSET.get(k, 0.0)
                                     for k in ("friction", "contact_fraction",
                                               "mean_separation", "wall_time")}
                                    | {"steady": 1.0})
        return out

    return runner, seen


def test_fem_runs_on_the_first_r_realizations_only(tmp_path):
    runner, seen = _offset_fem_runner()
    ds = rc.pipeline.run(_config(tmp_path), runner=runner, progress=False)
    fem_labels = [t.label for t in seen if t.function.endswith(":fem_task")]
    assert sorted(int(LABEL.match(x).group(3)) for x in fem_labels) == [0, 0, 1, 1]
    vhs_tasks = [t for t in seen if t.label.startswith("vhs ")]
    assert len(vhs_tasks) == 6      # one per realization, over both loads
    status = ds["status"].sel(model="fem")
    assert set(status.isel(realization=slice(0, 2)).values.ravel()) == {"ok"}
    assert set(status.isel(realization=slice(2, None)).values.ravel()) == {
        "not run (fem.realizations = 2)"}
    assert np.isnan(ds["friction"].sel(model="fem").isel(realization=slice(2, None))).all()
    assert ds.attrs["fem_realizations"] == 2


def test_phase_mean_of_an_offset_fem_is_its_mean_over_all_realizations(tmp_path):
    runner, _ = _offset_fem_runner()
    ds = rc.pipeline.run(_config(tmp_path), runner=runner, progress=False)
    for k, off in OFFSET.items():
        vhs = ds[k].sel(model="vhs")
        # what the stand-in would give on all 6 realizations, had it run there
        want = (vhs + off).mean("realization")
        got = ds[f"{k}_phase_mean"].sel(model="fem")
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-15)
        # the plain mean is still the FEM's own (first 2 realizations)
        np.testing.assert_allclose(ds[f"{k}_mean"].sel(model="fem"),
                                   (vhs + off).isel(realization=slice(0, 2)).mean("realization"),
                                   rtol=1e-12, atol=1e-15)
        # cheap models: the plain mean over all realizations
        np.testing.assert_allclose(ds[f"{k}_phase_mean"].sel(model="vhs"),
                                   vhs.mean("realization"), rtol=1e-12)
        # FEM − VHS is constant: the standard error is the VHS's alone, sd/sqrt(N)
        np.testing.assert_allclose(ds[f"{k}_phase_se"], vhs.std("realization", ddof=1)
                                   / np.sqrt(6), rtol=1e-9, atol=1e-15)


def test_eq28_compares_against_the_phase_mean(tmp_path):
    runner, _ = _offset_fem_runner()
    ds = rc.pipeline.run(_config(tmp_path), runner=runner, progress=False)
    vhs = ds["friction"].sel(model="vhs").mean("realization").values.ravel()
    want = mean_relative_error(vhs + OFFSET["friction"], vhs)
    got = float(ds["error_vs_fem"].sel(compared_model="vhs", velocity=10.0))
    assert got == pytest.approx(want, rel=1e-12)
    assert ds["error_vs_fem"].attrs["fem_reference"].startswith("phase average")
    table = summary_table(ds)
    assert "fem ran on 2 of 6 realizations" in table
    assert f"{100 * want:.1f} %" in table
    figures = plot_all(ds, tmp_path / "figs")
    assert any(f.name.startswith("fig5") for f in figures)


def test_target_areas_use_the_phase_mean_too(tmp_path):
    runner, _ = _offset_fem_runner()
    cfg = _config(tmp_path, loads={"contact_areas": [0.03, 0.05]})
    ds = rc.pipeline.run(cfg, runner=runner, progress=False)
    assert "friction_at_area_phase_mean" in ds
    fem = ds["friction_at_area_phase_mean"].sel(model="fem")
    assert np.isfinite(fem).all()
    assert ds["error_vs_fem"].attrs["compared_over"] == "contact_area"


def test_a_failed_fem_test_is_left_out_at_its_load_only(tmp_path):
    runner, _ = _offset_fem_runner(fail=(0, 1.0))
    with pytest.warns(RuntimeWarning, match="1 of 16 solves failed"):
        ds = rc.pipeline.run(_config(tmp_path), runner=runner, progress=False)
    vhs = ds["friction"].sel(model="vhs")
    # still exact: realization 1 alone carries the offset at 1 MPa
    np.testing.assert_allclose(ds["friction_phase_mean"].sel(model="fem"),
                               (vhs + OFFSET["friction"]).mean("realization"), rtol=1e-12)
    se = ds["friction_phase_se"].sel(velocity=10.0)
    assert np.isfinite(se.sel(pressure=0.3)) and np.isnan(se.sel(pressure=1.0))  # R = 1


def test_all_realizations_keep_the_plain_comparison(tmp_path):
    runner, seen = _offset_fem_runner()
    ds = rc.pipeline.run(_config(tmp_path, realizations=2), runner=runner, progress=False)
    assert "friction_phase_mean" not in ds and "fem_realizations" not in ds.attrs
    assert ds["error_vs_fem"].attrs["fem_reference"] == "mean over the realizations"


@pytest.mark.parametrize("over, message", [
    ({"fem": {"realizations": 7}}, r"fem.realizations \(7\) exceeds realizations \(6\)"),
    ({"models": ["hybrid", "fem"]}, "needs the 'vhs' model"),
    ({"fem": {"realizations": 0}}, "fem.realizations"),
])
def test_bad_fem_realizations_fail_fast_in_one_line(tmp_path, over, message):
    with pytest.raises(InputError, match=message) as err:
        _config(tmp_path, **over)
    assert "\n" not in str(err.value)


def test_runs_give_eq28_at_equal_area_as_the_validation_does(tmp_path, monkeypatch):
    # A FEM stand-in equal to the VHS gives 0 at equal area; one offset in friction only
    # (areas equal) gives mean_k c/(μ_VHS(A_k) + c) at the common areas, which lies between
    # c/(max μ + c) and c/(min μ + c) over the loads' VHS friction (μ grows with A here).
    cfg = _config(tmp_path, loads={"pressures": [0.3, 0.6, 1.0]})
    for k in OFFSET:
        monkeypatch.setitem(OFFSET, k, 0.0)
    ds = rc.pipeline.run(cfg, runner=_offset_fem_runner()[0], progress=False)
    twin = float(ds["error_vs_fem_at_area"].sel(compared_model="vhs", velocity=10.0))
    assert twin == pytest.approx(0.0, abs=1e-12)
    c = 0.05
    monkeypatch.setitem(OFFSET, "friction", c)
    ds = rc.pipeline.run(_config(tmp_path / "b", loads={"pressures": [0.3, 0.6, 1.0]}),
                         runner=_offset_fem_runner()[0], progress=False)
    mu = ds["friction_phase_mean"].sel(model="vhs", velocity=10.0).values
    e = float(ds["error_vs_fem_at_area"].sel(compared_model="vhs", velocity=10.0))
    assert c / (mu.max() + c) - 1e-12 <= e <= c / (mu.min() + c) + 1e-12
    assert ds["error_vs_fem_at_area"].attrs["compared_over"] == "contact_area"
    assert f"at equal A_c: {100 * e:.1f} %" in summary_table(ds)
