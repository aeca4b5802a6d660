"""The half-space and hybrid flash through sweep tasks and the result cache
(:mod:`rubbercontact.pipeline.flash_task`, :mod:`rubbercontact.pipeline.flash_halfspace`;
``meanfield-hybrid``: :mod:`rubbercontact.pipeline.flash_meanfield_task`).

Checked against the run itself, not against numbers it printed: a second run is served
from the cache (no flash task computed) and is the first run bit for bit; a run killed
between the flash's two rounds resumes with only the unfinished tasks computed and gives
the uninterrupted run bit for bit; the task's key holds the code of the flash kernel (an
edit of any of its modules is a new key) and not the run's set-up or config (an edit there
leaves it).
"""

import shutil

import numpy as np
import pytest
from test_pipeline_flash_hybrid import _config, _linear_law

import rubbercontact as rc
import rubbercontact.pipeline.flash_meanfield_task as meanfield_task
import rubbercontact.pipeline.flash_task as flash_task
from rubbercontact.config import parse_config
from rubbercontact.pipeline import resolve
from rubbercontact.pipeline.cost import estimate_cost
from rubbercontact.pipeline.execute import make_runner
from rubbercontact.sweep import code_digest, codehash
from rubbercontact.sweep.tasks import task_key

MODELS = ["vhs", "hybrid", "hybrid-windowed", "meanfield-hybrid"]
TASKS = {flash_task.FLASH_TASK: (flash_task, "halfspace_flash_task"),
         meanfield_task.MEANFIELD_FLASH_TASK: (meanfield_task, "meanfield_hybrid_flash_task")}
VARIABLES = ("friction_flash", "contact_fraction_flash", "flash_temperature",
             "flash_heat_flux", "flash_temperature_hs")


@pytest.fixture(autouse=True)
def _no_continuation(monkeypatch):
    monkeypatch.setattr("rubbercontact.hybrid.lawtask.continue_with_linear_shape",
                        lambda table, *args, **kwargs: table)


@pytest.fixture
def calls(monkeypatch) -> list:
    """The flash tasks computed (the synchronous executor resolves a task by its path)."""
    done: list = []

    def counted(task, name: str):
        def run(**kwargs):
            done.append(name)
            return task(**kwargs)
        return run

    for module, name in TASKS.values():
        monkeypatch.setattr(module, name, counted(getattr(module, name), name))
    return done


def _cfg(tmp_path, cache: str) -> dict:
    cfg = _config(tmp_path, speeds=(100.0, 1e4), models=MODELS, realizations=2)
    cfg["execution"]["cache"] = str(tmp_path / cache)
    return cfg


def _same(a, b) -> None:
    for k in VARIABLES:
        np.testing.assert_array_equal(a[k].values, b[k].values, err_msg=k)
    for k in ("flash_note", "flash_residual_K", "flash_halfspace_solves"):
        assert a.attrs[k] == b.attrs[k], k


@pytest.mark.filterwarnings("ignore::rubbercontact.hybrid.LawWarning")   # the law's range
def test_a_second_run_is_served_from_the_cache_and_a_killed_run_resumes(tmp_path, calls):
    cfg = _cfg(tmp_path, "a")
    law = _linear_law(cfg)
    first = rc.pipeline.run(cfg, law=law, progress=False)
    tasks = len(calls)
    assert tasks == len(MODELS)            # one per model at one load, no temperatures
    stages = {s.name.split(" (")[0]: s for s in estimate_cost(resolve(parse_config(cfg))).stages}
    flash = stages["flash temperature: half-space solves"]
    # the cost model counts the run's flash tasks
    assert len(flash.tasks) + stages["flash temperature: meanfield-hybrid curves"].count == tasks
    assert flash.count == stages["half-space solves"].count    # a heated search per solve
    assert first.attrs["flash_halfspace_solves"] > 0

    calls.clear()
    again = rc.pipeline.run(cfg, law=law, progress=False)
    assert calls == []                     # every flash task from the cache
    _same(first, again)

    killed = _cfg(tmp_path, "b")
    runner = make_runner(rc.config.parse_config(killed), progress=False)
    rounds = []

    def kill_at_the_second_round(tasks, *args, **kwargs):
        if tasks and tasks[0].function in TASKS:
            rounds.append(len(tasks))
            if len(rounds) == 2:
                raise KeyboardInterrupt("killed")
        return runner(tasks, *args, **kwargs)

    calls.clear()
    with pytest.raises(KeyboardInterrupt):
        rc.pipeline.run(killed, law=law, runner=kill_at_the_second_round, progress=False)
    assert rounds == [3, 1] and len(calls) == 3      # all done but hybrid-windowed
    calls.clear()
    resumed = rc.pipeline.run(killed, law=law, progress=False)
    assert calls == ["halfspace_flash_task"]        # hybrid-windowed, from hybrid's roots
    _same(first, resumed)


def _edited(tmp_path, monkeypatch, module: str) -> None:
    """The digest reads ``module``'s source from a copy with one statement more."""
    path = codehash._module_file(module)
    copy = tmp_path / f"{module}.py"
    shutil.copy(path, copy)
    copy.write_text(copy.read_text() + "\n_EDITED = 1\n")
    real = codehash._module_file
    monkeypatch.setattr(codehash, "_module_file",
                        lambda name: copy if name == module else real(name))
    codehash._reset()


@pytest.mark.parametrize("function, module", [
    *((flash_task.FLASH_TASK, m) for m in (
        "rubbercontact.thermal.kernel",            # the moving heat source (FFT)
        "rubbercontact.thermal.contact",           # the contact temperature's search
        "rubbercontact.thermal.sweep",             # the sweep over speeds
        "rubbercontact.pipeline.flash_scales",     # the high-slope scale's own flash
        "rubbercontact.pipeline.flash_hybrid",     # the hybrid's solve with the law
        "rubbercontact.halfspace.solver")),        # the half-space solve
    *((meanfield_task.MEANFIELD_FLASH_TASK, m) for m in (
        "rubbercontact.meanfield.flash",           # the cascade of spots
        "rubbercontact.thermal.spots",             # the band source
        "rubbercontact.pipeline.flash_scales",
        "rubbercontact.meanfield.solve")),         # the mean-field solve
])
def test_an_edit_of_the_flash_kernel_is_a_new_key(tmp_path, monkeypatch, function, module):
    kwargs = {"solves": [], "pressure": 0.3, "velocities": [1.0], "shift": {},
              "thermal": {}, "temperature": None, "search": {}}
    before = task_key(function, kwargs)
    _edited(tmp_path, monkeypatch, module)
    try:
        assert task_key(function, kwargs) != before
    finally:
        monkeypatch.undo()
        codehash._reset()
    assert task_key(function, kwargs) == before


@pytest.mark.parametrize("function", [flash_task.FLASH_TASK,
                                      meanfield_task.MEANFIELD_FLASH_TASK])
@pytest.mark.parametrize("module", ["rubbercontact.pipeline.setup",
                                    "rubbercontact.pipeline.flash",
                                    "rubbercontact.pipeline.flash_meanfield",
                                    "rubbercontact.config"])
def test_the_run_set_up_is_not_part_of_the_task_code(tmp_path, monkeypatch, function, module):
    before = code_digest(function)
    _edited(tmp_path, monkeypatch, module)
    try:
        assert code_digest(function) == before
    finally:
        monkeypatch.undo()
        codehash._reset()
