"""The FEM takes any Prony series (:class:`rubbercontact.materials.PronyMaterial`), not one
class, and refuses a material without Prony branches in one line.

A plain dataclass carrying ``E_∞``, the branches ``(E_i, τ_i)`` and ``as_dict`` — no
:class:`GeneralizedMaxwell` — must relax in the FEM's constitutive law as its closed-form
``E(t) = E_∞ + Σ E_i exp(−t/τ_i)``, and a whole sliding test on it must be the test of the
same series as a :class:`GeneralizedMaxwell` (the FEM reads nothing else of a material).
A closed-form Cole–Cole solid (the ``cole_cole`` fixture) has ``E(ω)`` but no branches
to integrate in time.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.fem.constitutive import MaterialParameters
from rubbercontact.materials import GeneralizedMaxwell, PronyMaterial, check_prony
from rubbercontact.roughness import SineSeries


@dataclass(frozen=True)
class PlainProny:
    """A Prony series that is not a :class:`GeneralizedMaxwell`: Young's moduli [MPa],
    relaxation times [s]."""

    equilibrium_modulus: float = 3.0
    moduli: np.ndarray = field(default_factory=lambda: np.array([30.0, 300.0]))
    relaxation_times: np.ndarray = field(default_factory=lambda: np.array([1e-2, 1e-5]))

    def as_dict(self) -> dict:
        return {"equilibrium_modulus": self.equilibrium_modulus,
                "moduli": list(self.moduli), "relaxation_times": list(self.relaxation_times)}

    def relaxation_modulus(self, t: np.ndarray) -> np.ndarray:
        """Closed form ``E(t)`` [MPa] at times ``t`` [s]."""
        t = np.asarray(t, float)[..., None]
        return self.equilibrium_modulus + np.sum(
            self.moduli * np.exp(-t / self.relaxation_times), axis=-1)


PLAIN: PronyMaterial = PlainProny()


def test_a_prony_series_of_another_class_relaxes_in_the_fem_as_its_closed_form(step_shear):
    # finite simple shear γ applied in 1e-15 s and held: the neo-Hookean branches give
    # σ_xy = γ E(t)/3 exactly, each branch relaxing on its own τ_i
    times, sxy = step_shear(PLAIN, np.geomspace(1e-8, 0.05, 30), shear=0.5)
    # the 1e-15 s step is glassy to 1e-15/1e-5 relative
    np.testing.assert_allclose(sxy, 0.5 * PLAIN.relaxation_modulus(times) / 3.0, rtol=1e-8)


def test_a_sliding_test_on_another_prony_class_is_the_generalized_maxwell_one():
    gm = GeneralizedMaxwell(PLAIN.equilibrium_modulus, PLAIN.moduli, PLAIN.relaxation_times)
    surf = SineSeries([0.125], [0.004])
    a = rc.fem.sliding_test(surf, PLAIN, 0.2, 10.0, (16, 8))
    b = rc.fem.sliding_test(surf, gm, 0.2, 10.0, (16, 8))
    assert 0.0 < b.contact_fraction < 1.0 and b.friction > 0.0   # partial, dissipative
    # the FEM reads E∞, E_i, τ_i only: the same arithmetic, the same numbers
    assert a.friction == b.friction
    assert a.contact_fraction == b.contact_fraction


def test_the_fem_refuses_a_material_without_prony_branches_in_one_line(cole_cole):
    surf = SineSeries([0.125], [0.004])
    with pytest.raises(InputError, match="not a Prony series") as err:
        rc.fem.sliding_test(surf, cole_cole(), 0.2, 10.0, (16, 8))
    msg = str(err.value)
    assert "\n" not in msg
    assert all(m in msg for m in ("equilibrium_modulus", "moduli", "relaxation_times"))
    with pytest.raises(InputError, match="not a Prony series"):
        MaterialParameters.from_material(cole_cole())


def test_branch_arrays_of_different_lengths_are_refused():
    bad = PlainProny(moduli=np.array([30.0, 300.0]), relaxation_times=np.array([1e-2]))
    with pytest.raises(InputError, match="1-D arrays of one length"):
        check_prony(bad)
    assert check_prony(rc.materials.sbr()) is not None
