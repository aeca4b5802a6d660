"""Viscoelastic half-space steady-sliding contact (the low-slope model, paper §2.3).

``solve_sliding`` is the entry point; interaction laws live in :mod:`.laws`. The method is
documented in :mod:`rubbercontact.halfspace.solver`.
"""

from .laws import InteractionLaw, LennardJonesRepulsion, SumLaw, TabulatedLaw
from .solver import SlidingResult, solve_sliding

__all__ = ["InteractionLaw", "LennardJonesRepulsion", "SlidingResult", "SumLaw", "TabulatedLaw",
           "solve_sliding"]
