"""The loads the FEM cell holds: a law point's mean pressure stays at or below ``E∞``.

In steady sliding the cell's mean compression is static, carried by the relaxed rubber, so
above the relaxed modulus ``E∞`` its strains are very large. On steep cells the rubber then
wraps the crests until the face is stretched two- or threefold and Newton stops after
minutes of attempts, or converges sheared as a whole or with its face impaled
(docs/validation/steep_cells.md, parts ``strain`` and ``rounded``).

One rule, used three times: a run's law extension adds no pressure above it
(:func:`rubbercontact.pipeline.lawcover.plan_extension`), a test on the automatic mesh
(the law's mesh) refuses such a load before any work (:func:`~.sliding.check_test`), and
a run's full FEM does not run its loads above it (:func:`rubbercontact.pipeline.plan.model_tasks`:
they may stop and fall back, for long, and past the range the reference is not one). A
test called directly on an explicit mesh is tried, with a warning.
"""

from __future__ import annotations

import numpy as np

#: The study behind the rule.
LOAD_RANGE_STUDY = "docs/validation/steep_cells.md"


def outside_range(mean_pressure: float, relaxed_modulus: float) -> str | None:
    """Why a mean pressure is outside the FEM cell's range, or None if it is inside.

    Parameters
    ----------
    mean_pressure
        ``p̄`` [MPa].
    relaxed_modulus
        The rubber's relaxed (equilibrium) modulus ``E∞`` [MPa].

    Returns
    -------
    str or None
        One clause naming the pressure and ``E∞`` (None: ``p̄ <= E∞``).
    """
    if held(mean_pressure, relaxed_modulus):
        return None
    return (f"{mean_pressure:.3g} MPa is above the relaxed modulus E∞ = "
            f"{relaxed_modulus:.3g} MPa (very large strains in the cell; {LOAD_RANGE_STUDY})")


def held(mean_pressures, relaxed_modulus: float) -> np.ndarray:
    """Mask of the mean pressures [MPa] inside the cell's range (``p̄ <= E∞``, the rule of
    :func:`outside_range`)."""
    return np.asarray(mean_pressures, dtype=float) <= relaxed_modulus
