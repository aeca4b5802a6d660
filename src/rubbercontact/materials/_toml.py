"""A minimal TOML writer for plain data (material files): exact float round trip.

Writes strings, booleans, integers, floats (``repr``: shortest form that reads back to the
same double; ``inf``/``nan`` as TOML spells them), lists of those, and nested tables.
``None`` has no TOML form and is rejected.
"""

from __future__ import annotations

import json
import math
import numbers

from ..errors import InputError


def _value(key: str, v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        f = float(v)
        if math.isnan(f):
            return "nan"
        if math.isinf(f):
            return "inf" if f > 0 else "-inf"
        return repr(f)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)  # a JSON string is a TOML basic string
    if isinstance(v, list | tuple):
        return "[" + ", ".join(_value(key, x) for x in v) + "]"
    raise InputError(f"{key}: {type(v).__name__} value {v!r} cannot be written to TOML")


def _key(k: str) -> str:
    if k and all(c.isalnum() or c in "_-" for c in k):
        return k
    return json.dumps(k, ensure_ascii=False)


def dumps(data: dict, _prefix: str = "") -> str:
    """TOML text of ``data`` (a dict with string keys)."""
    lines, tables = [], []
    for k, v in data.items():
        if not isinstance(k, str):
            raise InputError(f"{_prefix}{k!r}: TOML keys must be strings")
        if isinstance(v, dict):
            tables.append((k, v))
        else:
            lines.append(f"{_key(k)} = {_value(_prefix + k, v)}")
    out = "\n".join(lines) + ("\n" if lines else "")
    for k, v in tables:
        name = f"{_prefix}{_key(k)}"
        out += f"\n[{name}]\n" + dumps(v, name + ".")
    return out
