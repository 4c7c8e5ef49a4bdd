"""The engine's one exception hierarchy: callers catch :class:`SorguiError`."""

from __future__ import annotations


class SorguiError(Exception):
    """Base class of every error the exact engine raises on purpose."""

    def __init__(self, message: str) -> None:
        super().__init__(message)
        self.message = message


class ParseError(SorguiError):
    """Pasted text is not a polynomial in x, y, z; ``position`` is the 0-based character offset."""

    def __init__(self, message: str, position: int, end: int | None = None) -> None:
        super().__init__(message)
        self.position = position
        self.end = position + 1 if end is None else end

    def __str__(self) -> str:
        return f"{self.message} (at character {self.position + 1})"


class ExpressionError(SorguiError, ValueError):
    """A machine-written formula (Singular's answer, an engine result string) that cannot be read."""


class AnalysisError(SorguiError):
    """The input parsed, but the analysis cannot proceed (e.g. a degenerate surface)."""


class OutOfReach(AnalysisError):
    """An exact step needs what cannot be had quickly (the primes of an integer of hundreds of
    digits, :mod:`.algebra.factoring`): the stage is left undecided, not run for minutes."""


class SingularError(SorguiError):
    """Singular failed, was not found, or answered something that could not be read."""


class SingularNotFound(SingularError):
    """Neither the bundled nor a system ``Singular`` executable exists."""


class SingularTimeout(SingularError):
    """A Singular computation did not finish within its time limit."""


class TimeLimitReached(SorguiError):
    """The whole analysis did not finish within its time limit (:mod:`.timelimit`)."""


class Cancelled(SorguiError):
    """The computation was cancelled by the caller."""


class ClaimError(SorguiError):
    """A claim of a saved report does not hold for its polynomial (:mod:`.claims`); ``field``
    names the claim (``axis.point``, ``parametrizations[1]``)."""

    def __init__(self, field: str, message: str) -> None:
        super().__init__(f"{field} {message}")
        self.field = field
