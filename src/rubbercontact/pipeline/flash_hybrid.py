r"""The hybrids' friction with the flash temperature (``hybrid``, ``hybrid-windowed``).

What is computed
----------------
Per realization, load and run temperature ``T0``, the hybrid's low-slope half-space solve
at the contact's own mean temperature, as for ``vhs`` (:mod:`rubbercontact.thermal.contact`,
searched over the run's speeds by :func:`~rubbercontact.thermal.flash_sweep`): the heat
``Q = μ p v`` of the hybrid's friction ``μ = μ_ls + μ_hs`` (pointwise or windowed, as the
model reads the law) and its low-slope pressure ``p`` diffuses into the rubber moving at
the true speed ``v``; ``T_c`` is its mean rise over the low-slope contact, the points where
the high-slope law carries load (separation below the law's zero-load anchor, the
high-slope peak); and the solve is repeated at the reduced speed ``a_T(T0 + T_c) v`` —
the low-slope solve with the rubber at ``T0 + T_c`` (the reference rubber at ``a_T v``),
its interface the law at that speed — until ``T_c`` is the rise its own friction gives,
the high-slope terms of that friction at their own temperature (below).

The law is an FEM table at the run's (reduced) speeds; at a reduced speed between them
it is interpolated linearly in ``ln v`` at fixed pressure
(:mod:`rubbercontact.hybrid.lawspeed`). A heated contact is slower than a cold one, so
the speed read is below the run's: below the law's slowest speed the law is read at its
slowest one (clamped, not extrapolated) and ``attrs["flash_note"]`` says so, one line
with the lowest speed reached.

The high-slope scale at its own temperature
------------------------------------------
At each step of that search the high-slope scale's friction and real contact are re-read
at the high-slope spots' temperature ``T0 + T_c + ΔT_hs`` (:func:`hybrid_scale`,
:mod:`.flash_scales`): the law at ``a_T(T0 + T_c + ΔT_hs) v`` at the solve's low-slope
pressure, as the model reads it (pointwise: at ``p(x)``; windowed: at ``p`` averaged over
one high-slope period), ``ΔT_hs`` the flash of the high-slope spots (half-width a quarter
of the law cell's period) on top of the low-slope contact, self-consistent with that
friction. The heat of both (``μ = μ_ls + μ_hs(T_hs)``) is what heats the low-slope
contact.

The approximation
-----------------
One temperature for the low-slope contact — its mean — for the low-slope solve and for the
law's load–separation, its interface (the pressure is not re-solved at ``T_hs``); the
high-slope spots' own temperature by one mean-field step (:mod:`.flash_scales` says
where that holds). The heat is released at the surface where the low-slope pressure is.
The ``meanfield`` model's per-scale rise (``flash_scale_temperature``) beside it shows
the cascade through every scale. Between the law's speeds the interpolation error adds
(:mod:`rubbercontact.hybrid.lawspeed`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from ..hybrid.lawspeed import LawAtSpeed, LawSpeeds, SpeedBracket
from ..materials import GeneralizedMaxwell
from ..materials.shift import ShiftLaw
from ..roughness import SineSeries
from ..thermal.contact import CONTACT_SEPARATION, contact_mask, start_pressure
from .flash_scales import (
    HighSlopeTerms,
    LawInPressure,
    ScaleSpots,
    scale_flash,
    shifted_reader,
)

#: The hybrids computed with the flash temperature.
HYBRID_FLASH_MODELS = ("hybrid", "hybrid-windowed")


@dataclass
class LawReads:
    """Where the hybrids' flash solves read the law outside its tabulated speeds.

    Attributes
    ----------
    slowest
        The law's slowest tabulated speed [mm/s] (None: no law).
    lowest
        The lowest speed a solve asked the law for below ``slowest`` [mm/s] (inf: none).
    clamped
        Solves that read the law at ``slowest`` instead of their own speed.
    reads
        Solves that read the law.
    """

    slowest: float | None = None
    lowest: float = np.inf
    clamped: int = 0
    reads: int = 0

    def table(self, laws: LawSpeeds | None, speed: float):
        """The law's table at ``speed`` (None without a law), the read counted."""
        if laws is None:
            return None
        read = laws.at(speed)
        self.count(laws, read)
        return read.table

    def where(self, laws: LawSpeeds, speed: float) -> SpeedBracket:
        """Where ``speed`` falls among the law's speeds, the read counted."""
        return self.count(laws, laws.where(speed))

    def count(self, laws: LawSpeeds, read: SpeedBracket | LawAtSpeed):
        """``read`` (of ``laws``), counted (clamped or not)."""
        if self.slowest is None:
            self.slowest = float(laws.speeds[0])
        self.reads += 1
        if read.clamped:
            self.clamped += 1
            self.lowest = min(self.lowest, read.speed)
        return read

    def note(self, models: tuple[str, ...]) -> str:
        """One line on the clamped reads ("" when none)."""
        if not self.clamped:
            return ""
        return (f"{', '.join(models)}: the high-slope law is tabulated from "
                f"{self.slowest:g} mm/s; {self.clamped} of {self.reads} reads by heated "
                f"contacts asked for it below (down to {self.lowest:.4g} mm/s, a factor "
                f"{self.slowest / self.lowest:.3g}) and read it at {self.slowest:g} mm/s "
                f"(clamped, not extrapolated): add slower speeds for the law")

def law_speeds(tables: dict | None) -> LawSpeeds | None:
    """The run's law tables (:attr:`~.lawstage.LawStage.tables`) read at any speed, or
    None without a law (no high-slope scale: the hybrid is its plain half-space solve)."""
    return LawSpeeds(tables) if tables else None


def halfspace_solver(kw: dict, pressure: float, laws: LawSpeeds | None, reads: LawReads,
                     memo: bool = True) -> Callable[[float, object], object] | None:
    """``solve(reduced_speed, start=None)`` of a half-space solve at ``pressure`` [MPa] as
    the run's task solves it: ``kw``, the arguments of its
    :func:`~rubbercontact.hybrid.tasks.halfspace_loads_task` (the surface, grid, rubber,
    interaction and tolerance; ``hs_window`` for the windowed reading; its speed, loads and
    law not read), the law (``vhs``: None) at ``reduced_speed`` [mm/s] (module docstring);
    None when the surface is flat (no half-space solve to heat). With ``memo`` a solve at a
    speed already solved is returned again (a temperature-independent rubber asks for the
    same speed at every temperature)."""
    from ..halfspace import solve_sliding
    from ..hybrid.tasks import halfspace_law
    from ..hybrid.windowing import windowed_hs_terms

    surface = SineSeries(kw["surface"]["wavelengths"], kw["surface"]["amplitudes"],
                         kw["surface"].get("phases"))
    if surface.size == 0:
        return None
    mat = GeneralizedMaxwell(**kw["material"])
    window = kw.get("hs_window")
    solved: dict[float, object] = {}

    def solve(speed: float, start=None):
        key = float(speed)
        if memo and key in solved:
            return solved[key]
        table = reads.table(laws, key)
        res = solve_sliding(surface, kw["period"], mat, key, pressure,
                            law=halfspace_law(kw["law"], table, key), n=kw["n"], nu=kw["nu"],
                            tol=kw["tol"],
                            start=None if start is None else start_pressure(start))
        if table is not None:
            res = _with_law_terms(res, table, kw["period"], window, pressure,
                                  windowed_hs_terms)
        if memo:
            solved[key] = res
        return res

    return solve


def _with_law_terms(res, table: dict, period: float, window: float | None, pressure: float,
                    windowed: Callable):
    """``res`` with its contact (where the law carries load) for the heat's mean, and the
    windowed reading's ``μ_hs`` and area when ``window`` [mm] is given."""
    sig = np.asarray(table["pressure"], float)
    zero = np.flatnonzero(sig <= 0)
    limit = float(np.asarray(table["separation"], float)[zero[0]]) if zero.size else np.inf
    info = {**res.info, CONTACT_SEPARATION: limit}
    if window is None:
        return replace(res, info=info)
    mu_hs, area = windowed(res.pressure, period, float(window), table, pressure)
    return replace(res, friction=res.friction_ls + mu_hs, friction_hs=mu_hs,
                   contact_fraction=area, info=info)


#: Key of a hybrid flash solve's ``info``: its :class:`~.flash_scales.ScaleFlash`.
SCALE_FLASH = "scale_flash"


def hybrid_scale(pressure: float, laws: LawSpeeds | None, reads: LawReads,
                 window: float | None, spots: ScaleSpots, shift: ShiftLaw
                 ) -> Callable[[object, float, float], object] | None:
    """``scale(result, temperature, velocity)`` for :func:`~rubbercontact.thermal.flash_sweep`:
    a hybrid's low-slope solve at ``pressure`` [MPa] with its high-slope terms at the
    high-slope spots' own temperature (module docstring), the
    :class:`~.flash_scales.ScaleFlash` in its ``info`` under :data:`SCALE_FLASH`; None
    without a law. ``window`` [mm]: the windowed reading's (None: pointwise)."""
    from ..hybrid.windowing import window_average

    if laws is None:
        return None
    law = LawInPressure(laws, reads)

    def scale(res, temperature: float, velocity: float):
        p = np.asarray(res.pressure, float).ravel()
        if window is not None:              # the windowed reading (hybrid.windowing)
            period = float((res.x[1] - res.x[0]) * res.x.size)
            p = np.maximum(window_average(p, period, window), 0.0)
        read = law.reader(p, np.mean, pressure)
        low = HighSlopeTerms(float(res.friction_hs), float(res.contact_fraction))
        flash = scale_flash(shifted_reader(read, low, float(res.velocity)),
                            low, temperature, velocity, pressure,
                            float(np.mean(contact_mask(res))), shift, spots)
        return replace(res, friction=res.friction + (flash.terms.friction - low.friction),
                       friction_hs=flash.terms.friction,
                       contact_fraction=flash.terms.contact_fraction,
                       info={**res.info, SCALE_FLASH: flash})

    return scale
