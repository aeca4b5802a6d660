"""Stacking task results into the run's dataset (rubbercontact.pipeline.assemble)."""

import warnings

import numpy as np
import pytest
import xarray as xr

import rubbercontact as rc
from rubbercontact.pipeline.assemble import assemble
from rubbercontact.pipeline.plan import Slot


def _fem_point(impaled=None) -> xr.Dataset:
    """A full-FEM task's scalars (the variables fem_task returns that assemble reads)."""
    values = {"friction": 0.3, "contact_fraction": 0.2, "mean_separation": 0.01,
              "wall_time": 1.0}
    if impaled is not None:
        values["impaled"] = float(impaled)
    return xr.Dataset({k: ((), v) for k, v in values.items()})


def test_an_impaled_full_fem_test_is_flagged_and_named_and_its_numbers_kept():
    # An impaled face (the surface passes through it between nodes) keeps its numbers, but
    # the run says which test it was, and stores the flag; results cached before the flag
    # existed have none (NaN), and a run without an impaled test stays silent about it.
    slots = [Slot("fem", 0, 0, 0), Slot("fem", 0, 0, 1), Slot("fem", 0, 0, 2)]
    results = [_fem_point(0), _fem_point(1), _fem_point()]
    with pytest.warns(RuntimeWarning, match=r"1 full-FEM test\(s\) had the rubber face "
                                            r"impaled \(v=10 σ0=2 r=0\)") as caught:
        ds = assemble(["fem"], np.array([10.0]), 1, np.array([1.0, 2.0, 3.0]), slots,
                      results, rc.materials.sbr(), 1)
    assert sum("impaled" in str(w.message) for w in caught) == 1
    np.testing.assert_array_equal(ds["fem_impaled"].values[0, 0], [0.0, 1.0, np.nan])
    assert float(ds["friction"].sel(model="fem").values[0, 0, 1]) == 0.3   # kept
    assert list(ds["status"].values[0, 0, 0]) == ["ok"] * 3
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assemble(["fem"], np.array([10.0]), 1, np.array([1.0]), slots[:1], results[:1],
                 rc.materials.sbr(), 1)


def test_the_full_fems_loads_above_e_inf_are_not_run_and_the_run_says_so():
    # The rule of fem.loadrange (p̄ <= E∞): the planner sends no full FEM task above it,
    # the dataset marks those loads "not run" (not failed) and the run says so in one line;
    # the other models run every load.
    from rubbercontact.config import parse_config
    from rubbercontact.pipeline import resolve
    from rubbercontact.pipeline.assemble import NOT_RUN, failed_solves
    from rubbercontact.pipeline.plan import model_tasks
    from rubbercontact.pipeline.setup import task_material

    mat = rc.materials.sbr()
    e_inf = float(mat.equilibrium_modulus)
    p = np.array([0.5 * e_inf, e_inf, 1.2 * e_inf])
    setup = resolve(parse_config({"surface": {"preset": "section3"}, "velocities": [10.0],
                                  "loads": {"pressures": p.tolist()}, "realizations": 1,
                                  "models": ["vhs", "fem"], "halfspace": {"n": 1024},
                                  "fem": {"mesh": [40, 30]}}))
    task_mat = rc.materials.GeneralizedMaxwell(**task_material(setup.material))
    slots, _ = model_tasks(setup, task_mat, p, {})
    assert [s.ip for s in slots if s.model == "fem"] == [0, 1]           # E∞ itself runs
    assert [s.ip for s in slots if s.model == "vhs"] == [None]           # every load
    fem = [sl for sl in slots if sl.model == "fem"]
    with pytest.warns(RuntimeWarning, match=rf"full FEM not run at {1.2 * e_inf:.3g} MPa: "
                                            r"above the rubber's E∞") as caught:
        ds = assemble(["fem"], np.array([10.0]), 1, p, fem, [_fem_point(0)] * 2, mat, 1)
    assert sum("not run" in str(w.message) for w in caught) == 1
    status = ds["status"].values[0, 0, 0]
    assert list(status[:2]) == ["ok", "ok"] and status[2].startswith(NOT_RUN)
    assert not failed_solves(ds["status"].values).any()
    assert np.isnan(ds["friction"].values[0, 0, 0, 2])
