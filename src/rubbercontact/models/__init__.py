"""Contact models as objects: ``rc.models.Hybrid(law=...).solve(surface, material, v, p)``.

Every model follows one protocol (:class:`ContactModel`: ``solve(surface, material,
velocity, pressures) -> ContactResult``) and one result type (:class:`ContactResult`, with
``to_dataset()``); they are registered by name (:mod:`.registry`). Modules: :mod:`.base`
(protocol, result, the task-based base class), :mod:`.halfspace` (VHS, Hybrid),
:mod:`.fem` (FEM), :mod:`.meanfield` (MeanField, MeanFieldStrips), :mod:`.registry`.
"""

from .base import ContactModel, ContactResult, TaskModel
from .fem import FEM
from .halfspace import VHS, HalfspaceOptions, Hybrid
from .meanfield import MeanField, MeanFieldStrips
from .registry import available, create, needs_law, register

__all__ = ["FEM", "VHS", "ContactModel", "ContactResult", "HalfspaceOptions", "Hybrid",
           "MeanField", "MeanFieldStrips", "TaskModel", "available", "create", "needs_law",
           "register"]
