"""A run against the validated classes: one :class:`Note` per condition outside a class.

:func:`assess` takes what a run has (the waves, the contact fractions, the speeds, the local
pressures against the law's range, the friction beside the VHS's) and returns the notes;
:func:`summarize` folds them into one line per model, each condition once and the speeds
folded.

Speeds enter as frequencies: a class bounds ``q v`` of the waves it concerns on the scale of
the SBR of Table 1 (every study's rubber), and a run's rubber is compared on its own loss
peak, ``q v ω_peak,SBR / ω_peak`` (:func:`loss_peak_frequency`). A rubber shifted in
temperature shifts its loss peak alike, so a reduced speed at the reference temperature and
the speed at the shifted rubber give the same note.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from functools import cache

import numpy as np

from ..errors import InputError
from .classes import (
    CLASSES,
    MU_NOISE,
    QUANTITIES,
    SPEED_QUANTITIES,
    Condition,
    ValidatedClass,
)


@dataclass(frozen=True)
class SurfaceStats:
    """The waves of a sine series as the classes see them.

    Attributes
    ----------
    wavelengths
        Wavelengths [mm], any order.
    m2
        Per-wave rms slopes ``q Δ/√2``, in the same order.
    m2_threshold
        The split: waves with ``m2 > m2_threshold`` are the high-slope part.
    dimension
        1 for profiles (sine series, line scans), 2 for a height map's octave bands
        (:mod:`.maps`).
    """

    wavelengths: tuple[float, ...]
    m2: tuple[float, ...]
    m2_threshold: float = 1.0
    dimension: int = 1

    def __post_init__(self) -> None:
        lam, m2 = np.asarray(self.wavelengths, float), np.asarray(self.m2, float)
        if lam.ndim != 1 or lam.shape != m2.shape or lam.size == 0:
            raise InputError(f"surface: wavelengths and m2 must be two non-empty lists of "
                             f"one length, got {lam.size} and {m2.size}")
        if not (np.all(np.isfinite(lam)) and np.all(lam > 0)):
            raise InputError(f"surface: wavelengths must be positive [mm], got {lam.tolist()}")
        if not (np.all(np.isfinite(m2)) and np.all(m2 >= 0)):
            raise InputError(f"surface: rms slopes m2 must be >= 0, got {m2.tolist()}")
        if not (math.isfinite(self.m2_threshold) and self.m2_threshold > 0):
            raise InputError(f"surface: m2_threshold must be > 0, got {self.m2_threshold!r}")
        if self.dimension not in (1, 2):
            raise InputError(f"surface: dimension must be 1 (profiles) or 2 (a map), got "
                             f"{self.dimension!r}")

    @classmethod
    def from_series(cls, surface, m2_threshold: float = 1.0) -> SurfaceStats:
        """From a :class:`~rubbercontact.roughness.SineSeries` and the split threshold."""
        return cls(tuple(map(float, surface.wavelengths)),
                   tuple(map(float, surface.rms_slopes())), float(m2_threshold))

    def _arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        lam, m2 = np.asarray(self.wavelengths, float), np.asarray(self.m2, float)
        return lam, m2, m2 > self.m2_threshold

    def values(self) -> dict[str, np.ndarray]:
        """The surface's values of each surface quantity (empty where it does not apply)."""
        lam, m2, hs = self._arrays()
        ratio = (np.array([lam[~hs].min() / lam[hs].max()]) if hs.any() and (~hs).any()
                 else np.array([]))
        ordered = np.sort(lam)
        return {"m2": m2, "m2_low": m2[~hs], "m2_high": m2[hs], "split_ratio": ratio,
                "spacing": ordered[1:] / ordered[:-1],
                "dimension": np.array([float(self.dimension)])}

    def wavenumbers(self, high_only: bool) -> np.ndarray:
        """``2π/λ`` [1/mm] of every wave, or of the high-slope waves only."""
        lam, _, hs = self._arrays()
        return 2 * np.pi / (lam[hs] if high_only else lam)


@dataclass(frozen=True)
class SpeedPoint:
    """What a run has at one speed for one model.

    Attributes
    ----------
    velocity
        Sliding speed [mm/s] (at the rubber whose loss peak :func:`assess` is given).
    contact
        The model's contact fraction at each load.
    friction, friction_vhs
        The model's μ and the VHS's on the same surface at each load (empty: no comparison).
    local_pressure
        The highest local low-slope pressure [MPa] the law was read at (None: no law).
    law_top
        The law's highest successful FEM pressure [MPa] at this speed (None: no law).
    temperature
        The temperature [°C] of a run with temperatures, for the note (None otherwise).
    """

    velocity: float
    contact: tuple[float, ...] = ()
    friction: tuple[float, ...] = ()
    friction_vhs: tuple[float, ...] = ()
    local_pressure: float | None = None
    law_top: float | None = None
    temperature: float | None = None

    def __post_init__(self) -> None:
        if not (math.isfinite(self.velocity) and self.velocity > 0):
            raise InputError(f"speed: sliding speed {self.velocity!r} mm/s must be > 0")
        c = np.asarray(self.contact, float)
        if np.any(c[np.isfinite(c)] < 0) or np.any(c[np.isfinite(c)] > 1):
            raise InputError(f"speed {self.velocity:g} mm/s: contact fractions must lie in "
                             f"[0, 1], got {c.tolist()}")
        if len(self.friction) != len(self.friction_vhs):
            raise InputError(f"speed {self.velocity:g} mm/s: friction and friction_vhs need "
                             f"one value per load each, got {len(self.friction)} and "
                             f"{len(self.friction_vhs)}")
        if (self.law_top is None) != (self.local_pressure is None):
            raise InputError(f"speed {self.velocity:g} mm/s: give local_pressure and law_top "
                             f"together (MPa), or neither")

    def departure(self, tolerance: float) -> tuple[float, float, float] | None:
        """The load where μ departs most from the VHS beyond ``tolerance`` (relative) plus
        the half-space's noise floor :data:`~.classes.MU_NOISE`: (that excess, >= 0, 1 at
        the bound; μ; μ_VHS), or None without a comparison."""
        mu, ref = np.asarray(self.friction, float), np.asarray(self.friction_vhs, float)
        ok = np.isfinite(mu) & np.isfinite(ref)
        if not ok.any():
            return None
        mu, ref = mu[ok], ref[ok]
        excess = np.abs(mu - ref) / (tolerance * np.abs(ref) + MU_NOISE)
        i = int(np.argmax(excess))
        return float(excess[i]), float(mu[i]), float(ref[i])


@dataclass(frozen=True)
class Note:
    """A model run outside its validated class, in one line.

    Attributes
    ----------
    model
        The model.
    condition
        The quantity outside the class (a key of :data:`QUANTITIES`), or ``"vhs"``: μ
        departs from the VHS by more than the class's tolerance.
    reason
        What is outside, against which bound, and the report that measured it.
    velocity
        The speed [mm/s]; None for a condition on the surface alone.
    temperature
        The temperature [°C] of a run with temperatures, else None.
    excess
        How far outside: the worst value over its bound (or the departure over the
        tolerance); 1 at the bound.
    detail
        The condition alone (values, bound, report), for a departure note to quote and for
        :func:`summarize`'s line.
    class_name
        The validated class the note is about ("" for the run's own notes, such as an
        under-resolved FEM).
    """

    model: str
    condition: str
    reason: str
    velocity: float | None = None
    temperature: float | None = None
    excess: float = 1.0
    detail: str = ""
    class_name: str = ""

    @property
    def text(self) -> str:
        """The note as one line: the model, where, and the reason."""
        where = "" if self.velocity is None else f" at {self.velocity:.3g} mm/s"
        if self.temperature is not None:
            where += f", {self.temperature:g} °C"
        return f"{self.model}{where}: {self.reason}"


@cache
def _sbr_loss_peak() -> float:
    from ..materials import sbr

    return loss_peak_frequency(sbr())


def loss_peak_frequency(material) -> float:
    """The angular frequency [rad/s] of the rubber's largest loss factor ``Im E/Re E``.

    Parameters
    ----------
    material
        Anything with ``complex_modulus(omega)`` (MPa), e.g. a ``GeneralizedMaxwell``.
    """
    omega = np.logspace(-12, 16, 2801)
    e = np.asarray(material.complex_modulus(omega))
    loss = e.imag / e.real
    i = int(np.argmax(loss))
    if i in (0, omega.size - 1) or not loss[i] > 0:
        raise InputError("material: its loss factor Im E/Re E has no peak within "
                         "1e-12-1e16 rad/s; the speed classes are scaled on that peak")
    # the parabola through the three grid points around the peak, in log frequency
    y0, y1, y2 = np.log(loss[i - 1:i + 2])
    step = np.log(omega[1] / omega[0])
    shift = 0.5 * (y0 - y2) / (y0 - 2 * y1 + y2) if y0 - 2 * y1 + y2 < 0 else 0.0
    return float(omega[i] * np.exp(shift * step))


def assess(model: str, surface: SurfaceStats, points: Sequence[SpeedPoint] = (),
           loss_peak: float | None = None, run_notes: Sequence[Note] = ()) -> tuple[Note, ...]:
    """The notes of ``model`` on ``surface`` at ``points``: one per condition outside its class.

    Parameters
    ----------
    model
        A key of :data:`CLASSES`.
    surface
        The surface's waves and split.
    points
        The run's speeds, each with what the run has there (may be empty: the surface alone).
    loss_peak
        The run's rubber's loss-peak frequency [rad/s] (:func:`loss_peak_frequency`);
        ``math.inf`` for an elastic rubber, which has no hysteresis and so no speed bound;
        needed when ``points`` are given and the class bounds the speed.
    run_notes
        The run's own notes on ``model`` that are not about the surface or the speed (its
        FEM tests under-resolved): they are not returned, but a departure from the VHS
        names them as where the run leaves the class, not "inside its validated class".

    Returns
    -------
    tuple of Note
        The surface's conditions first (no speed), then per speed its conditions and, where
        μ departs from the VHS by more than the class's tolerance, a note saying so and
        whether the run lies outside the class.
    """
    if model not in CLASSES:
        raise InputError(f"validity: unknown model {model!r}; choose one of "
                         f"{', '.join(CLASSES)}")
    cls = CLASSES[model]
    if cls.reduces_to and not surface.values()["m2_high"].size:
        # no high-slope wave: the model is the one it reduces to, on the same surface
        base = CLASSES[cls.reduces_to]
        cls = replace(base, model=model, name=f"{base.name}, as {base.model} without a "
                                              f"high-slope wave")
    surface_values = surface.values()
    on_surface = [n for c in cls.conditions if c.quantity not in SPEED_QUANTITIES
                  for n in _check(cls, c, surface_values[c.quantity], surface)]
    notes = list(on_surface)
    if points:
        scale = None if loss_peak == math.inf else _frequency_scale(cls, loss_peak)
        for p in points:
            notes.extend(_at_speed(cls, surface, p, scale, on_surface + list(run_notes)))
    return tuple(notes)


def _frequency_scale(cls: ValidatedClass, loss_peak: float | None) -> float:
    """``ω_peak,SBR / ω_peak`` of the run's rubber (1 if the class has no speed bound)."""
    if not any(c.quantity.startswith("frequency") for c in cls.conditions):
        return 1.0
    if loss_peak is None or not (math.isfinite(loss_peak) and loss_peak > 0):
        raise InputError(f"validity: {cls.model} bounds the speed: give the rubber's "
                         f"loss-peak frequency [rad/s] > 0 (loss_peak_frequency), got "
                         f"{loss_peak!r}")
    return _sbr_loss_peak() / loss_peak


def _at_speed(cls: ValidatedClass, surface: SurfaceStats, p: SpeedPoint, scale: float | None,
              on_surface: list[Note]) -> list[Note]:
    notes: list[Note] = []
    for c in cls.conditions:
        if scale is None and c.quantity.startswith("frequency"):
            continue   # an elastic rubber: no loss peak to measure speeds on
        if c.quantity in SPEED_QUANTITIES:
            values = _speed_values(c.quantity, surface, p, scale)
            notes.extend(_check(cls, c, values, surface, p, scale))
    found = p.departure(cls.tolerance)
    if cls.departs and found is not None and found[0] > 1.0:
        notes.append(_departure(cls, p, found, on_surface + notes))
    return notes


def _speed_values(quantity: str, surface: SurfaceStats, p: SpeedPoint,
                  scale: float) -> np.ndarray:
    if quantity == "contact":
        return np.asarray(p.contact, float)
    if quantity == "law_pressure":
        if p.law_top is None:
            return np.array([])
        return np.array([p.local_pressure / p.law_top if p.law_top > 0 else math.inf])
    return surface.wavenumbers(quantity == "frequency_high") * p.velocity * scale


def _check(cls: ValidatedClass, c: Condition, values: np.ndarray, surface: SurfaceStats,
           p: SpeedPoint | None = None, scale: float = 1.0) -> list[Note]:
    excess = c.excess(values)
    if excess <= 1.0:
        return []
    detail = f"{_what(c, values, surface, p, scale)} ({c.report})"
    return [Note(cls.model, c.quantity, f"outside its validated class ({cls.name}): {detail}",
                 None if p is None else p.velocity, None if p is None else p.temperature,
                 excess, detail, cls.name)]


def _what(c: Condition, values: np.ndarray, surface: SurfaceStats, p: SpeedPoint | None,
          scale: float) -> str:
    """The failing values against the bounds, in words."""
    v = np.asarray(values, float)
    v = v[np.isfinite(v)] if np.isfinite(v).any() else v
    label = QUANTITIES[c.quantity]
    if c.quantity.startswith("frequency"):
        q = surface.wavenumbers(c.quantity == "frequency_high") * scale
        lo, hi = c.low / q.min(), c.high / q.max()
        span = (f"{lo:.3g}–{hi:.3g} mm/s" if lo <= hi else
                "no speed (the waves span more frequencies than were measured)")
        waves = "high-slope waves'" if c.quantity == "frequency_high" else "waves'"
        return f"its {waves} frequencies q·v leave the measured band; validated speeds {span}"
    if c.quantity == "dimension":
        return ("validated on one-dimensional surfaces only; on maps the mean-field was "
                "measured against the 2D BEM (docs/validation/maps_meanfield.md) and the "
                "hybrid's scale split, with the linear law, against the 2D VHS")
    if c.quantity == "law_pressure":
        return (f"local pressures reach {p.local_pressure:.3g} MPa, the law's FEM points end "
                f"at {p.law_top:.3g} MPa (the law is extrapolated)")
    lo, hi = float(v.min()), float(v.max())
    if lo < c.low and hi > c.high:
        got = f"{lo:.3g}–{hi:.3g}"
    else:
        got = f"up to {hi:.3g}" if hi > c.high else f"down to {lo:.3g}"
    return f"{label} {got}, validated {c.bounds_text()}"


def _departure(cls: ValidatedClass, p: SpeedPoint, found: tuple[float, float, float],
               outside: list[Note]) -> Note:
    """μ departs from the VHS beyond the class's tolerance: say so, and why, in one line."""
    excess, mu, ref = found
    if outside:
        worst = max(outside, key=lambda n: n.excess)
        more = f"; {len(outside) - 1} more condition(s)" if len(outside) > 1 else ""
        where = f"and the run lies outside its validated class ({cls.name}): {worst.detail}{more}"
    else:
        where = f"inside its validated class ({cls.name}): check the run ({cls.report})"
    detail = (f"μ {mu:.3g} departs from the VHS's {ref:.3g} beyond the {cls.tolerance:.0%} "
              f"measured against {cls.reference}")
    return Note(cls.model, "vhs", f"{detail}, {where}", p.velocity, p.temperature, excess,
                detail, cls.name)


def summarize(notes: Sequence[Note]) -> tuple[str, ...]:
    """One line per model: where it leaves its validated class, each condition once (the
    notes of many speeds folded into the speeds they hold at and the worst of them); a model
    inside its class whose μ departs from the VHS gets that note's line, folded likewise."""
    by_model: dict[str, list[Note]] = {}
    for n in notes:
        by_model.setdefault(n.model, []).append(n)
    return tuple(_model_line(model, group) for model, group in by_model.items())


def _model_line(model: str, notes: list[Note]) -> str:
    groups: dict[tuple[str, bool], list[Note]] = {}
    for n in notes:
        groups.setdefault((n.condition, n.velocity is None), []).append(n)
    if all(condition == "vhs" for condition, _ in groups):
        (group,) = groups.values()
        worst = max(group, key=lambda n: n.excess)
        return f"{model}{_where(group, worst)}: {worst.reason}"
    names = [n.class_name for n in notes if n.class_name]
    head = f"outside its validated class ({names[0]})" if names else "outside its class"
    parts = []
    for group in groups.values():
        worst = max(group, key=lambda n: n.excess)
        where = _where(group, worst).strip()
        parts.append(f"{where}: {worst.detail or worst.reason}" if where
                     else worst.detail or worst.reason)
    return f"{model}: {head}: " + "; ".join(parts)


def _where(group: list[Note], worst: Note) -> str:
    """Where a condition holds: nothing on the surface, the speed, or the speeds folded."""
    if worst.velocity is None:
        return ""
    at = Note("", "", "", worst.velocity, worst.temperature).text[:-2]
    if len(group) == 1:
        return at
    v = sorted(n.velocity for n in group)
    t = sorted({n.temperature for n in group if n.temperature is not None})
    what = "speeds" if not t else "(speed, temperature) points"
    span = _span(v, "mm/s", ".3g") + (", " + _span(t, "°C", "g") if t else "")
    return f" at {len(group)} {what} ({span}), worst{at}"


def _span(values: list[float], unit: str, fmt: str) -> str:
    lo, hi = format(values[0], fmt), format(values[-1], fmt)
    return f"{lo} {unit}" if lo == hi else f"{lo} … {hi} {unit}"


def as_attrs(model: str, notes: Sequence[Note]) -> dict[str, str]:
    """``{"validity_<model>": line}`` for a results file's attrs: the :func:`summarize`
    line of ``model``'s notes (empty: inside its class)."""
    return {f"validity_{model}": "\n".join(summarize([n for n in notes if n.model == model]))}
