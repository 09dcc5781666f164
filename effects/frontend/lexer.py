"""The effect-file lexer: text → lark tokens.

Hand-written (lark drives it as a custom lexer, `LexerAdapter`) because parts of an effect are
opaque and balanced: `asm { ... }` and `decl { ... }` bodies, HLSL function parameter lists and
bodies, struct bodies. It also matches keywords case-insensitively, limits nesting depth, and
remembers which braces are open so a syntax error can say "missing '}' to close pass 'P0'
opened at line 4" (the messages are in `effects.frontend.parser`).
"""
from __future__ import annotations

import re
from bisect import bisect_right
from typing import Any

from lark import Token
from lark.lexer import Lexer as _LarkLexer

__all__ = ["EffectLexer", "LexerAdapter", "Located", "MAX_NESTING", "PUNCT", "STORAGE_CLASSES"]

MAX_NESTING = 64          # braces/parentheses/brackets open at once
MAX_PREFIX_RUN = 64       # `- - - - x`: more unary operators in a row than anyone writes
MAX_LITERAL_LENGTH = 400  # characters in one number literal


class Located(Exception):
    """Raised inside the lexer/transformer with a position in the preprocessed text; turned
    into a `ParseError` at the original location by `parse_effect`."""

    def __init__(self, message: str, line: int, column: int) -> None:
        super().__init__(message)
        self.message, self.line, self.column = message, line, column


_TOKEN_RE = re.compile(r"""
(?:[ \t\r\n\f\v]+|//[^\n]*|/\*.*?\*/)*         # blanks and comments
(?:
  (?P<NAME>[A-Za-z_][A-Za-z0-9_]*)
| (?P<HEX>0[xX][0-9A-Fa-f]+[uUlL]*)
| (?P<FLOAT>(?:[0-9]+\.[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?[fFhHlL]?|[0-9]+[eE][+-]?[0-9]+[fFhHlL]?|[0-9]+[fF])
| (?P<INT>[0-9]+[uUlL]*)
| (?P<STRING>"(?:[^"\\\n]|\\.)*")
| (?P<INDEX>\[[ \t]*(?:0[xX][0-9A-Fa-f]+|[0-9]+)[ \t]*\])
| (?P<OP2><=|>=|==|!=|&&|\|\||<<|>>)
| (?P<P>[{}()\[\];,=:<>|+\-*/%&^!~?.])
| (?P<END>\Z)
| (?P<BAD>.)    # so that the token part never fails: a failure would make the blank-skipping
                # loop above backtrack, which takes exponential time on long runs of blanks
)""", re.X | re.S)

PUNCT = {
    "{": "LBRACE", "}": "RBRACE", "(": "LPAR", ")": "RPAR", "[": "LSQB", "]": "RSQB",
    "<": "LT", ">": "GT", ";": "SEMI", ",": "COMMA", "=": "EQUAL", ":": "COLON",
    "-": "MINUS", "+": "PLUS", "*": "STAR", "/": "SLASH", "%": "PERCENT", "|": "BAR",
    "&": "AMP", "^": "CARET", "!": "BANG", "~": "TILDE", "?": "QMARK", ".": "DOT",
}

# Effect keywords are case-insensitive in non-strict fxc (docs/reference/effect_format.md §7).
_KEYWORDS = {
    "technique": "TECHNIQUE", "pass": "PASS", "compile": "COMPILE",
    "sampler_state": "SAMPLER_STATE", "stateblock_state": "STATEBLOCK_STATE",
    "struct": "STRUCT", "null": "NULL", "true": "TRUE", "false": "FALSE",
    "typedef": "TYPEDEF", "cbuffer": "CBUFFER",
    "tbuffer": "CBUFFER",       # the same block; shapes.cbuffer marks a tbuffer's members
}
STORAGE_CLASSES = ("shared", "static", "uniform", "const", "extern", "volatile",
                   "row_major", "column_major", "inline")
_KEYWORDS.update({s: "STORAGE" for s in STORAGE_CLASSES})
# ... but HLSL's own keywords are case-sensitive: `Shared`, `Static` or `Struct` is a name
# (naga's back/hlsl/keywords.rs lists the only case-insensitive ones, with fxc's X3086 for
# them in strict mode: asm, decl, pass, technique and the Direct3D 10 texture types)
_EXACT_CASE = frozenset(STORAGE_CLASSES) | {"struct", "typedef", "cbuffer", "tbuffer"}

# What a brace-scan skips so that a brace inside a comment or string does not count.
_BRACE_SCAN_RE = re.compile(r'[{}]|//[^\n]*|/\*.*?(?:\*/|\Z)|"(?:[^"\\\n]|\\.)*"', re.S)
_PAREN_SCAN_RE = re.compile(r'[()]|//[^\n]*|/\*.*?(?:\*/|\Z)|"(?:[^"\\\n]|\\.)*"', re.S)
_GAP_RE = re.compile(r"(?:\s+|//[^\n]*|/\*.*?\*/)*", re.S)
# `matrix<float, 4, 3>` / `vector<float, 3>`: one type-name token, written without blanks.
_TEMPLATE_RE = re.compile(r"<\s*([A-Za-z_][A-Za-z0-9_]*)\s*(?:,\s*([0-9]+)\s*)?(?:,\s*([0-9]+)\s*)?>")
# `Texture2D<float4>`: the later fxc's texture with its element type (types.texture_element),
# one type-name token. One name between the brackets, so an annotation block (`Texture2D T <
# string ResourceName = "x.png"; >`: a type, a name, `=`) is never read as one.
_TEXTURE_TEMPLATE_RE = re.compile(r"<\s*([A-Za-z_][A-Za-z0-9_]*)\s*>")
_TEXTURE_KINDS = frozenset({"texture1d", "texture2d", "texture3d", "texturecube"})
# `(float4)`, `(int)`: a cast to a numeric type, read as one token when a value follows.
_CAST_RE = re.compile(r"\(\s*((?:bool|int|uint|half|float|double|dword)(?:[1-4](?:x[1-4])?)?)\s*\)"
                      r"(?=(?:\s|//[^\n]*\n|/\*.*?\*/)*[-+!~0-9.({A-Za-z_])", re.S | re.I)

_OPENERS = {"LBRACE": "RBRACE", "LPAR": "RPAR", "LSQB": "RSQB"}
_CLOSERS = frozenset(("RBRACE", "RPAR", "RSQB"))
_HEADERS = frozenset(("TECHNIQUE", "PASS", "SAMPLER_STATE", "STATEBLOCK_STATE"))
_LIST_OPENERS = frozenset(("EQUAL", "COMMA", "LBRACE", "LPAR"))
# Token kinds the lexer keeps track of (everything else is just passed on).
_BOOKKEPT = frozenset(("LBRACE", "LPAR", "LSQB", "RBRACE", "RPAR", "RSQB", "LT", "GT", "EQUAL",
                       "SEMI", "COMMA", "MINUS", "BANG", "TILDE", "PLUS")) | _HEADERS
# lark's Token constructor without its keyword-argument shim (older lark: the class itself).
_make_token = getattr(Token, "_future_new", Token)
_PREFIX_OPS = frozenset(("MINUS", "BANG", "TILDE", "PLUS"))


class _Open:
    """An open brace/parenthesis/bracket: what it belongs to, for error messages."""

    __slots__ = ("kind", "name", "line", "column", "closer")

    def __init__(self, kind: str, name: str | None, line: int, column: int, closer: str) -> None:
        self.kind, self.name, self.line, self.column, self.closer = kind, name, line, column, closer

    def describe(self) -> str:
        if self.kind in ("technique", "pass"):
            return f"{self.kind} '{self.name}'" if self.name else self.kind
        return {"sampler_state": "sampler_state", "stateblock_state": "stateblock_state",
                "list": "initializer list", "block": "block", "LPAR": "'('",
                "LSQB": "'['"}.get(self.kind, self.kind)


class EffectLexer:
    """Tokens of an effect text, produced lazily (lark pulls them one at a time, so when the
    parser fails, `open` still describes the braces open at the failing token)."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.open: list[_Open] = []
        self.annotation: _Open | None = None  # an annotation block `< ... >` being read
        self.annotation_depth = 0             # len(open) when it started
        self.popped: _Open | None = None      # the entry a closer token closed ...
        self.popped_at = -1                   # ... and that token's offset
        self.closed_annotation_at = -1        # offset of the '>' that closed annotations
        self.pushed_at = -1                   # offset of the last opener
        self.decl_name: str | None = None     # the name declared by the current top-level statement
        self.line_starts = [0] + [m.end() for m in re.finditer("\n", text)]

    # -- positions ------------------------------------------------------------------------
    def position(self, offset: int) -> tuple[int, int]:
        """1-based (line, column) of a character offset."""
        line = bisect_right(self.line_starts, offset)
        return line, offset - self.line_starts[line - 1] + 1

    def end_position(self) -> tuple[int, int]:
        """Where 'end of file' is reported: just after the last non-blank character."""
        stripped = self.text.rstrip()
        if not stripped:
            return 1, 1
        return self.position(len(stripped))

    # -- scanning -------------------------------------------------------------------------
    def _balanced(self, start: int, scan: re.Pattern, opener: str, what: str) -> int:
        """Offset just past the closer matching the opener at `start`."""
        depth = 0
        for m in scan.finditer(self.text, start):
            ch = m.group()
            if ch == opener:
                depth += 1
            elif len(ch) == 1 and ch != opener:
                depth -= 1
                if depth == 0:
                    return m.end()
        line, col = self.position(start)
        eline, ecol = self.end_position()
        closer = "}" if opener == "{" else ")"
        raise Located(f"unexpected end of file: missing '{closer}' to close {what} "
                       f"opened at line {line}", eline, ecol)

    def tokens(self):
        text = self.text
        match = _TOKEN_RE.match
        starts = self.line_starts
        make = _make_token
        keywords, punct, special = _KEYWORDS, PUNCT, _BOOKKEPT
        opened = self.open
        pos = 0
        prev = prev2 = ""               # types of the two previous tokens
        pending: _Open | None = None    # technique/pass/sampler_state header awaiting its '{'
        stmt_eq = stmt_params = False   # top-level statement state: saw '=', saw '(...)'
        # a `cbuffer`'s braces: its members are read as top-level declarations (annotations,
        # initialisers), so its '{' and '}' are not counted as open (0: none, 1: its header
        # read, 2: inside it)
        cbuffer = 0
        cbuffer_at = 0                  # where the open cbuffer's '{' is (for an unclosed one)
        prefix_run = 0
        while True:
            m = match(text, pos)
            kind = m.lastgroup
            if kind == "END":
                if cbuffer == 2:
                    line, _ = self.position(cbuffer_at)
                    raise Located(f"unexpected end of file: missing '}}' to close the cbuffer "
                                  f"opened at line {line}", *self.end_position())
                return
            if kind == "BAD":
                raise self._bad_character(m.start(kind))
            start = m.start(kind)
            end = m.end()
            value = text[start:end]
            line = bisect_right(starts, start)
            col = start - starts[line - 1] + 1
            multiline = False
            if kind == "NAME":
                low = value.lower()
                kw = keywords.get(low)
                if kw is not None and value != low and low in _EXACT_CASE:
                    kw = None
                if kw is not None:
                    kind = kw
                    if kind == "CBUFFER" and not opened:
                        cbuffer = 1
                elif (low == "matrix" or low == "vector") and \
                        (t := _TEMPLATE_RE.match(text, _GAP_RE.match(text, end).end())):
                    end = t.end()
                    value = f"{value}<{','.join(g for g in t.groups() if g)}>"
                elif low in _TEXTURE_KINDS and \
                        (t := _TEXTURE_TEMPLATE_RE.match(text, _GAP_RE.match(text, end).end())):
                    end = t.end()
                    value = f"{value}<{t.group(1)}>"
                elif low == "asm" or low == "decl":
                    gap = _GAP_RE.match(text, end).end()
                    if text.startswith("{", gap):
                        end = self._balanced(gap, _BRACE_SCAN_RE, "{", f"{low} block")
                        kind, value, multiline = low.upper(), text[start:end], True
                elif not opened and self.annotation is None:
                    if prev == "NAME" and not stmt_eq and self.decl_name is None:
                        self.decl_name = value
                if pending is not None and (prev == "TECHNIQUE" or prev == "PASS"):
                    pending.name = value
            elif kind == "P":
                kind = punct[value]
                if kind == "LPAR" and prev != "NAME" and (cast := _CAST_RE.match(text, start)):
                    end = cast.end()
                    kind, value = "CAST", text[start:end]
                if kind == "SLASH" and text.startswith("/*", start):
                    raise Located("unterminated comment: '/*' has no closing '*/'", line, col)
            elif kind != "STRING" and len(value) > MAX_LITERAL_LENGTH:  # INDEX too: `[999...]`
                raise Located(f"number literal is too long ({len(value)} characters)", line, col)

            if cbuffer and not opened and self.annotation is None and (
                    (cbuffer == 1 and kind == "LBRACE") or (cbuffer == 2 and kind == "RBRACE")):
                cbuffer = 2 if kind == "LBRACE" else 0
                cbuffer_at = start
                stmt_eq = stmt_params = False
                self.decl_name = None
            elif kind in special:
                # -- nesting, error context and the opaque-part decisions --
                top = not opened
                in_ann = self.annotation is not None
                if kind == "LPAR" and top and not in_ann and not stmt_eq and prev == "NAME" \
                        and prev2 == "NAME":
                    # `type name(` at top level: an HLSL function's parameter list, kept as text.
                    end = self._balanced(start, _PAREN_SCAN_RE, "(", "parameter list")
                    kind, value, stmt_params = "PARAMS", text[start:end], True
                    multiline = True
                elif kind == "LBRACE" and top and not in_ann and stmt_params and not stmt_eq:
                    end = self._balanced(start, _BRACE_SCAN_RE, "{", "function body")
                    kind, value, multiline = "FUNC_BODY", text[start:end], True
                elif kind == "LBRACE" and (prev == "NAME" and prev2 == "STRUCT" or prev == "STRUCT"):
                    # `struct S { ... }`, and `typedef struct { ... } T;` (a body with no name)
                    end = self._balanced(start, _BRACE_SCAN_RE, "{", "struct")
                    kind, value, multiline = "STRUCT_BODY", text[start:end], True

                if kind in _OPENERS:
                    if len(opened) >= MAX_NESTING:
                        raise Located(f"nesting is too deep (more than {MAX_NESTING} levels of "
                                       f"braces, parentheses or brackets)", line, col)
                    if kind == "LBRACE" and pending is not None and prev not in _LIST_OPENERS:
                        entry, pending = pending, None
                    else:
                        k = kind if kind != "LBRACE" else (
                            "list" if prev in _LIST_OPENERS else "block")
                        entry = _Open(k, None, line, col, _OPENERS[kind])
                    opened.append(entry)
                    self.pushed_at = start
                elif kind in _CLOSERS:
                    if opened and opened[-1].closer == kind:
                        closed = opened.pop()
                        self.popped, self.popped_at = closed, start
                        if not opened and closed.kind == "technique" and not in_ann:
                            stmt_eq = stmt_params = False
                            self.decl_name = None
                elif kind in _HEADERS:
                    pending = _Open(kind.lower(), None, line, col, "RBRACE")
                elif kind == "LT":
                    if not in_ann and not stmt_eq and (top or pending is not None):
                        self.annotation = _Open("annotation", None, line, col, "GT")
                        self.annotation_depth = len(opened)
                elif kind == "GT":
                    if in_ann and self.annotation_depth == len(opened):
                        self.annotation = None
                        self.closed_annotation_at = start
                if top and not in_ann:
                    if kind == "EQUAL":
                        stmt_eq = True
                    elif kind == "COMMA":   # the next declarator of `float a = 1, b < ... >;`
                        stmt_eq = False
                    elif kind == "SEMI" or kind == "FUNC_BODY" or kind == "STRUCT_BODY":
                        stmt_eq = stmt_params = False
                        self.decl_name = None
                        pending = None
                if kind in _PREFIX_OPS:
                    prefix_run += 1
                    if prefix_run > MAX_PREFIX_RUN:
                        raise Located("too many operators in a row", line, col)
                else:
                    prefix_run = 0
            else:
                prefix_run = 0

            if not multiline:
                yield make(kind, value, start, line, col, line, col + end - start, end)
            else:  # a block, possibly spanning lines
                eline = bisect_right(starts, end - 1)
                yield make(kind, value, start, line, col, eline, end - starts[eline - 1] + 1, end)
            prev2, prev = prev, kind
            pos = end

    def _bad_character(self, pos: int) -> Located:
        line, col = self.position(pos)
        ch = self.text[pos]
        if self.text.startswith("/*", pos):
            return Located("unterminated comment: '/*' has no closing '*/'", line, col)
        if ch == '"':
            return Located("unterminated string literal", line, col)
        shown = f"'{ch}'" if ch.isprintable() and not ch.isspace() else f"U+{ord(ch):04X}"
        return Located(f"unexpected character {shown}", line, col)


class LexerAdapter(_LarkLexer):
    """Lets lark pull tokens from an `EffectLexer` passed as the parse input."""

    __future_interface__ = 2

    def __init__(self, lexer_conf: Any) -> None:
        pass

    def lex(self, lexer_state: Any, parser_state: Any):
        return lexer_state.text.tokens()
