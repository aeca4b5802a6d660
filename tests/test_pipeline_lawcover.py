"""A law that covers the run (``rubbercontact.pipeline.lawcover``, issue 41 item 3).

Expectations from outside the code: the half-decade ladder (rungs 10^(k/2) MPa), the
coverage as the plain maximum of the law models' local pressures (the VHS does not read the
law), the stop rules stated in the module (a failed point, the relaxed modulus,
``law.max_pressure``, a bulk shear growing as a power of the load), and on a small run the
law's own table: every point the run added lies on the ladder, the law's top is where the
extension stopped, and the run's note quotes the stored local pressure and that top.
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

import rubbercontact as rc
from rubbercontact.fem.result import BULK_SHEAR_LIMIT
from rubbercontact.pipeline.lawcover import (
    NOT_NEEDED,
    Coverage,
    coverage,
    ladder_above,
    merge_points,
    plan_extension,
    predicted_shear,
)

S10 = 10 ** 0.5


def _law(pressures, status, shear=None, speeds=(10.0,)) -> xr.Dataset:
    """A law table at ``speeds`` (every row alike) with the given statuses and shears."""
    shape = (len(speeds), len(pressures))

    def grid(values):
        return ("velocity", "pressure"), np.array(np.broadcast_to(np.array(values), shape))

    law = xr.Dataset(
        {"status": grid(status),
         "friction": (("velocity", "pressure"), np.full(shape, 0.3))},
        coords={"velocity": list(speeds), "pressure": list(pressures)})
    if shear is not None:
        law["bulk_shear"] = grid(shear)
    return law


def test_ladder_is_half_decades_up_to_the_first_rung_past_the_need():
    assert ladder_above(2.0, 4.12) == pytest.approx([S10, 10.0])
    assert ladder_above(0.5, 0.9) == pytest.approx([1.0])
    # a top on a rung starts at the next one
    assert ladder_above(1.0, 1.5) == pytest.approx([S10])
    assert ladder_above(S10, 31.0) == pytest.approx([10.0, 10 * S10])


def test_coverage_reads_only_the_models_that_read_the_law():
    local = np.array([[[[1.0, 50.0]]], [[[2.0, 3.0]]], [[[0.5, np.nan]]]])   # m, v, r, p
    ds = xr.Dataset({"max_local_pressure": (("model", "velocity", "realization", "pressure"),
                                            local)},
                    coords={"model": ["vhs", "hybrid", "hybrid-windowed"], "velocity": [10.0]})
    cov = coverage(ds, _law([0.5, 2.5], ["ok", "ok"]))
    assert cov.reached == pytest.approx([3.0])          # not the VHS's 50 MPa
    assert cov.tops == pytest.approx([2.5]) and cov.uncovered.tolist() == [True]


def test_extension_plans_the_rungs_and_stops_where_stated():
    law = _law([0.1, 0.3, 1.0, 2.0], ["ok", "ok", "ok", "failed: line search"],
               speeds=(1.0, 10.0, 100.0))
    law["status"].values[1:, 3] = "ok"
    cov = Coverage(np.array([1.0, 10.0, 100.0]), np.array([5.0, 0.9, 40.0]),
                   np.array([1.0, 1.0, 2.0]))
    ext = plan_extension(cov, law, max_pressure=20.0, relaxed_modulus=3000.0)
    # 1 mm/s: the tried point above its top failed; 10 mm/s: covered; 100 mm/s: rungs
    # above 2 MPa up to law.max_pressure
    assert "FEM at 2 MPa: failed: line search" in ext.stopped[1.0]
    assert sorted(ext.points) == pytest.approx([S10, 10.0])
    assert all(v == [100.0] for v in ext.points.values())
    ext = plan_extension(cov, law, max_pressure=1.5, relaxed_modulus=3000.0)
    assert not ext.points and "law.max_pressure" in ext.stopped[100.0]
    ext = plan_extension(cov, law, max_pressure=np.inf, relaxed_modulus=3.0)
    assert not ext.points and "relaxed modulus" in ext.stopped[100.0]


def test_shear_prediction_is_the_power_law_of_the_two_top_points():
    row = _law([0.5, 1.0, 2.0], ["ok", "ok", "ok"], shear=[0.05, 0.1, 0.4]).isel(velocity=0)
    # exponent log(0.4/0.1)/log 2 = 2 from the two highest points
    assert predicted_shear(row, 4.0) == pytest.approx(1.6)
    # a shear growing slower than the load is taken as linear (μ does not fall with load)
    row = _law([1.0, 2.0], ["ok", "ok"], shear=[0.3, 0.4]).isel(velocity=0)
    assert predicted_shear(row, 4.0) == pytest.approx(0.8)
    law = _law([1.0, 2.0], ["ok", "ok"], shear=[0.3, 0.6])
    cov = Coverage(np.array([10.0]), np.array([9.0]), np.array([2.0]))
    ext = plan_extension(cov, law, np.inf, 3000.0)
    # 3.16 MPa: shear 0.6 * 1.58 = 0.95 <= 1 computed; 10 MPa: 3.0 > 1 not
    assert list(ext.points) == pytest.approx([S10]) and not ext.stopped
    assert BULK_SHEAR_LIMIT == 1.0


def test_merge_puts_the_computed_points_in_and_keeps_the_rest():
    raw = _law([0.5, 1.0], ["ok", "ok"], speeds=(1.0, 2.0))
    raw["status"].values[1, 1] = NOT_NEEDED
    new = _law([1.0, S10], [NOT_NEEDED, NOT_NEEDED], speeds=(1.0, 2.0))
    new["status"] = new["status"].copy(data=np.array([[NOT_NEEDED, NOT_NEEDED],
                                                      ["ok", "failed: x"]]))
    new["friction"].values[1] = [0.7, 0.8]
    out = merge_points(raw, new)
    assert out["pressure"].values == pytest.approx([0.5, 1.0, S10])
    assert out["status"].values.tolist() == [["ok", "ok", NOT_NEEDED],
                                             ["ok", "ok", "failed: x"]]
    assert out["friction"].values[1, 1:] == pytest.approx([0.7, 0.8])
    assert out["friction"].values[0, 1] == pytest.approx(0.3)


def test_run_extends_its_law_until_the_cell_would_shear(tmp_path):
    """A law given at 0.2 and 0.5 MPa under a low-slope solve that reaches about 3 MPa: the
    run adds ladder rungs while the cell's predicted bulk shear stays at or below 1, then
    says in one line how far the local pressures went and why the law stops, and the
    hybrid's validity note quotes the same two numbers."""
    from rubbercontact import validity as va
    from rubbercontact.hybrid.lawio import law_from_results
    from rubbercontact.hybrid.lawtable import law_top
    from rubbercontact.pipeline.execute import as_config
    from rubbercontact.pipeline.setup import resolve

    cfg = {"surface": {"preset": "section3"}, "loads": {"pressures": [0.3]},
           "velocities": [10.0], "realizations": 1, "seed": 3,
           "models": ["vhs", "hybrid-windowed"], "halfspace": {"n": 1024},
           "fem": {"mesh": [24, 12]}, "law": {"pressures": [0.2, 0.5]},
           "execution": {"workers": 1, "cache": str(tmp_path / "cache")},
           "output": {"directory": str(tmp_path / "out")}}
    ds = rc.pipeline.run(cfg, progress=False)
    law = law_from_results(ds)
    added = sorted(set(law["pressure"].values.tolist()) - {0.2, 0.5})
    assert added, "the law was not extended"
    for p in added:                                    # every added point is a rung
        assert 2 * np.log10(p) == pytest.approx(round(2 * np.log10(p)), abs=1e-9)
    top = law_top(law, 10.0)
    reached = float(ds["max_local_pressure"].sel(model="hybrid-windowed").max())
    line = ds.attrs["law_coverage"]
    if reached <= top * 1.02:
        assert "covers" in line
        return
    # not covered: the next rung is where the cell's predicted shear passes 1
    nxt = ladder_above(top, reached)[0]
    assert predicted_shear(law.sel(velocity=10.0), nxt) > BULK_SHEAR_LIMIT
    assert f"{reached:.3g} MPa against {top:.3g} MPa" in line and "shear" in line
    notes = va.assess_run(ds, resolve(as_config(cfg)))
    (note,) = [n for n in notes if n.condition == "law_pressure"]
    assert note.excess == pytest.approx(reached / top)
    assert f"{reached:.3g} MPa" in note.text and f"{top:.3g} MPa" in note.text
