"""A run's map from measured line scans (``[surface.map.synthetic] kind = "from-profiles"``):
the isotropic map whose line scans have the scans' spectrum.

For an isotropic surface every straight line scan has the same spectrum, so a map built from
the CAPTIF scans' spectrum must give back, along x, the scans' rms height and rms slope —
up to the lattice: each ring's variance moves to the nearest lattice shell, which shifts the
slope by the shell spacing's share (measured 0.3 % here; bound 1 %).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from rubbercontact.config import load_config, parse_config
from rubbercontact.errors import InputError
from rubbercontact.io.profiles import read_profiles
from rubbercontact.meanfield import PSD
from rubbercontact.pipeline import run
from rubbercontact.pipeline.maprun import build_map
from rubbercontact.roughness.mapstats import rms_height, rms_slope_x

REAL = Path(__file__).resolve().parents[1] / "examples" / "data" / "real_surfaces"
SCAN = REAL / "captif_20211011_aylesbury_dec_station_0.dat"
PROFILES = {"files": [str(SCAN)], "format": "captif", "despike": True}
RUN = {"loads": {"pressures": [0.2]}, "velocities": [10.0]}


def _spec(**synthetic):
    table = {"kind": "from-profiles", "size": 16.0, "points": 512, "seed": 1,
             "profiles": PROFILES} | synthetic
    cfg = parse_config({"surface": {"map": {"synthetic": table}}} | RUN)
    return cfg.surface.map


def test_the_map_has_the_scans_height_and_slope_along_x():
    scans = read_profiles([SCAN], format="captif", despike=True)
    line = PSD.from_profiles(scans)
    hmap = build_map(_spec())          # 16 mm, 512²: the lattice holds every scan wavelength
    assert rms_height(hmap) == pytest.approx(line.rms_height, rel=0.01)
    assert rms_slope_x(hmap) == pytest.approx(line.rms_slope, rel=0.01)
    assert hmap.periodic and "isotropy" in hmap.source
    assert hmap.source["files"] == [str(SCAN)] and hmap.source["n_scans"] == len(scans.profiles)


def test_the_cutoffs_bound_the_maps_wavelengths():
    lo, hi = 0.15, 4.0
    hmap = build_map(_spec(profiles=PROFILES | {"lower_cutoff": lo, "upper_cutoff": hi}))
    psd = PSD.from_map(hmap.heights, hmap.lengths, nodes_per_decade=None)
    # every mode within the band, up to half a shell (2π/L) of the lattice
    half = np.pi / 16.0
    assert psd.wavenumbers.min() >= 2 * np.pi / hi - half
    assert psd.wavenumbers.max() <= 2 * np.pi / lo + half
    with pytest.raises(InputError, match="no wavelength of the scans"):
        build_map(_spec(profiles=PROFILES | {"lower_cutoff": 50.0, "upper_cutoff": 60.0}))


@pytest.mark.parametrize(("table", "message"), [
    ({"kind": "from-profiles"}, "needs profiles"),
    ({"kind": "self-affine", "profiles": PROFILES}, "needs hurst, rms_gradient"),
    ({"kind": "from-profiles", "profiles": PROFILES, "hurst": 0.8},
     "hurst do not apply to kind = 'from-profiles'"),
])
def test_each_kind_takes_its_own_keys(table, message):
    data = {"surface": {"map": {"synthetic": {"size": 1.0, "points": 64} | table}}} | RUN
    with pytest.raises(InputError, match=message):
        parse_config(data)


def test_a_run_reads_the_scans_relative_to_its_config(tmp_path):
    (tmp_path / "road.dat").write_bytes(SCAN.read_bytes())
    (tmp_path / "run.toml").write_text(
        'velocities = [10.0]\nmodels = ["vhs"]\n[loads]\npressures = [0.2]\n'
        '[surface.map.synthetic]\nkind = "from-profiles"\nsize = 4.0\npoints = 64\n'
        '[surface.map.synthetic.profiles]\nfiles = ["road.dat"]\nformat = "captif"\n'
        'lower_cutoff = 0.15\n')
    cfg = load_config(tmp_path / "run.toml")
    assert cfg.surface.map.synthetic.profiles.files == [(tmp_path / "road.dat").resolve()]
    ds = run(cfg, progress=False)
    mu = float(ds["friction"].sel(model="vhs").squeeze())
    assert 0 < mu < 2 and "road.dat" in ds.attrs["surface"]
    with pytest.raises(InputError, match="surface.map.synthetic.profiles.files: file"):
        parse_config({"surface": {"map": {"synthetic": {
            "kind": "from-profiles", "size": 1.0, "points": 64,
            "profiles": {"files": ["nowhere.dat"]}}}}} | RUN, base_dir=tmp_path)
