"""Contact models as objects (rc.models): closed forms, the hybrid's scale split, the registry."""

from __future__ import annotations

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.hybrid.law import linear_law
from rubbercontact.models import VHS, ContactModel, HalfspaceOptions, Hybrid, MeanField

SBR = rc.materials.sbr()


def test_vhs_and_meanfield_in_full_contact_are_the_closed_form(closed_forms):
    # Full contact superposes: μ = Σ q²Δ² Im E_r(qv)/(4σ0) (plane strain); the BEM holds the
    # sines exactly and the mean-field's P(q) is 1 within 1e-6 at 200 MPa.
    waves = rc.roughness.SineSeries([0.125, 0.25], [0.02648, 0.02939])
    v, p = 10.0, 200.0
    exact = sum(closed_forms.full_contact_friction(SBR, lam, amp, v, p)
                for lam, amp in ((0.125, 0.02648), (0.25, 0.02939)))
    for model in (VHS(HalfspaceOptions(n=1024)), MeanField()):
        res = model.solve(waves, SBR, v, [p])
        assert res.status == ("ok",)
        np.testing.assert_allclose(res.contact_fraction, 1.0, atol=1e-6)
        np.testing.assert_allclose(res.friction, exact, rtol=1e-4)


def test_hybrid_with_the_linear_law_is_the_vhs_at_scale_separation():
    # With the linear (VHS) law of the high-slope wave, the hybrid's only error is its scale
    # split. At λ_ls/λ_hs = 16 (m2_hs = 1.33, m2_ls = 0.3) docs/validation/scale_separation.md
    # measured +1 % (pointwise) and -1 to -0 % (windowed) on 4 realizations; one realization
    # here, so 5 % in μ and A.
    lam_hs, lam_ls = 0.0625, 1.0
    amp = [0.3 * np.sqrt(2) * lam_ls / (2 * np.pi), 1.33 * np.sqrt(2) * lam_hs / (2 * np.pi)]
    surface = rc.roughness.SineSeries([lam_ls, lam_hs], amp, [0.3, 1.1])
    high, _ = surface.partition(1.0)
    v, pressures = 10.0, [0.15, 0.35]

    def law(velocity):
        return linear_law(high, SBR, velocity, n=1024, points=60)

    ref = VHS(HalfspaceOptions(n=4096)).solve(surface, SBR, v, pressures)
    for reading in ("windowed", "pointwise"):
        hyb = Hybrid(law, reading, options=HalfspaceOptions(n=4096)).solve(surface, SBR, v,
                                                                            pressures)
        assert hyb.ok.all()
        np.testing.assert_allclose(hyb.friction, ref.friction, rtol=0.05)
        np.testing.assert_allclose(hyb.contact_fraction, ref.contact_fraction, rtol=0.05)
        assert np.all(hyb.friction_hs > 0) and np.all(np.isnan(ref.friction_hs))


def test_registry_creates_every_model_by_name():
    assert {"vhs", "hybrid-windowed", "hybrid", "meanfield", "fem"} <= set(rc.models.available())
    table = {10.0: {"separation": [0.0, 1.0], "pressure": [1.0, 0.0],
                    "contact_fraction": [1.0, 0.0], "shear_stress": [0.1, 0.0]}}
    for name in rc.models.available():
        kwargs = {"law": table} if rc.models.needs_law(name) else {}
        model = rc.models.create(name, **kwargs)
        assert isinstance(model, ContactModel) and model.name == name
    with pytest.raises(InputError, match="unknown 'bem'; available: vhs"):
        rc.models.create("bem")


def test_hybrid_refuses_what_it_cannot_answer():
    table = {10.0: {"separation": [0.0, 1.0], "pressure": [1.0, 0.0],
                    "contact_fraction": [1.0, 0.0], "shear_stress": [0.1, 0.0]}}
    gentle = rc.roughness.SineSeries([1.0], [0.01])   # m2 = 0.044: no high-slope wave
    with pytest.raises(InputError, match="no wave has m2 > 1"):
        Hybrid(table).solve(gentle, SBR, 10.0, [0.1])
    steep = rc.roughness.SineSeries([1.0, 0.0625], [0.01, 0.02])
    with pytest.raises(InputError, match="no table at 50.0 mm/s"):
        Hybrid(table).solve(steep, SBR, 50.0, [0.1])
    with pytest.raises(InputError, match="velocity: must be > 0"):
        Hybrid(table).solve(steep, SBR, 0.0, [0.1])
    with pytest.raises(InputError, match="reading"):
        Hybrid(table, "crest")


def test_result_dataset_has_units_and_the_pressure_dimension():
    res = VHS(HalfspaceOptions(n=256)).solve(rc.roughness.SineSeries([1.0], [0.01]), SBR,
                                             10.0, [0.3, 0.1])
    ds = res.to_dataset()
    assert list(ds["pressure"].values) == [0.1, 0.3]          # ascending
    assert ds["friction"].attrs["units"] == "1" and ds["mean_separation"].attrs["units"] == "mm"
    assert ds.attrs["model"] == "vhs" and list(ds["status"].values) == ["ok", "ok"]


def test_a_script_and_a_run_share_their_tasks(tmp_path):
    # The models write the same tasks as a run's plan (one writer of the arguments), so a
    # script reuses a run's cache entries and the reverse; the mean-field's defaults and
    # the config's agree (they drifted before).
    from rubbercontact.pipeline import make_runner
    from rubbercontact.pipeline.execute import as_config
    from rubbercontact.pipeline.setup import resolve

    cfg = as_config({"surface": {"preset": "section3"}, "velocities": [10.0],
                     "loads": {"pressures": [0.2, 0.35]}, "realizations": 2,
                     "models": ["vhs", "meanfield"], "halfspace": {"n": 512},
                     "execution": {"workers": 1, "cache": str(tmp_path / "cache")},
                     "output": {"directory": str(tmp_path / "out")}})
    keys: set[str] = set()
    runner = make_runner(cfg, progress=False)

    def recording(tasks, description="sweep"):
        keys.update(t.key() for t in tasks)
        return runner(tasks, description)

    rc.pipeline.run(cfg, runner=recording)
    setup = resolve(cfg)
    mat, p = setup.material, np.array([0.2, 0.35])
    vhs = VHS(HalfspaceOptions(n=512, nu=cfg.material.nu)).tasks(setup.realizations[1], mat,
                                                                   10.0, p)
    mf = MeanField(nu=cfg.material.nu).tasks(setup.base, mat, 10.0, p)
    assert {t.key() for t in vhs + mf} <= keys
