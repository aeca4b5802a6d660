"""What every contact model is: a protocol, one result type, one way to run.

A model turns (surface, material, speed, mean pressures) into the friction coefficient and
the contact fraction at each pressure. It states its work as sweep tasks (pure functions of
plain data, :class:`~rubbercontact.sweep.Task`) and collects their results, so the same
model runs in a script (:meth:`TaskModel.solve`, in process, optionally cached) and in a
run's sweep (Dask, the result cache) without a second code path.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar, Protocol, runtime_checkable

import numpy as np
import xarray as xr

from .._validation import finite_array
from ..errors import InputError
from .planning import Planning, RunPoint

__all__ = ["ContactModel", "ContactResult", "TaskModel", "check_pressures"]

#: Units of the result variables.
UNITS = {"friction": "1", "contact_fraction": "1", "friction_hs": "1",
         "mean_separation": "mm", "pressure": "MPa", "velocity": "mm/s"}


@dataclass(frozen=True)
class ContactResult:
    """One model's answer at one speed over a set of mean pressures.

    Attributes
    ----------
    model
        Registered name of the model (``"vhs"``, ``"hybrid-windowed"``, ...).
    velocity
        Sliding speed v [mm/s].
    pressure
        Mean pressures σ0 [MPa], ascending.
    friction
        Friction coefficient μ per pressure [-] (NaN where the solve failed).
    contact_fraction
        Real contact area over nominal area A_c/A_0 per pressure [-].
    mean_separation
        Mean separation ū [mm] (NaN where the model has none, e.g. the mean-field).
    friction_hs
        The high-slope law's share of μ [-] (NaN for models without a law).
    status
        ``"ok"`` or the failure message, per pressure.
    attrs
        Provenance: the model's options, the surface and material as plain data.
    """

    model: str
    velocity: float
    pressure: np.ndarray
    friction: np.ndarray
    contact_fraction: np.ndarray
    mean_separation: np.ndarray
    friction_hs: np.ndarray
    status: tuple[str, ...]
    attrs: Mapping[str, Any] = field(default_factory=dict)

    @property
    def ok(self) -> np.ndarray:
        """Boolean mask of the pressures whose solve succeeded."""
        return np.array([s == "ok" for s in self.status])

    def to_dataset(self) -> xr.Dataset:
        """The result as an ``xarray.Dataset`` on a ``pressure`` dimension, units in attrs."""
        data = {k: ("pressure", np.asarray(getattr(self, k), float), {"units": UNITS[k]})
                for k in ("friction", "contact_fraction", "mean_separation", "friction_hs")}
        ds = xr.Dataset(data, coords={"pressure": ("pressure", np.asarray(self.pressure),
                                                   {"units": "MPa"})})
        ds["status"] = ("pressure", np.array(self.status, dtype=str))
        ds.attrs = {"model": self.model, "velocity_mm_s": float(self.velocity),
                    **{k: v for k, v in self.attrs.items() if isinstance(v, (str, int, float))}}
        return ds


@runtime_checkable
class ContactModel(Protocol):
    """A contact model: ``solve(surface, material, velocity, pressures) -> ContactResult``."""

    name: str

    def solve(self, surface: Any, material: Any, velocity: float,
              pressures: Sequence[float]) -> ContactResult:
        """μ and A_c/A_0 of ``surface`` against ``material`` at ``velocity`` [mm/s] and each
        mean pressure [MPa]."""
        ...


def check_pressures(pressures: Sequence[float], velocity: float) -> np.ndarray:
    """Mean pressures as an ascending array > 0 MPa, and a speed > 0 mm/s (one-line errors)."""
    p = np.sort(finite_array("pressures", pressures, ndim=1))
    if p.size == 0 or np.any(p <= 0):
        raise InputError(f"pressures: need at least one, each > 0 MPa, got {p.tolist()}")
    if not np.isfinite(velocity) or velocity <= 0:
        raise InputError(f"velocity: must be > 0 mm/s, got {velocity}")
    return p


class TaskModel:
    """Base of the models that state their work as sweep tasks.

    Subclasses set :attr:`name` and implement :meth:`tasks` (the work) and
    :meth:`collect` (the tasks' datasets to a :class:`ContactResult`); a model a run can
    plan also sets :attr:`planning` and implements :meth:`run_task` (and, for data its
    tasks share, :meth:`run_data`).
    """

    name: str = ""
    #: How a run plans it (:class:`~.planning.Planning`); ``None``: scripts only.
    planning: ClassVar[Planning | None] = None

    @classmethod
    def run_data(cls, name: str, setup: Any) -> Any:
        """Data the model's tasks in a run share, built once per run (default: none)."""
        return None

    @classmethod
    def run_task(cls, name: str, point: RunPoint) -> tuple[str, dict]:
        """The task function (``"module:function"``) and its arguments at one place of a
        run; ``name`` is the registered name (one class may serve several)."""
        raise NotImplementedError(f"model {name!r} does not say how a run plans it")

    def tasks(self, surface: Any, material: Any, velocity: float,
              pressures: np.ndarray) -> list:
        """The sweep tasks of one solve."""
        raise NotImplementedError

    def collect(self, results: list, velocity: float, pressures: np.ndarray) -> ContactResult:
        """The tasks' results (datasets or failures, in the order of :meth:`tasks`)."""
        raise NotImplementedError

    def solve(self, surface: Any, material: Any, velocity: float,
              pressures: Sequence[float], *, cache: Any = None) -> ContactResult:
        """Run the tasks in this process (with ``cache``, a
        :class:`~rubbercontact.sweep.ResultCache`, reusing and storing results)."""
        from ..sweep import ExecutorConfig, run_sweep

        p = check_pressures(pressures, float(velocity))
        tasks = self.tasks(surface, material, float(velocity), p)
        res = run_sweep(tasks, cache=cache, executor=ExecutorConfig(synchronous=True),
                        progress=False)
        return self.collect(list(res.results), float(velocity), p)


def scalar_rows(model: str, results: list, velocity: float, pressures: np.ndarray,
                attrs: Mapping[str, Any]) -> ContactResult:
    """A result from one scalar dataset (or failure) per pressure."""
    def get(ds, k):
        return float(ds[k]) if isinstance(ds, xr.Dataset) and k in ds else np.nan

    cols = {k: np.array([get(ds, k) for ds in results])
            for k in ("friction", "contact_fraction", "mean_separation", "friction_hs")}
    status = tuple("ok" if isinstance(ds, xr.Dataset) else f"failed: {ds}" for ds in results)
    return ContactResult(model, velocity, pressures, cols["friction"],
                         cols["contact_fraction"], cols["mean_separation"],
                         cols["friction_hs"], status, dict(attrs))
