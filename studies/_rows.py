"""Resumable studies: one JSON line per finished case, appended as the case ends, and
the study's Markdown report printed and written in one step.

A kill can cut only the line being written; that line is not valid JSON, so it is skipped
on reading and its case runs again. Everything finished before is kept.
"""

from __future__ import annotations

import json
from pathlib import Path


def read_rows(path: Path) -> list[dict]:
    """The finished cases in ``path`` (none if it does not exist yet)."""
    rows = []
    if path.exists():
        for line in path.read_text().splitlines():
            try:
                rows.append(json.loads(line))
            except json.JSONDecodeError:   # a line cut by a kill: that case runs again
                continue
    return rows


def append_row(path: Path, row: dict) -> None:
    """Print ``row`` and append it to ``path`` as one whole line."""
    text = json.dumps(row)
    print(text, flush=True)
    with path.open("a") as fh:
        fh.write(text + "\n")


def publish(text: str, path: Path | None, echo: bool = True) -> int:
    """Print a study's report (unless ``echo`` is false) and, when ``path`` is given, write
    it there atomically (a temporary file renamed over the old report); the exit status for
    ``main``."""
    if echo:
        print(text)
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_name(path.name + ".tmp")
        tmp.write_text(text)
        tmp.replace(path)
    return 0
