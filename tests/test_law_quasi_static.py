"""The law cell's quasi-static check (:mod:`rubbercontact.pipeline.lawcheck`).

Physics: slid slowly enough that the rubber is relaxed at the shortest wave's frequency,
the cell is elastic and dissipates nothing, so the law's friction must vanish there; a
mesh too coarse for its contact patches keeps a friction of the lattice instead.
"""

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.fem import make_options
from rubbercontact.pipeline.lawcheck import (
    QS_LOSS_TANGENT,
    QS_TOL,
    QuasiStaticCheck,
    check_quasi_static,
    quasi_static_speed,
)
from rubbercontact.sweep import run_sweep


def _sls_loss_tangent(omega, e_inf, e1, tau):
    """Closed form of the standard linear solid: E = E∞ + E1 iωτ/(1 + iωτ)."""
    x = omega * tau
    return (e1 * x / (1 + x * x)) / (e_inf + e1 * x * x / (1 + x * x))


@pytest.mark.parametrize("tau", [1e-3, 1.0, 1e3])
def test_quasi_static_speed_is_the_fastest_relaxed_decade(tau):
    e_inf, e1, lam = 4.0, 400.0, 0.25
    mat = rc.materials.GeneralizedMaxwell(e_inf, np.array([e1]), np.array([tau]))
    v = quasi_static_speed(mat, lam)
    tan = _sls_loss_tangent(2 * np.pi * np.array([v, 10 * v]) / lam, e_inf, e1, tau)
    assert tan[0] <= QS_LOSS_TANGENT
    assert v == 1.0 or tan[1] > QS_LOSS_TANGENT


def test_quasi_static_speed_of_an_elastic_rubber_and_of_one_that_never_relaxes():
    assert quasi_static_speed(rc.materials.GeneralizedMaxwell.elastic(5.0), 0.1) == 1.0
    # E∞ a billionth of the branch: tan δ ≈ (E1/E∞) ωτ stays above 1e-3 down to 1e-12 mm/s
    never = rc.materials.GeneralizedMaxwell(1e-9, np.array([1.0]), np.array([1e3]))
    with pytest.raises(ValueError, match="no speed"):
        quasi_static_speed(never, 0.1)


def test_the_check_sorts_merges_and_says_where_it_fails():
    a = QuasiStaticCheck(1e-3, np.array([0.1, 1.0]), np.array([0.02, 0.001]), ("ok", "ok"))
    b = QuasiStaticCheck(1e-3, np.array([0.3]), np.array([np.nan]), ("ConvergenceError: x",))
    both = a.merged(b)
    assert both.pressure.tolist() == [0.1, 0.3, 1.0]
    assert both.status == ("ok", "ConvergenceError: x", "ok")
    assert both.failing.tolist() == [True, False, False]
    assert both.stopped.tolist() == [False, True, False]
    assert "1 of 3 law pressures pass; 0.1 MPa fail; 0.3 MPa did not converge" in \
        both.describe()
    assert "friction 0.02 at 0.1 MPa" in both.warning()
    assert a.merged(QuasiStaticCheck(1e-3, np.array([3.0]), np.array([0.0]), ("ok",))
                    ).warning().count("\n") == 0
    ds = both.as_dataset()
    assert ds["law_quasi_static_friction"].attrs["velocity_mm_s"] == 1e-3
    with pytest.raises(ValueError):
        a.merged(QuasiStaticCheck(1e-2, np.array([3.0]), np.array([0.0]), ("ok",)))


def _runner(tasks):
    return run_sweep(tasks, cache=None, progress=False).results


@pytest.fixture(scope="module")
def steep_cell():
    # two steep waves an octave apart (peak slopes 3.1 and 1.6), crests unrounded: the
    # shape of the CAPTIF high-slope cells in docs/validation/steep_cells.md
    return rc.roughness.SineSeries([0.25, 0.5], [0.125, 0.125])


def test_a_resolved_cell_passes_and_a_coarse_one_keeps_a_lattice_friction(steep_cell):
    sbr = rc.materials.sbr()
    resolved = check_quasi_static(make_options(mesh="auto"), steep_cell, sbr, [0.1], _runner)
    assert resolved.speed == quasi_static_speed(sbr, 0.25)
    assert resolved.status == ("ok",)
    assert abs(resolved.friction[0]) <= QS_TOL and resolved.warning() is None
    coarse = check_quasi_static(make_options(mesh=(32, 8)), steep_cell, sbr, [0.1], _runner)
    assert coarse.failing.all(), coarse.friction
    assert "law cell under-resolved" in coarse.warning()


def test_a_run_carries_the_check_on_its_law_pressures_and_warns_once_where_it_fails():
    import warnings

    import xarray as xr

    from rubbercontact.hybrid.lawtable import LawWarning
    from rubbercontact.pipeline.lawcheck import add_quasi_static

    ds = xr.Dataset(coords={"law_pressure": [0.1, 0.3, 1.0]})
    check = QuasiStaticCheck(1e-3, np.array([1.0, 0.1, 0.3])[[1, 2, 0]],
                             np.array([-0.3, 0.0, 0.001]), ("ok",) * 3)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        out = add_quasi_static(ds, check)
    assert [w.category for w in seen] == [LawWarning]
    assert "-0.3 at 0.1 MPa" in str(seen[0].message)
    np.testing.assert_array_equal(out["law_quasi_static_friction"], [-0.3, 0.0, 0.001])
    assert out.attrs["law_quasi_static"].endswith("2 of 3 law pressures pass; 0.1 MPa fail")


def test_the_law_and_its_check_go_to_the_workers_in_one_sweep(monkeypatch):
    """The check's points share the law's sweep (they fill the workers while the law's
    longest speed path runs) and each part reads back exactly its own answers."""
    from rubbercontact.config import parse_config
    from rubbercontact.pipeline import lawstage

    cfg = parse_config({"surface": {"preset": "section3"}, "velocities": [10.0, 50.0],
                        "loads": {"pressures": [0.2]},
                        "law": {"pressures": [0.1, 0.5]}, "fem": {"mesh": [24, 12]}})
    calls, seen = [], {}

    def runner(tasks):
        calls.append([t.label for t in tasks])
        return [f"answer {t.label}" for t in tasks]

    def law_from(answers):
        seen["law"] = answers
        return "raw"

    monkeypatch.setattr(lawstage, "_stage", lambda law, *a, quasi_static=None, **k:
                        (law, quasi_static))
    real = lawstage.law_batch

    def spy(*a, **k):
        batch = real(*a, **k)
        return lawstage.Batch(batch.tasks, law_from)

    monkeypatch.setattr(lawstage, "law_batch", spy)
    raw, qs = lawstage.build_law(cfg, rc.roughness.high_slope_wave(), rc.materials.sbr(),
                                 np.array([0.2]), runner)
    assert len(calls) == 1
    law_labels = [c for c in calls[0] if "quasi-static" not in c]
    qs_labels = [c for c in calls[0] if "quasi-static" in c]
    assert calls[0] == law_labels + qs_labels and len(qs_labels) == 2
    assert raw == "raw" and seen["law"] == [f"answer {c}" for c in law_labels]
    # the check read its own two answers (strings: failures, in the pressures' order)
    assert qs.pressure.tolist() == [0.1, 0.5] and qs.stopped.all()


def test_the_check_sends_the_highest_pressure_first_and_reads_each_answer_at_its_own():
    # the costliest point first (pipeline/costmodel.py prices it so, and a graded cell's top
    # point takes minutes): the answers come back in the order sent, the check in p order
    import xarray as xr

    from rubbercontact.pipeline.lawcheck import quasi_static_batch

    cell = rc.roughness.high_slope_wave()
    batch = quasi_static_batch(make_options(mesh=(32, 8)), cell, rc.materials.sbr(),
                               [0.5, 0.1, 2.0])
    sent = [t.kwargs["mean_pressure"] for t in batch.tasks]
    assert sent == [2.0, 0.5, 0.1]
    assert [t.cost for t in batch.tasks] == sorted(t.cost for t in batch.tasks)[::-1]
    # each task a path: the quasi-static speed, then the speed it is continued from
    speeds = batch.tasks[0].kwargs["velocities"]
    assert speeds == [check_speed := quasi_static_speed(rc.materials.sbr(), 0.0625), 10.0]
    assert check_speed < speeds[1]
    answers = [xr.Dataset({"friction": ("velocity", [p / 100, 9.0]),
                           "status": ("velocity", ["ok", "ok"])}) if p != 0.5 else None
               for p in sent]
    check = batch.collect(answers)
    assert check.pressure.tolist() == [0.1, 0.5, 2.0]
    assert check.friction[[0, 2]].tolist() == [0.001, 0.02] and np.isnan(check.friction[1])
    assert check.status[0] == check.status[2] == "ok" and check.status[1] != "ok"


def test_the_continued_point_answers_what_a_fresh_press_at_the_quasi_static_speed_does(
        steep_cell):
    # old and new: the check's point continued down from TAIL_FROM against the press at
    # the quasi-static speed it replaced, on the same options (no transient fallback)
    from rubbercontact.hybrid.tasks import fem_task
    from rubbercontact.pipeline.setup import task_material

    sbr = rc.materials.sbr()
    options = make_options(mesh="auto")
    check = check_quasi_static(options, steep_cell, sbr, [0.1], _runner)
    fresh = fem_task(steep_cell.as_dict(), task_material(sbr), check.speed, 0.1,
                     options.with_(steady={"fallback": False}).to_dict())
    # within the check's tolerance of each other, so the same verdict (the steep cell's
    # relaxed contact settles 8e-4 apart by the two routes; asphalt's and captif_road's
    # cells to 2e-8, benchmarks/qs_tail.md)
    assert check.status == ("ok",)
    assert abs(check.friction[0] - float(fresh["friction"])) < QS_TOL
    assert abs(float(fresh["friction"])) <= QS_TOL and not check.failing.any()


def test_a_continued_point_that_stops_is_recorded_as_stopped():
    import xarray as xr

    from rubbercontact.pipeline.lawcheck import quasi_static_batch

    batch = quasi_static_batch(make_options(mesh=(32, 8)), rc.roughness.high_slope_wave(),
                               rc.materials.sbr(), [0.1])
    check = batch.collect([xr.Dataset({"friction": ("velocity", [np.nan, 0.2]),
                                       "status": ("velocity", ["ConvergenceError: x", "ok"])})])
    assert check.stopped.all() and check.status == ("ConvergenceError: x",)
