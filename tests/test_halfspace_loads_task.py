"""The half-space task over several loads (one pipeline task per speed and realization).

Each load is the same solve as the one-load task (the batching only saves cache files), a
load that fails is recorded and the others are kept, and the profiles keep their loads.
"""

import numpy as np

import rubbercontact as rc
from rubbercontact.hybrid.tasks import halfspace_loads_task, halfspace_task
from rubbercontact.roughness import SineSeries

SURF = SineSeries([0.25, 1.0], [0.01, 0.04], [0.3, 1.1])
SBR = rc.materials.sbr()
LOADS = [0.05, 0.2]


def _kw(**over):
    return {"surface": SURF.as_dict(), "period": 1.0, "material": SBR.as_dict(),
            "velocity": 10.0, "n": 512, **over}


def test_each_load_is_the_one_load_solve():
    ds = halfspace_loads_task(mean_pressures=LOADS, **_kw())
    assert list(ds["status"].values) == ["ok", "ok"]
    for p in LOADS:
        one = halfspace_task(mean_pressure=p, **_kw())
        for k in ("friction", "contact_fraction", "mean_separation", "max_local_pressure"):
            # the same deterministic solve: equal to rounding
            np.testing.assert_allclose(float(ds[k].sel(pressure=p)), float(one[k]),
                                       rtol=1e-12, err_msg=k)
        assert ds["friction"].attrs["units"] == one["friction"].attrs["units"]


def test_a_failing_load_is_recorded_and_the_others_kept():
    ds = halfspace_loads_task(mean_pressures=[0.05, -1.0, 0.2], **_kw())
    status = list(ds["status"].values)
    assert status[0] == "ok" and status[2] == "ok"
    assert status[1].startswith("InputError") and "mean_pressure" in status[1]
    assert np.isnan(float(ds["friction"][1]))
    assert np.isfinite(ds["friction"].values[[0, 2]]).all()


def test_profiles_on_every_load():
    ds = halfspace_loads_task(mean_pressures=LOADS, keep_profile=True, **_kw())
    assert ds["pressure_profile"].dims == ("pressure", "x")
    assert ds["heights_profile"].dims == ("x",)
    # each load's profile carries its mean pressure
    np.testing.assert_allclose(ds["pressure_profile"].mean("x"), LOADS, rtol=1e-10)


def test_the_tolerance_reaches_the_solver():
    """``halfspace.tol`` of the config is the solver's: a loose one stops earlier."""
    from rubbercontact.config import parse_config
    from rubbercontact.pipeline.plan import model_tasks
    from rubbercontact.pipeline.setup import resolve

    cfg = parse_config({"surface": {"wavelengths": [0.25, 1.0], "amplitudes": [0.01, 0.04]},
                        "loads": {"pressures": LOADS}, "velocities": [10.0], "realizations": 1,
                        "models": ["vhs"], "halfspace": {"n": 512, "tol": 1e-4}})
    setup = resolve(cfg)
    _, tasks = model_tasks(setup, setup.material, np.array(LOADS), {})
    assert tasks[0].kwargs["tol"] == 1e-4
    loose = halfspace_loads_task(mean_pressures=LOADS, tol=1e-4, **_kw())
    tight = halfspace_loads_task(mean_pressures=LOADS, tol=1e-10, **_kw())
    assert (loose["iterations"] < tight["iterations"]).any()
