"""The code a new user copies runs: the README's quick starts and the tutorial's blocks.

Each block is executed exactly as written (the README's Python snippet, the tutorial's
``python`` blocks in order in one namespace, the README's command lines in ``bash`` from
the repository root), with the result cache in the test's folder. Their settings are the
small ones the pages show, so this takes seconds.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

# the runs warn about what they screened or extrapolated on these small settings
pytestmark = pytest.mark.filterwarnings("ignore::UserWarning", "ignore::RuntimeWarning")

FENCE = re.compile(r"^```(\w+)\n(.*?)^```", re.S | re.M)


def blocks(path: Path, language: str) -> list[str]:
    return [code for lang, code in FENCE.findall(path.read_text(encoding="utf-8"))
            if lang == language]


@pytest.fixture
def in_tmp(monkeypatch, tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    monkeypatch.setenv("RUBBERCONTACT_CACHE", str(tmp_path / "cache"))
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def run_blocks(codes: list[str], source: str) -> dict:
    namespace: dict = {"__name__": "__main__"}
    for i, code in enumerate(codes):
        exec(compile(code, f"{source} block {i + 1}", "exec"), namespace)
    return namespace


def test_readme_is_short(repo_root):
    readme = repo_root / "README.md"
    assert len(readme.read_text(encoding="utf-8").splitlines()) <= 120
    (python,) = blocks(readme, "python")
    assert len(python.strip().splitlines()) <= 10
    shell = blocks(readme, "bash")
    assert len(shell) == 2                      # the two make commands, the CLI quick start
    assert len(shell[1].strip().splitlines()) <= 5


def test_readme_python_quick_start(repo_root, in_tmp, capsys):
    (code,) = blocks(repo_root / "README.md", "python")
    ns = run_blocks([code], "README.md")
    ds = ns["ds"]
    assert list(ds["model"].values) == ["vhs", "hybrid-windowed"]
    point = ds.sel(velocity=10.0, realization=0)
    mu, area = point["friction"].values, point["contact_fraction"].values
    assert np.all(np.isfinite(mu)) and np.all(mu > 0)
    assert np.all((area > 0) & (area < 1))
    assert np.all(np.diff(area, axis=-1) > 0)   # more load, more contact
    assert "hybrid-windowed" in capsys.readouterr().out


def test_readme_command_line_quick_start(repo_root, tmp_path):
    shell = blocks(repo_root / "README.md", "bash")[1]
    env = {**os.environ, "RUBBERCONTACT_CACHE": str(tmp_path / "cache"), "MPLBACKEND": "Agg",
           "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"}
    for line in shell.strip().splitlines():
        command = line.split("#")[0].strip()
        done = subprocess.run(["bash", "-c", command], cwd=repo_root, env=env,
                              capture_output=True, text=True, timeout=300)
        assert done.returncode == 0, f"{command}: {done.stderr[-2000:]}"
        assert done.stdout.strip(), command


def test_tutorial_blocks(repo_root, in_tmp, capsys):
    codes = blocks(repo_root / "docs" / "tutorial.md", "python")
    assert len(codes) >= 5
    ns = run_blocks(codes, "docs/tutorial.md")
    np.testing.assert_allclose(ns["surface"].rms_slopes(), [1.33, 0.94, 0.52], atol=0.01)
    assert list(ns["hs"].wavelengths) == [0.0625]
    assert len(ns["realizations"]) == 3
    ds = ns["ds"]
    assert set(ds["model"].values) == {"vhs", "hybrid", "hybrid-windowed", "fem"}
    mu = ds["friction"].isel(velocity=0, realization=0, pressure=0)
    assert np.all(np.isfinite(mu.values)) and np.all(mu.values > 0)
    assert "units" in ds["friction"].attrs and ds["pressure"].attrs["units"] == "MPa"
    out = capsys.readouterr().out
    assert "p̄ =  0.1 MPa" in out
