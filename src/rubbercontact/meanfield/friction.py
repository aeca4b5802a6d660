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
sine series, optionally, the contact fraction once the wave is in place (``"after"``): a wave is one
coherent mode, not a band resolved step by step, and it dissipates in the contact it forms
itself. The two agree as the nodes get dense; for a few waves whose last one carries most
of ``G`` the cell mean counts that wave at contact fractions the surface never has
(docs/validation/meanfield.md compares both against the BEM).

Persson's ``S(q)``
------------------
``S = γ + (1 − γ) A²`` (Yang & Persson 2008; :class:`~.options.SCorrection`) corrects for
the elastic energy a mode does *not* store near the edges of the contact patches: exact in
full contact (``A = 1``), lower where the contact is small. ``γ = 1`` is ``S = 1``, the
friction the diffusion equation itself implies (Persson 2001: every mode dissipates at its
full-contact rate on the area where it is in contact). The default ``γ`` is chosen against
the BEM (:mod:`.options`; docs/validation/meanfield.md). On a 1D spectrum the *patch
spectrum* (:mod:`.patches`, ``dissipation="patch"``) derives a reduction of its own, which
``S < 1`` would count twice: use ``γ = 1`` with it.

Where the friction stress comes from (``dissipation``)
------------------------------------------------------
``f_i`` above is ``s_i (−2 Im[1/E_r(q_i v)])`` (``"mode"``), or ``s_i Σ_n h_n(r_i)
(−2 Im[1/E_r(n q_i v)])`` with the local patch fraction ``r_i`` of
:meth:`.options.Dissipation.local_fraction`
(``"patch"``, ``"cascade"``; :mod:`.patches`).
"""

from __future__ import annotations

import numpy as np

from .options import SCorrection, Weighting


def friction_contributions(friction_stress: np.ndarray, g_after: np.ndarray, mean_pressure,
                           correction: SCorrection, points: int,
                           weighting: Weighting) -> np.ndarray:
    """``f_i · (A S)_i / σ0`` per node [-] (last axis); their sum is ``μ``.

    ``friction_stress`` [MPa] and ``mean_pressure`` ``σ0`` [MPa]; ``g_after`` the diffusion
    variance once each node is in place [-]; ``points`` Gauss points per cell.
    """
    sigma0 = np.asarray(mean_pressure, float)[..., None]
    return friction_stress * weighting.weights(g_after, correction, points) / sigma0
