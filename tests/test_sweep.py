"""run_sweep in the synchronous executor: caching, failures, duplicates, progress, input errors."""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from rubbercontact.errors import InputError
from rubbercontact.sweep import ExecutorConfig, ResultCache, Task, TaskFailure, run_sweep
from rubbercontact.sweep.examples import toy_kernel
from rubbercontact.sweep.progress import make_reporter

FN = "rubbercontact.sweep.examples:toy_kernel"
SYNC = ExecutorConfig(workers=1, synchronous=True)  # even if RUBBERCONTACT_SCHEDULER is set


def _grid(velocities, pressures, log=None, fail_at=None):
    tasks = []
    for v in velocities:
        for p in pressures:
            kw = {"velocity": v, "pressure": p}
            if log is not None:
                kw["calls_log"] = str(log)
            if fail_at == (v, p):
                kw["fail"] = True
            tasks.append(Task(FN, kw, label=f"v={v},p={p}"))
    return tasks


def _calls(log):
    return log.read_text().count("\n") if log.exists() else 0


def complex_kernel(x: float) -> xr.Dataset:
    """A kernel whose result NetCDF cannot store (complex values)."""
    return xr.Dataset({"z": ((), complex(x, 1.0))})


def test_results_equal_direct_calls_in_task_order():
    tasks = _grid([10.0, 50.0], [0.1, 0.2, 0.4])
    res = run_sweep(tasks, executor=SYNC, progress=False)
    assert len(res) == 6 and res.ok and res.n_computed == 6 and res.n_cached == 0
    for task, ds in zip(tasks, res, strict=True):
        xr.testing.assert_identical(ds, toy_kernel(**task.kwargs))


def test_rerun_recomputes_nothing_and_one_new_velocity_only_its_column(tmp_path):
    log = tmp_path / "calls.txt"
    cache = ResultCache(tmp_path / "cache")
    first = run_sweep(_grid([10.0, 50.0], [0.1, 0.2, 0.4], log), cache=cache, executor=SYNC,
                      progress=False)
    assert (first.n_computed, first.n_cached, _calls(log)) == (6, 0, 6)
    again = run_sweep(_grid([10.0, 50.0], [0.1, 0.2, 0.4], log), cache=cache, executor=SYNC,
                      progress=False)
    assert (again.n_computed, again.n_cached, _calls(log)) == (0, 6, 6)
    for a, b in zip(first, again, strict=True):
        xr.testing.assert_identical(a, b)
    changed = run_sweep(_grid([10.0, 20.0], [0.1, 0.2, 0.4], log), cache=cache, executor=SYNC,
                        progress=False)
    assert (changed.n_computed, changed.n_cached, _calls(log)) == (3, 3, 9)
    assert changed.sources == ["cache"] * 3 + ["computed"] * 3


def test_failed_task_is_recorded_others_complete_and_summary_lists_it(tmp_path):
    log = tmp_path / "calls.txt"
    cache = ResultCache(tmp_path / "cache")
    tasks = _grid([10.0, 50.0], [0.1, 0.2], log, fail_at=(50.0, 0.1))
    res = run_sweep(tasks, cache=cache, executor=SYNC, progress=False)
    assert not res.ok and res.n_failed == 1 and res.n_computed == 4
    failure = res[2]
    assert isinstance(failure, TaskFailure) and failure.status == "failed"
    assert failure.error_type == "ConvergenceError" and "forced failure" in failure.message
    assert failure.diagnostics["iterations"] == 50
    assert failure.diagnostics["residual"] == [1.0, 0.1, 0.03]
    assert "ConvergenceError" in failure.traceback
    assert res.datasets[2] is None and all(isinstance(res.datasets[i], xr.Dataset)
                                           for i in (0, 1, 3))
    assert [t.label for t, _ in res.failures] == ["v=50.0,p=0.1"]
    summary = res.summary()
    assert "1 failed" in summary and "FAILED v=50.0,p=0.1" in summary
    assert "forced failure" in summary

    # The failure is cached with its diagnostics: a rerun does not recompute it ...
    again = run_sweep(tasks, cache=cache, executor=SYNC, progress=False)
    assert (again.n_computed, again.n_cached, again.n_failed, _calls(log)) == (0, 4, 1, 4)
    assert again[2].diagnostics == failure.diagnostics and again[2].cached
    # ... unless asked to retry failures.
    retry = run_sweep(tasks, cache=cache, executor=SYNC, progress=False, retry_failed=True)
    assert (retry.n_computed, retry.n_cached, _calls(log)) == (1, 3, 5)


def test_kernel_input_error_is_a_recorded_failure_replaced_by_a_later_success(tmp_path):
    cache = ResultCache(tmp_path)
    task = Task(FN, {"velocity": 1.0, "pressure": -1.0})  # kernel raises InputError
    res = run_sweep([task], cache=cache, executor=SYNC, progress=False)
    assert res[0].error_type == "InputError" and "pressure" in res[0].message
    assert cache.info().n_failed == 1
    # e.g. a fixed kernel with the same key: the success replaces the recorded failure
    cache.store(task.key(), task, toy_kernel(1.0, 1.0), 0.1)
    assert (cache.info().n_entries, cache.info().n_failed) == (1, 0)
    assert isinstance(cache.load(task.key()).result, xr.Dataset)


def test_duplicates_run_once(tmp_path):
    log = tmp_path / "calls.txt"
    tasks = _grid([10.0], [0.1], log) * 3
    res = run_sweep(tasks, executor=SYNC, progress=False)
    assert _calls(log) == 1 and res.sources == ["computed", "duplicate", "duplicate"]
    xr.testing.assert_identical(res[0], res[2])


def test_wrong_return_type_and_unstorable_result_are_failures(tmp_path):
    cache = ResultCache(tmp_path)
    res = run_sweep([Task("builtins:dict", {"a": 1}),
                     Task("test_sweep:complex_kernel", {"x": 2.0}),
                     Task(FN, {"velocity": 1.0, "pressure": 1.0})],
                    cache=cache, executor=SYNC, progress=False)
    assert res.n_failed == 2 and isinstance(res[2], xr.Dataset)
    assert res[0].error_type == "TypeError" and "expected xarray.Dataset" in res[0].message
    assert res[1].error_type == "CacheWriteError" and "NetCDF" in res[1].message
    # Neither is an answer about the task's inputs worth keeping, except the TypeError.
    assert cache.info().n_entries == 2 and cache.info().n_failed == 1


def test_progress_log_lines_and_quiet(capsys):
    tasks = _grid([10.0], [0.1, 0.2], fail_at=(10.0, 0.2))
    run_sweep(tasks, executor=SYNC, progress="log", description="law")
    err = capsys.readouterr().err
    assert "[law] 0/2 done" in err and "[law] 2/2 done (0 from cache, 1 failed)" in err
    assert "FAILED v=10.0,p=0.2" in err
    run_sweep(tasks, executor=SYNC, progress=False)
    assert capsys.readouterr().err == ""
    run_sweep(tasks, executor=SYNC, progress="auto")  # not a TTY under pytest: log lines
    assert "[sweep] 2/2 done" in capsys.readouterr().err


def test_progress_bar_renders(tmp_path):
    import io

    stream = io.StringIO()
    rep = make_reporter("bar", "bar-test", stream=stream)
    rep.start(3, cached=1)
    rep.advance()
    rep.advance(failed=True, label="t3", message="boom")
    rep.close()
    text = stream.getvalue()
    assert "bar-test" in text and "3/3" in text and "1 failed" in text and "boom" in text


@pytest.mark.parametrize("kwargs, field", [
    ({"workers": 0}, "workers"),
    ({"workers": 1.5}, "workers"),
    ({"threads_per_worker": 0}, "threads_per_worker"),
    ({"scheduler": "localhost:8786"}, "scheduler"),
])
def test_bad_executor_config(kwargs, field):
    with pytest.raises(InputError, match=field):
        ExecutorConfig(**kwargs)


def test_bad_scheduler_environment_variable(monkeypatch):
    monkeypatch.setenv("RUBBERCONTACT_SCHEDULER", "not-an-address")
    with pytest.raises(InputError, match="RUBBERCONTACT_SCHEDULER"):
        ExecutorConfig(workers=2).resolved()
    monkeypatch.setenv("RUBBERCONTACT_SCHEDULER", "tcp://10.0.0.1:8786")
    assert ExecutorConfig().resolved()[:2] == ("remote", "tcp://10.0.0.1:8786")
    assert ExecutorConfig(synchronous=True).resolved()[0] == "sync"


def test_executor_modes(monkeypatch):
    monkeypatch.delenv("RUBBERCONTACT_SCHEDULER", raising=False)
    assert ExecutorConfig(workers=1).resolved()[0] == "sync"
    assert ExecutorConfig(workers=1, synchronous=False).resolved()[0] == "local"
    assert ExecutorConfig(workers=3).resolved() == ("local", None, 3)


def test_bad_arguments_to_run_sweep(tmp_path):
    with pytest.raises(InputError, match=r"tasks\[0\]"):
        run_sweep([{"function": FN}], executor=SYNC)
    with pytest.raises(InputError, match="cache"):
        run_sweep([], cache=str(tmp_path), executor=SYNC)
    with pytest.raises(InputError, match="progress"):
        run_sweep(_grid([1.0], [1.0]), executor=SYNC, progress="fancy")
    with pytest.raises(InputError, match="no function"):
        run_sweep([Task("rubbercontact.sweep.examples:missing", {})], executor=SYNC)


def test_empty_sweep():
    res = run_sweep([], executor=SYNC, progress=False)
    assert len(res) == 0 and res.ok and res.summary().startswith("0 tasks")


def test_numpy_arguments_reach_the_kernel():
    task = Task(FN, {"velocity": np.float64(10.0), "pressure": 0.1,
                     "wavelengths": np.array([0.5, 1.0]), "amplitudes": (0.01, 0.02)})
    res = run_sweep([task], executor=SYNC, progress=False)
    np.testing.assert_array_equal(res[0]["wavelength"].values, [0.5, 1.0])
