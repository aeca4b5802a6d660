"""Any profile file: :func:`detect_format` and :func:`read_profiles`."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from ...errors import InputError
from .captif import is_captif, read_captif
from .common import Format, NanPolicy
from .container import Profiles
from .text import read_text
from .topography import TOPOGRAPHY_EXTENSIONS, read_topography_file


def detect_format(path: str | Path) -> str:
    """The reader a file needs, from its head and extension.

    Parameters
    ----------
    path
        The file.

    Returns
    -------
    str
        ``"captif"`` if its head holds the CAPTIF data marker, ``"topography"`` if its
        extension is in :data:`TOPOGRAPHY_EXTENSIONS`, else ``"text"``.
    """
    path = Path(path)
    if is_captif(path):
        return "captif"
    if path.suffix.lower() in TOPOGRAPHY_EXTENSIONS:
        return "topography"
    return "text"


def read_profiles(paths: str | Path | Sequence[str | Path], *, format: Format = "auto",
                  unit: str | None = None, dx: float | None = None,
                  nan: NanPolicy = "windows", window: float = 16.0,
                  window_overlap: float = 0.5, despike: bool = False,
                  despike_window: int = 7, despike_k: float = 5.0,
                  **format_options: Any) -> Profiles:
    """Read one or many files into one :class:`Profiles` (all must share the step).

    Parameters
    ----------
    paths
        One file or several.
    format
        ``"auto"`` picks CAPTIF by its ``*****DATA*****`` line, SurfaceTopography by
        the extension (:data:`TOPOGRAPHY_EXTENSIONS`), else text
        (:func:`detect_format`); or ``"text"``, ``"captif"``, ``"topography"``.
    unit
        Unit of the numbers in the files (default mm; instrument files state their
        own; CAPTIF files are in mm).
    dx
        Sampling step [mm] for text files without a position column.
    nan, window, window_overlap
        Dropout policy, by default gap-free windows of 16 mm (package docstring).
    despike, despike_window, despike_k
        Whether to apply the Hampel filter (:func:`despike`), and its settings.
    **format_options
        Passed to the reader: ``x_column``, ``columns`` for text; ``trim``,
        ``plate_margin`` for CAPTIF; ``channel`` for instrument files.

    Returns
    -------
    Profiles
        The scans of all files, with one source dict per file.

    Raises
    ------
    FileNotFoundError
        If a file does not exist.
    InputError
        If no file is given, the format or unit is wrong, a reader fails, or the
        files' sampling steps differ by more than 1 %.
    """
    if isinstance(paths, str | Path):
        paths = [paths]
    paths = [Path(p) for p in paths]
    if not paths:
        raise InputError("paths: no file given")
    common = {"nan": nan, "window": window, "window_overlap": window_overlap,
              "despike": despike, "despike_window": despike_window, "despike_k": despike_k}
    parts: list[Profiles] = []
    for p in paths:
        if not p.exists():
            raise FileNotFoundError(f"{p}: no such file")
        fmt = detect_format(p) if format == "auto" else format
        if fmt == "captif":
            if unit not in (None, "mm"):
                raise InputError(f"unit: CAPTIF files are in mm, got {unit!r}")
            parts.append(read_captif(p, **common, **format_options))
        elif fmt == "text":
            parts.append(read_text(p, unit=unit or "mm", dx=dx, **common, **format_options))
        elif fmt == "topography":
            parts.append(read_topography_file(p, unit=unit, dx=dx, **common,
                                              **format_options))
        else:
            raise InputError(f"format: expected auto, text, captif or topography, got "
                             f"{format!r}")
    dx0 = parts[0].dx
    for p, part in zip(paths[1:], parts[1:], strict=True):
        if not math.isclose(part.dx, dx0, rel_tol=0.01):
            raise InputError(f"{p.name}: sampling step {part.dx:g} mm differs from "
                             f"{paths[0].name} ({dx0:g} mm); statistics need one step")
    return Profiles(tuple(z for part in parts for z in part.profiles), dx0,
                    tuple(s for part in parts for s in part.sources))
