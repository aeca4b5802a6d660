r"""Hysteretic friction of the mean-field theory, and the choice of Persson's ``S(q)``.

Exact identity
--------------
For the steady-sliding half-space the dissipated power equals the work of the contact
pressure on the rubber's surface velocity, ``μσ0 = <σ ∂z/∂x> = <σ ∂w/∂x>``; in Fourier space

.. math:: μ σ_0 = Σ_k  \mathrm{var}\,σ_k \; (−k_x \,\mathrm{Im}\,M(k)),

the pressure power of every mode times the half-space's loss compliance at that mode
(:mod:`.contact` for ``M``). The theory knows the pressure power: mode ``i`` carries its
full-contact power ``s_i`` inside the contact fraction ``A(ζ_i)`` of its magnification
(the variance budget of the diffusion equation). Hence

.. math:: μ = Σ_i f_i\,(A\,S)_i / σ_0,

``f_i`` the full-contact friction stress of node ``i``. Which contact fraction weighs a node
(``weighting``): for a continuous spectrum, the mean over the node's step in ``G``
(``"cell"``, :func:`~.contact.cell_average`; the quadrature of Persson's integral); for a
sine series, the contact fraction once the wave is in place (``"after"``): a wave is one
coherent mode, not a band resolved step by step, and it dissipates in the contact it forms
itself. The two agree as the nodes get dense; for a few waves whose last one carries most
of ``G`` the cell mean counts that wave at contact fractions the surface never has
(docs/validation/meanfield.md compares both against the BEM).

Variants of ``S``
-----------------
``"none"`` (``S = 1``, the default): the friction the diffusion equation itself implies —
every mode dissipates at its full-contact rate on the area where it is in contact. It is
exact in full contact (``A = 1``).

``"persson"``: ``S = γ + (1 − γ) A²`` (Persson 2006, ``γ ≈ 0.5``), a correction for the
elastic energy that a mode does *not* store near the edges of the contact patches. It too is
exact in full contact and lowers the friction where the contact is small.

We default to ``S = 1``: it is the theory's own friction, and against our BEM it is the
closer of the two on the multi-wave surfaces and on the 2D map of the validation. On a 1D
self-affine profile over four decades ``S = 1`` with Persson's own-wavenumber dissipation
is high and Persson's ``S`` low; the *patch spectrum* (:mod:`.patches`, the default on
continuous 1D spectra) derives the reduction instead: a mode in partial contact carries its
pressure power at the harmonics of its patches, which dissipate at their own frequencies
(docs/validation/meanfield.md gives every variant against the BEM).

Where the friction stress comes from (``dissipation``)
------------------------------------------------------
``f_i`` above is ``s_i (−2 Im[1/E_r(q_i v)])`` (``"mode"``), or ``s_i Σ_n h_n(r_i)
(−2 Im[1/E_r(n q_i v)])`` with the local patch fraction ``r_i`` of :func:`local_fraction`
(``"patch"``, ``"cascade"``; :mod:`.patches`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .contact import cell_average, contact_fraction

CORRECTIONS = ("none", "persson")
DISSIPATIONS = ("auto", "mode", "patch", "cascade")
WEIGHTINGS = ("auto", "after", "cell")
#: Persson's γ of ``S = γ + (1 − γ)A²``.
PERSSON_GAMMA = 0.5


@dataclass(frozen=True)
class FrictionCorrection:
    """Which ``S(q)``: ``"none"`` (S = 1) or ``"persson"`` (``γ + (1 − γ)A²``)."""

    kind: str = "none"
    gamma: float = PERSSON_GAMMA

    def __post_init__(self) -> None:
        if self.kind not in CORRECTIONS:
            raise InputError(f"correction: expected one of {', '.join(CORRECTIONS)}, got "
                             f"{self.kind!r}")
        if not (isinstance(self.gamma, int | float) and 0.0 < self.gamma <= 1.0):
            raise InputError(f"gamma: Persson's γ must lie in (0, 1], got {self.gamma!r}")

    def area_weight(self, g: np.ndarray) -> np.ndarray:
        """``A(G) S(A(G))`` [-]."""
        a = contact_fraction(g)
        if self.kind == "none":
            return a
        return a * (self.gamma + (1.0 - self.gamma) * a**2)

    def describe(self) -> str:
        return "S = 1" if self.kind == "none" else f"S = {self.gamma:g} + {1 - self.gamma:g} A²"


def check_dissipation(dissipation: str) -> str:
    if dissipation not in DISSIPATIONS:
        raise InputError(f"dissipation: expected one of {', '.join(DISSIPATIONS)}, got "
                         f"{dissipation!r}")
    return dissipation


def local_fraction(g_after: np.ndarray, dissipation: str) -> np.ndarray:
    """The contact fraction ``r_i`` a node's patches have (:mod:`.patches`): ``A(ζ_i)``
    (``"patch"``) or ``A(ζ_i)/A(ζ_{i−1})`` (``"cascade"``), along the last axis."""
    a = contact_fraction(g_after)
    if dissipation == "patch":
        return a
    before = np.concatenate([np.ones_like(a[..., :1]), a[..., :-1]], axis=-1)
    return np.minimum(a / before, 1.0)


def check_weighting(weighting: str) -> str:
    if weighting not in WEIGHTINGS:
        raise InputError(f"weighting: expected one of {', '.join(WEIGHTINGS)}, got "
                         f"{weighting!r}")
    return weighting


def node_weights(g_after: np.ndarray, correction: FrictionCorrection, points: int,
                 weighting: str) -> np.ndarray:
    """``(A·S)`` of each node (last axis): at ``G_i`` (``"after"``) or its mean over the
    node's step ``[G_{i−1}, G_i]`` (``"cell"``)."""
    if weighting == "after":
        return correction.area_weight(g_after)
    g_before = np.concatenate([np.zeros_like(g_after[..., :1]), g_after[..., :-1]], axis=-1)
    return cell_average(correction.area_weight, g_before, g_after, points)


def friction_contributions(friction_stress: np.ndarray, g_after: np.ndarray, mean_pressure,
                           correction: FrictionCorrection, points: int,
                           weighting: str) -> np.ndarray:
    """``f_i · (A S)_i / σ0`` per node [-]; their sum is ``μ`` (``weighting``: "after" or
    "cell", see the module docstring)."""
    sigma0 = np.asarray(mean_pressure, float)[..., None]
    return friction_stress * node_weights(g_after, correction, points, weighting) / sigma0
