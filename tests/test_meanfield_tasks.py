"""The mean-field pipeline task: plain data in, the half-space task's variables out."""

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact import meanfield as mf
from rubbercontact.hybrid.tasks import halfspace_task
from rubbercontact.meanfield.tasks import meanfield_task
from rubbercontact.roughness import SineSeries

SBR = rc.materials.sbr()
SHARED = ("friction", "friction_ls", "friction_hs", "contact_fraction", "mean_pressure",
          "velocity", "max_local_pressure", "wall_time")


def _table():
    sig = np.linspace(10.0, 0.0, 401)
    return {"separation": list(1.0 - sig / 20), "pressure": list(sig),
            "contact_fraction": list(sig / (1 + sig)), "shear_stress": list(0.3 * sig**2)}


def test_task_has_the_half_space_task_s_names_and_units():
    surf = rc.roughness.section3()
    ds = meanfield_task(surf.as_dict(), SBR.as_dict(), 10.0, 0.2)
    ref = halfspace_task(surf.as_dict(), surf.period, SBR.as_dict(), 10.0, 0.2, n=1024,
                         law="hard-wall")
    for name in SHARED:
        assert name in ds and name in ref
        assert ds[name].attrs["units"] == ref[name].attrs["units"]
    direct = mf.solve(mf.PSD.from_sines(surf), SBR, 10.0, 0.2)
    assert float(ds["friction"]) == direct.friction
    assert float(ds["contact_fraction"]) == direct.contact_fraction
    assert ds.attrs["model"] == "meanfield" and ds.attrs["hybrid"] == 0
    # the 99.9 % quantile of P(σ) in contact lies above σ0 and below σ0 + 9 sd
    dist = direct.pressure_distribution
    assert 0.2 < float(ds["max_local_pressure"]) < dist.sigma[-1]


def test_task_takes_a_spectrum_and_a_law():
    psd = mf.PSD.self_affine(hurst=0.8, qr=1.0, q1=1e3, rms_slope=0.3)
    opts = mf.MeanFieldOptions(correction=0.4)
    ds = meanfield_task(psd.as_dict(), SBR.as_dict(), 50.0, 0.5, options=opts.to_dict())
    assert float(ds["friction"]) == pytest.approx(
        mf.solve(psd, SBR, 50.0, 0.5, options=opts).friction, rel=1e-14)
    ls = SineSeries([8.0, 4.0], [0.2, 0.05])
    hyb = meanfield_task(ls.as_dict(), SBR.as_dict(), 10.0, 0.5, interface_law=_table())
    assert hyb.attrs["hybrid"] == 1
    assert float(hyb["friction_hs"]) > 0
    assert float(hyb["friction"]) == pytest.approx(float(hyb["friction_ls"])
                                                   + float(hyb["friction_hs"]), rel=1e-14)
    with pytest.raises(rc.errors.InputError, match="surface"):
        meanfield_task({"heights": [1, 2]}, SBR.as_dict(), 10.0, 0.5)


def test_config_dissipation_reaches_the_task():
    """``[meanfield] dissipation`` is a config field the plan passes to the task; on a
    continuous 1D spectrum 'mode' (Persson's) and 'patch' answer differently, and the task
    answers what ``solve`` does with the same option."""
    from pydantic import ValidationError

    from rubbercontact.config import RunConfig
    from rubbercontact.pipeline.plan import meanfield_call

    psd = mf.PSD.self_affine(hurst=0.8, qr=1.0, q1=1e3, rms_slope=0.3)
    base = {"surface": {"preset": "section3"}, "loads": {"pressures": [0.5]},
            "velocities": [10.0], "models": ["meanfield"]}
    mus = {}
    for choice in ("mode", "patch"):
        cfg = RunConfig.model_validate({**base, "meanfield": {"dissipation": choice}})
        fn, kw = meanfield_call(cfg, "meanfield", psd.as_dict(), SBR, 10.0, 0.5, None, 8.0)
        assert kw["options"]["dissipation"] == choice
        mus[choice] = float(meanfield_task(**kw)["friction"])
        direct = mf.solve(psd, SBR, 10.0, 0.5, options=mf.MeanFieldOptions(dissipation=choice))
        assert mus[choice] == pytest.approx(direct.friction, rel=1e-12)
    assert mus["mode"] != pytest.approx(mus["patch"], rel=1e-3)
    with pytest.raises(ValidationError, match="dissipation"):
        RunConfig.model_validate({**base, "meanfield": {"dissipation": "everywhere"}})
