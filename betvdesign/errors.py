"""Exception hierarchy shared by every layer.

Every error a user can cause derives from :class:`BetvError`; the CLI turns them
into one clear line on stderr and exit code 2 (bad input or usage), never a
traceback.
"""

from __future__ import annotations

from dataclasses import dataclass


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


class ParameterError(BetvError, ValueError):
    """Dimensionless parameters outside what the model supports (non-positive, NaN, inf)."""


class UsageError(BetvError):
    """Command-line arguments that cannot be acted on (empty range, unwritable output...)."""
