"""Exception types shared by every part of rubbercontact.

User mistakes (bad input) raise :class:`InputError`, a ``ValueError`` so that
generic callers can still catch it; numerical failures raise
:class:`ConvergenceError`, which carries what the solver tried and the last
state it reached so nothing computed is lost.
"""

from __future__ import annotations

from typing import Any


class RubberContactError(Exception):
    """Base class of every error raised on purpose by rubbercontact."""


class InputError(RubberContactError, ValueError):
    """Invalid user input: the message names the offending field and value."""


class ConvergenceError(RubberContactError, RuntimeError):
    """A solver did not converge.

    Parameters
    ----------
    message
        What failed, in words.
    diagnostics
        What was tried (iterations, residual history, step sizes, ...).
    last_state
        The last converged (or best) state, so that finished work is kept.
    """

    def __init__(
        self,
        message: str,
        diagnostics: dict[str, Any] | None = None,
        last_state: Any = None,
    ) -> None:
        super().__init__(message)
        self.diagnostics = dict(diagnostics or {})
        self.last_state = last_state
