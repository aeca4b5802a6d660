r"""``meanfield-hybrid`` with the flash temperature: the low-slope scale at its finest spots'
temperature, the high-slope law at its own spots'.

What is computed
----------------
Per load and run temperature ``T0``, at each of the run's true speeds ``v``: the contact
temperature ``T0 + T_c`` that the model's own friction gives. At a rise ``T_c`` the model
is solved as the run solves it (:func:`rubbercontact.meanfield.solve` on the low-slope
waves with the high-slope law, the same options) at the reduced speed
``u = a_T(T0 + T_c) v``: the reference rubber at ``u`` is the rubber at ``T0 + T_c``, and
the law is read at ``u`` (:mod:`rubbercontact.hybrid.lawspeed`: interpolated in ``ln v``
between its tabulated speeds, clamped below the slowest and said in
``attrs["flash_note"]``, as for the hybrids). Its heat gives the rise by the mean-field
flash's cascade (:func:`rubbercontact.meanfield.flash.cascade_rise`, the spots of each
low-slope node, radius ``spot_radius/q``, sliding at ``v``): each node's ``w_j = μ_j σ0 v``
and the law's ``μ_hs σ0 v``, released where the law acts, inside the finest low-slope
spots; ``T_c`` is the rise of those finest spots — where the high-slope law is read — and
the root of ``T_c = ΔT(T_c)`` is found by Brent's method to the flash's tolerance. At each
step the law's share (``μ_hs``, the real contact) is re-read at the high-slope spots' own
temperature ``T0 + T_c + ΔT_hs`` (:func:`meanfield_scale`, :mod:`.flash_scales`): the law at
``a_T(T0 + T_c + ΔT_hs) v`` weighted by the solve's ``P(σ)``, ``ΔT_hs`` the flash of the
high-slope spots inside the finest low-slope ones, self-consistent with that friction;
its heat is the ``μ_hs σ0 v`` above.

The approximation
-----------------
One temperature for every low-slope scale — the finest low-slope spots', the hottest of
the low-slope nodes — where the ``meanfield`` model gives each node its own
(:mod:`rubbercontact.meanfield.flash`): the coarse nodes are evaluated hotter than they
are, which moves μ the way the flash does, by somewhat more. The high-slope scale one
cascade level hotter, its law's load–separation (the low-slope solve's interface) at the
low-slope temperature (:mod:`.flash_scales` says where that holds). The limits are exact:
an infinitely conducting rubber has no rise and the run's own solve, bit for bit; so does
a rubber whose shift is 1.

As a sweep task (:func:`meanfield_hybrid_flash_task`, one per run temperature and load, a
pure function of plain data through the run's runner and cache, as the half-space
models' flash: :mod:`.flash_task`); the run's side is :mod:`.flash_meanfield`.
"""

from __future__ import annotations

import json
import warnings
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
import xarray as xr

from ..errors import ConvergenceError
from ..hybrid.lawspeed import LawSpeeds
from ..hybrid.lawtable import LawWarning
from ..materials import GeneralizedMaxwell
from ..materials.shift import shift_law_from_dict
from ..meanfield import PSD
from ..meanfield import solve as solve_meanfield
from ..meanfield.flash import FlashOptions, cascade_rise, tread_rise
from ..meanfield.options import options_from_dict
from ..thermal.properties import ThermalProperties
from ..thermal.spots import band_centre_temperature
from .flash_hybrid import SCALE_FLASH, LawReads
from .flash_scales import (
    HighSlopeTerms,
    LawInPressure,
    ScaleSpots,
    rise_root,
    scale_flash,
    shifted_reader,
)

#: The model.
MODEL = "meanfield-hybrid"
#: The task's import path.
MEANFIELD_FLASH_TASK = ("rubbercontact.pipeline.flash_meanfield_task:"
                        "meanfield_hybrid_flash_task")
#: The per-speed variables of the task's result (:class:`MeanFieldHybridFlash`'s arrays).
ROWS = ("friction", "contact_fraction", "rise", "heat_flux", "residual", "rise_hs")


@dataclass(frozen=True)
class MeanFieldHybridFlash:
    """``meanfield-hybrid`` with the flash at one load and run temperature, per speed.

    Attributes
    ----------
    friction, contact_fraction
        ``μ``, ``A/A0`` [-] at the contact temperature (NaN where the search failed).
    rise
        ``T_c`` [K] above the run's temperature.
    heat_flux
        ``μ σ0 v`` [mW/mm²].
    residual
        ``|ΔT(T_c) − T_c|`` [K] (or the high-slope step's, if larger).
    rise_hs
        ``T_c + ΔT_hs`` [K]: the high-slope spots' rise above the run's temperature (NaN
        without a ``scale``).
    failures
        ``{speed [mm/s]: message}``.
    """

    friction: np.ndarray
    contact_fraction: np.ndarray
    rise: np.ndarray
    heat_flux: np.ndarray
    residual: np.ndarray
    rise_hs: np.ndarray
    failures: dict


def meanfield_solver(kw: dict, pressure: float, laws: LawSpeeds | None,
                    reads: LawReads) -> Callable[[float], object]:
    """``solve(reduced_speed)``: the model's :func:`~rubbercontact.meanfield.solve` at
    ``pressure`` [MPa] as the run's task solves it (``kw``: its task's ``surface``,
    ``material``, ``nu``, ``options``), the law read at ``reduced_speed`` [mm/s];
    ``solve.beyond``: the largest share [%] of a solve's contact beyond the law's
    pressures."""
    psd, material = PSD.from_dict(kw["surface"]), GeneralizedMaxwell(**kw["material"])

    def solve(speed: float):
        table = reads.table(laws, speed)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", LawWarning)
            res = solve_meanfield(psd, material, float(speed), float(pressure), nu=kw["nu"],
                                  law=table, options=options_from_dict(kw["options"]))
        for w in caught:
            if not issubclass(w.category, LawWarning):
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
                continue
            share = getattr(w.message, "share", None)       # weigh_law's coverage warning
            solve.beyond = max(solve.beyond, np.inf if share is None else 100.0 * share)
        return res

    solve.beyond = 0.0
    return solve


def contact_rise(result, velocity: float, pressure: float, flash: FlashOptions) -> float:
    """``ΔT`` [K] of the finest low-slope spots from the heat of ``result`` (a
    :class:`~rubbercontact.meanfield.MeanFieldResult`) sliding at the true ``velocity``
    [mm/s] under ``pressure`` [MPa] (module docstring)."""
    q, parts = result.friction_spectrum
    heat = np.asarray(parts, float) * pressure * velocity
    heat[-1] += result.friction_hs * pressure * velocity
    spots = band_centre_temperature(flash.spot_radius / q, velocity, flash.thermal)
    return float(cascade_rise(heat, np.asarray(result.area.contact_fraction, float), spots,
                              tread_rise(flash))[-1])


def meanfield_scale(pressure: float, laws: LawSpeeds | None, reads: LawReads,
                    spots: ScaleSpots, shift) -> Callable[[object, float, float], object] | None:
    """``scale(result, temperature, velocity)``: a mean-field solve at ``pressure`` [MPa]
    with its law's share at the high-slope spots' own temperature (module docstring), the
    :class:`~.flash_scales.ScaleFlash` in its ``inputs`` under
    :data:`~.flash_hybrid.SCALE_FLASH`; None without a law."""
    if laws is None:
        return None
    law = shift_law_from_dict(shift)
    reading = LawInPressure(laws, reads)

    def scale(res, temperature: float, velocity: float):
        dist = res.pressure_distribution
        read = reading.reader(dist.sigma, dist.expect, pressure)   # weigh_law's reading
        low = HighSlopeTerms(float(res.friction_hs), float(res.contact_fraction))
        speed = float(res.inputs["velocity"])
        flash = scale_flash(shifted_reader(read, low, speed), low,
                            temperature, velocity, pressure, float(res.contact_fraction_ls),
                            law, spots)
        return replace(res, friction=res.friction + (flash.terms.friction - low.friction),
                       friction_hs=flash.terms.friction,
                       contact_fraction=flash.terms.contact_fraction,
                       inputs={**res.inputs, SCALE_FLASH: flash})

    return scale


def meanfield_hybrid_flash(solve: Callable[[float], object], velocities: np.ndarray,
                           pressure: float, shift, temperature: float | None,
                           flash: FlashOptions,
                           scale: Callable[[object, float, float], object] | None = None
                           ) -> MeanFieldHybridFlash:
    """The root ``T_c = ΔT(T_c)`` at each speed (module docstring) by
    :func:`~.flash_scales.rise_root` to ``flash.tolerance`` [K]: a speed whose heat at
    ``T_c = 0`` raises the spots by no more than the tolerance keeps its isothermal solve.
    ``scale(result, temperature, velocity)``: the high-slope scale at its own temperature
    (:func:`meanfield_scale`; None: at ``T0 + T_c``)."""
    law = shift_law_from_dict(shift)
    t0 = law.t_ref if temperature is None else float(temperature)
    v = np.asarray(velocities, float)
    out = np.full((6, v.size), np.nan)
    failures: dict = {}
    for k, speed in enumerate(v):
        seen: dict = {}

        def excess(rise: float, speed: float = speed, seen: dict = seen) -> float:
            if rise not in seen:
                res = solve(float(10.0 ** float(law.log10_shift(t0 + rise)) * speed))
                if scale is not None:
                    res = scale(res, t0 + rise, float(speed))
                seen[rise] = (res, contact_rise(res, speed, pressure, flash) - rise)
            return seen[rise][1]

        try:
            root = rise_root(excess, flash.tolerance)
            resid = abs(excess(root))
        except ConvergenceError as exc:
            failures[float(speed)] = str(exc).splitlines()[0]
            continue
        res = seen[root][0]
        hs = None if scale is None else res.inputs[SCALE_FLASH]
        out[:, k] = (res.friction, res.contact_fraction, root,
                     res.friction * pressure * speed,
                     resid if hs is None else max(resid, hs.residual),
                     np.nan if hs is None else root + hs.rise)
    return MeanFieldHybridFlash(*out, failures=failures)


def meanfield_hybrid_flash_task(solve: dict, pressure: float, velocities: list, shift: dict,
                                thermal: dict, flash: dict, temperature: float | None,
                                laws: dict | None = None,
                                scale: dict | None = None) -> xr.Dataset:
    """``meanfield-hybrid``'s flash μ(v) at one run temperature and load (module
    docstring), as a sweep task.

    Parameters
    ----------
    solve
        The model's task arguments the solve reads (:func:`meanfield_solver`).
    pressure
        ``σ0`` [MPa].
    velocities
        The run's true speeds [mm/s].
    shift, thermal
        The material's shift law and the compound's thermal properties, as plain data.
    flash
        :class:`~rubbercontact.meanfield.flash.FlashOptions` as plain data, without its
        ``thermal``, ``shift`` and ``temperature``.
    temperature
        The run temperature [°C] (None: the shift law's reference).
    laws
        ``{"speeds": [...], "tables": [...]}``: the law at its tabulated speeds (None:
        none, the plain theory).
    scale
        ``{"period" [mm], "spot_radius", "tolerance" [K]}``: the high-slope scale at its
        own temperature (None: at ``T0 + T_c``).

    Returns
    -------
    xarray.Dataset
        :data:`ROWS` on ``velocity``; ``beyond`` [%]; in ``attrs`` the failures (JSON
        ``[[speed, message], ...]``) and the law's reads.
    """
    props = ThermalProperties.from_dict(thermal)
    reads = LawReads()
    table = None if laws is None else LawSpeeds(dict(zip((float(s) for s in laws["speeds"]),
                                                         laws["tables"], strict=True)))
    solver = meanfield_solver(solve, pressure, table, reads)
    hook = None
    if scale is not None:
        spots = ScaleSpots.of_cell(scale["period"], scale["spot_radius"], props,
                                   scale["tolerance"])
        hook = meanfield_scale(pressure, table, reads, spots, shift)
    options = FlashOptions(**flash, thermal=props, temperature=temperature)
    res = meanfield_hybrid_flash(solver, np.asarray(velocities, float), pressure, shift,
                                 temperature, options, hook)
    ds = xr.Dataset({k: ("velocity", getattr(res, k)) for k in ROWS},
                    coords={"velocity": np.asarray(velocities, float)})
    ds["beyond"] = ((), float(solver.beyond))
    ds.attrs.update(failures=json.dumps([[s, m] for s, m in res.failures.items()]),
                    reads=json.dumps(vars(reads)))
    return ds
