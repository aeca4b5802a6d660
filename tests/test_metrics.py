"""Eq. 28 and area interpolation on hand-made curves."""

import numpy as np
import pytest

from rubbercontact.errors import InputError
from rubbercontact.hybrid.metrics import interpolate_at_areas, mean_relative_error


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
