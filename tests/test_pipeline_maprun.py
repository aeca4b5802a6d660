"""A run on a height map ([surface.map]): the config's validation and the models' answers
against the library called directly (solve_map; meanfield.solve on PSD.from_map)."""

from __future__ import annotations

import json

import pytest

from rubbercontact import meanfield
from rubbercontact.config import load_config, parse_config
from rubbercontact.errors import InputError
from rubbercontact.halfspace import LennardJonesRepulsion
from rubbercontact.hybrid.maps import (
    MapHybridOptions,
    linear_law_map,
    solve_map,
    solve_map_hybrid,
)
from rubbercontact.io import write_map
from rubbercontact.materials import sbr
from rubbercontact.meanfield import PSD
from rubbercontact.pipeline import run
from rubbercontact.roughness import self_affine_map, split_map

SYN = {"size": 1.0, "points": 64, "hurst": 0.8, "rms_gradient": 0.5, "seed": 4}
SPEEDS, LOADS = [1.0, 100.0], [0.1, 0.4]


def config(surface_map: dict, **extra) -> dict:
    return {"surface": {"map": surface_map}, "loads": {"pressures": LOADS},
            "velocities": SPEEDS, **extra}


@pytest.fixture(scope="module")
def synthetic_run():
    return run(config({"synthetic": SYN}))


def test_vhs_on_a_synthetic_map_is_solve_map(synthetic_run):
    ds = synthetic_run
    assert list(ds["model"].values) == ["vhs", "meanfield"]
    hm = self_affine_map((64, 64), 1.0, 0.8, rms_gradient=0.5, seed=4)
    for v in SPEEDS:
        for p in LOADS:
            ref = solve_map(hm, sbr(), v, p, LennardJonesRepulsion())
            got = ds.sel(model="vhs", velocity=v, pressure=p)
            # the same map, the same solver and tolerance: equal to round-off
            assert float(got["friction"]) == pytest.approx(ref.friction, rel=1e-12)
            assert float(got["contact_fraction"]) == pytest.approx(ref.contact_fraction,
                                                                   rel=1e-12)
    assert (ds["status"].values == "ok").all()
    info = json.loads(ds.attrs["surface"])
    assert info["shape"] == [64, 64] and info["map"]["seed"] == 4
    # the synthetic map is scaled to its rms gradient exactly (spectral, periodic)
    assert info["rms_gradient"] == pytest.approx(0.5, rel=1e-12)


def test_meanfield_on_a_map_is_meanfield_on_its_periodogram(synthetic_run):
    hm = self_affine_map((64, 64), 1.0, 0.8, rms_gradient=0.5, seed=4)
    psd = PSD.from_map(hm.heights, hm.lengths)
    for v in SPEEDS:
        for p in LOADS:
            ref = meanfield.solve(psd, sbr(), v, p)
            got = synthetic_run.sel(model="meanfield", velocity=v, pressure=p)
            assert float(got["friction"]) == pytest.approx(ref.friction, rel=1e-12)
            assert float(got["contact_fraction"]) == pytest.approx(ref.contact_fraction,
                                                                   rel=1e-12)


def test_the_recorded_config_reparses_to_the_same_run(synthetic_run):
    cfg = parse_config(json.loads(synthetic_run.attrs["config"]))
    assert cfg.surface.map.synthetic.seed == 4 and list(cfg.models) == ["vhs", "meanfield"]


def test_physics_of_the_map_run(synthetic_run):
    ds = synthetic_run.sel(model="vhs")
    # more load, more contact; friction of SBR at 1 and 100 mm/s is positive
    assert (ds["contact_fraction"].diff("pressure") > 0).all()
    assert (ds["friction"] > 0).all()


def test_a_map_file_run_records_its_provenance(tmp_path):
    hm = self_affine_map((32, 32), 0.5, 0.7, rms_gradient=0.3, seed=1)
    write_map(hm, tmp_path / "road.txt")
    path = tmp_path / "run.toml"
    path.write_text('models = ["vhs"]\nvelocities = [1.0]\n[loads]\npressures = [0.1]\n'
                    '[surface.map]\nfile = "road.txt"\nperiodize = "none"\n')

    ds = run(load_config(path))
    info = json.loads(ds.attrs["surface"])
    assert info["map"]["path"] == str(tmp_path / "road.txt") and len(info["map"]["sha256"]) == 64
    ref = solve_map(hm, sbr(), 1.0, 0.1, LennardJonesRepulsion())
    # the text file holds 17 digits: the map differs by its mean (round-off)
    assert float(ds["friction"].sel(model="vhs", velocity=1.0, pressure=0.1)) == \
        pytest.approx(ref.friction, rel=1e-9)


def test_hybrids_on_a_map_are_solve_map_hybrid_with_the_linear_law():
    ds = run({**config({"synthetic": SYN}, models=["hybrid", "hybrid-windowed"]),
              "surface": {"map": {"synthetic": SYN}, "m2_threshold": 0.15},
              "velocities": [10.0], "loads": {"pressures": [0.2]}})
    hm = self_affine_map((64, 64), 1.0, 0.8, rms_gradient=0.5, seed=4)
    split = split_map(hm, 0.15)
    assert split.cell is not None              # bands of slope 0.16, 0.18 > 0.15
    law = linear_law_map(split.cell, sbr(), 10.0)
    for model, window in (("hybrid", False), ("hybrid-windowed", True)):
        ref = solve_map_hybrid(split, law, sbr(), 10.0, 0.2,
                               MapHybridOptions(law="lennard-jones", window=window))
        got = ds.sel(model=model, velocity=10.0, pressure=0.2)
        assert float(got["friction"]) == pytest.approx(ref.friction, rel=1e-12)
        assert float(got["contact_fraction"]) == pytest.approx(ref.contact_fraction, rel=1e-12)
    assert "linear" in ds.attrs["high_slope_law"]


@pytest.mark.parametrize("surface_map, extra, message", [
    ({"synthetic": SYN}, {"models": ["vhs", "fem"]}, "not models fem"),
    ({"synthetic": SYN}, {"law": {"pressures": [0.1, 1.0]}}, "linear law of its cell"),
    ({"synthetic": SYN}, {"realizations": 3}, "realizations > 1"),
    ({"synthetic": SYN}, {"halfspace": {"n": 1024}}, "solved on its own grid"),
    ({"synthetic": {**SYN, "hurst": 1.2}}, {}, "surface.map.synthetic.hurst"),
    ({"synthetic": SYN, "file": "x.txt"}, {}, "exactly one of 'file' and 'synthetic'"),
    ({"synthetic": {**SYN, "colour": 1}}, {}, "unknown key 'surface.map.synthetic.colour'"),
    ({"file": "missing.txt"}, {}, "surface.map.file: not found"),
    ({"file": "road.npy"}, {}, "a .npy map carries no pixel size: give dx"),
])
def test_bad_map_config_is_one_line(tmp_path, surface_map, extra, message):
    with pytest.raises(InputError) as err:
        parse_config(config(surface_map, **extra), base_dir=tmp_path)
    assert message in str(err.value) and "\n" not in str(err.value)


def test_a_map_and_a_sine_table_are_refused_together():
    with pytest.raises(InputError, match="exactly one of 'preset'"):
        parse_config({**config({"synthetic": SYN}),
                      "surface": {"map": {"synthetic": SYN}, "preset": "section3"}})


def test_without_a_high_slope_band_the_hybrid_is_the_vhs():
    # every band's slope along x is below 0.2 < m2_threshold = 1: z_ls = z, no law
    ds = run({**config({"synthetic": SYN}, models=["vhs", "hybrid-windowed"]),
              "velocities": [10.0], "loads": {"pressures": [0.2]}})
    assert ds["friction"].sel(model="hybrid-windowed").item() == \
        ds["friction"].sel(model="vhs").item()
