"""Sweeps that scale: Dask execution, a content-addressed result cache, progress.

Generic infrastructure: it runs any pure task function that takes plain keyword
arguments and returns an :class:`xarray.Dataset`::

    from rubbercontact.sweep import ExecutorConfig, ResultCache, Task, run_sweep

    tasks = [Task("rubbercontact.sweep.examples:toy_kernel",
                  {"velocity": v, "pressure": p}, label=f"p={p},v={v}")
             for p in (0.1, 0.2) for v in (10.0, 50.0)]
    res = run_sweep(tasks, cache=ResultCache("~/.cache/rc-demo"),
                    executor=ExecutorConfig(workers=2), progress="auto")
    res.results      # per task a Dataset or a TaskFailure
    res.summary()    # counts computed / from cache / failed, wall time, failures

Modules: :mod:`.tasks` (Task, keys), :mod:`.codehash` (the code part of a key), :mod:`.cache`
(ResultCache), :mod:`.executor` (ExecutorConfig, run_sweep), :mod:`.progress`,
:mod:`.results` (SweepResult, TaskFailure), :mod:`.examples` (toy_kernel).
See ``docs/scaling.md`` for clusters and the scaling model.
"""

from .cache import ResultCache, default_cache_dir
from .codehash import code_digest
from .executor import ExecutorConfig, run_sweep
from .results import SweepResult, TaskFailure
from .tasks import Task, task_key

__all__ = ["ExecutorConfig", "ResultCache", "SweepResult", "Task",
           "TaskFailure", "code_digest", "default_cache_dir", "run_sweep", "task_key"]
