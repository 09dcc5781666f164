"""Preprocessor tokens: the C-like token kinds, tokenizing, and spans of joined lines.

The macro expander, the `#if` evaluator and the directive driver all work on these.
A token keeps its offset in the span it came from, so every error can name a line:column.
"""
from __future__ import annotations

import bisect
import re
from dataclasses import dataclass
from typing import NamedTuple

from effects.base.errors import Location

MAX_TOKENIZED_CHARS = 200_000   # a directive, or a line needing the full macro algorithm

_TOKEN = re.compile(
    r'(?P<id>[A-Za-z_][A-Za-z0-9_]*)'
    r'|(?P<num>\.?[0-9](?:[eEpP][+-]|[A-Za-z0-9_.])*)'   # a C "pp-number": 1.5e-3f, 0x1F, 10u
    r'|(?P<str>"[^"\\\n]*(?:\\.[^"\\\n]*)*"?)'
    r'|(?P<ws>[ \t\f\v\n]+)'
    r'|(?P<punct>##|\.\.\.|<<|>>|<=|>=|==|!=|&&|\|\||.)', re.S)
IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
BLANKS = re.compile(r"[ \t\f\v]*")
NO_HIDE: frozenset[str] = frozenset()


class Token(NamedTuple):
    text: str
    kind: str             # "id", "num", "str", "ws", "punct", or "mark" (an empty ## operand)
    hide: frozenset[str]  # macros that must not expand this token (C's hide set)
    pos: int              # offset in the span where it (or the macro call it came from) stands


def tokenize(text: str, start: int = 0, hide: frozenset[str] = NO_HIDE, pos: int | None = None) -> list[Token]:
    """Tokens of text[start:]; positions are offsets into `text`, or all `pos` when given."""
    return [Token(m.group(), m.lastgroup, hide, m.start() if pos is None else pos)
            for m in _TOKEN.finditer(text, start)]


def strip_blanks(tokens: list[Token]) -> list[Token]:
    """`tokens` without leading and trailing whitespace tokens."""
    lo, hi = 0, len(tokens)
    while lo < hi and tokens[lo].kind == "ws":
        lo += 1
    while hi > lo and tokens[hi - 1].kind == "ws":
        hi -= 1
    return tokens[lo:hi]


def next_solid(tokens: list[Token], k: int) -> int:
    """The index of the first non-whitespace token from k on (len(tokens) when none)."""
    while k < len(tokens) and tokens[k].kind == "ws":
        k += 1
    return k


def word_after(text: str, pos: int) -> tuple[str | None, int]:
    """The identifier after blanks from `pos` (None when there is none), and where it starts."""
    pos = BLANKS.match(text, pos).end()
    match = IDENT.match(text, pos)
    return (match.group() if match else None), pos


@dataclass
class Span:
    """Physical lines joined into one logical text, with the way back to line:column."""

    path: str
    text: str
    starts: list[int]  # offset in `text` where each physical line's part begins
    lines: list[int]   # 1-based line number of each part

    def location(self, offset: int) -> Location:
        k = max(bisect.bisect_right(self.starts, offset) - 1, 0)
        return Location(self.path, self.lines[k], offset - self.starts[k] + 1)
