"""The phase-averaged eq. 28 of the validation (``studies/_compare.py``, its report in
``studies/_section3_report.py``) on hand-made realizations."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))   # the repository's studies/
from studies import _compare as compare  # noqa: E402
from studies import _section3_report as s3report  # noqa: E402
from studies._templates import render  # noqa: E402


def _data(r: int = 10, n: int = 200, offset: float = 0.02) -> dict:
    """VHS-like curves varying with the phase; FEM = VHS − ``offset`` in friction, same
    area, on the first ``r``; every hybrid equal to the VHS on all ``n``."""
    rng = np.random.default_rng(3)
    phi = rng.uniform(0, 2 * np.pi, n)
    pressures = np.array([0.15, 0.35, 0.8])
    area = 0.03 * pressures ** 0.8 * (1 + 0.1 * np.sin(phi))[:, None]
    mu = 0.4 + 0.5 * pressures ** 0.5 * (1 + 0.2 * np.cos(phi))[:, None]
    every = {m: (area, mu) for m in ("hybrid", "hybrid-windowed", "vhs")}
    paired = {m: (a[:r], x[:r]) for m, (a, x) in every.items()}
    return {"pressures": pressures, "fem": (area[:r], mu[:r] - offset),
            "paired": paired, "all": every}


def test_control_variate_fem_curve_is_the_vhs_mean_over_all_realizations_minus_the_offset():
    data = _data()
    curves = compare.phase_mean_curves(data)
    a_all, mu_all = (x.mean(axis=0) for x in data["all"]["vhs"])
    np.testing.assert_allclose(curves["phase"]["fem"][0], a_all, rtol=1e-13)
    np.testing.assert_allclose(curves["phase"]["fem"][1], mu_all - 0.02, rtol=1e-13)
    # the plain curves are the means over the first r
    np.testing.assert_allclose(curves["plain"]["fem"][1],
                               data["fem"][1].mean(axis=0), rtol=1e-13)


def test_phase_averaged_eq28_is_the_offset_over_the_fem_friction():
    data = _data()
    (e, ci), = compare.eq28_phase_averaged({10.0: data}, resamples=200).values()
    # FEM and hybrids share the area curve, and linear interpolation keeps a constant
    # offset: e = mean_k 0.02 / μ_FEM(A_k) over the 4 common areas, exactly.
    curves = compare.phase_mean_curves(data)["phase"]
    areas, mus = compare.common_areas({m: curves[m] for m in ("fem", "vhs")})
    expected = np.mean(0.02 / mus["fem"])
    for m in ("hybrid", "hybrid-windowed", "vhs"):
        assert e[m] == pytest.approx(expected, rel=1e-12)
        low, high, used = ci[m]
        assert used == 200 and low <= e[m] * 1.05 and high >= e[m] * 0.95


def test_a_failed_fem_test_drops_only_that_realization_at_that_load():
    data = _data()
    fem_a, fem_mu = (x.copy() for x in data["fem"])
    fem_a[3, 1] = fem_mu[3, 1] = np.nan
    data["fem"] = (fem_a, fem_mu)
    est = compare.phase_mean_curves(data)["phase"]["fem"][1]
    vhs = data["paired"]["vhs"][1]
    keep = np.arange(10) != 3
    expected = data["all"]["vhs"][1][:, 1].mean() + (fem_mu[keep, 1] - vhs[keep, 1]).mean()
    assert est[1] == pytest.approx(expected, rel=1e-13)
    assert np.all(np.isfinite(est))


def _data_at(pressures, r: int, n: int = 200, offset: float = 0.02) -> dict:
    """``_data`` at other loads (the same phases, so it merges with ``_data``)."""
    rng = np.random.default_rng(3)
    phi = rng.uniform(0, 2 * np.pi, n)
    p = np.asarray(pressures, float)
    area = 0.03 * p ** 0.8 * (1 + 0.1 * np.sin(phi))[:, None]
    mu = 0.4 + 0.5 * p ** 0.5 * (1 + 0.2 * np.cos(phi))[:, None]
    every = {m: (area, mu) for m in ("hybrid", "hybrid-windowed", "vhs")}
    return {"pressures": p, "fem": (area[:r], mu[:r] - offset),
            "paired": {m: (a[:r], x[:r]) for m, (a, x) in every.items()}, "all": every}


def test_merged_loads_keep_each_loads_fem_realizations():
    # 10 FEM realizations at three loads, 5 at two added ones: the merge pads the added
    # loads' FEM with NaN, sorts by load, and the control variate at every load is then
    # exactly mean_N(VHS) - offset (the offset is constant, whatever R is).
    merged = compare.merge_phase_data(_data(), _data_at([0.05, 1.2], r=5))
    np.testing.assert_array_equal(merged["pressures"], [0.05, 0.15, 0.35, 0.8, 1.2])
    fem_mu = merged["fem"][1]
    assert fem_mu.shape == (10, 5)
    assert np.isnan(fem_mu[5:, [0, 4]]).all() and np.isfinite(fem_mu[:, 1:4]).all()
    assert merged["paired"]["vhs"][1].shape == (10, 5)
    np.testing.assert_array_equal(merged["paired"]["vhs"][1], merged["all"]["vhs"][1][:10])
    est = compare.phase_mean_curves(merged)["phase"]["fem"][1]
    np.testing.assert_allclose(est, merged["all"]["vhs"][1].mean(axis=0) - 0.02, rtol=1e-13)
    # eq. 28 over the wider range: still the offset over the FEM friction at common areas
    (e, _), = compare.eq28_phase_averaged({10.0: merged}, resamples=50).values()
    curves = compare.phase_mean_curves(merged)["phase"]
    areas, mus = compare.common_areas({m: curves[m] for m in ("fem", "vhs")})
    assert areas[0] < 0.03 * 0.15 ** 0.8 and areas[-1] > 0.03 * 0.8 ** 0.8   # wider range
    assert e["hybrid-windowed"] == pytest.approx(np.mean(0.02 / mus["fem"]), rel=1e-12)


def test_merging_refuses_repeated_loads_or_another_n():
    with pytest.raises(ValueError, match="loads repeat"):
        compare.merge_phase_data(_data(), _data_at([0.35], r=5))
    with pytest.raises(ValueError, match="differ"):
        compare.merge_phase_data(_data(), _data_at([1.2], r=5, n=100))


def test_extended_rows_name_the_range_and_leave_the_pointwise_hybrid_out_in_the_second():
    merged = compare.merge_phase_data(_data(), _data_at([0.05, 1.2], r=5))
    rows, text = s3report.extended_rows({10.0: merged}, 1.39)
    assert len(rows) == 3 and "all models" in rows[0] and "without the pointwise" in rows[1]
    assert rows[1].split("|")[3].strip() == "-"          # no pointwise-hybrid entry
    assert "below the top load (1.2 MPa)" in rows[2]
    assert "0.05 (5), 0.15 (10), 0.35 (10), 0.8 (10), 1.2 (5)" in text
    assert "exceeds" not in text        # μσ0 <= 1.14 MPa < E∞/3 = 1.39 MPa everywhere


def test_a_fem_friction_stress_above_the_relaxed_shear_modulus_is_named_and_left_out():
    merged = compare.merge_phase_data(_data(), _data_at([0.05, 1.2], r=5))
    fem_a, fem_mu = (x.copy() for x in merged["fem"])
    fem_mu[:, -1] = 1.5                                  # μσ0 = 1.8 MPa at 1.2 MPa
    merged["fem"] = (fem_a, fem_mu)
    _, text = s3report.extended_rows({50.0: merged}, 1.39)
    # the phase average is mean_N(VHS) + mean_R(FEM − VHS), not 1.5 itself
    assert "At 50 mm/s and 1.2 MPa the FEM's phase-averaged friction stress μσ0 = " in text
    assert "MPa exceeds E∞/3 = 1.39 MPa; from 0.8 MPa its μ goes from" in text
    assert render("validation_section3", "extended_fem_caveat") in text
    assert "and 0.8 MPa the FEM's" not in text          # below E∞/3: not named
    below = compare.below_load(merged, 1.2)
    np.testing.assert_array_equal(below["pressures"], [0.05, 0.15, 0.35, 0.8])
    assert below["fem"][1].shape == (10, 4) and below["all"]["vhs"][0].shape == (200, 4)


def test_phase_curves_figure_is_drawn(tmp_path):
    merged = compare.merge_phase_data(_data(), _data_at([0.05, 1.2], r=5))
    path = s3report.plot_phase_curves({10.0: merged, 50.0: merged}, tmp_path / "f.png")
    assert path.stat().st_size > 1000


def test_fitted_beta_is_one_for_an_offset_fem_and_gives_the_same_error():
    # FEM = VHS − offset: the fitted β is exactly 1, so the regression estimator is the
    # difference estimator and eq. 28 is unchanged.
    data = _data()
    (e_d, _), = compare.eq28_phase_averaged({10.0: data}, resamples=20).values()
    (e_r, _), = compare.eq28_phase_averaged({10.0: data}, resamples=20,
                                             beta="regression").values()
    for m in e_d:
        assert e_r[m] == pytest.approx(e_d[m], rel=1e-9)
    assert "β = 1.00 (0.000 → 0.000)" in s3report.beta_text({10.0: data})
