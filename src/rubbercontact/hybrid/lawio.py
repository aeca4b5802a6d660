"""A law table read back: from a run's results or a law file, and checked before reuse.

:func:`law_from_results` and :func:`as_law` give the table in the form
:func:`~rubbercontact.hybrid.law.effective_law` returns; :func:`check_law_matches` fails
unless a reused law belongs to this run's high-slope scale, rubber and speeds.
"""

from __future__ import annotations

import json
from collections.abc import Sequence

import numpy as np
import xarray as xr

from ..errors import InputError
from ..materials import GeneralizedMaxwell
from ..roughness import SineSeries
from .steadiness import STEADINESS_VARIABLES

#: Variables of a law table as :func:`effective_law` and the pipeline build it; a results
#: file carries each as ``law_<name>`` on the dims ``(velocity, law_pressure)``.
LAW_VARIABLES = ("mean_separation", "contact_fraction", "shear_stress", "friction", "status",
                 "wall_time", *STEADINESS_VARIABLES, "vhs_friction",
                 "vhs_contact_fraction")
_LAW_REQUIRED = ("mean_separation", "contact_fraction", "shear_stress", "status")
_LAW_PROVENANCE = ("hs_wavelengths_mm", "hs_amplitudes_mm", "hs_phases_rad",
                   "hs_max_height_mm", "material")


def law_from_results(ds: xr.Dataset, source: str = "results") -> xr.Dataset:
    """The law table a results dataset carries, in the form :func:`effective_law` returns.

    Raises :class:`~rubbercontact.errors.InputError` when the run had no law (no hybrid
    model, or no high-slope scale) or its file predates the law's provenance attributes.
    """
    if "law_pressure" not in ds.coords:
        raise InputError(f"{source}: carries no law (no hybrid model ran on a high-slope "
                         f"scale)")
    if "law_attrs" not in ds.attrs:
        raise InputError(f"{source}: its law has no provenance (written before "
                         f"rubbercontact stored it); rerun the law or use a law.nc")
    # a run with temperatures keeps its law on the reduced speeds, dim law_velocity
    names = {"law_pressure": "pressure", "law_velocity": "velocity"}
    law = xr.Dataset({k: ds[f"law_{k}"].rename({d: names[d] for d in ds[f"law_{k}"].dims
                                                if d in names})
                      for k in LAW_VARIABLES if f"law_{k}" in ds})
    law.attrs.update(json.loads(ds.attrs["law_attrs"]))
    return law


def as_law(ds: xr.Dataset, source: str = "law") -> xr.Dataset:
    """A law table from a law dataset or from a run's results; checked for completeness."""
    if "law_pressure" in ds.coords or "model" in ds.dims:   # a run's results
        return law_from_results(ds, source)
    missing = [k for k in _LAW_REQUIRED if k not in ds]
    if missing or set(ds["mean_separation"].dims) != {"velocity", "pressure"}:
        raise InputError(f"{source}: not a law table (needs variables {list(_LAW_REQUIRED)} "
                         f"on dims (velocity, pressure); missing {missing}); use the law.nc "
                         f"or results.nc a rubbercontact run wrote")
    absent = [k for k in _LAW_PROVENANCE if k not in ds.attrs]
    if absent:
        raise InputError(f"{source}: no {absent} attribute(s): cannot check that the law "
                         f"belongs to this surface and rubber")
    return ds


def check_law_matches(law: xr.Dataset, hs_surface: SineSeries, material: GeneralizedMaxwell,
                      velocities: Sequence[float], source: str = "law") -> None:
    """Fail unless a reused law was built for this high-slope scale, rubber and speeds.

    The law is a property of the high-slope waves (up to a translation: compare
    ``hs_surface`` at zero phase) and of the rubber; the FEM options it was built with
    (mesh, sliding) are the user's choice and are not checked. Tolerance: relative
    ``1e-9``, i.e. the same numbers up to their round trip through a file.
    """
    attrs = law.attrs

    def vec(key):
        return np.atleast_1d(np.asarray(attrs[key], float))   # NetCDF stores [x] as x

    wl, amp, ph = vec("hs_wavelengths_mm"), vec("hs_amplitudes_mm"), vec("hs_phases_rad")
    same = (wl.size == hs_surface.size
            and np.allclose(wl, hs_surface.wavelengths, rtol=1e-9, atol=0)
            and np.allclose(amp, hs_surface.amplitudes, rtol=1e-9, atol=0)
            and np.allclose(np.angle(np.exp(1j * (ph - hs_surface.phases))), 0, atol=1e-9))
    if not same:
        raise InputError(f"{source}: built for the high-slope waves wavelengths {wl.tolist()} "
                         f"mm, amplitudes {amp.tolist()} mm, phases {ph.tolist()} rad; this "
                         f"run's high-slope scale is {hs_surface.wavelengths.tolist()} mm, "
                         f"{hs_surface.amplitudes.tolist()} mm, "
                         f"{hs_surface.phases.tolist()} rad")
    built = json.loads(attrs["material"])
    mine = material.as_dict()
    same = (np.isclose(built["equilibrium_modulus"], mine["equilibrium_modulus"], rtol=1e-9)
            and len(built["moduli"]) == len(mine["moduli"])
            and np.allclose(built["moduli"], mine["moduli"], rtol=1e-9, atol=0)
            and np.allclose(built["relaxation_times"], mine["relaxation_times"], rtol=1e-9,
                            atol=0))
    if not same:
        raise InputError(f"{source}: built for the rubber {built.get('name')!r} (E_inf = "
                         f"{built['equilibrium_modulus']:g} MPa, {len(built['moduli'])} "
                         f"branches), not this run's {mine['name']!r} (E_inf = "
                         f"{mine['equilibrium_modulus']:g} MPa, {len(mine['moduli'])} branches)")
    speeds = law["velocity"].values
    absent = [float(v) for v in velocities
              if not np.any(np.isclose(speeds, v, rtol=1e-9, atol=1e-12))]
    if absent:
        raise InputError(f"{source}: has no FEM points at {absent} mm/s (it has "
                         f"{speeds.tolist()} mm/s); build the law at those speeds or drop "
                         f"them from velocities")
