"""Config validation: one clear line naming the file, key, unit and problem."""

import pytest

from rubbercontact.config import default_config, load_config, parse_config
from rubbercontact.errors import InputError

BASE = {"surface": {"preset": "section3"}, "loads": {"pressures": [1.0]}, "velocities": [10.0]}


def _with(**changes):
    d = {k: (dict(v) if isinstance(v, dict) else v) for k, v in BASE.items()}
    for path, value in changes.items():
        keys = path.split("__")
        cur = d
        for k in keys[:-1]:
            cur = cur.setdefault(k, {})
        cur[keys[-1]] = value
    return d


def test_default_config_is_valid():
    cfg = default_config()
    assert cfg.models == ["vhs", "hybrid", "hybrid-windowed", "fem"]
    assert cfg.surface.preset == "section3"
    assert (cfg.realizations, cfg.fem.realizations) == (8, 1)   # FEM on one, CV for the rest


@pytest.mark.parametrize("data, expected", [
    (_with(loads={"pressure": [1.0]}), r"unknown key 'loads.pressure'; did you mean 'pressures'"),
    (_with(surface={"presett": "section3"}), r"did you mean 'preset'"),
    (_with(velocity=[1.0]), r"unknown key 'velocity'; did you mean 'velocities'"),
    (_with(loads={"pressures": [-1.0]}), r"loads.pressures.0.*MPa.*greater than 0"),
    (_with(loads={"contact_areas": [1.5]}), r"loads.contact_areas.0.*less than or equal to 1"),
    (_with(loads={"pressures": [1.0], "contact_areas": [0.1]}), r"exactly one of"),
    (_with(velocities=[-5.0]), r"'velocities'.*> 0 mm/s"),
    (_with(velocities=[10.0, 0.0]), r"'velocities'.*> 0 mm/s.*static"),
    (_with(material={"nu": 0.7}), r"material.nu"),
    (_with(fem={"mesh": [2, 90]}), r"fem.mesh.*nx >= 3"),
    (_with(surface={"wavelengths": [0.1, 0.2]}), r"go together"),
    (_with(surface={"wavelengths": [0.1, 0.2], "amplitudes": [0.01]}), r"differ in length"),
    (_with(models=["vhs", "bem"]), r"models.1"),
    (_with(execution={"scheduler": "http://x"}), r"execution.scheduler"),
    (_with(loads={"pressures": [1.0], "sweep_points": 4}), r"'sweep_points' applies to"),
    (_with(loads={"contact_areas": [0.1], "sweep_points": 1}), r"loads.sweep_points"),
    (_with(fem={"contact_points": 0}), r"fem.contact_points"),
    (_with(fem={"full_grading": -2.0}), r"fem.full_grading"),
])
def test_config_errors_name_the_key(data, expected):
    with pytest.raises(InputError, match=expected):
        parse_config(data, source="case.toml")


@pytest.mark.parametrize("mesh", [(3, 1), (2, 90), (40, 0), (4, 2), (120, 90)])
def test_config_and_fem_options_accept_the_same_meshes(mesh):
    # one definition of the mesh limits: FemOptions's, which the CLI's --mesh also meets
    from rubbercontact.fem.options import FemOptions

    try:
        FemOptions(mesh=mesh)
        fem_ok = True
    except InputError:
        fem_ok = False
    for key in ("mesh", "full_mesh"):
        try:
            parse_config(_with(fem={key: list(mesh)}))
            config_ok = True
        except InputError:
            config_ok = False
        assert config_ok == fem_ok, (key, mesh)


def test_errors_name_the_file(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text('velocities = [1.0]\n[surface]\npreset = "section3"\n[loads]\npresures = [1]\n')
    with pytest.raises(InputError, match=r"bad\.toml: unknown key 'loads.presures'"):
        load_config(p)
    p.write_text("velocities = [1.0\n")
    with pytest.raises(InputError, match=r"bad\.toml: invalid TOML"):
        load_config(p)
    with pytest.raises(InputError, match="not found"):
        load_config(tmp_path / "missing.toml")


def test_paths_resolve_relative_to_config(tmp_path):
    (tmp_path / "sub").mkdir()
    prof = tmp_path / "sub" / "scan.txt"
    prof.write_text("0 0\n")
    cfg_file = tmp_path / "sub" / "c.toml"
    cfg_file.write_text('velocities = [1.0]\n[surface.profiles]\nfiles = ["scan.txt"]\n'
                        '[loads]\npressures = [1.0]\n[output]\ndirectory = "out"\n')
    cfg = load_config(cfg_file)
    assert cfg.surface.profiles.files == [prof.resolve()]
    assert cfg.output.directory == (tmp_path / "sub" / "out").resolve()
    cfg_file.write_text('velocities = [1.0]\n[surface.profiles]\nfiles = ["nope.txt"]\n'
                        '[loads]\npressures = [1.0]\n')
    with pytest.raises(InputError, match=r"surface.profiles.files: file\(s\) not found"):
        load_config(cfg_file)


# -- fuzzing: random and truncated bytes give only clean InputErrors -------------------------
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

VALID = (b'velocities = [10.0, 50.0]\nrealizations = 5\n[surface]\npreset = "section3"\n'
         b'[loads]\ncontact_areas = [0.01, 0.05, 0.1]\n[fem]\nmesh = [120, 90]\n')


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.one_of(st.binary(max_size=400),
                      st.integers(0, len(VALID)).map(lambda k: VALID[:k]),
                      st.text(max_size=200).map(str.encode)))
def test_fuzz_config_loader(tmp_path_factory, data):
    p = tmp_path_factory.mktemp("fuzz") / "c.toml"
    p.write_bytes(data)
    try:
        load_config(p)
    except InputError as exc:
        assert str(exc) and "\n" not in str(exc)[:1]


def test_models_default_to_the_ones_to_run_first():
    # the recommended hybrid reading, without the full FEM (hours on a real surface)
    cfg = parse_config(BASE)
    assert "hybrid-windowed" in cfg.models and "vhs" in cfg.models
    assert "fem" not in cfg.models and "hybrid" not in cfg.models
