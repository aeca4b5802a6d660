"""Kinematically non-linear FEM micromechanical sliding test (paper §2.4, Fig. 4).

``steady_sliding(surface, material, mean_pressure, velocity, ...)`` solves the steady
state of a periodic plane-strain cell of finite-strain viscoelastic rubber sliding over
a rigid sine-series surface directly; ``sliding_test(..., solver="transient")`` time-steps
the press / settle / slide protocol. Both take one :class:`FemOptions` and return a
:class:`SlidingTestResult`.

Modules: :mod:`.options`, :mod:`.mesh` (periodic structured mesh), :mod:`.constitutive`
(finite-strain generalized Maxwell), :mod:`.element` (Q1/P0 mean dilatation),
:mod:`.assembly` (CSR scatter), :mod:`.contact` (analytic rigid surface, penalty),
:mod:`.cell` (the test cell), :mod:`.setup` (one test's cell), :mod:`.solver` (Newton with
direct solves), :mod:`.transient` (the time-stepped protocol), :mod:`.streamline`,
:mod:`.steady`, :mod:`.newton_krylov`, :mod:`.multilevel`, :mod:`.steady_solver` (the
steady solver), :mod:`.result`, :mod:`.resolution` (the automatic mesh, ``mesh = "auto"``,
and each test's check of its narrowest contact patch), :mod:`.sliding` (entry points),
:mod:`.sweep` (continuation along loads and speeds).
"""

from .constitutive import DEFAULT_BULK_MODULUS, MaterialParameters
from .options import SOLVERS, FemOptions, SteadyOptions, TransientOptions
from .result import PressureProfile, SlidingTestResult, SolverStats
from .sliding import make_options, sliding_test, steady_sliding
from .steady_solver import SteadyState
from .sweep import continuation_order, steady_sweep

__all__ = ["DEFAULT_BULK_MODULUS", "SOLVERS", "FemOptions", "MaterialParameters",
           "PressureProfile", "SlidingTestResult", "SolverStats", "SteadyOptions",
           "SteadyState", "TransientOptions", "make_options", "sliding_test",
           "steady_sliding", "steady_sweep", "continuation_order"]
