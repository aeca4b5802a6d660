r"""The mean-field models' options: one frozen object per model, built of small strategies.

Two models read a spectrum (docs/validation/meanfield.md compares them with the BEM):

- :class:`MeanFieldOptions` — Persson's theory (the models ``meanfield`` and, with a law,
  ``meanfield-hybrid``): the diffusion of ``P(σ)`` (:mod:`.contact`) and the friction
  ``μ = Σ_i f_i A_i S_i/σ0`` (:mod:`.friction`) with the strategies :class:`SCorrection`
  (Persson's ``S(q)``), :class:`Weighting` (which contact fraction weighs a node) and
  :class:`Dissipation` (at which wavenumbers a node's pressure power dissipates).
- :class:`StripOptions` — the cascade of Westergaard strips of a 1D sine series
  (:mod:`.strips`; the model ``meanfield-strips``).

An option a model does not read is not a field of its object, and an option that does not
apply to the input (a patch spectrum in 2D, an interface without a law, the strips on a
continuous spectrum) is refused with one line, never dropped.

Why ``γ = 0.8`` by default
--------------------------
Persson's ``S = γ + (1 − γ)A²`` (Yang & Persson 2008; Persson quotes ``γ ≈ 1/2``) with
``γ`` from 0.5 to 1 against every stored BEM point of the validation (1D sine series and
profiles, the 2D map): ``γ = 0.8`` puts the most points within 15 %, the 2D map (the
theory's own dimension) among them; ``γ ≈ 1/2`` is low on most surface classes
(docs/validation/meanfield.md, "Persson's S(q) and its γ").
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields

import numpy as np

from ..errors import InputError
from .contact import ANGLES_2D, CELL_POINTS, cell_average, contact_fraction

#: Default ``γ`` of Persson's ``S(q)`` (module docstring).
DEFAULT_GAMMA = 0.8
DISSIPATIONS = ("mode", "patch", "cascade")
WEIGHTINGS = ("cell", "after")
INTERFACES = ("law", "rigid")


def _one_of(name: str, value, allowed: tuple[str, ...]) -> None:
    if value not in allowed:
        raise InputError(f"{name}: expected one of {', '.join(allowed)}, got {value!r}")


@dataclass(frozen=True)
class SCorrection:
    """Persson's ``S(q) = γ + (1 − γ) A(q)²`` [-]; ``γ = 1`` is ``S = 1`` (Persson 2001).

    Attributes
    ----------
    gamma
        ``γ`` in ``(0, 1]`` [-].
    """

    gamma: float = DEFAULT_GAMMA

    def __post_init__(self) -> None:
        g = self.gamma
        if isinstance(g, bool) or not (isinstance(g, int | float) and 0.0 < g <= 1.0):
            raise InputError(f"gamma: Persson's γ must lie in (0, 1], got {g!r}")

    def area_weight(self, g: np.ndarray) -> np.ndarray:
        """``A(G) S(A(G))`` [-] at the diffusion variance ``G`` [-]."""
        a = contact_fraction(g)
        return a * (self.gamma + (1.0 - self.gamma) * a**2)

    def describe(self) -> str:
        return "S = 1" if self.gamma == 1 else f"S = {self.gamma:g} + {1 - self.gamma:g} A²"


@dataclass(frozen=True)
class Weighting:
    """Which contact fraction weighs a node's friction (:mod:`.friction`): ``"cell"`` (the
    mean over the node's step in ``G``, the quadrature of Persson's integral) or
    ``"after"`` (the fraction once the node is in place)."""

    kind: str = "cell"

    def __post_init__(self) -> None:
        _one_of("weighting", self.kind, WEIGHTINGS)

    def weights(self, g_after: np.ndarray, correction: SCorrection, points: int
                ) -> np.ndarray:
        """``(A S)`` of each node (last axis) [-]; ``points`` Gauss points per cell."""
        if self.kind == "after":
            return correction.area_weight(g_after)
        g_before = np.concatenate([np.zeros_like(g_after[..., :1]), g_after[..., :-1]],
                                  axis=-1)
        return cell_average(correction.area_weight, g_before, g_after, points)


@dataclass(frozen=True)
class Dissipation:
    """Where a node in partial contact dissipates (:mod:`.patches`): ``"mode"`` (at its own
    wavenumber, Persson's), ``"patch"`` or ``"cascade"`` (at the harmonics of its contact
    patches, of local fraction ``A_i`` or ``A_i/A_(i−1)``; 1D spectra only)."""

    kind: str = "mode"

    def __post_init__(self) -> None:
        _one_of("dissipation", self.kind, DISSIPATIONS)

    def check(self, dimension: int) -> None:
        if dimension != 1 and self.kind != "mode":
            raise InputError(f"dissipation={self.kind!r}: the patch spectrum is the 1D "
                             "(plane-strain) sine's; use 'mode' in 2D")

    def local_fraction(self, g_after: np.ndarray) -> np.ndarray:
        """The contact fraction ``r_i`` of a node's patches [-] (last axis)."""
        a = contact_fraction(g_after)
        if self.kind == "patch":
            return a
        before = np.concatenate([np.ones_like(a[..., :1]), a[..., :-1]], axis=-1)
        return np.minimum(a / before, 1.0)


def _coerce(obj, name: str, cls, build):
    """Let a string (or a number, for ``correction``) stand for its strategy object."""
    val = getattr(obj, name)
    if not isinstance(val, cls):
        object.__setattr__(obj, name, build(val))


@dataclass(frozen=True)
class MeanFieldOptions:
    """Persson's theory (models ``meanfield``, ``meanfield-hybrid``): one object, passed as is.

    Attributes
    ----------
    correction
        :class:`SCorrection` (or its ``γ`` as a number); default ``γ = 0.8``.
    weighting
        :class:`Weighting` (or ``"cell"``, default, / ``"after"``).
    dissipation
        :class:`Dissipation` (or ``"mode"``, default, / ``"patch"`` / ``"cascade"``).
    interface
        With a law (``meanfield-hybrid``) only: ``"law"`` (the law's compliance in series
        with the half-space, :mod:`.enriched`) or ``"rigid"``; ``None`` (default) is
        ``"law"`` with a law, and a value without a law is refused.
    angles
        Gauss–Legendre points over the wave-vector direction (2D).
    cell_points
        Gauss–Legendre points per node for the ``"cell"`` weights.
    pressure_points
        Samples of ``P(σ)``.
    """

    correction: SCorrection = field(default_factory=SCorrection)
    weighting: Weighting = field(default_factory=Weighting)
    dissipation: Dissipation = field(default_factory=Dissipation)
    interface: str | None = None
    angles: int = ANGLES_2D
    cell_points: int = CELL_POINTS
    pressure_points: int = 801

    def __post_init__(self) -> None:
        _coerce(self, "correction", SCorrection, SCorrection)
        _coerce(self, "weighting", Weighting, Weighting)
        _coerce(self, "dissipation", Dissipation, Dissipation)
        if self.interface is not None:
            _one_of("interface", self.interface, INTERFACES)
        for name in ("angles", "cell_points", "pressure_points"):
            val = getattr(self, name)
            if isinstance(val, bool) or int(val) != val or val < 2:
                raise InputError(f"{name}: must be an integer >= 2, got {val!r}")

    @property
    def gamma(self) -> float:
        return self.correction.gamma

    def interface_for(self, law: bool) -> str | None:
        """The interface used (``None`` without a law; refuses one given without a law)."""
        if not law:
            if self.interface is not None:
                raise InputError(f"interface={self.interface!r}: applies with a law "
                                 "(meanfield-hybrid) only")
            return None
        return self.interface or "law"

    def to_dict(self) -> dict:
        """Plain data (a task's argument): the strategies by their kind and ``γ``."""
        return {"model": "persson", "gamma": float(self.gamma),
                "weighting": self.weighting.kind, "dissipation": self.dissipation.kind,
                "interface": self.interface, "angles": self.angles,
                "cell_points": self.cell_points, "pressure_points": self.pressure_points}


@dataclass(frozen=True)
class StripOptions:
    """The cascade of Westergaard strips of a 1D sine series (model ``meanfield-strips``,
    :mod:`.strips`).

    Attributes
    ----------
    outer_crests
        ``True`` (default): a wave's crests just outside a longer wave's strip come into
        contact where the strips inside lift the rubber (:mod:`.outer`); ``False``: each
        wave's contact kept inside the longer waves' strips (the nested strips, for
        comparison).
    """

    outer_crests: bool = True

    def __post_init__(self) -> None:
        if not isinstance(self.outer_crests, bool):
            raise InputError(f"outer_crests: expected true or false, got "
                             f"{self.outer_crests!r}")

    def to_dict(self) -> dict:
        return {"model": "strips", "outer_crests": self.outer_crests}


def options_from_dict(data: dict | None) -> MeanFieldOptions | StripOptions:
    """The options object of :meth:`MeanFieldOptions.to_dict` / :meth:`StripOptions.to_dict`
    (``None``: Persson's defaults); an unknown key is refused."""
    data = dict(data or {"model": "persson"})
    kind = data.pop("model", "persson")
    classes = {"persson": MeanFieldOptions, "strips": StripOptions}
    if kind not in classes:
        raise InputError(f"options: model must be one of {', '.join(classes)}, got {kind!r}")
    cls = classes[kind]
    names = {f.name for f in fields(cls)}
    if cls is MeanFieldOptions:          # the S strategy travels as its γ
        names = names - {"correction"} | {"gamma"}
    bad = sorted(set(data) - names)
    if bad:
        raise InputError(f"options: {', '.join(bad)} do not apply to the {kind} model")
    if cls is MeanFieldOptions and "gamma" in data:
        data["correction"] = data.pop("gamma")
    return cls(**data)
