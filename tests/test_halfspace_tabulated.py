"""The tabulated law's vectorised evaluation against scipy's own PCHIP, and the GMRES
combination of a single-precision basis against numpy's product."""

import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator

from rubbercontact.halfspace import TabulatedLaw
from rubbercontact.halfspace.krylov import _add_combination
from rubbercontact.halfspace.tabulated import _MAX_CELLS, _Pieces, _ppoly


def _points(x: np.ndarray, rng) -> np.ndarray:
    """Random points over and beyond ``x``, every breakpoint and its two neighbours."""
    span = x[-1] - x[0]
    return np.concatenate([rng.uniform(x[0] - 0.3 * span, x[-1] + 0.3 * span, 20000), x,
                           np.nextafter(x, np.inf), np.nextafter(x, -np.inf)])


@pytest.mark.parametrize("spacing", ["uniform", "graded", "clustered"])
def test_pieces_as_searchsorted(spacing):
    rng = np.random.default_rng(3)
    x = {"uniform": np.linspace(0.0, 1e-3, 21),
         "graded": 1e-3 * np.linspace(0.0, 1.0, 31) ** 2 + 2e-6,
         "clustered": np.r_[0.0, 1e-12, np.linspace(1e-3, 2e-3, 5)]}[spacing]
    pieces = _Pieces(x)
    assert (pieces.lut is None) == (spacing == "clustered")   # bisection past _MAX_CELLS
    assert pieces.lut is None or pieces.lut.size <= _MAX_CELLS + 1
    u = _points(x, rng)
    expected = np.clip(np.searchsorted(x, u, side="right") - 1, 0, x.size - 2)
    np.testing.assert_array_equal(pieces(u), expected)


def test_ppoly_is_scipys_pchip():
    rng = np.random.default_rng(4)
    x = np.sort(rng.uniform(0.0, 1e-3, 25))
    pp = PchipInterpolator(x, np.log(np.linspace(3.0, 0.01, 25)), extrapolate=False)
    u = _points(x, rng)
    u = u[(u >= x[0]) & (u <= x[-1])]
    j = _Pieces(x)(u)
    for poly in (pp, pp.derivative()):
        np.testing.assert_array_equal(_ppoly(poly, u, j), poly(u))   # the same numbers


def test_tabulated_law_closed_form_exponential():
    # PCHIP in log σ is exact for an exponential law, inside the table and in its
    # continuation above it
    u = np.linspace(1e-3, 1e-2, 13)
    law = TabulatedLaw(u, 2.0 * np.exp(-u / 2e-3))
    q = np.linspace(1e-3, 2e-2, 5001)
    sig, k = law.pressure_and_stiffness(q)
    np.testing.assert_allclose(sig, 2.0 * np.exp(-q / 2e-3), rtol=1e-12)
    np.testing.assert_allclose(k, sig / 2e-3, rtol=1e-9)


def test_add_combination_single_basis():
    rng = np.random.default_rng(5)
    for kk, n in ((1, 70001), (9, 50000), (33, 40000)):
        y = rng.standard_normal(kk)
        z = rng.standard_normal((kk, n)).astype(np.float32)
        x0 = rng.standard_normal(n)
        x = x0.copy()
        _add_combination(x, y, z)
        np.testing.assert_allclose(x, x0 + y @ z, rtol=1e-14, atol=1e-14)


def test_tabulated_law_non_finite_separations():
    # NaN carries no pressure (not below any sample), ±inf the table's limits
    u = np.linspace(1e-3, 1e-2, 13)
    for law in (TabulatedLaw(u, 2.0 * np.exp(-u / 2e-3)),
                TabulatedLaw(u, np.r_[2.0 * np.exp(-u[:-1] / 2e-3), 0.0])):
        sig, k = law.pressure_and_stiffness(np.array([np.nan, np.inf, -np.inf, 5e-3]))
        assert sig[0] == 0.0 and k[0] == 0.0
        assert sig[1] == 0.0 and sig[2] > sig[3] > 0.0
