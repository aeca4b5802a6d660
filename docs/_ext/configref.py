"""``.. config-reference::``: the TOML configuration's keys, from the pydantic models.

Renders one table per TOML table of :class:`rubbercontact.config.RunConfig` (key, type and
allowed values, default, description), read from the models at build time, so the page
follows the code by itself.
"""

from __future__ import annotations

import types
import typing
from enum import Enum

from docutils import nodes
from docutils.statemachine import StringList
from pydantic import BaseModel
from pydantic_core import PydanticUndefined
from sphinx.util.docutils import SphinxDirective


def _is_model(tp) -> bool:
    return isinstance(tp, type) and issubclass(tp, BaseModel)


def _args(tp):
    return [a for a in typing.get_args(tp) if a is not type(None)]


def _models_in(tp) -> list[type[BaseModel]]:
    if _is_model(tp):
        return [tp]
    return [m for a in _args(tp) for m in _models_in(a)]


def _type_text(tp) -> str:
    origin = typing.get_origin(tp)
    if tp is type(None):
        return "none"
    if origin is typing.Literal:
        return " | ".join(f'``"{a}"``' if isinstance(a, str) else f"``{a}``"
                          for a in typing.get_args(tp))
    if origin is typing.Annotated:
        base, *meta = typing.get_args(tp)
        bounds = [_bound_text(m) for m in meta]
        return _type_text(base) + "".join(f" {b}" for b in bounds if b)
    if origin in (typing.Union, types.UnionType):
        parts = [_type_text(a) for a in typing.get_args(tp) if a is not type(None)]
        optional = type(None) in typing.get_args(tp)
        return " or ".join(parts) + (" (optional)" if optional else "")
    if origin in (list, tuple, dict):
        inner = ", ".join(_type_text(a) for a in typing.get_args(tp) if a is not Ellipsis)
        return f"{origin.__name__}[{inner}]" if inner else origin.__name__
    if _is_model(tp):
        return "table"
    if isinstance(tp, type) and issubclass(tp, Enum):
        return " | ".join(f"``{m.value}``" for m in tp)
    return getattr(tp, "__name__", str(tp))


def _bound_text(meta) -> str:
    text = []
    for attr, sign in (("gt", ">"), ("ge", ">="), ("lt", "<"), ("le", "<="),
                       ("min_length", "length >="), ("max_length", "length <=")):
        value = getattr(meta, attr, None)
        if value is not None:
            text.append(f"{sign} {value}")
    for inner in getattr(meta, "metadata", []) or []:
        text.append(_bound_text(inner))
    return ", ".join(t for t in text if t)


def _field_bounds(info) -> str:
    return ", ".join(b for b in (_bound_text(m) for m in info.metadata) if b)


def _default_text(info) -> str:
    if info.default is PydanticUndefined:
        return "(required)" if info.default_factory is None else \
            f"``{info.default_factory()!r}``" if not _is_model(info.annotation) else ""
    if info.default is None:
        return "none"
    if isinstance(info.default, BaseModel):
        return ""
    value = info.default
    if isinstance(value, str):
        return f'``"{value}"``'
    if isinstance(value, tuple):
        value = list(value)
    return f"``{value!s}``"


def _cell(text: str) -> str:
    return " ".join(str(text).split()) or " "


def _table(model: type[BaseModel], name: str, out: list[str]) -> None:
    title = f"[{name}]" if name else "top level (no table)"
    doc = (model.__doc__ or "").strip().splitlines()
    out += [f".. rubric:: {title}", ""]
    if doc and not doc[0].startswith("Usage docs"):
        out += [doc[0], ""]
    out += [".. list-table::", "   :header-rows: 1", "   :widths: 18 30 14 38", "",
            "   * - key", "     - type / allowed", "     - default", "     - description"]
    nested = []
    for key, info in model.model_fields.items():
        tp = info.annotation
        subs = _models_in(tp)
        kind = _type_text(tp)
        bounds = _field_bounds(info)
        if bounds:
            kind += f" ({bounds})"
        desc = info.description or ""
        if subs:
            desc = (desc + " " if desc else "") + f"see ``[{name + '.' if name else ''}{key}]``"
            nested += [(sub, f"{name}.{key}" if name else key) for sub in subs]
        out += [f"   * - ``{key}``", f"     - {_cell(kind)}",
                f"     - {_cell(_default_text(info))}", f"     - {_cell(desc)}"]
    out.append("")
    for sub, sub_name in nested:
        _table(sub, sub_name, out)


def config_reference_lines() -> list[str]:
    from rubbercontact.config import RunConfig

    out: list[str] = []
    _table(RunConfig, "", out)
    return out


class ConfigReference(SphinxDirective):
    has_content = False

    def run(self):
        container = nodes.container()
        container.document = self.state.document
        self.state.nested_parse(StringList(config_reference_lines(), "config-reference"),
                                self.content_offset, container)
        return container.children


def setup(app):
    app.add_directive("config-reference", ConfigReference)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
