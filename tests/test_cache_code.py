"""The code part of the cache key: an edit of the numerics is a miss, never a stale hit.

A toy package is written to a temporary directory; its task function calls a helper in
another module through a relative import. The tests edit its source the way a developer
would and check what the cache serves.
"""

from __future__ import annotations

import importlib
import os
import sys
import textwrap
from pathlib import Path

import pytest
import xarray as xr

from rubbercontact.sweep import ExecutorConfig, ResultCache, Task, code_digest, run_sweep
from rubbercontact.sweep.codehash import package_digest

SYNC = ExecutorConfig(synchronous=True)
FN = "toyrc.tasks:kernel"

FILES = {
    "__init__.py": '"""Toy package."""\n',
    "sub/__init__.py": 'from .laws import scale\n',
    "sub/laws.py": 'def scale(x):\n    return 2.0 * x\n',
    "sub/other.py": 'def unused():\n    return 0\n',
    "physics.py": '''
        """Helpers."""


        def friction(velocity):
            """The toy law."""
            return 0.5 * velocity  # a comment
        ''',
    "unrelated.py": '''
        def other():
            return 1
        ''',
    "tasks.py": '''
        import xarray as xr

        from .physics import friction
        from .sub import scale

        SCALE = 2.0


        def kernel(velocity):
            return xr.Dataset({"mu": ((), SCALE * friction(scale(velocity) / 2.0))})


        def other_task(velocity):
            return xr.Dataset({"mu": ((), velocity)})
        ''',
}


def _write(root: Path, name: str, text: str) -> None:
    path = root / "toyrc" / name
    old = path.stat().st_mtime_ns if path.exists() else 0
    path.write_text(textwrap.dedent(text))
    # The digest is memoised on (mtime, size): make the edit visible within one clock tick.
    os.utime(path, ns=(old + 10**9, old + 10**9))
    importlib.invalidate_caches()


@pytest.fixture
def toy(tmp_path, monkeypatch):
    (tmp_path / "toyrc" / "sub").mkdir(parents=True)
    for name, text in FILES.items():
        _write(tmp_path, name, text)
    monkeypatch.syspath_prepend(str(tmp_path))
    yield tmp_path
    for mod in [m for m in sys.modules if m == "toyrc" or m.startswith("toyrc.")]:
        del sys.modules[mod]


def _edit(root: Path, name: str, old: str, new: str) -> None:
    text = (root / "toyrc" / name).read_text()
    assert old in text
    _write(root, name, text.replace(old, new))
    for mod in [m for m in sys.modules if m == "toyrc" or m.startswith("toyrc.")]:
        del sys.modules[mod]  # the next run imports the edited code, as a new process would


def _mu(cache: ResultCache) -> tuple[float, str]:
    res = run_sweep([Task(FN, {"velocity": 1.0})], cache=cache, executor=SYNC, progress=False)
    out = res.results[0]
    assert isinstance(out, xr.Dataset)
    return float(out["mu"]), res.sources[0]


def test_an_edit_of_a_called_helper_is_a_miss_and_never_stale(toy, tmp_path):
    cache = ResultCache(tmp_path / "cache")
    assert _mu(cache) == (1.0, "computed")
    assert _mu(cache) == (1.0, "cache")
    _edit(toy, "physics.py", "0.5 * velocity", "0.25 * velocity")
    # The old answer (1.0) is in the cache under the old key; the new code must not get it.
    assert _mu(cache) == (0.5, "computed")


def test_an_edit_of_a_module_constant_the_task_uses_is_a_miss(toy):
    before = code_digest(FN)
    _edit(toy, "tasks.py", "SCALE = 2.0", "SCALE = 3.0")
    assert code_digest(FN) != before


def test_what_the_task_does_not_run_leaves_the_key(toy):
    before = code_digest(FN)
    # comments and docstrings
    _edit(toy, "physics.py", "# a comment", "# another comment")
    _edit(toy, "physics.py", '"""The toy law."""', '"""The toy law, better said."""')
    # another task of the same module, and a module the task does not import
    _edit(toy, "tasks.py", "((), velocity)", "((), 2 * velocity)")
    _edit(toy, "unrelated.py", "return 1", "return 2")
    assert code_digest(FN) == before


def test_the_parent_package_is_part_of_the_code(toy):
    # Importing toyrc.tasks runs toyrc/__init__.py: a statement there can change answers.
    before = code_digest(FN)
    _edit(toy, "__init__.py", '"""Toy package."""\n', '"""Toy package."""\nGRAVITY = 9.81\n')
    assert code_digest(FN) != before


def test_cache_reports_and_prunes_entries_of_other_code(toy, tmp_path):
    cache = ResultCache(tmp_path / "cache")
    _mu(cache)
    report = cache.code_report()
    assert (report.current, report.other, report.unknown) == (1, 0, 0)
    _edit(toy, "physics.py", "0.5 * velocity", "0.25 * velocity")
    _mu(cache)
    report = cache.code_report()
    assert (report.current, report.other) == (1, 1)
    assert cache.prune() == 1
    assert cache.code_report().other == 0 and _mu(cache)[1] == "cache"


def test_a_name_from_a_package_counts_through_its_defining_module(toy):
    # `from .sub import scale`: sub/laws.py defines it and counts; a new export of the
    # package, or a module of it the task does not use, does not.
    before = code_digest(FN)
    _edit(toy, "sub/__init__.py", "from .laws import scale\n",
          "from .laws import scale\nfrom .other import unused\n")
    _edit(toy, "sub/other.py", "return 0", "return 1")
    assert code_digest(FN) == before
    _edit(toy, "sub/laws.py", "2.0 * x", "3.0 * x")
    assert code_digest(FN) != before


def test_package_digest_follows_any_module(toy):
    before = package_digest("toyrc")
    _edit(toy, "unrelated.py", "return 1", "return 2")
    assert package_digest("toyrc") != before


def test_the_package_tasks_have_a_code_digest():
    # Every task the pipeline runs must have a readable source (static imports only).
    for fn in ("rubbercontact.hybrid.tasks:fem_task", "rubbercontact.hybrid.tasks:halfspace_task",
               "rubbercontact.meanfield.tasks:meanfield_task"):
        assert len(code_digest(fn)) == 64
