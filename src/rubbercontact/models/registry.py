"""Models by name: the one list the command line, the config and the pipeline read.

A new model is a module defining a :class:`~rubbercontact.models.base.TaskModel` (or any
:class:`~rubbercontact.models.base.ContactModel`) and one :func:`register` call here.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..errors import InputError
from .base import ContactModel

__all__ = ["available", "create", "register"]

_FACTORIES: dict[str, Callable[..., ContactModel]] = {}
_NEEDS_LAW: set[str] = set()


def register(name: str, factory: Callable[..., ContactModel], *, needs_law: bool = False
             ) -> None:
    """Make ``factory(**options)`` available as the model ``name``."""
    if name in _FACTORIES:
        raise InputError(f"model {name!r} is already registered")
    _FACTORIES[name] = factory
    if needs_law:
        _NEEDS_LAW.add(name)


def available() -> tuple[str, ...]:
    """Registered model names, in registration order."""
    return tuple(_FACTORIES)


def needs_law(name: str) -> bool:
    """Whether model ``name`` reads a high-slope law (so a run must build one)."""
    return name in _NEEDS_LAW


def create(name: str, **options: Any) -> ContactModel:
    """The model ``name`` with ``options`` (``create("hybrid-windowed", law=table)``)."""
    if name not in _FACTORIES:
        raise InputError(f"model: unknown {name!r}; available: {', '.join(available())}")
    return _FACTORIES[name](**options)


def _register_builtins() -> None:
    from .fem import FEM
    from .halfspace import VHS, Hybrid
    from .meanfield import MeanField, MeanFieldStrips

    register("vhs", VHS)
    register("hybrid-windowed", lambda law, **kw: Hybrid(law, "windowed", **kw), needs_law=True)
    register("hybrid", lambda law, **kw: Hybrid(law, "pointwise", **kw), needs_law=True)
    register("meanfield", MeanField)
    register("meanfield-strips", MeanFieldStrips)
    register("fem", FEM)


_register_builtins()
