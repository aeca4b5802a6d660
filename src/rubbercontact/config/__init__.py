"""Run configuration: a TOML file validated with pydantic.

Every field carries its unit and allowed range; unknown keys are rejected with a
did-you-mean suggestion, and every error names the file and the key. Paths in the
file are resolved relative to the file itself.

One module per table (``loads``, ``halfspace``, ``fem``, ``law``, ``meanfield``,
``friction``, ``execution``), the whole run's table and its cross-table checks (``run``),
the reading of a file (``parse``) and the built-in default (``default``); every name is
imported from here, ``rubbercontact.config``.
"""

from ..inputs import ProfileInput  # noqa: F401  (re-exported: config.ProfileInput)
from .default import DEFAULT_CONFIG, default_config
from .execution import ExecutionConfig, OutputConfig
from .fem import STEADY_FALLBACK_PERIODS, TRANSIENT_ONLY, FemConfig, Mesh  # noqa: F401
from .friction import AdhesionConfig, FlashTemperatureConfig, FrictionConfig
from .halfspace import HalfSpaceConfig
from .law import LawConfig
from .loads import MAX_SPEED_POINTS, LoadConfig
from .meanfield import MEANFIELD_KEYS, REMOVED_MEANFIELD_KEYS, MeanFieldConfig
from .parse import load_config, parse_config
from .run import (  # noqa: F401  (the [surface] and [material] tables: rubbercontact.inputs)
    DEFAULT_MODELS,
    MAP_DEFAULT_MODELS,
    MAP_MODELS,
    MODELS,
    MaterialConfig,
    RunConfig,
    SurfaceConfig,
)

# The API page lists the classes and functions named here (docs/conf.py reads __all__).
__all__ = [
    "DEFAULT_CONFIG", "DEFAULT_MODELS", "MAP_DEFAULT_MODELS", "MAP_MODELS", "MAX_SPEED_POINTS",
    "MEANFIELD_KEYS", "MODELS", "REMOVED_MEANFIELD_KEYS", "STEADY_FALLBACK_PERIODS",
    "TRANSIENT_ONLY", "AdhesionConfig", "ExecutionConfig", "FemConfig",
    "FlashTemperatureConfig", "FrictionConfig", "HalfSpaceConfig", "LawConfig", "LoadConfig",
    "MeanFieldConfig", "OutputConfig", "RunConfig", "default_config", "load_config",
    "parse_config",
]
