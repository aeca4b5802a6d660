"""The documentation builds with warnings as errors (what ``make docs`` runs).

The gallery's examples are not executed here (``-D plot_gallery=0``):
tests/test_example_scripts.py runs each of them and pins its numbers. Everything else is
built: the pages, the API reference from the docstrings, the configuration and
command-line references generated from the code, the included VALIDATION.md and
BENCHMARKS.md. A warning (a broken link or reference, a malformed docstring, a page in no
table of contents) fails the test with Sphinx's message.
"""

from __future__ import annotations

import importlib.util
import subprocess
import sys

import pytest

NEEDED = ("sphinx", "myst_parser", "numpydoc", "sphinx_gallery", "furo")


def test_docs_build_without_warnings(repo_root, tmp_path):
    missing = [m for m in NEEDED if importlib.util.find_spec(m) is None]
    if missing:
        pytest.skip(f"the docs extra is not installed (no {', '.join(missing)}): "
                    f"pip install -e '.[docs]', or make test, which installs it")
    command = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
               "-D", "plot_gallery=0", "-d", str(tmp_path / "doctrees"),
               str(repo_root / "docs"), str(tmp_path / "html")]
    done = subprocess.run(command, capture_output=True, text=True, timeout=900,
                          env={**__import__("os").environ, "MPLBACKEND": "Agg"})
    assert done.returncode == 0, f"sphinx-build failed:\n{done.stderr[-6000:]}"
    html = tmp_path / "html"
    for page in ("index", "tutorial", "theory", "guide/configuration", "guide/cli",
                 "validation/index", "validation_report", "benchmarks", "api/index"):
        assert (html / f"{page}.html").is_file(), page
    assert "fem.mesh" in (html / "guide" / "configuration.html").read_text(encoding="utf-8") \
        or "[fem]" in (html / "guide" / "configuration.html").read_text(encoding="utf-8")
