"""The ``[execution]`` and ``[output]`` tables: where the run computes and what it writes."""

from __future__ import annotations

from pathlib import Path

from pydantic import Field

from ..inputs import Strict as _Strict


class ExecutionConfig(_Strict):
    workers: int = Field(1, ge=1, le=4096)
    threads_per_worker: int = Field(1, ge=1, le=256)
    scheduler: str | None = Field(None, pattern=r"^(tcp|tls|inproc)://.+",
                                  description="address of an existing Dask scheduler")
    cache: Path | None = Field(None, description="result cache directory")


class OutputConfig(_Strict):
    directory: Path = Path("results")
    figures: bool = True
    overwrite: bool = False

