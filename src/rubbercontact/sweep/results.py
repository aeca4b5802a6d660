"""What a sweep returns: one result per task, failures as records, and counts."""

from __future__ import annotations

import json
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import xarray as xr

from .tasks import Task

__all__ = ["SweepResult", "TaskFailure", "jsonable"]


def jsonable(value: Any) -> Any:
    """Best-effort conversion of diagnostics to JSON-ready data (arrays to lists, ...)."""
    if value is None or isinstance(value, (str, bool, int)):
        return value
    if isinstance(value, float):
        return value if np.isfinite(value) else repr(value)
    if isinstance(value, np.generic):
        return jsonable(value.item())
    if isinstance(value, np.ndarray):
        return jsonable(value.tolist())
    if isinstance(value, complex):
        return {"real": jsonable(value.real), "imag": jsonable(value.imag)}
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, set)):
        return [jsonable(v) for v in value]
    return repr(value)


@dataclass
class TaskFailure:
    """A task that raised instead of returning a dataset.

    Attributes
    ----------
    message
        ``str(exception)``.
    error_type
        Exception class name, e.g. ``"ConvergenceError"``.
    diagnostics
        ``exception.diagnostics`` for :class:`~rubbercontact.errors.ConvergenceError`
        (JSON-ready), else empty.
    traceback
        Formatted traceback from the worker (may be empty for cached failures
        written by other tools).
    wall_time
        Seconds spent in the task before it failed.
    cached
        True when the failure is written to (or was read from) the cache. Worker
        crashes, cancellations and ``MemoryError`` are not cached: they say nothing
        about the task itself.
    """

    message: str
    error_type: str = "Exception"
    diagnostics: dict[str, Any] = field(default_factory=dict)
    traceback: str = ""
    wall_time: float = 0.0
    cached: bool = False
    status: str = "failed"

    def to_attrs(self) -> dict[str, Any]:
        """NetCDF attributes describing the failure."""
        return {"message": self.message, "error_type": self.error_type,
                "diagnostics": json.dumps(jsonable(self.diagnostics), sort_keys=True),
                "traceback": self.traceback}

    def __str__(self) -> str:
        return f"{self.error_type}: {self.message}"


@dataclass
class SweepResult:
    """Outcome of :func:`~rubbercontact.sweep.run_sweep`, in task order.

    Attributes
    ----------
    tasks
        The tasks, as given.
    keys
        Their cache keys.
    results
        Per task an :class:`xarray.Dataset` or a :class:`TaskFailure`.
    sources
        Per task ``"computed"``, ``"cache"`` or ``"duplicate"`` (same key as an
        earlier task in the list: computed once).
    wall_time
        Wall-clock time of the whole sweep [s].
    task_times
        Per task the wall time of the function call itself [s] (from the cache
        entry for cached results).
    """

    tasks: list[Task]
    keys: list[str]
    results: list[xr.Dataset | TaskFailure]
    sources: list[str]
    wall_time: float
    task_times: list[float]

    # -- counts -------------------------------------------------------------------------
    @property
    def n_computed(self) -> int:
        """Tasks whose function ran in this sweep (successfully or not)."""
        return self.sources.count("computed")

    @property
    def n_cached(self) -> int:
        """Tasks answered from the cache (successful or recorded failures)."""
        return self.sources.count("cache")

    @property
    def n_failed(self) -> int:
        """Tasks whose result is a :class:`TaskFailure`."""
        return sum(isinstance(r, TaskFailure) for r in self.results)

    @property
    def ok(self) -> bool:
        """True when no task failed; a CLI exits non-zero otherwise."""
        return self.n_failed == 0

    @property
    def failures(self) -> list[tuple[Task, TaskFailure]]:
        """(task, failure) pairs of the failed tasks."""
        return [(t, r) for t, r in zip(self.tasks, self.results, strict=True)
                if isinstance(r, TaskFailure)]

    @property
    def datasets(self) -> list[xr.Dataset | None]:
        """Per task its dataset, or None where it failed (aligned with ``tasks``)."""
        return [r if isinstance(r, xr.Dataset) else None for r in self.results]

    def summary(self) -> str:
        """Multi-line human-readable summary listing each failure."""
        lines = [f"{len(self.tasks)} tasks: {self.n_computed} computed, {self.n_cached} from "
                 f"cache, {self.n_failed} failed; wall time {self.wall_time:.1f} s"]
        for task, failure in self.failures:
            lines.append(f"  FAILED {task.name}: {failure}")
        return "\n".join(lines)

    def __len__(self) -> int:
        return len(self.results)

    def __getitem__(self, index: int) -> xr.Dataset | TaskFailure:
        return self.results[index]

    def __iter__(self) -> Iterator[xr.Dataset | TaskFailure]:
        return iter(self.results)

    @classmethod
    def _empty(cls, tasks: Sequence[Task], keys: Sequence[str]) -> SweepResult:
        n = len(tasks)
        return cls(list(tasks), list(keys), [None] * n, [""] * n, 0.0, [0.0] * n)  # type: ignore[list-item]
