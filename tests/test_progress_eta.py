"""The progress ETA weighted by the tasks' cost hints (issue 39), against a fake clock: the
hand-worked wall time left of known schedules, and the count rate without hints."""

import io

import numpy as np
import pytest
from test_pipeline_cost import CONFIG  # the same run: its --check stages are priced there

from rubbercontact.config import parse_config
from rubbercontact.errors import InputError
from rubbercontact.pipeline import resolve
from rubbercontact.pipeline.cost import estimate_cost
from rubbercontact.pipeline.lawstage import _grid_batch, _quasi_static, law_pressures
from rubbercontact.pipeline.plan import model_tasks
from rubbercontact.sweep import ExecutorConfig, Task, run_sweep
from rubbercontact.sweep.progress import ProgressReporter, Workload, make_reporter


class Clock:
    """A clock that moves only when told."""

    def __init__(self) -> None:
        self.t = 100.0

    def __call__(self) -> float:
        return self.t


def _reporter(costs, workers=1):
    clock = Clock()
    rep = ProgressReporter("test", clock=clock)
    rep.start(len(costs), workload=Workload(tuple(costs), workers))
    return rep, clock


def test_one_long_task_then_short_ones_the_eta_is_what_is_left_not_ten_times_it():
    # one worker: a 10 s task, then ten 1 s tasks; the first ends at 10 s as hinted
    rep, clock = _reporter([10.0] + [1.0] * 10)
    clock.t += 10.0
    rep.advance(task=0, seconds=10.0)
    assert rep.eta() == pytest.approx(10.0)
    # the count rate, 10 s a task for the 10 left, said 100 s
    plain, pclock = _reporter([None] * 11)
    pclock.t += 10.0
    plain.advance(task=0, seconds=10.0)
    assert plain.eta() == pytest.approx(100.0)


def test_the_hints_are_scaled_by_what_the_finished_tasks_took():
    rep, clock = _reporter([10.0] + [1.0] * 10)
    clock.t += 20.0                     # twice its hint (a loaded machine)
    rep.advance(task=0, seconds=20.0)
    assert rep.eta() == pytest.approx(20.0)
    clock.t += 2.0                      # then one short task at twice its hint too
    rep.advance(task=1, seconds=2.0)
    assert rep.eta() == pytest.approx(18.0)
    clock.t += 0.5                      # half a second into the next task
    assert rep.eta() == pytest.approx(17.5)


def test_two_workers_the_tasks_left_are_shared_and_the_running_ones_credited():
    # a law's three speed paths, highest pressure (longest) first, then three quasi-static
    # points: 90, 60, 30, 7, 7, 7 s on 2 workers. The 60 s path ends at 60 s: the 90 s path
    # has 30 s left, the 30 s path just started; then 7 s, 7 s on one worker, 7 s on the
    # other: 30 + 7 + 7 = 44 s left.
    rep, clock = _reporter([90.0, 60.0, 30.0, 7.0, 7.0, 7.0], workers=2)
    clock.t += 60.0
    rep.advance(task=1, seconds=60.0)
    assert rep.eta() == pytest.approx(44.0)
    # the count rate: 60 s for 1 task, 5 left
    plain, pclock = _reporter([None] * 6, workers=2)
    pclock.t += 60.0
    plain.advance(task=1, seconds=60.0)
    assert plain.eta() == pytest.approx(300.0)


def test_two_workers_one_long_task_then_short_ones():
    # 10 s on one worker, ten 1 s tasks on the other: at 1 s one short task is done, 9 s
    # are left on both
    rep, clock = _reporter([10.0] + [1.0] * 10, workers=2)
    clock.t += 1.0
    rep.advance(task=1, seconds=1.0)
    assert rep.eta() == pytest.approx(9.0)


def test_before_any_task_ends_the_eta_is_the_estimate_counting_down():
    rep, clock = _reporter([4.0, 2.0, 2.0], workers=2)
    assert rep.eta() == pytest.approx(4.0)       # 4 | 2 + 2
    clock.t += 1.0
    assert rep.eta() == pytest.approx(3.0)


def test_a_failed_task_does_not_scale_the_hints_and_the_end_is_zero():
    rep, clock = _reporter([10.0, 10.0])
    clock.t += 0.5
    rep.advance(failed=True, task=0, seconds=0.5)  # failed at once: says nothing of 10 s
    assert rep.eta() == pytest.approx(10.0)
    clock.t += 10.0
    rep.advance(task=1, seconds=10.0)
    assert rep.eta() == 0.0


@pytest.mark.parametrize("workload", [None, Workload(()), Workload((1.0, None, 1.0))])
def test_without_a_hint_for_every_task_the_eta_is_the_count_rate(workload):
    clock = Clock()
    rep = ProgressReporter("test", clock=clock)
    rep.start(4, cached=1, workload=workload)
    assert rep.eta() is None                 # nothing computed yet
    clock.t += 6.0
    rep.advance(task=0, seconds=6.0)
    assert rep.eta() == pytest.approx(12.0)  # 6 s a task, 2 left


def test_the_log_lines_print_the_weighted_eta():
    stream, clock = io.StringIO(), Clock()
    rep = make_reporter("log", "law FEM", stream=stream)
    rep.clock = clock
    rep.start(11, workload=Workload((10.0,) + (1.0,) * 10))
    clock.t += 10.0
    rep.advance(task=0, seconds=10.0)        # the interval since the first line is up
    assert stream.getvalue().splitlines()[-1].endswith("ETA 00:10")


def test_a_hint_is_not_part_of_a_tasks_key_or_record():
    args = dict(function="rubbercontact.sweep.examples:toy_kernel",
                kwargs={"velocity": 1.0, "pressure": 0.2}, label="t")
    hinted, bare = Task(**args, cost=12.5), Task(**args)
    assert hinted.key() == bare.key() and hinted.describe() == bare.describe()
    assert hinted == bare
    with pytest.raises(InputError, match="cost"):
        Task(**args, cost=-1.0)
    with pytest.raises(InputError, match="cost"):
        Task(**args, cost=float("nan"))


def test_run_sweep_hands_the_hints_and_each_tasks_time_to_the_reporter(capsys):
    tasks = [Task("rubbercontact.sweep.examples:toy_kernel",
                  {"velocity": 1.0, "pressure": p}, label=f"p={p}", cost=1.0)
             for p in (0.1, 0.2, 0.3)]
    res = run_sweep(tasks, executor=ExecutorConfig(workers=1), progress="log",
                    description="hinted")
    assert res.ok
    err = capsys.readouterr().err
    # before any task ended the weighted ETA is the hints' 3 s, not the count rate's "?"
    assert "[hinted] 0/3 done (0 from cache, 0 failed), elapsed 00:00, ETA 00:03" in err
    assert "[hinted] 3/3 done" in err and err.rstrip().endswith("ETA 00:00")



@pytest.mark.parametrize("speeds", [[10.0, 50.0], [1.0, 3.0, 10.0, 50.0]])
def test_the_pipelines_hints_are_run_checks_prices_of_its_tasks(speeds):
    # one source of truth: the hints of the tasks a run sends add up to --check's stages
    setup = resolve(parse_config({**CONFIG, "velocities": speeds}))
    cfg, mat = setup.config, setup.material
    stages = {s.name.split(" (")[0]: s for s in estimate_cost(setup).stages}
    law = _grid_batch(cfg, setup.hs0, mat, law_pressures(cfg, np.ones(1)), np.asarray(speeds))
    assert [t.cost for t in law.tasks] == pytest.approx(stages["law FEM points"].task_s)
    qs = _quasi_static(cfg, setup.hs0, mat, law_pressures(cfg, np.ones(1)), None)
    assert [t.cost for t in qs.tasks] == pytest.approx(        # highest pressure first
        stages["law cell quasi-static check"].task_s)
    slots, tasks = model_tasks(setup, mat, np.asarray(CONFIG["loads"]["pressures"]), {})
    by_model = {m: sum(t.cost for s, t in zip(slots, tasks, strict=True) if s.model == m)
                for m in setup.models}
    assert by_model["vhs"] + by_model["hybrid-windowed"] == pytest.approx(
        stages["half-space solves"].total_s)
    assert by_model["fem"] == pytest.approx(stages["full FEM tests"].total_s)
    assert by_model["meanfield"] == pytest.approx(stages["mean-field points"].total_s)
