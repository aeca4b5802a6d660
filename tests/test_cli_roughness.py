"""``rubbercontact roughness fit`` and the default roughness job."""

import json

import numpy as np
import pytest

from rubbercontact.cli import main
from rubbercontact.cli.roughness import analyse_default
from rubbercontact.roughness import TABLE2, asphalt_ac8, synthetic_line_scans


@pytest.fixture(scope="module")
def scan_file(tmp_path_factory):
    """Six 16 mm scans of Table 2's surface at 5 µm, one column per scan, with a header."""
    z = synthetic_line_scans(asphalt_ac8(), n_scans=6, seed=5)
    f = tmp_path_factory.mktemp("cli") / "scans.txt"
    np.savetxt(f, z.T, fmt="%.7f", header="six line scans, heights in mm, dx 0.005 mm")
    return f


def test_fit_prints_table_and_writes_plot(scan_file, tmp_path, capsys):
    png = tmp_path / "fig" / "hdc.png"
    code = main(["roughness", "fit", str(scan_file), "--dx", "0.005", "--waves", "8",
                 "--upper-cutoff", "8", "--plot", str(png)])
    out = capsys.readouterr()
    assert code == 0, out.err
    assert "wavelength [mm]" in out.out and "amplitude [mm]" in out.out
    rows = [ln.split() for ln in out.out.splitlines() if ln.strip()[:1].isdigit()
            and ln.split()[-1] in ("high-slope", "low-slope")]
    assert len(rows) == 8
    wavelengths = [float(r[1]) for r in rows]
    np.testing.assert_allclose(wavelengths, TABLE2[:, 0])
    assert [r[-1] for r in rows] == ["high-slope"] + ["low-slope"] * 7
    amplitudes = np.array([float(r[2]) for r in rows])
    np.testing.assert_allclose(amplitudes[:6] / TABLE2[:6, 1], 1.0, atol=0.1)
    assert "high-slope scale (m2 > 1): 0.0625 mm" in out.out
    assert png.stat().st_size > 10_000


def test_fit_json_output(scan_file, capsys):
    code = main(["roughness", "fit", str(scan_file), "--dx", "0.005", "--lower-cutoff",
                 "0.0625", "--upper-cutoff", "8", "--method", "paper", "--json"])
    out = capsys.readouterr().out
    assert code == 0
    record = json.loads(out)
    assert record["method"] == "paper" and record["n_scans"] == 6
    assert [w["wavelength"] for w in record["waves"]] == TABLE2[:, 0].tolist()
    assert len(record["sources"][0]["sha256"]) == 64
    assert record["log10_rms_error"] < 0.05


def test_fit_warns_about_unresolved_wavelengths(scan_file, capsys):
    # resample to the paper's 0.05 mm: its own 0.0625 mm wave is not resolved
    z = np.loadtxt(scan_file)[::10]
    coarse = scan_file.with_name("coarse.txt")
    np.savetxt(coarse, z)
    code = main(["roughness", "fit", str(coarse), "--dx", "0.05", "--waves", "8",
                 "--upper-cutoff", "8"])
    err = capsys.readouterr().err
    assert code == 0
    assert "warning: dx = 0.05 mm cannot resolve the wavelength(s) 0.0625 mm" in err


@pytest.mark.parametrize("args, message", [
    (["--dx", "-0.005"], "dx: must be > 0"),
    (["--dx", "0.005", "--waves", "8", "--upper-cutoff", "8", "--lower-cutoff", "0.1"],
     "give two of the three"),
    (["--dx", "0.005", "--unit", "furlong"], "unit: unknown length unit"),
])
def test_fit_bad_options_exit_2_with_clear_error(scan_file, capsys, args, message):
    code = main(["roughness", "fit", str(scan_file), *args])
    assert code == 2
    assert message in capsys.readouterr().err


def test_fit_missing_file(tmp_path, capsys):
    assert main(["roughness", "fit", str(tmp_path / "absent.txt"), "--dx", "0.1"]) == 2
    assert "absent.txt: no such file" in capsys.readouterr().err


def test_help_lists_roughness(capsys):
    assert main(["--help"]) == 0
    out = capsys.readouterr().out
    assert "roughness" in out
    assert main(["roughness", "--help"]) == 0
    assert "fit" in capsys.readouterr().out


def test_analyse_default_writes_figure_and_recovers_table2(tmp_path):
    lines = []
    series = analyse_default(tmp_path, echo=lines.append)
    np.testing.assert_allclose(series.wavelengths, TABLE2[:, 0])
    np.testing.assert_allclose(series.amplitudes / TABLE2[:, 1], 1.0, atol=0.05)
    assert (tmp_path / "roughness_fit.png").stat().st_size > 10_000
    record = json.loads((tmp_path / "roughness_fit.json").read_text())
    assert record["dataset"]["n_scans"] == 30 and record["dataset"]["dx"] == 0.005
    text = "\n".join(lines)
    assert "high-slope scale (m2 > 1): 0.0625 mm" in text
