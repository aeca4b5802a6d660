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
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from ..errors import ConvergenceError
from ..hybrid.lawspeed import LawSpeeds
from ..hybrid.lawtable import LawWarning
from ..materials import GeneralizedMaxwell
from ..materials.shift import shift_law_from_dict
from ..meanfield import PSD
from ..meanfield import solve as solve_meanfield
from ..meanfield.flash import FlashOptions, cascade_rise, flash_friction_curve, tread_rise
from ..meanfield.options import options_from_dict
from ..models import registry
from ..models.planning import RunPoint
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
from .plan import meanfield_surfaces
from .setup import RunSetup, task_material

if TYPE_CHECKING:
    from .flash import FlashPlan, Tally

#: The model.
MODEL = "meanfield-hybrid"


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


def meanfield_hybrid_solver(setup: RunSetup, pressure: float, laws: LawSpeeds | None,
                            reads: LawReads) -> Callable[[float], object] | None:
    """``solve(reduced_speed)``: the model's :class:`~rubbercontact.meanfield.solve` at
    ``pressure`` [MPa] as the run's task solves it, the law read at ``reduced_speed``
    [mm/s]; None when the model has no low-slope wave (its answer is the law's
    flat-interface half-space solve, not a mean-field one)."""
    material = GeneralizedMaxwell(**task_material(setup.material))
    cls = registry.model_class(MODEL)
    data = cls.run_data(MODEL, setup)

    def task(speed: float) -> tuple[str, dict]:
        table = reads.table(laws, speed)
        return cls.run_task(MODEL, RunPoint(setup, material, float(speed),
                                            np.array([pressure]), table, None, data))

    if not data.get("wavelengths"):
        return None

    def solve(speed: float):
        _, kw = task(speed)             # the mean-field task's (there are low-slope waves)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", LawWarning)
            res = solve_meanfield(PSD.from_dict(kw["surface"]),
                                  GeneralizedMaxwell(**kw["material"]), kw["velocity"],
                                  kw["mean_pressure"], nu=kw["nu"], law=kw["interface_law"],
                                  options=options_from_dict(kw["options"]))
        for w in caught:
            if not issubclass(w.category, LawWarning):
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
                continue
            share = getattr(w.message, "share", None)       # weigh_law's coverage warning
            solve.beyond = max(solve.beyond, np.inf if share is None else 100.0 * share)
        return res

    solve.beyond = 0.0          # the largest share [%] of a contact beyond the law's pressures
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


def fill_meanfield(out: dict, at: tuple, m: str, setup: RunSetup, pressure: float,
                    temperature: float | None, plan: FlashPlan, acc: Tally) -> None:
    """One mean-field flash μ(v) into ``out[...][at]``."""
    psd = PSD.from_dict(meanfield_surfaces(setup)[m])
    try:
        curve = _curve(psd, setup, setup.speeds.velocities, pressure, temperature, plan)
    except ConvergenceError as exc:
        acc.failed(m, pressure, temperature, str(exc).splitlines()[0])
        return
    acc.residual = max(acc.residual, float(np.max(curve.residual)))
    for key, values in (("friction_flash", curve.friction),
                        ("contact_fraction_flash", curve.contact_fraction),
                        ("flash_temperature", curve.flash_temperature),
                        ("flash_heat_flux", curve.friction * pressure
                         * setup.speeds.velocities)):
        out[key][at] = values
    out["flash_scale_temperature"][at] = (curve.node_temperature
                                          - curve.background_temperature)


def fill_meanfield_hybrid(out: dict, at: tuple, setup: RunSetup, pressure: float,
                           temperature: float | None, plan: FlashPlan, acc: Tally,
                           laws, reads: LawReads) -> None:
    """One ``meanfield-hybrid`` flash μ(v) into ``out[...][at]`` (module docstring)."""
    m = MODEL
    solve = meanfield_hybrid_solver(setup, pressure, laws, reads)
    if solve is None:
        acc.failed(m, pressure, temperature, "no low-slope wave: the law's flat-interface "
                                             "solve, isothermal")
        return
    scale = None
    if setup.hs0.size and plan.per_scale:
        spots = ScaleSpots.of_cell(setup.hs0.period, plan.options.spot_radius, plan.thermal,
                                   plan.options.tolerance)
        scale = meanfield_scale(pressure, laws, reads, spots, setup.material.shift)
    res = meanfield_hybrid_flash(solve, setup.speeds.velocities, pressure,
                                 setup.material.shift, temperature,
                                 replace(plan.options, temperature=temperature), scale)
    for speed, message in res.failures.items():
        acc.failed(m, pressure, temperature, f"{speed:g} mm/s: {message}")
    if solve.beyond > 0:
        acc.failed(m, pressure, temperature, f"up to {solve.beyond:.1f} % of a flash "
                                             f"solve's low-slope contact beyond the law's "
                                             f"highest pressure, where it is held")
    if np.isfinite(res.residual).any():
        acc.residual = max(acc.residual, float(np.nanmax(res.residual)))
    for key, values in (("friction_flash", res.friction),
                        ("contact_fraction_flash", res.contact_fraction),
                        ("flash_temperature", res.rise), ("flash_heat_flux", res.heat_flux),
                        ("flash_temperature_hs", res.rise_hs)):
        out[key][at] = values


def _curve(psd: PSD, setup: RunSetup, velocities: np.ndarray, pressure: float,
           temperature: float | None, plan: FlashPlan):
    """One flash μ(v) at a run temperature [°C] (None: the reference) and load [MPa]."""
    return flash_friction_curve(psd, setup.material, velocities, pressure,
                                nu=setup.config.material.nu, options=plan.mean_field,
                                flash=replace(plan.options, temperature=temperature))
