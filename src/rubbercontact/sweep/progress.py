"""Progress reporting for sweeps: a rich bar on a terminal, log lines otherwise.

``progress="auto"`` (or True) shows a bar (done/total, failures, elapsed, ETA)
when stderr is a terminal and plain lines otherwise, at most one every
``interval`` seconds plus one per failure and a final one; ``"bar"`` and
``"log"`` force a mode; False (``--quiet``) is silent.

The ETA
-------
Without cost hints it is the count rate: the elapsed time per task computed, times the
tasks left. A sweep sends its longest tasks first (a law's highest-pressure speed paths,
the full FEM before the half-space solves), so a count rate read after the first, long task
prices every short task left as long as that one: 5 min after the first task of a 30 s
stage. When every task to compute carries a cost hint (:attr:`~.tasks.Task.cost`, expected
seconds, from ``run --check``'s per-task estimates), the ETA weighs the tasks instead
(:class:`WeightedEta`): the hints of the tasks left, scaled by what the finished tasks took
against their hints, shared between the workers.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import IO

from ..errors import InputError

__all__ = ["ProgressReporter", "WeightedEta", "Workload", "make_reporter"]


def _fmt(seconds: float) -> str:
    seconds = max(0, int(round(seconds)))
    h, rem = divmod(seconds, 3600)
    m, s = divmod(rem, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m:02d}:{s:02d}"


@dataclass(frozen=True)
class Workload:
    """What a sweep tells its reporter about the tasks it computes.

    Attributes
    ----------
    costs
        Each task's expected seconds (its cost hint, None: none), in the order the tasks
        are sent to the workers; the reporter's ``advance(task=k)`` names them by this
        index.
    workers
        Tasks that run at once (worker processes times threads; 1 in process).
    """

    costs: tuple[float | None, ...] = ()
    workers: int = 1

    @property
    def weighted(self) -> bool:
        """Whether every task has a hint (else the ETA is the count rate)."""
        return bool(self.costs) and all(c is not None for c in self.costs)


def scheduled(tasks: Sequence[float], workers: int) -> float:
    """Wall time [s] of ``tasks`` [s] on ``workers``, each task to the first free worker in
    order (how a sweep hands them out; ``run --check``'s wall time too)."""
    if not len(tasks):
        return 0.0
    free = [0.0] * max(1, min(workers, len(tasks)))
    for t in tasks:
        free[free.index(min(free))] += t
    return max(free)


@dataclass
class WeightedEta:
    """The ETA of a sweep whose tasks all have cost hints.

    ``finished(k, seconds)`` as each task ends; ``eta(elapsed)`` then estimates the wall
    time left: each unfinished task's hint times the ratio measured / expected of the tasks
    finished so far (1 before any), those that run now (the first ``workers`` unfinished,
    in the order sent) less the time the workers have spent on them since the start,
    handed out in order to the workers (:func:`scheduled`). The estimate assumes the workers
    take the tasks in the order sent (Dask's default priority: first submitted, first run)
    and were busy from the start (a cluster's start-up counts as work done, a few seconds).

    Attributes
    ----------
    workload
        The tasks' hints and the workers.
    left
        Indices of the unfinished tasks, in the order sent.
    measured, expected
        Seconds the finished tasks took (by their own clocks), and their hints: the scale
        of the hints left. A failed task is not counted (its time says nothing of its
        estimate).
    spent
        Seconds of every finished task, failed or not: the workers' time not spent on the
        tasks that run now.
    """

    workload: Workload
    left: list[int] = field(init=False)
    measured: float = 0.0
    expected: float = 0.0
    spent: float = 0.0

    def __post_init__(self) -> None:
        self.left = list(range(len(self.workload.costs)))

    @property
    def ratio(self) -> float:
        """Measured over expected seconds of the finished tasks (1 before any)."""
        return self.measured / self.expected if self.expected > 0 else 1.0

    def finished(self, task: int, seconds: float | None, failed: bool = False) -> None:
        """Task ``task`` ended after ``seconds`` (None: unknown)."""
        if task not in self.left:
            return
        self.left.remove(task)
        if seconds is None:
            return
        self.spent += seconds
        if not failed:
            self.measured += seconds
            self.expected += float(self.workload.costs[task])

    def eta(self, elapsed: float) -> float:
        """Wall seconds left, ``elapsed`` seconds after the sweep started."""
        rest = [self.ratio * float(self.workload.costs[k]) for k in self.left]
        if not rest:
            return 0.0
        workers = max(1, min(self.workload.workers, len(self.workload.costs)))
        # the workers' time since the start not spent on a finished task went to the tasks
        # that run now: the first unfinished ones in the order sent, the earliest sent having
        # started first, so it is credited first (none for longer than the sweep ran)
        pool = max(0.0, workers * elapsed - self.spent)
        for k in range(min(workers, len(rest))):
            credit = min(pool, elapsed)
            rest[k], pool = max(0.0, rest[k] - credit), pool - credit
        return scheduled(rest, workers)


class ProgressReporter:
    """Silent reporter; the base of the bar and line reporters.

    ``start(total, cached, workload=...)`` once, ``advance(failed=..., label=...,
    task=..., seconds=...)`` per task computed, ``close()`` at the end.

    Parameters
    ----------
    description
        Name shown in front of the bar or lines.
    clock
        Seconds of a monotonic clock (default :func:`time.perf_counter`).
    """

    def __init__(self, description: str = "sweep",
                 clock: Callable[[], float] = time.perf_counter) -> None:
        self.description = description
        self.clock = clock
        self.total = 0
        self.done = 0
        self.failed = 0
        self.cached = 0
        self.weights: WeightedEta | None = None
        self.t0 = clock()

    def start(self, total: int, cached: int = 0, cached_failed: int = 0,
              workload: Workload | None = None) -> None:
        """``total`` tasks, ``cached`` of them (``cached_failed`` failed) from the cache;
        ``workload``: the hints of the tasks to compute, in the order sent."""
        self.total, self.done, self.cached = total, cached, cached
        self.failed = cached_failed
        self.weights = (WeightedEta(workload) if workload is not None and workload.weighted
                        else None)
        self.t0 = self.clock()

    def advance(self, failed: bool = False, label: str = "", message: str = "",
                task: int | None = None, seconds: float | None = None) -> None:
        """One task computed: ``task``, its index in the workload, took ``seconds``."""
        self.done += 1
        self.failed += bool(failed)
        if self.weights is not None and task is not None:
            self.weights.finished(task, seconds, failed)

    def close(self) -> None:
        pass

    def eta(self) -> float | None:
        """Seconds left (None if unknown): weighted by the tasks' cost hints when they all
        have one (:class:`WeightedEta`), else extrapolated from the count of tasks
        computed so far."""
        elapsed = self.clock() - self.t0
        if self.weights is not None:
            return self.weights.eta(elapsed)
        computed = self.done - self.cached
        if computed <= 0:
            return None
        return elapsed / computed * (self.total - self.done)


class _LineReporter(ProgressReporter):
    def __init__(self, description: str, stream: IO[str], interval: float,
                 clock: Callable[[], float] = time.perf_counter) -> None:
        super().__init__(description, clock)
        self.stream = stream
        self.interval = interval
        self._last = 0.0

    def _line(self) -> None:
        elapsed = self.clock() - self.t0
        eta = self.eta()
        eta_text = "?" if eta is None else _fmt(eta)
        self.stream.write(f"[{self.description}] {self.done}/{self.total} done "
                          f"({self.cached} from cache, {self.failed} failed), "
                          f"elapsed {_fmt(elapsed)}, ETA {eta_text}\n")
        self.stream.flush()
        self._last = self.clock()

    def start(self, total: int, cached: int = 0, cached_failed: int = 0,
              workload: Workload | None = None) -> None:
        super().start(total, cached, cached_failed, workload)
        self._line()

    def advance(self, failed: bool = False, label: str = "", message: str = "",
                task: int | None = None, seconds: float | None = None) -> None:
        super().advance(failed, label, message, task, seconds)
        if failed:
            self.stream.write(f"[{self.description}] FAILED {label}: {message}\n")
        if failed or self.done == self.total \
                or self.clock() - self._last >= self.interval:
            self._line()

    def close(self) -> None:
        if self.done != self.total:  # interrupted: say where it stopped
            self._line()


class _BarReporter(ProgressReporter):
    def __init__(self, description: str, stream: IO[str]) -> None:
        super().__init__(description)
        from rich.console import Console
        from rich.progress import (
            BarColumn,
            MofNCompleteColumn,
            Progress,
            ProgressColumn,
            TextColumn,
            TimeElapsedColumn,
        )
        from rich.text import Text

        reporter = self

        class _Eta(ProgressColumn):
            # the reporter's ETA (weighted by the cost hints), not rich's own rate of
            # completions, which is the count rate the hints are there to replace
            def render(self, task) -> Text:
                eta = reporter.eta()
                return Text("-:--:--" if eta is None else _fmt(eta),
                            style="progress.remaining")

        self._progress = Progress(
            TextColumn("[bold]{task.description}"), BarColumn(), MofNCompleteColumn(),
            TextColumn("{task.fields[failed]} failed"), TimeElapsedColumn(),
            TextColumn("ETA"), _Eta(),
            console=Console(file=stream), transient=False)
        self._task = None

    def start(self, total: int, cached: int = 0, cached_failed: int = 0,
              workload: Workload | None = None) -> None:
        super().start(total, cached, cached_failed, workload)
        self._progress.start()
        self._task = self._progress.add_task(self.description, total=total,
                                             completed=cached, failed=self.failed)

    def advance(self, failed: bool = False, label: str = "", message: str = "",
                task: int | None = None, seconds: float | None = None) -> None:
        super().advance(failed, label, message, task, seconds)
        if failed:
            self._progress.console.print(f"FAILED {label}: {message}", markup=False)
        self._progress.update(self._task, advance=1, failed=self.failed)

    def close(self) -> None:
        self._progress.stop()


def make_reporter(progress: bool | str = "auto", description: str = "sweep",
                  stream: IO[str] | None = None, interval: float = 10.0) -> ProgressReporter:
    """Reporter for ``progress`` in {"auto", True, "bar", "log", False}.

    Parameters
    ----------
    progress
        ``"auto"``/True: bar on a TTY, lines otherwise; ``"bar"``, ``"log"``; False: silent.
    description
        Name shown in front of the bar or lines.
    stream
        Output stream (default ``sys.stderr``).
    interval
        Minimum seconds between two log lines (failures and the end always print).
    """
    stream = sys.stderr if stream is None else stream
    if progress is False or progress is None:
        return ProgressReporter(description)
    if progress is True or progress == "auto":
        progress = "bar" if getattr(stream, "isatty", lambda: False)() else "log"
    if progress == "bar":
        return _BarReporter(description, stream)
    if progress == "log":
        return _LineReporter(description, stream, interval)
    raise InputError(f"progress: expected 'auto', 'bar', 'log', True or False, "
                     f"got {progress!r}")
