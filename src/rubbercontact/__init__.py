"""rubbercontact: hybrid multiscale rubber friction and contact area on rough surfaces.

Units everywhere: mm, MPa (= N/mm²), s, mm/s.
"""

from importlib.metadata import PackageNotFoundError, version

from . import materials, roughness
from .errors import ConvergenceError, InputError, RubberContactError

try:
    __version__ = version("rubbercontact")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0.0.0+unknown"

_LAZY = ("halfspace", "fem", "hybrid", "meanfield", "models", "pipeline", "sweep", "io", "config",
         "inputs", "plotting", "cli")


def __getattr__(name: str):
    # Heavy subpackages (FEM, Dask, matplotlib) load on first use only.
    if name in _LAZY:
        import importlib

        module = importlib.import_module(f".{name}", __name__)
        globals()[name] = module
        return module
    raise AttributeError(f"module 'rubbercontact' has no attribute {name!r}")


__all__ = ["materials", "roughness", "ConvergenceError", "InputError", "RubberContactError",
           "__version__"]
