"""Config fields made from the frozen option dataclasses: one source of options.

A run config's key that sets a solver option (:mod:`rubbercontact.config`) takes its
default, and unless the config has more to say its help, from the option dataclass that
the solver reads (``FemOptions``, ``TransientOptions``, ``HalfspaceOptions``, ...), so the
two cannot drift.
"""

from __future__ import annotations

import dataclasses
import inspect
import re
from typing import Any

from pydantic import Field

__all__ = ["option_default", "option_field", "option_help"]

#: Sphinx roles and literals of a docstring, dropped from a one-line help text.
_ROLE = re.compile(r":\w+:`~?([^`]+)`")


def option_default(cls: type, name: str) -> Any:
    """The default of field ``name`` of the dataclass ``cls`` (built if it is a factory)."""
    field = {f.name: f for f in dataclasses.fields(cls)}[name]
    if field.default is not dataclasses.MISSING:
        return field.default
    if field.default_factory is not dataclasses.MISSING:
        return field.default_factory()
    raise KeyError(f"{cls.__name__}.{name} has no default")


def option_help(cls: type, name: str) -> str:
    """The text of ``name`` in the ``Attributes`` section of ``cls``'s numpy docstring, as
    one line without Sphinx markup or final full stop (``""`` if it is not documented)."""
    lines = inspect.cleandoc(cls.__doc__ or "").splitlines()
    text, inside = [], False
    for line in lines:
        if line and not line[0].isspace():          # an entry's name, or a section title
            if inside:
                break
            inside = name in (n.strip() for n in line.split(","))
        elif inside:
            text.append(line.strip())
    line = _ROLE.sub(r"\1", " ".join(text)).replace("``", "").strip().removesuffix(".")
    # in the config's style: lower case, unless the first word is an acronym ("FEM")
    return line[:1].lower() + line[1:] if line[1:2].islower() else line


def option_field(cls: type, name: str, *, prefix: str = "", description: str | None = None,
                 **constraints: Any) -> Any:
    """A pydantic ``Field`` with the default of ``cls.name`` and its help (``prefix`` + the
    docstring's text, or ``description``); ``constraints`` are ``Field``'s (``ge``, ...)."""
    text = description if description is not None else prefix + option_help(cls, name)
    return Field(option_default(cls, name), description=text, **constraints)
