"""Results files: NetCDF with provenance, written atomically, never silently overwritten."""

from __future__ import annotations

import json
import platform
import sys
from datetime import UTC, datetime
from pathlib import Path

import xarray as xr

from .atomic import write_netcdf_atomic


def provenance() -> dict[str, str]:
    """Platform and library versions, as NetCDF-storable strings."""
    import numpy
    import scipy

    from .. import __version__

    return {
        "rubbercontact_version": __version__,
        "created": datetime.now(UTC).isoformat(timespec="seconds"),
        "python": sys.version.split()[0],
        "platform": platform.platform(),
        "machine": platform.machine(),
        "libraries": json.dumps({"numpy": numpy.__version__, "scipy": scipy.__version__,
                                 "xarray": xr.__version__}),
    }


def _netcdf_safe(ds: xr.Dataset) -> xr.Dataset:
    """Drop the attribute types NetCDF cannot store (bool, dict, None) by encoding them as JSON."""
    ds = ds.copy()
    for obj in [ds, *ds.variables.values()]:
        for k, v in list(obj.attrs.items()):
            if isinstance(v, bool) or v is None or isinstance(v, dict):
                obj.attrs[k] = json.dumps(v)
            elif isinstance(v, list | tuple) and any(isinstance(e, str | dict) for e in v):
                obj.attrs[k] = json.dumps(v)
    return ds


def write_results(ds: xr.Dataset, path: str | Path, *, overwrite: bool = False) -> Path:
    """Write a results dataset with provenance attributes, atomically.

    Raises ``FileExistsError`` when ``path`` exists and ``overwrite`` is False.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    out = _netcdf_safe(ds)
    for k, v in provenance().items():
        out.attrs.setdefault(k, v)
    return write_netcdf_atomic(out, path, overwrite=overwrite)


def read_results(path: str | Path) -> xr.Dataset:
    """Load a results file written by :func:`write_results` into memory."""
    from ..errors import InputError

    path = Path(path)
    if not path.is_file():
        raise InputError(f"results file {path}: not found")
    try:
        return xr.load_dataset(path)
    except (OSError, ValueError) as exc:
        raise InputError(f"results file {path}: not a readable NetCDF file ({exc})") from None


def write_law(law: xr.Dataset, path: str | Path, *, overwrite: bool = True) -> Path:
    """Write a law table (:func:`~rubbercontact.hybrid.effective_law`) as :func:`write_results`
    does: reusable as ``law.file`` by any run on the same high-slope scale and rubber."""
    from ..hybrid.law import as_law

    return write_results(as_law(law), path, overwrite=overwrite)


def read_law(path: str | Path) -> xr.Dataset:
    """Load a law table from a ``law.nc`` (:func:`write_law`) or from a run's ``results.nc``.

    Raises :class:`~rubbercontact.errors.InputError` when the file is missing, unreadable or
    carries no law with its provenance.
    """
    from ..hybrid.law import as_law

    ds = read_results(path)
    return as_law(ds, source=f"law file {path}")
