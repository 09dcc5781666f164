"""Where preprocessed text came from: a line map from output lines back to original files.

The preprocessor splices `#include`d files and drops directive lines, so line N of the text
lark parses is not line N of any one file. `SourceMap` keeps, for every output line, the
original file and line, and the texts of those files so that errors can show the line itself.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from effects.base.errors import EffectError, EffectWarning, Location, through_expansion


@dataclass
class SourceMap:
    """Maps 1-based (line, column) of preprocessed text to original `Location`s.

    `lines[i]` is the origin (path, line) of output line i+1. Columns are passed through:
    the preprocessor keeps each surviving line's text in place, but for a line macro
    expansion made (`expanded`), whose columns lead to the call or the argument they are in.
    """

    lines: list[tuple[str, int]] = field(default_factory=list)
    texts: dict[str, list[str]] = field(default_factory=dict)
    # output line -> where the pieces of a line macro expansion made came from
    # (`effects.base.errors.through_expansion`): errors in it point at the call or argument
    expanded: dict[int, tuple] = field(default_factory=dict)

    def add_file(self, path: str, text: str) -> None:
        # split on "\n" only: str.splitlines() also breaks at \x85 and friends, which a stray
        # latin-1 byte produces, and line numbers must agree with the preprocessor's.
        self.texts[path] = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")

    def locate(self, line: int, column: int) -> Location:
        if not self.lines:
            return Location("<string>", line, column)
        # past the end (an error at end of file): the last line
        path, original = self.lines[min(max(line, 1), len(self.lines)) - 1]
        pieces = self.expanded.get(line)
        if pieces:
            original, column = through_expansion(pieces, column)
        return Location(path, original, column)

    def source_line(self, location: Location) -> str | None:
        text = self.texts.get(location.path)
        if text is None or not 1 <= location.line <= len(text):
            return None
        return text[location.line - 1]

    def error(self, cls: type[EffectError], message: str, line: int, column: int,
              **kwargs) -> EffectError:
        """An error of type `cls` at output (line, column), with its original source line."""
        loc = self.locate(line, column)
        return cls(message, loc, source_line=self.source_line(loc), **kwargs)

    def error_at(self, cls: type[EffectError], message: str, location: Location,
                 **kwargs) -> EffectError:
        """An error at an already-located original position."""
        return cls(message, location, source_line=self.source_line(location), **kwargs)

    def warning_at(self, message: str, location: Location) -> EffectWarning:
        return EffectWarning(message, location, self.source_line(location))


@dataclass
class Preprocessed:
    """The preprocessor's result: text for the parser, its map, and every file read."""

    text: str
    source_map: SourceMap
    files: tuple[str, ...] = ()
    # `#pragma pack_matrix`: (line of `text` it stands on, True for row_major), in order
    pack_matrix: tuple[tuple[int, bool], ...] = ()
    # located warnings of the preprocessor (an include found under another letter case)
    warnings: tuple[EffectWarning, ...] = ()
