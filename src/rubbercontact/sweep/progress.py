"""Progress reporting for sweeps: a rich bar on a terminal, log lines otherwise.

``progress="auto"`` (or True) shows a bar (done/total, failures, elapsed, ETA)
when stderr is a terminal and plain lines otherwise, at most one every
``interval`` seconds plus one per failure and a final one; ``"bar"`` and
``"log"`` force a mode; False (``--quiet``) is silent.
"""

from __future__ import annotations

import sys
import time
from typing import IO

from ..errors import InputError

__all__ = ["ProgressReporter", "make_reporter"]


def _fmt(seconds: float) -> str:
    seconds = max(0, int(round(seconds)))
    h, rem = divmod(seconds, 3600)
    m, s = divmod(rem, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m:02d}:{s:02d}"


class ProgressReporter:
    """Silent reporter; the base of the bar and line reporters.

    ``start(total, cached)`` once, ``advance(failed=..., label=...)`` per task
    computed, ``close()`` at the end.
    """

    def __init__(self, description: str = "sweep") -> None:
        self.description = description
        self.total = 0
        self.done = 0
        self.failed = 0
        self.cached = 0
        self.t0 = time.perf_counter()

    def start(self, total: int, cached: int = 0, cached_failed: int = 0) -> None:
        self.total, self.done, self.cached = total, cached, cached
        self.failed = cached_failed
        self.t0 = time.perf_counter()

    def advance(self, failed: bool = False, label: str = "", message: str = "") -> None:
        self.done += 1
        self.failed += bool(failed)

    def close(self) -> None:
        pass

    def eta(self) -> float | None:
        """Seconds left, extrapolated from the tasks computed so far (None if unknown)."""
        computed = self.done - self.cached
        if computed <= 0:
            return None
        rate = (time.perf_counter() - self.t0) / computed
        return rate * (self.total - self.done)


class _LineReporter(ProgressReporter):
    def __init__(self, description: str, stream: IO[str], interval: float) -> None:
        super().__init__(description)
        self.stream = stream
        self.interval = interval
        self._last = 0.0

    def _line(self) -> None:
        elapsed = time.perf_counter() - self.t0
        eta = self.eta()
        eta_text = "?" if eta is None else _fmt(eta)
        self.stream.write(f"[{self.description}] {self.done}/{self.total} done "
                          f"({self.cached} from cache, {self.failed} failed), "
                          f"elapsed {_fmt(elapsed)}, ETA {eta_text}\n")
        self.stream.flush()
        self._last = time.perf_counter()

    def start(self, total: int, cached: int = 0, cached_failed: int = 0) -> None:
        super().start(total, cached, cached_failed)
        self._line()

    def advance(self, failed: bool = False, label: str = "", message: str = "") -> None:
        super().advance(failed, label, message)
        if failed:
            self.stream.write(f"[{self.description}] FAILED {label}: {message}\n")
        if failed or self.done == self.total \
                or time.perf_counter() - self._last >= self.interval:
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
            TextColumn,
            TimeElapsedColumn,
            TimeRemainingColumn,
        )

        self._progress = Progress(
            TextColumn("[bold]{task.description}"), BarColumn(), MofNCompleteColumn(),
            TextColumn("{task.fields[failed]} failed"), TimeElapsedColumn(),
            TextColumn("ETA"), TimeRemainingColumn(),
            console=Console(file=stream), transient=False)
        self._task = None

    def start(self, total: int, cached: int = 0, cached_failed: int = 0) -> None:
        super().start(total, cached, cached_failed)
        self._progress.start()
        self._task = self._progress.add_task(self.description, total=total,
                                             completed=cached, failed=self.failed)

    def advance(self, failed: bool = False, label: str = "", message: str = "") -> None:
        super().advance(failed, label, message)
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
