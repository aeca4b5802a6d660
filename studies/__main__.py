"""``python -m studies [NAME [ARGS...]]``: run one study; without NAME, list them.

A study is any ``studies/<name>.py`` whose name does not start with ``_`` (those are shared
helpers); it defines ``DESCRIPTION`` (one line) and ``main(argv) -> int``. The list is read
from the files, so adding a study needs no edit here (studies/README.md).
"""

from __future__ import annotations

import ast
import importlib
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


def discover() -> dict[str, str]:
    """``{name: DESCRIPTION}`` of every study, read without importing it.

    Raises
    ------
    SystemExit
        A study file without a literal one-line ``DESCRIPTION`` or without ``main``.
    """
    out = {}
    for path in sorted(HERE.glob("*.py")):
        if path.stem.startswith("_"):
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        description, has_main = None, False
        for node in tree.body:
            if isinstance(node, ast.Assign) and any(
                    isinstance(t, ast.Name) and t.id == "DESCRIPTION" for t in node.targets):
                description = ast.literal_eval(node.value)
            elif isinstance(node, ast.FunctionDef) and node.name == "main":
                has_main = True
        if not (isinstance(description, str) and "\n" not in description and has_main):
            raise SystemExit(f"{path.relative_to(ROOT)}: a study defines a one-line "
                             "DESCRIPTION and main(argv) -> int (studies/README.md)")
        out[path.stem] = description
    return out


def _listing(studies: dict[str, str]) -> str:
    width = max(map(len, studies))
    return "\n".join(["usage: python -m studies NAME [ARGS...]   (NAME --help for its options)",
                      "", *(f"  {name:<{width}}  {text}" for name, text in studies.items())])


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    studies = discover()
    if not argv or argv[0] in ("-h", "--help", "list"):
        print(_listing(studies))
        return 0
    name, args = argv[0], argv[1:]
    if name not in studies:
        print(f"unknown study {name!r}\n\n{_listing(studies)}", file=sys.stderr)
        return 2
    # the studies run against this checkout's src/, not another installed copy
    sys.path.insert(0, str(ROOT / "src"))
    module = importlib.import_module(f"studies.{name}")
    sys.argv = [f"python -m studies {name}", *args]    # argparse's prog in --help
    return int(module.main(args) or 0)


if __name__ == "__main__":
    sys.exit(main())
