"""Results files: NetCDF with provenance, written atomically, never silently overwritten.

A results file (:func:`rubbercontact.pipeline.run`) keeps each statistic over the
random-phase realizations as its own variable: ``k_mean`` and ``k_std`` (over the
realizations), and with the FEM on a subset of them ``k_phase_mean``/``k_phase_se`` (the
phase averages, the FEM's by control variate). The ``ds.rc`` accessor
(:class:`ResultsAccessor`, registered on import of this module) reads them by what they
are: ``ds.rc.mean("friction")``, ``ds.rc.spread("friction")``, ``ds.rc.stderr(...)``.
Files of the first layout (no ``results_format`` attribute) read the same way.
"""

from __future__ import annotations

import json
import platform
import sys
from datetime import UTC, datetime
from pathlib import Path

import numpy as np
import xarray as xr

from .atomic import write_netcdf_atomic


def mean_of(ds: xr.Dataset, k: str) -> xr.DataArray:
    """``k_phase_mean`` when the run estimated phase averages, else ``k_mean``."""
    return ds[f"{k}_phase_mean"] if f"{k}_phase_mean" in ds else ds[f"{k}_mean"]


@xr.register_dataset_accessor("rc")
class ResultsAccessor:
    """Statistics of a results dataset by what they are, not by their variable names.

    Examples
    --------
    >>> ds.rc.mean("friction").sel(model="hybrid")     # doctest: +SKIP
    >>> ds.rc.curve("friction", model="vhs", pressure=0.2)   # μ over the speeds
    """

    def __init__(self, ds: xr.Dataset) -> None:
        self._ds = ds

    @property
    def format(self) -> int:
        """Layout version of the file (1: before the attribute existed)."""
        return int(self._ds.attrs.get("results_format", 1))

    @property
    def temperatures(self) -> np.ndarray | None:
        """The run's temperatures [°C], or None for an isothermal run."""
        ds = self._ds
        return ds["temperature"].values if "temperature" in ds.dims else None

    def has(self, k: str) -> bool:
        """Whether the results carry the statistics of ``k``."""
        return f"{k}_mean" in self._ds or f"{k}_phase_mean" in self._ds

    def mean(self, k: str) -> xr.DataArray:
        """The phase average of ``k``: ``k_phase_mean`` (the FEM's by control variate) when
        the run estimated it, else the mean over the realizations."""
        return mean_of(self._ds, k)

    def spread(self, k: str) -> xr.DataArray:
        """Standard deviation of ``k`` over the realizations (the phase-to-phase scatter)."""
        ds = self._ds
        if f"{k}_std" in ds:
            return ds[f"{k}_std"]
        return ds[k].std("realization")

    def stderr(self, k: str) -> xr.DataArray:
        """Standard error of :meth:`mean`: ``k_phase_se`` for the FEM on a subset, else the
        spread over ``sqrt(n)`` realizations that ran (NaN with fewer than two)."""
        ds = self._ds
        n = ds[k].notnull().sum("realization")
        se = (ds[k].std("realization", ddof=1) / np.sqrt(n)).where(n > 1)
        if f"{k}_phase_se" in ds and "fem" in ds["model"].values:
            fem = ds[f"{k}_phase_se"].expand_dims(model=["fem"])
            se = xr.where(se["model"] == "fem", fem.reindex_like(se), se)
        return se

    def curve(self, k: str, *, model: str, pressure: float | None = None,
              temperature: float | None = None, **at) -> xr.DataArray:
        """:meth:`mean` of ``k`` over the speeds at one model, load (and temperature)."""
        sel = {"model": model, **at}
        if pressure is not None:
            sel["pressure"] = pressure
        if temperature is not None:
            sel["temperature"] = temperature
        return self.mean(k).sel(sel)


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
    except ValueError:      # no xarray backend recognises the file; its advice is not ours
        raise InputError(f"results file {path}: not a NetCDF file") from None
    except OSError as exc:
        raise InputError(f"results file {path}: not readable "
                         f"({str(exc).splitlines()[0]})") from None


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
