"""The phase-averaged eq. 28 of ``benchmarks/validate.py`` on hand-made realizations."""

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import validate  # noqa: E402


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
    curves = validate.phase_mean_curves(data)
    a_all, mu_all = (x.mean(axis=0) for x in data["all"]["vhs"])
    np.testing.assert_allclose(curves["phase"]["fem"][0], a_all, rtol=1e-13)
    np.testing.assert_allclose(curves["phase"]["fem"][1], mu_all - 0.02, rtol=1e-13)
    # the plain curves are the means over the first r
    np.testing.assert_allclose(curves["plain"]["fem"][1],
                               data["fem"][1].mean(axis=0), rtol=1e-13)


def test_phase_averaged_eq28_is_the_offset_over_the_fem_friction():
    data = _data()
    (e, ci), = validate.eq28_phase_averaged({10.0: data}, resamples=200).values()
    # FEM and hybrids share the area curve, and linear interpolation keeps a constant
    # offset: e = mean_k 0.02 / μ_FEM(A_k) over the 4 common areas, exactly.
    curves = validate.phase_mean_curves(data)["phase"]
    areas, mus = validate._common_areas({m: curves[m] for m in ("fem", "vhs")})
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
    est = validate.phase_mean_curves(data)["phase"]["fem"][1]
    vhs = data["paired"]["vhs"][1]
    keep = np.arange(10) != 3
    expected = data["all"]["vhs"][1][:, 1].mean() + (fem_mu[keep, 1] - vhs[keep, 1]).mean()
    assert est[1] == pytest.approx(expected, rel=1e-13)
    assert np.all(np.isfinite(est))
