"""The half-space models: the VHS on the whole surface, and the hybrid with a law.

Both run :func:`rubbercontact.hybrid.tasks.halfspace_loads_task` (one task over every
load), the same task the pipeline runs, so a script and a run share cache entries.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import xarray as xr

from ..errors import InputError
from ..roughness import SineSeries
from .base import ContactResult, TaskModel
from .planning import PER_REALIZATION, Planning, RunPoint

__all__ = ["HalfspaceOptions", "VHS", "Hybrid"]

LOADS_TASK = "rubbercontact.hybrid.tasks:halfspace_loads_task"
#: The rubber-road interactions of the half-space solve.
LAWS = ("lennard-jones", "hard-wall")


@dataclass(frozen=True)
class HalfspaceOptions:
    """The half-space solve of a model.

    Attributes
    ----------
    n
        Grid points per period [-] (the hybrid's low-slope grid defaults to the
        equal-points-per-wave rule of :func:`rubbercontact.hybrid.grid.low_slope_points`).
    nu
        Poisson's ratio of the rubber [-].
    law
        The rubber-road interaction: ``"lennard-jones"`` (a stiff repulsive wall) or
        ``"hard-wall"`` (exact complementarity).
    tol
        Relative residual tolerance of the solve [-].
    """

    n: int = 4096
    nu: float = 0.5
    law: Literal[LAWS] = "lennard-jones"
    tol: float = 1e-8

    def __post_init__(self) -> None:
        if not (isinstance(self.n, int) and self.n >= 64):
            raise InputError(f"n: grid points per period must be an int >= 64, got {self.n!r}")
        if self.law not in LAWS:
            raise InputError(f"law: one of {', '.join(LAWS)}, got {self.law!r}")
        if not 0 < self.tol < 1:
            raise InputError(f"tol: must be in (0, 1), got {self.tol!r}")


def _material_dict(material: Any) -> dict:
    from ..pipeline.setup import task_material

    return task_material(material)


def _surface(surface: Any) -> SineSeries:
    if not isinstance(surface, SineSeries):
        raise InputError(f"surface: the half-space models take a SineSeries, got "
                         f"{type(surface).__name__}")
    return surface


def _loads_result(name: str, results: list, velocity: float, pressures: np.ndarray,
                  attrs: Mapping[str, Any]) -> ContactResult:
    (ds,) = results
    if not isinstance(ds, xr.Dataset):
        nan = np.full(pressures.size, np.nan)
        return ContactResult(name, velocity, pressures, nan, nan, nan, nan,
                             (f"failed: {ds}",) * pressures.size, dict(attrs))

    def col(k):
        return np.asarray(ds[k].values, float) if k in ds else np.full(pressures.size, np.nan)

    hs = col("friction_hs") if attrs.get("hybrid") else np.full(pressures.size, np.nan)
    return ContactResult(name, velocity, pressures, col("friction"), col("contact_fraction"),
                         col("mean_separation"), hs, tuple(ds["status"].values.astype(str)),
                         dict(attrs))


def loads_kwargs(surface: SineSeries, period: float, material: Any, velocity: float,
                 pressures, options: HalfspaceOptions, *, n: int | None = None,
                 interface_law: dict | None = None, hs_window: float | None = None,
                 keep_profile: bool = False) -> dict:
    """Arguments of one :func:`~rubbercontact.hybrid.tasks.halfspace_loads_task`: the VHS
    (no law) or the hybrid's low-slope solve. The one place they are written, for the
    models and for a run's plan alike, so that both share cache entries."""
    kw = {"surface": surface.as_dict(), "period": float(period),
          "material": _material_dict(material), "velocity": float(velocity),
          "mean_pressures": [float(p) for p in pressures], "n": int(n or options.n),
          "nu": options.nu, "law": options.law, "tol": options.tol,
          "interface_law": interface_law, "keep_profile": bool(keep_profile)}
    if hs_window is not None:
        kw["hs_window"] = float(hs_window)
    return kw


def run_options(cfg: Any) -> HalfspaceOptions:
    """A run config's (:class:`rubbercontact.config.RunConfig`) half-space options."""
    hsc = cfg.halfspace
    return HalfspaceOptions(n=hsc.n, nu=cfg.material.nu, law=hsc.law, tol=hsc.tol)


class VHS(TaskModel):
    """The viscoelastic half-space (BEM) on the whole surface (``"vhs"``)."""

    name = "vhs"
    planning = Planning(PER_REALIZATION)

    @classmethod
    def run_task(cls, name: str, point: RunPoint) -> tuple[str, dict]:
        """One realization at every load (its profiles kept for the first)."""
        s, ir = point.setup, point.realization
        return LOADS_TASK, loads_kwargs(s.realizations[ir], s.period, point.material,
                                        point.velocity, point.pressures,
                                        run_options(s.config), keep_profile=ir == 0)

    def __init__(self, options: HalfspaceOptions | None = None) -> None:
        self.options = options or HalfspaceOptions()

    def tasks(self, surface, material, velocity, pressures):
        from ..sweep import Task

        surf = _surface(surface)
        kw = loads_kwargs(surf, surf.period, material, velocity, pressures, self.options)
        return [Task(LOADS_TASK, kw, label=f"vhs v={velocity:g}")]

    def collect(self, results, velocity, pressures):
        return _loads_result(self.name, results, velocity, pressures, {"law": self.options.law})


#: A law: a table over speeds (:func:`rubbercontact.hybrid.effective_law`), a callable
#: ``velocity -> table`` (e.g. the linear law), or ``{velocity: table}``.
LawSource = xr.Dataset | Callable[[float], dict] | Mapping[float, dict]


def check_law(law: LawSource) -> LawSource:
    """``law`` if it is a :data:`LawSource` (else one :class:`InputError` line)."""
    if not isinstance(law, (xr.Dataset, Mapping)) and not callable(law):
        raise InputError(f"law: a law table (xarray.Dataset), a callable velocity -> "
                         f"table, or {{velocity: table}}; got {type(law).__name__}")
    return law


def read_law(law: LawSource, velocity: float) -> dict:
    """The law at ``velocity`` [mm/s] as plain data (separation, pressure, α, Δτ)."""
    from ..hybrid import law_at_velocity

    if isinstance(law, xr.Dataset):
        return law_at_velocity(law, velocity)
    if isinstance(law, Mapping):
        match = [v for v in law if np.isclose(float(v), velocity, rtol=1e-9)]
        if not match:
            raise InputError(f"law: no table at {velocity} mm/s (has "
                             f"{sorted(map(float, law))} mm/s)")
        return dict(law[match[0]])
    return dict(law(velocity))


class Hybrid(TaskModel):
    """The hybrid: the low-slope waves by the half-space, the high-slope ones by a law.

    Parameters
    ----------
    law
        The high-slope scale's interface law (see :data:`LawSource`).
    reading
        ``"windowed"`` (``"hybrid-windowed"``: the law read at the pressure averaged over
        one high-slope period, this package's recommended reading) or ``"pointwise"``
        (``"hybrid"``: the paper's reading at each grid point).
    m2_threshold
        A wave is high-slope when its rms slope m2 exceeds this [-] (the paper's 1).
    options
        The low-slope half-space solve.
    """

    planning = Planning(PER_REALIZATION, reads_law=True, splits=True)
    #: The registered names and the reading each stands for.
    READINGS = {"hybrid-windowed": "windowed", "hybrid": "pointwise"}

    def __init__(self, law: LawSource, reading: Literal["windowed", "pointwise"] = "windowed",
                 m2_threshold: float = 1.0, options: HalfspaceOptions | None = None) -> None:
        if reading not in ("windowed", "pointwise"):
            raise InputError(f"reading: 'windowed' or 'pointwise', got {reading!r}")
        self.law, self.reading = check_law(law), reading
        self.m2_threshold = float(m2_threshold)
        self.options = options or HalfspaceOptions()
        self.name = next(k for k, r in self.READINGS.items() if r == reading)

    @classmethod
    def run_task(cls, name: str, point: RunPoint) -> tuple[str, dict]:
        """The low-slope solve of one realization at every load: on ``halfspace.hybrid_n``
        points or the grid of :func:`~rubbercontact.hybrid.grid.low_slope_points`; a
        realization without a high-slope wave is solved whole on ``halfspace.n``."""
        from ..hybrid.grid import low_slope_points

        s, ir = point.setup, point.realization
        real, parts, opts = s.realizations[ir], s.parts[ir], run_options(s.config)
        args = (s.period, point.material, point.velocity, point.pressures, opts)
        if parts.high.size == 0:
            return LOADS_TASK, loads_kwargs(real, *args, interface_law=point.table,
                                            keep_profile=ir == 0)
        windowed = cls.READINGS[name] == "windowed"
        return LOADS_TASK, loads_kwargs(
            parts.low, *args, n=s.config.halfspace.hybrid_n or low_slope_points(opts.n, real,
                                                                                parts.low),
            interface_law=point.table, hs_window=float(s.hs0.period) if windowed else None,
            keep_profile=ir == 0)

    def table(self, velocity: float) -> dict:
        """The law at ``velocity`` as plain data (separation, pressure, α, Δτ)."""
        return read_law(self.law, velocity)

    def tasks(self, surface, material, velocity, pressures):
        from ..hybrid.grid import low_slope_points
        from ..sweep import Task

        surf, o = _surface(surface), self.options
        high, low = surf.partition(self.m2_threshold)
        if high.size == 0:
            raise InputError(f"surface: no wave has m2 > {self.m2_threshold:g}; without a "
                             f"high-slope scale the hybrid is the VHS (use VHS)")
        kw = loads_kwargs(low, surf.period, material, velocity, pressures, o,
                          n=low_slope_points(o.n, surf, low),
                          interface_law=self.table(velocity),
                          hs_window=float(high.period) if self.reading == "windowed" else None)
        return [Task(LOADS_TASK, kw, label=f"{self.name} v={velocity:g}")]

    def collect(self, results, velocity, pressures):
        return _loads_result(self.name, results, velocity, pressures,
                             {"law": self.options.law, "hybrid": 1, "reading": self.reading,
                              "m2_threshold": self.m2_threshold})
