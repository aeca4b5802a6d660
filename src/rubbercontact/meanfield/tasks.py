"""The mean-field model as a pipeline task: plain data in, an ``xarray.Dataset`` of scalars out.

Same variable names and units as :func:`rubbercontact.hybrid.tasks.halfspace_task`, so the
pipeline can run it as the models ``meanfield`` (no law), ``meanfield-hybrid`` (the
low-slope surface with the high-slope law as ``interface_law``) and ``meanfield-strips``
(the strip cascade): the model is in ``options`` (:func:`~.options.options_from_dict`).
"""

from __future__ import annotations

import time

import numpy as np
import xarray as xr

from ..materials import GeneralizedMaxwell
from .options import options_from_dict
from .psd import PSD
from .solve import solve

#: Units of the scalars (the half-space task's names and units, plus the model's own).
UNITS = {
    "friction": "1", "friction_ls": "1", "friction_hs": "1", "contact_fraction": "1",
    "contact_fraction_ls": "1", "friction_full": "1", "mean_pressure": "MPa",
    "velocity": "mm/s", "max_local_pressure": "MPa", "wall_time": "s",
}
#: The options recorded in the result's attrs (as used: :attr:`MeanFieldResult.inputs`).
ATTRS = ("gamma", "correction", "weighting", "dissipation", "interface",
         "outer_crests")
#: Share of the contact below ``max_local_pressure``.
PRESSURE_QUANTILE = 0.999


def meanfield_task(surface: dict, material: dict, velocity: float, mean_pressure: float,
                   nu: float = 0.5, interface_law: dict | None = None,
                   options: dict | None = None) -> xr.Dataset:
    """One mean-field solve (:func:`rubbercontact.meanfield.solve`).

    Parameters
    ----------
    surface
        A sine series as plain data (``wavelengths``, ``amplitudes``, optional ``phases``,
        which do not enter) or a spectrum (:meth:`~rubbercontact.meanfield.PSD.as_dict`).
        With ``interface_law``: the low-slope part, as for the half-space task.
    material
        :meth:`~rubbercontact.materials.GeneralizedMaxwell.as_dict` output.
    velocity, mean_pressure, nu
        Speed [mm/s], ``σ0`` [MPa], Poisson's ratio.
    interface_law
        The high-slope law at this speed (the half-space task's ``interface_law``,
        :func:`rubbercontact.hybrid.law_at_velocity`), or ``None``.
    options
        ``to_dict()`` of :class:`~rubbercontact.meanfield.MeanFieldOptions` (Persson's
        theory; ``None``: its defaults) or :class:`~rubbercontact.meanfield.StripOptions`.

    Returns
    -------
    xarray.Dataset
        Scalars ``friction``, ``friction_ls``, ``friction_hs``, ``contact_fraction``,
        ``contact_fraction_ls``, ``friction_full``, ``mean_pressure``, ``velocity``,
        ``max_local_pressure`` (the pressure below which 99.9 % of the contact lies),
        ``wall_time``; units in each variable's ``attrs``.
    """
    t0 = time.perf_counter()
    psd = PSD.from_dict(surface)
    opts = options_from_dict(options)
    res = solve(psd, GeneralizedMaxwell(**material), velocity, mean_pressure, nu=nu,
                law=interface_law, options=opts)
    dist = res.pressure_distribution
    cdf = np.concatenate([[0.0], np.cumsum(np.diff(dist.sigma) * 0.5
                                           * (dist.density[1:] + dist.density[:-1]))])
    top = float(np.interp(PRESSURE_QUANTILE * cdf[-1], cdf, dist.sigma))
    values = {
        "friction": res.friction, "friction_ls": res.friction_ls,
        "friction_hs": res.friction_hs, "contact_fraction": res.contact_fraction,
        "contact_fraction_ls": res.contact_fraction_ls, "friction_full": res.friction_full,
        "mean_pressure": float(mean_pressure), "velocity": float(velocity),
        "max_local_pressure": top, "wall_time": time.perf_counter() - t0,
    }
    ds = xr.Dataset({k: ((), float(v), {"units": UNITS[k]}) for k, v in values.items()})
    used = {k: str(v) for k, v in res.inputs.items() if k in ATTRS}
    ds.attrs.update({"model": "meanfield", "hybrid": int(interface_law is not None),
                     "theory": res.inputs["model"], "dimension": psd.dimension, **used,
                     "psd": psd.source})
    return ds
