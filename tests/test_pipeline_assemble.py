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
