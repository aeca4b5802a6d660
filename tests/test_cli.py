"""CLI behaviour: help, version, one-line user errors with exit code 2."""

import subprocess
import sys

from rubbercontact import __version__
from rubbercontact.cli import main


def test_version(capsys):
    assert main(["--version"]) == 0
    assert __version__ in capsys.readouterr().out


def test_help_lists_commands(capsys):
    assert main(["--help"]) == 0
    out = capsys.readouterr().out
    for cmd in ("run", "plot"):
        assert cmd in out


def test_bad_config_is_one_line_exit_2(tmp_path, capsys):
    p = tmp_path / "c.toml"
    p.write_text('velocities = [1.0]\n[surface]\npreset = "section3"\n[loads]\npresures = [1]\n')
    assert main(["run", str(p), "--output", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and "presures" in err[0]


def test_missing_results_file_exit_2(tmp_path, capsys):
    assert main(["plot", str(tmp_path / "nope.nc")]) == 2
    assert "not found" in capsys.readouterr().err


def test_unknown_option_is_usage_error(capsys):
    assert main(["run", "--no-such-option"]) == 2


def test_console_script_entry_point():
    # The installed entry point, as a user runs it.
    out = subprocess.run([sys.executable, "-m", "rubbercontact.cli", "--version"],
                         capture_output=True, text=True, timeout=60)
    assert out.returncode == 0 and __version__ in out.stdout
