"""``rubbercontact fem`` command: JSON output, TOML config, plot, bad input."""

import json

import pytest

from rubbercontact.cli import main


def test_fem_cli_json_and_plot(tmp_path, capsys):
    cfg = tmp_path / "t.toml"
    cfg.write_text('surface = {wavelengths = [0.0625], amplitudes = [0.004]}\n'
                   'material = "sbr"\nmean_pressure = 0.5\nvelocity = 10.0\n'
                   'mesh = [16, 12]\ncontact_points = 2\n')
    png = tmp_path / "f.png"
    nc = tmp_path / "r.nc"
    code = main(["fem", "--config", str(cfg), "--json", "--plot", str(png),
                 "--netcdf", str(nc), "--grading", "2"])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert out["mesh"] == [16, 12]
    assert out["mean_pressure_MPa"] == 0.5
    assert out["friction"] > 0             # v > 0 on a viscoelastic solid
    assert 0 < out["contact_fraction"] <= 1
    # the friction drags the face behind the driven top: the cell shears
    assert out["stats"]["bulk_shear"] > 0 and out["stats"]["solver"] == "steady"
    assert png.stat().st_size > 10_000
    import xarray as xr

    with xr.open_dataset(nc) as ds:
        assert ds["friction"].attrs["units"] == "1"


# Two periods on a 16 x 12 mesh keep the test fast; steadiness is not the point here.
@pytest.mark.filterwarnings("ignore:FEM sliding test:RuntimeWarning")
def test_fem_cli_text_summary_reports_the_cell_shear(tmp_path, capsys):
    code = main(["fem", "--wavelength", "0.0625", "--amplitude", "0.004", "--pressure", "0.5",
                 "--velocity", "10", "--mesh", "16x12", "--solver", "transient",
                 "--periods", "2"])
    assert code == 0
    text = capsys.readouterr().out
    assert "friction coefficient μ" in text and "solver transient" in text
    line = next(x for x in text.splitlines() if "cell shear (face lag/H)" in x)
    assert float(line.split()[4]) > 0 and "over the last period" in line
    code = main(["fem", "--wavelength", "0.0625", "--amplitude", "0.004", "--pressure", "0.5",
                 "--velocity", "10", "--mesh", "16x12"])
    assert code == 0
    text = capsys.readouterr().out
    assert "solver steady" in text and "GMRES iterations" in text


def test_fem_cli_bad_input_exit_code(capsys):
    assert main(["fem", "--pressure", "-1", "--mesh", "16x12", "--quiet"]) == 2
    assert "mean_pressure" in capsys.readouterr().err
    assert main(["fem", "--mesh", "abc"]) == 2
    assert main(["fem", "--mesh", "16x12", "--contact-points", "0", "--quiet"]) == 2
    assert "contact_points" in capsys.readouterr().err
    assert main(["fem", "--wavelength", "0.0625", "--mesh", "16x12"]) == 2
    # a transient-only option with the (default) steady solver: one clear line, exit 2
    assert main(["fem", "--mesh", "16x12", "--periods", "2", "--quiet"]) == 2
    assert "solver='transient'" in capsys.readouterr().err


def test_fem_cli_automatic_mesh(capsys):
    # 64 columns per shortest wave (rubbercontact.fem.resolution), and the patch check
    code = main(["fem", "--wavelength", "0.0625", "--amplitude", "0.004", "--pressure", "0.5",
                 "--velocity", "10", "--mesh", "auto", "--json"])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert out["mesh"][0] == 64
    assert out["stats"]["patch_columns"] is None or out["stats"]["patch_columns"] >= 4
