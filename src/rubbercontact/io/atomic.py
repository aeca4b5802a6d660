"""Atomic NetCDF writes: a reader never sees a half-written file.

The dataset is written to a temporary file in the *same directory* as the
target (so the final rename stays on one filesystem and is atomic), flushed to
disk with ``fsync``, then moved into place. A crash or kill at any moment
leaves either the old file, the complete new file, or no file, plus at worst a
stray hidden ``.<name>.*.tmp`` file that readers ignore.
"""

from __future__ import annotations

import contextlib
import os
import secrets
from pathlib import Path

import xarray as xr

__all__ = ["TEMP_SUFFIX", "write_netcdf_atomic"]

#: Suffix of the temporary files; anything ending in it is an interrupted write.
TEMP_SUFFIX = ".tmp"


def _fsync_directory(directory: Path) -> None:
    # Makes the rename itself durable on POSIX; not possible (nor needed) on Windows.
    if os.name != "posix":
        return
    fd = os.open(directory, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _local_write_lock() -> contextlib.AbstractContextManager[object]:
    # With a dask.distributed client alive in this process, xarray guards NetCDF writes
    # with a *distributed* lock (a scheduler round trip per write, ~10-40 ms). This file
    # is private to this process until renamed, so a local lock is enough.
    try:
        import dask
    except ImportError:
        return contextlib.nullcontext()
    return dask.config.set(scheduler="synchronous")


def write_netcdf_atomic(dataset: xr.Dataset, path: str | os.PathLike[str],
                        overwrite: bool = False) -> Path:
    """Write ``dataset`` to ``path`` as NetCDF-4, atomically.

    Parameters
    ----------
    dataset
        The dataset to write. Everything in it must be storable in NetCDF-4
        (real or integer numbers, strings; no complex values, no ``bool`` or
        ``dict`` attributes).
    path
        Target file. Its directory must exist.
    overwrite
        Replace an existing file. When False (default) an existing ``path``
        raises :class:`FileExistsError` and is left untouched.

    Returns
    -------
    Path
        The path written.

    Raises
    ------
    FileExistsError
        ``path`` exists and ``overwrite`` is False.
    FileNotFoundError
        The directory of ``path`` does not exist.
    """
    target = Path(path)
    directory = target.parent if str(target.parent) else Path(".")
    if not directory.is_dir():
        raise FileNotFoundError(f"path: directory {str(directory)!r} does not exist; "
                                f"create it first")
    if target.exists() and not overwrite:
        raise FileExistsError(f"path: {str(target)!r} already exists; pass overwrite=True "
                              f"(or --overwrite on the command line) to replace it")
    # Not tempfile.mkstemp: its 0600 mode would survive the rename. O_EXCL with a random
    # name is as safe and gives the file the usual umask-derived permissions.
    while True:
        tmp = directory / f".{target.name}.{secrets.token_hex(6)}{TEMP_SUFFIX}"
        try:
            os.close(os.open(tmp, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o666))
            break
        except FileExistsError:
            continue
    try:
        with _local_write_lock():
            dataset.to_netcdf(tmp, mode="w", format="NETCDF4", engine="netcdf4")
        # The netCDF library has closed the file; fsync forces its bytes to disk before the
        # rename publishes it, so a power cut cannot leave a renamed but empty file.
        with open(tmp, "rb+") as fh:
            os.fsync(fh.fileno())
        if overwrite:
            os.replace(tmp, target)
        else:
            # A hard link fails if the target appeared meanwhile: no-clobber without a race.
            try:
                os.link(tmp, target)
            except FileExistsError:
                raise FileExistsError(f"path: {str(target)!r} already exists (created while "
                                      f"writing); pass overwrite=True to replace it") from None
            except OSError:
                # Filesystems without hard links: a check-then-rename is the best we can do.
                if target.exists():
                    raise FileExistsError(f"path: {str(target)!r} already exists; pass "
                                          f"overwrite=True to replace it") from None
                os.replace(tmp, target)
            with contextlib.suppress(FileNotFoundError):
                tmp.unlink()
        _fsync_directory(directory)
    except BaseException:
        with contextlib.suppress(OSError):
            tmp.unlink()
        raise
    return target
