"""Linear viscoelastic materials (generalized Maxwell / Prony series)."""

from .maxwell import GeneralizedMaxwell, sbr

__all__ = ["GeneralizedMaxwell", "sbr"]
