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


@pytest.fixture
def tabulate(monkeypatch):
    """``lawstage._stage`` with the continuation replaced by a marker that records the
    speeds it was asked for (the continuation's numbers are tested in test_hybrid)."""
    asked = []

    def continuation(table, hs, material, velocity, nu=0.5):
        asked.append(velocity)
        return {**table, "continued_at": velocity}

    monkeypatch.setattr(lawstage, "continue_with_linear_shape", continuation)
    cfg = SimpleNamespace(material=SimpleNamespace(nu=0.5))      # what _stage reads

    def run(law, before=None, progress=False):
        return lawstage._stage(law, None, None, None, np.array(SPEEDS), cfg, raw=law,
                               progress=progress, before=before)
    return run, asked


def test_an_extension_recomputes_only_the_tables_whose_reading_changed(tabulate):
    run, asked = tabulate
    first = run(_law())
    assert asked == list(SPEEDS)
    asked.clear()
    same = run(_law(), before=first)
    assert asked == [] and all(same.tables[v] is first.tables[v] for v in SPEEDS)
    extended = run(_law(extra_at_10=True), before=first)
    assert asked == [10.0]
    assert extended.tables[1.0] is first.tables[1.0]
    assert extended.tables[10.0]["pressure"][0] == 2.0      # the new top point, read


def test_the_law_tables_are_a_stage_with_progress_lines(tabulate, capsys):
    run, _ = tabulate
    first = run(_law(), progress="log")
    assert "[law tables] 2/2 done" in capsys.readouterr().err
    run(_law(), before=first, progress="log")                # nothing to compute: silent
    assert capsys.readouterr().err == ""


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
