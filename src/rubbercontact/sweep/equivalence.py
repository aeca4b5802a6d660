"""Declared equivalence of code digests, for result caches kept across code changes.

The code a task runs is part of its cache key (:mod:`.codehash`), so every edit of the FEM
makes the tracked FEM solves behind the validation report (``docs/validation/
reference-cache``, hours of compute) unreachable. Recomputing them after a refactoring
that does not change the answers would be waste; serving them without a word would be
the stale cache this design exists to prevent. The way between is an explicit record, kept
beside the cache (``equivalence.json``): *entries of this function computed by code A are
accepted as answers of code B*, with the reason and the check that supports it. A check
recomputes a sample of the entries with code B and compares every variable
(:func:`check_sample`); :func:`accept` refuses to record an equivalence the check does not
support. :func:`seed` copies a reference cache into a working cache, re-keying the accepted
entries under the current code's keys (their arguments as the current code writes them,
:data:`CURRENT_ARGUMENTS`); an entry of any other code is not copied.
"""

from __future__ import annotations

import json
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from ..errors import InputError
from .cache import CopyReport, ResultCache, entry_code
from .codehash import code_digest
from .tasks import Task, plain

__all__ = ["Accepted", "SampleCheck", "accept", "check_sample", "entries", "load_equivalence",
           "seed"]

#: File of the declared equivalences, beside the cache's ``sweep-v1`` directory.
FILE_NAME = "equivalence.json"
#: Variables that say how a solve went, not what it found: an equivalent code may take
#: other steps to the same answer, so these are not compared.
EFFORT = ("wall_time", "steps", "iterations", "newton_iterations", "cutbacks",
          "krylov_iterations")
_PREFIX = "rc_cache_"


@dataclass(frozen=True)
class Accepted:
    """Entries of ``function`` computed by code ``stored`` answer as code ``current``.

    ``stored`` is "" for entries written before keys carried a code digest.
    """

    function: str
    stored: str
    current: str
    why: str
    checked: str


@dataclass(frozen=True)
class SampleCheck:
    """What :func:`check_sample` recomputed and the largest relative difference found."""

    function: str
    stored: str
    n: int
    max_rel_diff: float
    worst: str

    def __str__(self) -> str:
        return (f"recomputed {self.n} entries of {self.function.split(':')[-1]} "
                f"(stored code {self.stored[:12] or 'before digests'}): largest relative "
                f"difference {self.max_rel_diff:.2e} ({self.worst})")


def load_equivalence(directory: Path) -> list[Accepted]:
    """The equivalences recorded beside the cache in ``directory`` ([] if none)."""
    path = Path(directory) / FILE_NAME
    if not path.exists():
        return []
    try:
        rows = json.loads(path.read_text())["accepted"]
        return [Accepted(**row) for row in rows]
    except (json.JSONDecodeError, KeyError, TypeError) as exc:
        raise InputError(f"{path}: not an equivalence file ({exc})") from exc


def entries(reference: ResultCache, functions: tuple[str, ...]):
    """``(path, function, stored code)`` of the successful entries of ``functions``."""
    for path in sorted(reference.directory.glob("sweep-v1/*/*.nc")):
        if path.name.endswith(".failed.nc") or path.name.startswith("."):
            continue
        function, code = entry_code(path)
        if function.endswith(functions):
            yield path, function, code


def _task_of(ds: xr.Dataset) -> Task:
    desc = json.loads(str(ds.attrs[_PREFIX + "task"]))
    return Task(desc["function"], plain(desc["kwargs"]), desc.get("label", ""))


def _fem_arguments(kwargs: dict) -> dict:
    from ..fem import FemOptions

    return {**kwargs, "options": FemOptions.from_dict(kwargs.get("options") or {}).to_dict()}


#: The arguments of a stored task as the current code writes them, by function: an option
#: added since the entry was written takes its default, one the current code leaves out at
#: its default is left out. That is the task :func:`check_sample` recomputes (the task reads
#: its options the same way), so an accepted entry is seeded under the key of the task the
#: current code makes; without it, a new option in the key (``steady.newton_budget``) made
#: every accepted FEM solve unreachable and ``make validate`` recomputed them all.
CURRENT_ARGUMENTS = {"rubbercontact.hybrid.tasks:fem_task": _fem_arguments}


def _current_task(task: Task) -> Task:
    rewrite = CURRENT_ARGUMENTS.get(task.function)
    return task if rewrite is None else Task(task.function, rewrite(dict(task.kwargs)),
                                             task.label)


def seed(reference: Path, cache: Path, functions: tuple[str, ...]) -> CopyReport:
    """Copy the entries of ``functions`` from ``reference`` that ``cache`` lacks: those of
    the current code as they are, those of an accepted code under the current key (with
    ``code_accepted_from`` in their attributes); entries of other code are left out."""
    src, dest = ResultCache(reference), ResultCache(cache)
    accepted = {(a.function, a.stored, a.current) for a in load_equivalence(reference)}
    current: dict[str, str] = {}
    copied = present = corrupt = 0
    for path, function, stored in entries(src, functions):
        if function not in current:
            current[function] = code_digest(function)
        now = current[function]
        if stored != now and (function, stored, now) not in accepted:
            continue
        entry = src.load(path.stem)
        if entry is None:
            corrupt += 1
            continue
        task = _current_task(_task_of(xr.load_dataset(path)))
        key = task.key(code=now)
        if dest.load(key) is not None:
            present += 1
            continue
        result = entry.result
        if stored != now:
            result.attrs["code_accepted_from"] = stored or "before digests"
        dest.store(key, task, result, entry.wall_time)
        copied += 1
    return CopyReport(copied, present, corrupt)


def _max_rel_diff(old: xr.Dataset, new: xr.Dataset) -> tuple[float, str]:
    worst, name = 0.0, ""
    for var in old.data_vars:
        if var in EFFORT or var not in new or old[var].dtype.kind not in "fiu":
            continue
        a, b = np.asarray(old[var], float), np.asarray(new[var], float)
        if a.shape != b.shape or not np.array_equal(np.isfinite(a), np.isfinite(b)):
            return np.inf, f"{var}: {a.shape} -> {b.shape} or other non-finite entries"
        fin = np.isfinite(a)
        if not fin.any():
            continue
        scale = max(float(np.max(np.abs(a[fin]))), 1e-300)
        diff = float(np.max(np.abs(a[fin] - b[fin]))) / scale
        if diff > worst:
            worst, name = diff, var
    return worst, name


def check_sample(reference: Path, function: str, stored: str, n: int = 3) -> SampleCheck:
    """Recompute the ``n`` cheapest entries of ``function`` computed by code ``stored``
    with the current code and compare every numeric variable (not the wall time)."""
    from .executor import ExecutorConfig, run_sweep

    src = ResultCache(reference)
    rows = []
    for path, fn, code in entries(src, (function,)):
        if fn == function and code == stored:
            entry = src.load(path.stem)
            if entry is not None and entry.status == "ok":
                rows.append((entry.wall_time, path, entry.result))
    if not rows:
        raise InputError(f"no entries of {function} computed by code {stored[:12]!r} "
                         f"in {reference}")
    rows.sort(key=lambda r: r[0])
    tasks = [_task_of(xr.load_dataset(path)) for _, path, _ in rows[:n]]
    fresh = run_sweep(tasks, cache=None, executor=ExecutorConfig(synchronous=True),
                      progress=False)
    worst, where = 0.0, ""
    for (_, path, old), new in zip(rows[:n], fresh.results, strict=True):
        if not isinstance(new, xr.Dataset):
            return SampleCheck(function, stored, len(tasks), np.inf, f"{path.stem}: {new}")
        diff, var = _max_rel_diff(old, new)
        if diff > worst:
            worst, where = diff, f"{var} of {path.stem[:12]}"
    return SampleCheck(function, stored, len(tasks), worst, where or "all equal")


def accept(reference: Path, check: SampleCheck, why: str, rtol: float) -> Accepted:
    """Record that ``check.function``'s entries of code ``check.stored`` answer as the
    current code's, if the recomputed sample agrees within ``rtol``.

    ``rtol`` is the tolerance the entries are trusted to: for the steady FEM its Newton
    tolerance propagated to μ and A (not round-off: an iterative solve started from the
    same state reproduces its answer to its stopping tolerance).

    Raises
    ------
    InputError
        The sample differs by more than ``rtol``.
    """
    if not check.max_rel_diff <= rtol:
        raise InputError(f"not accepted: {check} exceeds rtol {rtol:g}; the reference "
                         f"entries are stale, recompute them")
    row = Accepted(check.function, check.stored, code_digest(check.function), why,
                   f"{check} (rtol {rtol:g}), {time.strftime('%Y-%m-%d', time.gmtime())}")
    rows = [a for a in load_equivalence(reference)
            if (a.function, a.stored, a.current) != (row.function, row.stored, row.current)]
    path = Path(reference) / FILE_NAME
    path.write_text(json.dumps({"accepted": [asdict(a) for a in [*rows, row]]}, indent=1)
                    + "\n")
    return row
