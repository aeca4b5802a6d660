"""BLAS/OpenMP threads of the tasks: one per task, in worker processes and in this one."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
import xarray as xr

from rubbercontact.sweep import ExecutorConfig, Task, executor, run_sweep

SYNC = ExecutorConfig(workers=1, synchronous=True)


def blas_threads() -> xr.Dataset:
    """The largest thread count of the thread pools loaded in this process, as a task."""
    from threadpoolctl import threadpool_info

    return xr.Dataset({"threads": ((), max(p["num_threads"] for p in threadpool_info()))})


def _threads() -> list[int]:
    from threadpoolctl import threadpool_info

    return [p["num_threads"] for p in threadpool_info()]


def test_a_synchronous_sweep_runs_its_tasks_on_one_thread_and_restores_the_process():
    pytest.importorskip("threadpoolctl")
    import numpy  # noqa: F401 - its BLAS pool

    before = _threads()
    res = run_sweep([Task("test_sweep_threads:blas_threads", {})], executor=SYNC,
                    progress=False)
    assert int(res[0]["threads"]) == 1
    assert _threads() == before                # the limit ends with the sweep


def test_a_worker_process_limits_the_pools_it_has_loaded_once_for_good():
    pytest.importorskip("threadpoolctl")
    if (os.cpu_count() or 1) < 2:
        pytest.skip("one core: BLAS pools have one thread anyway")
    env = {k: v for k, v in os.environ.items() if k not in executor.THREAD_ENV}
    code = ("import numpy\n"
            "from threadpoolctl import threadpool_info\n"
            "from rubbercontact.sweep.executor import _limit_worker_threads\n"
            "n = lambda: max(p['num_threads'] for p in threadpool_info())\n"
            "a = n(); _limit_worker_threads('f'); b = n(); _limit_worker_threads('f')\n"
            "print(a, b, n())\n")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                         text=True, check=True).stdout.split()
    assert int(out[0]) > 1                     # a fresh process without the variables
    assert out[1:] == ["1", "1"]


def test_without_threadpoolctl_the_environment_only(monkeypatch):
    monkeypatch.setitem(sys.modules, "threadpoolctl", None)     # import fails
    monkeypatch.setattr(os, "environ", {})
    monkeypatch.setattr(executor, "_LIMITED_FOR", set())
    executor._limit_worker_threads("f")
    assert os.environ == executor.THREAD_ENV
    with executor._limit_threads():            # a context that does nothing
        pass
    res = run_sweep([Task("rubbercontact.sweep.examples:toy_kernel",
                          {"velocity": 10.0, "pressure": 0.1})], executor=SYNC,
                    progress=False)
    assert res.ok
