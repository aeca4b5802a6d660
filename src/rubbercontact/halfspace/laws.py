"""Local interaction laws ``σ = f(u)`` between the rubber and the rigid surface (paper eq. 24).

Every law maps the local separation ``u`` [mm] to a compressive pressure ``σ`` [MPa] that is
>= 0 and non-increasing in ``u``, and gives its stiffness ``k(u) = −dσ/du >= 0`` [MPa/mm]. A law
may also carry the high-slope companion quantities of the hybrid method: the contact fraction
``α(u)`` (eq. 8) and the shear stress ``Δτ(u)`` [MPa] (eq. 6).

Laws compose: ``LennardJonesRepulsion() + TabulatedLaw(...)`` (:mod:`.tabulated`) is a
:class:`SumLaw` whose pressure and stiffness are the sums, and whose ``α`` and ``Δτ`` come from
the one member that carries them.

Every law declares its :attr:`~InteractionLaw.kind`: ``"wall"`` for a stiff stand-in for the hard
wall (the half-space solver then treats it as the wall of the wall + soft algorithm,
:mod:`.walls`), ``"soft"`` for any other law. A new law class states its kind; the solvers read
the attribute, never the class.

A law need not inherit from :class:`InteractionLaw`: any object with the members of
:class:`Law` (``kind``, ``pressure``, ``stiffness``) is one. :func:`check_law` checks them
structurally and fills the optional members (``contact_fraction``, ``resolve``, ...) with
:class:`InteractionLaw`'s defaults where the object has none.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Literal, Protocol

import numpy as np

from .._validation import missing_members, positive_scalar, require_members
from ..errors import InputError
from .inverse import InverseWall

__all__ = ["LAW_KINDS", "InteractionLaw", "Law", "LennardJonesRepulsion", "SumLaw", "check_law"]

#: The kinds a law may declare (see the module docstring).
LAW_KINDS = ("wall", "soft")


class InteractionLaw:
    """Base class: subclasses implement :meth:`pressure` and :meth:`stiffness`.

    Attributes
    ----------
    kind
        ``"wall"`` (a stiff stand-in for the hard wall, solved by the wall + soft algorithm
        when combined with soft laws) or ``"soft"`` (the default).
    """

    kind: ClassVar[Literal["wall", "soft"]] = "soft"

    def pressure(self, u: np.ndarray) -> np.ndarray:  # pragma: no cover - abstract
        """Pressure ``σ(u)`` [MPa], >= 0, non-increasing."""
        raise NotImplementedError

    def stiffness(self, u: np.ndarray) -> np.ndarray:  # pragma: no cover - abstract
        """Stiffness ``k(u) = −dσ/du`` [MPa/mm], >= 0."""
        raise NotImplementedError

    def pressure_and_stiffness(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(σ(u), k(u))`` [MPa, MPa/mm], the same arrays as :meth:`pressure` and
        :meth:`stiffness`; a law that computes both in one pass overrides it."""
        return self.pressure(u), self.stiffness(u)

    def contact_fraction(self, u: np.ndarray) -> np.ndarray | None:
        """Local contact fraction ``α(u)`` in [0, 1], or ``None`` when the law carries none."""
        return None

    def shear_stress(self, u: np.ndarray) -> np.ndarray | None:
        """Local hysteretic shear stress ``Δτ(u)`` [MPa], or ``None``."""
        return None

    def in_contact(self, u: np.ndarray) -> np.ndarray:
        """Boolean mask: where the law is in its repulsive "contact" range."""
        return self.pressure(u) > 0

    def resolve(self, length_scale: float, pressure_scale: float) -> InteractionLaw:
        """Return the law with parameters left as ``None`` filled from the problem's scales."""
        return self

    @property
    def members(self) -> tuple[InteractionLaw, ...]:
        """The laws this one sums: ``(self,)``, or a :class:`SumLaw`'s terms."""
        return (self,)

    def inverse(self) -> InverseWall | None:
        """The inverse form ``u = g(σ)`` the mixed Newton may linearise instead of ``f``
        (:mod:`.newton`), or ``None`` (the default: Newton on ``f`` itself)."""
        return None

    def describe(self) -> dict:
        """Plain-data description (for result attributes)."""
        return {"law": type(self).__name__}

    def __add__(self, other: Law) -> SumLaw:
        if _missing(other):
            return NotImplemented
        return SumLaw(self, other)

    def __radd__(self, other: Law) -> SumLaw:
        # ``user_law + LennardJonesRepulsion()``: a protocol law need not define ``__add__``
        if _missing(other):
            return NotImplemented
        return SumLaw(other, self)


class Law(Protocol):
    """What the solvers need of an interaction law (see the module docstring).

    The optional members of :class:`InteractionLaw` (``contact_fraction``,
    ``shear_stress``, ``in_contact``, ``resolve``, ``members``, ``inverse``, ``describe``,
    ``pressure_and_stiffness``)
    are used when present; :func:`check_law` supplies the defaults otherwise.
    """

    #: ``"wall"`` or ``"soft"`` (:data:`LAW_KINDS`).
    kind: str

    def pressure(self, u: np.ndarray) -> np.ndarray:
        """Pressure ``σ(u)`` [MPa], >= 0, non-increasing in the separation ``u`` [mm]."""
        ...

    def stiffness(self, u: np.ndarray) -> np.ndarray:
        """Stiffness ``k(u) = −dσ/du`` [MPa/mm], >= 0."""
        ...


#: The members :func:`check_law` requires, and what each one is.
_LAW_MEMBERS = {
    "kind": f"one of {LAW_KINDS}",
    "pressure": "a method u [mm] -> sigma [MPa]",
    "stiffness": "a method u [mm] -> -dsigma/du [MPa/mm]",
}
#: Those of them that must be callable.
_LAW_METHODS = ("pressure", "stiffness")
#: The members :func:`check_law` fills from :class:`InteractionLaw` when a law lacks them.
_OPTIONAL_MEMBERS = ("contact_fraction", "shear_stress", "in_contact", "resolve", "members",
                     "inverse", "describe", "pressure_and_stiffness")


def _missing(law: object) -> list[str]:
    """The required members ``law`` lacks (empty: it is a :class:`Law`)."""
    return missing_members(law, _LAW_MEMBERS, _LAW_METHODS)


def check_law(law: object, what: str = "law") -> InteractionLaw:
    """Return ``law`` as a law the solvers can use, or raise.

    Structural, like :func:`rubbercontact.materials.check_material`: the members of
    :class:`Law` are looked up, the class is not. An object with all of
    :class:`InteractionLaw`'s members is returned as it is; one with only the required
    members is wrapped so that the optional ones take :class:`InteractionLaw`'s defaults
    (no companions ``α``/``Δτ``, "in contact" where ``σ > 0``, nothing to resolve, no
    inverse form).

    Raises
    ------
    InputError
        One line naming what is missing, or the undeclared kind.
    """
    require_members(law, _LAW_MEMBERS, methods=_LAW_METHODS, what=what,
                    kind="an interaction law", hint="see rubbercontact.halfspace.laws")
    if law.kind not in LAW_KINDS:
        raise InputError(f"{what}: {type(law).__name__} declares kind {law.kind!r}; expected "
                         f"one of {LAW_KINDS}")
    if all(hasattr(law, m) for m in _OPTIONAL_MEMBERS):
        return law
    return _ProtocolLaw(law)


class _ProtocolLaw(InteractionLaw):
    """A :class:`Law` with only some of the optional members: the others are the base's."""

    def __init__(self, law: Law) -> None:
        self.law = law

    @property
    def kind(self) -> str:  # type: ignore[override]  # the wrapped law's, per instance
        return self.law.kind

    def pressure(self, u):
        return self.law.pressure(u)

    def stiffness(self, u):
        return self.law.stiffness(u)

    def _optional(self, name: str, *args):
        own = getattr(self.law, name, None)
        return getattr(super(), name)(*args) if own is None else own(*args)

    def pressure_and_stiffness(self, u):
        return self._optional("pressure_and_stiffness", u)

    def contact_fraction(self, u):
        return self._optional("contact_fraction", u)

    def shear_stress(self, u):
        return self._optional("shear_stress", u)

    def in_contact(self, u):
        return self._optional("in_contact", u)

    def inverse(self):
        return self._optional("inverse")

    def resolve(self, length_scale: float, pressure_scale: float) -> InteractionLaw:
        own = getattr(self.law, "resolve", None)
        return self if own is None else check_law(own(length_scale, pressure_scale))

    @property
    def members(self) -> tuple[InteractionLaw, ...]:
        own = getattr(self.law, "members", None)
        return (self,) if own is None else tuple(check_law(m) for m in own)

    def describe(self) -> dict:
        own = getattr(self.law, "describe", None)
        return {"law": type(self.law).__name__} if own is None else own()

    def __repr__(self) -> str:
        return repr(self.law)


def _ninth_power(r: np.ndarray) -> np.ndarray:
    """``r**9`` by three squarings and a product: the wall is evaluated on every grid point
    in every Newton and root-finding step, where ``np.power`` with a float exponent is the
    dearer operation."""
    r2 = r * r
    r4 = r2 * r2
    return r4 * r4 * r


@dataclass(frozen=True)
class LennardJonesRepulsion(InteractionLaw):
    """Adhesionless integrated Lennard-Jones wall–wall repulsion ``σ = p_ref (ℓ/u)⁹``.

    Integrating the repulsive ``r⁻¹²`` term of the Lennard-Jones potential over two half-spaces
    gives a wall–wall pressure ``∝ u⁻⁹``. Here it is used as a smooth, very stiff stand-in for a
    hard wall: ``σ`` rises by a factor 2 every time ``u`` shrinks by 8 %, so in contact the gap is
    ``u ≈ ℓ`` whatever the pressure.

    Parameters
    ----------
    length
        ``ℓ`` [mm], the separation at which ``σ = p_ref``. ``None`` (default): ``ℓ =
        relative_length × rms height of the surface`` (set by the solver), i.e. a hard wall at the
        scale of the roughness.
    reference_pressure
        ``p_ref`` [MPa]. ``None`` (default): the imposed mean pressure ``σ0``.
    relative_length
        ``ℓ / h_rms`` used when ``length`` is ``None``; default ``1e-5`` (the contact edge is then
        blurred over ~``(1e-5)^(2/3) ≈ 5e-4`` of a wavelength, below a grid step at N = 4096).

    Notes
    -----
    Below ``u_min = ℓ/4`` (``σ = 4⁹ p_ref``) the law continues linearly with the slope at
    ``u_min``, so it is finite for any ``u`` (Newton trial steps may overshoot into ``u <= 0``).
    "In contact" means ``u < 2ℓ`` (``σ > p_ref/512``).
    """

    kind: ClassVar[Literal["wall", "soft"]] = "wall"

    length: float | None = None
    reference_pressure: float | None = None
    relative_length: float = 1e-5

    def __post_init__(self) -> None:
        if self.length is not None:
            positive_scalar("length", self.length, unit="mm")
        if self.reference_pressure is not None:
            positive_scalar("reference_pressure", self.reference_pressure, unit="MPa")
        positive_scalar("relative_length", self.relative_length)

    def resolve(self, length_scale: float, pressure_scale: float) -> LennardJonesRepulsion:
        length = self.length if self.length is not None else self.relative_length * length_scale
        pref = self.reference_pressure if self.reference_pressure is not None else pressure_scale
        return LennardJonesRepulsion(float(length), float(pref), self.relative_length)

    def inverse(self) -> InverseWall | None:
        """``u = ℓ (p_ref/σ)^(1/9)`` once resolved (``None`` while a parameter is unset)."""
        if self.length is None or self.reference_pressure is None:
            return None
        return InverseWall(float(self.length), float(self.reference_pressure))

    def _params(self) -> tuple[float, float]:
        if self.length is None or self.reference_pressure is None:
            raise InputError("law: LennardJonesRepulsion parameters are unresolved; pass length= "
                             "and reference_pressure= or let solve_sliding resolve them")
        return self.length, self.reference_pressure

    def pressure(self, u):
        ell, p = self._params()
        u = np.asarray(u, dtype=float)
        umin = 0.25 * ell
        us = np.maximum(u, umin)
        sig = p * _ninth_power(ell / us)
        below = u < umin
        if np.any(below):
            s_min = p * 4.0**9
            k_min = 9.0 * s_min / umin
            sig = np.where(below, s_min + k_min * (umin - u), sig)
        return sig

    def stiffness(self, u):
        ell, p = self._params()
        u = np.asarray(u, dtype=float)
        us = np.maximum(u, 0.25 * ell)
        return 9.0 * p * _ninth_power(ell / us) / us

    def in_contact(self, u):
        ell, _ = self._params()
        return np.asarray(u) < 2.0 * ell

    def describe(self) -> dict:
        return {"law": "LennardJonesRepulsion", "length": self.length,
                "reference_pressure": self.reference_pressure}


class SumLaw(InteractionLaw):
    """Sum of laws: pressures and stiffnesses add; ``α``/``Δτ`` come from the member carrying them.

    "In contact" is where any member is in contact.
    """

    def __init__(self, *laws: Law) -> None:
        flat: list[InteractionLaw] = []
        for law in laws:
            flat.extend(check_law(law).members)
        if not flat:
            raise InputError("law: SumLaw needs at least one law")
        for name in ("contact_fraction", "shear_stress"):
            n = sum(1 for law in flat if getattr(law, f"{name}_table", None) is not None)
            if n > 1:
                raise InputError(f"law: {n} members carry {name}; at most one may")
        self.laws = tuple(flat)

    @property
    def members(self) -> tuple[InteractionLaw, ...]:
        return self.laws

    def pressure(self, u):
        return sum(law.pressure(u) for law in self.laws)

    def stiffness(self, u):
        return sum(law.stiffness(u) for law in self.laws)

    def pressure_and_stiffness(self, u):
        pairs = [law.pressure_and_stiffness(u) for law in self.laws]
        return sum(p for p, _ in pairs), sum(k for _, k in pairs)

    def _first(self, name: str, u):
        for law in self.laws:
            out = getattr(law, name)(u)
            if out is not None:
                return out
        return None

    def contact_fraction(self, u):
        return self._first("contact_fraction", u)

    def shear_stress(self, u):
        return self._first("shear_stress", u)

    def in_contact(self, u):
        mask = np.zeros(np.shape(u), dtype=bool)
        for law in self.laws:
            mask |= law.in_contact(u)
        return mask

    def resolve(self, length_scale: float, pressure_scale: float) -> SumLaw:
        return SumLaw(*(law.resolve(length_scale, pressure_scale) for law in self.laws))

    def describe(self) -> dict:
        return {"law": "SumLaw", "members": [law.describe() for law in self.laws]}

    def __repr__(self) -> str:
        return "SumLaw(" + ", ".join(repr(law) for law in self.laws) + ")"
