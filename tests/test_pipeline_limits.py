"""The physical range of loads and speeds (rubbercontact.pipeline.limits)."""

import pytest

from rubbercontact.errors import InputError
from rubbercontact.materials import GeneralizedMaxwell
from rubbercontact.pipeline.limits import check_pressures, check_velocity


def test_pressure_bound_is_the_glassy_modulus():
    # E_g = E_inf + sum E_i: the modulus at infinite frequency
    rubber = GeneralizedMaxwell(equilibrium_modulus=2.0, moduli=[3.0, 5.0],
                                relaxation_times=[1e-3, 1.0])
    check_pressures([1e-6, 9.99], rubber, "loads.pressures")
    for bad in (10.0, 1e6, 0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(InputError, match=r"loads.pressures: .*\(0, 10\) MPa"):
            check_pressures([0.5, bad], rubber, "loads.pressures")
    with pytest.raises(InputError, match=r"\(0, 7\) MPa"):
        check_pressures([7.0], GeneralizedMaxwell.elastic(7.0), "p")
    with pytest.raises(InputError, match="expected a number"):
        check_pressures(["abc"], rubber, "p")


def test_speed_sign():
    check_velocity(0.0, "velocity")
    check_velocity(1e-9, "velocity", static=False)
    with pytest.raises(InputError, match=r"velocity: sliding speed -10 mm/s: must be >= 0"):
        check_velocity(-10.0, "velocity")
    with pytest.raises(InputError, match=r"must be > 0 mm/s"):
        check_velocity(0.0, "velocity", static=False)
    with pytest.raises(InputError):
        check_velocity(float("nan"), "velocity")
