"""The studies runner finds every study by the convention of studies/README.md, and every
template block is rendered by a study (the studies' own tests: tests/ tests the package)."""

import ast
import subprocess
import sys
from pathlib import Path

import pytest

from studies.__main__ import discover, main

ROOT = Path(__file__).resolve().parents[2]

STUDY_FILES = sorted(p for p in (ROOT / "studies").glob("*.py") if not p.stem.startswith("_"))


def test_every_study_file_is_discovered_with_its_description():
    studies = discover()
    assert sorted(studies) == [p.stem for p in STUDY_FILES]
    assert "validate" in studies
    assert all(text and len(text) <= 120 for text in studies.values())


@pytest.mark.parametrize("path", STUDY_FILES, ids=[p.stem for p in STUDY_FILES])
def test_study_main_takes_argv(path):
    tree = ast.parse(path.read_text(encoding="utf-8"))
    (fn,) = [n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "main"]
    assert [a.arg for a in fn.args.args] == ["argv"], "main(argv) -> int"


def test_a_study_without_description_is_refused(tmp_path, monkeypatch):
    import studies.__main__ as runner

    (tmp_path / "nodesc.py").write_text("def main(argv=None):\n    return 0\n")
    monkeypatch.setattr(runner, "HERE", tmp_path)
    monkeypatch.setattr(runner, "ROOT", tmp_path.parent)
    with pytest.raises(SystemExit, match="DESCRIPTION"):
        runner.discover()


def test_unknown_study_exits_2_and_lists_the_studies(capsys):
    assert main(["no_such_study"]) == 2
    assert "validate" in capsys.readouterr().err


def test_runner_runs_a_study_from_the_command_line():
    out = subprocess.run([sys.executable, "-m", "studies", "validate", "--help"], cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("usage: python -m studies validate")


def test_template_blocks_unwrap_paragraphs_keep_tables_and_refuse_missing_fields(tmp_path,
                                                                                  monkeypatch):
    import studies._templates as templates

    (tmp_path / "t.md").write_text("a comment\n<!-- block: one -->\nA ${x}\nwrapped line.\n\n"
                                   "| a | b |\n|---|---|\n<!-- block: two -->\nno fields\n")
    monkeypatch.setattr(templates, "TEMPLATES", tmp_path)
    templates.blocks.cache_clear()
    try:
        assert templates.render("t", "one", x=1.5) == "A 1.5 wrapped line.\n\n| a | b |\n|---|---|"
        assert templates.render("t", "two") == "no fields"
        with pytest.raises(KeyError):
            templates.render("t", "one")
    finally:
        templates.blocks.cache_clear()


def test_every_template_block_is_used_by_a_study():
    from studies._templates import TEMPLATES, blocks

    literals = {n.value for p in (ROOT / "studies").glob("*.py")
                for n in ast.walk(ast.parse(p.read_text(encoding="utf-8")))
                if isinstance(n, ast.Constant) and isinstance(n.value, str)}
    for path in sorted(TEMPLATES.glob("*.md")):
        assert path.stem in literals, f"{path.name} is not rendered by any study"
        unused = sorted(set(blocks(path.stem)) - literals)
        assert not unused, f"{path.name}: blocks {unused} are not rendered by any study"
