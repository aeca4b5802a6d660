"""CLI behaviour: help, version, one-line user errors with exit code 2."""

import subprocess
import sys

import pytest

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


# All of the surface is high-slope: the hybrid's half-space part is flat, so at the law's own
# pressures the hybrid must return exactly the FEM law's friction and contact fraction (the
# cache shares those FEM runs between the law and the full-FEM model).
TINY = """
velocities = [10.0]
realizations = 1
seed = 5
models = ["vhs", "hybrid", "fem"]
[surface]
preset = "high_slope_wave"
[loads]
pressures = [0.3, 1.0]
[halfspace]
n = 512
[fem]
mesh = [30, 23]
[law]
pressures = [0.3, 1.0]
[execution]
workers = 1
cache = "cache"
[output]
directory = "out"
"""


def test_run_end_to_end_tiny(tmp_path, capsys):
    import numpy as np
    import xarray as xr

    cfg = tmp_path / "tiny.toml"
    cfg.write_text(TINY)
    assert main(["run", str(cfg), "--quiet"]) == 0
    out = capsys.readouterr().out
    assert "eq. 28 error of hybrid vs FEM" in out
    ds = xr.load_dataset(tmp_path / "out" / "results.nc")
    # The law on its own, next to the results, for reuse as law.file.
    from rubbercontact.io.results import read_law
    law = read_law(tmp_path / "out" / "law.nc")
    np.testing.assert_array_equal(law["friction"], ds["law_friction"])
    assert "law: " in out
    assert list(ds["model"].values) == ["vhs", "hybrid", "fem"]
    assert ds.attrs["rubbercontact_version"] == __version__ and "config" in ds.attrs
    assert ds["friction"].attrs["units"] == "1" and ds["pressure"].attrs["units"] == "MPa"
    # Flat low-slope part: hybrid = FEM law at the law's nodes (brentq to 1e-12 relative).
    for k in ("friction", "contact_fraction"):
        np.testing.assert_allclose(ds[k].sel(model="hybrid"), ds[k].sel(model="fem"),
                                   rtol=1e-6)
    assert float(ds["error_vs_fem"].sel(compared_model="hybrid").max()) < 1e-6
    for fig in ("fig2_law.png", "fig5_friction_vs_area.png", "fig7_high_slope_friction.png",
                "fig8_pressure_profiles.png", "fig9_friction_vs_pressure.png"):
        assert (tmp_path / "out" / fig).stat().st_size > 1000
    # No silent overwrite; the second run finds everything in the cache.
    assert main(["run", str(cfg), "--quiet"]) == 2
    assert "--overwrite" in capsys.readouterr().err
    assert main(["run", str(cfg), "--quiet", "--overwrite"]) == 0
    assert main(["plot", str(tmp_path / "out" / "results.nc"), "-o", str(tmp_path / "f")]) == 0
    assert (tmp_path / "f" / "fig5_friction_vs_area.png").exists()


def test_run_with_the_fem_on_a_subset_is_not_a_failure(tmp_path, capsys):
    # fem.realizations = 1 of 2: the skipped FEM slots are "not run", not failed solves, so
    # the run exits 0; the summary says how the FEM's phase average was estimated, and the
    # figures redraw from the file.
    import xarray as xr

    cfg = tmp_path / "tiny.toml"
    cfg.write_text(TINY.replace("realizations = 1", "realizations = 2")
                   .replace("mesh = [30, 23]", "mesh = [30, 23]\nrealizations = 1"))
    assert main(["run", str(cfg), "--quiet"]) == 0
    captured = capsys.readouterr()
    assert "fem ran on 1 of 2 realizations" in captured.out
    assert "failed" not in captured.err
    ds = xr.load_dataset(tmp_path / "out" / "results.nc")
    assert "friction_phase_mean" in ds and ds.attrs["fem_realizations"] == 1
    assert main(["plot", str(tmp_path / "out" / "results.nc"), "-o", str(tmp_path / "f")]) == 0


def test_a_command_exit_code_reaches_the_shell(monkeypatch):
    # Solver failures end `rubbercontact run` with typer.Exit(1); without click's standalone
    # mode that code is returned, not raised, and must still become the process's.
    import typer

    import rubbercontact.cli as cli

    app = typer.Typer()

    @app.command()
    def fails():
        raise typer.Exit(3)

    @app.command()
    def works():
        pass

    monkeypatch.setattr(cli, "app", app)
    assert cli.main(["fails"]) == 3
    assert cli.main(["works"]) == 0


# A cheap run: the VHS alone on one wave, for the command-line checks below.
CHEAP = """
velocities = [10.0]
models = ["vhs"]
[surface]
preset = "high_slope_wave"
[loads]
pressures = [0.3]
[halfspace]
n = 256
[execution]
workers = 1
cache = "cache"
"""


def test_make_run_can_run_twice(tmp_path, repo_root, capsys):
    # the options of the Makefile's `run` recipe (as `make -n` prints it), on a cheap config
    # instead of the built-in default: a second run with the same options must succeed
    import shlex

    recipe = subprocess.run(["make", "-n", "-s", "run"], cwd=repo_root, capture_output=True,
                            text=True, timeout=60).stdout.splitlines()
    line = next(x for x in recipe if "rubbercontact run" in x)
    args = shlex.split(line.split("rubbercontact", 1)[1])
    assert args[0] == "run"
    out = tmp_path / "out"
    args = [a if a != "results" else str(out) for a in args]
    cfg = tmp_path / "cheap.toml"
    cfg.write_text(CHEAP)
    for _ in range(2):
        assert main([*args, str(cfg), "--quiet", "--no-figures"]) == 0
    assert (out / "results.nc").is_file()


def test_summary_of_a_file_that_is_not_netcdf_is_one_line(tmp_path, capsys):
    bad = tmp_path / "notes.nc"
    bad.write_text("not a results file\n")
    for cmd in ("summary", "plot"):
        assert main([cmd, str(bad)]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert err == [f"error: results file {bad}: not a NetCDF file"]


@pytest.mark.parametrize("args, says", [
    (["halfspace", "--velocity", "-10", "--pressure", "0.35"], "velocity: sliding speed -10"),
    (["fem", "--velocity", "-1", "--mesh", "16x12", "--quiet"], "velocity: sliding speed -1"),
    (["halfspace", "--velocity", "10", "--pressure", "1e6"], "(0, 2902) MPa"),
    (["fem", "--pressure", "1e6", "--mesh", "16x12", "--quiet"], "(0, 2902) MPa"),
])
def test_commands_refuse_negative_speeds_and_absurd_pressures(args, says, capsys):
    # the SBR of Table 1: glassy modulus E_inf + sum E_i = 4.17 + 2897.72 MPa
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and says in err[0]


@pytest.mark.parametrize("change, says", [
    (("velocities = [10.0]", "velocities = [0.0]"), "'velocities'"),
    (("velocities = [10.0]", "velocities = [-10.0]"), "'velocities'"),
    (("pressures = [0.3]", "pressures = [0.3, 1e6]"), "loads.pressures: mean pressure 1e+06"),
])
def test_run_check_refuses_what_would_not_slide_or_load(change, says, tmp_path, capsys):
    cfg = tmp_path / "c.toml"
    cfg.write_text(CHEAP.replace(*change))
    assert main(["run", str(cfg), "--check"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and says in err[0]


def test_the_built_in_default_says_what_its_numbers_are(tmp_path, monkeypatch, capsys):
    # the built-in default's config swapped for a cheap one: the note under the numbers
    # comes with the default (no CONFIG argument), not with a user's config
    import tomllib

    import rubbercontact.config as config
    from rubbercontact.cli.run import DEFAULT_RUN_NOTE

    cheap = config.parse_config(tomllib.loads(CHEAP), base_dir=tmp_path)
    monkeypatch.setattr(config, "default_config", lambda: cheap)
    assert main(["run", "--output", str(tmp_path / "d"), "--quiet", "--no-figures"]) == 0
    assert DEFAULT_RUN_NOTE in capsys.readouterr().out
    cfg = tmp_path / "cheap.toml"
    cfg.write_text(CHEAP)
    assert main(["run", str(cfg), "-o", str(tmp_path / "u"), "--quiet", "--no-figures"]) == 0
    assert DEFAULT_RUN_NOTE not in capsys.readouterr().out


def test_run_check_prints_the_cost(tmp_path, capsys):
    cfg = tmp_path / "cheap.toml"
    cfg.write_text(CHEAP)
    assert main(["run", str(cfg), "--check", "--workers", "2"]) == 0
    out = capsys.readouterr().out
    assert "cost: half-space solves (vhs; 256 points): 1 x" in out
    assert "on 2 worker(s)" in out


def test_run_prints_each_distinct_warning_once_with_its_count(tmp_path, capsys, monkeypatch):
    # the law's reading warns once per speed and solve: the same line must not fill the
    # terminal (speed_sweep printed one 20 times)
    import warnings

    import rubbercontact.pipeline as pipeline

    real = pipeline.run

    def noisy(cfg, **kw):
        for _ in range(3):
            warnings.warn("law: the same thing", UserWarning, stacklevel=2)
        warnings.warn("law: another thing", UserWarning, stacklevel=2)
        return real(cfg, **kw)

    monkeypatch.setattr(pipeline, "run", noisy)
    cfg = tmp_path / "vhs.toml"
    cfg.write_text(TINY.replace('models = ["vhs", "hybrid", "fem"]', 'models = ["vhs"]'))
    assert main(["run", str(cfg), "--quiet"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err.count("warning: law: the same thing (×3)") == 1
    assert err.count("warning: law: another thing") == 1
