"""What a solver needs of a material: the :class:`Material` protocol.

The half-space solver (:func:`rubbercontact.halfspace.solve_sliding`) and the mean-field
theory (:func:`rubbercontact.meanfield.solve`) use a material only through its complex
Young's modulus ``E(ω)``, whether it dissipates at all, and its name. Any object with
these members is a material for them: a Prony series
(:class:`~rubbercontact.materials.GeneralizedMaxwell`), a fractional (Cole–Cole) solid
written in closed form, a tabulated master curve. The FEM cell integrates the Prony
series' internal variables in time and so still needs a
:class:`~rubbercontact.materials.GeneralizedMaxwell`.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from ..errors import InputError

__all__ = ["Material", "check_material"]

#: The members :func:`check_material` looks for, and what each one is.
_MEMBERS = {
    "complex_modulus": "a method omega [rad/s] -> E(omega) [MPa]",
    "is_elastic": "a bool (True: no dissipation at any frequency)",
    "name": "a str",
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


def check_material(material: object, what: str = "material") -> Material:
    """Return ``material`` if it has the members of :class:`Material`, else raise.

    The check is structural (the members are looked up, the class is not): a solver accepts
    any object that provides them.

    Raises
    ------
    InputError
        One line naming the missing members and what each should be.
    """
    missing = [m for m in _MEMBERS if not hasattr(material, m)]
    if not missing and not callable(material.complex_modulus):
        missing = ["complex_modulus"]
    if missing:
        wants = "; ".join(f"{m}: {_MEMBERS[m]}" for m in missing)
        raise InputError(f"{what}: {type(material).__name__} is not a material (missing "
                         f"{wants}); use rubbercontact.materials.GeneralizedMaxwell or any "
                         f"object with these members")
    return material
