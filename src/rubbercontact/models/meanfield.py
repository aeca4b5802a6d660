"""The mean-field models: Persson's theory (``"meanfield"``), the same on the low-slope
waves with the high-slope law (``"meanfield-hybrid"``) and the strip cascade of a 1D sine
series (``"meanfield-strips"``); one solve per mean pressure."""

from __future__ import annotations

from typing import Any

from ..errors import InputError
from ..roughness import SineSeries
from .base import TaskModel, scalar_rows
from .halfspace import LawSource, _material_dict, check_law, read_law
from .planning import PER_LOAD, Planning, RunPoint

__all__ = ["MeanField", "MeanFieldHybrid", "MeanFieldStrips"]

MEANFIELD_TASK = "rubbercontact.meanfield.tasks:meanfield_task"
HALFSPACE_TASK = "rubbercontact.hybrid.tasks:halfspace_task"


def task_kwargs(surface: dict, material: dict, velocity: float, mean_pressure: float,
                nu: float, options: Any, interface_law: dict | None = None) -> dict:
    """The mean-field task's arguments (the one writer: scripts and runs share entries)."""
    return {"surface": surface, "material": material, "velocity": float(velocity),
            "mean_pressure": float(mean_pressure), "nu": float(nu),
            "interface_law": interface_law, "options": options.to_dict()}


class MeanField(TaskModel):
    """Persson's mean-field theory with ``S(q)`` on the surface's spectrum.

    Parameters
    ----------
    options
        :class:`rubbercontact.meanfield.MeanFieldOptions` (default: its defaults).
    nu
        Poisson's ratio [-].
    """

    name = "meanfield"
    _options_class = "MeanFieldOptions"
    planning = Planning(PER_LOAD)

    def __init__(self, options: Any = None, nu: float = 0.5) -> None:
        from .. import meanfield as mf

        cls = getattr(mf, self._options_class)
        opts = cls() if options is None else options
        if not isinstance(opts, cls):
            raise InputError(f"model {self.name}: options must be {cls.__name__}, got "
                             f"{type(opts).__name__}")
        self.options = opts
        self.nu = float(nu)

    def tasks(self, surface, material, velocity, pressures):
        from ..meanfield import PSD
        from ..sweep import Task

        data = surface.as_dict() if isinstance(surface, (SineSeries, PSD)) else dict(surface)
        mat = _material_dict(material)
        return [Task(MEANFIELD_TASK, task_kwargs(data, mat, velocity, p, self.nu, self.options),
                     label=f"{self.name} v={velocity:g} p={p:.4g}") for p in pressures]

    def collect(self, results, velocity, pressures):
        return scalar_rows(self.name, results, velocity, pressures,
                           {k: str(v) for k, v in self.options.to_dict().items()})

    @classmethod
    def run_data(cls, name: str, setup: Any) -> dict:
        """The spectrum the theory reads: the run's sine series without phases, or the
        measured profiles' periodogram (``meanfield.spectrum = "profiles"``)."""
        from ..pipeline.setup import static_series

        cfg = setup.config
        if cfg.meanfield.spectrum != "profiles":
            return static_series(setup.base).as_dict()
        from ..meanfield import PSD
        from ..meanfield.psd import NODES_PER_DECADE

        return PSD.from_profiles(setup.surface.profiles,
                                 nodes_per_decade=cfg.meanfield.nodes_per_decade
                                 or NODES_PER_DECADE).as_dict()

    @classmethod
    def run_task(cls, name: str, point: RunPoint) -> tuple[str, dict]:
        """One load; the answer stands for every realization."""
        law = point.table if cls.planning.reads_law else None
        return config_call(point.setup.config, name, point.shared, point.material,
                           point.velocity, point.pressure, law, point.setup.period)


class MeanFieldStrips(MeanField):
    """The cascade of Westergaard strips of a 1D sine series
    (:class:`rubbercontact.meanfield.StripOptions`)."""

    name = "meanfield-strips"
    _options_class = "StripOptions"

    @classmethod
    def run_data(cls, name: str, setup: Any) -> dict:
        """The run's sine series without phases."""
        from ..pipeline.setup import static_series

        return static_series(setup.base).as_dict()


class MeanFieldHybrid(MeanField):
    """Persson's theory on the low-slope waves with the high-slope law as the interface
    (``"meanfield-hybrid"``).

    Parameters
    ----------
    law
        The high-slope scale's interface law (:data:`~.halfspace.LawSource`).
    options
        :class:`rubbercontact.meanfield.MeanFieldOptions` (default: its defaults).
    nu
        Poisson's ratio [-].
    m2_threshold
        A wave is high-slope when its rms slope m2 exceeds this [-].
    """

    name = "meanfield-hybrid"
    planning = Planning(PER_LOAD, reads_law=True, splits=True)

    def __init__(self, law: LawSource, options: Any = None, nu: float = 0.5,
                 m2_threshold: float = 1.0) -> None:
        super().__init__(options, nu)
        self.law = check_law(law)
        self.m2_threshold = float(m2_threshold)

    def tasks(self, surface, material, velocity, pressures):
        from ..pipeline.setup import static_series
        from ..sweep import Task

        if not isinstance(surface, SineSeries):
            raise InputError(f"surface: {self.name} takes a SineSeries, got "
                             f"{type(surface).__name__}")
        high, low = static_series(surface).partition(self.m2_threshold)
        if high.size == 0 or low.size == 0:
            raise InputError(f"surface: {self.name} needs waves on both sides of m2 = "
                             f"{self.m2_threshold:g} (without high-slope waves use "
                             f"MeanField; with only high-slope ones the law is the answer)")
        kw = {"interface_law": read_law(self.law, velocity)}
        mat = _material_dict(material)
        return [Task(MEANFIELD_TASK, task_kwargs(low.as_dict(), mat, velocity, p, self.nu,
                                                 self.options, **kw),
                     label=f"{self.name} v={velocity:g} p={p:.4g}") for p in pressures]

    @classmethod
    def run_data(cls, name: str, setup: Any) -> dict:
        """The low-slope waves without phases (the law carries the rest), or the whole
        series when it has no high-slope wave."""
        from ..pipeline.setup import static_series

        series = static_series(setup.base)
        high, low = series.partition(setup.config.surface.m2_threshold)
        return (low if high.size else series).as_dict()


def config_call(cfg: Any, model: str, surface: dict, material: Any, velocity: float,
                mean_pressure: float, law: dict | None, period: float) -> tuple[str, dict]:
    """Function and arguments of one mean-field task of a run config
    (:class:`rubbercontact.config.RunConfig`).

    ``meanfield-hybrid`` on a surface whose waves are all high-slope has no low-slope
    spectrum: the interface is flat and the exact answer is the law itself, which the
    half-space task's flat-interface solve gives (as for the hybrid).
    """
    mat = _material_dict(material)
    if law is not None and not surface["wavelengths"]:
        return HALFSPACE_TASK, {"surface": surface, "period": period, "material": mat,
                                "velocity": velocity, "mean_pressure": mean_pressure,
                                "n": cfg.halfspace.n, "nu": cfg.material.nu,
                                "law": cfg.halfspace.law, "interface_law": law}
    # without a law (no high-slope wave) meanfield-hybrid is the plain theory: no interface
    opts = cfg.meanfield.options(model if law is not None or model != "meanfield-hybrid"
                                 else "meanfield")
    return MEANFIELD_TASK, task_kwargs(surface, mat, velocity, mean_pressure,
                                       cfg.material.nu, opts, interface_law=law)
