"""Kill-and-resume: a sweep killed (SIGKILL) half-way keeps its finished tasks on disk;
the rerun computes only the rest and ends with the results of an uninterrupted run."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time

import xarray as xr

from rubbercontact.sweep import ExecutorConfig, ResultCache, Task, run_sweep

FN = "rubbercontact.sweep.examples:toy_kernel"
N = 10

SCRIPT = textwrap.dedent("""
    import sys
    from rubbercontact.sweep import ExecutorConfig, ResultCache, Task, run_sweep

    if __name__ == "__main__":  # worker processes are spawned and re-import this module
        cache_dir, log, mode = sys.argv[1:4]
        executor = ExecutorConfig(workers=1) if mode == "sync" else ExecutorConfig(workers=2)
        tasks = [Task("{fn}", {{"velocity": 10.0 * (i + 1), "pressure": 0.2, "sleep": 0.4,
                               "calls_log": log}}, label=f"task {{i}}") for i in range({n})]
        run_sweep(tasks, cache=ResultCache(cache_dir), executor=executor, progress="log")
""").format(fn=FN, n=N)


def _tasks(log, sleep=0.4):
    return [Task(FN, {"velocity": 10.0 * (i + 1), "pressure": 0.2, "sleep": sleep,
                      "calls_log": str(log)}, label=f"task {i}") for i in range(N)]


def _kill_after(tmp_path, mode, min_done):
    script = tmp_path / "sweep_script.py"
    script.write_text(SCRIPT)
    cache_dir, log = tmp_path / "cache", tmp_path / "calls.txt"
    env = {**os.environ, "OMP_NUM_THREADS": "1"}
    env.pop("RUBBERCONTACT_SCHEDULER", None)
    proc = subprocess.Popen([sys.executable, str(script), str(cache_dir), str(log), mode],
                            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            start_new_session=True)  # own process group: kill its workers too
    cache = ResultCache(cache_dir)
    try:
        deadline = time.monotonic() + 60
        while cache.info().n_entries < min_done:
            assert proc.poll() is None, proc.stderr.read().decode()
            assert time.monotonic() < deadline, "sweep subprocess made no progress"
            time.sleep(0.05)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait(timeout=30)
    return cache, log


def _check_resume(tmp_path, cache, log):
    done_before = cache.info().n_entries
    started_before = log.read_text().count("\n")
    assert 0 < done_before < N
    resumed = run_sweep(_tasks(log), cache=cache, executor=ExecutorConfig(synchronous=True),
                        progress=False)
    # Finished tasks are not recomputed: counted by the sweep and by the kernel's call log.
    assert resumed.n_cached == done_before
    assert resumed.n_computed == N - done_before
    assert log.read_text().count("\n") - started_before == N - done_before
    assert resumed.ok
    uninterrupted = run_sweep(_tasks(tmp_path / "other.txt", sleep=0.0), cache=None,
                              executor=ExecutorConfig(synchronous=True), progress=False)
    for a, b in zip(resumed, uninterrupted, strict=True):
        xr.testing.assert_identical(a, b)


def test_kill_and_resume_synchronous(tmp_path):
    cache, log = _kill_after(tmp_path, "sync", min_done=3)
    _check_resume(tmp_path, cache, log)


def test_kill_and_resume_local_cluster(tmp_path):
    # Killed while two worker processes run tasks: those are lost, nothing else.
    cache, log = _kill_after(tmp_path, "cluster", min_done=4)
    _check_resume(tmp_path, cache, log)
