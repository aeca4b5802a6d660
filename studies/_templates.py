"""Report prose kept out of the code: ``studies/templates/<name>.md``, filled from results.

A template file holds named blocks, each starting with a line ``<!-- block: NAME -->``
(text before the first block is a comment for the reader). A block is Markdown with
``${field}`` placeholders (:class:`string.Template`; ``$$`` is a literal ``$``). Lines are
wrapped for reading: within a paragraph (lines between blank lines) they are joined with
single spaces, except table lines (starting with ``|``), which stay lines; paragraphs are
separated by one blank line. A block may start with ``${...}`` or end without a full stop:
the study composes sentences from blocks. Every field must be given (a missing one raises
``KeyError``), so a template cannot silently print a stale number.
"""

from __future__ import annotations

import functools
import re
from pathlib import Path
from string import Template

TEMPLATES = Path(__file__).resolve().parent / "templates"
_BLOCK = re.compile(r"^<!-- block: ([a-z0-9_]+) -->$")


def _paragraph(lines: list[str]) -> str:
    if lines[0].startswith("|"):
        return "\n".join(lines)
    return " ".join(line.strip() for line in lines)


def _unwrap(text: str) -> str:
    paragraphs, current = [], []
    for line in text.splitlines():
        if line.strip():
            current.append(line)
        elif current:
            paragraphs.append(_paragraph(current))
            current = []
    if current:
        paragraphs.append(_paragraph(current))
    return "\n\n".join(paragraphs)


@functools.cache
def blocks(name: str) -> dict[str, Template]:
    """The blocks of ``templates/<name>.md`` by name.

    Raises
    ------
    ValueError
        A block name that repeats.
    """
    out: dict[str, list[str]] = {}
    current = None
    for line in (TEMPLATES / f"{name}.md").read_text(encoding="utf-8").splitlines():
        match = _BLOCK.match(line)
        if match:
            current = match.group(1)
            if current in out:
                raise ValueError(f"templates/{name}.md: block {current!r} repeats")
            out[current] = []
        elif current is not None:
            out[current].append(line)
    return {k: Template(_unwrap("\n".join(v))) for k, v in out.items()}


def render(name: str, block: str, **fields: object) -> str:
    """Block ``block`` of ``templates/<name>.md`` with ``fields`` filled in."""
    return blocks(name)[block].substitute({k: str(v) for k, v in fields.items()})
