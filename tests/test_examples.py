"""The bundled example configs are valid (their data files exist, keys and ranges are right)."""

from pathlib import Path

import pytest

from rubbercontact.config import load_config

EXAMPLES = sorted((Path(__file__).parents[1] / "examples").glob("*.toml"))


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.name for p in EXAMPLES])
def test_example_config_loads(path):
    cfg = load_config(path)
    assert cfg.velocities
