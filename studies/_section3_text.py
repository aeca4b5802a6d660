"""The prose blocks of ``templates/validation_section3.md``, section 3 of VALIDATION.md."""

from __future__ import annotations

from ._templates import render


def _s3(block: str, **fields) -> str:
    return render("validation_section3", block, **fields)
