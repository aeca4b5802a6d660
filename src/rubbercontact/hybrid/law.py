"""The effective interface law of the high-slope scale (paper eqs. 1–3).

FEM sliding tests on the high-slope surface ``z_hs`` over a grid of mean pressures
``p̄`` and speeds ``v`` give, per test, the mean separation ``ū``, the contact
fraction ``α_hs`` and the viscoelastic shear stress ``Δτ_hs = μ_hs p̄``. Read at a
fixed speed as functions of ``ū`` they are the law ``σ_hs(ū)``, ``α_hs(ū)``,
``Δτ_hs(ū)`` that the half-space solver applies locally to the low-slope scale.

The law table is an ``xarray.Dataset`` (dims ``velocity``, ``pressure``). Computing it
is the expensive part of the method; once saved it serves any surface that shares
the same high-slope scale and material.

This module builds the table (:func:`effective_law`, :func:`assemble_law`). Reading it
back is :mod:`rubbercontact.hybrid.lawio`; screening it and reading it per speed,
:mod:`rubbercontact.hybrid.lawtable`; the linear (VHS) law,
:mod:`rubbercontact.hybrid.linearlaw`; the FEM tests' steadiness diagnostics,
:mod:`rubbercontact.hybrid.steadiness`. Their names are importable from here as well.
"""

from __future__ import annotations

import json
import warnings
from collections.abc import Sequence

import numpy as np
import xarray as xr

from .._validation import finite_array
from ..errors import InputError
from ..materials import GeneralizedMaxwell
from ..roughness import SineSeries
from .lawio import LAW_VARIABLES, as_law, check_law_matches, law_from_results
from .lawtable import (
    IMPALED_STATUS,
    LawWarning,
    check_coverage,
    law_at_velocity,
    law_top,
    max_height,
    screen_impaled,
    screen_monotone,
    tabulated_law_from_dict,
)
from .linearlaw import continue_with_linear_shape, linear_law
from .steadiness import (
    CREEP_SETTLED_TIMES,
    STEADINESS_UNITS,
    STEADINESS_VARIABLES,
    creep_unsettled_message,
    describe_unsteady,
    sheared_cells_message,
)

__all__ = ["effective_law", "assemble_law", "LawWarning", "IMPALED_STATUS",
           "STEADINESS_VARIABLES", "STEADINESS_UNITS", "CREEP_SETTLED_TIMES",
           "creep_unsettled_message", "sheared_cells_message", "describe_unsteady",
           "LAW_VARIABLES", "law_from_results", "as_law", "check_law_matches", "max_height",
           "screen_impaled", "screen_monotone", "law_at_velocity", "linear_law",
           "continue_with_linear_shape", "tabulated_law_from_dict", "law_top",
           "check_coverage"]


def effective_law(hs_surface: SineSeries, material: GeneralizedMaxwell,
                  pressures: Sequence[float], velocities: Sequence[float], *,
                  options=None, runner=None, **changes) -> xr.Dataset:
    """Run the FEM sliding test over ``pressures × velocities`` and tabulate the law.

    Parameters
    ----------
    hs_surface
        High-slope surface ``z_hs`` (cell width = its longest wavelength).
    material
        Rubber.
    pressures
        Mean pressures ``p̄`` [MPa], > 0. They should span the local pressures of the
        low-slope solve (checked later by :func:`check_coverage`).
    velocities
        Sliding speeds ``v`` [mm/s], >= 0.
    options
        The FEM test (:class:`rubbercontact.fem.FemOptions`; default: the steady solver
        on 120 × 90).
    runner
        Callable ``runner(tasks) -> list`` executing :class:`~rubbercontact.sweep.Task`
        objects, returning per task an ``xr.Dataset`` or a failure record;
        default: the package's sweep executor without cache.
    **changes
        Fields of the options by name (``mesh=``, ``grading=``, ``solver=``, ...; see
        :func:`rubbercontact.fem.make_options`).

    Returns
    -------
    xarray.Dataset
        Variables ``mean_separation`` [mm], ``contact_fraction`` [-], ``shear_stress``
        [MPa], ``friction`` [-], ``status`` (``"ok"``, the failure message, or
        ``"excluded: impaled ..."``, see :func:`screen_impaled`), ``impaled`` (1/0), dims
        ``(velocity, pressure)``; the surface, material and FEM options in ``attrs``.
    """
    from ..fem import make_options

    p = np.sort(finite_array("pressures", pressures, ndim=1))
    v = np.sort(finite_array("velocities", velocities, ndim=1))
    if np.any(p <= 0):
        raise InputError(f"pressures: must be > 0 MPa, got {p.tolist()}")
    if np.any(v < 0):
        raise InputError(f"velocities: must be >= 0 mm/s, got {v.tolist()}")
    if hs_surface.size == 0:
        raise InputError("hs_surface: the high-slope surface is empty; no law is needed")
    opts = make_options(options, **changes)      # fails here, not in every FEM task
    from ..sweep import Task

    fem_opts = opts.to_dict()
    tasks = [Task(function="rubbercontact.hybrid.tasks:fem_task",
                  kwargs={"surface": hs_surface.as_dict(), "material": material.as_dict(),
                          "velocity": float(vi), "mean_pressure": float(pi),
                          "options": fem_opts},
                  label=f"law FEM v={vi:g} mm/s p={pi:g} MPa")
             for vi in v for pi in p]
    results = (runner or _default_runner)(tasks)
    return assemble_law(results, p, v, hs_surface, material, fem_opts)


def _default_runner(tasks):
    from ..sweep import run_sweep

    return run_sweep(tasks, cache=None).results


def assemble_law(results, pressures, velocities, hs_surface: SineSeries,
                 material: GeneralizedMaxwell, fem_options: dict) -> xr.Dataset:
    """Stack per-test datasets (row-major over velocity, pressure) into the law table.

    Points whose FEM test reported an impaled face are excluded there
    (:func:`screen_impaled`), with their numbers and flag kept in the table.
    """
    names = ("mean_separation", "contact_fraction", "shear_stress", "friction", "wall_time")
    shape = (len(velocities), len(pressures))
    data = {k: np.full(shape, np.nan) for k in names}
    status = np.full(shape, "ok", dtype=object)
    diag = {k: np.full(shape, np.nan) for k in STEADINESS_VARIABLES}
    for idx, ds in enumerate(results):
        i, j = divmod(idx, len(pressures))
        if not isinstance(ds, xr.Dataset):
            status[i, j] = "missing result" if ds is None else str(ds)
            continue
        for k in names:
            data[k][i, j] = float(ds[k])
        for k in diag:
            if k in ds:     # results cached before a diagnostic existed lack it
                diag[k][i, j] = float(ds[k])
    units = {"mean_separation": "mm", "contact_fraction": "1", "shear_stress": "MPa",
             "friction": "1", "wall_time": "s"}
    law = xr.Dataset(
        {k: (("velocity", "pressure"), data[k], {"units": units[k]}) for k in names},
        coords={"velocity": ("velocity", np.asarray(velocities, float), {"units": "mm/s"}),
                "pressure": ("pressure", np.asarray(pressures, float), {"units": "MPa"})},
    )
    law["status"] = (("velocity", "pressure"), status.astype(str))
    for k, text in STEADINESS_VARIABLES.items():
        law[k] = (("velocity", "pressure"), diag[k],
                  {"units": STEADINESS_UNITS.get(k, "1"), "long_name": text})
    def label(i, j):
        return f"v={velocities[i]:g} p={pressures[j]:g}"

    n_bad, where, recorded = describe_unsteady(diag, label)
    if n_bad:
        # Kept in the table (the last period's averages): in the law cell the friction
        # settles within a few periods, the contact fraction can keep swinging by several
        # per cent from one period to the next.
        brackets = " (change over the last period in brackets)" if recorded else ""
        warnings.warn(f"law: {n_bad} of {diag['steady'].size} FEM points did not reach "
                      f"steady sliding within fem.periods{brackets}: {where}; they are kept "
                      f"(last period's averages); use fem.solver = 'steady' or more periods",
                      LawWarning, stacklevel=3)
    creep = creep_unsettled_message(diag, material, label, "law")
    if creep:
        warnings.warn(creep, LawWarning, stacklevel=3)
    # an under-resolved point is said once by the run, in the validity note of each model
    # that reads the law (rubbercontact.validity.run), not here
    sheared = sheared_cells_message(diag, label, "law")
    if sheared:
        warnings.warn(sheared, LawWarning, stacklevel=3)
    law.attrs.update({
        "title": "effective interface law of the high-slope scale (paper eqs. 1-3)",
        "hs_wavelengths_mm": hs_surface.wavelengths.tolist(),
        "hs_amplitudes_mm": hs_surface.amplitudes.tolist(),
        "hs_phases_rad": hs_surface.phases.tolist(),
        "hs_max_height_mm": float(max_height(hs_surface)),
        "material": json.dumps(material.as_dict()),
        "fem_options": json.dumps(fem_options),
    })
    # the only exclusion made here: an impaled point says "ok" but its numbers are
    # meaningless, so no reader of the table may take it for a law point
    return screen_impaled(law, stacklevel=4)
