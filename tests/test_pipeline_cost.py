"""run --check's cost estimate: the solves counted as the planner plans them, priced by
the measured per-point costs."""

import math

import numpy as np
import pytest

from rubbercontact.config import parse_config
from rubbercontact.pipeline import resolve
from rubbercontact.pipeline.cost import (
    Stage,
    estimate_cost,
    law_mesh,
    law_point_seconds,
    law_refined_mesh,
)
from rubbercontact.pipeline.costmodel import (
    AUTO_REFINED_SHARE,
    CONTINUATION_FACTOR,
    FEM_ELEMENT_EXPONENT,
    FEM_POINT_S,
    FEM_PRESSURE_SLOPE,
    FEM_REFERENCE_MESH,
    FULL_FEM_FACTOR,
    HALFSPACE_POINTS,
    HALFSPACE_SOLVE_S,
    OVERHEAD_S,
    QS_GRADED_FACTOR,
    QS_POINT_FACTOR,
    TRANSIENT_FACTOR,
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


def test_the_law_cells_quasi_static_check_is_one_point_per_law_pressure():
    setup = resolve(parse_config(CONFIG))
    cost = {s.name.split(" (")[0]: s for s in estimate_cost(setup).stages}
    check = cost["law cell quasi-static check"]
    fresh = [law_point_seconds(setup, p) for p in CONFIG["law"]["pressures"]]
    assert check.count == 3
    assert check.total_s == pytest.approx(QS_POINT_FACTOR * sum(fresh))
    off = resolve(parse_config({**CONFIG, "law": {**CONFIG["law"],
                                                  "quasi_static_check": False}}))
    assert not [s for s in estimate_cost(off).stages if "quasi-static" in s.name]
    assert check.same_sweep           # sent with the law's own points (lawstage.build_law)


@pytest.mark.parametrize("fem, factor", [
    ({"mesh": [40, 30], "grading": 8.0}, QS_GRADED_FACTOR),   # the section 3 cell's kind
    ({"mesh": [40, 30], "grading": 2.0}, QS_POINT_FACTOR),
    ({"mesh": "auto"}, QS_POINT_FACTOR),                      # graded by the rule: cheap
])
def test_a_quasi_static_point_on_an_explicitly_graded_cell_costs_more(fem, factor):
    # measured: 272-970 Newton iterations on the 120 x 23 cell graded 8 against 22-92 for
    # its law points fresh, 84-1035 continued down from 10 mm/s; 34 iterations graded 1
    # (pipeline/costmodel.py, QS_GRADED_FACTOR)
    setup = resolve(parse_config({**CONFIG, "fem": {**CONFIG["fem"], **fem}}))
    check = {s.name.split(" (")[0]: s for s in estimate_cost(setup).stages}[
        "law cell quasi-static check"]
    fresh = [law_point_seconds(setup, p) for p in CONFIG["law"]["pressures"]]
    assert check.total_s == pytest.approx(factor * sum(fresh))
    assert QS_GRADED_FACTOR > 2 * QS_POINT_FACTOR


def test_stages_sent_in_one_sweep_share_the_workers():
    """Two tasks of 5 s after one of 10 s: in one sweep the second worker takes both while
    the first runs the long one (10 s); in two sweeps the short ones wait (15 s)."""
    from rubbercontact.pipeline.cost import CostEstimate

    long = Stage("long", 1, 10.0)
    short = Stage("short", 2, 5.0)
    apart = CostEstimate((long, short), workers=2)
    together = CostEstimate((long, Stage("short", 2, 5.0, same_sweep=True)), workers=2)
    assert apart.wall_s - OVERHEAD_S == pytest.approx(15.0)
    assert together.wall_s - OVERHEAD_S == pytest.approx(10.0)
    assert together.cpu_s == apart.cpu_s


def test_prices_scale_from_the_measured_points():
    assert fem_point_seconds(FEM_REFERENCE_MESH) == pytest.approx(FEM_POINT_S)
    # elements to the power FEM_ELEMENT_EXPONENT: doubling nx or ny costs the same
    nx, ny = FEM_REFERENCE_MESH
    double = 2 ** FEM_ELEMENT_EXPONENT
    assert fem_point_seconds((2 * nx, ny)) == pytest.approx(FEM_POINT_S * double)
    assert fem_point_seconds((nx, 2 * ny)) == pytest.approx(FEM_POINT_S * double)
    # the load against the relaxed modulus: linear in p / E_inf, and only through it
    at = fem_point_seconds((40, 30), pressure=2.0, modulus=4.0)
    assert at == pytest.approx(fem_point_seconds((40, 30)) * (1 + FEM_PRESSURE_SLOPE / 2))
    assert fem_point_seconds((40, 30), pressure=4.0, modulus=8.0) == pytest.approx(at)
    assert fem_point_seconds((40, 30), pressure=3.0, modulus=4.0) > at
    assert fem_point_seconds((40, 30), "transient", 2.0, 4.0) == pytest.approx(
        TRANSIENT_FACTOR * at)
    assert TRANSIENT_FACTOR > 10
    assert halfspace_solve_seconds(HALFSPACE_POINTS) == pytest.approx(HALFSPACE_SOLVE_S)
    assert halfspace_solve_seconds(2 * HALFSPACE_POINTS) == pytest.approx(
        HALFSPACE_SOLVE_S * 2 * math.log(2 * HALFSPACE_POINTS) / math.log(HALFSPACE_POINTS))


def _law_stage(cfg: dict):
    setup = resolve(parse_config(cfg))
    return setup, next(s for s in estimate_cost(setup).stages
                       if s.name.startswith("law FEM"))


def test_the_law_costs_its_points_at_their_pressures_on_its_mesh():
    setup, stage = _law_stage(CONFIG)
    e_inf = setup.material.equilibrium_modulus
    each = [fem_point_seconds((40, 30), "steady", p, e_inf) for p in (0.1, 0.5, 2.0)]
    assert stage.total_s == pytest.approx(2 * sum(each))            # 2 speeds
    # twice the points (a second set of pressures a hair apart): twice the cost
    more = {**CONFIG, "law": {"pressures": [0.1, 0.5, 2.0, 0.1001, 0.5001, 2.0001]}}
    assert _law_stage(more)[1].total_s == pytest.approx(2 * stage.total_s, rel=1e-3)
    # a finer law cell: each point by the elements to the exponent
    finer = {**CONFIG, "fem": {**CONFIG["fem"], "mesh": [80, 30]}}
    assert _law_stage(finer)[1].each_s == pytest.approx(
        stage.each_s * 2 ** FEM_ELEMENT_EXPONENT)
    # the time-stepped solver
    transient = {**CONFIG, "fem": {**CONFIG["fem"], "solver": "transient"}}
    assert _law_stage(transient)[1].each_s == pytest.approx(TRANSIENT_FACTOR * stage.each_s)


def test_a_law_by_continuation_runs_one_task_per_pressure():
    speeds = {"from": 1.0, "to": 100.0, "points": 5}
    pressures = [0.1, 0.2, 0.5, 1.0, 2.0]
    setup, stage = _law_stage({**CONFIG, "velocities": speeds,
                               "law": {"pressures": pressures}})
    assert setup.speeds.computed.size == 5 and len(stage.tasks) == 5
    fresh = [law_point_seconds(setup, p) for p in pressures]
    assert stage.total_s == pytest.approx(5 * CONTINUATION_FACTOR * sum(fresh))
    # highest pressure first, each path its pressure's points in a row
    assert stage.tasks == pytest.approx([5 * CONTINUATION_FACTOR * t for t in fresh[::-1]])
    # five paths on two workers: the workers take them in order as they come free
    assert stage.wall_s(2) < stage.total_s
    assert stage.wall_s(2) >= max(stage.total_s / 2, max(stage.tasks))
    assert stage.wall_s(5) == pytest.approx(max(stage.tasks))


def test_an_automatic_mesh_budgets_the_refined_points():
    cfg = {**CONFIG, "fem": {"full_mesh": [64, 48], "realizations": 2}}     # mesh = "auto"
    setup, stage = _law_stage(cfg)
    mesh = tuple(int(n) for n in stage.name.split("(")[1].split(" (")[0].split(" x "))
    e_inf = setup.material.equilibrium_modulus
    fine = law_refined_mesh(setup)
    expect = [fem_point_seconds(mesh, "steady", p, e_inf)
              + AUTO_REFINED_SHARE * fem_point_seconds(fine, "steady", p, e_inf)
              for p in (0.1, 0.5, 2.0)]
    assert stage.total_s == pytest.approx(2 * sum(expect))


@pytest.mark.parametrize("columns", [16, 64])
def test_the_refined_points_are_priced_on_the_mesh_the_solver_refines_to(columns):
    # The budget of a re-solved point is the FEM's own refined mesh for the largest factor
    # (fem.sliding's _refined, the most a refinement costs): nx doubled and the rows of the
    # rule for twice the columns per wave, which keeps the face rows' aspect and so has
    # more rows than the first mesh.
    from rubbercontact.fem.resolution import REFINE_FACTORS
    from rubbercontact.fem.sliding import _refined

    cfg = {**CONFIG, "fem": {"full_mesh": [64, 48], "realizations": 2,
                             "columns_per_wave": columns}}
    setup = resolve(parse_config(cfg))
    first = setup.config.fem.options(setup.material).resolved(setup.hs0)
    fine = law_refined_mesh(setup)
    assert fine == tuple(_refined(setup.hs0, first, REFINE_FACTORS[-1]).mesh)
    assert fine[0] == 2 * law_mesh(setup)[0] and fine[1] > law_mesh(setup)[1]
    assert law_point_seconds(setup, 1.0) == pytest.approx(
        fem_point_seconds(law_mesh(setup), "steady", 1.0, setup.material.equilibrium_modulus)
        + AUTO_REFINED_SHARE * fem_point_seconds(fine, "steady", 1.0,
                                                 setup.material.equilibrium_modulus))


def test_wall_time_runs_the_tasks_in_rounds_of_the_workers():
    assert Stage("x", 4, 10.0).wall_s(2) == pytest.approx(20.0)
    assert Stage("x", 5, 10.0).wall_s(2) == pytest.approx(30.0)       # 3 rounds
    assert Stage("x", 5, 10.0).wall_s(1) == pytest.approx(50.0)
    assert Stage("x", 4, 10.0, (30.0, 4.0, 3.0, 3.0)).wall_s(2) == pytest.approx(30.0)


def test_wall_time_shares_the_solves_between_the_workers():
    setup = resolve(parse_config(CONFIG))
    est = estimate_cost(setup)
    assert est.compute_s == pytest.approx(sum(s.count * s.each_s for s in est.stages))
    # stages sent in one sweep share the workers: never slower than one after the other
    assert est.wall_s <= sum(s.wall_s(2) for s in est.stages) + OVERHEAD_S
    assert est.compute_s / 2 + OVERHEAD_S <= est.wall_s <= est.compute_s + OVERHEAD_S
    assert est.cpu_s == pytest.approx(est.compute_s + OVERHEAD_S)
    text = est.describe()
    assert "full FEM tests (64 x 48): 12 x" in text and "on 2 worker(s)" in text
    assert "of CPU" in text


def test_a_reused_law_costs_no_fem(tmp_path):
    law = tmp_path / "law.nc"
    law.write_bytes(b"")         # resolve checks only that it exists
    cfg = parse_config({**CONFIG, "models": ["vhs", "hybrid-windowed"],
                        "law": {"file": str(law)}})
    names = [s.name for s in estimate_cost(resolve(cfg)).stages]
    assert not any("FEM" in n for n in names)


def test_each_mean_field_model_has_its_own_price():
    # Persson's theory takes milliseconds a point, the strip cascade a tenth of a second
    from rubbercontact.pipeline.costmodel import MEANFIELD_POINT_S

    cfg = {**CONFIG, "models": ["meanfield", "meanfield-strips", "meanfield-hybrid"]}
    cfg.pop("fem")
    stages = {s.name: s for s in estimate_cost(resolve(parse_config(cfg))).stages}
    for m in ("meanfield", "meanfield-strips", "meanfield-hybrid"):
        stage = stages[f"mean-field points ({m})"]
        assert stage.count == 2 * 3 and stage.each_s == MEANFIELD_POINT_S[m]
    assert MEANFIELD_POINT_S["meanfield"] < 0.01 < MEANFIELD_POINT_S["meanfield-strips"]


def test_law_points_above_the_relaxed_modulus_are_said_not_budgeted():
    said = estimate_cost(resolve(parse_config(CONFIG))).describe()
    assert "law extension, if the local pressures pass the law" in said
    assert "above the rubber" not in said
    high = {**CONFIG, "law": {"pressures": [0.1, 2.0, 8.0, 16.0]}}
    said = estimate_cost(resolve(parse_config(high))).describe()
    assert "cost: not budgeted: law FEM points at 8, 16 MPa, above the rubber's E∞" in said
    # the automatic mesh does not try them (fem.loadrange): said so, and priced at nothing
    auto = {**high, "fem": {**CONFIG["fem"], "mesh": "auto"}}
    setup = resolve(parse_config(auto))
    assert "8, 16 MPa, above the rubber's E∞ (4.17 MPa), not tried" in \
        estimate_cost(setup).describe()
    assert law_point_seconds(setup, 8.0) == 0.0 < law_point_seconds(setup, 2.0)


def test_the_law_tables_cost_each_computed_speed_as_a_task_of_the_workers():
    from rubbercontact.pipeline.costmodel import LAW_TABLE_SPEED_S

    def tables(cfg):
        return next(s for s in estimate_cost(resolve(parse_config(cfg))).stages
                    if s.name.startswith("law tables"))

    two = tables(CONFIG)
    five = tables({**CONFIG, "velocities": {"from": 1.0, "to": 100.0, "points": 5}})
    assert two.count == 2 and five.count == 5
    assert five.total_s == pytest.approx(5 * LAW_TABLE_SPEED_S)
    # one task per speed (lawstage.law_tables, since the tables are cached tasks): two
    # workers take three rounds of the five, eight one
    assert five.wall_s(2) == pytest.approx(3 * LAW_TABLE_SPEED_S)
    assert five.wall_s(8) == pytest.approx(LAW_TABLE_SPEED_S)


def test_a_full_fem_test_is_priced_as_the_full_factor_times_a_point_of_its_mesh_and_load():
    # the full cell (several waves) needs more Newton iterations than a law point at the
    # same mesh and load (FULL_FEM_FACTOR); each test at its own load, and the price is
    # linear in the load, so the mean test costs a test at the mean pressure
    setup = resolve(parse_config(CONFIG))
    cost = {s.name.split(" (")[0]: s for s in estimate_cost(setup).stages}
    mesh = setup.config.fem.full_mesh_or_default
    e_inf = setup.material.equilibrium_modulus
    mean = float(np.mean(CONFIG["loads"]["pressures"]))
    assert cost["full FEM tests"].each_s == pytest.approx(
        FULL_FEM_FACTOR * fem_point_seconds(tuple(mesh), "steady", mean, e_inf), rel=1e-12)



def test_the_laws_extension_is_priced_as_one_round_at_its_worst():
    # law pressures 0.1-2 MPa, E∞ 4.17: the ladder's next rung 3.16 MPa at both speeds, its
    # quasi-static point, the tables of both speeds and hybrid-windowed's solves again
    setup = resolve(parse_config(CONFIG))
    ext, qs, tables, again = [s for s in estimate_cost(setup).stages
                              if s.name.startswith("law extension")]
    assert ext.count == 2 and "3.16 MPa" in ext.name
    assert ext.task_s == pytest.approx([law_point_seconds(setup, 10 ** 0.5)] * 2)
    assert qs.count == 1 and qs.same_sweep and "quasi-static" in qs.name
    assert qs.total_s == pytest.approx(QS_POINT_FACTOR * law_point_seconds(setup, 10 ** 0.5))
    assert tables.count == 2 and "tables" in tables.name
    assert again.count == 2 * 4 * 3                 # hybrid-windowed only: vhs reads no law
    # nothing to price: the extension off, or no rung at or below E∞ above the law's top
    for law in ({**CONFIG["law"], "extend": False}, {"pressures": [0.1, 2.0, 8.0]}):
        stages = estimate_cost(resolve(parse_config({**CONFIG, "law": law}))).stages
        assert not [s for s in stages if s.name.startswith("law extension")]


def test_the_full_fem_is_priced_at_the_runs_own_loads_and_skips_those_above_e_inf():
    """Each full FEM test priced at its own pressure; for target contact areas those are
    the VHS grid the run sweeps (pipeline.loads.run_pressures), so the count is the run's;
    a load above E∞ (outside the FEM cell's range, fem.loadrange) is not run, and named."""
    from rubbercontact.pipeline.cost import full_fem_seconds
    from rubbercontact.pipeline.loads import run_pressures

    setup = resolve(parse_config(CONFIG))
    e_inf = setup.material.equilibrium_modulus
    full = {s.name.split(" (")[0]: s for s in estimate_cost(setup).stages}["full FEM tests"]
    prices = [full_fem_seconds(setup, p) for p in CONFIG["loads"]["pressures"]]
    assert full.total_s == pytest.approx(2 * 2 * sum(prices))      # 2 speeds, 2 FEM reals
    assert not [n for n in estimate_cost(setup).notes if "full FEM" in n]
    high = resolve(parse_config({**CONFIG, "loads": {"pressures": [0.2, 1.2 * e_inf]}}))
    note, = [n for n in estimate_cost(high).notes if "full FEM" in n]
    assert note.startswith(f"full FEM not run at {1.2 * e_inf:.3g} MPa")
    full = {s.name.split(" (")[0]: s for s in estimate_cost(high).stages}["full FEM tests"]
    assert full.count == 2 * 2 and full.total_s == pytest.approx(2 * 2 * full_fem_seconds(
        high, 0.2))
    areas = resolve(parse_config({**CONFIG, "loads": {"contact_areas": [0.02, 0.05]}}))
    grid = run_pressures(areas)
    full = {s.name.split(" (")[0]: s for s in estimate_cost(areas).stages}["full FEM tests"]
    grid = grid[grid <= e_inf]
    assert full.count == 2 * 2 * grid.size
    assert full.total_s == pytest.approx(2 * 2 * sum(full_fem_seconds(areas, p)
                                                     for p in grid))
