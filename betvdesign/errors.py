"""Exception hierarchy shared by every layer.

Every error a user can cause derives from :class:`BetvError`; the CLI turns them
into one clear line on stderr and exit code 2 (bad input or usage), never a
traceback.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import TypeVar

T = TypeVar("T")
R = TypeVar("R")


class BetvError(Exception):
    """Base class of errors caused by input the user can fix."""


@dataclass(frozen=True)
class Location:
    """Where in an input file a problem sits (1-based line and column)."""

    file: str
    line: int | None = None
    col: int | None = None

    def __str__(self) -> str:
        parts = [self.file]
        if self.line is not None:
            parts.append(str(self.line))
            if self.col is not None:
                parts.append(str(self.col))
        return ":".join(parts)


@dataclass(frozen=True)
class SpecIssue:
    """One problem found in a device file: ``file:line:col: field.path: message``."""

    location: Location
    field: str
    message: str

    def __str__(self) -> str:
        field = f"{self.field}: " if self.field else ""
        return f"{self.location}: {field}{self.message}"


class SpecError(BetvError):
    """A device file could not be read or validated; carries every issue found."""

    def __init__(self, issues: list[SpecIssue]):
        self.issues = list(issues)
        super().__init__("\n".join(str(i) for i in self.issues))


def each_or_issues(fn: Callable[[T], R], items: Iterable[T]) -> list[R]:
    """``fn`` of every item, or one SpecError with the issues of every item that failed.

    Parameters
    ----------
    fn : callable
        Reads or prepares one item (a device file); raises SpecError.
    items : iterable
        The items, in order.

    Returns
    -------
    list
        ``fn``'s results, in order, when no item raised.

    Raises
    ------
    SpecError
        Every failed item's issues, in order, after all were tried.
    """
    done: list[R] = []
    issues: list[SpecIssue] = []
    for item in items:
        try:
            done.append(fn(item))
        except SpecError as exc:
            issues.extend(exc.issues)
    if issues:
        raise SpecError(issues)
    return done


class ParameterError(BetvError, ValueError):
    """Dimensionless parameters outside what the model supports (non-positive, NaN, inf)."""


class UsageError(BetvError):
    """Command-line arguments that cannot be acted on (empty range, unwritable output...)."""
