"""`make run` as a new user meets it (issue 39's bar): the built-in default, from an empty
result cache, twice in a row with the Makefile's own options, prints no warning and says
under its numbers what they are (a reduced demonstration, not the README's validated
table). Slow: the default's law and FEM solves take about half a minute on a quiet 2-core
machine (``make validate`` runs it)."""

import shlex
import subprocess

import pytest

from rubbercontact.cli import main
from rubbercontact.cli.run import DEFAULT_RUN_NOTE


def _make_run_args(repo_root) -> list[str]:
    """The arguments of the Makefile's `run` recipe, as `make -n` prints them."""
    recipe = subprocess.run(["make", "-n", "-s", "run"], cwd=repo_root, capture_output=True,
                            text=True, timeout=60).stdout.splitlines()
    line = next(x for x in recipe if "rubbercontact run" in x)
    return shlex.split(line.split("rubbercontact", 1)[1])


@pytest.mark.slow
def test_make_run_twice_prints_no_warning_and_says_what_its_numbers_are(
        tmp_path, repo_root, monkeypatch, capsys):
    args = _make_run_args(repo_root)
    assert args[0] == "run" and not any(a.endswith(".toml") for a in args)  # the default
    monkeypatch.setenv("RUBBERCONTACT_CACHE", str(tmp_path / "cache"))
    monkeypatch.chdir(tmp_path)                  # results/ lands in the test's folder
    for attempt in ("empty cache", "second run"):
        assert main(args) == 0, attempt
        captured = capsys.readouterr()
        said = (captured.out + captured.err).splitlines()
        assert [s for s in said if "warning" in s.lower()] == [], attempt
        assert DEFAULT_RUN_NOTE in said, attempt
    for name in ("results.nc", "law.nc", "fig5_friction_vs_area.png"):
        assert (tmp_path / "results" / name).stat().st_size > 1000, name
