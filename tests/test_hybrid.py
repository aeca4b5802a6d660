"""Hybrid pipeline: consistency limits and the law table's contract."""

import numpy as np
import pytest
import xarray as xr

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.hybrid.law import LawWarning, assemble_law, law_at_velocity, max_height


def _config(tmp_path, **over):
    cfg = {"surface": {"wavelengths": [0.125, 0.25], "amplitudes": [0.02648, 0.02939]},
           "loads": {"pressures": [0.3, 1.0]}, "velocities": [10.0], "realizations": 2,
           "seed": 3, "models": ["vhs", "hybrid"], "halfspace": {"n": 1024},
           "execution": {"workers": 1, "cache": str(tmp_path / "cache")},
           "output": {"directory": str(tmp_path / "out")}}
    cfg.update(over)
    return cfg


def test_empty_high_slope_set_hybrid_equals_vhs(tmp_path):
    # Both waves have m2 < 1: the hybrid has no law and must reproduce the VHS exactly.
    ds = rc.hybrid.run(_config(tmp_path), progress=False)
    assert "law_mean_separation" not in ds
    for k in ("friction", "contact_fraction", "mean_separation"):
        np.testing.assert_array_equal(ds[k].sel(model="hybrid").values,
                                      ds[k].sel(model="vhs").values)
    assert np.all(ds["friction_hs"].sel(model="hybrid") == 0)
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
