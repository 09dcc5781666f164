"""lark's contextual lexer for the HLSL grammar, its per-token loop made cheap (issue 31).

lark's ContextualLexer builds, per parser state, one regular expression of the terminals that
state accepts (in lark's order) and the callbacks that retype a NAME that is a keyword. Those
are kept as lark built them; only the loop around them is ours: lark's spends most of a
function's lexing time in Python calls per token (three nested `match` calls, a line counter
object, a keyword regex `fullmatch`, a token's keyword-argument constructor), more than its
parser spends on the same tokens. Here one loop does what they did, with the same result:
the same tokens, types and positions, in the same states. Where nothing matches, lark's own
loop takes over at that place, so an error is the exception lark raises.

The alternation is also tried by the lexeme's first character: Python's `re` tries a state's
alternatives one by one (forty and more), so a state's pattern is narrowed, per first
character, to the terminals that can start with it, in lark's order (the same first match:
the others cannot match there). Which characters a terminal can start with is read from its
pattern's parse; where that is not plain, every character.

Plugged in through lark's `_plugins` option (the way lark-cython replaces lark's parts), so the
parse table stays lark's and `cache=True` still holds it.
"""
from __future__ import annotations

import re
from typing import Any, Callable, Iterator

import lark
from lark.lexer import ContextualLexer, LexerState, UnlessCallback

from effects.base import caches

try:
    from re import _parser as _sre            # the regular expressions' own parser
except ImportError:                           # Python 3.10 names it so
    import sre_parse as _sre                  # type: ignore[no-redef]

_Match = Callable[[str, int, int], Any]
# Token(...) is a wrapper that checks for a deprecated keyword and calls this; a token per
# lexeme, so called directly where this lark has it
_NEW_TOKEN: Callable[..., lark.Token] = getattr(lark.Token, "_future_new", lark.Token)


class FastContextualLexer(ContextualLexer):
    """ContextualLexer with one loop over the text (see the module's note)."""

    def __init__(self, conf: Any, states: dict[int, Any], always_accept: Any = ()) -> None:
        super().__init__(conf, states, always_accept)
        self.table = _Table(self.lexers)

    def lex(self, lexer_state: LexerState, parser_state: Any) -> Iterator[lark.Token]:
        text_slice = lexer_state.text
        text, end = text_slice.text, text_slice.end
        counter = lexer_state.line_ctr
        pos, line, line_start = counter.char_pos, counter.line, counter.line_start_pos
        table = self.table
        new_token = _NEW_TOKEN
        last = lexer_state.last_token
        states = parser_state.state_stack     # the parser's own list: its top is `position`
        while pos < end:
            narrowed, keywords, callbacks, ignore = table[states[-1]]
            match = narrowed.get(text[pos])
            if match is None:
                match = narrowed.add(text[pos])
            m = match(text, pos, end)
            if m is None:
                break                           # lark's loop raises its error from here
            value = m.group()
            kind = m.lastgroup
            after = m.end()
            start, column = pos, pos - line_start + 1
            newlines = value.count("\n")
            if newlines:
                line += newlines
                line_start = pos + value.rindex("\n") + 1
            pos = after
            if kind in ignore:
                continue
            retype = keywords.get(kind)
            if retype is not None:
                kind = retype.get(value, kind)
            tok = new_token(kind, value, start, line - newlines, column, line,
                            after - line_start + 1, after)
            if callbacks:
                callback = callbacks.get(tok.type)
                if callback is not None:
                    tok = callback(tok)
            last = tok
            yield tok
        counter.char_pos, counter.line, counter.line_start_pos = pos, line, line_start
        counter.column = pos - line_start + 1
        lexer_state.last_token = last
        if pos < end:
            yield from super().lex(lexer_state, parser_state)


class _Table(dict):
    """{parser state: what the loop needs of its basic lexer}, made when the state is first
    met (lark makes a basic lexer's pattern then too: most states never lex). Per basic lexer
    (states that accept the same terminals share one): its patterns' match by first character
    (_Narrowed), {type: {text: keyword type}}, the other callbacks, the ignored types."""

    def __init__(self, lexers: dict[int, Any]) -> None:
        super().__init__()
        self.lexers = lexers
        self.made: dict[int, tuple] = {}

    def __missing__(self, state: int) -> tuple:
        basic = self.lexers[state]
        entry = self.made.get(id(basic))
        if entry is None:
            entry = self.made[id(basic)] = _entry(basic)
        self[state] = entry
        return entry


def _entry(basic: Any) -> tuple["_Narrowed", dict[str, dict[str, str]], dict[str, Any],
                               frozenset]:
    """What the loop needs of one of lark's basic lexers. lark matches the state's terminals as
    one alternation in its order (its Scanner); a keyword string that NAME's pattern also
    matches is left out of it and a NAME equal to it retyped (UnlessCallback's `fullmatch` of
    plain strings, a dictionary here)."""
    narrowed = _Narrowed(basic)               # (lark makes `callback` with the scanner)
    keywords: dict[str, dict[str, str]] = {}
    callbacks: dict[str, Any] = {}
    for kind, callback in basic.callback.items():
        words = None if basic.g_regex_flags else _plain_strings(callback)
        if words is None:
            callbacks[kind] = callback
        else:
            keywords[kind] = words
    return narrowed, keywords, callbacks, basic.ignore_types


class _Narrowed(dict):
    """{first character: the match of the state's terminals that can start with it}, filled
    as characters are met (a state meets few; a dispatch table of the lexer, as lark keeps
    its scanners on its basic lexers, the compiled patterns held by `_alternation`). A
    character outside ASCII, or with global flags, or one no terminal starts with (lark's
    loop then reports it), takes the whole alternation."""

    def __init__(self, basic: Any) -> None:
        super().__init__()
        self.terminals = list(basic.scanner.terminals)
        self.flags = basic.g_regex_flags
        self.compile = basic.re.compile

    def add(self, char: str) -> _Match:
        starting = self.terminals
        if not self.flags and char.isascii():
            starting = [t for t in self.terminals if _can_start(t.pattern.to_regexp(), char)]
        match = self[char] = self._match(starting or self.terminals)
        return match

    def _match(self, terminals: list) -> _Match:
        return _alternation(tuple((t.name, t.pattern.to_regexp()) for t in terminals),
                            self.flags, self.compile)


# one compiled alternation per terminal list, shared by the states and characters that have it
# (a grammar makes a few dozen: ~1 ms of `re` compiling each, ~20 KB held)
@caches.memo("shaders.hlsl.lexer_patterns", keys="terminal names and patterns, regex flags, "
             "the regex module's compile", entry_bytes=20 << 10, max_bytes=256 * (20 << 10))
def _alternation(terminals: tuple[tuple[str, str], ...], flags: int,
                 compile_: Callable[..., Any]) -> _Match:
    return compile_("|".join(f"(?P<{name}>{regexp})" for name, regexp in terminals),
                    flags).match


def _can_start(regexp: str, char: str) -> bool:
    first = _first_characters(regexp)
    return first is None or char in first


@caches.memo("shaders.hlsl.first_characters", keys="a terminal's pattern", entry_bytes=1024,
             max_bytes=512 * 1024)
def _first_characters(regexp: str) -> frozenset[str] | None:
    """The ASCII characters a match of `regexp` can start with; None: any."""
    try:
        found, nullable = _first(_sre.parse(regexp))
    except Exception:                     # a form this reading does not know: any character
        return None
    return None if found is None or nullable else frozenset(found)


_ASCII = [chr(k) for k in range(128)]
_CATEGORIES = {"CATEGORY_DIGIT": r"\d", "CATEGORY_NOT_DIGIT": r"\D", "CATEGORY_SPACE": r"\s",
               "CATEGORY_NOT_SPACE": r"\S", "CATEGORY_WORD": r"\w", "CATEGORY_NOT_WORD": r"\W"}
_REPEATS = ("MAX_REPEAT", "MIN_REPEAT", "POSSESSIVE_REPEAT")


def _first(items: Any) -> tuple[set[str] | None, bool]:
    """(the ASCII characters a match of the parsed sequence `items` can start with, whether
    it can match nothing); None for the characters where a form is not worked out here."""
    out: set[str] = set()
    for op, arg in items:
        found, nullable = _first_of(str(op), arg)
        if found is None:
            return None, True
        out |= found
        if not nullable:
            return out, False
    return out, True


def _first_of(op: str, arg: Any) -> tuple[set[str] | None, bool]:
    if op == "LITERAL":
        return {chr(arg)} if arg < 128 else set(), False
    if op == "NOT_LITERAL":
        return {c for c in _ASCII if ord(c) != arg}, False
    if op == "IN":
        return _in_set(arg), False
    if op in ("ASSERT", "ASSERT_NOT", "AT"):       # they consume nothing
        return set(), True
    if op == "SUBPATTERN":
        _group, add_flags, del_flags, sub = arg
        return _first(sub) if not (add_flags or del_flags) else (None, True)
    if op == "BRANCH":
        out: set[str] = set()
        nullable = False
        for alternative in arg[1]:
            found, empty = _first(alternative)
            if found is None:
                return None, True
            out |= found
            nullable = nullable or empty
        return out, nullable
    if op in _REPEATS:
        low, _high, sub = arg
        found, empty = _first(sub)
        return found, empty or low == 0
    return None, True


def _in_set(items: Any) -> set[str] | None:
    """The ASCII characters of a character class `[...]`."""
    negate = False
    tests: list[Callable[[str], bool]] = []
    for op, arg in items:
        op = str(op)
        if op == "NEGATE":
            negate = True
        elif op == "LITERAL":
            tests.append(lambda c, k=arg: ord(c) == k)
        elif op == "RANGE":
            tests.append(lambda c, r=arg: r[0] <= ord(c) <= r[1])
        elif op == "CATEGORY" and str(arg) in _CATEGORIES:
            tests.append(re.compile(_CATEGORIES[str(arg)]).fullmatch)
        else:
            return None
    return {c for c in _ASCII if any(t(c) for t in tests) != negate}


def _plain_strings(callback: Any) -> dict[str, str] | None:
    """{text: type} of an UnlessCallback whose strings carry no flags (with no global flags
    either, a fullmatch of one is equality; the first string wins, as in lark's alternation);
    None for any other callback, which the loop calls as lark did."""
    if type(callback) is not UnlessCallback:
        return None
    words: dict[str, str] = {}
    for t in callback.scanner.terminals:
        if t.pattern.type != "str" or t.pattern.flags:
            return None
        words.setdefault(t.pattern.value, t.name)
    return words
