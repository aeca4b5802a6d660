"""The law table of one speed as a sweep task (:func:`law_table_task`).

The table continues the FEM law past its highest pressure with the linear law's shape
(:func:`~.linearlaw.continue_with_linear_shape`): half-space solves whose last bits depend
on the BLAS thread count of the process that runs them. The tables are in the hybrid
tasks' keys, so a table computed again in another thread setting (a run from the cache
against the run that computed the FEM) gave the hybrid tasks other keys, and a repeat
re-ran them. As a task the table is cached under its reading: a repeat reads the table the
first run computed, and on the workers it runs on one thread (seconds, not tens of seconds
in a process whose threads compete with the workers).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..materials import GeneralizedMaxwell
from ..roughness import SineSeries
from .linearlaw import continue_with_linear_shape

#: The keys of a law table (:func:`~.lawtable.law_at_velocity`), in order.
TABLE_KEYS = ("separation", "pressure", "contact_fraction", "shear_stress")


def law_table_task(reading: dict, surface: dict, material: dict, velocity: float,
                   nu: float = 0.5) -> xr.Dataset:
    """The law ``reading`` at ``velocity`` continued with the linear law's shape, as a
    dataset on a ``row`` dimension (:func:`table_from_dataset` reads it back)."""
    hs = SineSeries(surface["wavelengths"], surface["amplitudes"], surface.get("phases"))
    table = continue_with_linear_shape(reading, hs, GeneralizedMaxwell(**material),
                                       float(velocity), nu=nu)
    return xr.Dataset({k: ("row", np.asarray(table[k], float)) for k in TABLE_KEYS})


def table_from_dataset(ds: xr.Dataset) -> dict:
    """The table of :func:`law_table_task`'s dataset, as plain lists of floats."""
    return {k: [float(x) for x in ds[k].values] for k in TABLE_KEYS}
