"""`rubbercontact halfspace` command: options, TOML, JSON, plots, sweeps and user errors."""

from __future__ import annotations

import json

import numpy as np
import pytest

import rubbercontact as rc
from rubbercontact.cli import main


def run(args, capsys):
    code = main(["halfspace", *args])
    out = capsys.readouterr()
    return code, out.out, out.err


def test_json_matches_python_api(capsys, tmp_path):
    code, out, _ = run(["--surface", "section3", "--velocity", "10", "--pressure", "0.3",
                        "--n", "512", "--law", "hardwall", "--json",
                        "--plot", str(tmp_path / "p.png")], capsys)
    assert code == 0
    data = json.loads(out)
    res = rc.halfspace.solve_sliding(rc.roughness.section3(), None, rc.materials.sbr(), 10.0,
                                     0.3, n=512)
    assert data["friction"] == pytest.approx(res.friction, rel=1e-12)
    assert data["contact_fraction"] == pytest.approx(res.contact_fraction)
    assert (tmp_path / "p.png").stat().st_size > 0


def test_toml_and_sweep(capsys, tmp_path):
    cfg = tmp_path / "case.toml"
    cfg.write_text('material = "elastic"\nmodulus = 10.0\npressure = 0.05\nn = 256\n'
                   '[surface]\nwavelengths = [0.125]\namplitudes = [0.002]\n')
    code, out, _ = run(["--config", str(cfg), "--velocities", "1,10,100", "--json",
                        "--plot", str(tmp_path / "mu.png")], capsys)
    assert code == 0
    rows = json.loads(out)
    assert [r["velocity"] for r in rows] == [1.0, 10.0, 100.0]
    # elastic material: no hysteretic friction at any speed
    assert np.allclose([r["friction"] for r in rows], 0.0, atol=1e-9)
    assert (tmp_path / "mu.png").exists()


def test_text_output(capsys):
    code, out, _ = run(["--wavelengths", "0.125,0.25", "--amplitudes", "0.002,0.003",
                        "--velocity", "1", "--pressure", "0.5", "--n", "256"], capsys)
    assert code == 0 and "mu" in out


@pytest.mark.parametrize("args, field", [
    (["--velocity", "1", "--pressure", "-1"], "mean_pressure"),
    (["--surface", "nope", "--velocity", "1", "--pressure", "1"], "surface"),
    (["--velocity", "1"], "pressure"),
    (["--pressure", "1"], "velocity"),
    (["--material", "steel", "--velocity", "1", "--pressure", "1"], "material"),
    (["--law", "magic", "--velocity", "1", "--pressure", "1"], "law"),
    (["--velocities", "1,x", "--pressure", "1"], "velocities"),
    (["--wavelengths", "0.1,0.25", "--amplitudes", "0.01,0.01", "--velocity", "1",
      "--pressure", "1"], "wavelengths"),
])
def test_user_errors(args, field, capsys):
    code, _, err = run(args, capsys)
    assert code == 2
    assert err.startswith("error:") and field in err
