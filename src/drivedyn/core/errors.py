"""Exceptions of drivedyn.

A ``ModelError`` is the user's mistake (bad file, bad value): the command line prints its
message on one line and exits with status 2. A ``SolverError`` is a failed computation: it
carries whatever was computed up to the failure in ``partial`` (a Result or None).
"""


class DrivedynError(Exception):
    """Base class of all drivedyn errors."""


class ModelError(DrivedynError, ValueError):
    """Invalid model input. The message names the field and the problem, on one line."""

    def __init__(self, message: str, field: str | None = None):
        self.field = field
        # one line whatever the message carries (a linear-algebra error's text, a quoted value):
        # line breaks and runs of white space become single spaces
        message = " ".join(str(message).split()) if any(c in str(message) for c in "\n\r\t\v\f") else str(message)
        super().__init__(f"{field}: {message}" if field else message)


class SolverError(DrivedynError, RuntimeError):
    """A solve that could not finish; ``partial`` holds the results computed so far."""

    def __init__(self, message: str, partial=None):
        self.partial = partial
        super().__init__(message)


class Stopped(DrivedynError):
    """Raised by a ``progress`` callback to stop a run early (a study's ``case_timeout``).

    Analyses that integrate in time end the run there and raise a ``SolverError`` that keeps the
    results computed so far; the others let it through.
    """


def stop_reason(exc: BaseException) -> str:
    """Why a time integration stopped early: a ``Stopped``'s message, or Ctrl-C."""
    return str(exc) if isinstance(exc, Stopped) else "interrupted by the user"


class DrivedynWarning(UserWarning):
    """Warnings about questionable but admissible input or results."""
