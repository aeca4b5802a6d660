"""The automatic FEM mesh and each test's check of its own resolution (issue 41, item 2).

References: the rule's arithmetic (columns per shortest wave, geometric rows that fill the
cell), the widths of contact patches given by hand, and Westergaard's elastic sine, whose
contact half-width ``a`` follows from ``sin²(πa/λ) = p̄/p*`` — so its patch spans a known
number of columns.
"""

from __future__ import annotations

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.errors import InputError
from rubbercontact.fem.options import FemOptions
from rubbercontact.fem.resolution import (
    FACE_ASPECT,
    MIN_ROWS,
    REFINE_FACTORS,
    TOP_ROWS_PER_WIDTH,
    auto_mesh,
    auto_nx,
    graded_rows,
    patch_widths,
    refine_factor,
)

#: The high-slope cell of both CAPTIF stations (examples/captif_road.toml).
STEEP = rc.roughness.SineSeries([0.25, 0.5], [0.1273, 0.1208], [0.0, 0.0])


@pytest.mark.parametrize("n, nx", [(8, 16), (16, 32), (32, 64), (64, 128)])
def test_columns_per_shortest_wave(n, nx):
    assert auto_nx(STEEP, n) == nx
    one = rc.roughness.SineSeries([1.0 / 3.0, 1.0], [0.01, 0.02])
    assert auto_nx(one, 11) == 34          # 33 rounded up to even (the nested iteration)


@pytest.mark.parametrize("n", [8, 16, 32, 64, 128])
def test_rows_fill_the_cell_from_the_face_row_to_the_top_row(n):
    m = auto_mesh(STEEP, 0.75, n)
    width, height = STEEP.period, 0.75 * STEEP.period
    cell = rc.fem.mesh.periodic_cell(width, height, m.nx, m.ny, grading=m.grading)
    dy = np.diff(cell.y_nodes)
    assert dy.sum() == pytest.approx(height)
    assert m.ny >= MIN_ROWS
    assert dy[-1] <= width / TOP_ROWS_PER_WIDTH * (1 + 1e-9) or m.grading == 1.0
    if m.grading > 1.0:
        # the face row is the rule's, and one row fewer would leave the top row too tall
        assert dy[0] == pytest.approx(FACE_ASPECT * width / m.nx, rel=1e-6)
        fewer, _ = graded_rows(height, dy[0], width / TOP_ROWS_PER_WIDTH)
        assert fewer == m.ny
    else:
        assert dy[0] <= FACE_ASPECT * width / m.nx * (1 + 1e-9)


def test_rows_on_a_shallow_cell_are_uniform():
    assert graded_rows(1.0, 0.2, 0.5) == (MIN_ROWS, 1.0)
    ny, g = graded_rows(1.0, 0.01, 1.0)     # the top row may be as tall as the cell
    assert ny == MIN_ROWS and g > 1


def test_patch_widths():
    x = np.linspace(0.0, 1.0, 100, endpoint=False)
    gap = np.ones_like(x)
    gap[10:20] = -1.0                        # nodes 10..19: 9 intervals + two crossings
    gap[50:52] = -1.0
    w = np.sort(patch_widths(x, gap, 1.0))
    assert w == pytest.approx([0.02, 0.10])  # each end crossing half an interval out
    # a patch over the seam is one patch
    gap = np.ones_like(x)
    gap[:5] = gap[-5:] = -1.0
    assert patch_widths(x, gap, 1.0) == pytest.approx([0.10])
    assert patch_widths(x, np.ones_like(x), 1.0).size == 0
    assert patch_widths(x, -np.ones_like(x), 1.0) == pytest.approx([1.0])


def test_auto_options_round_trip_and_resolve():
    opts = FemOptions(mesh="auto", columns_per_wave=16)
    assert opts.auto and FemOptions.from_dict(opts.to_dict()) == opts
    res = opts.resolved(STEEP)
    assert res.mesh == (32, 10) and not res.auto and res.grading > 1
    # the nested iteration's coarsest mesh keeps the rule's columns per wave
    assert res.steady.coarse_elements == 16
    explicit = FemOptions(mesh=(40, 30))
    assert explicit.resolved(STEEP) is explicit
    # an explicit mesh keeps its task arguments (and cache keys): no rule fields
    assert "columns_per_wave" not in explicit.to_dict()
    assert "patch_columns" not in explicit.to_dict()
    with pytest.raises(InputError, match="grading"):
        FemOptions(mesh="auto", grading=4.0)
    with pytest.raises(InputError, match="'auto'"):
        FemOptions(mesh="fine")


def _westergaard(fraction_of_full: float):
    """An elastic sine pressed to ``fraction_of_full`` of full contact, and its contact
    width ``2a/λ`` (Westergaard)."""
    E, lam, amp = 4.0, 1.0, 0.01
    surf = rc.roughness.SineSeries([lam], [amp], [np.pi / 2])
    p_full = np.pi * (4 * E / 3) * amp / lam
    pbar = fraction_of_full * p_full
    width = 2 / np.pi * np.arcsin(np.sqrt(fraction_of_full))
    return surf, rc.materials.GeneralizedMaxwell.elastic(E), pbar, width


def test_patch_check_on_westergaard():
    surf, mat, pbar, width = _westergaard(0.3)
    out = rc.fem.sliding_test(surf, mat, pbar, 0.0, mesh=(40, 30))
    # the patch spans 2a/λ · nx columns, edges resolved to about one column each
    assert out.stats.patch_columns == pytest.approx(width * 40, abs=1.5)
    assert not out.stats.under_resolved and not out.stats.refined


def test_narrow_patch_is_flagged_and_refined_once():
    surf, mat, pbar, width = _westergaard(0.01)      # 2a/λ = 0.064: 2.6 of 40 columns
    out = rc.fem.sliding_test(surf, mat, pbar, 0.0, mesh=(40, 30))
    assert out.stats.under_resolved and not out.stats.refined   # explicit: flagged only
    assert out.stats.patch_columns == pytest.approx(width * 40, abs=1.5)
    with pytest.warns(RuntimeWarning, match="under-resolved"):
        auto = rc.fem.sliding_test(surf, mat, pbar, 0.0, mesh="auto", columns_per_wave=40,
                                   patch_columns=6)
    # 40 columns -> 2.6 wide: refined once to 80 (5.1 wide), still below 6, and says so
    assert auto.mesh[0] == 80 and auto.stats.refined and auto.stats.under_resolved
    assert auto.stats.patch_columns == pytest.approx(width * 80, abs=1.5)
    assert auto.stats.tried[0].startswith("refined to 80x")
    assert auto.contact_fraction == pytest.approx(width, abs=2 / 80)


def test_refine_factor_is_the_smallest_that_widens_the_patch_enough():
    assert refine_factor(3.0, 4) == 1.5      # 4.5 columns after 1.5x
    assert refine_factor(2.6, 4) == 2.0      # 3.9 after 1.5x: too few
    assert refine_factor(0.5, 4) == REFINE_FACTORS[-1]   # beyond every factor: the largest
    assert refine_factor(np.nan, 4) == REFINE_FACTORS[-1]


def test_a_patch_a_third_too_narrow_is_refined_by_half_not_doubled():
    # 2a/λ = 0.080: 3.2 columns of 40 (3.8 measured) against 4 needed -> 60 columns, where
    # the patch is 4.8 wide (4.4 measured, edges resolved to about a column) and resolved
    surf, mat, pbar, width = _westergaard(0.0157)
    auto = rc.fem.sliding_test(surf, mat, pbar, 0.0, mesh="auto", columns_per_wave=40,
                               patch_columns=4)
    assert auto.mesh[0] == 60 and auto.stats.refined and not auto.stats.under_resolved
    assert auto.stats.patch_columns == pytest.approx(width * 60, abs=1.5)
    assert auto.stats.tried[0].startswith("refined to 60x")
    assert auto.contact_fraction == pytest.approx(width, abs=2 / 60)


def test_a_refinement_still_too_narrow_goes_on_to_the_largest_factor(monkeypatch):
    # the first factor chosen too small (as a patch narrowing with the mesh would make
    # it): 40 -> 50 columns leave the 2.6-column patch at 3.2, below 6; the test goes on to
    # 80 columns and keeps that answer, flagged, as the plain 2x refinement gives it
    import rubbercontact.fem.sliding as sliding

    surf, mat, pbar, _ = _westergaard(0.01)
    monkeypatch.setattr(sliding, "REFINE_FACTORS", (1.25, 2.0))
    monkeypatch.setattr(sliding, "refine_factor", lambda patch, need: 1.25)
    with pytest.warns(RuntimeWarning, match="under-resolved"):
        auto = rc.fem.sliding_test(surf, mat, pbar, 0.0, mesh="auto", columns_per_wave=40,
                                   patch_columns=6)
    monkeypatch.undo()
    with pytest.warns(RuntimeWarning, match="under-resolved"):
        doubled = rc.fem.sliding_test(surf, mat, pbar, 0.0, mesh="auto", columns_per_wave=40,
                                      patch_columns=6)
    assert auto.mesh == doubled.mesh and auto.mesh[0] == 80 and auto.stats.refined
    assert auto.contact_fraction == doubled.contact_fraction


def test_a_refinement_that_fails_keeps_the_first_answer_and_tries_no_finer_mesh(monkeypatch):
    # the press of the 1.5x mesh stops: the 2x mesh (harder still) is not tried, and the
    # first mesh's answer stands, flagged, with the failure in its stages
    import rubbercontact.fem.sliding as sliding
    from rubbercontact.errors import ConvergenceError

    surf, mat, pbar, _ = _westergaard(0.0157)
    meshes, steady = [], sliding._steady

    def failing_when_refined(surface, material, p, v, opts, start):
        meshes.append(opts.mesh[0])
        if opts.mesh[0] != 40:
            raise ConvergenceError("press stopped (test)")
        return steady(surface, material, p, v, opts, start)

    monkeypatch.setattr(sliding, "_steady", failing_when_refined)
    with pytest.warns(RuntimeWarning, match="under-resolved"):
        auto = rc.fem.sliding_test(surf, mat, pbar, 0.0, mesh="auto", columns_per_wave=40,
                                   patch_columns=4)
    assert meshes == [40, 60]
    assert auto.mesh[0] == 40 and auto.stats.under_resolved and not auto.stats.refined
    assert any(t.startswith("refine 60x") and "failed" in t for t in auto.stats.tried)


def test_a_point_sheared_as_a_whole_is_not_refined(monkeypatch):
    # a narrow patch on a cell sheared as a whole beyond the limit (the steep CAPTIF cell at
    # 3 MPa / 30 mm/s: 2.7 columns, sheared by 1.5): outside the cell's range whatever the
    # mesh, so it is not re-solved finer; it stands flagged, and says why
    from dataclasses import replace

    import rubbercontact.fem.sliding as sliding
    from rubbercontact.fem.result import BULK_SHEAR_LIMIT

    surf, mat, pbar, _ = _westergaard(0.0157)
    meshes, steady = [], sliding._steady

    def sheared(surface, material, p, v, opts, start):
        meshes.append(opts.mesh[0])
        res = steady(surface, material, p, v, opts, start)
        return replace(res, stats=replace(res.stats, bulk_shear=1.5 * BULK_SHEAR_LIMIT))

    monkeypatch.setattr(sliding, "_steady", sheared)
    with pytest.warns(RuntimeWarning, match="under-resolved"):
        auto = rc.fem.sliding_test(surf, mat, pbar, 0.0, mesh="auto", columns_per_wave=40,
                                   patch_columns=4)
    assert meshes == [40] and auto.mesh[0] == 40
    assert auto.stats.under_resolved and not auto.stats.refined
    assert any(t.startswith("not refined: the cell sheared as a whole")
               for t in auto.stats.tried)


def test_config_mesh_is_auto_by_default_and_explicit_still_works():
    base = {"surface": {"preset": "section3"}, "velocities": [10.0],
            "loads": {"pressures": [0.2]}}
    mat = rc.materials.sbr()
    cfg = rc.config.parse_config(base)
    assert cfg.fem.mesh == "auto" and cfg.fem.options(mat).auto
    assert cfg.fem.options(mat).columns_per_wave == cfg.fem.columns_per_wave
    # the full-surface FEM does not follow the rule (a whole surface's columns)
    assert cfg.fem.options(mat, full=True).mesh == (120, 90)
    cfg = rc.config.parse_config({**base, "fem": {"mesh": [60, 45], "grading": 2.0}})
    assert cfg.fem.options(mat).mesh == (60, 45)
    assert cfg.fem.options(mat, full=True).mesh == (60, 45)
    with pytest.raises(InputError, match="grading"):
        rc.config.parse_config({**base, "fem": {"grading": 2.0}})
    with pytest.raises(InputError, match="columns_per_wave"):
        rc.config.parse_config({**base, "fem": {"columns_per_wave": 4}})


def test_cost_estimate_prices_the_automatic_mesh():
    from rubbercontact.pipeline import resolve
    from rubbercontact.pipeline.cost import estimate_cost, law_mesh, law_point_seconds

    cfg = rc.config.parse_config({
        "surface": {"preset": "section3"}, "velocities": [10.0],
        "loads": {"pressures": [0.2]}, "models": ["vhs", "hybrid"],
        "law": {"pressures": [0.1, 0.5]}, "fem": {"columns_per_wave": 16}})
    setup = resolve(cfg)
    mesh = law_mesh(setup)
    assert mesh == cfg.fem.options(setup.material).resolved(setup.hs0).mesh
    assert mesh[0] == auto_nx(setup.hs0, 16)
    stage = next(s for s in estimate_cost(setup).stages if s.name.startswith("law FEM"))
    assert f"{mesh[0]} x {mesh[1]} (auto)" in stage.name
    assert stage.each_s == pytest.approx(np.mean([law_point_seconds(setup, p)
                                                  for p in (0.1, 0.5)]))


def test_quasi_static_friction_vanishes_on_the_chosen_mesh():
    # The coarse subset of docs/validation/mesh_resolution.md (whose quasi-static point is
    # 1 MPa, 35 s): the steep CAPTIF cell at 0.3 MPa, 1e-3 mm/s (loss tangent 1e-4: μ must
    # vanish). On 32 columns per 0.25 mm wave its narrowest patch is under 2 columns, which
    # the check flags; on the chosen 64 μ is within 0.005 of zero (6e-4 measured).
    mat = rc.materials.sbr()
    coarse = rc.fem.steady_sliding(STEEP, mat, 0.3, 1e-3, mesh=(64, 13), grading=4.8,
                                   coarse_elements=32, fallback=False)
    assert coarse.stats.under_resolved and coarse.stats.patch_columns < 4
    m = auto_mesh(STEEP, 0.75, FemOptions().columns_per_wave)
    fine = rc.fem.steady_sliding(STEEP, mat, 0.3, 1e-3, mesh=(m.nx, m.ny), grading=m.grading,
                                 coarse_elements=64, fallback=False)
    assert not fine.stats.under_resolved
    assert abs(fine.friction) < 0.005


def test_under_resolved_law_points_are_one_line_in_the_notes():
    import warnings

    import xarray as xr

    from rubbercontact.validity.run import _fem_resolution, _law_resolution

    flag = np.array([[0.0, 1.0, np.nan], [0.0, 1.0, 0.0]])
    cols = np.array([[9.0, 2.5, np.nan], [12.0, 3.1, np.inf]])
    law = xr.Dataset({"under_resolved": (("pressure", "velocity"), flag.T),
                      "patch_columns": (("pressure", "velocity"), cols.T)},
                     coords={"velocity": [1.0, 10.0], "pressure": [0.1, 0.3, 1.0]})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        (note,) = _law_resolution("hybrid", law)
    assert "2 of 6 law FEM points under-resolved" in note.text
    assert "2.5 columns (p = 0.3 MPa, v = 1 mm/s)" in note.text
    # the advice names the option that refines this law's mesh
    assert "a larger fem.columns_per_wave refines" in note.text
    law.attrs["fem_options"] = '{"mesh": [40, 30]}'
    (pinned,) = _law_resolution("hybrid", law)
    assert 'fem.mesh = "auto" or a finer fem.mesh than 40 x 30 refines' in pinned.text
    assert "columns_per_wave" not in pinned.text
    assert _law_resolution("vhs", law) == []
    # the full FEM's tests likewise, in the FEM's note
    ds = xr.Dataset({"fem_under_resolved": (("velocity", "pressure"), flag),
                     "fem_patch_columns": (("velocity", "pressure"), cols)})
    (note,) = _fem_resolution("fem", ds)
    assert "2 of 5 FEM tests under-resolved, narrowest contact patch 2.5 columns" in note.text
    assert _fem_resolution("vhs", ds) == []


def test_a_refined_neighbour_starts_the_next_point_on_its_mesh():
    # continuation along loads (as the law's speed paths): the first point refines, the
    # next starts on the refined mesh from its neighbour instead of checking afresh
    surf, mat, _, _ = _westergaard(0.01)
    p_full = np.pi * (4 * 4.0 / 3) * 0.01
    with pytest.warns(RuntimeWarning, match="under-resolved"):
        out = rc.fem.steady_sweep(surf, mat, [0.010 * p_full, 0.012 * p_full], 0.0,
                                  first=0, mesh="auto", columns_per_wave=40,
                                  patch_columns=6)
    assert [r.mesh[0] for r in out] == [80, 80] and all(r.stats.refined for r in out)
    assert "neighbour's refined mesh" in out[1].stats.tried[0]
    assert "from the neighbour" in " ".join(out[1].stats.tried)


#: The law cell of examples/captif_road.toml exactly (its run's ``hs0``: both stations'
#: high-slope waves, translated to zero phase).
CAPTIF_LAW_CELL = rc.roughness.SineSeries([0.25, 0.5],
                                          [0.12730956250957495, 0.12080265476330462],
                                          [0.0, 3.673565245973281])


@pytest.mark.slow
def test_a_refinement_whose_plain_repair_fails_is_repaired_not_pressed_again():
    # captif_road's 1 MPa / 10 mm/s law point: its narrowest patch on 128 x 16 is about a
    # column, so it is re-solved on 256 x 19, nested from 128 x 19. The plain Newton repair
    # of the prolonged state stalls at its first iteration there; the repair homotopy
    # carries it, and the fine mesh is not pressed from the start. The answer is the
    # fine mesh's own: the direct press on the same 256 x 19 cell (no nested iteration),
    # to the solver's tolerance (1e-6 of the load; measured 9e-7 relative in μ).
    mat = rc.materials.sbr()
    out = rc.fem.steady_sliding(CAPTIF_LAW_CELL, mat, 1.0, 10.0, mesh="auto",
                                columns_per_wave=64, fallback=False)
    assert out.stats.refined and out.mesh == (256, 19), out.stats.tried
    assert any(t.startswith("repair 256x19") and t.endswith("λ = 1")
               for t in out.stats.tried), out.stats.tried
    assert not any(t.startswith("press 256x19") for t in out.stats.tried), out.stats.tried
    m = auto_mesh(CAPTIF_LAW_CELL, FemOptions().height_ratio, 128)
    direct = rc.fem.steady_sliding(CAPTIF_LAW_CELL, mat, 1.0, 10.0, mesh=(m.nx, m.ny),
                                   grading=m.grading, coarse_elements=0, fallback=False)
    assert out.friction == pytest.approx(direct.friction, rel=1e-5)
    assert out.contact_fraction == pytest.approx(direct.contact_fraction, rel=1e-5)
    assert out.mean_separation == pytest.approx(direct.mean_separation, rel=1e-5)
