"""One location type and one error formatter for everything the framework reports.

Every problem a user can cause (a bad effect file, a broken profile, an invalid shader) is an
`EffectError` that knows the file, line and column it came from; `str()` is the one-line
`PATH:LINE:COL: error: MESSAGE` form and `report()` adds the source line with a caret.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, order=True)
class Location:
    """A position in an original source file: 1-based line and column."""

    path: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.path}:{self.line}:{self.column}"


UNKNOWN_LOCATION = Location("<unknown>", 0, 0)


def caret_lines(source_line: str | None, column: int) -> str:
    """The offending source line and a caret under `column` (1-based), or '' without a line."""
    if source_line is None:
        return ""
    text = source_line.rstrip("\r\n").expandtabs(1)
    # Keep pathological lines readable: show a window around the column.
    start = 0
    if len(text) > 120:
        start = max(0, column - 60)
        text = text[start:start + 120]
    return f"{text}\n{' ' * max(0, column - 1 - start)}^"


class EffectError(Exception):
    """A located error in user input. `str()` is `PATH:LINE:COL: error: MESSAGE`."""

    severity = "error"

    def __init__(self, message: str, location: Location | None = None, *,
                 source_line: str | None = None) -> None:
        self.message = message
        self.location = location or UNKNOWN_LOCATION
        self.source_line = source_line
        super().__init__(str(self))

    @property
    def path(self) -> str:
        return self.location.path

    @property
    def line(self) -> int:
        return self.location.line

    @property
    def column(self) -> int:
        return self.location.column

    def __str__(self) -> str:
        return f"{self.location}: {self.severity}: {self.message}"

    def report(self) -> str:
        """The error as a user sees it on the console: message, source line, caret."""
        extra = caret_lines(self.source_line, self.column)
        return f"{self}\n{extra}" if extra else str(self)


class PreprocessError(EffectError):
    """#include / #define / #if problems."""


class ParseError(EffectError):
    """The effect text does not follow the effect grammar."""


class StateError(EffectError):
    """A state assignment names an unknown state (strict mode) or has a value of the wrong type."""


class AsmError(EffectError):
    """A shader assembly program is malformed or breaks its version's limits."""


class ProfileError(EffectError):
    """A caps profile YAML is malformed or names unknown caps."""


class SceneError(EffectError):
    """A scene file, a `--set` value or an asset could not be used."""


class NoValidTechnique(EffectError):
    """No technique of the effect is valid on the card; `.reasons` says why, technique by technique."""

    def __init__(self, message: str, location: Location | None = None, *,
                 reasons: dict | None = None) -> None:
        self.reasons = reasons or {}
        super().__init__(message, location)


@dataclass(frozen=True)
class EffectWarning:
    """A located warning (an unknown state name, an ignored construct...)."""

    message: str
    location: Location
    source_line: str | None = None

    def __str__(self) -> str:
        return f"{self.location}: warning: {self.message}"

    def report(self) -> str:
        extra = caret_lines(self.source_line, self.location.column)
        return f"{self}\n{extra}" if extra else str(self)
