"""lark's contextual lexer for the HLSL grammar, its per-token loop made cheap (issue 31).

lark's ContextualLexer builds, per parser state, one regular expression of the terminals that
state accepts (in lark's order) and the callbacks that retype a NAME that is a keyword. Those
are kept as lark built them; only the loop around them is ours: lark's spends most of a
function's lexing time in Python calls per token (three nested `match` calls, a line counter
object, a keyword regex `fullmatch`, a token's keyword-argument constructor), more than its
parser spends on the same tokens. Here one loop does what they did, with the same result:
the same tokens, types and positions, in the same states. Where nothing matches, lark's own
loop takes over at that place, so an error is the exception lark raises.

Plugged in through lark's `_plugins` option (the way lark-cython replaces lark's parts), so the
parse table stays lark's and `cache=True` still holds it.
"""
from __future__ import annotations

from typing import Any, Callable, Iterator

import lark
from lark.lexer import ContextualLexer, LexerState, UnlessCallback

_Match = Callable[[str, int, int], Any]
# Token(...) is a wrapper that checks for a deprecated keyword and calls this; a token per
# lexeme, so called directly where this lark has it
_NEW_TOKEN: Callable[..., lark.Token] = getattr(lark.Token, "_future_new", lark.Token)


class FastContextualLexer(ContextualLexer):
    """ContextualLexer with one loop over the text (see the module's note)."""

    def __init__(self, conf: Any, states: dict[int, Any], always_accept: Any = ()) -> None:
        super().__init__(conf, states, always_accept)
        # per basic lexer (states that accept the same terminals share one): its compiled
        # pattern's match, {type: {text: keyword type}}, the other callbacks, the ignored types
        made: dict[int, tuple[_Match, dict[str, dict[str, str]], dict[str, Any], frozenset]] = {}
        self.table = {}
        for state, basic in self.lexers.items():
            entry = made.get(id(basic))
            if entry is None:
                entry = made[id(basic)] = _entry(basic)
            self.table[state] = entry

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
            match, keywords, callbacks, ignore = table[states[-1]]
            m = match(text, pos, end)
            if m is None:
                break                           # lark's loop raises its error from here
            value = m.group()
            kind = m.lastgroup
            after = m.end()
            newlines = value.count("\n")
            if kind in ignore:
                if newlines:
                    line += newlines
                    line_start = pos + value.rindex("\n") + 1
                pos = after
                continue
            retype = keywords.get(kind)
            if retype is not None:
                kind = retype.get(value, kind)
            tok = new_token(kind, value, pos, line, pos - line_start + 1)
            if newlines:
                line += newlines
                line_start = pos + value.rindex("\n") + 1
            tok.end_line, tok.end_column, tok.end_pos = line, after - line_start + 1, after
            pos = after
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


def _entry(basic: Any) -> tuple[_Match, dict[str, dict[str, str]], dict[str, Any], frozenset]:
    """What the loop needs of one of lark's basic lexers. lark matches the state's terminals as
    one alternation in its order (its Scanner); a keyword string that NAME's pattern also
    matches is left out of it and a NAME equal to it retyped (UnlessCallback's `fullmatch` of
    plain strings, a dictionary here)."""
    scanner = basic.scanner
    pattern = "|".join(f"(?P<{t.name}>{t.pattern.to_regexp()})" for t in scanner.terminals)
    match = basic.re.compile(pattern, basic.g_regex_flags).match
    keywords: dict[str, dict[str, str]] = {}
    callbacks: dict[str, Any] = {}
    for kind, callback in basic.callback.items():
        words = None if basic.g_regex_flags else _plain_strings(callback)
        if words is None:
            callbacks[kind] = callback
        else:
            keywords[kind] = words
    return match, keywords, callbacks, basic.ignore_types


def _plain_strings(callback: Any) -> dict[str, str] | None:
    """{text: type} of an UnlessCallback whose strings carry no flags (with no global flags
    either, a fullmatch of one is equality; the first string wins, as in lark's alternation); None for any other callback, which the loop calls as lark did."""
    if type(callback) is not UnlessCallback:
        return None
    words: dict[str, str] = {}
    for t in callback.scanner.terminals:
        if t.pattern.type != "str" or t.pattern.flags:
            return None
        words.setdefault(t.pattern.value, t.name)
    return words
