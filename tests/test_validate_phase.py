"""The phase-averaged eq. 28 of the validation (:mod:`rubbercontact.compare`, which
``studies/_compare.py`` re-exports) on hand-made realizations; the report's words on them
are tested with the studies (studies/tests/test_section3_report.py). The realizations are
the ``phase_data`` fixture's (conftest.py at the repository root, shared with those tests)."""

import numpy as np
import pytest

import rubbercontact.compare as compare


def test_control_variate_fem_curve_is_the_vhs_mean_over_all_realizations_minus_the_offset(
        phase_data):
    data = phase_data()
    curves = compare.phase_mean_curves(data)
    a_all, mu_all = (x.mean(axis=0) for x in data["all"]["vhs"])
    np.testing.assert_allclose(curves["phase"]["fem"][0], a_all, rtol=1e-13)
    np.testing.assert_allclose(curves["phase"]["fem"][1], mu_all - 0.02, rtol=1e-13)
    # the plain curves are the means over the first r
    np.testing.assert_allclose(curves["plain"]["fem"][1],
                               data["fem"][1].mean(axis=0), rtol=1e-13)


def test_phase_averaged_eq28_is_the_offset_over_the_fem_friction(phase_data):
    data = phase_data()
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


def test_a_failed_fem_test_drops_only_that_realization_at_that_load(phase_data):
    data = phase_data()
    fem_a, fem_mu = (x.copy() for x in data["fem"])
    fem_a[3, 1] = fem_mu[3, 1] = np.nan
    data["fem"] = (fem_a, fem_mu)
    est = compare.phase_mean_curves(data)["phase"]["fem"][1]
    vhs = data["paired"]["vhs"][1]
    keep = np.arange(10) != 3
    expected = data["all"]["vhs"][1][:, 1].mean() + (fem_mu[keep, 1] - vhs[keep, 1]).mean()
    assert est[1] == pytest.approx(expected, rel=1e-13)
    assert np.all(np.isfinite(est))


def test_merged_loads_keep_each_loads_fem_realizations(phase_data):
    # 10 FEM realizations at three loads, 5 at two added ones: the merge pads the added
    # loads' FEM with NaN, sorts by load, and the control variate at every load is then
    # exactly mean_N(VHS) - offset (the offset is constant, whatever R is).
    merged = compare.merge_phase_data(phase_data(), phase_data([0.05, 1.2], r=5))
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


def test_merging_refuses_repeated_loads_or_another_n(phase_data):
    with pytest.raises(ValueError, match="loads repeat"):
        compare.merge_phase_data(phase_data(), phase_data([0.35], r=5))
    with pytest.raises(ValueError, match="differ"):
        compare.merge_phase_data(phase_data(), phase_data([1.2], r=5, n=100))


def test_below_load_keeps_the_loads_under_the_limit(phase_data):
    merged = compare.merge_phase_data(phase_data(), phase_data([0.05, 1.2], r=5))
    below = compare.below_load(merged, 1.2)
    np.testing.assert_array_equal(below["pressures"], [0.05, 0.15, 0.35, 0.8])
    assert below["fem"][1].shape == (10, 4) and below["all"]["vhs"][0].shape == (200, 4)


def test_fitted_beta_is_one_for_an_offset_fem_and_gives_the_same_error(phase_data):
    # FEM = VHS − offset: the fitted β is exactly 1, so the regression estimator is the
    # difference estimator and eq. 28 is unchanged.
    data = phase_data()
    (e_d, _), = compare.eq28_phase_averaged({10.0: data}, resamples=20).values()
    (e_r, _), = compare.eq28_phase_averaged({10.0: data}, resamples=20,
                                             beta="regression").values()
    for m in e_d:
        assert e_r[m] == pytest.approx(e_d[m], rel=1e-9)
