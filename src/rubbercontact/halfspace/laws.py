"""Local interaction laws ``σ = f(u)`` between the rubber and the rigid surface (paper eq. 24).

Every law maps the local separation ``u`` [mm] to a compressive pressure ``σ`` [MPa] that is
>= 0 and non-increasing in ``u``, and gives its stiffness ``k(u) = −dσ/du >= 0`` [MPa/mm]. A law
may also carry the high-slope companion quantities of the hybrid method: the contact fraction
``α(u)`` (eq. 8) and the shear stress ``Δτ(u)`` [MPa] (eq. 6).

Laws compose: ``LennardJonesRepulsion() + TabulatedLaw(...)`` is a :class:`SumLaw` whose pressure
and stiffness are the sums, and whose ``α`` and ``Δτ`` come from the one member that carries them.

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

from dataclasses import dataclass, field
from typing import ClassVar, Literal, Protocol

import numpy as np
from scipy.interpolate import PchipInterpolator

from .._validation import finite_array, missing_members, positive_scalar, require_members
from ..errors import InputError
from .inverse import InverseWall

__all__ = ["LAW_KINDS", "InteractionLaw", "Law", "LennardJonesRepulsion", "TabulatedLaw", "SumLaw",
           "check_law"]

#: E-folds of the exponential continuation below a table before it turns linear.
_MAX_EFOLDS = 20.0


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


def _pchip_with_slopes(x: np.ndarray, y: np.ndarray) -> PchipInterpolator:
    return PchipInterpolator(x, y, extrapolate=False)


@dataclass(frozen=True, eq=False)
class TabulatedLaw(InteractionLaw):
    """Law interpolated from monotone samples ``(u_j, σ_j)`` (e.g. the FEM high-slope law).

    Parameters
    ----------
    separation
        ``u_j`` [mm], strictly increasing, at least 2 samples.
    pressure
        ``σ_j`` [MPa], >= 0 and non-increasing in ``u``.
    contact_fraction, shear_stress
        Optional companion tables ``α_j`` (in [0, 1]) and ``Δτ_j`` [MPa] at the same ``u_j``.

    Notes
    -----
    Interpolation (monotone by construction, so ``k = −dσ/du >= 0`` everywhere):

    * where ``σ_j > 0``: PCHIP (Fritsch–Carlson, shape preserving) in ``log σ``, which is
      exact for exponential laws and keeps ``σ > 0``;
    * from the last positive sample to the first zero sample: PCHIP in ``σ`` on that segment
      (monotone, reaches 0); ``σ = 0`` (and ``k = 0``) beyond the first ``u_j`` with ``σ_j = 0``;
    * below ``u_0``: stiff continuation, ``log σ`` extended linearly with the end slope of the
      log-PCHIP, but at least as steep as ``d log σ/du = −9/u_0`` when that slope is flatter —
      pressure keeps rising, never a plateau;
    * above the last sample when the table never reaches 0: ``log σ`` extended linearly with
      the end slope (exponential decay; constant only if the table ends flat).

    Companion tables use PCHIP in linear space (no overshoot), are held at their first value
    below ``u_0`` and at their last value above the table, and are 0 where ``σ = 0``. A held
    ``Δτ`` beyond the highest tabulated pressure is the linear theory's full-contact limit
    (there ``Δτ`` no longer depends on ``σ``) and a lower bound while ``Δτ`` still grows
    with ``σ``. The hybrid therefore first continues its FEM law to near full contact
    (:func:`rubbercontact.hybrid.law.continue_with_linear_shape`), so that this hold only
    applies where it is the right limit.
    """

    separation: np.ndarray
    pressure_table: np.ndarray
    contact_fraction_table: np.ndarray | None = None
    shear_stress_table: np.ndarray | None = None
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    def __init__(self, separation, pressure, contact_fraction=None, shear_stress=None) -> None:
        u = finite_array("separation", separation, ndim=1, min_size=2)
        s = finite_array("pressure", pressure, ndim=1, min_size=2)
        if s.shape != u.shape:
            raise InputError(f"pressure: expected {u.size} values like separation, got {s.size}")
        du = np.diff(u)
        if np.any(du <= 0):
            i = int(np.argmax(du <= 0))
            raise InputError(f"separation: must be strictly increasing, got u[{i}]={u[i]} >= "
                             f"u[{i + 1}]={u[i + 1]}")
        if np.any(s < 0):
            i = int(np.argmax(s < 0))
            raise InputError(f"pressure: must be >= 0 MPa, got pressure[{i}]={s[i]}")
        ds = np.diff(s)
        if np.any(ds > 0):
            i = int(np.argmax(ds > 0))
            raise InputError(f"pressure: must be non-increasing in separation, got "
                             f"pressure[{i}]={s[i]} < pressure[{i + 1}]={s[i + 1]}")
        if s[0] <= 0:
            raise InputError("pressure: the first sample must be > 0 MPa")
        tables = {}
        for name, tab in (("contact_fraction", contact_fraction), ("shear_stress", shear_stress)):
            if tab is None:
                tables[name] = None
                continue
            t = finite_array(name, tab, ndim=1, min_size=2)
            if t.shape != u.shape:
                raise InputError(f"{name}: expected {u.size} values like separation, got {t.size}")
            if name == "contact_fraction" and (np.any(t < 0) or np.any(t > 1)):
                raise InputError(f"{name}: values must lie in [0, 1], got {t.min()}..{t.max()}")
            tables[name] = t
        object.__setattr__(self, "separation", u)
        object.__setattr__(self, "pressure_table", s)
        object.__setattr__(self, "contact_fraction_table", tables["contact_fraction"])
        object.__setattr__(self, "shear_stress_table", tables["shear_stress"])
        object.__setattr__(self, "_cache", {})
        self._build()

    def _build(self) -> None:
        u, s = self.separation, self.pressure_table
        zero = np.flatnonzero(s == 0)
        npos = int(zero[0]) if zero.size else u.size
        c = self._cache
        c["npos"] = npos
        c["u_zero"] = float(u[npos]) if zero.size else np.inf
        if npos >= 2:
            logp = _pchip_with_slopes(u[:npos], np.log(s[:npos]))
            d0 = float(logp.derivative()(u[0]))
            d1 = float(logp.derivative()(u[npos - 1]))
        else:
            logp = None
            d0 = d1 = 0.0
        c["logp"] = logp
        # derivatives built once: PPoly.derivative() builds a new polynomial on every call
        c["dlogp"] = None if logp is None else logp.derivative()
        # stiff continuation below the table: never flatter than the first secant nor than
        # one e-fold over the table's span (a strictly rising pressure, no plateau)
        secant = (np.log(s[1]) - np.log(s[0])) / (u[1] - u[0]) if s[1] > 0 else 0.0
        c["slope_lo"] = min(d0, secant, -1.0 / (u[-1] - u[0]))
        c["slope_hi"] = min(d1, 0.0)
        # last segment (last positive sample -> first zero sample), linear-space PCHIP
        c["tail"] = (_pchip_with_slopes(u[npos - 1:npos + 1], s[npos - 1:npos + 1])
                     if zero.size else None)
        c["dtail"] = None if c["tail"] is None else c["tail"].derivative()
        c["companions"] = {}
        for name, tab in (("alpha", self.contact_fraction_table),
                          ("tau", self.shear_stress_table)):
            c["companions"][name] = None if tab is None else _pchip_with_slopes(u, tab)

    # -- evaluation ----------------------------------------------------------------
    def _eval(self, u: np.ndarray, stiffness: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """``(σ(u), k(u) = −σ'(u))``; ``k`` is left 0 unless ``stiffness`` (the law is
        evaluated on the whole grid in every Newton and line-search step).

        A table that reaches ``σ = 0`` is evaluated only where ``u`` is below that
        separation (its support): on a rough surface a few percent of the grid, so the
        whole-grid work is one comparison and the scatter of the results.
        """
        c = self._cache
        u = np.asarray(u, dtype=float)
        sig = np.zeros(u.shape)
        k = np.zeros(u.shape)
        flat = u.reshape(-1)
        if np.isfinite(c["u_zero"]):
            idx = np.flatnonzero(flat < c["u_zero"])
            if idx.size == 0:
                return sig, k
            s_in, k_in = self._eval_flat(flat[idx], stiffness)
            sig.reshape(-1)[idx] = s_in
            k.reshape(-1)[idx] = k_in
            return sig, k
        s_in, k_in = self._eval_flat(flat, stiffness)
        return s_in.reshape(u.shape), k_in.reshape(u.shape)

    def _eval_flat(self, u: np.ndarray, stiffness: bool) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_eval` on a 1-D array of separations."""
        c = self._cache
        tab_u, tab_s = self.separation, self.pressure_table
        npos = c["npos"]
        sig = np.zeros(u.shape)
        k = np.zeros(u.shape)
        u0, s0 = tab_u[0], tab_s[0]
        lo = u < u0
        if np.any(lo):
            a = -c["slope_lo"]
            t = a * (u0 - u[lo])
            # exponential rise for 20 e-folds, then linear (C1), so far extrapolation stays
            # finite and monotone
            tc = np.minimum(t, _MAX_EFOLDS)
            sig[lo] = s0 * np.exp(tc) * (1.0 + (t - tc))
            k[lo] = a * s0 * np.exp(tc)
        upos = tab_u[npos - 1]
        mid = (u >= u0) & (u <= upos)
        if np.any(mid) and c["logp"] is not None:
            um = u[mid]
            sig[mid] = np.exp(c["logp"](um))
            if stiffness:
                k[mid] = -c["dlogp"](um) * sig[mid]
        elif np.any(mid):  # single positive sample: only u == u0 can land here
            sig[mid] = s0
        if c["tail"] is not None:
            seg = (u > upos) & (u < c["u_zero"])
            if np.any(seg):
                sig[seg] = c["tail"](u[seg])
                if stiffness:
                    k[seg] = -c["dtail"](u[seg])
        else:
            hi = u > upos
            if np.any(hi):
                sig[hi] = tab_s[npos - 1] * np.exp(c["slope_hi"] * (u[hi] - upos))
                k[hi] = -c["slope_hi"] * sig[hi]
        return np.maximum(sig, 0.0), np.maximum(k, 0.0)

    def pressure(self, u):
        return self._eval(u, stiffness=False)[0]

    def stiffness(self, u):
        return self._eval(u)[1]

    def pressure_and_stiffness(self, u):
        return self._eval(u)   # the stiffness is computed with the pressure anyway

    def _companion(self, name: str, u) -> np.ndarray | None:
        interp = self._cache["companions"][name]
        if interp is None:
            return None
        u = np.asarray(u, dtype=float)
        tab = self.contact_fraction_table if name == "alpha" else self.shear_stress_table
        uc = np.clip(u, self.separation[0], self.separation[-1])
        out = interp(uc)
        out = np.where(u < self.separation[0], tab[0], out)
        out = np.where(u > self.separation[-1], tab[-1], out)
        out = np.where(u >= self._cache["u_zero"], 0.0, out)
        if name == "alpha":
            out = np.clip(out, 0.0, 1.0)
        return out

    def contact_fraction(self, u):
        return self._companion("alpha", u)

    def shear_stress(self, u):
        return self._companion("tau", u)

    def in_contact(self, u):
        return self.pressure(u) > 0

    def describe(self) -> dict:
        return {"law": "TabulatedLaw", "samples": int(self.separation.size),
                "separation_range": [float(self.separation[0]), float(self.separation[-1])],
                "has_contact_fraction": self.contact_fraction_table is not None,
                "has_shear_stress": self.shear_stress_table is not None}


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
