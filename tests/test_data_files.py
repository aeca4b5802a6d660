"""The examples run from a fresh clone: every file a config names is inside the repository,
exists and parses, and the bundled real profiles are the upstream bytes (README checksums)."""

import hashlib
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

from rubbercontact.config import load_config
from rubbercontact.hybrid.law import as_law
from rubbercontact.inputs import build_material
from rubbercontact.io.profiles import read_profiles
from rubbercontact.io.results import read_results

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
CONFIGS = sorted(EXAMPLES.glob("*.toml"))
REAL = EXAMPLES / "data" / "real_surfaces"
#: config keys whose values are paths (inputs: file/files; outputs: directory/cache)
PATH_KEYS = ("file", "files", "directory", "cache")


def _path_values(table: dict, where: str = "") -> list[tuple[str, str]]:
    """``(key path, value)`` of every path-valued key in a parsed TOML table."""
    out = []
    for key, value in table.items():
        name = f"{where}.{key}" if where else key
        if isinstance(value, dict):
            out += _path_values(value, name)
        elif key in PATH_KEYS:
            out += [(name, v) for v in (value if isinstance(value, list) else [value])]
    return out


@pytest.mark.parametrize("path", CONFIGS, ids=[p.name for p in CONFIGS])
def test_example_config_names_only_paths_inside_the_repository(path):
    for key, value in _path_values(tomllib.loads(path.read_text(encoding="utf-8"))):
        resolved = (path.parent / value).resolve()
        assert resolved.is_relative_to(ROOT), f"{path.name}: {key} = {value!r} leaves the repo"


@pytest.mark.parametrize("path", CONFIGS, ids=[p.name for p in CONFIGS])
def test_example_input_files_exist_and_parse(path):
    cfg = load_config(path)        # raises InputError on a missing file
    prof = cfg.surface.profiles
    if prof is not None:
        profiles = read_profiles(prof.files, format=prof.format, unit=prof.unit, dx=prof.dx,
                                 window=prof.window or 16.0, despike=prof.despike)
        assert profiles.profiles, f"{path.name}: no NaN-free window in {prof.files}"
        for z in profiles.profiles:
            assert np.all(np.isfinite(z)) and z.size * profiles.dx >= (prof.window or 16.0) * 0.99
    assert build_material(cfg.material).equilibrium_modulus > 0     # reads material.file if given
    if cfg.law.file is not None:
        as_law(read_results(cfg.law.file), f"law.file {cfg.law.file}")   # checks the law


def test_no_example_reads_outside_the_repository():
    # the project's shared directory (../shared/...) is not part of a clone
    for path in sorted(EXAMPLES.rglob("*")):
        if path.suffix in {".toml", ".py", ".md"} and path.is_file():
            text = path.read_text(encoding="utf-8")
            assert not re.search(r"\.\./+shared|/work/shared", text), path


def test_bundled_real_profiles_are_the_upstream_files():
    """The README's provenance table gives each file's SHA-256; the licence is kept."""
    table = re.findall(r"^\| (\S+\.dat) \| .* \| ([0-9a-f]{64}) \|$",
                       (REAL / "README.md").read_text(encoding="utf-8"), flags=re.M)
    assert sorted(name for name, _ in table) == sorted(p.name for p in REAL.glob("*.dat"))
    for name, sha in table:
        assert hashlib.sha256((REAL / name).read_bytes()).hexdigest() == sha, name
    assert "MIT License" in (REAL / "LICENSE").read_text(encoding="utf-8")
