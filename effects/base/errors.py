"""One location type and one error formatter for everything the framework reports.

Every problem a user can cause (a bad effect file, a broken profile, an invalid shader) is an
`EffectError` that knows the file, line and column it came from; `str()` is the one-line
`PATH:LINE:COL: error: MESSAGE` form and `report()` adds the source line with a caret.
"""
from __future__ import annotations



class Location:
    """A position in an original source file: 1-based line and column. Immutable, equal and
    ordered by (path, line, column), hashable, picklable: what `@dataclass(frozen=True,
    order=True)` gave, written out because `effects --help` imports this module and importing
    dataclasses (and inspect with it) was a fifth of that command's start-up."""

    __slots__ = ("path", "line", "column")
    __match_args__ = ("path", "line", "column")
    path: str
    line: int
    column: int

    def __init__(self, path: str, line: int, column: int) -> None:
        object.__setattr__(self, "path", path)
        object.__setattr__(self, "line", line)
        object.__setattr__(self, "column", column)

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"cannot assign to field '{name}' of a Location")

    def __delattr__(self, name: str) -> None:
        raise AttributeError(f"cannot delete field '{name}' of a Location")

    def _key(self) -> tuple[str, int, int]:
        return (self.path, self.line, self.column)

    def __eq__(self, other: object) -> bool:
        if other.__class__ is not Location:
            return NotImplemented
        return self._key() == other._key()  # type: ignore[attr-defined]

    def __lt__(self, other: "Location") -> bool:
        if other.__class__ is not Location:
            return NotImplemented
        return self._key() < other._key()

    def __le__(self, other: "Location") -> bool:
        if other.__class__ is not Location:
            return NotImplemented
        return self._key() <= other._key()

    def __gt__(self, other: "Location") -> bool:
        if other.__class__ is not Location:
            return NotImplemented
        return self._key() > other._key()

    def __ge__(self, other: "Location") -> bool:
        if other.__class__ is not Location:
            return NotImplemented
        return self._key() >= other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def __reduce__(self) -> tuple:
        return (Location, self._key())

    def __repr__(self) -> str:
        return f"Location(path={self.path!r}, line={self.line!r}, column={self.column!r})"

    def __str__(self) -> str:
        return f"{self.path}:{self.line}:{self.column}"

    def line_in(self, main_path: str) -> str:
        """"line N" for a place in the file `main_path`, "PATH, line N" for one in another (an
        #include), as a report about that file says where."""
        if self.line and main_path and self.path != main_path:
            return f"{self.path}, line {self.line}"
        return f"line {self.line}"


UNKNOWN_LOCATION = Location("<unknown>", 0, 0)


def through_expansion(pieces: tuple, column: int) -> tuple[int, int]:
    """(line, column) in the file of `column` (1-based) of a line that macro expansion made.
    `pieces` (the preprocessor's, in column order) are (column in the made line, file line,
    file column, verbatim): a verbatim piece is text of the file at that place (a macro
    argument, the text around a call), any other a macro's body, placed at the call."""
    found = pieces[0]
    for piece in pieces:
        if piece[0] > column:
            break
        found = piece
    start, line, col, verbatim = found
    return line, col + (column - start if verbatim and column >= start else 0)


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
    # True for an error in a shader's language, which fxc gives whatever the target (a syntax,
    # type or name error): it rejects a technique on every card, so the commands report it
    # as an error, where a refusal for one target's limits stays a card's reason. Set where
    # the error is made (effects.shaders.hlsl.parse.HlslError).
    language = False

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


class EffectWarning:
    """A located warning (an unknown state name, an ignored construct...). Immutable, equal
    and hashable by its three fields (written out for the reason Location is)."""

    __slots__ = ("message", "location", "source_line")
    __match_args__ = ("message", "location", "source_line")
    message: str
    location: Location
    source_line: str | None

    def __init__(self, message: str, location: Location, source_line: str | None = None) -> None:
        object.__setattr__(self, "message", message)
        object.__setattr__(self, "location", location)
        object.__setattr__(self, "source_line", source_line)

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"cannot assign to field '{name}' of an EffectWarning")

    def __delattr__(self, name: str) -> None:
        raise AttributeError(f"cannot delete field '{name}' of an EffectWarning")

    def _key(self) -> tuple:
        return (self.message, self.location, self.source_line)

    def __eq__(self, other: object) -> bool:
        if other.__class__ is not EffectWarning:
            return NotImplemented
        return self._key() == other._key()  # type: ignore[attr-defined]

    def __hash__(self) -> int:
        return hash(self._key())

    def __reduce__(self) -> tuple:
        return (EffectWarning, self._key())

    def __repr__(self) -> str:
        return (f"EffectWarning(message={self.message!r}, location={self.location!r}, "
                f"source_line={self.source_line!r})")

    def __str__(self) -> str:
        return f"{self.location}: warning: {self.message}"

    def report(self) -> str:
        extra = caret_lines(self.source_line, self.location.column)
        return f"{self}\n{extra}" if extra else str(self)
