"""Kinematically non-linear FEM micromechanical sliding test (paper §2.4, Fig. 4).

``sliding_test(surface, material, mean_pressure, velocity, ...)`` presses a periodic
plane-strain cell of finite-strain viscoelastic rubber onto a rigid sine-series
surface and slides it; see :mod:`.sliding` for the protocol and definitions.
Modules: :mod:`.mesh` (periodic structured mesh), :mod:`.constitutive`
(finite-strain generalized Maxwell), :mod:`.element` (Q1/P0 mean dilatation),
:mod:`.assembly` (CSR scatter), :mod:`.contact` (analytic rigid surface, penalty),
:mod:`.solver` (Newton), :mod:`.cell` (the test cell), :mod:`.sliding`.
"""

from .constitutive import DEFAULT_BULK_MODULUS, MaterialParameters
from .sliding import PressureProfile, SlidingTestResult, SolverStats, sliding_test

__all__ = ["DEFAULT_BULK_MODULUS", "MaterialParameters", "PressureProfile",
           "SlidingTestResult", "SolverStats", "sliding_test"]
