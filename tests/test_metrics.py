"""Eq. 28 and area interpolation on hand-made curves."""

import numpy as np
import pytest

from rubbercontact.errors import InputError
from rubbercontact.hybrid.metrics import (
    bootstrap_interval,
    control_variate_by_column,
    control_variate_mean,
    interpolate_at_areas,
    mean_relative_error,
    rising_branch,
)


def test_eq28_hand_computed():
    ref = np.array([0.2, 0.4, 0.5])
    cand = np.array([0.22, 0.36, 0.5])
    # (0.02/0.2 + 0.04/0.4 + 0)/3 = (0.1 + 0.1 + 0)/3
    assert mean_relative_error(ref, cand) == pytest.approx(0.2 / 3, rel=1e-14)
    assert mean_relative_error(ref, ref) == 0.0


def test_eq28_bad_input():
    with pytest.raises(InputError, match="lengths differ"):
        mean_relative_error([1.0, 2.0], [1.0])
    with pytest.raises(InputError, match="zeros"):
        mean_relative_error([0.0, 2.0], [1.0, 1.0])
    with pytest.raises(InputError, match="NaN"):
        mean_relative_error([np.nan, 2.0], [1.0, 1.0])


def test_interpolation_is_exact_for_log_linear_curve_and_nan_outside():
    area = np.array([0.01, 0.03, 0.1, 0.3])
    mu = 0.5 + 0.1 * np.log(area)   # linear in log(area): interpolation is exact
    t = np.array([0.005, 0.02, 0.05, 0.2, 0.5])
    out = interpolate_at_areas(area[::-1], mu[::-1], t)   # unsorted input is fine
    np.testing.assert_allclose(out[1:4], 0.5 + 0.1 * np.log(t[1:4]), rtol=1e-12)
    assert np.isnan(out[0]) and np.isnan(out[4])


def test_rising_branch_drops_loads_whose_area_does_not_grow():
    # A settled full FEM at 50 mm/s: the area peaks at 0.8 MPa and falls above it; a small
    # dip at 0.35 MPa below the area at 0.15 MPa is left out as well (μ(A) must be
    # single-valued). Loads may come in any order.
    p = np.array([0.1, 0.15, 0.35, 0.8, 2.0, 3.0])
    a = np.array([0.009, 0.013, 0.012, 0.032, 0.025, 0.021])
    np.testing.assert_array_equal(rising_branch(p, a), [1, 1, 0, 1, 0, 0])
    shuffle = np.array([4, 0, 5, 2, 1, 3])
    np.testing.assert_array_equal(rising_branch(p[shuffle], a[shuffle]),
                                  np.array([1, 1, 0, 1, 0, 0], bool)[shuffle])
    # μ on the falling branch is 0.9, on the rising one 0.5: interpolation along the load
    # sweep sees only the rising branch (exactly 0.5), and nothing beyond its largest area
    mu = np.where(p > 0.8, 0.9, 0.5)
    out = interpolate_at_areas(a, mu, [0.02, 0.03, 0.04], loads=p)
    np.testing.assert_array_equal(out[:2], [0.5, 0.5])
    assert np.isnan(out[2])
    with pytest.raises(InputError, match="repeated"):
        rising_branch([0.1, 0.1], [0.01, 0.02])
    with pytest.raises(InputError, match="lengths differ"):
        rising_branch([0.1, 0.2], [0.01])


def test_bootstrap_interval_of_a_mean_matches_the_central_limit():
    # For the mean of n samples the bootstrap distribution is ~ normal with the sample's
    # standard error s/sqrt(n); the 90 % interval half-width is then 1.645 s/sqrt(n).
    # Tolerance 10 %: the quantile noise of 2000 resamples is about 3 % of the width.
    x = np.random.default_rng(1).normal(size=400)
    lo, hi, used = bootstrap_interval(lambda i: x[i].mean(), x.size, resamples=2000,
                                      level=0.9, seed=3)
    half = 1.6449 * x.std() / np.sqrt(x.size)
    assert used == 2000
    assert (hi - lo) / 2 == pytest.approx(half, rel=0.10)
    assert (lo + hi) / 2 == pytest.approx(x.mean(), abs=0.15 * half)


def test_bootstrap_interval_is_paired_across_models():
    # Two "models" that differ by a constant on every realization: a paired resample sees
    # no spread in their difference at all, however much the realizations differ.
    base = np.array([0.25, 0.5, 0.42, 0.49, 0.48])
    lo, hi, _ = bootstrap_interval(lambda i: np.mean(base[i] + 0.1) - np.mean(base[i]),
                                   base.size, resamples=500)
    assert lo == pytest.approx(0.1, abs=1e-12) and hi == pytest.approx(0.1, abs=1e-12)
    lo, hi, _ = bootstrap_interval(lambda i: np.mean(base[i]), base.size, resamples=500)
    assert lo < np.mean(base) < hi


def test_bootstrap_interval_leaves_out_nan_resamples():
    # A statistic undefined whenever realization 0 is drawn: the kept share is the chance
    # that none of 5 draws is 0, (4/5)^5 = 0.328 (binomial sd 0.0105 at 2000; 4 sd).
    _, _, used = bootstrap_interval(lambda i: np.nan if 0 in i else 1.0, 5,
                                    resamples=2000, seed=7)
    assert used / 2000 == pytest.approx(0.8**5, abs=0.042)


@pytest.mark.parametrize("kwargs", [{"n_realizations": 1}, {"level": 1.0},
                                    {"resamples": 10}, {"n_realizations": 2.5}])
def test_bootstrap_interval_rejects_bad_input(kwargs):
    args = {"n_realizations": 5, "resamples": 200, "level": 0.9} | kwargs
    with pytest.raises(InputError):
        bootstrap_interval(lambda i: 1.0, args.pop("n_realizations"), **args)


def test_control_variate_mean_is_exact_for_a_constant_offset():
    control_all = np.array([[1.0, 2.0], [3.0, 6.0], [5.0, 4.0]])   # mean (3, 4)
    control = control_all[:2]
    target = control + np.array([0.5, -1.0])
    np.testing.assert_allclose(control_variate_mean(target, control, control_all),
                               [3.5, 3.0], rtol=1e-15)


def _phase_trials(seed: int, target_of, r: int, n: int, trials: int):
    """Seeded trials of N random phases: ``(target on the first r, control = 1 + sin φ)``."""
    rng = np.random.default_rng(seed)
    for _ in range(trials):
        phi = rng.uniform(0, 2 * np.pi, n)
        yield target_of(phi[:r], rng), 1.0 + np.sin(phi)


def test_control_variate_mean_is_unbiased_with_the_predicted_variance():
    # target = 1.2 + 1.05 sin(phi), control = 1 + sin(phi): E[target] = 1.2 exactly;
    # control_variate_by_column gives the same estimate and a standard error whose square
    # must be unbiased for the estimate's variance.
    r, n, trials = 10, 500, 2000
    est, plain, se2 = np.empty(trials), np.empty(trials), np.empty(trials)
    for i, (target, control_all) in enumerate(_phase_trials(
            7, lambda phi, rng: 1.2 + 1.05 * np.sin(phi), r, n, trials)):
        est[i] = control_variate_mean(target, control_all[:r], control_all)
        plain[i] = target.mean()
        e, se = control_variate_by_column(target, control_all[:r], control_all)
        assert float(e) == pytest.approx(est[i], rel=1e-14)
        se2[i] = float(se) ** 2
    # The estimate with N including the R paired ones has variance
    # var(d)/R + var(c)/N + 2 cov(mean_R d, mean_N c) = (0.05^2/2)/R + (1/2)/N
    # + 2 * 0.05 * (1/2) / N = 1.25e-4 + 1e-3 + 1e-4.
    predicted = 0.05**2 / 2 / r + 0.5 / n + 2 * 0.05 * 0.5 / n
    # tolerances: 4 standard errors of a mean and of a variance over 2000 trials
    assert abs(est.mean() - 1.2) < 4 * np.sqrt(predicted / trials)
    assert est.var() == pytest.approx(predicted, rel=4 * np.sqrt(2 / trials))
    assert plain.var() > 30 * est.var()       # 1.05^2/2/R = 0.055 against 1.2e-3
    assert se2.mean() == pytest.approx(predicted, abs=4 * se2.std() / np.sqrt(trials))


def test_control_variate_mean_bad_input():
    with pytest.raises(InputError, match="same shape"):
        control_variate_mean([1.0, 2.0], [1.0], [1.0, 2.0])
    with pytest.raises(InputError, match="control_all"):
        control_variate_mean([[1.0, 2.0]], [[1.0, 2.0]], [[1.0, 2.0, 3.0]])
    with pytest.raises(InputError, match="NaN"):
        control_variate_mean([1.0, np.nan], [1.0, 2.0], [1.0, 2.0, 3.0])


def test_control_variate_by_column_leaves_out_failed_pairs_per_column():
    rng = np.random.default_rng(2)
    control_all = rng.uniform(0.3, 0.8, size=(8, 2, 3))       # (N, velocity, load)
    control = control_all[:4].copy()
    target = control + 0.1 + rng.normal(0, 0.01, size=control.shape)
    target[1, 0, 2] = np.nan                                   # one failed FEM test
    target[:, 1, 0] = np.nan                                   # a load where all failed
    est, se = control_variate_by_column(target, control, control_all)
    assert est.shape == se.shape == (2, 3)
    keep = [0, 2, 3]
    assert est[0, 2] == pytest.approx(control_variate_mean(
        target[keep, 0, 2], control[keep, 0, 2], control_all[:, 0, 2]), rel=1e-15)
    assert est[0, 0] == pytest.approx(control_variate_mean(
        target[:, 0, 0], control[:, 0, 0], control_all[:, 0, 0]), rel=1e-15)
    assert np.isnan(est[1, 0]) and np.isnan(se[1, 0])
    assert np.isfinite(se[0]).all()
    one = control_variate_by_column(target[:1], control[:1], control_all)[1]
    assert np.isnan(one).all()                                 # R = 1: no spread to judge
    with pytest.raises(InputError, match="same trailing shape"):
        control_variate_by_column(target, control, control_all[:, :1])


def test_regression_control_variate_is_unbiased_and_tighter_when_the_slopes_differ():
    # target = 1.2 + 0.6 sin(phi) + noise, control = 1 + sin(phi): the FEM responding to the
    # phases at 0.6 of the VHS's strength (section 3 has 0.63-1.29). For a linear relation
    # the regression estimator is unbiased given the controls, so E = 1.2; its variance
    # is var(noise)/R + 0.6^2 var(c)/N = 2.5e-4 + 3.6e-4, where the difference estimator
    # carries var(0.4 sin(phi))/R = 8e-3 more. The standard error leaves out the noise of
    # the fitted beta, of relative order 1/R (~4 % here). Tolerances: 4 standard errors of
    # the trials' mean; 20 % on a variance (12.6 % is 4 standard errors over 2000 trials,
    # plus that omission).
    r, n, trials = 10, 500, 2000
    reg, dif, se2 = np.empty(trials), np.empty(trials), np.empty(trials)
    for i, (target, control_all) in enumerate(_phase_trials(
            5, lambda phi, rng: 1.2 + 0.6 * np.sin(phi) + rng.normal(0, 0.05, phi.size),
            r, n, trials)):
        e, se = control_variate_by_column(target, control_all[:r], control_all,
                                          beta="regression")
        reg[i], se2[i] = float(e), float(se) ** 2
        dif[i] = control_variate_mean(target, control_all[:r], control_all)
    predicted = 0.05**2 / r + 0.36 * 0.5 / n
    assert abs(reg.mean() - 1.2) < 4 * reg.std() / np.sqrt(trials)
    assert reg.var() == pytest.approx(predicted, rel=0.2)
    assert se2.mean() == pytest.approx(reg.var(), rel=0.2)
    assert dif.var() > 5 * reg.var()
    # too few pairs to fit, or no spread in the control: NaN, not a guess
    est, _ = control_variate_by_column([[1.0], [2.0]], [[1.0], [2.0]], [[1.0], [2.0], [3.0]],
                                       beta="regression")
    assert np.isnan(est).all()
    with pytest.raises(InputError, match="beta"):
        control_variate_by_column([1.0], [1.0], [1.0], beta="fitted")
