"""The README's validation table is the generated one, word for word (no hand-typed figures)."""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
START, END = "<!-- headline:start -->", "<!-- headline:end -->"


def test_readme_quotes_the_generated_headline_table():
    readme = (ROOT / "README.md").read_text()
    assert readme.count(START) == 1 and readme.count(END) == 1
    block = readme.split(START, 1)[1].split(END, 1)[0]
    generated = (ROOT / "docs" / "validation" / "headline.md").read_text()
    assert block.strip() == generated.strip(), (
        "README.md's validation table differs from docs/validation/headline.md; "
        "re-render with `python -m studies validate`, never edit either by hand")


def test_findings_include_the_generated_table_instead_of_quoting_it():
    findings = (ROOT / "docs" / "findings.md").read_text()
    assert "```{include} validation/headline.md" in findings
