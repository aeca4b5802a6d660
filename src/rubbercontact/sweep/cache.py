"""Content-addressed result cache: one NetCDF file per task result.

Layout under the cache directory::

    <dir>/sweep-v1/<key[:2]>/<key>.nc          successful result
    <dir>/sweep-v1/<key[:2]>/<key>.failed.nc   recorded failure (no data variables)

``key`` is the task's SHA-256 key (:func:`~rubbercontact.sweep.tasks.task_key`).
Each file carries, as global attributes prefixed ``rc_cache_``: the key, the task
description (canonical JSON), the status, the wall time of the computation, the
package version, the creation time and a SHA-256 checksum of all its variables
(names, dimensions, dtypes and values), and the digest of the code that computed it
(:mod:`.codehash`; part of the key, stored so that ``rubbercontact cache info`` can tell
entries of the current code from those of other code, and ``prune`` delete the latter).
Files are written atomically
(:func:`~rubbercontact.io.atomic.write_netcdf_atomic`). On reading, an
unreadable file, a key that does not match the file name or a checksum
mismatch marks the entry as corrupt: it is deleted and the task recomputed,
never returned as a result. No pickle anywhere.

The directory is, in order of precedence: the ``directory`` argument (``--cache
DIR``), the environment variable ``RUBBERCONTACT_CACHE``, or
``platformdirs.user_cache_dir("rubbercontact")``.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import logging
import os
import shutil
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ..errors import InputError
from ..io.atomic import TEMP_SUFFIX, write_netcdf_atomic
from .codehash import code_digest
from .results import TaskFailure
from .tasks import Task

__all__ = ["CacheEntry", "CacheInfo", "CodeReport", "CopyReport", "ResultCache",
           "dataset_checksum", "default_cache_dir", "entry_code"]

log = logging.getLogger(__name__)

ENV_CACHE = "RUBBERCONTACT_CACHE"
_FORMAT_DIR = "sweep-v1"
_PREFIX = "rc_cache_"
_FAILED_SUFFIX = ".failed.nc"


def _package_version() -> str:
    from .. import __version__

    return str(__version__)


def default_cache_dir() -> Path:
    """``$RUBBERCONTACT_CACHE`` if set, else the platform's user cache directory."""
    env = os.environ.get(ENV_CACHE)
    if env:
        return Path(env).expanduser()
    import platformdirs

    return Path(platformdirs.user_cache_dir("rubbercontact"))


def dataset_checksum(dataset: xr.Dataset) -> str:
    """SHA-256 over every variable (data and coordinates) of ``dataset``.

    Covers names, dimensions, dtypes, shapes and values; not attributes (NetCDF
    changes their Python types on a round trip). Strings are hashed as text so
    that ``<U`` and ``object`` arrays of the same strings agree; NaNs are
    canonicalised so their bit payload does not matter.
    """
    h = hashlib.sha256()
    for name in sorted(map(str, dataset.variables)):
        var = dataset.variables[name]
        values = np.asarray(var.values)
        h.update(json.dumps([name, list(map(str, var.dims)), list(values.shape)]).encode())
        if values.dtype.kind in "OUS":
            h.update(b"str")
            h.update(json.dumps([str(v) for v in values.ravel().tolist()]).encode())
        else:
            h.update(values.dtype.str.encode())
            data = np.ascontiguousarray(values)
            if data.dtype.kind in "fc":
                data = np.where(np.isnan(data), np.nan, data).astype(values.dtype)
            h.update(data.tobytes())
    return h.hexdigest()


@dataclass
class CacheEntry:
    """A valid entry read from the cache."""

    key: str
    status: str  # "ok" or "failed"
    result: xr.Dataset | TaskFailure
    wall_time: float
    path: Path


@dataclass(frozen=True)
class CopyReport:
    """What :meth:`ResultCache.copy_to` did: entries copied, already present, corrupt."""

    copied: int
    present: int
    corrupt: int

    def __str__(self) -> str:
        return (f"{self.copied} copied, {self.present} already present, "
                f"{self.corrupt} corrupt (not copied)")


@dataclass
class CacheInfo:
    """Summary of a cache directory (``rubbercontact cache info``)."""

    location: Path
    n_entries: int
    n_failed: int
    n_temporary: int
    size_bytes: int

    def __str__(self) -> str:
        return (f"location:  {self.location}\n"
                f"entries:   {self.n_entries} ({self.n_entries - self.n_failed} ok, "
                f"{self.n_failed} failed)\n"
                f"size:      {self.size_bytes / 1e6:.2f} MB\n"
                f"temporary: {self.n_temporary} (interrupted writes; removed by clear)")


@dataclass(frozen=True)
class CodeReport:
    """Entries of a cache by the code that computed them (``rubbercontact cache info``).

    ``other`` were computed by code that differs from this installation's (they can never
    be hit again: the code is part of the key); ``unknown`` carry no code digest (written
    before keys had one) or name a function this installation does not have.
    """

    current: int
    other: int
    unknown: int

    def __str__(self) -> str:
        return (f"code:      {self.current} of the current code, {self.other} of other code, "
                f"{self.unknown} of unknown code (`rubbercontact cache prune` deletes "
                f"the last two)")


def entry_code(path: Path) -> tuple[str, str]:
    """``(function, code digest)`` stored in the entry file ``path`` ("" where absent)."""
    import netCDF4

    with netCDF4.Dataset(path) as nc:
        attrs = {k: nc.getncattr(k) for k in nc.ncattrs()}
    function = str(attrs.get(_PREFIX + "function", ""))
    if not function:  # entries written before the function had its own attribute
        with contextlib.suppress(json.JSONDecodeError):
            function = json.loads(str(attrs.get(_PREFIX + "task", "{}"))).get("function", "")
    return function, str(attrs.get(_PREFIX + "code", ""))


class ResultCache:
    """Content-addressed store of task results.

    Parameters
    ----------
    directory
        Cache root; default ``$RUBBERCONTACT_CACHE`` or the user cache directory.
        Created on first write.
    shared
        The directory is visible at the same path to every Dask worker (shared
        filesystem): workers then write the entries themselves, in parallel,
        instead of the client one after the other. If an entry written by a
        worker is not visible to the client, the client writes it again and warns.
    """

    def __init__(self, directory: str | os.PathLike[str] | None = None,
                 shared: bool = False) -> None:
        root = default_cache_dir() if directory is None else Path(directory).expanduser()
        if root.exists() and not root.is_dir():
            raise InputError(f"cache: {str(root)!r} exists and is not a directory")
        self.directory = root.absolute()
        self.shared = bool(shared)
        #: Entries found corrupt (and deleted) by this object so far.
        self.n_corrupt = 0

    @classmethod
    def default(cls) -> ResultCache:
        """The cache in ``$RUBBERCONTACT_CACHE`` or the user cache directory."""
        return cls(None)

    def __repr__(self) -> str:
        return f"ResultCache({str(self.directory)!r})"

    # -- paths ------------------------------------------------------------------------
    @property
    def _root(self) -> Path:
        return self.directory / _FORMAT_DIR

    def path_for(self, key: str, failed: bool = False) -> Path:
        """File of the entry ``key`` (successful or failed variant)."""
        return self._root / key[:2] / (key + (_FAILED_SUFFIX if failed else ".nc"))

    def _files(self) -> list[Path]:
        if not self._root.is_dir():
            return []
        return [p for p in self._root.glob("*/*.nc") if not p.name.startswith(".")]

    def _temporaries(self) -> list[Path]:
        if not self._root.is_dir():
            return []
        return list(self._root.glob(f"*/.*{TEMP_SUFFIX}"))

    # -- read -------------------------------------------------------------------------
    def load(self, key: str) -> CacheEntry | None:
        """The valid entry for ``key``, or None (missing, or corrupt and now deleted)."""
        for failed in (False, True):
            path = self.path_for(key, failed)
            if not path.exists():
                continue
            entry = self._read(key, path)
            if entry is not None:
                return entry
        return None

    @staticmethod
    def _check(key: str, path: Path) -> tuple[xr.Dataset | None, str | None]:
        """``(dataset, None)`` for a valid entry file, ``(None, problem)`` otherwise."""
        try:
            ds = xr.load_dataset(path, engine="netcdf4")
            attrs = ds.attrs
            problem = None
            if attrs.get(_PREFIX + "key") != key:
                problem = f"key attribute {attrs.get(_PREFIX + 'key')!r} does not match"
            elif attrs.get(_PREFIX + "status") not in ("ok", "failed"):
                problem = f"unknown status {attrs.get(_PREFIX + 'status')!r}"
            elif attrs.get(_PREFIX + "checksum") != dataset_checksum(ds):
                problem = "checksum mismatch"
        except Exception as exc:  # noqa: BLE001 - any unreadable file is a corrupt entry
            return None, f"unreadable ({type(exc).__name__}: {exc})"
        return (None, problem) if problem is not None else (ds, None)

    def _read(self, key: str, path: Path) -> CacheEntry | None:
        ds, problem = self._check(key, path)
        if problem is not None:
            self._discard(path, problem)
            return None
        attrs = ds.attrs
        status = str(attrs[_PREFIX + "status"])
        wall_time = float(attrs.get(_PREFIX + "wall_time_s", 0.0))
        if status == "failed":
            try:
                diagnostics = json.loads(str(attrs.get(_PREFIX + "diagnostics", "{}")))
            except json.JSONDecodeError:
                diagnostics = {"raw": str(attrs.get(_PREFIX + "diagnostics"))}
            result: xr.Dataset | TaskFailure = TaskFailure(
                message=str(attrs.get(_PREFIX + "message", "")),
                error_type=str(attrs.get(_PREFIX + "error_type", "Exception")),
                diagnostics=diagnostics,
                traceback=str(attrs.get(_PREFIX + "traceback", "")),
                wall_time=wall_time, cached=True)
        else:
            ds.attrs = {k: v for k, v in ds.attrs.items() if not k.startswith(_PREFIX)}
            result = ds
        return CacheEntry(key, status, result, wall_time, path)

    def _discard(self, path: Path, problem: str) -> None:
        self.n_corrupt += 1
        log.warning("cache entry %s is corrupt (%s): deleted, will be recomputed", path, problem)
        with contextlib.suppress(FileNotFoundError):
            path.unlink()

    def __contains__(self, key: str) -> bool:
        return self.load(key) is not None

    # -- write ------------------------------------------------------------------------
    def store(self, key: str, task: Task, result: xr.Dataset | TaskFailure,
              wall_time: float) -> Path:
        """Write the entry for ``key`` atomically and return its path.

        A successful result replaces a recorded failure of the same key and vice
        versa. Raises whatever NetCDF raises if ``result`` cannot be stored
        (e.g. complex variables or ``bool`` attributes).
        """
        failed = isinstance(result, TaskFailure)
        if failed:
            ds = xr.Dataset()
            extra: dict[str, Any] = {_PREFIX + k: v for k, v in result.to_attrs().items()}
        elif isinstance(result, xr.Dataset):
            ds = result.copy(deep=False)
            extra = {}
        else:
            raise TypeError(f"result: expected xarray.Dataset or TaskFailure, "
                            f"got {type(result).__name__}")
        ds.attrs = {**ds.attrs, **extra,
                    _PREFIX + "key": key,
                    _PREFIX + "status": "failed" if failed else "ok",
                    _PREFIX + "task": task.describe(),
                    _PREFIX + "label": task.label,
                    _PREFIX + "wall_time_s": float(wall_time),
                    _PREFIX + "function": task.function,
                    _PREFIX + "code": code_digest(task.function),
                    _PREFIX + "package_version": _package_version(),
                    _PREFIX + "created": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
                    _PREFIX + "checksum": dataset_checksum(ds)}
        path = self.path_for(key, failed)
        path.parent.mkdir(parents=True, exist_ok=True)
        # Overwrite: the same key means the same answer, whichever concurrent writer wins.
        write_netcdf_atomic(ds, path, overwrite=True)
        with contextlib.suppress(FileNotFoundError):
            self.path_for(key, not failed).unlink()
        return path

    # -- copying between caches ------------------------------------------------------
    def copy_to(self, other: ResultCache, functions: tuple[str, ...] | None = None,
                keys: set[str] | None = None, include_failed: bool = False) -> CopyReport:
        """Copy this cache's valid entries that ``other`` lacks into ``other``.

        Used to keep the expensive results (the FEM solves behind VALIDATION.md) in a
        tracked directory and to seed a fresh working cache from it. Every source file is
        checked (key, status, checksum) before it is copied; a corrupt one is counted and
        left where it is, never copied (the source may be read-only or under version
        control). Copies are atomic (temporary file, then rename), so an interrupted copy
        leaves no half entry.

        Parameters
        ----------
        other
            Destination cache.
        functions
            Only tasks whose function name (``module:name``) ends with one of these, e.g.
            ``("fem_task",)``; None copies every function.
        keys
            Only these task keys; None copies every key.
        include_failed
            Also copy recorded failures (by default only successful results travel).
        """
        copied = present = corrupt = 0
        for path in sorted(self._files()):
            failed = path.name.endswith(_FAILED_SUFFIX)
            key = path.name[: -len(_FAILED_SUFFIX)] if failed else path.name[:-3]
            if (failed and not include_failed) or (keys is not None and key not in keys):
                continue
            ds, problem = self._check(key, path)
            if problem is not None:
                log.warning("cache entry %s is corrupt (%s): not copied", path, problem)
                corrupt += 1
                continue
            if functions is not None:
                function = json.loads(str(ds.attrs.get(_PREFIX + "task", "{}"))).get(
                    "function", "")
                if not function.endswith(tuple(functions)):
                    continue
            # A result the destination has is kept; a recorded failure there gives way to
            # a successful result (as a recompute would), never the reverse.
            if other.path_for(key).exists() or (failed and other.path_for(key, True).exists()):
                present += 1
                continue
            dest = other.path_for(key, failed)
            dest.parent.mkdir(parents=True, exist_ok=True)
            tmp = dest.with_name(f".{dest.name}.{os.getpid()}{TEMP_SUFFIX}")
            shutil.copyfile(path, tmp)
            os.replace(tmp, dest)
            with contextlib.suppress(FileNotFoundError):
                other.path_for(key, not failed).unlink()
            copied += 1
        return CopyReport(copied, present, corrupt)

    # -- maintenance ------------------------------------------------------------------
    def info(self) -> CacheInfo:
        """Location, number of entries (and failed ones), size on disk, stray temp files."""
        files = self._files()
        temps = self._temporaries()
        size = 0
        for p in files + temps:
            with contextlib.suppress(FileNotFoundError):
                size += p.stat().st_size
        n_failed = sum(p.name.endswith(_FAILED_SUFFIX) for p in files)
        return CacheInfo(self.directory, len(files), n_failed, len(temps), size)

    def _by_code(self) -> dict[str, list[Path]]:
        """Entry files grouped as "current", "other" or "unknown" code (see CodeReport)."""
        current: dict[str, str | None] = {}
        groups: dict[str, list[Path]] = {"current": [], "other": [], "unknown": []}
        for path in self._files():
            try:
                function, code = entry_code(path)
            except (OSError, RuntimeError):
                groups["unknown"].append(path)  # unreadable: corrupt, never a hit
                continue
            if function not in current:
                try:
                    current[function] = code_digest(function)
                except InputError:
                    current[function] = None
            if not code or current[function] is None:
                groups["unknown"].append(path)
            else:
                groups["current" if code == current[function] else "other"].append(path)
        return groups

    def code_report(self) -> CodeReport:
        """How many entries the current code computed, other code, or unknown code."""
        groups = self._by_code()
        return CodeReport(len(groups["current"]), len(groups["other"]), len(groups["unknown"]))

    def prune(self) -> int:
        """Delete the entries of other or unknown code (never hit again); their number."""
        groups = self._by_code()
        n = 0
        for path in groups["other"] + groups["unknown"]:
            with contextlib.suppress(FileNotFoundError):
                path.unlink()
                n += 1
        return n

    def clear(self, failed_only: bool = False) -> int:
        """Delete entries (only recorded failures if ``failed_only``) and stray temp files.

        Returns
        -------
        int
            Number of entries deleted (temporary files not counted).
        """
        n = 0
        for p in self._files():
            if failed_only and not p.name.endswith(_FAILED_SUFFIX):
                continue
            with contextlib.suppress(FileNotFoundError):
                p.unlink()
                n += 1
        for p in self._temporaries():
            with contextlib.suppress(FileNotFoundError):
                p.unlink()
        if self._root.is_dir():
            for sub in self._root.iterdir():
                with contextlib.suppress(OSError):
                    sub.rmdir()  # only succeeds when empty
        return n
