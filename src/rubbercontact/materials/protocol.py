"""What a solver needs of a material: the :class:`Material` protocol.

The half-space solver (:func:`rubbercontact.halfspace.solve_sliding`) and the mean-field
theory (:func:`rubbercontact.meanfield.solve`) use a material only through its complex
Young's modulus ``E(ω)``, whether it dissipates at all, and its name. Any object with
these members is a material for them: a Prony series
(:class:`~rubbercontact.materials.GeneralizedMaxwell`), a fractional (Cole–Cole) solid
written in closed form, a tabulated master curve. The FEM cell integrates one internal
variable per Prony branch in time, so it needs what :class:`PronyMaterial` states: the
relaxed modulus and the branches ``(E_i, τ_i)``; any object with them is a material for the
FEM too (:func:`check_prony`).
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from .._validation import require_members
from ..errors import InputError

__all__ = ["Material", "PronyMaterial", "check_material", "check_prony"]

#: The members :func:`check_material` looks for, and what each one is.
_MEMBERS = {
    "complex_modulus": "a method omega [rad/s] -> E(omega) [MPa]",
    "is_elastic": "a bool (True: no dissipation at any frequency)",
    "name": "a str",
}
#: The members :func:`check_prony` looks for, and what each one is.
_PRONY_MEMBERS = {
    "equilibrium_modulus": "the relaxed Young's modulus E_inf [MPa]",
    "moduli": "the branches' Young's moduli E_i [MPa]",
    "relaxation_times": "the branches' relaxation times tau_i [s]",
    "as_dict": "a method -> plain data recorded with the FEM result",
}


class Material(Protocol):
    """A linear viscoelastic solid, as the half-space and mean-field solvers see it.

    Conventions (those of :class:`~rubbercontact.materials.GeneralizedMaxwell`): Young's
    moduli [MPa] at angular frequency ``ω`` [rad/s], ``σ(t) = Re[E(ω) ε̂ e^{iωt}]``, so
    the loss modulus ``Im E(ω) >= 0`` for ``ω > 0`` and ``E(−ω) = conj E(ω)``. The solvers
    evaluate ``E`` at negative frequencies (sliding backwards, the ``q_x < 0`` half of a
    spectrum) and at ``ω = 0`` (the relaxed modulus, the ``v = 0`` limit).
    """

    name: str

    @property
    def is_elastic(self) -> bool:
        """True when ``Im E(ω) = 0`` at every ``ω``: the solvers then use real operators."""
        ...

    def complex_modulus(self, omega) -> np.ndarray:
        """Complex Young's modulus ``E(ω)`` [MPa] at angular frequencies ``omega`` [rad/s],
        any array shape (the result has the shape of ``omega``)."""
        ...


class PronyMaterial(Protocol):
    """A Prony series, as the FEM sees a material.

    ``E(t) = E_∞ + Σ_i E_i exp(−t/τ_i)`` (Young's moduli of an incompressible solid): the
    FEM's constitutive law (:class:`rubbercontact.fem.constitutive.MaterialParameters`)
    scales the shear modulus ``E_∞/3`` by one branch ``E_i/E_∞`` per relaxation time
    ``τ_i`` and integrates each branch's internal variable in time, which a closed-form
    ``E(ω)`` alone does not allow. :class:`~rubbercontact.materials.GeneralizedMaxwell` is
    one.
    """

    @property
    def equilibrium_modulus(self) -> float:
        """Relaxed (long-time) Young's modulus ``E_∞`` [MPa], > 0."""
        ...

    @property
    def moduli(self) -> np.ndarray:
        """Branch Young's moduli ``E_i`` [MPa], shape ``(n,)``."""
        ...

    @property
    def relaxation_times(self) -> np.ndarray:
        """Branch relaxation times ``τ_i`` [s], shape ``(n,)``, > 0."""
        ...

    def as_dict(self) -> dict:
        """Plain data of the material, recorded with the FEM's result."""
        ...


def check_prony(material: object, what: str = "material") -> PronyMaterial:
    """Return ``material`` if it has the members of :class:`PronyMaterial`, else raise.

    Structural, like :func:`check_material`: the members are looked up (and the branch
    arrays' shapes checked, which a numpy error deep in the FEM would otherwise report),
    the class is not.

    Raises
    ------
    InputError
        One line naming what is missing or malformed.
    """
    require_members(material, _PRONY_MEMBERS, methods=("as_dict",), what=what,
                    kind="a Prony series",
                    hint="the FEM integrates each Prony branch in time: use "
                         "rubbercontact.materials.GeneralizedMaxwell (fit_prony fits one to "
                         "DMA data)")
    moduli = np.asarray(material.moduli, dtype=float)
    times = np.asarray(material.relaxation_times, dtype=float)
    if moduli.ndim != 1 or moduli.shape != times.shape:
        raise InputError(f"{what}: moduli [MPa] and relaxation_times [s] must be 1-D arrays "
                         f"of one length, got shapes {moduli.shape} and {times.shape}")
    return material


def check_material(material: object, what: str = "material") -> Material:
    """Return ``material`` if it has the members of :class:`Material`, else raise.

    The check is structural (the members are looked up, the class is not): a solver accepts
    any object that provides them.

    Raises
    ------
    InputError
        One line naming the missing members and what each should be.
    """
    require_members(material, _MEMBERS, methods=("complex_modulus",), what=what,
                    kind="a material",
                    hint="use rubbercontact.materials.GeneralizedMaxwell or any object with "
                         "these members")
    return material
