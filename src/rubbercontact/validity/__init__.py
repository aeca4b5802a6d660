"""Where each model holds: its validated class, and the notes of a run outside it.

Every model was validated against a reference (the full FEM for the VHS and the FEM; the
VHS BEM, which solves the linear problem exactly, for the hybrids and the mean-field
models) on a class of surfaces, contacts and speeds: :mod:`.classes` states each class as
data, every bound with the report that measured it; :mod:`.assess` returns, for a model and
what a run has, one note per condition outside the class (:func:`summarize`: one line a
model); :mod:`.run` reads those inputs
from a run's results. The guide's table is docs/guide/models.md ("Where each model was
validated").
"""

from .assess import (
    Note,
    SpeedPoint,
    SurfaceStats,
    as_attrs,
    assess,
    loss_peak_frequency,
    summarize,
)
from .classes import CLASSES, QUANTITIES, Condition, ValidatedClass
from .run import assess_run

__all__ = ["CLASSES", "QUANTITIES", "Condition", "Note", "SpeedPoint", "SurfaceStats",
           "ValidatedClass", "as_attrs", "assess", "assess_run", "loss_peak_frequency", "summarize"]
