"""Viscoelastic half-space steady-sliding contact (the low-slope model, paper §2.3).

``solve_sliding`` is the entry point (model and outputs in :mod:`.solver`), tuned by a
``SolverOptions``; interaction laws live in :mod:`.laws`, the algorithms in :mod:`.hardwall`,
:mod:`.newton` and :mod:`.walls`, their common linear solve in :mod:`.contact_set`.
"""

from .laws import InteractionLaw, Law, LennardJonesRepulsion, SumLaw, check_law
from .options import SolverOptions
from .solver import SlidingResult, solve_sliding
from .tabulated import TabulatedLaw

__all__ = ["InteractionLaw", "Law", "LennardJonesRepulsion", "SlidingResult", "SolverOptions",
           "SumLaw", "TabulatedLaw", "check_law", "solve_sliding"]
