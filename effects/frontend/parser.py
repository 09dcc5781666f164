"""The effect-file parser: preprocessed text → `Effect` model.

Three steps, each with one job:

1. `EffectLexer` turns text into lark tokens. It is hand-written (lark drives it as a custom
   lexer) because parts of an effect are opaque and balanced: `asm { ... }` and `decl { ... }`
   bodies, HLSL function parameter lists and bodies, struct bodies. It also matches keywords
   case-insensitively, limits nesting depth, and remembers which braces are open so a syntax
   error can say "missing '}' to close pass 'P0' opened at line 4".
2. The LALR grammar in `grammar/effect.lark`, with `_Shapes` as lark's inline transformer,
   builds light raw records (`_V` values, `_RawState`, `_RawPass` ...) carrying positions.
3. `_Builder` turns the records into model objects: resolves types, types parameter values
   as numpy arrays, coerces state values through `effects.states`, reports unknown states.

`parse_effect` is the only public entry; every problem becomes a located `ParseError` /
`StateError`, never a lark exception or a Python traceback.

Parameter values: numeric parameters are numpy arrays shaped (array dims) + () for a scalar,
(n,) for a vector, (r, c) for a matrix; float/half/double are float32, bool is bool, and
int/uint/dword are int32, or int64 when a value does not fit in int32 (hex colours such as
0xff202060 in a DWORD); a value beyond 64 bits is an error. A non-constant initializer is kept
as an `Expression`.
"""
from __future__ import annotations

import gc
import math
import re
from bisect import bisect_right
from pathlib import Path
from typing import Any

import numpy as np
from lark import Lark, Token, Transformer
from lark.exceptions import LarkError, UnexpectedInput, UnexpectedToken, VisitError
from lark.lexer import Lexer as _LarkLexer

from effects.errors import EffectError, Location, ParseError, StateError
from effects.model import (Annotation, CompileShader, Effect, Expression, Function, NullValue,
                    Parameter, ParamRef, Pass, SamplerState, ShaderBlock, StateAssignment, Struct,
                    Technique, TypeSpec, VertexDeclElement)
from effects.frontend.source import Preprocessed

MAX_NESTING = 64          # braces/parentheses/brackets open at once
MAX_PREFIX_RUN = 64       # `- - - - x`: more unary operators in a row than anyone writes
MAX_LITERAL_LENGTH = 400  # characters in one number literal

__all__ = ["parse_effect", "EffectLexer", "TERMINAL_WORDS", "MAX_NESTING"]


class _Located(Exception):
    """Raised inside the lexer/transformer with a position in the preprocessed text; turned
    into a `ParseError` at the original location by `parse_effect`."""

    def __init__(self, message: str, line: int, column: int) -> None:
        super().__init__(message)
        self.message, self.line, self.column = message, line, column


# =============================================================================================
# 1. Lexer

_TOKEN_RE = re.compile(r"""
(?:[ \t\r\n\f\v]+|//[^\n]*|/\*.*?\*/)*         # blanks and comments
(?:
  (?P<NAME>[A-Za-z_][A-Za-z0-9_]*)
| (?P<HEX>0[xX][0-9A-Fa-f]+[uUlL]*)
| (?P<FLOAT>(?:[0-9]+\.[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?[fFhH]?|[0-9]+[eE][+-]?[0-9]+[fFhH]?|[0-9]+[fF])
| (?P<INT>[0-9]+[uUlL]*)
| (?P<STRING>"(?:[^"\\\n]|\\.)*")
| (?P<INDEX>\[[ \t]*(?:0[xX][0-9A-Fa-f]+|[0-9]+)[ \t]*\])
| (?P<OP2><=|>=|==|!=|&&|\|\||<<|>>)
| (?P<P>[{}()\[\];,=:<>|+\-*/%&^!~?.])
| (?P<END>\Z)
| (?P<BAD>.)    # so that the token part never fails: a failure would make the blank-skipping
                # loop above backtrack, which takes exponential time on long runs of blanks
)""", re.X | re.S)

_PUNCT = {
    "{": "LBRACE", "}": "RBRACE", "(": "LPAR", ")": "RPAR", "[": "LSQB", "]": "RSQB",
    "<": "LT", ">": "GT", ";": "SEMI", ",": "COMMA", "=": "EQUAL", ":": "COLON",
    "-": "MINUS", "+": "PLUS", "*": "STAR", "/": "SLASH", "%": "PERCENT", "|": "BAR",
    "&": "AMP", "^": "CARET", "!": "BANG", "~": "TILDE", "?": "QMARK", ".": "DOT",
}

# Effect keywords are case-insensitive in non-strict fxc (effect_format.md §7).
_KEYWORDS = {
    "technique": "TECHNIQUE", "pass": "PASS", "compile": "COMPILE",
    "sampler_state": "SAMPLER_STATE", "stateblock_state": "STATEBLOCK_STATE",
    "struct": "STRUCT", "null": "NULL", "true": "TRUE", "false": "FALSE",
}
STORAGE_CLASSES = ("shared", "static", "uniform", "const", "extern", "volatile",
                   "row_major", "column_major", "inline")
_KEYWORDS.update({s: "STORAGE" for s in STORAGE_CLASSES})

# What a brace-scan skips so that a brace inside a comment or string does not count.
_BRACE_SCAN_RE = re.compile(r'[{}]|//[^\n]*|/\*.*?(?:\*/|\Z)|"(?:[^"\\\n]|\\.)*"', re.S)
_PAREN_SCAN_RE = re.compile(r'[()]|//[^\n]*|/\*.*?(?:\*/|\Z)|"(?:[^"\\\n]|\\.)*"', re.S)
_GAP_RE = re.compile(r"(?:\s+|//[^\n]*|/\*.*?\*/)*", re.S)

_OPENERS = {"LBRACE": "RBRACE", "LPAR": "RPAR", "LSQB": "RSQB"}
_CLOSERS = frozenset(("RBRACE", "RPAR", "RSQB"))
_HEADERS = frozenset(("TECHNIQUE", "PASS", "SAMPLER_STATE", "STATEBLOCK_STATE"))
_LIST_OPENERS = frozenset(("EQUAL", "COMMA", "LBRACE", "LPAR"))
# Token kinds the lexer keeps track of (everything else is just passed on).
_BOOKKEPT = frozenset(("LBRACE", "LPAR", "LSQB", "RBRACE", "RPAR", "RSQB", "LT", "GT", "EQUAL",
                       "SEMI", "MINUS", "BANG", "TILDE", "PLUS")) | _HEADERS
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
        raise _Located(f"unexpected end of file: missing '{closer}' to close {what} "
                       f"opened at line {line}", eline, ecol)

    def tokens(self):
        text = self.text
        match = _TOKEN_RE.match
        starts = self.line_starts
        make = _make_token
        keywords, punct, special = _KEYWORDS, _PUNCT, _BOOKKEPT
        opened = self.open
        pos = 0
        prev = prev2 = ""               # types of the two previous tokens
        pending: _Open | None = None    # technique/pass/sampler_state header awaiting its '{'
        stmt_eq = stmt_params = False   # top-level statement state: saw '=', saw '(...)'
        prefix_run = 0
        while True:
            m = match(text, pos)
            kind = m.lastgroup
            if kind == "END":
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
                if kw is not None:
                    kind = kw
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
                if kind == "SLASH" and text.startswith("/*", start):
                    raise _Located("unterminated comment: '/*' has no closing '*/'", line, col)
            elif kind != "STRING" and kind != "INDEX" and len(value) > MAX_LITERAL_LENGTH:
                raise _Located(f"number literal is too long ({len(value)} characters)", line, col)

            if kind in special:
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
                elif kind == "LBRACE" and prev == "NAME" and prev2 == "STRUCT":
                    end = self._balanced(start, _BRACE_SCAN_RE, "{", "struct")
                    kind, value, multiline = "STRUCT_BODY", text[start:end], True

                if kind in _OPENERS:
                    if len(opened) >= MAX_NESTING:
                        raise _Located(f"nesting is too deep (more than {MAX_NESTING} levels of "
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
                    elif kind == "SEMI" or kind == "FUNC_BODY" or kind == "STRUCT_BODY":
                        stmt_eq = stmt_params = False
                        self.decl_name = None
                        pending = None
                if kind in _PREFIX_OPS:
                    prefix_run += 1
                    if prefix_run > MAX_PREFIX_RUN:
                        raise _Located("too many operators in a row", line, col)
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

    def _bad_character(self, pos: int) -> _Located:
        line, col = self.position(pos)
        ch = self.text[pos]
        if self.text.startswith("/*", pos):
            return _Located("unterminated comment: '/*' has no closing '*/'", line, col)
        if ch == '"':
            return _Located("unterminated string literal", line, col)
        shown = f"'{ch}'" if ch.isprintable() and not ch.isspace() else f"U+{ord(ch):04X}"
        return _Located(f"unexpected character {shown}", line, col)


class _LexerAdapter(_LarkLexer):
    """Lets lark pull tokens from an `EffectLexer` passed as the parse input."""

    __future_interface__ = 2

    def __init__(self, lexer_conf: Any) -> None:
        pass

    def lex(self, lexer_state: Any, parser_state: Any):
        return lexer_state.text.tokens()


# =============================================================================================
# 2. Grammar shapes → raw records


class _V:
    """A value as written: `kind` says its shape, `data` its parts, start/end its text span."""

    __slots__ = ("kind", "data", "start", "end", "line", "column")

    def __init__(self, kind: str, data: Any, start: int, end: int, line: int, column: int) -> None:
        self.kind, self.data = kind, data
        self.start, self.end, self.line, self.column = start, end, line, column


def _tok_v(kind: str, data: Any, tok: Token) -> _V:
    return _V(kind, data, tok.start_pos, tok.end_pos, tok.line, tok.column)


def _span_v(kind: str, data: Any, first: Any, last: Any) -> _V:
    f_start, f_line, f_col = ((first.start, first.line, first.column) if isinstance(first, _V)
                              else (first.start_pos, first.line, first.column))
    end = last.end if isinstance(last, _V) else last.end_pos
    return _V(kind, data, f_start, end, f_line, f_col)


class _RawState:
    __slots__ = ("name", "index", "value")

    def __init__(self, name: Token, index: Token | None, value: _V) -> None:
        self.name, self.index, self.value = name, index, value


class _RawBlock:
    """A technique or pass: keyword token, optional name, annotations, items."""

    __slots__ = ("keyword", "name", "annotations", "items")

    def __init__(self, keyword: Token, name: Token | None, annotations: list, items: list) -> None:
        self.keyword, self.name, self.annotations, self.items = keyword, name, annotations, items


class _RawParam:
    __slots__ = ("storage", "type", "name", "dims", "semantic", "annotations", "value")

    def __init__(self, *fields: Any) -> None:
        (self.storage, self.type, self.name, self.dims, self.semantic, self.annotations,
         self.value) = fields


_INT_SUFFIX = "uUlL"
_FLOAT_SUFFIX = "fFhH"


def _int_value(text: str) -> int:
    text = text.strip("[] \t").rstrip(_INT_SUFFIX)
    return int(text, 16) if text[:2] in ("0x", "0X") else int(text)


class _Shapes(Transformer):
    """lark's inline transformer: one small method per grammar shape, no tree is built."""

    def start(self, c): return c[0]

    def items(self, c):
        if not c:
            return []
        if not isinstance(c[1], Token):  # a free-standing ';' adds nothing
            c[0].append(c[1])
        return c[0]

    passes = states = items

    # -- literals -------------------------------------------------------------------------
    def int(self, c): return _tok_v("int", _int_value(c[0].value), c[0])
    def float(self, c):
        tok = c[0]
        value = float(tok.value.rstrip(_FLOAT_SUFFIX))
        if math.isinf(value):
            raise _Located(f"number {tok.value} is out of range", tok.line, tok.column)
        return _tok_v("float", value, tok)

    def string(self, c): return _tok_v("str", _unescape(c[0].value[1:-1]), c[0])
    def true(self, c): return _tok_v("bool", True, c[0])
    def false(self, c): return _tok_v("bool", False, c[0])
    def null(self, c): return _tok_v("null", None, c[0])

    # -- operands -------------------------------------------------------------------------
    def name(self, c): return _tok_v("name", c[0].value, c[0])

    def const_index(self, c):
        return _span_v("index", (c[0].value, _tok_v("int", _int_value(c[1].value), c[1])),
                       c[0], c[1])

    def index(self, c): return _span_v("index", (c[0].value, c[2]), c[0], c[3])
    def call(self, c): return _span_v("call", (c[0].value, c[2] or []), c[0], c[3])
    def paren(self, c): return _span_v("paren", c[1], c[0], c[2])
    def angle_ref(self, c): return _span_v("ref", c[1].value, c[0], c[2])
    def list(self, c): return _span_v("list", c[1] or [], c[0], c[3])
    def args(self, c): return c[::2]

    def neg(self, c):
        v = c[1]
        if v.kind in ("int", "float"):
            return _span_v(v.kind, -v.data, c[0], v)
        return _span_v("expr", None, c[0], v)

    def unary(self, c): return _span_v("expr", None, c[0], c[1])

    def chain(self, c):
        operands = c[::2]
        if all(op.type == "BAR" for op in c[1::2]):
            return _span_v("bar", operands, c[0], c[-1])
        return _span_v("expr", None, c[0], c[-1])

    def asm(self, c): return _tok_v("asm", (c[0], None), c[0])
    def decl_asm(self, c): return _span_v("asm", (c[1], c[0]), c[0], c[1])

    def compile(self, c):
        return _span_v("compile", (c[1].value, c[2].value, c[4] or []), c[0], c[5])

    def sampler_state(self, c): return _span_v("sampler", c[2], c[0], c[3])
    def stateblock_state(self, c): return _span_v("stateblock", c[2], c[0], c[3])

    # -- statements -----------------------------------------------------------------------
    def state(self, c): return _RawState(c[0], None, c[2])
    def indexed_state(self, c): return _RawState(c[0], c[1], c[3])
    def pass_block(self, c): return _RawBlock(c[0], c[1], c[2] or [], c[4])
    def technique(self, c): return _RawBlock(c[0], c[1], c[2] or [], c[4])
    def annotations(self, c): return c[1:-1]
    def annotation(self, c): return (c[0], c[1], c[3])
    def initializer(self, c): return c[1]
    def semantic(self, c): return c[1].value
    def register_semantic(self, c): return f"{c[1].value}({c[3].value})"
    def storage(self, c): return c
    def dims(self, c): return c

    def param_decl(self, c):
        return _RawParam(c[0], c[1], c[2], c[3], c[4], c[5] or [], c[6])

    def func_def(self, c): return ("function", c)
    def struct_def(self, c): return ("struct", c)


_ESCAPES = {"n": "\n", "t": "\t", "r": "\r", "\\": "\\", '"': '"', "'": "'", "0": "\0"}


def _unescape(body: str) -> str:
    if "\\" not in body:
        return body
    return re.sub(r"\\(.)", lambda m: _ESCAPES.get(m.group(1), m.group(1)), body)


_GRAMMAR_PATH = Path(__file__).with_name("grammar") / "effect.lark"
_parser: Lark | None = None


def _lark() -> Lark:
    """The LALR parser, built once per process; lark also caches its tables on disk
    (`cache=True`, keyed by the grammar text), which makes the first load ~15x faster."""
    global _parser
    if _parser is None:
        _parser = Lark(_GRAMMAR_PATH.read_text(), parser="lalr", lexer=_LexerAdapter,
                       transformer=_Shapes(), maybe_placeholders=True, cache=True)
    return _parser


# =============================================================================================
# Syntax-error messages

TERMINAL_WORDS = {
    "NAME": "a name", "INT": "an integer", "HEX": "an integer", "FLOAT": "a number",
    "STRING": "a string", "STORAGE": "a storage class", "TECHNIQUE": "'technique'",
    "PASS": "'pass'", "COMPILE": "'compile'", "SAMPLER_STATE": "'sampler_state'",
    "STATEBLOCK_STATE": "'stateblock_state'", "STRUCT": "'struct'", "NULL": "'NULL'",
    "TRUE": "'true'", "FALSE": "'false'", "ASM": "an asm block", "DECL": "a decl block",
    "FUNC_BODY": "a function body", "STRUCT_BODY": "a struct body",
    "PARAMS": "a parameter list", "$END": "end of file", "INDEX": "an index such as [0]",
    **{v: f"'{k}'" for k, v in _PUNCT.items()}, "OP2": "an operator",
}
# Preferred order when several terminals are listed.
_ORDER = ["SEMI", "EQUAL", "LBRACE", "RBRACE", "LPAR", "RPAR", "LSQB", "RSQB", "COMMA", "LT",
          "GT", "COLON", "NAME", "INT", "FLOAT", "STRING", "PASS", "TECHNIQUE", "ASM"]
_BINOPS = {"BAR", "PLUS", "MINUS", "STAR", "SLASH", "PERCENT", "AMP", "CARET", "LT", "GT",
           "OP2", "QMARK", "COLON", "DOT"}
_VALUE_STARTS = {"INT", "HEX", "FLOAT", "STRING", "NAME", "LBRACE", "LPAR", "NULL", "TRUE"}


def _describe_token(tok: Token) -> str:
    if tok.type == "$END":
        return "end of file"
    if tok.type in ("ASM", "DECL"):
        return f"'{tok.type.lower()}' block"
    if tok.type in ("FUNC_BODY", "STRUCT_BODY"):
        return "'{'"
    if tok.type == "PARAMS":
        return "'('"
    text = tok.value if len(tok.value) <= 24 else tok.value[:21] + "..."
    if tok.type == "STRING":
        return f"string {text}"
    return f"'{text}'"


def _word_list(names: list[str]) -> str:
    words = []
    for n in names:
        w = TERMINAL_WORDS.get(n, n)
        if w not in words:
            words.append(w)
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " or " + words[-1]


def _syntax_message(exc: UnexpectedToken, lexer: EffectLexer) -> tuple[str, int, int]:
    tok = exc.token
    expected = set(exc.expected)
    found = _describe_token(tok)
    at_end = tok.type == "$END"
    if at_end:
        line, col = lexer.end_position()
        if lexer.annotation is not None and lexer.annotation_depth == len(lexer.open):
            a = lexer.annotation
            return (f"unexpected end of file: missing '>' to close the annotations opened at "
                    f"line {a.line}"), line, col
        if lexer.open:
            o = lexer.open[-1]
            closer = TERMINAL_WORDS[o.closer]
            return (f"unexpected end of file: missing {closer} to close {o.describe()} "
                    f"opened at line {o.line}"), line, col
        found = "end of file"
    else:
        line, col = tok.line, tok.column
    # lark has already pulled `tok` from the lexer: when it was a closer, the lexer has
    # popped what it closed, which is the context the parser was in.
    popped = lexer.popped if lexer.popped_at == tok.start_pos and not at_end else None
    open_ = lexer.open[:-1] if lexer.pushed_at == tok.start_pos and not at_end else lexer.open
    inner = popped or (open_[-1] if open_ else None)
    ctx = inner.kind if inner else "top"
    if lexer.closed_annotation_at == tok.start_pos or (lexer.annotation is not None
                                   and lexer.annotation_depth == len(lexer.open)):
        ctx = "annotation"
    # LALR merges look-aheads of similar states: drop closers that cannot close anything here.
    closers = {"RBRACE", "RPAR", "RSQB"}
    keep = {inner.closer} if inner is not None else set()
    expected -= closers - keep

    if "SEMI" in expected and not expected & {"NAME", "PASS", "TECHNIQUE", "$END"}:
        what = {"annotation": "annotation", "pass": "state assignment",
                "sampler_state": "state assignment",
                "stateblock_state": "state assignment"}.get(ctx)
        if what is None and ctx == "top":
            what = f"the declaration of '{lexer.decl_name}'" if lexer.decl_name else "declaration"
        if what is not None:
            return f"expected ';' after {what}, found {found}", line, col
    if ctx in ("pass", "sampler_state", "stateblock_state") and {"NAME", "RBRACE"} <= expected:
        return (f"expected a state assignment or '}}' to close {inner.describe()}, "
                f"found {found}"), line, col
    if ctx == "technique" and {"PASS", "RBRACE"} <= expected:
        return (f"expected 'pass' or '}}' to close {inner.describe()}, found {found}"), line, col
    if ctx == "top" and {"TECHNIQUE", "NAME"} <= expected:
        return f"expected a declaration or a technique, found {found}", line, col
    if ctx == "annotation" and {"NAME", "GT"} <= expected:
        return f"expected an annotation or '>', found {found}", line, col
    if tok.type == "LSQB" and "INDEX" in expected:
        return "a state index must be a constant integer such as [0]", line, col
    if _VALUE_STARTS <= expected:
        return f"expected a value, found {found}", line, col
    names = _ordered(expected - _BINOPS) or _ordered(expected)
    return f"expected {_word_list(names)}, found {found}", line, col


def _ordered(names: set[str]) -> list[str]:
    rank = {n: i for i, n in enumerate(_ORDER)}
    return sorted(names, key=lambda n: (rank.get(n, len(rank)), n))


# =============================================================================================
# 3. Raw records → model

_NUMERIC_RE = re.compile(r"(bool|int|uint|half|float|double|dword)([1-4])?(?:x([1-4]))?")
_BASE_OF = {"bool": "bool", "int": "int", "uint": "dword", "half": "half", "float": "float",
            "double": "float", "dword": "dword"}
_OBJECT_TYPES = {
    "string": ("string", ""), "texture": ("texture", ""), "texture1d": ("texture", "1D"),
    "texture2d": ("texture", "2D"), "texture3d": ("texture", "3D"),
    "texturecube": ("texture", "CUBE"), "sampler": ("sampler", ""),
    "sampler1d": ("sampler", "1D"), "sampler2d": ("sampler", "2D"),
    "sampler3d": ("sampler", "3D"), "samplercube": ("sampler", "CUBE"),
    "vertexshader": ("vertexshader", ""), "pixelshader": ("pixelshader", ""),
    "stateblock": ("stateblock", ""),
}
_INT32 = (-(2 ** 31), 2 ** 31 - 1)
_INT64 = (-(2 ** 63), 2 ** 63 - 1)
_ASM_GAP_RE = re.compile(r"(?:\s+|//[^\n]*|;[^\n]*|/\*.*?\*/)*", re.S)
_VERSION_RE = re.compile(r"(vs|ps)[._]([0-9])[._]([0-9a-z]+)\b", re.I)
_DECL_TYPES = {"float": 1, "d3dcolor": 4, "ubyte": 4, "short": 2}


def type_shape(spec: TypeSpec) -> tuple[int, ...]:
    """The numeric shape of one element of a type: () scalar, (n,) vector, (r, c) matrix.
    Read from the spelling, because float and float1 share rows/cols but not shape."""
    spelling = spec.spelling.lower()
    if spelling == "vector":
        return (4,)
    if spelling == "matrix":
        return (4, 4)
    m = _NUMERIC_RE.fullmatch(spelling)
    if m is None:  # no spelling (a model built in code): infer from rows/cols
        if spec.rows > 1:
            return (spec.rows, spec.cols)
        return (spec.cols,) if spec.cols > 1 else ()
    if m.group(3):
        return (int(m.group(2)), int(m.group(3)))
    return (int(m.group(2)),) if m.group(2) else ()


def resolve_type(name: str, structs: set[str] = frozenset()) -> TypeSpec | None:
    """The TypeSpec a type name denotes, or None when no such type exists."""
    low = name.lower()
    if low == "vector":
        return TypeSpec("float", 1, 4, spelling=name)
    if low == "matrix":
        return TypeSpec("float", 4, 4, spelling=name)
    m = _NUMERIC_RE.fullmatch(low)
    if m:
        base = _BASE_OF[m.group(1)]
        if m.group(3):
            return TypeSpec(base, int(m.group(2)), int(m.group(3)), spelling=name)
        return TypeSpec(base, 1, int(m.group(2) or 1), spelling=name)
    if low in _OBJECT_TYPES:
        base, dim = _OBJECT_TYPES[low]
        return TypeSpec(base, dim=dim, spelling=name)
    if name in structs:
        return TypeSpec(name, struct=True, spelling=name)
    return None


class _NotConstant(Exception):
    """A value is an expression, not a constant the parser can evaluate."""


class _Builder:
    def __init__(self, pre: Preprocessed, lexer: EffectLexer, strict: bool) -> None:
        self.pre, self.text, self.strict = pre, pre.text, strict
        self.smap = pre.source_map
        self.lexer = lexer
        self.map_lines = self.smap.lines
        self.nlines = len(self.map_lines)
        self.warnings: list = []
        self.param_names: set[str] = set()
        from effects import states  # the states table; imported late so the parser loads without it
        self.states = states

    # -- locations and errors -------------------------------------------------------------
    def loc(self, item: Any) -> Location:
        line = item.line
        if 0 < line <= self.nlines:  # SourceMap.locate, inlined: this runs for every node
            path, original = self.map_lines[line - 1]
            return Location(path, original, item.column)
        return self.smap.locate(line, item.column)

    def error(self, cls: type, message: str, item: Any) -> Exception:
        return self.smap.error_at(cls, message, self.loc(item))

    def text_of(self, v: _V) -> str:
        return self.text[v.start:v.end]

    # -- the effect -----------------------------------------------------------------------
    def build(self, items: list) -> Effect:
        path = self.pre.files[0] if self.pre.files else (
            self.smap.lines[0][0] if self.smap.lines else "<string>")
        effect = Effect(path)
        structs: set[str] = set()
        first_param: dict[str, Any] = {}
        for item in items:
            if isinstance(item, _RawParam):
                prior = first_param.get(item.name.value)
                if prior is not None:
                    raise self.error(ParseError, f"duplicate parameter '{item.name.value}' "
                                     f"(first declared at line {self.loc(prior).line})", item.name)
                first_param[item.name.value] = item.name
        self.param_names = set(first_param)
        seen_tech: dict[str, Token] = {}
        for item in items:
            if isinstance(item, _RawParam):
                effect.parameters.append(self.parameter(item, structs))
            elif isinstance(item, _RawBlock):
                if item.name is not None:
                    prior = seen_tech.get(item.name.value)
                    if prior is not None:
                        raise self.error(ParseError, f"duplicate technique '{item.name.value}' "
                                         f"(first declared at line {self.loc(prior).line})",
                                         item.name)
                    seen_tech[item.name.value] = item.name
                effect.techniques.append(self.technique(item))
            elif item[0] == "struct":
                c = item[1]
                structs.add(c[1].value)
                effect.structs.append(Struct(c[1].value, self.text[c[0].start_pos:c[3].end_pos],
                                             self.loc(c[0])))
            else:
                c = item[1]
                first = c[0][0] if c[0] else c[1]
                effect.functions.append(Function(c[2].value, c[1].value,
                                                 self.text[first.start_pos:c[5].end_pos],
                                                 self.loc(first)))
        effect.warnings = self.warnings
        effect.files = tuple(self.pre.files)
        return effect

    # -- parameters -----------------------------------------------------------------------
    def type_of(self, tok: Token, structs: set[str]) -> TypeSpec:
        spec = resolve_type(tok.value, structs)
        if spec is None:
            raise self.error(ParseError, f"unknown type '{tok.value}'", tok)
        return spec

    def parameter(self, raw: _RawParam, structs: set[str]) -> Parameter:
        spec = self.type_of(raw.type, structs)
        dims = tuple(self.small_int(t, "array size") for t in raw.dims)
        if any(d == 0 for d in dims):
            raise self.error(ParseError, "array size must be at least 1", raw.dims[0])
        name = raw.name.value
        value = None if raw.value is None else self.param_value(spec, dims, raw.value, name)
        return Parameter(name, spec, tuple(t.value.lower() for t in raw.storage), dims,
                         raw.semantic, self.annotations(raw.annotations), value, self.loc(raw.name))

    def small_int(self, tok: Token, what: str) -> int:
        value = _int_value(tok.value)
        if value > 65535:
            raise self.error(ParseError, f"{what} {value} is too large", tok)
        return value

    def annotations(self, raws: list) -> list[Annotation]:
        out = []
        for type_tok, name_tok, v in raws:
            spec = self.type_of(type_tok, set())
            out.append(Annotation(spec, name_tok.value,
                                  self.param_value(spec, (), v, name_tok.value),
                                  self.loc(name_tok)))
        return out

    def param_value(self, spec: TypeSpec, dims: tuple[int, ...], v: _V, name: str) -> Any:
        if spec.struct:
            return Expression(self.text_of(v), self.loc(v))
        if spec.is_numeric:
            return self.numeric(spec, dims, v, name)
        if spec.base == "string":
            if v.kind != "str":
                raise self.error(ParseError, f"'{name}' is a string: expected a string literal, "
                                 f"found '{self.text_of(v)[:40]}'", v)
            return v.data
        if dims:
            if v.kind != "list":
                raise self.error(ParseError, f"'{name}' is an array: expected '{{' with "
                                 f"{math.prod(dims)} values", v)
            if len(v.data) != math.prod(dims):
                raise self.error(ParseError, f"'{name}' has {math.prod(dims)} elements, "
                                 f"the initializer gives {len(v.data)}", v)
            return [self.object_value(spec, item, name) for item in v.data]
        return self.object_value(spec, v, name)

    def object_value(self, spec: TypeSpec, v: _V, name: str) -> Any:
        if v.kind == "null":
            return NullValue(self.loc(v))
        if spec.base == "sampler":
            if v.kind == "sampler":
                return SamplerState([self.state(s, "sampler") for s in v.data], self.loc(v))
        elif spec.base == "stateblock":
            if v.kind in ("stateblock", "sampler"):
                return SamplerState([self.state(s, "pass") for s in v.data], self.loc(v))
        elif spec.base in ("vertexshader", "pixelshader"):
            if v.kind == "asm":
                return self.shader_block(v, "vertex" if spec.base == "vertexshader" else "pixel")
            if v.kind == "compile":
                return self.compile_shader(v)
            if v.kind == "name":
                return ParamRef(v.data, False, None, self.loc(v))
            if v.kind in ("ref", "paren", "index"):
                return self.state_raw(v, None)
        elif spec.base == "texture":
            return Expression(self.text_of(v), self.loc(v))
        raise self.error(ParseError, f"'{name}' ({spec.spelling}) cannot be initialised with "
                         f"'{self.text_of(v)[:40]}'", v)

    def numeric(self, spec: TypeSpec, dims: tuple[int, ...], v: _V, name: str) -> Any:
        try:
            flat = self.flatten(v, [])
        except _NotConstant:
            return Expression(self.text_of(v), self.loc(v))
        shape = dims + type_shape(spec)
        need = math.prod(shape)
        if len(flat) == 1 and need > 1 and not dims:
            flat = flat * need  # a scalar initialises every component (HLSL promotion)
        if len(flat) != need:
            raise self.error(ParseError, f"'{name}' ({spec.spelling}"
                             f"{''.join(f'[{d}]' for d in dims)}) needs {need} "
                             f"value{'s' if need != 1 else ''}, the initializer gives {len(flat)}",
                             v)
        base = spec.base
        if base == "bool":
            return np.array([bool(x) for x in flat], dtype=bool).reshape(shape)
        if base in ("float", "half"):
            try:
                values = [float(x) for x in flat]
            except OverflowError:
                values = [math.inf]
            with np.errstate(over="ignore"):
                arr = np.array(values, dtype=np.float32)
            if not np.all(np.isfinite(arr)):
                raise self.error(ParseError, f"a value for '{name}' is out of range for "
                                 f"{spec.spelling}", v)
            return arr.reshape(shape)
        try:
            ints = [int(x) for x in flat]
        except (OverflowError, ValueError):
            raise self.error(ParseError, f"a value for '{name}' is out of range for "
                             f"{spec.spelling}", v) from None
        lo, hi = min(ints), max(ints)
        if _INT32[0] <= lo and hi <= _INT32[1]:
            dtype = np.int32
        elif _INT64[0] <= lo and hi <= _INT64[1]:
            dtype = np.int64  # hex colours such as 0xff202060 do not fit in int32
        else:
            raise self.error(ParseError, f"a value for '{name}' does not fit in 64 bits", v)
        return np.array(ints, dtype=dtype).reshape(shape)

    def flatten(self, v: _V, out: list) -> list:
        """Numbers of a constant initializer in order; raises _NotConstant otherwise."""
        kind = v.kind
        if kind in ("int", "float", "bool"):
            out.append(v.data)
        elif kind in ("list", "paren"):
            for item in v.data:
                self.flatten(item, out)
        elif kind == "call" and resolve_type(v.data[0]) is not None \
                and resolve_type(v.data[0]).is_numeric:
            for item in v.data[1]:
                self.flatten(item, out)
        else:
            raise _NotConstant
        return out

    # -- shaders --------------------------------------------------------------------------
    def shader_block(self, v: _V, stage_hint: str | None) -> ShaderBlock:
        tok, decl_tok = v.data
        brace = tok.value.index("{")
        body = tok.value[brace + 1:-1]
        line, col = self.lexer.position(tok.start_pos + brace + 1)
        version = None
        stage = stage_hint or "pixel"
        m = _VERSION_RE.match(body, _ASM_GAP_RE.match(body).end())
        if m:
            kind = m.group(1).lower()
            version = f"{kind}_{m.group(2)}_{m.group(3).lower()}"
            stage = "vertex" if kind == "vs" else "pixel"
        decl = self.vertex_decl(decl_tok) if decl_tok is not None else None
        return ShaderBlock(stage, version, body, decl, self.smap.locate(line, col))

    def vertex_decl(self, tok: Token) -> tuple[VertexDeclElement, ...]:
        """DX8 `decl { stream 0; float v0[3]; D3DCOLOR v5; skip 2; }` (a skip is an element
        of type 'skip', register -1, `count` DWORDs)."""
        brace = tok.value.index("{")
        body = tok.value[brace + 1:-1]
        base = tok.start_pos + brace + 1
        clean = re.sub(r"//[^\n]*|/\*.*?\*/", lambda m: " " * len(m.group()), body, flags=re.S)
        elements: list[VertexDeclElement] = []
        stream = 0
        offset = 0
        for stmt in clean.split(";"):
            words = stmt.split()
            start = offset + len(stmt) - len(stmt.lstrip())
            offset += len(stmt) + 1
            if not words:
                continue
            line, col = self.lexer.position(base + start)
            where = self.smap.locate(line, col)
            head = words[0].lower()
            m = None
            if head in ("stream", "skip") and len(words) == 2 and words[1].isdigit():
                if head == "stream":
                    stream = int(words[1])
                else:
                    elements.append(VertexDeclElement(stream, "skip", -1, int(words[1]), where))
                continue
            if head in _DECL_TYPES and len(words) >= 2:
                m = re.fullmatch(r"[vV]([0-9]{1,2})(?:\[([1-4])\])?", "".join(words[1:]))
            if m is None:
                raise self.smap.error_at(ParseError, f"cannot read vertex declaration "
                                         f"'{' '.join(words)[:40]}' (expected 'stream N', "
                                         f"'skip N' or 'TYPE vN[count]')", where)
            count = int(m.group(2)) if m.group(2) else _DECL_TYPES[head]
            elements.append(VertexDeclElement(stream, head, int(m.group(1)), count, where))
        return tuple(elements)

    def compile_shader(self, v: _V) -> CompileShader:
        profile, function, args = v.data
        return CompileShader(profile.lower(), function, tuple(self.text_of(a) for a in args),
                             self.loc(v))

    # -- techniques, passes, states -------------------------------------------------------
    def technique(self, raw: _RawBlock) -> Technique:
        passes = []
        for p in raw.items:
            passes.append(Pass(p.name.value if p.name is not None else None,
                               [self.state(s, "pass") for s in p.items],
                               self.annotations(p.annotations), self.loc(p.keyword)))
        return Technique(raw.name.value if raw.name is not None else None, passes,
                         self.annotations(raw.annotations), self.loc(raw.keyword))

    def state(self, raw: _RawState, context: str) -> StateAssignment:
        name_tok = raw.name
        name = name_tok.value
        index = None if raw.index is None else self.small_int(raw.index, "state index")
        where = self.loc(name_tok)
        info = self.states.lookup_state(name)
        if info is not None and context == "sampler" and info.kind not in ("sampler", "texture"):
            self.complain(f"state '{info.name}' cannot be set inside sampler_state "
                          f"(only sampler states and Texture)", where)
            return StateAssignment(name, self.unknown_value(raw.value), index, False, where)
        if info is None:
            hint = self.states.suggest_state(name)
            message = f"unknown state '{name}'" + (f" (did you mean '{hint}'?)" if hint else "")
            self.complain(message, where)
            return StateAssignment(name, self.unknown_value(raw.value), index, False, where)
        self.check_index(info, index, context, raw, where)
        stage = {"vertexshader": "vertex", "pixelshader": "pixel"}.get(info.type)
        value = self.states.coerce_state_value(info, self.state_raw(raw.value, stage),
                                               self.loc(raw.value), self.param_names)
        return StateAssignment(info.name, value, index, True, where)

    def complain(self, message: str, where: Location) -> None:
        if self.strict:
            raise self.smap.error_at(StateError, message, where)
        self.warnings.append(self.smap.warning_at(message, where))

    def check_index(self, info: Any, index: int | None, context: str, raw: _RawState,
                    where: Location) -> None:
        if context == "sampler":
            if index is not None:
                raise self.error(StateError, f"{info.name} takes no index inside "
                                 f"sampler_state; remove [{index}]", raw.index)
            return
        if index is None or (info.index != "none" and (info.max_index is None
                                                       or index <= info.max_index)):
            self.states.check_index(info, index, where)  # fine, or a missing index
        else:
            self.states.check_index(info, index, self.loc(raw.index))

    def state_raw(self, v: _V, stage: str | None) -> Any:
        """A state value in the form `states.coerce_state_value` reads."""
        kind = v.kind
        if kind in ("int", "float", "bool", "str"):
            return v.data
        if kind == "null":
            return NullValue(self.loc(v))
        if kind == "name":
            return [v.data]
        if kind == "bar":
            if all(o.kind in ("name", "int") for o in v.data):
                return [o.data for o in v.data]
        elif kind == "ref":
            return ParamRef(v.data, True, None, self.loc(v))
        elif kind == "index":
            name, idx = v.data
            if idx.kind == "int":
                return ParamRef(name, False, idx.data, self.loc(v))
        elif kind == "paren":
            if len(v.data) == 1:
                inner = v.data[0]
                if inner.kind in ("name", "index"):
                    ref = self.state_raw(inner, stage)
                    if isinstance(ref, list):
                        return ParamRef(inner.data, False, None, self.loc(v))
                    if isinstance(ref, ParamRef):
                        return ref
                if inner.kind in ("int", "float", "bool", "str", "paren", "ref", "null"):
                    return self.state_raw(inner, stage)
            else:
                try:
                    return tuple(self.flatten(v, []))
                except _NotConstant:
                    pass
        elif kind in ("list", "call"):
            try:
                return tuple(self.flatten(v, []))
            except _NotConstant:
                pass
        elif kind == "asm":
            return self.shader_block(v, stage)
        elif kind == "compile":
            return self.compile_shader(v)
        elif kind == "sampler":
            return SamplerState([self.state(s, "sampler") for s in v.data], self.loc(v))
        elif kind == "stateblock":
            return SamplerState([self.state(s, "pass") for s in v.data], self.loc(v))
        return Expression(self.text_of(v), self.loc(v))

    def unknown_value(self, v: _V) -> Any:
        """The value of an assignment to an unknown state, kept in model form."""
        from effects.model import EnumValue
        raw = self.state_raw(v, None)
        if isinstance(raw, list):
            return EnumValue(tuple(str(x).upper() for x in raw), None, self.loc(v))
        return raw


# =============================================================================================
# Entry point


def parse_effect(pre: Preprocessed, *, strict: bool = False) -> Effect:
    """Parse preprocessed effect text into an `Effect`.

    Unknown state names become warnings in `effect.warnings` (a `StateError` when `strict`).
    Raises `ParseError` / `StateError` located in the original files for bad input.
    """
    # Parsing allocates many small objects and frees none of them until the end; the cyclic
    # collector's passes over them would cost about a tenth of the time, for nothing.
    collecting = gc.isenabled()
    gc.disable()
    try:
        return _parse(pre, strict)
    finally:
        if collecting:
            gc.enable()


def _parse(pre: Preprocessed, strict: bool) -> Effect:
    lexer = EffectLexer(pre.text)
    try:
        items = _lark().parse(lexer)
    except _Located as exc:
        raise pre.source_map.error(ParseError, exc.message, exc.line, exc.column) from None
    except UnexpectedToken as exc:
        message, line, col = _syntax_message(exc, lexer)
        raise pre.source_map.error(ParseError, message, line, col) from None
    except VisitError as exc:  # not raised by the inline transformer, kept for safety
        inner = exc.orig_exc
        if isinstance(inner, _Located):
            raise pre.source_map.error(ParseError, inner.message, inner.line,
                                       inner.column) from None
        raise pre.source_map.error(ParseError, f"cannot parse: {inner}", 1, 1) from None
    except (UnexpectedInput, LarkError) as exc:
        line, col = getattr(exc, "line", 1), getattr(exc, "column", 1)
        if not isinstance(line, int) or not isinstance(col, int):
            line, col = lexer.end_position()
        raise pre.source_map.error(ParseError, f"syntax error: {exc}", line, col) from None
    try:
        return _Builder(pre, lexer, strict).build(items)
    except EffectError as exc:  # errors from the states table come without the source line
        if exc.source_line is None:
            exc.source_line = pre.source_map.source_line(exc.location)
        raise
