"""Contact models as objects: ``rc.models.Hybrid(law=...).solve(surface, material, v, p)``.

Every model follows one protocol (:class:`ContactModel`: ``solve(surface, material,
velocity, pressures) -> ContactResult``) and one result type (:class:`ContactResult`, with
``to_dataset()``); they are registered by name (:mod:`.registry`), and each says how a run
plans it (:mod:`.planning`). Modules: :mod:`.base` (protocol, result, the task-based base
class), :mod:`.planning`, :mod:`.halfspace` (VHS, Hybrid), :mod:`.fem` (FEM),
:mod:`.meanfield` (MeanField, MeanFieldHybrid, MeanFieldStrips), :mod:`.registry`.
"""

from .base import ContactModel, ContactResult, TaskModel
from .fem import FEM
from .halfspace import VHS, HalfspaceOptions, Hybrid
from .meanfield import MeanField, MeanFieldHybrid, MeanFieldStrips
from .planning import Planning, RunPoint
from .registry import available, create, needs_law, register

__all__ = ["FEM", "VHS", "ContactModel", "ContactResult", "HalfspaceOptions", "Hybrid",
           "MeanField", "MeanFieldHybrid", "MeanFieldStrips", "Planning", "RunPoint",
           "TaskModel", "available", "create", "needs_law", "register"]
