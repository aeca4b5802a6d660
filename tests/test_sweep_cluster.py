"""The same sweep on the synchronous executor, the managed local cluster and an external
``distributed.LocalCluster`` reached over TCP gives identical results."""

from __future__ import annotations

import warnings

import pytest
import xarray as xr

from rubbercontact.sweep import ExecutorConfig, ResultCache, Task, TaskFailure, run_sweep

FN = "rubbercontact.sweep.examples:toy_kernel"


def _tasks():
    # Some real FFT work per task so both workers get tasks; one forced failure.
    return [Task(FN, {"velocity": v, "pressure": p, "work": 30, "fail": (v, p) == (50.0, 0.4)},
                 label=f"v={v},p={p}")
            for v in (10.0, 50.0) for p in (0.1, 0.2, 0.4)]


def _assert_same(a, b):
    assert len(a) == len(b)
    for x, y in zip(a, b, strict=True):
        if isinstance(x, TaskFailure):
            assert isinstance(y, TaskFailure)
            assert (x.error_type, x.message, x.diagnostics) == (y.error_type, y.message,
                                                                 y.diagnostics)
        else:
            xr.testing.assert_identical(x, y)


@pytest.fixture(scope="module")
def tcp_cluster():
    from distributed import LocalCluster

    with warnings.catch_warnings():
        # its HTTP (metrics) server takes a free port when another cluster holds 8787, as
        # the library's own cluster does (sweep/executor.py)
        warnings.filterwarnings("ignore", message="Port .* is already in use")
        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                               host="127.0.0.1", dashboard_address=None, silence_logs=40)
    try:
        yield cluster
    finally:
        cluster.close()


def test_sync_managed_and_external_cluster_agree(tcp_cluster, tmp_path, monkeypatch):
    monkeypatch.delenv("RUBBERCONTACT_SCHEDULER", raising=False)
    reference = run_sweep(_tasks(), executor=ExecutorConfig(synchronous=True), progress=False)
    assert reference.n_failed == 1

    address = tcp_cluster.scheduler_address
    assert address.startswith("tcp://127.0.0.1:")
    remote = run_sweep(_tasks(), executor=ExecutorConfig(scheduler=address), progress=False)
    _assert_same(reference, remote)
    assert remote.n_computed == 6 and remote.n_failed == 1

    # The worker processes really ran tasks (not the client), with BLAS pinned to 1 thread
    # by the environment that the nanny sets before the worker imports numpy.
    from distributed import Client

    with Client(address) as client:
        envs = client.run(lambda: __import__("os").environ.get("OMP_NUM_THREADS"))
    assert len(envs) == 2 and set(envs.values()) == {"1"}

    # The environment variable selects the same cluster; results go through the cache.
    monkeypatch.setenv("RUBBERCONTACT_SCHEDULER", address)
    cache = ResultCache(tmp_path)
    via_env = run_sweep(_tasks(), cache=cache, executor=ExecutorConfig(), progress=False)
    _assert_same(reference, via_env)
    again = run_sweep(_tasks(), cache=cache, executor=ExecutorConfig(), progress=False)
    assert (again.n_computed, again.n_cached) == (0, 6)
    _assert_same(reference, again)


def test_managed_local_cluster_agrees_with_sync(monkeypatch):
    monkeypatch.delenv("RUBBERCONTACT_SCHEDULER", raising=False)
    reference = run_sweep(_tasks(), executor=ExecutorConfig(synchronous=True), progress=False)
    local = run_sweep(_tasks(), executor=ExecutorConfig(workers=2), progress=False)
    _assert_same(reference, local)


def test_worker_version_mismatch_is_refused(tcp_cluster, monkeypatch):
    import rubbercontact.sweep.executor as executor_module

    # The client process pretends to run other code; the workers report the real digest.
    monkeypatch.setattr(executor_module, "package_digest", lambda: "999-other")
    from rubbercontact.errors import InputError

    with pytest.raises(InputError, match="code"):
        run_sweep(_tasks()[:1], executor=ExecutorConfig(scheduler=tcp_cluster.scheduler_address),
                  progress=False)


def test_workers_write_a_shared_cache(tcp_cluster, tmp_path, monkeypatch):
    cache = ResultCache(tmp_path, shared=True)

    def client_store(*args, **kwargs):
        raise AssertionError("the client wrote an entry")

    # Only the client process is patched: any write from it turns into a CacheWriteError.
    monkeypatch.setattr(ResultCache, "store", client_store)
    res = run_sweep(_tasks(), cache=cache,
                    executor=ExecutorConfig(scheduler=tcp_cluster.scheduler_address),
                    progress=False)
    monkeypatch.undo()
    assert res.n_computed == 6 and res.n_failed == 1
    assert res.failures[0][1].error_type == "ConvergenceError"
    assert (cache.info().n_entries, cache.info().n_failed) == (6, 1)
    again = run_sweep(_tasks(), cache=cache, executor=ExecutorConfig(synchronous=True),
                      progress=False)
    assert again.n_cached == 6
    _assert_same(res, again)


def test_shared_cache_that_is_not_shared_falls_back_to_client_writes(tcp_cluster, tmp_path,
                                                                     monkeypatch, caplog):
    worker_dir, client_dir = tmp_path / "worker-view", tmp_path / "client-view"
    cache = ResultCache(worker_dir, shared=True)
    # The client sees the cache under another path than the workers (not really shared).
    monkeypatch.setattr(cache, "directory", client_dir)
    import rubbercontact.sweep.executor as ex

    real = ex._execute

    def execute_in_worker_view(function, kwargs, limit_threads=False, store_in=None):
        if store_in is not None:
            store_in = (str(worker_dir), *store_in[1:])
        return real(function, kwargs, limit_threads, store_in)

    monkeypatch.setattr(ex, "_execute", execute_in_worker_view)
    with caplog.at_level("WARNING", logger="rubbercontact.sweep.executor"):
        res = run_sweep(_tasks(), cache=cache,
                        executor=ExecutorConfig(scheduler=tcp_cluster.scheduler_address),
                        progress=False)
    assert res.n_failed == 1 and "not visible to the client" in caplog.text
    assert ResultCache(client_dir).info().n_entries == 6  # written by the client
    assert ResultCache(worker_dir).info().n_entries == 6  # and by the workers


def crash_kernel(x: float):
    """Kills its worker process, like an out-of-memory kill would."""
    import os

    os._exit(1)


def test_worker_crash_is_reported_not_cached(tmp_path, monkeypatch):
    import dask

    monkeypatch.delenv("RUBBERCONTACT_SCHEDULER", raising=False)
    cache = ResultCache(tmp_path)
    tasks = [*_tasks()[:2], Task("test_sweep_cluster:crash_kernel", {"x": 1.0}, label="crash")]
    # Give up on the first worker death instead of retrying the task on other workers, and
    # send a worker only the task it runs (no queued task dies with it).
    with dask.config.set({"distributed.scheduler.allowed-failures": 0,
                          "distributed.scheduler.worker-saturation": 1.0}):
        res = run_sweep(tasks, cache=cache, executor=ExecutorConfig(workers=2), progress=False)
    assert isinstance(res[0], xr.Dataset) and isinstance(res[1], xr.Dataset)
    failure = res[2]
    assert isinstance(failure, TaskFailure) and not failure.cached
    assert "did not complete on the cluster" in failure.message
    assert cache.info().n_entries == 2  # the crash says nothing about the inputs


def test_only_the_heartbeat_after_close_record_is_dropped():
    # The local cluster's workers drop the harmless heartbeat error of a closing cluster
    # (dask/distributed#7192) and nothing else: other errors still reach the log.
    import logging

    from rubbercontact.sweep._dask_plugins import HeartbeatAfterCloseFilter

    def record(msg):
        return logging.LogRecord("distributed.worker", logging.ERROR, __file__, 1, msg, None,
                                 None)

    f = HeartbeatAfterCloseFilter()
    assert not f.filter(record("Failed to communicate with scheduler during heartbeat."))
    assert f.filter(record("Compute Failed"))
    assert f.filter(record("Worker stream died during communication"))
