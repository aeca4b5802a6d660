"""Run a list of tasks on Dask, with the result cache and progress reporting.

Execution modes (:class:`ExecutorConfig`):

* **synchronous** -- tasks run one after the other in the calling process, no
  Dask at all. Chosen automatically when ``workers == 1`` and no scheduler is
  given; useful for tests and debugging (breakpoints and tracebacks work).
* **local cluster** -- a ``distributed.LocalCluster`` started and shut down by
  :func:`run_sweep`, with ``workers`` worker *processes* (default: the number
  of cores available to this process) of ``threads_per_worker`` threads
  (default 1: the kernels are single-threaded and CPU-bound, so one task per
  core).
* **existing cluster** -- ``scheduler="tcp://HOST:PORT"`` (or the environment
  variable ``RUBBERCONTACT_SCHEDULER``) connects a client to a running Dask
  scheduler (``dask scheduler`` / ``dask worker``, dask-jobqueue on
  SLURM/PBS). Its workers must have the same rubbercontact version installed.

BLAS/OpenMP threads are pinned to 1 in worker processes (environment variables
set by the nanny before the worker imports numpy), so two tasks do not fight
over one core; ``threadpoolctl`` (a dependency; without it the variables alone)
also limits the pools already loaded, once per task function in each worker
process, which covers workers started by hand without the variables. Tasks run
in this process (synchronous, or a local cluster of threads) run under one
thread too, for the sweep: a half-space solve's last bits differ with the
thread count, and a run on one worker computes what a run on two would.

Results are written to the cache by the *client* as each future completes
(``as_completed``), so the cache directory only has to be visible to the client
and a kill loses only the tasks running at that moment. The price is that every
result travels to the client and is written there one after the other (≈ 6–20
ms per entry): keep results small (per-task summaries and profiles, not full FEM
fields). With ``ResultCache(dir, shared=True)`` (a directory every worker sees
at the same path) the workers write the entries in parallel instead; the client
checks that each entry is visible and writes it itself (with a warning) if not.
"""

from __future__ import annotations

import contextlib
import logging
import os
import re
import time
import traceback
import warnings
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import xarray as xr

from ..errors import ConvergenceError, InputError
from .cache import ResultCache
from .codehash import code_digest, package_digest
from .progress import Workload, make_reporter
from .results import SweepResult, TaskFailure, jsonable
from .tasks import Task, resolve_function, task_key

__all__ = ["ENV_SCHEDULER", "THREAD_ENV", "ExecutorConfig", "run_sweep"]

ENV_SCHEDULER = "RUBBERCONTACT_SCHEDULER"

#: Environment of worker processes: one BLAS/OpenMP thread per task.
THREAD_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
              "NUMEXPR_NUM_THREADS": "1", "VECLIB_MAXIMUM_THREADS": "1"}

log = logging.getLogger(__name__)

_ADDRESS_RE = re.compile(r"^(tcp|tls|inproc|ucx|ws|wss)://\S+$")


def _available_cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # macOS, Windows
        return os.cpu_count() or 1


@dataclass(frozen=True)
class ExecutorConfig:
    """Where and how the tasks of a sweep run.

    Parameters
    ----------
    workers
        Number of worker processes of the local cluster (``--workers``); default:
        the cores available to this process. Ignored with ``scheduler``.
    threads_per_worker
        Tasks run concurrently per worker process (``--threads-per-worker``).
        Keep 1 for CPU-bound kernels holding the GIL.
    scheduler
        Address ``tcp://HOST:PORT`` of an existing Dask scheduler
        (``--scheduler``); default ``$RUBBERCONTACT_SCHEDULER``, else a local
        cluster.
    processes
        Local cluster with worker processes (True) or threads in this process.
    synchronous
        Run in the calling process without Dask. Default (None): True when
        ``workers == 1`` and no scheduler is configured.
    """

    workers: int | None = None
    threads_per_worker: int = 1
    scheduler: str | None = None
    processes: bool = True
    synchronous: bool | None = None

    def __post_init__(self) -> None:
        if self.workers is not None and (isinstance(self.workers, bool)
                                         or not isinstance(self.workers, int)
                                         or self.workers < 1):
            raise InputError(f"workers: expected an integer >= 1, got {self.workers!r}")
        if isinstance(self.threads_per_worker, bool) or not isinstance(
                self.threads_per_worker, int) or self.threads_per_worker < 1:
            raise InputError(f"threads_per_worker: expected an integer >= 1, "
                             f"got {self.threads_per_worker!r}")
        if self.scheduler is not None and not _ADDRESS_RE.match(str(self.scheduler)):
            raise InputError(f"scheduler: expected an address like 'tcp://HOST:PORT', "
                             f"got {self.scheduler!r}")

    def resolved(self) -> tuple[str, str | None, int]:
        """``(mode, address, workers)`` with mode in {"sync", "local", "remote"}."""
        address = self.scheduler
        if address is None and not self.synchronous:
            env = os.environ.get(ENV_SCHEDULER, "").strip()
            if env:
                if not _ADDRESS_RE.match(env):
                    raise InputError(f"{ENV_SCHEDULER}: expected an address like "
                                     f"'tcp://HOST:PORT', got {env!r}")
                address = env
        workers = self.workers if self.workers is not None else _available_cores()
        if self.synchronous:
            return "sync", None, 1
        if address is not None:
            return "remote", address, workers
        if self.synchronous is None and workers == 1:
            return "sync", None, 1
        return "local", None, workers


# -- worker side ------------------------------------------------------------------------
def _limit_threads() -> contextlib.AbstractContextManager[Any]:
    """One BLAS/OpenMP thread in every thread pool loaded, inside the context
    (``threadpoolctl``; without it, a context that does nothing). Entering costs a scan
    of the process's libraries, several ms: once per sweep, not per task."""
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:
        return contextlib.nullcontext()
    return threadpool_limits(1)


#: The task functions this worker process has limited the threads for (each may load
#: libraries of its own).
_LIMITED_FOR: set[str] = set()


def _limit_worker_threads(function: str) -> None:
    """In a worker process, once per task function: :data:`THREAD_ENV` for libraries
    loaded later and one thread in the pools already loaded, for the process's life (the
    nanny's environment does the same for a local cluster's workers; this covers workers
    started by hand). Without ``threadpoolctl`` the environment only."""
    if function in _LIMITED_FOR:
        return
    for name, value in THREAD_ENV.items():
        os.environ.setdefault(name, value)
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:
        pass
    else:
        threadpool_limits(1)               # kept: not used as a context
    _LIMITED_FOR.add(function)


def _execute(function: str, kwargs: dict[str, Any], limit_threads: bool = False,
             store_in: tuple[str, str, Task] | None = None
             ) -> tuple[str, xr.Dataset | TaskFailure, float, bool]:
    """Run one task; never raises.

    Returns ``(status, dataset or failure, wall time, stored)``; status is "ok",
    "failed" (an exception from the task: cached) or "error" (``MemoryError``: says
    nothing about the task itself, not cached). With ``store_in = (cache directory,
    key, task)`` the entry is written here, on the worker, and ``stored`` tells
    whether that worked.
    """
    status, payload, dt = _run(function, kwargs, limit_threads)
    stored = False
    if store_in is not None and status in ("ok", "failed"):
        directory, key, task = store_in
        try:
            ResultCache(directory).store(key, task, payload, dt)
            stored = True
        except Exception:  # noqa: BLE001 - the client retries and reports
            stored = False
    return status, payload, dt, stored


def _run(function: str, kwargs: dict[str, Any],
         limit_threads: bool) -> tuple[str, xr.Dataset | TaskFailure, float]:
    t0 = time.perf_counter()
    try:
        func = resolve_function(function)         # imports its libraries first
        if limit_threads:
            _limit_worker_threads(function)
        out = func(**kwargs)
        if not isinstance(out, xr.Dataset):
            raise TypeError(f"task function {function} returned {type(out).__name__}, "
                            f"expected xarray.Dataset")
        return "ok", out, time.perf_counter() - t0
    except Exception as exc:  # noqa: BLE001 - a failing task must not stop the sweep
        dt = time.perf_counter() - t0
        diagnostics = jsonable(exc.diagnostics) if isinstance(exc, ConvergenceError) else {}
        failure = TaskFailure(message=str(exc), error_type=type(exc).__name__,
                              diagnostics=diagnostics, traceback=traceback.format_exc(),
                              wall_time=dt, cached=not isinstance(exc, MemoryError))
        return ("failed" if failure.cached else "error"), failure, dt


# -- client side ------------------------------------------------------------------------
def _versions() -> tuple[str, str]:
    """(package version, digest of the package's code) of the calling process."""
    from .. import __version__

    return str(__version__), package_digest()


def _check_worker_versions(client: Any, address: str | None) -> None:
    # Workers of an external cluster must compute what this client would compute: a worker
    # with other numerics would silently fill the cache with answers under the wrong keys.
    try:
        found = client.run(_versions)
    except Exception as exc:  # noqa: BLE001 - e.g. rubbercontact missing on a worker
        raise InputError(f"scheduler: the workers of {address!r} cannot run rubbercontact "
                         f"tasks ({type(exc).__name__}: {exc}); install the same "
                         f"rubbercontact version on every worker") from exc
    mine = _versions()
    bad = {w: v for w, v in found.items() if tuple(v) != mine}
    if bad:
        worker, (version, code) = next(iter(bad.items()))
        raise InputError(f"scheduler: worker {worker} of {address!r} runs rubbercontact "
                         f"{version} (code {code[:12]}), this client {mine[0]} (code "
                         f"{mine[1][:12]}); {len(bad)} worker(s) differ")


@contextlib.contextmanager
def _dask_client(mode: str, address: str | None, workers: int,
                 config: ExecutorConfig) -> Iterator[Any]:
    import dask
    from distributed import Client, LocalCluster

    if mode == "remote":
        try:
            client = Client(address, timeout="30s")
        except OSError as exc:
            raise InputError(f"scheduler: cannot connect to {address!r}: {exc}") from exc
        with client:
            _check_worker_versions(client, address)
            yield client
        return
    # The nanny sets these in each worker process before it imports numpy.
    with dask.config.set({"distributed.nanny.pre-spawn-environ": THREAD_ENV}), \
            warnings.catch_warnings():
        # The scheduler's HTTP (metrics) server falls back to a free port when 8787 is taken.
        warnings.filterwarnings("ignore", message="Port .* is already in use")
        cluster = LocalCluster(n_workers=workers, threads_per_worker=config.threads_per_worker,
                               processes=config.processes, dashboard_address=None,
                               silence_logs=40)  # logging.ERROR: no worker chatter
    with cluster, Client(cluster) as client:
        from ._dask_plugins import QuietShutdown

        client.register_plugin(QuietShutdown(), name="rubbercontact-quiet-shutdown")
        yield client


def _dask_key(task: Task, key: str) -> str:
    name = re.sub(r"[^\w.-]", "_", task.function.split(":")[1])
    return f"rc-{name}-{key}"


def run_sweep(tasks: Sequence[Task], cache: ResultCache | None = None,
              executor: ExecutorConfig | None = None, progress: bool | str = "auto",
              retry_failed: bool = False, description: str = "sweep") -> SweepResult:
    """Run every task (or take it from the cache) and return all results in order.

    Parameters
    ----------
    tasks
        The tasks. Tasks with the same key run once.
    cache
        Where results are looked up first and stored as they complete; None
        disables caching (everything is computed, nothing is written).
    executor
        Where tasks run (see :class:`ExecutorConfig`); default: local cluster
        sized to the machine (synchronous on a single core).
    progress
        ``"auto"``/True, ``"bar"``, ``"log"`` or False (see
        :mod:`rubbercontact.sweep.progress`).
    retry_failed
        Recompute tasks whose cached entry is a recorded failure
        (``--retry-failed``); by default a recorded failure is returned as is.
    description
        Name shown by the progress reporter.

    Returns
    -------
    SweepResult
        Per task a dataset or a :class:`TaskFailure`, with counts and timings.
        Failures do not raise: check ``result.ok`` / ``result.summary()``.

    Raises
    ------
    InputError
        A task that is not a :class:`Task`, an unknown function, a bad executor
        configuration or an unreachable scheduler.
    """
    t_start = time.perf_counter()
    tasks = list(tasks)
    for i, t in enumerate(tasks):
        if not isinstance(t, Task):
            raise InputError(f"tasks[{i}]: expected a rubbercontact.sweep.Task, "
                             f"got {type(t).__name__}")
    if cache is not None and not isinstance(cache, ResultCache):
        raise InputError(f"cache: expected a ResultCache or None, got {type(cache).__name__}")
    config = executor if executor is not None else ExecutorConfig()
    if not isinstance(config, ExecutorConfig):
        raise InputError(f"executor: expected an ExecutorConfig or None, "
                         f"got {type(config).__name__}")

    # Keys: import each function once, on the client, so a wrong path fails before any work;
    # the code part of the key is read from the function's source once per function.
    codes: dict[str, str] = {}
    keys = []
    for t in tasks:
        if t.function not in codes:
            resolve_function(t.function)
            codes[t.function] = code_digest(t.function)
        keys.append(task_key(t.function, t.kwargs, code=codes[t.function]))
    result = SweepResult._empty(tasks, keys)
    first: dict[str, int] = {}  # key -> index of the first task with that key
    for i, k in enumerate(keys):
        first.setdefault(k, i)

    # Cache lookups.
    todo: list[int] = []
    n_cached_failed = 0
    for k, i in first.items():
        entry = cache.load(k) if cache is not None else None
        if entry is not None and not (retry_failed and entry.status == "failed"):
            result.results[i] = entry.result
            result.sources[i] = "cache"
            result.task_times[i] = entry.wall_time
            n_cached_failed += entry.status == "failed"
        else:
            todo.append(i)

    # the ETA weighs the tasks to compute by their cost hints, shared by the tasks that run
    # at once; ``slot`` is each one's index in that list (the order they are sent)
    slot = {i: k for k, i in enumerate(todo)}
    mode, address, workers = config.resolved() if todo else ("sync", None, 1)
    workload = Workload(tuple(tasks[i].cost for i in todo),
                        1 if mode == "sync" else workers * config.threads_per_worker)
    reporter = make_reporter(progress, description)
    reporter.start(len(first), cached=len(first) - len(todo), cached_failed=n_cached_failed,
                   workload=workload)

    warned = []

    def finish(i: int, status: str, payload: xr.Dataset | TaskFailure, dt: float,
               stored: bool = False) -> None:
        if stored and cache.path_for(keys[i], isinstance(payload, TaskFailure)).exists():
            pass  # written by the worker
        elif cache is not None and status in ("ok", "failed"):
            if stored and not warned:
                warned.append(True)
                log.warning("cache %s: entries written by the workers are not visible to "
                            "the client (is the directory really shared?); the client "
                            "writes them", cache.directory)
            try:
                cache.store(keys[i], tasks[i], payload, dt)
            except Exception as exc:  # noqa: BLE001 - report, keep the sweep going
                payload = TaskFailure(
                    message=f"result could not be written to the cache as NetCDF "
                            f"({type(exc).__name__}: {exc}); task functions must return "
                            f"NetCDF-storable datasets (no complex values, no bool/dict attrs)",
                    error_type="CacheWriteError", traceback=traceback.format_exc(),
                    wall_time=dt, cached=False)
        result.results[i] = payload
        result.sources[i] = "computed"
        result.task_times[i] = dt
        failed = isinstance(payload, TaskFailure)
        reporter.advance(failed=failed, label=tasks[i].name,
                         message=str(payload) if failed else "", task=slot[i], seconds=dt)

    try:
        if todo:
            if mode == "sync":
                # in this process on one thread, as on a worker: the same last bits (a
                # half-space solve's differ with the BLAS thread count, and results that
                # reach other tasks' keys would give them other keys)
                with _limit_threads():
                    for i in todo:
                        finish(i, *_execute(tasks[i].function, dict(tasks[i].kwargs)))
            else:
                from distributed import as_completed

                # worker processes limit their own threads; threads of this process (a
                # local cluster without processes) run under this process's limit
                in_here = mode == "local" and not config.processes
                with _limit_threads() if in_here else contextlib.nullcontext(), \
                        _dask_client(mode, address, min(workers, len(todo)), config) as client:
                    # One batched submission: client.submit in a loop costs ~1 ms per task.
                    shared = cache is not None and cache.shared
                    submitted = client.map(_execute, [tasks[i].function for i in todo],
                                           [dict(tasks[i].kwargs) for i in todo],
                                           [not in_here] * len(todo),
                                           [(str(cache.directory), keys[i], tasks[i])
                                            if shared else None for i in todo],
                                           key=[_dask_key(tasks[i], keys[i]) for i in todo],
                                           pure=False)
                    futures = dict(zip(submitted, todo, strict=True))
                    del submitted
                    for fut in as_completed(list(futures)):
                        # Dropping our reference lets the cluster free the result at once.
                        i = futures.pop(fut)
                        try:
                            status, payload, dt, stored = fut.result()
                        except Exception as exc:  # noqa: BLE001 - worker crash, cancellation
                            status, dt, stored = "error", 0.0, False
                            payload = TaskFailure(
                                message=f"task did not complete on the cluster "
                                        f"({type(exc).__name__}: {exc})",
                                error_type=type(exc).__name__, wall_time=0.0, cached=False)
                        del fut
                        finish(i, status, payload, dt, stored)
    finally:
        reporter.close()

    for i, k in enumerate(keys):  # duplicates share the first task's answer
        j = first[k]
        if j != i:
            result.results[i] = result.results[j]
            result.sources[i] = "duplicate"
            result.task_times[i] = result.task_times[j]
    result.wall_time = time.perf_counter() - t_start
    return result

