"""Result cache: atomic writes, corruption detection, info/clear and the CLI group."""

from __future__ import annotations

import os

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from rubbercontact.io.atomic import write_netcdf_atomic
from rubbercontact.sweep import ExecutorConfig, ResultCache, Task, TaskFailure, run_sweep
from rubbercontact.sweep.examples import toy_kernel

FN = "rubbercontact.sweep.examples:toy_kernel"
SYNC = ExecutorConfig(workers=1, synchronous=True)  # even if RUBBERCONTACT_SCHEDULER is set


def _task(v=10.0, p=0.2, **extra):
    return Task(FN, {"velocity": v, "pressure": p, **extra}, label=f"v={v},p={p}")


# -- atomic writes --------------------------------------------------------------------------
def _ds():
    return xr.Dataset({"a": ("x", np.arange(4.0))}, coords={"x": [1, 2, 3, 4]})


def test_atomic_write_refuses_to_overwrite_unless_asked(tmp_path):
    path = tmp_path / "out.nc"
    write_netcdf_atomic(_ds(), path)
    with pytest.raises(FileExistsError, match="already exists.*overwrite=True"):
        write_netcdf_atomic(_ds() * 2, path)
    xr.testing.assert_identical(xr.load_dataset(path), _ds())  # untouched
    write_netcdf_atomic(_ds() * 2, path, overwrite=True)
    xr.testing.assert_identical(xr.load_dataset(path), _ds() * 2)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.nc"]  # no temp files left


def test_atomic_write_failure_leaves_nothing(tmp_path):
    bad = xr.Dataset({"z": ("x", np.array([1j, 2j]))})  # complex: not storable in NetCDF-4
    with pytest.raises(Exception):  # noqa: B017 - whatever the netCDF backend raises
        write_netcdf_atomic(bad, tmp_path / "bad.nc")
    assert list(tmp_path.iterdir()) == []


def test_atomic_write_needs_existing_directory(tmp_path):
    with pytest.raises(FileNotFoundError, match="does not exist"):
        write_netcdf_atomic(_ds(), tmp_path / "missing" / "out.nc")


# -- corruption ---------------------------------------------------------------------------
def _entry_path(cache, task):
    return cache.path_for(task.key())


def _fresh(task):
    return toy_kernel(**task.kwargs)


def test_entry_round_trip_is_identical(tmp_path):
    cache = ResultCache(tmp_path)
    task = _task()
    run_sweep([task], cache=cache, executor=SYNC, progress=False)
    entry = cache.load(task.key())
    assert entry is not None and entry.status == "ok" and entry.wall_time >= 0
    xr.testing.assert_identical(entry.result, _fresh(task))


def _corrupt_truncate(path):
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])


def _corrupt_garbage(path):
    path.write_bytes(b"\x89HDF\r\n\x1a\n" + os.urandom(500))


def _corrupt_flip_value(path):
    # Silent bit rot inside the data: flip one byte of the stored friction array.
    friction = xr.load_dataset(path)["friction"].values.astype("<f8").tobytes()
    data = bytearray(path.read_bytes())
    at = bytes(data).find(friction)
    assert at >= 0, "friction array not found verbatim in the file"
    data[at + 3] ^= 0xFF
    path.write_bytes(bytes(data))


def _corrupt_rewrite_value(path):
    # A valid NetCDF file whose values no longer match the stored checksum.
    ds = xr.load_dataset(path)
    ds["friction"] = ds["friction"] * 1.001
    ds.to_netcdf(path)


def _corrupt_wrong_key(path):
    # A valid entry of another task copied under this task's name.
    other = ResultCache(path.parents[2])
    other_task = _task(v=99.0)
    run_sweep([other_task], cache=other, executor=SYNC, progress=False)
    path.write_bytes(other.path_for(other_task.key()).read_bytes())


@pytest.mark.parametrize("corrupt", [_corrupt_truncate, _corrupt_garbage, _corrupt_flip_value,
                                     _corrupt_rewrite_value, _corrupt_wrong_key])
def test_corrupted_entry_is_detected_and_recomputed(tmp_path, corrupt):
    cache = ResultCache(tmp_path)
    task = _task(calls_log=str(tmp_path / "calls.txt"))
    run_sweep([task], cache=cache, executor=SYNC, progress=False)
    path = _entry_path(cache, task)
    corrupt(path)
    assert cache.load(task.key()) is None  # never read as a result
    assert not path.exists() and cache.n_corrupt == 1
    res = run_sweep([task], cache=cache, executor=SYNC, progress=False)
    assert (res.n_computed, res.n_cached) == (1, 0)
    assert (tmp_path / "calls.txt").read_text().count("\n") == 2  # ran again
    xr.testing.assert_identical(res[0], _fresh(task))
    assert cache.load(task.key()) is not None  # healthy again


def test_interrupted_write_leftovers_are_ignored_and_cleared(tmp_path):
    cache = ResultCache(tmp_path)
    task = _task()
    run_sweep([task], cache=cache, executor=SYNC, progress=False)
    path = _entry_path(cache, task)
    stray = path.parent / f".{path.name}.abc123.tmp"
    stray.write_bytes(path.read_bytes()[:100])
    info = cache.info()
    assert (info.n_entries, info.n_temporary) == (1, 1)
    res = run_sweep([task], cache=cache, executor=SYNC, progress=False)
    assert res.n_cached == 1
    cache.clear()
    assert not stray.exists() and cache.info().n_entries == 0


# -- info / clear / CLI -------------------------------------------------------------------
def _populate(directory):
    cache = ResultCache(directory)
    tasks = [_task(p=0.1), _task(p=0.2), _task(p=0.3, fail=True)]
    res = run_sweep(tasks, cache=cache, executor=SYNC, progress=False)
    assert res.n_failed == 1
    return cache, tasks


def test_info_and_clear_failed_only(tmp_path):
    cache, tasks = _populate(tmp_path)
    info = cache.info()
    assert (info.n_entries, info.n_failed) == (3, 1) and info.size_bytes > 0
    assert isinstance(cache.load(tasks[2].key()).result, TaskFailure)
    assert cache.clear(failed_only=True) == 1
    assert (cache.info().n_entries, cache.info().n_failed) == (2, 0)
    assert cache.clear() == 2 and cache.info().n_entries == 0


def test_default_directory_from_environment(tmp_path, monkeypatch):
    monkeypatch.setenv("RUBBERCONTACT_CACHE", str(tmp_path / "envcache"))
    assert ResultCache().directory == tmp_path / "envcache"
    assert ResultCache.default().directory == tmp_path / "envcache"
    monkeypatch.delenv("RUBBERCONTACT_CACHE")
    assert "rubbercontact" in str(ResultCache().directory)


def test_cli_cache_info_and_clear(tmp_path):
    from rubbercontact.cli import app

    _populate(tmp_path)
    runner = CliRunner()
    out = runner.invoke(app, ["cache", "info", "--cache", str(tmp_path)])
    assert out.exit_code == 0, out.output
    assert str(tmp_path) in out.output and "3 (2 ok, 1 failed)" in out.output
    out = runner.invoke(app, ["cache", "clear", "--cache", str(tmp_path)], input="n\n")
    assert out.exit_code == 1 and ResultCache(tmp_path).info().n_entries == 3
    out = runner.invoke(app, ["cache", "clear", "--failed-only", "--yes", "--cache",
                              str(tmp_path)])
    assert out.exit_code == 0 and "deleted 1 failed entries" in out.output
    assert ResultCache(tmp_path).info().n_entries == 2
    out = runner.invoke(app, ["cache", "clear", "--cache", str(tmp_path)], input="y\n")
    assert out.exit_code == 0 and ResultCache(tmp_path).info().n_entries == 0


def test_cli_cache_uses_environment_default(tmp_path, monkeypatch):
    from rubbercontact.cli import main

    monkeypatch.setenv("RUBBERCONTACT_CACHE", str(tmp_path))
    _populate(tmp_path)
    assert main(["cache", "clear", "--yes"]) == 0
    assert ResultCache(tmp_path).info().n_entries == 0


def test_various_dtypes_round_trip_without_false_corruption(tmp_path):
    # A checksum that changed on a NetCDF round trip would recompute forever.
    ds = xr.Dataset(
        {"f64": ("x", np.array([1.0, np.nan, -0.0])),
         "f32": ("x", np.array([1.5, 2.5, np.inf], dtype=np.float32)),
         "i64": ("x", np.array([1, -2, 3], dtype=np.int64)),
         "i8": ("x", np.array([1, 0, 1], dtype=np.int8)),
         "flag": ("x", np.array([True, False, True])),
         "status": ("x", np.array(["ok", "failed: no convergence", "ok"], dtype=object)),
         "ustr": ("x", np.array(["a", "bb", "ccc"])),
         "when": ((), np.datetime64("2024-01-02T03:04:05", "ns")),
         "scalar": ((), 3.25)},
        coords={"x": ("x", np.array([0.1, 0.2, 0.3])), "name": ("x", ["u", "v", "w"])},
        attrs={"units_note": "mm, MPa", "n": 3, "values": [1.0, 2.0]})
    cache = ResultCache(tmp_path)
    task = _task()
    cache.store(task.key(), task, ds, 0.5)
    entry = cache.load(task.key())
    assert entry is not None and cache.n_corrupt == 0
    assert entry.wall_time == 0.5
    xr.testing.assert_equal(entry.result, ds)
    assert entry.result.attrs["units_note"] == "mm, MPa"


def test_atomic_write_gives_normal_permissions(tmp_path):
    umask = os.umask(0)
    os.umask(umask)
    path = write_netcdf_atomic(_ds(), tmp_path / "perm.nc")
    assert path.stat().st_mode & 0o777 == 0o666 & ~umask


# -- copying between caches -----------------------------------------------------------------
def test_copy_to_seeds_an_empty_cache_with_checked_entries(tmp_path):
    src, tasks = _populate(tmp_path / "src")
    dest = ResultCache(tmp_path / "dest")
    report = src.copy_to(dest)
    assert (report.copied, report.present, report.corrupt) == (2, 0, 0)  # failure not copied
    for t in tasks[:2]:
        xr.testing.assert_identical(dest.load(t.key()).result, src.load(t.key()).result)
    assert dest.load(tasks[2].key()) is None and dest.info().n_temporary == 0
    # A rerun copies nothing and a sweep on the seeded cache computes nothing.
    assert src.copy_to(dest).present == 2
    res = run_sweep(tasks[:2], cache=dest, executor=SYNC, progress=False)
    assert res.n_cached == 2 and res.n_computed == 0


def test_copy_to_never_copies_or_deletes_a_corrupt_source_entry(tmp_path):
    src, tasks = _populate(tmp_path / "src")
    bad = src.path_for(tasks[0].key())
    with xr.open_dataset(bad) as ds:
        tampered = ds.load()
    tampered["friction"] = tampered["friction"] + 1.0   # checksum no longer matches
    write_netcdf_atomic(tampered, bad, overwrite=True)
    dest = ResultCache(tmp_path / "dest")
    report = src.copy_to(dest, include_failed=True)
    assert (report.copied, report.corrupt) == (2, 1)
    assert dest.load(tasks[0].key()) is None and bad.exists()   # source left as it was
    assert isinstance(dest.load(tasks[2].key()).result, TaskFailure)


def test_copy_to_selects_by_function_and_key(tmp_path):
    src, tasks = _populate(tmp_path / "src")
    assert src.copy_to(ResultCache(tmp_path / "a"), functions=("fem_task",)).copied == 0
    # Entries outside the selection are neither copied nor counted as present.
    src.copy_to(ResultCache(tmp_path / "a2"))
    assert src.copy_to(ResultCache(tmp_path / "a2"), functions=("fem_task",)).present == 0
    assert src.copy_to(ResultCache(tmp_path / "b"), functions=("toy_kernel",)).copied == 2
    only = ResultCache(tmp_path / "c")
    assert src.copy_to(only, keys={tasks[1].key()}).copied == 1
    assert only.load(tasks[1].key()) is not None and only.load(tasks[0].key()) is None


def test_cli_cache_copy(tmp_path, capsys):
    from rubbercontact.cli import app, main

    _populate(tmp_path / "src")
    runner = CliRunner()
    out = runner.invoke(app, ["cache", "copy", str(tmp_path / "src"), str(tmp_path / "dst"),
                              "--function", "toy_kernel"])
    assert out.exit_code == 0, out.output
    assert "2 copied, 0 already present, 0 corrupt" in out.output
    assert main(["cache", "copy", str(tmp_path / "nowhere"), str(tmp_path / "d")]) == 2
    assert "not a directory" in capsys.readouterr().err


def test_copy_to_replaces_a_recorded_failure_with_a_result_never_the_reverse(tmp_path):
    src, tasks = _populate(tmp_path / "src")
    dest = ResultCache(tmp_path / "dest")
    failure = TaskFailure(message="worker lost", error_type="KilledWorker")
    dest.store(tasks[0].key(), tasks[0], failure, 1.0)       # failed here, ok in src
    dest.store(tasks[2].key(), tasks[2], _fresh(tasks[0]), 1.0)  # ok here, failed in src
    report = src.copy_to(dest, include_failed=True)
    assert (report.copied, report.present) == (2, 1)
    assert dest.load(tasks[0].key()).status == "ok"
    assert not dest.path_for(tasks[0].key(), failed=True).exists()
    assert dest.load(tasks[2].key()).status == "ok"
