"""The validation report's words on the phase-averaged eq. 28 (studies/_section3_report.py,
studies/_section3_phase.py) on hand-made realizations; the numbers themselves are the
package's (rubbercontact.compare, tests/test_validate_phase.py), on the same ``phase_data``
fixture's realizations (conftest.py at the repository root)."""

import rubbercontact.compare as compare
from studies import _section3_report as s3report
from studies._templates import render


def test_extended_rows_name_the_range_and_leave_the_pointwise_hybrid_out_in_the_second(phase_data):
    merged = compare.merge_phase_data(phase_data(), phase_data([0.05, 1.2], r=5))
    rows, text = s3report.extended_rows({10.0: merged}, 1.39)
    assert len(rows) == 3 and "all models" in rows[0] and "without the pointwise" in rows[1]
    assert rows[1].split("|")[3].strip() == "-"          # no pointwise-hybrid entry
    assert "below the top load (1.2 MPa)" in rows[2]
    assert "0.05 (5), 0.15 (10), 0.35 (10), 0.8 (10), 1.2 (5)" in text
    assert "exceeds" not in text        # μσ0 <= 1.14 MPa < E∞/3 = 1.39 MPa everywhere


def test_a_fem_friction_stress_above_the_relaxed_shear_modulus_is_named_and_left_out(phase_data):
    merged = compare.merge_phase_data(phase_data(), phase_data([0.05, 1.2], r=5))
    fem_a, fem_mu = (x.copy() for x in merged["fem"])
    fem_mu[:, -1] = 1.5                                  # μσ0 = 1.8 MPa at 1.2 MPa
    merged["fem"] = (fem_a, fem_mu)
    _, text = s3report.extended_rows({50.0: merged}, 1.39)
    # the phase average is mean_N(VHS) + mean_R(FEM − VHS), not 1.5 itself
    assert "At 50 mm/s and 1.2 MPa the FEM's phase-averaged friction stress μσ0 = " in text
    assert "MPa exceeds E∞/3 = 1.39 MPa; from 0.8 MPa its μ goes from" in text
    assert render("validation_section3", "extended_fem_caveat") in text
    assert "and 0.8 MPa the FEM's" not in text          # below E∞/3: not named


def test_phase_curves_figure_is_drawn(tmp_path, phase_data):
    merged = compare.merge_phase_data(phase_data(), phase_data([0.05, 1.2], r=5))
    path = s3report.plot_phase_curves({10.0: merged, 50.0: merged}, tmp_path / "f.png")
    assert path.stat().st_size > 1000


def test_beta_text_names_the_fitted_beta_of_an_offset_fem(phase_data):
    # FEM = VHS − offset: the fitted β is exactly 1 (tests/test_validate_phase.py)
    assert "β = 1.00 (0.000 → 0.000)" in s3report.beta_text({10.0: phase_data()})


def test_the_law_cells_quasi_static_points_are_not_counted_as_law_points():
    # The law cell's quasi-static check (pipeline/lawcheck.py) solves the law cell at
    # 1e-3 mm/s; a point it cannot solve is a failed check, said by the run's law line
    # ("6 of 9 law pressures pass; 4, 6, 8 MPa did not converge"), not a law point that
    # "fell back to the transient test".
    import xarray as xr

    from studies._section3_prose import steady_sentence
    from studies._validation_report import law_lines

    def solve(label, kind, solver="steady"):
        return {"label": label, "kind": kind, "solver": solver, "status": "ok",
                "wall_time": 1.0, "newton_iterations": 10.0}

    solves = [solve("fem v=10 r=0 p=0.35", "full"), solve("law p=1", "law"),
              solve("law cell quasi-static p=1 MPa", "check"),
              solve("law cell quasi-static p=8 MPa", "check", "failed")]
    text = steady_sentence(xr.Dataset(), solves)
    assert "of the 1 law points 1;" in text and "quasi-static" not in text
    assert "none fell back" in text
    ds = xr.Dataset(attrs={"law_quasi_static": "quasi-static check: 1 of 2 law pressures "
                                               "pass; 8 MPa did not converge"})
    assert law_lines(ds) == ["- law cell: quasi-static check: 1 of 2 law pressures pass; "
                             "8 MPa did not converge"]
