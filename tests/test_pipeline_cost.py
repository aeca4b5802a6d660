"""run --check's cost estimate: the solves counted as the planner plans them, priced by
the measured per-point costs."""

import numpy as np
import pytest

from rubbercontact.config import parse_config
from rubbercontact.pipeline import resolve
from rubbercontact.pipeline.cost import (
    FEM_POINT_S,
    HALFSPACE_SOLVE_S,
    OVERHEAD_S,
    estimate_cost,
    fem_point_seconds,
    halfspace_solve_seconds,
)
from rubbercontact.pipeline.lawstage import law_pressures
from rubbercontact.pipeline.plan import model_tasks

CONFIG = {"surface": {"preset": "section3"}, "velocities": [10.0, 50.0],
          "loads": {"pressures": [0.15, 0.25, 0.35]}, "realizations": 4,
          "models": ["vhs", "hybrid-windowed", "fem", "meanfield"],
          "fem": {"mesh": [40, 30], "full_mesh": [64, 48], "realizations": 2},
          "law": {"pressures": [0.1, 0.5, 2.0]}, "halfspace": {"n": 2048},
          "execution": {"workers": 2}}


def test_counts_are_the_planned_solves():
    setup = resolve(parse_config(CONFIG))
    cost = {s.name.split(" (")[0]: s for s in estimate_cost(setup).stages}
    pressures = np.asarray(CONFIG["loads"]["pressures"])
    slots, tasks = model_tasks(setup, setup.material, pressures, {})
    hs = sum(len(t.kwargs["mean_pressures"]) for t in tasks if "mean_pressures" in t.kwargs)
    fem = sum(1 for s in slots if s.model == "fem")
    mf = sum(1 for s in slots if s.model == "meanfield")
    assert cost["half-space solves"].count == hs == 2 * 2 * 4 * 3
    assert cost["full FEM tests"].count == fem == 2 * 2 * 3          # fem.realizations = 2
    assert cost["mean-field points"].count == mf == 2 * 3
    n_law = len(law_pressures(setup.config, pressures))
    assert cost["law FEM points"].count == n_law * 2 == 6


def test_prices_scale_from_the_measured_points():
    assert fem_point_seconds((40, 30)) == pytest.approx(FEM_POINT_S)
    # unknowns 2 (nx + 1)(ny + 1) to the power 1.5
    ratio = (2 * 65 * 49 / (2 * 41 * 31)) ** 1.5
    assert fem_point_seconds((64, 48)) == pytest.approx(FEM_POINT_S * ratio)
    assert fem_point_seconds((40, 30), "transient") > 10 * fem_point_seconds((40, 30))
    assert halfspace_solve_seconds(2048) == pytest.approx(HALFSPACE_SOLVE_S)
    assert halfspace_solve_seconds(4096) == pytest.approx(HALFSPACE_SOLVE_S * 2 * 12 / 11)


def test_wall_time_shares_the_solves_between_the_workers():
    setup = resolve(parse_config(CONFIG))
    est = estimate_cost(setup)
    assert est.compute_s == pytest.approx(sum(s.count * s.each_s for s in est.stages))
    assert est.wall_s == pytest.approx(est.compute_s / 2 + OVERHEAD_S)
    text = est.describe()
    assert "full FEM tests (64 x 48): 12 x" in text and "on 2 worker(s)" in text


def test_a_reused_law_costs_no_fem(tmp_path):
    law = tmp_path / "law.nc"
    law.write_bytes(b"")         # resolve checks only that it exists
    cfg = parse_config({**CONFIG, "models": ["vhs", "hybrid-windowed"],
                        "law": {"file": str(law)}})
    names = [s.name for s in estimate_cost(resolve(cfg)).stages]
    assert not any("FEM" in n for n in names)


def test_each_mean_field_model_has_its_own_price():
    # Persson's theory takes milliseconds a point, the strip cascade a tenth of a second
    from rubbercontact.pipeline.cost import MEANFIELD_POINT_S

    cfg = {**CONFIG, "models": ["meanfield", "meanfield-strips", "meanfield-hybrid"]}
    cfg.pop("fem")
    stages = {s.name: s for s in estimate_cost(resolve(parse_config(cfg))).stages}
    for m in ("meanfield", "meanfield-strips", "meanfield-hybrid"):
        stage = stages[f"mean-field points ({m})"]
        assert stage.count == 2 * 3 and stage.each_s == MEANFIELD_POINT_S[m]
    assert MEANFIELD_POINT_S["meanfield"] < 0.01 < MEANFIELD_POINT_S["meanfield-strips"]
