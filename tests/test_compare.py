"""rubbercontact.compare: eq. 28 at equal area and an uncertainty that contains it.

Synthetic random-phase ensembles with a known truth: the FEM's mean friction-area curve
``μ(A) = 0.2 + 2A`` and a model off it by a known relative bias, each realization with its
own scatter (the phases), the model's scatter partly shared with the FEM's (the same
crests), as the VHS and the FEM share theirs.
"""

from __future__ import annotations

import numpy as np
import pytest

from rubbercontact.compare import eq28_bounds, eq28_of_curves

LOADS = np.array([0.15, 0.35, 0.8])


def ensemble(r: int, bias: float, seed: int = 1) -> dict:
    """``{model: (A, μ)}`` arrays (realization, load) with the model ``bias`` off the FEM."""
    rng = np.random.default_rng(seed)
    area = 0.02 + 0.06 * LOADS / LOADS[-1]
    a_fem = area * (1 + 0.05 * rng.standard_normal((r, LOADS.size)))
    shared = 0.15 * rng.standard_normal((r, LOADS.size))
    mu_fem = (0.2 + 2 * area) * (1 + shared)
    mu_mod = (0.2 + 2 * area) * (1 + bias) * (1 + 0.3 * shared
                                              + 0.03 * rng.standard_normal((r, LOADS.size)))
    return {"fem": (a_fem, mu_fem), "hybrid": (np.tile(area, (r, 1)), mu_mod)}


def bounds(data: dict, resamples: int = 400):
    r = data["fem"][0].shape[0]

    def curves_of(idx):
        idx = np.arange(r) if idx is None else idx
        return {m: (a[idx].mean(axis=0), mu[idx].mean(axis=0)) for m, (a, mu) in data.items()}

    return eq28_bounds(curves_of, lambda rng: rng.integers(0, r, r), ["hybrid"],
                       resamples=resamples)["hybrid"], curves_of


@pytest.mark.parametrize("seed", range(6))
def test_the_interval_contains_the_estimate_even_at_zero_error(seed):
    # At a true error of zero the percentile interval of mean|r| lies above the estimate
    # (the fold); the range over the signed errors' intervals contains it by construction.
    res, curves_of = bounds(ensemble(6, 0.0, seed))
    assert res.low <= res.error <= res.high
    assert np.all((res.signed_low <= res.signed) & (res.signed <= res.signed_high))
    # the same eq. 28 as the paper's statistic on the same curves
    assert res.error == pytest.approx(eq28_of_curves(curves_of(None), ["hybrid"])["hybrid"])


def test_the_uncertainty_shrinks_as_one_over_root_r():
    # 16 -> 64 realizations: the signed intervals narrow by 1/2 (sqrt 4); the bootstrap's
    # own quantile noise at 400 resamples and the realizations drawn allow 0.35-0.7.
    widths = [float(np.mean(bounds(ensemble(r, 0.1, seed=3))[0].signed_high
                            - bounds(ensemble(r, 0.1, seed=3))[0].signed_low))
              for r in (16, 64)]
    assert 0.35 < widths[1] / widths[0] < 0.7


def test_a_known_bias_is_found_within_the_interval():
    # 10 % high on 400 realizations: the signed errors' intervals hold +10 %, the eq. 28
    # range holds 0.10, and the interval is narrow (the scatter's standard error ~1 %).
    res, _ = bounds(ensemble(400, 0.10, seed=5))
    assert np.all((res.signed_low <= 0.10) & (0.10 <= res.signed_high))
    assert res.low <= 0.10 <= res.high and res.high - res.low < 0.05
    assert res.bias == pytest.approx(0.10, abs=0.02)


def test_the_folded_percentile_interval_is_what_failed():
    # The interval VALIDATION.md printed before (percentiles of the resampled eq. 28): at a
    # true error of zero it can lie above the estimate, as 0.6 % (0.7-4.8) did on section 3
    # at 50 mm/s; the new range never does (test above).
    from rubbercontact.hybrid.metrics import bootstrap_interval

    above = 0
    for seed in range(20):
        data = ensemble(6, 0.0, seed)
        res, curves_of = bounds(data, resamples=100)
        assert res.low <= res.error <= res.high
        e = eq28_of_curves(curves_of(None), ["hybrid"])["hybrid"]
        low, _, _ = bootstrap_interval(
            lambda idx, c=curves_of: eq28_of_curves(c(idx), ["hybrid"])["hybrid"], 6,
            resamples=400)
        above += e < low
    assert above >= 1   # seeded: deterministic
