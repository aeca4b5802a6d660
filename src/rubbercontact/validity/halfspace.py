"""A half-space solve's friction against the rubber's dissipation: is the contact resolved?

The solver reports the friction from the surface's slopes, ``μ = <σ ∂z/∂x>/σ0``. With
``u = ū + w − z`` the separation and ``w = Mσ`` the displacement,

``<σ ∂z/∂x> = <σ ∂w/∂x> − <σ ∂u/∂x>``,

and the last term vanishes in the continuum (a hard wall: ``σ = 0`` where ``u > 0`` and
``u = 0`` where ``σ > 0``; a law ``σ = f(u)``: ``f(u) ∂u/∂x`` is the derivative of a periodic
function). The first, ``μ_w = <σ ∂w/∂x>/σ0``, is the power the rubber dissipates per unit
sliding distance and load, ``≥ 0`` for a passive material whatever the grid. On a grid that
does not resolve the contact (slopes at the grid scale: every pixel of a white-noise map is
its own asperity) the discrete ``<σ ∂u/∂x>`` is of the order of ``μ`` itself and ``μ`` may
even be negative, though the solver converged. :func:`resolution_note` says so in one
line when the two forms disagree by more than :data:`RESOLUTION_TOLERANCE`, which sits
between the gaps measured on resolved and on white-noise grids (``benchmarks/maps.md``,
"The resolution note's tolerance").
"""

from __future__ import annotations

import numpy as np

from ..halfspace.kernels import derivative_x
from .assess import Note

__all__ = ["RESOLUTION_TOLERANCE", "dissipation_friction", "resolution_note", "worst_per_speed"]

#: The slope and dissipation forms of μ may differ by this fraction of the larger one.
RESOLUTION_TOLERANCE = 0.5
#: Below this difference (absolute, in μ) the two forms agree whatever their ratio: an
#: elastic rubber's μ is solver noise around 0.
RESOLUTION_FLOOR = 1e-6


def dissipation_friction(result) -> float:
    """``μ_w = <σ ∂w/∂x>/σ0``: the friction of the power the rubber dissipates.

    Parameters
    ----------
    result
        A :class:`~rubbercontact.halfspace.SlidingResult` (a profile or a map; ``x`` its
        grid along the sliding direction, ``pressure`` and ``displacement`` on it).

    Returns
    -------
    float
        ``μ_w``; equal to the result's ``friction_ls`` on a grid that resolves the contact,
        ``≥ 0`` for a passive rubber on any grid.
    """
    x = np.asarray(result.x, float)
    w = np.asarray(result.displacement, float)
    dw = derivative_x(w, float(x[1] - x[0]) * w.shape[-1])
    return float(np.mean(np.asarray(result.pressure, float) * dw)) / result.mean_pressure


def resolution_note(result, model: str = "vhs") -> Note | None:
    """One line if the grid does not resolve the contact of ``result``, else ``None``.

    Parameters
    ----------
    result
        A :class:`~rubbercontact.halfspace.SlidingResult`.
    model
        The model named in the note.

    Returns
    -------
    Note or None
        A note (condition ``"resolution"``) when the slope form ``friction_ls`` and the
        dissipation form :func:`dissipation_friction` differ by more than
        :data:`RESOLUTION_TOLERANCE` of the larger (and by more than
        :data:`RESOLUTION_FLOOR`), or when ``friction_ls`` is negative beyond the floor.
    """
    mu, mu_w = float(result.friction_ls), dissipation_friction(result)
    gap = abs(mu - mu_w)
    negative = mu < -RESOLUTION_FLOOR
    if not negative and gap <= max(RESOLUTION_TOLERANCE * max(abs(mu), abs(mu_w)),
                                   RESOLUTION_FLOOR):
        return None
    what = "negative" if negative else "off"
    reason = (f"σ0 = {result.mean_pressure:.3g} MPa, μ from the slopes <σ ∂z/∂x> = {mu:.3g} "
              f"is {what}: the rubber's dissipation "
              f"<σ ∂w/∂x> gives {mu_w:.3g} (>= 0); the grid does not resolve the contact "
              f"(slopes at the grid scale): refine the grid or drop the shortest waves")
    excess = gap / max(RESOLUTION_TOLERANCE * max(abs(mu), abs(mu_w)), RESOLUTION_FLOOR)
    return Note(model, "resolution", reason, result.velocity, None, excess, reason)


def worst_per_speed(notes) -> tuple[Note, ...]:
    """The worst of ``notes`` at each speed (a run's loads share a speed's note: the
    run's summary folds notes over speeds, and counts each)."""
    worst: dict = {}
    for n in notes:
        if n.velocity not in worst or n.excess > worst[n.velocity].excess:
            worst[n.velocity] = n
    return tuple(worst.values())
