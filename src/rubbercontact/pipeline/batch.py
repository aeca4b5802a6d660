"""Task batches: the sweep tasks of one result and how to read it from their answers.

A stage that needs several independent results (the law's FEM points and the cell's
quasi-static check) sends all their tasks to the runner in one sweep, so that the workers
are never idle at the end of one part while the next waits: the quasi-static points fill
the workers while the law's longest speed path runs.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Batch:
    """The sweep ``tasks`` of one result and ``collect(answers) -> result``, the answers
    in the tasks' order."""

    tasks: list
    collect: Callable[[list], Any]


def run_batches(runner, batches: Sequence[Batch | None]) -> list:
    """The results of ``batches`` (None stays None), their tasks run in one sweep in the
    order given (``runner(tasks)`` returns the answers in order)."""
    tasks = [t for b in batches if b is not None for t in b.tasks]
    answers = runner(tasks) if tasks else []
    out, k = [], 0
    for b in batches:
        if b is None:
            out.append(None)
            continue
        out.append(b.collect(list(answers[k:k + len(b.tasks)])))
        k += len(b.tasks)
    return out
