"""Viscoelastic half-space steady-sliding contact (the low-slope model, paper §2.3).

``solve_sliding`` is the entry point (model and outputs in :mod:`.solver`), tuned by a
``SolverOptions``; interaction laws live in :mod:`.laws`, the algorithms in :mod:`.hardwall`,
:mod:`.newton` and :mod:`.walls`, their common linear solve in :mod:`.contact_set`.
"""

from .laws import InteractionLaw, LennardJonesRepulsion, SumLaw, TabulatedLaw
from .options import SolverOptions
from .solver import SlidingResult, solve_sliding

__all__ = ["InteractionLaw", "LennardJonesRepulsion", "SlidingResult", "SolverOptions", "SumLaw",
           "TabulatedLaw", "solve_sliding"]
