"""Task descriptions and their content-addressed keys.

A :class:`Task` names a pure function by import path (``"package.module:function"``)
and gives its keyword arguments as plain data, so a task can be sent to any
Dask worker that has rubbercontact installed and stored next to its result.

Cache key
---------
``key = SHA-256( canonical JSON of {"function", "kwargs", "code"} )`` where

* ``function`` is the import path string;
* ``kwargs`` is canonicalised (:func:`canonical`): dict keys are sorted, tuples
  and numpy arrays become lists, numpy scalars become Python numbers, and every
  number is written with a type tag so that the key distinguishes ``1``
  (int), ``1.0`` (float) and ``True`` (bool). Floats are written with
  ``repr`` (shortest round-trip form), so two floats give the same key exactly
  when they are the same IEEE double (``0.0`` and ``-0.0`` differ; all NaNs are
  equal). *Why not fold ints into floats?* A false cache hit silently returns
  a wrong answer, while a spurious miss only costs one recomputation; configs
  coerced by pydantic have consistent types anyway.
* ``code`` is :func:`~rubbercontact.sweep.codehash.code_digest` of the function: a
  digest of the source it runs (its slice of its module and every module of the
  package it imports), so any change of the numerics is a miss. There is no version
  to bump by hand.

Whatever is *not* in the key must not change the answer: task functions must
treat a tuple and a list alike, and must not read files, clocks or globals
that are not in their arguments.
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib
import json
import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import InputError
from .codehash import code_digest

__all__ = ["Task", "canonical", "canonical_json", "key_of_canonical", "plain",
           "resolve_function", "task_key"]

_PATH_RE = re.compile(r"^[A-Za-z_][\w.]*:[A-Za-z_]\w*$")


def canonical(value: Any, where: str = "kwargs") -> Any:
    """Plain-data value in canonical, type-tagged, JSON-ready form.

    Parameters
    ----------
    value
        ``None``, bool, int, float, str, numpy scalar or array, list/tuple, or a
        dict with string keys, nested arbitrarily.
    where
        Name of the field, used in error messages (``kwargs['surface'][2]``).

    Returns
    -------
    Any
        ``None``/str unchanged; numbers as ``{"b": ...}``, ``{"i": "..."}`` or
        ``{"f": repr}``; sequences as lists; dicts as dicts (sorted on dump).

    Raises
    ------
    InputError
        A value that is not plain data (object, set, complex, bytes, ...) or a
        dict key that is not a string.
    """
    if value is None or isinstance(value, str):
        return value
    if isinstance(value, (bool, np.bool_)):
        return {"b": bool(value)}
    if isinstance(value, (int, np.integer)):
        # A string keeps arbitrary-size ints exact (JSON readers may round big numbers).
        return {"i": str(int(value))}
    if isinstance(value, (float, np.floating)):
        x = float(value)
        return {"f": "nan" if math.isnan(x) else repr(x)}
    if isinstance(value, np.ndarray):
        if value.dtype.kind not in "biufU":
            raise InputError(f"{where}: numpy arrays of dtype {value.dtype} are not "
                             f"supported in task arguments (use real numbers or strings)")
        return [canonical(v, f"{where}[{i}]") for i, v in enumerate(value.tolist())]
    if isinstance(value, (list, tuple)):
        return [canonical(v, f"{where}[{i}]") for i, v in enumerate(value)]
    if isinstance(value, Mapping):
        out = {}
        for k, v in value.items():
            if not isinstance(k, str):
                raise InputError(f"{where}: dict keys must be strings, got {k!r} "
                                 f"({type(k).__name__})")
            out[k] = canonical(v, f"{where}[{k!r}]")
        return out
    raise InputError(f"{where}: {type(value).__name__} value {value!r:.80} is not plain data; "
                     f"task arguments must be numbers, strings, None, lists or dicts")


def canonical_json(value: Any) -> str:
    """Canonical JSON text of ``value`` (see :func:`canonical`): sorted keys, no spaces."""
    return _dumps(canonical(value))


def _dumps(value: Any) -> str:
    return json.dumps(value, sort_keys=True, separators=(",", ":"), ensure_ascii=True,
                      allow_nan=False)


def resolve_function(path: str) -> Callable[..., Any]:
    """Import ``"package.module:function"`` and return the function.

    Raises
    ------
    InputError
        Malformed path, missing module or missing attribute.
    """
    if not isinstance(path, str) or not _PATH_RE.match(path):
        raise InputError(f"function: expected 'package.module:function', got {path!r}")
    module_name, func_name = path.split(":")
    try:
        module = importlib.import_module(module_name)
    except ModuleNotFoundError as exc:
        raise InputError(f"function: cannot import module {module_name!r} of {path!r}: "
                         f"{exc}") from exc
    func = getattr(module, func_name, None)
    if func is None or not callable(func):
        raise InputError(f"function: module {module_name!r} has no function {func_name!r}")
    return func


def plain(value: Any) -> Any:
    """Inverse of :func:`canonical`: type-tagged numbers back to Python numbers.

    Used to rebuild a task from the description stored with its cached result.
    """
    if isinstance(value, dict):
        if len(value) == 1:
            ((tag, text),) = value.items()
            if tag == "b" and isinstance(text, bool):
                return text
            if tag in ("i", "f") and isinstance(text, str):
                with contextlib.suppress(ValueError):
                    return int(text) if tag == "i" else float(text)
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, list):
        return [plain(v) for v in value]
    return value


def key_of_canonical(function: str, canonical_kwargs: Any, code: str) -> str:
    """SHA-256 key from already canonical arguments (:func:`canonical`) and a code digest."""
    payload = {"function": function, "kwargs": canonical_kwargs, "code": str(code)}
    return hashlib.sha256(_dumps(payload).encode("ascii")).hexdigest()


def task_key(function: str, kwargs: Mapping[str, Any], *, code: str | None = None) -> str:
    """SHA-256 hex digest identifying the answer of ``function(**kwargs)``.

    Parameters
    ----------
    function
        Import path ``"package.module:function"``.
    kwargs
        Keyword arguments (plain data).
    code
        Digest of the code the function runs; default
        :func:`~rubbercontact.sweep.codehash.code_digest` of ``function`` (read from its
        source, memoised per file).
    """
    if code is None:
        resolve_function(function)  # a wrong path fails with its own message first
        code = code_digest(function)
    return key_of_canonical(function, canonical(kwargs), code)


@dataclass(frozen=True)
class Task:
    """One unit of work: ``function(**kwargs)`` returning an ``xarray.Dataset``.

    Parameters
    ----------
    function
        Import path ``"package.module:function"`` of a pure function taking
        keyword arguments and returning an :class:`xarray.Dataset`.
    kwargs
        Keyword arguments as plain data (numbers, strings, None, lists/tuples,
        numpy arrays of numbers, dicts with string keys).
    label
        Human-readable name for progress and failure reports (not in the key).
    cost
        Expected seconds of the task, or None: a hint for the progress ETA
        (:mod:`.progress`), which weighs the tasks done and left by it; not in the key,
        not stored with the result (a hint changes no answer). The pipeline takes it from
        the per-task estimates of ``run --check`` (:mod:`rubbercontact.pipeline.costmodel`).

    Raises
    ------
    InputError
        Malformed function path or non-plain-data arguments.
    """

    function: str
    kwargs: Mapping[str, Any] = field(default_factory=dict)
    label: str = ""
    cost: float | None = field(default=None, compare=False)

    def __post_init__(self) -> None:
        if not isinstance(self.function, str) or not _PATH_RE.match(self.function):
            raise InputError(f"function: expected 'package.module:function', "
                             f"got {self.function!r}")
        if not isinstance(self.kwargs, Mapping):
            raise InputError(f"kwargs: expected a dict of keyword arguments, "
                             f"got {type(self.kwargs).__name__}")
        canonical(self.kwargs)  # fail early, with the field named, on non-plain data
        if not isinstance(self.label, str):
            raise InputError(f"label: expected a string, got {self.label!r}")
        if self.cost is not None and not (isinstance(self.cost, (int, float))
                                          and not isinstance(self.cost, bool)
                                          and math.isfinite(self.cost) and self.cost >= 0):
            raise InputError(f"cost: expected expected seconds >= 0 or None, "
                             f"got {self.cost!r}")

    def key(self, code: str | None = None) -> str:
        """Content-addressed cache key (the code part read from the function's source)."""
        return task_key(self.function, self.kwargs, code=code)

    def describe(self) -> str:
        """Canonical JSON description stored with the cached result."""
        return json.dumps({"function": self.function, "kwargs": canonical(self.kwargs),
                           "label": self.label}, sort_keys=True, separators=(",", ":"))

    @property
    def name(self) -> str:
        """The label, or the function name when there is none."""
        return self.label or self.function.split(":")[1]
