"""Cache keys: change with every answer-changing input, and with nothing else."""

from __future__ import annotations

import hashlib
import json

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from rubbercontact.errors import InputError
from rubbercontact.sweep import Task, code_digest, task_key
from rubbercontact.sweep import tasks as sweep_tasks
from rubbercontact.sweep.tasks import canonical

FN = "rubbercontact.sweep.examples:toy_kernel"

leaves = st.one_of(
    st.none(), st.booleans(), st.integers(-(2**70), 2**70),
    st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=8))
plain = st.recursive(
    leaves,
    lambda children: st.one_of(st.lists(children, max_size=4),
                               st.dictionaries(st.text(max_size=6), children, max_size=4)),
    max_leaves=20)
kwargs_st = st.dictionaries(st.text(min_size=1, max_size=8), plain, max_size=6)


def _reorder(value):
    """Same data, different representation: reversed dict order, lists as tuples."""
    if isinstance(value, dict):
        return {k: _reorder(value[k]) for k in reversed(list(value))}
    if isinstance(value, list):
        return tuple(_reorder(v) for v in value)
    return value


def _leaf_paths(value, path=()):
    if isinstance(value, dict):
        for k, v in value.items():
            yield from _leaf_paths(v, (*path, k))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from _leaf_paths(v, (*path, i))
    else:
        yield path


def _replace(value, path, new):
    if not path:
        return new
    head, rest = path[0], path[1:]
    if isinstance(value, dict):
        return {**value, head: _replace(value[head], rest, new)}
    return [*value[:head], _replace(value[head], rest, new), *value[head + 1:]]


@settings(max_examples=150, deadline=None)
@given(kwargs_st)
def test_key_ignores_dict_order_and_tuple_vs_list(kwargs):
    assert task_key(FN, kwargs) == task_key(FN, _reorder(kwargs))


@settings(max_examples=150, deadline=None)
@given(kwargs_st, st.data())
def test_key_changes_when_any_leaf_changes(kwargs, data):
    paths = [p for p in _leaf_paths(kwargs) if p]
    assume(paths)
    path = data.draw(st.sampled_from(paths))
    old = kwargs
    for p in path:
        old = old[p]
    new = data.draw(leaves)
    # "Different" means a different value or type: 1, 1.0 and True are different inputs.
    assume(json.dumps(canonical(new)) != json.dumps(canonical(old)))
    assert task_key(FN, _replace(kwargs, path, new)) != task_key(FN, kwargs)


@settings(max_examples=100, deadline=None)
@given(kwargs_st, st.text(min_size=1, max_size=8), plain)
def test_key_changes_when_an_argument_is_added(kwargs, name, value):
    assume(name not in kwargs)
    assert task_key(FN, {**kwargs, name: value}) != task_key(FN, kwargs)


@settings(max_examples=50, deadline=None)
@given(kwargs_st)
def test_key_changes_with_function_and_code(kwargs):
    base = task_key(FN, kwargs)
    code = code_digest(FN)
    assert task_key(FN, kwargs, code=code) == base  # the default code part is the digest
    assert task_key("rubbercontact.sweep.examples:other", kwargs, code=code) != base
    assert task_key(FN, kwargs, code=code + "0") != base


def test_numbers_are_typed_and_numpy_is_plain_python():
    keys = {task_key(FN, {"x": v}) for v in (1, 1.0, True)}
    assert len(keys) == 3  # int, float and bool are different inputs
    assert task_key(FN, {"x": np.float64(0.5)}) == task_key(FN, {"x": 0.5})
    assert task_key(FN, {"x": np.int32(7)}) == task_key(FN, {"x": 7})
    assert task_key(FN, {"x": np.array([[1.0, 2.0]])}) == task_key(FN, {"x": [(1.0, 2.0)]})
    assert task_key(FN, {"x": 0.1 + 0.2}) != task_key(FN, {"x": 0.3})
    assert task_key(FN, {"x": 2**70}) != task_key(FN, {"x": 2**70 + 1})


def test_key_is_sha256_of_documented_canonical_json():
    # Independent re-statement of the documented format.
    text = ('{"code":"c0de","function":"m:f",'
            '"kwargs":{"a":[{"i":"1"},{"f":"2.5"}],"b":"s","c":{"b":true}}}')
    assert task_key("m:f", {"c": True, "b": "s", "a": (1, 2.5)}, code="c0de") == \
        hashlib.sha256(text.encode()).hexdigest()


@settings(max_examples=50, deadline=None)
@given(kwargs_st)
def test_canonical_form_reads_back_to_the_same_key(kwargs):
    # A cached entry stores its task's canonical arguments; rebuilding the task from them
    # (to re-key it under a new code digest) must give the task's own key.
    rebuilt = sweep_tasks.plain(sweep_tasks.canonical(kwargs))
    assert task_key(FN, rebuilt, code="c") == task_key(FN, kwargs, code="c")


@pytest.mark.parametrize("kwargs, field", [
    ({"x": object()}, "kwargs['x']"),
    ({"x": [1, {2: 3}]}, "kwargs['x'][1]"),
    ({"x": {1.5j}}, "kwargs['x']"),
    ({"x": np.array([1j])}, "kwargs['x']"),
])
def test_non_plain_arguments_are_rejected_with_the_field_named(kwargs, field):
    with pytest.raises(InputError, match=field.replace("[", r"\[").replace("]", r"\]")):
        Task(FN, kwargs)


@pytest.mark.parametrize("path", ["toy_kernel", "a.b", "a:b:c", "", "1mod:f"])
def test_malformed_function_path_is_rejected(path):
    with pytest.raises(InputError, match="function"):
        Task(path, {})


def test_unknown_function_is_reported_when_keyed():
    with pytest.raises(InputError, match="no function 'nope'"):
        Task("rubbercontact.sweep.examples:nope", {}).key()
    with pytest.raises(InputError, match="cannot import module"):
        Task("rubbercontact.no_such_module:f", {}).key()
