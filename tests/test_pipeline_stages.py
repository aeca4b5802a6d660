"""A run's stages say what they are while they run (issue 39: "long stages are never
silent"): each sweep's progress lines name its stage, and the law's tables (computed in
the run's own process, seconds a speed) are a stage of their own; an extension of the law
recomputes only the tables of the speeds whose reading it changed."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr

import rubbercontact as rc
from rubbercontact.pipeline import execute, lawstage
from rubbercontact.roughness import SineSeries

SPEEDS = (1.0, 10.0)


def _law(extra_at_10: bool = False) -> xr.Dataset:
    """A monotone law table: u falls with p at both speeds; ``extra_at_10`` adds a point at
    2 MPa to the 10 mm/s row only (what an extension at one speed does)."""
    p = [0.1, 0.5, 1.0, 2.0]
    u = np.array([[0.010, 0.008, 0.006, np.nan]] * 2)
    status = np.array([["ok"] * 3 + ["not computed"]] * 2, dtype=object)
    if extra_at_10:
        u[1, 3], status[1, 3] = 0.004, "ok"
    grid = ("velocity", "pressure")
    alpha = np.broadcast_to(np.array(p) / (1 + np.array(p)), u.shape)
    return xr.Dataset({"status": (grid, status.astype(str)), "mean_separation": (grid, u),
                       "contact_fraction": (grid, np.array(alpha)),
                       "shear_stress": (grid, 0.3 * np.array(alpha))},
                      coords={"velocity": list(SPEEDS), "pressure": p},
                      attrs={"hs_max_height_mm": 0.02})


HS = SineSeries([0.0625], [0.01])


def _material():
    from rubbercontact.materials.maxwell import sbr

    return sbr()


@pytest.fixture
def tabulate():
    """``lawstage._stage`` with a runner in place of the sweep that records the speeds
    and stage of the law table tasks and answers each with its reading (the
    continuation's numbers are tested in test_hybrid)."""
    asked, stages = [], []

    def runner(tasks, description="sweep"):
        stages.append(description)
        asked.extend(t.kwargs["velocity"] for t in tasks)
        assert {t.function for t in tasks} == {"rubbercontact.hybrid.lawtask:law_table_task"}
        return [xr.Dataset({k: ("row", np.asarray(t.kwargs["reading"][k]))
                            for k in ("separation", "pressure", "contact_fraction",
                                      "shear_stress")}) for t in tasks]

    cfg = SimpleNamespace(material=SimpleNamespace(nu=0.5))      # what _stage reads

    def run(law, before=None):
        return lawstage._stage(law, None, HS, _material(), np.array(SPEEDS), cfg, raw=law,
                               before=before, runner=runner)
    return run, asked, stages


def test_an_extension_recomputes_only_the_tables_whose_reading_changed(tabulate):
    run, asked, _ = tabulate
    first = run(_law())
    assert asked == list(SPEEDS)
    asked.clear()
    same = run(_law(), before=first)
    assert asked == [] and all(same.tables[v] is first.tables[v] for v in SPEEDS)
    extended = run(_law(extra_at_10=True), before=first)
    assert asked == [10.0]
    assert extended.tables[1.0] is first.tables[1.0]
    assert extended.tables[10.0]["pressure"][0] == 2.0      # the new top point, read


def test_the_law_tables_are_a_stage_of_their_own(tabulate):
    run, _, stages = tabulate
    first = run(_law())
    assert stages == ["law tables"]
    run(_law(), before=first)                                # nothing to compute: no sweep
    assert stages == ["law tables"]


def test_a_repeat_reads_the_law_tables_the_first_run_computed(tmp_path, monkeypatch):
    """The tables' half-space solves differ in their last bits with the process's BLAS
    thread count; the hybrid tasks' keys hold the tables, so a repeat that computed them
    again (other threads: a run from the cache against the run that computed the FEM)
    gave those tasks other keys and re-ran them. The tables are cached tasks now."""
    from rubbercontact.hybrid import lawtask
    from rubbercontact.sweep import ExecutorConfig, ResultCache, run_sweep

    calls = []

    def noisy(table, hs, material, velocity, nu=0.5):      # another last bit each time
        calls.append(velocity)
        return {k: [x * (1 + len(calls) * 2.0 ** -52) for x in vals]
                for k, vals in table.items()}

    monkeypatch.setattr(lawtask, "continue_with_linear_shape", noisy)
    cache = ResultCache(tmp_path / "cache")

    def runner(tasks, description="sweep"):
        return run_sweep(tasks, cache=cache, executor=ExecutorConfig(workers=1)).results

    cfg = SimpleNamespace(material=SimpleNamespace(nu=0.5))
    first, again = (lawstage._stage(_law(), None, HS, _material(), np.array(SPEEDS), cfg,
                                    raw=_law(), runner=runner) for _ in range(2))
    assert calls == list(SPEEDS)                           # the repeat computed none
    assert again.tables == first.tables


def test_named_gives_the_stage_to_runners_that_take_it():
    seen = []

    def takes(tasks, description="sweep"):
        seen.append(description)
        return tasks

    def plain(tasks):
        return tasks

    assert execute.named(takes, "law FEM")([1]) == [1] and seen == ["law FEM"]
    assert execute.named(plain, "law FEM") is plain


def test_a_run_names_its_sweeps(tmp_path, capsys):
    cfg = {"velocities": [10.0], "realizations": 1, "models": ["vhs"],
           "surface": {"preset": "section3"}, "loads": {"pressures": [0.3]},
           "halfspace": {"n": 256},
           "execution": {"workers": 1, "cache": str(tmp_path / "cache")}}
    rc.pipeline.run(cfg, progress="log")
    err = capsys.readouterr().err
    assert "[models] 1/1 done" in err and "[sweep]" not in err


def test_the_full_fem_tasks_go_to_the_workers_first_in_their_order():
    from rubbercontact.pipeline.plan import Slot

    slots = [Slot("vhs", 0, 0, None), Slot("fem", 0, 0, 0), Slot("hybrid", 0, 0, None),
             Slot("fem", 0, 0, 1), Slot("meanfield", 0, None, 0)]
    assert execute.longest_first(slots) == [1, 3, 0, 2, 4]


def test_the_cli_says_the_whole_runs_estimate_before_its_stages(tmp_path, capsys):
    from rubbercontact.cli import main

    cfg = tmp_path / "vhs.toml"
    cfg.write_text('velocities = [10.0]\nrealizations = 1\nmodels = ["vhs"]\n'
                   '[surface]\npreset = "section3"\n[loads]\npressures = [0.3]\n'
                   '[halfspace]\nn = 256\n[execution]\nworkers = 1\ncache = "cache"\n'
                   '[output]\ndirectory = "out"\n')
    assert main(["run", str(cfg), "--no-figures"]) == 0
    err = capsys.readouterr().err.splitlines()
    first = next(k for k, line in enumerate(err) if line.startswith("[models]"))
    said = [line for line in err[:first] if line.startswith("run: about ")]
    assert len(said) == 1 and "on 1 worker(s)" in said[0] and "of CPU" in said[0]
    assert main(["run", str(cfg), "--no-figures", "--quiet", "--overwrite"]) == 0
    assert "run: about" not in capsys.readouterr().err
