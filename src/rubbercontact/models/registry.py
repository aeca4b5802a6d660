"""Models by name: the one list the command line, the config and the pipeline read.

A new model is a module defining a :class:`~rubbercontact.models.base.TaskModel` (with its
:class:`~rubbercontact.models.planning.Planning` and ``run_task`` for a run to plan it) and
one :func:`register` call here.
"""

from __future__ import annotations

from typing import Any

from ..errors import InputError
from .base import ContactModel
from .planning import Planning

__all__ = ["available", "create", "model_class", "needs_law", "plannable", "planning",
           "register", "splits"]

#: name -> (the model's class, the constructor arguments the name fixes)
_MODELS: dict[str, tuple[type, dict[str, Any]]] = {}


def register(name: str, cls: type, **fixed: Any) -> None:
    """Make ``cls(**fixed, **options)`` available as the model ``name`` (``fixed``: what
    the name implies, e.g. the hybrid's ``reading``)."""
    if name in _MODELS:
        raise InputError(f"model {name!r} is already registered")
    _MODELS[name] = (cls, dict(fixed))


def available() -> tuple[str, ...]:
    """Registered model names, in registration order."""
    return tuple(_MODELS)


def model_class(name: str) -> type:
    """The class of model ``name``."""
    if name not in _MODELS:
        raise InputError(f"model: unknown {name!r}; available: {', '.join(available())}")
    return _MODELS[name][0]


def planning(name: str) -> Planning | None:
    """How a run plans model ``name`` (``None``: a model for scripts only)."""
    return getattr(model_class(name), "planning", None)


def plannable() -> tuple[str, ...]:
    """The models a run can plan, in registration order."""
    return tuple(m for m in _MODELS if planning(m) is not None)


def needs_law(name: str) -> bool:
    """Whether model ``name`` reads a high-slope law (so a run must build one)."""
    how = planning(name)
    return bool(how and how.reads_law)


def splits(name: str) -> bool:
    """Whether model ``name``'s friction is a low-slope part plus the law's share."""
    how = planning(name)
    return bool(how and how.splits)


def create(name: str, **options: Any) -> ContactModel:
    """The model ``name`` with ``options`` (``create("hybrid-windowed", law=table)``)."""
    cls, fixed = _MODELS[name] if name in _MODELS else (model_class(name), {})
    return cls(**fixed, **options)


def _register_builtins() -> None:
    from .fem import FEM
    from .halfspace import VHS, Hybrid
    from .meanfield import MeanField, MeanFieldHybrid, MeanFieldStrips

    register("vhs", VHS)
    register("hybrid", Hybrid, reading="pointwise")
    register("hybrid-windowed", Hybrid, reading="windowed")
    register("fem", FEM)
    register("meanfield", MeanField)
    register("meanfield-hybrid", MeanFieldHybrid)
    register("meanfield-strips", MeanFieldStrips)


_register_builtins()
