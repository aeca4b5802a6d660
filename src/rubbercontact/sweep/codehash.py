"""The code part of a task's cache key: a digest of the source the task runs.

A cached answer is the answer of a function *and of the code it calls*. A hand-bumped
version string forgets changes (the mean-field task's version stayed through five commits
that changed its answers, and the cache served the old ones), so the key's code part is
read from the source instead:

* the **task's slice** of its own module: the task function, and the module's top-level
  functions, classes and constants that it uses, transitively (a task module may hold
  several tasks: editing the FEM task does not invalidate the half-space task's results);
* every **module of the same package** that the slice imports, with the modules those
  import, and so on (:func:`module_closure`): a name taken from a package counts through
  the submodule that defines it, and a package's ``__init__`` (Python runs it on import)
  through its statements other than imports — so a new export of a package leaves the
  keys of tasks that do not use it.

Imports are found by reading the source (``import`` and ``from ... import`` at any depth,
absolute and relative), never by running it; a dynamic ``importlib.import_module(name)``
is not followed, so task code must import what it computes with statically.

What is hashed is the syntax tree without docstrings (``ast.dump``), so comments,
formatting and docstrings do not change a key; any change of a statement does. Modules of
other packages (numpy, scipy) are not part of the digest: a dependency upgrade that moves
results by round-off is not a change of the method. Per-file results are memoised on the
file's modification time and size, so a key costs a few ``stat`` calls once the package
has been read.
"""

from __future__ import annotations

import ast
import hashlib
import importlib.util
import sys
from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError

__all__ = ["code_digest", "module_closure", "package_digest"]


@dataclass(frozen=True)
class _Import:
    """``module`` imported, with the ``names`` taken from it (None: the module itself, or
    ``*``: whatever of it is used)."""

    module: str
    names: tuple[str, ...] | None


@dataclass(frozen=True)
class _Parsed:
    """One source file read once: its tree, its docstring-free digest (whole, and without
    its import statements for a package's ``__init__``), its imports and, for a package,
    the import that binds each name it re-exports."""

    tree: ast.Module
    digest: str
    own: str
    imports: tuple[_Import, ...]
    exports: dict[str, _Import]


_FILES: dict[tuple[str, int, int], _Parsed] = {}


def _strip_docstrings(tree: ast.AST) -> ast.AST:
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if (isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
                and body and isinstance(body[0], ast.Expr)
                and isinstance(body[0].value, ast.Constant)
                and isinstance(body[0].value.value, str)):
            node.body = body[1:] or [ast.Pass()]
    return tree


def _dump(node: ast.AST) -> str:
    return ast.dump(node, annotate_fields=False, include_attributes=False)


def _module_file(name: str) -> Path | None:
    """The source file of module ``name`` (a package's ``__init__.py``), without importing
    it; None for a name that is not a module (``from pkg import some_function``)."""
    try:
        spec = importlib.util.find_spec(name)
    except (ImportError, ValueError, AttributeError):
        return None
    if spec is None or not spec.origin or not spec.origin.endswith(".py"):
        return None
    return Path(spec.origin)


def _is_package(path: Path) -> bool:
    return path.name == "__init__.py"


def _base(sub: ast.ImportFrom, module: str, is_package: bool) -> str:
    if not sub.level:
        return sub.module or ""
    parts = (module if is_package else module.rpartition(".")[0]).split(".")
    base = ".".join(parts[: len(parts) - sub.level + 1])
    return f"{base}.{sub.module}" if sub.module else base


def _imports(node: ast.AST, module: str, is_package: bool) -> list[_Import]:
    """The imports anywhere in ``node``, with absolute module names."""
    out: list[_Import] = []
    for sub in ast.walk(node):
        if isinstance(sub, ast.Import):
            out.extend(_Import(alias.name, None) for alias in sub.names)
        elif isinstance(sub, ast.ImportFrom):
            names = tuple(alias.name for alias in sub.names)
            out.append(_Import(_base(sub, module, is_package), None if "*" in names else names))
    return out


def _exports(tree: ast.Module, module: str) -> dict[str, _Import]:
    """For a package's ``__init__``: the top-level ``from X import name`` binding each name."""
    out: dict[str, _Import] = {}
    for stmt in tree.body:
        if isinstance(stmt, ast.ImportFrom):
            base = _base(stmt, module, True)
            for alias in stmt.names:
                if alias.name != "*":
                    out[alias.asname or alias.name] = _Import(base, (alias.name,))
    return out


def _own(tree: ast.Module) -> ast.Module:
    """The statements of a module that are not imports or ``__all__``: what an
    ``__init__`` adds beyond the names it gathers from its submodules."""
    body = [s for s in tree.body
            if not isinstance(s, (ast.Import, ast.ImportFrom))
            and not (isinstance(s, ast.Assign)
                     and any(isinstance(t, ast.Name) and t.id == "__all__" for t in s.targets))]
    return ast.Module(body=body, type_ignores=[])


def _parse(path: Path, module: str) -> _Parsed:
    st = path.stat()
    memo = (str(path), st.st_mtime_ns, st.st_size)
    parsed = _FILES.get(memo)
    if parsed is None:
        try:
            tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        except (OSError, SyntaxError, UnicodeDecodeError) as exc:
            raise InputError(f"cache key: cannot read the source of {module} ({path}): "
                             f"{exc}") from exc
        stripped = _strip_docstrings(ast.parse(ast.unparse(tree)))
        package = _is_package(path)
        parsed = _Parsed(tree, _sha(_dump(stripped)), _sha(_dump(_own(stripped))),
                         tuple(_imports(tree, module, package)),
                         _exports(tree, module) if package else {})
        _FILES[memo] = parsed
    return parsed


def _sha(text: str) -> str:
    return hashlib.sha256(text.encode()).hexdigest()


def _in_package(name: str, root: str) -> bool:
    return name == root or name.startswith(root + ".")


def _with_parents(name: str, root: str) -> list[str]:
    parts = name.split(".")
    return [".".join(parts[:i]) for i in range(1, len(parts) + 1)
            if _in_package(".".join(parts[:i]), root)]


def module_closure(imports: list[_Import], root: str) -> dict[str, str]:
    """``{module: digest}`` of what ``imports`` bring in from package ``root``, transitively.

    A module imported as a whole (``import pkg.mod``, ``from pkg import mod``) counts with
    its source and everything it imports. Names taken from a package
    (``from ..roughness import SineSeries``) count through the submodule that defines them
    (the package ``__init__``'s re-export is followed), plus the ``__init__``'s own
    statements other than imports; so are the parent packages of every module counted,
    which Python runs on import. A new export added to a package therefore does not
    change the digest of tasks that do not use it.
    """
    seen: dict[str, str] = {}
    done: set[tuple[str, tuple[str, ...] | None]] = set()
    todo = [(i.module, i.names) for i in imports if _in_package(i.module, root)]
    while todo:
        name, names = todo.pop()
        if (name, names) in done or name in seen:
            continue
        done.add((name, names))
        path = _module_file(name)
        if path is None:  # not a module (an attribute of one): its module counts it
            continue
        parsed = _parse(path, name)
        todo.extend((p, ()) for p in _with_parents(name, root)[:-1])
        if not _is_package(path) or names is None:
            seen[name] = parsed.digest
            todo.extend((i.module, i.names) for i in parsed.imports
                        if _in_package(i.module, root))
            continue
        seen.setdefault(f"{name}[own]", parsed.own)
        for n in names:
            sub = f"{name}.{n}"
            if _module_file(sub) is not None:
                todo.append((sub, None))
            elif n in parsed.exports and _in_package(parsed.exports[n].module, root):
                todo.append((parsed.exports[n].module, parsed.exports[n].names))
    return seen


def _top_level(tree: ast.Module) -> dict[str, ast.stmt]:
    """Top-level statement defining each name (functions, classes, assignments)."""
    defs: dict[str, ast.stmt] = {}
    for stmt in tree.body:
        if isinstance(stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            defs[stmt.name] = stmt
        elif isinstance(stmt, (ast.Assign, ast.AnnAssign)):
            targets = stmt.targets if isinstance(stmt, ast.Assign) else [stmt.target]
            for t in targets:
                for n in ast.walk(t):
                    if isinstance(n, ast.Name):
                        defs[n.id] = stmt
    return defs


def _import_bindings(tree: ast.Module) -> dict[str, ast.stmt]:
    """Top-level import statement binding each name."""
    out: dict[str, ast.stmt] = {}
    for stmt in tree.body:
        if isinstance(stmt, (ast.Import, ast.ImportFrom)):
            for alias in stmt.names:
                out[(alias.asname or alias.name).split(".")[0]] = stmt
    return out


def _slice(tree: ast.Module, function: str) -> list[ast.stmt]:
    """The statements of ``tree`` that ``function`` uses, transitively (itself first)."""
    defs = _top_level(tree)
    if function not in defs:
        raise InputError(f"cache key: no top-level function {function!r} in its module")
    binds = _import_bindings(tree)
    used: dict[int, ast.stmt] = {}
    todo = [defs[function]]
    while todo:
        stmt = todo.pop()
        if id(stmt) in used:
            continue
        used[id(stmt)] = stmt
        for n in ast.walk(stmt):
            if isinstance(n, ast.Name):
                for table in (defs, binds):
                    dep = table.get(n.id)
                    if dep is not None and id(dep) not in used:
                        todo.append(dep)
    return sorted(used.values(), key=lambda s: s.lineno)


_SLICES: dict[tuple[str, int, int, str], tuple[str, list[_Import]]] = {}


def _task_slice(path: Path, module: str, name: str) -> tuple[str, list[_Import]]:
    """The dump of ``name``'s slice of its module and the imports it makes, memoised on
    the file's modification time and size like :func:`_parse` (the cache stores the
    digest with every entry: re-slicing per entry cost about 10 ms)."""
    st = path.stat()
    memo = (str(path), st.st_mtime_ns, st.st_size, name)
    if memo not in _SLICES:
        parsed = _parse(path, module)
        stmts = _slice(_strip_docstrings(ast.parse(ast.unparse(parsed.tree))), name)
        _SLICES[memo] = (_dump(ast.Module(body=stmts, type_ignores=[])),
                         [i for s in stmts for i in _imports(s, module, _is_package(path))])
    return _SLICES[memo]


def code_digest(function: str) -> str:
    """SHA-256 of the code that ``"package.module:function"`` runs (see the module doc).

    Raises
    ------
    InputError
        The module's source cannot be found or read, or has no such function.
    """
    module, _, name = function.partition(":")
    path = _module_file(module)
    if path is None:
        if module in sys.builtin_module_names:
            # Built in (``builtins:dict``): the interpreter is its code.
            return hashlib.sha256(f"{function}:{sys.version}".encode()).hexdigest()
        raise InputError(f"cache key: cannot find the source of module {module!r} "
                         f"(of {function!r})")
    root = module.split(".")[0]
    own, imported = _task_slice(path, module, name)
    parents = [_Import(p, ()) for p in _with_parents(module, root) if p != module]
    closure = module_closure(imported + parents, root)
    closure.pop(module, None)  # the task's own module enters through its slice only
    h = hashlib.sha256(own.encode())
    for mod in sorted(closure):
        h.update(f"\n{mod}:{closure[mod]}".encode())
    return h.hexdigest()


def package_digest(package: str = "rubbercontact") -> str:
    """SHA-256 over every module of ``package`` (what a Dask worker must share with its
    client so that both compute the same answers under the same keys)."""
    path = _module_file(package)
    if path is None or not _is_package(path):
        raise InputError(f"cache key: {package!r} is not a package with sources")
    h = hashlib.sha256()
    base = path.parent
    for file in sorted(base.rglob("*.py")):
        rel = file.relative_to(base).with_suffix("")
        parts = [package, *rel.parts]
        if parts[-1] == "__init__":
            parts = parts[:-1]
        h.update(f"\n{'.'.join(parts)}:{_parse(file, '.'.join(parts)).digest}".encode())
    return h.hexdigest()


def _reset() -> None:
    """Forget the memoised files (tests that rewrite a file within one mtime tick)."""
    _FILES.clear()
    _SLICES.clear()

