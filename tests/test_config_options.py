"""One source of options: the config's defaults (and help) are the option objects' own, and
every FEM option is reachable from a config (the drift of issue 38: TransientOptions.periods
= 6 against FemConfig.periods = 4, and penalty_factor, bulk_modulus, newton_tol
unreachable)."""

from __future__ import annotations

import dataclasses
import typing

import pytest

import rubbercontact as rc
from rubbercontact._optionfields import option_help
from rubbercontact.config import (
    STEADY_FALLBACK_PERIODS,
    FemConfig,
    HalfSpaceConfig,
    MeanFieldConfig,
    parse_config,
)
from rubbercontact.errors import InputError
from rubbercontact.fem.options import SOLVERS, VISCOUS_MODELS, FemOptions, TransientOptions
from rubbercontact.meanfield import MeanFieldOptions
from rubbercontact.meanfield.options import DISSIPATIONS, INTERFACES, WEIGHTINGS
from rubbercontact.models import HalfspaceOptions
from rubbercontact.models.halfspace import LAWS

BASE = {"surface": {"preset": "section3"}, "velocities": [10.0], "loads": {"pressures": [0.2]}}
#: Intended differences, each with its reason (not silently allowed).
KNOWN = {("FemConfig", "mesh"): "a run's law cell follows its surface ('auto', issue 41); "
                                "the library's FemOptions keeps an explicit default, so a "
                                "script's results and cache keys stay what they were",
         ("FemConfig", "crest_radius"): "a run's law cell of a measured road rounds its crests "
                                        "to the profiles' sampling ('sampling', issue 41); "
                                        "the library's FemOptions takes the surface as given"}


def _defaults(cls) -> dict:
    return {f.name: f.default for f in dataclasses.fields(cls)
            if f.default is not dataclasses.MISSING}


@pytest.mark.parametrize("config, options", [
    (FemConfig, FemOptions), (FemConfig, TransientOptions),
    (MeanFieldConfig, MeanFieldOptions), (HalfSpaceConfig, HalfspaceOptions)])
def test_config_defaults_are_the_option_objects(config, options):
    opts = _defaults(options)
    for name, field in config.model_fields.items():
        if name in opts and (config.__name__, name) not in KNOWN:
            default = field.default
            want = opts[name]
            assert (tuple(default) if isinstance(default, (list, tuple)) else default) == (
                tuple(want) if isinstance(want, (list, tuple)) else want), (config, name)


def test_every_fem_option_is_reachable_from_a_config():
    mat = rc.materials.sbr()
    fields = {f.name for f in dataclasses.fields(FemOptions)} - {"steady", "transient"}
    own = set(FemConfig.model_fields)
    changed = {"penalty_factor": 50.0, "contact_smoothing": 0.2, "contact": "barrier",
               "barrier_distance": 0.2, "barrier_stiffness": 2.0, "bulk_modulus": 1000.0,
               "newton_tol": 1e-7, "max_newton": 30, "patch_columns": 6}
    assert fields - own == set(changed)       # the rest have keys of their own
    cfg = rc.config.parse_config({**BASE, "fem": {"numerics": changed}})
    opts = cfg.fem.options(mat)
    assert {k: getattr(opts, k) for k in changed} == changed


def test_the_law_cell_rounds_crests_to_the_sampling_of_measured_profiles_only():
    mat = rc.materials.sbr()
    fem = rc.config.parse_config(BASE).fem
    assert fem.crest_radius == "sampling"
    assert fem.with_sampling(None).options(mat).crest_radius is None      # a sine table
    measured = fem.with_sampling(0.0375)
    assert measured.options(mat).crest_radius == 0.0375
    assert measured.options(mat, full=True).crest_radius is None          # the full FEM
    given = rc.config.parse_config({**BASE, "fem": {"crest_radius": 0.02}}).fem
    assert given.with_sampling(0.0375).options(mat).crest_radius == 0.02
    for bad in (-0.01, "sharp"):
        with pytest.raises(InputError, match="crest_radius") as err:
            rc.config.parse_config({**BASE, "fem": {"crest_radius": bad}})
        assert "\n" not in str(err.value)


@pytest.mark.parametrize("numerics, match", [
    ({"mesh": [40, 30]}, "set elsewhere"), ({"glue": 1}, "unknown"),
    ({"contact": "glue"}, "contact: must be one of")])
def test_bad_numerics_are_one_line(numerics, match):
    with pytest.raises(InputError, match=match) as err:
        rc.config.parse_config({**BASE, "fem": {"numerics": numerics}})
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("config, name, options, field", [
    (HalfSpaceConfig, "n", HalfspaceOptions, "n"), (HalfSpaceConfig, "tol", HalfspaceOptions,
                                                    "tol"),
    (FemConfig, "height_ratio", FemOptions, "height_ratio"),
    (FemConfig, "contact_points", FemOptions, "contact_points"),
    (FemConfig, "periods", TransientOptions, "periods")])
def test_config_help_is_the_option_objects(config, name, options, field):
    text = option_help(options, field)
    assert text and text in config.model_fields[name].description


@pytest.mark.parametrize("config, name, choices", [
    (FemConfig, "solver", SOLVERS), (FemConfig, "viscous_model", VISCOUS_MODELS),
    (HalfSpaceConfig, "law", LAWS), (MeanFieldConfig, "weighting", WEIGHTINGS),
    (MeanFieldConfig, "dissipation", DISSIPATIONS), (MeanFieldConfig, "interface",
                                                     INTERFACES)])
def test_config_choices_are_the_libraries(config, name, choices):
    def strings(annotation) -> set:
        args = typing.get_args(annotation)
        return {a for a in args if isinstance(a, str)}.union(
            *(strings(a) for a in args if not isinstance(a, str)))

    assert strings(config.model_fields[name].annotation) == set(choices)


def test_meanfield_help_names_the_option_objects_defaults():
    from rubbercontact.meanfield.options import DEFAULT_GAMMA
    from rubbercontact.meanfield.psd import NODES_PER_DECADE

    fields = MeanFieldConfig.model_fields
    assert f"default {DEFAULT_GAMMA:g}" in fields["gamma"].description
    assert f"default {NODES_PER_DECADE}" in fields["nodes_per_decade"].description
    assert f"default {MeanFieldOptions().weighting.kind}" in fields["weighting"].description


def test_periods_is_the_libraries_and_steady_runs_keep_their_fallback():
    # fem.periods is TransientOptions.periods (6) for the transient solver; the steady
    # solver's fallback keeps the 4 its runs' cache keys carry (config.STEADY_FALLBACK_PERIODS)
    mat = rc.materials.sbr()
    transient = parse_config({**BASE, "fem": {"solver": "transient"}}).fem
    assert transient.options(mat).transient.periods == TransientOptions.periods == 6
    steady = parse_config(BASE).fem
    for full in (False, True):
        assert steady.options(mat, full=full).transient.periods == STEADY_FALLBACK_PERIODS == 4
    with pytest.raises(InputError, match="periods apply to solver = 'transient' only"):
        parse_config({**BASE, "fem": {"periods": 4}})
