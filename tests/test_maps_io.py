"""Map readers and writers: round trips of every written format, one clear error line for
corrupt, truncated or unstated files."""

import numpy as np
import pytest

from rubbercontact.errors import InputError
from rubbercontact.io.maps import read_map, write_map
from rubbercontact.roughness.maps import HeightMap


@pytest.fixture
def hmap():
    rng = np.random.default_rng(0)
    z = rng.standard_normal((12, 20)) * 0.01
    z[3, 4] = np.nan
    return HeightMap.from_array(z, 0.05, 0.04, nan="fill")


@pytest.mark.parametrize("name", ["m.txt", "m.csv"])
def test_text_round_trip_is_exact(tmp_path, hmap, name):
    # %.17g: every double comes back bit for bit; the filled point is written as NaN
    back = read_map(write_map(hmap, tmp_path / name), nan="fill")
    assert np.array_equal(back.heights, hmap.heights)
    assert back.lengths == hmap.lengths and np.array_equal(back.filled, hmap.filled)
    assert back.source["format"] == "text" and len(back.source["sha256"]) == 64


def test_npy_round_trip_needs_the_pixel_size(tmp_path, hmap):
    path = write_map(hmap, tmp_path / "m.npy")
    with pytest.raises(InputError, match="dx"):
        read_map(path)
    back = read_map(path, dx=0.05, dy=0.04, nan="fill")
    assert np.array_equal(back.heights, hmap.heights) and back.lengths == hmap.lengths


def test_x3p_round_trip_through_surface_topography(tmp_path, hmap):
    pytest.importorskip("SurfaceTopography")
    full = HeightMap(hmap.heights, hmap.lengths)     # x3p stores no mask here: all measured
    back = read_map(write_map(full, tmp_path / "m.x3p"))
    # x3p stores heights in metres as doubles: mm → m → mm is exact to round-off
    np.testing.assert_allclose(back.heights, full.heights, rtol=0, atol=1e-15)
    assert back.lengths == pytest.approx(full.lengths, rel=1e-12)
    assert back.source["format"] == "topography"


def test_units_from_header_and_argument(tmp_path):
    (tmp_path / "um.txt").write_text("# dx = 10\n# unit = um\n1 2 3 4\n5 6 7 8\n1 1 1 1\n"
                                     "2 2 2 2\n")
    hm = read_map(tmp_path / "um.txt")
    assert hm.dx == pytest.approx(0.01) and hm.heights[1, 0] == pytest.approx(0.005)
    np.save(tmp_path / "a.npy", np.ones((4, 5)))
    assert read_map(tmp_path / "a.npy", dx=2.0, unit="um").dx == pytest.approx(0.002)


def _one_line(exc) -> bool:
    return "\n" not in str(exc.value)


def test_truncated_text_grid_is_one_clear_error(tmp_path, hmap):
    path = write_map(hmap, tmp_path / "m.txt")
    text = path.read_text()
    path.write_text(text[: len(text) - 40])         # cut inside the last row
    with pytest.raises(InputError, match="line 15 has") as exc:
        read_map(path, nan="fill")
    assert _one_line(exc)
    (tmp_path / "bad.txt").write_text("# dx = 1\n1 2 x 4\n")
    with pytest.raises(InputError, match="not a row of numbers") as exc:
        read_map(tmp_path / "bad.txt")
    assert _one_line(exc)


def test_corrupt_npy_and_x3p_are_one_clear_error(tmp_path, hmap):
    path = write_map(hmap, tmp_path / "m.npy")
    path.write_bytes(path.read_bytes()[:100])
    with pytest.raises(InputError, match="truncated or corrupt") as exc:
        read_map(path, dx=0.05)
    assert _one_line(exc)
    pytest.importorskip("SurfaceTopography")
    good = write_map(HeightMap(hmap.heights, hmap.lengths), tmp_path / "m.x3p")
    bad = tmp_path / "bad.x3p"
    bad.write_bytes(good.read_bytes()[:300])
    with pytest.raises(InputError, match="SurfaceTopography cannot read") as exc:
        read_map(bad)
    assert _one_line(exc)


def test_a_complex_npy_is_refused_not_cast(tmp_path, hmap):
    """astype(float) would keep the real part with a warning; a height map is real."""
    np.save(tmp_path / "c.npy", np.asarray(hmap.heights) * (1 + 1j))
    with pytest.raises(InputError, match="real numeric array") as exc:
        read_map(tmp_path / "c.npy", dx=0.05)
    assert _one_line(exc)


def test_unknown_format_and_existing_file(tmp_path, hmap):
    with pytest.raises(InputError, match="cannot write"):
        write_map(hmap, tmp_path / "m.xyz")
    path = write_map(hmap, tmp_path / "m.txt")
    with pytest.raises(FileExistsError):
        write_map(hmap, path)
    (tmp_path / "m.xyz").write_text("1")
    with pytest.raises(InputError, match="unknown map format"):
        read_map(tmp_path / "m.xyz")
