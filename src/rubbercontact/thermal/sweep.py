r"""The flash temperature of a half-space contact over a sweep of speeds, each speed's
search started from its neighbours.

:func:`~.contact.flash_contact` at every speed, in increasing order, each secant search
started (:class:`~.contact.FlashStart`) at the contact rise extrapolated from the speeds
already done — ``ln T_c`` against ``ln v``: quadratic through the last three heated
speeds, linear through two, ``T_c ∝ v^{1/2}`` (the moving source at high Péclet number)
from one, the exponent kept in ``[0, 3/2]`` — with the last root's slope
``d ln F/d ln T`` (and, with ``FlashSearch.warm_start``, its first solve started from the
last speed's final one). A speed whose predecessor stayed at the background (``T_c = 0``) starts
at the isothermal solve, which is then also its answer if ``F(0)`` is below the
tolerance; so the cold end of a sweep costs one solve per speed, as the isothermal one.

With a ``guide`` — the sweep of a similar contact over the same speeds (another random
realization of the surface, the other reading of the same hybrid) — a speed where the
guide heated starts instead at the guide's root with its slope: their roots differ by the
realizations' scatter (about a per cent), against the tens of per cent of an
extrapolation over a decade of speed, so the search usually ends at its second solve.
Only the guess is taken from it: the first solve still starts (``warm_start``) from this
sweep's own last solve, another surface's pressure being no start for this one.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import ConvergenceError, InputError
from ..materials.shift import ShiftLaw
from .contact import ContactFlash, FlashSearch, FlashStart, flash_contact
from .properties import ThermalProperties

#: Bounds of the extrapolation exponent ``d ln T_c / d ln v`` [-].
_EXPONENT = (0.0, 1.5)


@dataclass(frozen=True)
class FlashSweep:
    """The flash of a contact at each speed of a sweep.

    Attributes
    ----------
    velocities
        The true speeds [mm/s], increasing.
    flashes
        :class:`~.contact.ContactFlash` per speed (None where it failed).
    failures
        ``{speed [mm/s]: the error's first line}``.
    """

    velocities: np.ndarray
    flashes: tuple
    failures: dict = field(default_factory=dict)

    @property
    def solves(self) -> int:
        """Half-space solves of the sweep (the failed speeds' not counted)."""
        return sum(len(f.evaluations) for f in self.flashes if f is not None)


def predicted_start(done: list[tuple[float, ContactFlash]], velocity: float,
                    tolerance: float) -> FlashStart | None:
    """The :class:`~.contact.FlashStart` at ``velocity`` [mm/s] from ``done``, the
    ``(speed, flash)`` pairs of the lower speeds in order (module docstring); None to start
    from the isothermal solve."""
    if not done:
        return None
    v_last, last = done[-1]
    rise = last.contact_temperature - last.background_temperature
    if rise <= tolerance:
        return None
    pts = []
    for v, f in reversed(done):
        r = f.contact_temperature - f.background_temperature
        if r <= tolerance or len(pts) == 3:
            break
        pts.append((np.log(v), np.log(r)))
    x = np.log(velocity)
    if len(pts) == 1:
        guess = np.log(rise) + 0.5 * (x - pts[0][0])
    else:
        xs, ys = np.array(pts).T
        guess = float(np.polyval(np.polyfit(xs, ys, len(pts) - 1), x))
    lo, hi = (np.log(rise) + e * (x - np.log(v_last)) for e in _EXPONENT)
    return FlashStart(float(np.exp(np.clip(guess, lo, hi))), last.log_slope, last.result)


def guided_start(guide: ContactFlash | None, done: list[tuple[float, ContactFlash]],
                 tolerance: float) -> FlashStart | None:
    """The :class:`~.contact.FlashStart` at the guide's root (module docstring), or None
    when there is no guide or it stayed at the background."""
    if guide is None:
        return None
    rise = guide.contact_temperature - guide.background_temperature
    if rise <= tolerance:
        return None
    return FlashStart(float(rise), guide.log_slope, done[-1][1].result if done else None)


def flash_sweep(solve: Callable[[float], object], velocities, shift: ShiftLaw | dict,
                thermal: ThermalProperties | None = None, temperature: float | None = None,
                search: FlashSearch | None = None,
                guide: FlashSweep | None = None,
                scale: Callable[[object, float, float], object] | None = None) -> FlashSweep:
    """:func:`~.contact.flash_contact` at each speed, started from its neighbours.

    Parameters
    ----------
    solve
        ``solve(reduced_speed) -> SlidingResult`` (as for ``flash_contact``).
    velocities
        True sliding speeds [mm/s], > 0 (solved in increasing order).
    shift, thermal, temperature
        As for ``flash_contact``.
    search
        The search at every speed (default :class:`~.contact.FlashSearch`); its ``start``
        is replaced by the prediction (``method="bracket"``: the plain search, no starts).
    guide
        The sweep of a similar contact over the same speeds (module docstring; None: each
        speed started from the lower ones).
    scale
        As for ``flash_contact`` (a hybrid's finer scale at its own temperature).

    Returns
    -------
    FlashSweep
        A speed whose solve or search fails is recorded in ``failures`` and the next
        starts afresh.
    """
    v = np.sort(np.asarray(velocities, float).ravel())
    if v.size == 0 or not np.all(np.isfinite(v)) or np.any(v <= 0):
        raise InputError(f"velocities: expected finite speeds > 0 mm/s, got {velocities!r}")
    search = search or FlashSearch()
    if guide is not None and not np.array_equal(guide.velocities, v):
        raise InputError("guide: expected a sweep over the same speeds")
    done: list[tuple[float, ContactFlash]] = []
    flashes, failures = [], {}
    for k, speed in enumerate(v):
        start = None
        if search.method == "secant":
            start = (guided_start(guide.flashes[k] if guide else None, done, search.tolerance)
                     or predicted_start(done, float(speed), search.tolerance))
        try:
            out = flash_contact(solve, float(speed), shift, thermal, temperature,
                                search=replace(search, start=start), scale=scale)
        except ConvergenceError as exc:
            flashes.append(None)
            failures[float(speed)] = str(exc).splitlines()[0]
            done.clear()
            continue
        flashes.append(out)
        done.append((float(speed), out))
    return FlashSweep(v, tuple(flashes), failures)
