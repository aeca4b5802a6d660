"""A reference cache of other code is used only under a checked, recorded equivalence."""

from __future__ import annotations

import json

import netCDF4
import numpy as np
import pytest
import xarray as xr

from rubbercontact.errors import InputError
from rubbercontact.sweep import ExecutorConfig, ResultCache, Task, run_sweep
from rubbercontact.sweep import equivalence as eq
from rubbercontact.sweep.cache import dataset_checksum

FN = "rubbercontact.sweep.examples:toy_kernel"
SYNC = ExecutorConfig(synchronous=True)


def _tasks():
    return [Task(FN, {"velocity": v, "pressure": 0.3}) for v in (1.0, 10.0)]


def _reference(tmp_path, tamper: float = 1.0) -> ResultCache:
    """A reference cache whose entries claim to come from other code ("old")."""
    ref = ResultCache(tmp_path / "reference")
    run_sweep(_tasks(), cache=ref, executor=SYNC, progress=False)
    for path in ref.directory.glob("sweep-v1/*/*.nc"):
        with netCDF4.Dataset(path, "a") as nc:
            nc.setncattr("rc_cache_code", "old")
            if tamper != 1.0:  # another answer, as changed numerics would give
                nc["friction"][:] = nc["friction"][:] * tamper
        # the checksum covers the values: a valid entry of other code, not a corrupt one
        with netCDF4.Dataset(path, "a") as nc:
            nc.setncattr("rc_cache_checksum", dataset_checksum(xr.load_dataset(path)))
    return ref


def test_entries_of_other_code_are_not_seeded(tmp_path):
    ref = _reference(tmp_path)
    report = eq.seed(ref.directory, tmp_path / "work", (FN.split(":")[1],))
    assert report.copied == 0
    res = run_sweep(_tasks(), cache=ResultCache(tmp_path / "work"), executor=SYNC,
                    progress=False)
    assert set(res.sources) == {"computed"}


def test_an_accepted_equivalence_seeds_them_under_the_current_key(tmp_path):
    ref = _reference(tmp_path)
    check = eq.check_sample(ref.directory, FN, "old", n=2)
    # the toy kernel is a closed form: the same code gives the same bits
    assert check.n == 2 and check.max_rel_diff == 0.0
    row = eq.accept(ref.directory, check, "test: same code", rtol=1e-12)
    assert json.loads((ref.directory / "equivalence.json").read_text())["accepted"][0][
        "stored"] == "old" and row.why == "test: same code"
    report = eq.seed(ref.directory, tmp_path / "work", ("toy_kernel",))
    assert report.copied == 2
    res = run_sweep(_tasks(), cache=ResultCache(tmp_path / "work"), executor=SYNC,
                    progress=False)
    assert set(res.sources) == {"cache"}
    assert res.results[0].attrs["code_accepted_from"] == "old"


def test_a_sample_that_disagrees_is_refused(tmp_path):
    ref = _reference(tmp_path, tamper=1.01)
    check = eq.check_sample(ref.directory, FN, "old", n=2)
    assert check.max_rel_diff == pytest.approx(0.01 / 1.01, rel=1e-6)
    with pytest.raises(InputError, match="stale"):
        eq.accept(ref.directory, check, "wrong", rtol=1e-6)
    assert not (ref.directory / "equivalence.json").exists()
    assert eq.seed(ref.directory, tmp_path / "work", ("toy_kernel",)).copied == 0


def test_max_rel_diff_ignores_the_wall_time():
    a = xr.Dataset({"mu": ((), 0.5), "wall_time": ((), 1.0)})
    b = xr.Dataset({"mu": ((), 0.5), "wall_time": ((), 9.0)})
    assert eq._max_rel_diff(a, b) == (0.0, "")
    assert eq._max_rel_diff(a, b.assign(mu=0.55))[0] == pytest.approx(0.1)
    assert np.isinf(eq._max_rel_diff(a.assign(mu=("x", [1.0, 2.0])),
                                     b.assign(mu=("x", [1.0])))[0])


def test_fem_options_of_the_penalty_contact_keep_their_arguments():
    # Adding the barrier contact must not change the arguments (so the cache keys) of the
    # penalty's FEM tasks: the reference FEM solves were written before it existed.
    from rubbercontact.fem import FemOptions

    legacy = set(FemOptions().to_dict())
    assert not legacy & {"contact", "barrier_distance", "barrier_stiffness"}
    barrier = FemOptions(contact="barrier")
    assert FemOptions.from_dict(barrier.to_dict()) == barrier
    assert FemOptions.from_dict(FemOptions().to_dict()) == FemOptions()


def test_an_accepted_fem_solve_is_seeded_under_the_key_of_todays_options(tmp_path):
    # An entry written before an option existed (steady.newton_budget) must be found by
    # the task today's code makes, which carries that option at its default: the
    # equivalence check recomputed it with the default (fem_task reads its options through
    # FemOptions.from_dict). Without it every accepted FEM solve was unreachable.
    from rubbercontact.fem import FemOptions
    from rubbercontact.sweep.codehash import code_digest

    fn = "rubbercontact.hybrid.tasks:fem_task"
    today = FemOptions(mesh=(120, 23), grading=8.0).to_dict()
    old = json.loads(json.dumps(today))
    del old["steady"]["newton_budget"]
    args = {"surface": {"wavelengths": [0.0625], "amplitudes": [0.01867], "phases": [0.0]},
            "material": {"preset": "sbr"}, "velocity": 10.0, "mean_pressure": 1.0}
    stored = Task(fn, {**args, "options": old})
    ref = ResultCache(tmp_path / "reference")
    ref.store(stored.key(code="old"), stored, xr.Dataset({"friction": ((), 0.5)}), 1.0)
    (path,) = ref.directory.glob("sweep-v1/*/*.nc")
    with netCDF4.Dataset(path, "a") as nc:
        nc.setncattr("rc_cache_code", "old")
    (ref.directory / "equivalence.json").write_text(json.dumps({"accepted": [
        {"function": fn, "stored": "old", "current": code_digest(fn), "why": "test",
         "checked": "test"}]}))
    assert eq.seed(ref.directory, tmp_path / "work", ("fem_task",)).copied == 1
    work = ResultCache(tmp_path / "work")
    hit = work.load(Task(fn, {**args, "options": today}).key())
    assert hit is not None and hit.result.attrs["code_accepted_from"] == "old"
    assert float(hit.result["friction"]) == 0.5
