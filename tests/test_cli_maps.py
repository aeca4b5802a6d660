"""`rubbercontact roughness map` and `rubbercontact halfspace --map`: a map file's statistics
and the VHS on it, against closed forms (an oblique sine) and the library (solve_map)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from rubbercontact.cli import main
from rubbercontact.hybrid.maps import solve_map
from rubbercontact.io import write_map
from rubbercontact.materials import sbr
from rubbercontact.roughness import HeightMap, self_affine_map

AMP = 0.002
M, N = 2, 1          # oblique wave: 2 periods along x, 1 along y on a 1 mm square


def cli(args, capsys):
    code = main(args)
    out = capsys.readouterr()
    return code, out.out, out.err


def oblique_file(tmp_path, nx=32):
    x = np.arange(nx) / nx
    qx, qy = 2 * np.pi * M, 2 * np.pi * N
    z = AMP * np.sin(qx * x[None, :] + qy * x[:, None])
    return write_map(HeightMap(z, (1.0, 1.0), periodic=True), tmp_path / "sine.txt"), qx, qy


def test_map_statistics_of_an_oblique_sine(capsys, tmp_path):
    path, qx, qy = oblique_file(tmp_path)
    code, out, _ = cli(["roughness", "map", str(path), "--periodize", "none", "--json"],
                       capsys)
    assert code == 0
    rep = json.loads(out)
    q = np.hypot(qx, qy)
    assert rep["shape"] == [32, 32] and rep["lengths_mm"] == pytest.approx([1.0, 1.0])
    # one mode: rms height Δ/√2, gradient Δ|q|/√2, slope along x Δ q_x/√2 (spectral, exact)
    assert rep["rms_height_mm"] == pytest.approx(AMP / np.sqrt(2), rel=1e-12)
    assert rep["rms_gradient"] == pytest.approx(AMP * q / np.sqrt(2), rel=1e-12)
    assert rep["rms_slope_x"] == pytest.approx(AMP * qx / np.sqrt(2), rel=1e-12)
    assert rep["anisotropy"] == np.inf        # flat along the crests
    # |q| = 2π√5: log2(√5) = 1.16 → band 1 (λ 0.5 mm) holds all the slope
    slopes = [b["rms_slope_x"] for b in rep["bands"]]
    assert slopes[1] == pytest.approx(AMP * qx / np.sqrt(2), rel=1e-12)
    assert sum(s > 1e-12 * slopes[1] for s in slopes) == 1   # the others: round-off
    assert not any(b["high_slope"] for b in rep["bands"])   # slope 0.0089 < 1
    code, out, _ = cli(["roughness", "map", str(path), "--periodize", "none",
                        "--m2-threshold", "0.005"], capsys)
    assert code == 0 and "high-slope: rms slope along x > 0.005" in out
    assert out.count("yes") == 1


def test_halfspace_on_an_oblique_sine_in_full_contact_is_the_closed_form(capsys, tmp_path):
    path, qx, qy = oblique_file(tmp_path)
    q = np.hypot(qx, qy)
    er = complex(sbr().reduced_modulus(qx * 10.0, 0.5))
    sigma0 = 2.0 * AMP * q * abs(er) / 2          # twice the pressure amplitude: full contact
    code, out, _ = cli(["halfspace", "--map", str(path), "--periodize", "none",
                        "--velocity", "10", "--pressure", repr(float(sigma0)), "--law", "hard-wall",
                        "--json", "--plot", str(tmp_path / "contact.png")], capsys)
    assert code == 0
    res = json.loads(out)
    assert res["contact_fraction"] == 1.0
    # μ = |q| q_x Δ² Im E_r(q_x v)/(4σ0); one mode, solver tolerance 1e-8
    assert res["friction"] == pytest.approx(q * qx * AMP**2 * er.imag / (4 * sigma0), rel=1e-8)
    assert (tmp_path / "contact.png").stat().st_size > 10_000        # the contact map


def test_halfspace_on_a_synthetic_map_file_is_solve_map(capsys, tmp_path):
    hm = self_affine_map((64, 64), 1.0, 0.8, rms_gradient=0.5, seed=3)
    path = write_map(hm, tmp_path / "road.npy")
    code, out, _ = cli(["halfspace", "--map", str(path), "--map-dx", repr(float(hm.dx)),
                        "--periodize", "none", "--velocities", "1,10", "--pressure", "0.3",
                        "--json"], capsys)
    assert code == 0
    rows = json.loads(out)
    for row, v in zip(rows, (1.0, 10.0), strict=True):
        from rubbercontact.halfspace import LennardJonesRepulsion

        ref = solve_map(hm, sbr(), v, 0.3, LennardJonesRepulsion())
        # the .npy round trip is exact; the file's map differs by its mean (round-off)
        assert row["friction"] == pytest.approx(ref.friction, rel=1e-9)
        assert row["contact_fraction"] == pytest.approx(ref.contact_fraction, rel=1e-9)
        assert 0 < row["contact_fraction"] < 1


@pytest.mark.parametrize("args, message", [
    (["--map", "BAD", "--velocity", "10", "--pressure", "0.3"], "line 2 has 2 values"),
    (["--map", "BAD", "--surface", "section3", "--velocity", "10", "--pressure", "0.3"],
     "drop --surface"),
    (["--map", "BAD", "--periodize", "wrap", "--velocity", "10", "--pressure", "0.3"],
     "--periodize"),
])
def test_bad_map_input_is_one_line(capsys, tmp_path, args, message):
    bad = tmp_path / "bad.txt"
    bad.write_text("1 2 3\n4 5\n")
    args = [str(bad) if a == "BAD" else a for a in args]
    code, out, err = cli(["halfspace", *args], capsys)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and message in err
    code, _, err = cli(["roughness", "map", str(bad)], capsys)
    assert code == 2 and err.count("\n") == 1 and "truncated or corrupt" in err


def test_halfspace_fills_a_map_with_dropouts_as_roughness_map_does(capsys, tmp_path):
    """--map-nan fill reads the file as load_map(nan='fill') does (harmonic fill of the gap,
    then the plane and the mirror): the solve is solve_map on that map; without it, the
    dropouts are one error line."""
    from rubbercontact.halfspace import LennardJonesRepulsion
    from rubbercontact.io.mapload import load_map

    z = np.array(self_affine_map((32, 32), 1.0, 0.8, rms_gradient=0.5, seed=4).heights)
    z[10:13, 5:9] = np.nan
    path = tmp_path / "gaps.npy"
    np.save(path, z)
    args = ["halfspace", "--map", str(path), "--map-dx", repr(1 / 32), "--velocity", "10",
            "--pressure", "0.3", "--json"]
    code, out, err = cli(args, capsys)
    assert code == 2 and out == "" and err.count("\n") == 1 and "12 of 1024 points are NaN" in err
    code, out, _ = cli([*args, "--map-nan", "fill"], capsys)
    assert code == 0
    hmap = load_map(path, dx=1 / 32, nan="fill")[1]
    assert hmap.filled is not None and hmap.filled.sum() == 4 * 12   # mirrored 4 times
    ref = solve_map(hmap, sbr(), 10.0, 0.3, LennardJonesRepulsion())
    assert json.loads(out)["friction"] == pytest.approx(ref.friction, rel=1e-12)
    code, _, err = cli([*args, "--map-nan", "drop"], capsys)
    assert code == 2 and err.count("\n") == 1 and "--map-nan" in err


@pytest.mark.parametrize("heights", ["constant", "plane"])
def test_a_flat_map_file_is_one_line_not_a_failed_solve(capsys, tmp_path, heights):
    """A constant or tilted map has nothing to solve once its plane is removed: the detrended
    round-off is the flat map, refused in one line (it was a Newton failure on 1e-17 mm)."""
    x = np.arange(16) * 0.01
    z = np.full((16, 16), 1.234) if heights == "constant" else 0.3 * x[None, :] + 0.1 * x[:, None]
    np.save(tmp_path / "flat.npy", z)
    code, out, err = cli(["halfspace", "--map", str(tmp_path / "flat.npy"), "--map-dx", "0.01",
                          "--velocity", "1", "--pressure", "0.1"], capsys)
    assert code == 2 and out == "" and err.count("\n") == 1 and "flat surface" in err
    code, out, _ = cli(["roughness", "map", str(tmp_path / "flat.npy"), "--dx", "0.01",
                        "--json"], capsys)
    assert code == 0 and json.loads(out)["rms_height_mm"] == 0.0


def test_run_on_a_synthetic_map(capsys, tmp_path):
    import xarray as xr

    cfg = tmp_path / "run.toml"
    cfg.write_text('velocities = [10.0]\n[loads]\npressures = [0.2]\n'
                   '[surface.map.synthetic]\nsize = 1.0\npoints = 64\nhurst = 0.8\n'
                   'rms_gradient = 0.5\nseed = 2\n[output]\ndirectory = "out"\n')
    code, out, _ = cli(["run", str(cfg), "--check"], capsys)
    assert code == 0 and "models vhs, meanfield" in out and "64 x 64 points" in out
    code, out, _ = cli(["run", str(cfg)], capsys)
    assert code == 0 and "results:" in out
    with xr.open_dataset(tmp_path / "out" / "results.nc") as ds:
        mu = float(ds["friction"].sel(model="vhs", velocity=10.0, pressure=0.2))
    hm = self_affine_map((64, 64), 1.0, 0.8, rms_gradient=0.5, seed=2)
    from rubbercontact.halfspace import LennardJonesRepulsion

    ref = solve_map(hm, sbr(), 10.0, 0.2, LennardJonesRepulsion())
    assert mu == pytest.approx(ref.friction, rel=1e-12)
    assert f"{ref.friction:9.5f}" in out
    code, _, err = cli(["run", str(cfg)], capsys)        # results exist: one line
    assert code == 2 and err.count("\n") == 1 and "--overwrite" in err
    nc = str(tmp_path / "out" / "results.nc")
    code, again, _ = cli(["summary", nc], capsys)
    assert code == 0 and f"{ref.friction:9.5f}" in again
    code, plotted, _ = cli(["plot", nc, "-o", str(tmp_path / "fig")], capsys)
    assert code == 0 and plotted.count("figure:") == 4       # one speed: no μ(v) figure
