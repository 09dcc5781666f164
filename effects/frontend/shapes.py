"""Grammar shapes → raw records: lark's inline transformer for `grammar/effect.lark`.

`Shapes` has one small method per grammar shape and builds light records carrying positions
(`V` values, `RawState`, `RawBlock`, `RawParam`); no parse tree is built. `effects.frontend.
builder` turns the records into model objects.
"""
from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any

from lark import Lark, Token, Transformer

from effects.frontend.lexer import LexerAdapter, Located

__all__ = ["V", "RawState", "RawBlock", "RawParam", "Shapes", "int_value", "lark_parser"]


class V:
    """A value as written: `kind` says its shape, `data` its parts, start/end its text span."""

    __slots__ = ("kind", "data", "start", "end", "line", "column")

    def __init__(self, kind: str, data: Any, start: int, end: int, line: int, column: int) -> None:
        self.kind, self.data = kind, data
        self.start, self.end, self.line, self.column = start, end, line, column


def _tok_v(kind: str, data: Any, tok: Token) -> V:
    return V(kind, data, tok.start_pos, tok.end_pos, tok.line, tok.column)


def _span_v(kind: str, data: Any, first: Any, last: Any) -> V:
    f_start, f_line, f_col = ((first.start, first.line, first.column) if isinstance(first, V)
                              else (first.start_pos, first.line, first.column))
    end = last.end if isinstance(last, V) else last.end_pos
    return V(kind, data, f_start, end, f_line, f_col)


class RawState:
    __slots__ = ("name", "index", "value")

    def __init__(self, name: Token, index: Token | None, value: V) -> None:
        self.name, self.index, self.value = name, index, value


class RawBlock:
    """A technique or pass: keyword token, optional name, annotations, items."""

    __slots__ = ("keyword", "name", "annotations", "items")

    def __init__(self, keyword: Token, name: Token | None, annotations: list, items: list) -> None:
        self.keyword, self.name, self.annotations, self.items = keyword, name, annotations, items


class RawParam:
    __slots__ = ("storage", "type", "name", "dims", "semantic", "annotations", "value",
                 "tbuffer")

    def __init__(self, *fields: Any) -> None:
        (self.storage, self.type, self.name, self.dims, self.semantic, self.annotations,
         self.value) = fields
        self.tbuffer = ""          # the tbuffer it is declared in (Parameter.tbuffer)


INT_SUFFIX = "uUlL"
_FLOAT_SUFFIX = "fFhHlL"


def int_value(text: str) -> int:
    """An integer literal of the effect's own syntax. A leading 0 is octal, as in HLSL code
    (effects/shaders/hlsl/context.py int_literal): fxc's fx_2_0 binary of Wine's d3dx9 test
    effect holds 65 and 66 for `int i_2[2] = {0101, 0102}` (tests/data/fxo/wine)."""
    text = text.strip("[] \t").rstrip(INT_SUFFIX)
    if text[:2] in ("0x", "0X"):
        return int(text, 16)
    if len(text) > 1 and text[0] == "0" and not set(text) - set("01234567"):
        return int(text, 8)
    return int(text)


class Shapes(Transformer):
    """lark's inline transformer: one small method per grammar shape, no tree is built."""

    def start(self, c): return c[0]

    def items(self, c):
        if not c:
            return []
        if isinstance(c[1], list):        # the declarators of one declaration
            c[0].extend(c[1])
        elif not isinstance(c[1], Token):  # a free-standing ';' adds nothing
            c[0].append(c[1])
        return c[0]

    passes = states = cbuffer_items = items

    # -- literals -------------------------------------------------------------------------
    def int(self, c): return _tok_v("int", int_value(c[0].value), c[0])
    def float(self, c):
        tok = c[0]
        value = float(tok.value.rstrip(_FLOAT_SUFFIX))
        if math.isinf(value):
            raise Located(f"number {tok.value} is out of range", tok.line, tok.column)
        return _tok_v("float", value, tok)

    def string(self, c):
        # adjacent literals are one string, as in C ("Draw=Buffer;" "ScriptExternal=;")
        if len(c) == 1:
            return _tok_v("str", _unescape(c[0].value[1:-1]), c[0])
        return _span_v("str", "".join(_unescape(t.value[1:-1]) for t in c), c[0], c[-1])
    def true(self, c): return _tok_v("bool", True, c[0])
    def false(self, c): return _tok_v("bool", False, c[0])
    def null(self, c): return _tok_v("null", None, c[0])

    # -- operands -------------------------------------------------------------------------
    def name(self, c): return _tok_v("name", c[0].value, c[0])

    def const_index(self, c):
        if len(c) > 2:  # `world[3][2]`
            return _span_v("mindex", (c[0].value, [int_value(t.value) for t in c[1:]]),
                           c[0], c[-1])
        return _span_v("index", (c[0].value, _tok_v("int", int_value(c[1].value), c[1])),
                       c[0], c[1])

    def angle_index_ref(self, c):  # `<g_vLightPos[0]>`
        return _span_v("ref", (c[1].value, int_value(c[2].value)), c[0], c[3])

    def cast(self, c):  # `(float4)0`: the type, and the value it converts
        return _span_v("cast", (c[0].value.strip("() \t"), c[1]), c[0], c[1])

    def ann_paren(self, c):  # `string Format = (FMT);`: the value inside
        inner = c[1]
        return V(inner.kind, inner.data, inner.start, inner.end, inner.line, inner.column)

    def index(self, c): return _span_v("index", (c[0].value, c[2]), c[0], c[3])
    def call(self, c): return _span_v("call", (c[0].value, c[2] or []), c[0], c[3])
    def call_index(self, c): return _span_v("expr", None, c[0], c[-1])
    def paren(self, c): return _span_v("paren", c[1], c[0], c[2])
    def angle_ref(self, c): return _span_v("ref", c[1].value, c[0], c[2])
    def list(self, c): return _span_v("list", c[1], c[0], c[2])
    def list_items(self, c): return c[::2]
    def args(self, c): return c[::2]

    def neg(self, c):
        v = c[1]
        if v.kind in ("int", "float"):
            return _span_v(v.kind, -v.data, c[0], v)
        return _span_v("expr", None, c[0], v)

    def pos(self, c):
        """`+1.0f` (an XNA game's light positions `{-1.0f, +1.0f, -1.0f}`): the value itself."""
        v = c[1]
        if v.kind in ("int", "float"):
            return _span_v(v.kind, v.data, c[0], v)
        return _span_v("expr", None, c[0], v)

    def unary(self, c): return _span_v("expr", None, c[0], c[1])

    def chain(self, c):
        operands = c[::2]
        if all(op.type == "BAR" for op in c[1::2]):
            return _span_v("bar", operands, c[0], c[-1])
        # the operands and operators in order, for what must be constant (an array size)
        return _span_v("expr", (operands, [op.value for op in c[1::2]]), c[0], c[-1])

    def asm(self, c): return _tok_v("asm", (c[0], None), c[0])
    def decl_asm(self, c): return _span_v("asm", (c[1], c[0]), c[0], c[1])

    def compile(self, c):
        return _span_v("compile", (c[1].value, c[2].value, c[4] or []), c[0], c[5])

    def sampler_state(self, c): return _span_v("sampler", c[2], c[0], c[3])
    def stateblock_state(self, c): return _span_v("stateblock", c[2], c[0], c[3])

    # -- statements -----------------------------------------------------------------------
    def state(self, c): return RawState(c[0], None, c[2])
    def indexed_state(self, c): return RawState(c[0], c[1], c[3])
    def pass_block(self, c): return RawBlock(c[0], c[1], c[2] or [], c[4])
    def technique(self, c): return RawBlock(c[0], c[1], c[2] or [], c[4])
    def annotations(self, c): return c[1:-1]
    def annotation(self, c): return (c[0], c[1], c[4], c[2])
    def initializer(self, c): return c[1]
    def semantic(self, c): return c[1].value
    def register_semantic(self, c): return f"{c[1].value}({c[3].value})"
    # `: register(vs, c0)`: a binding for one profile (a target such as ps_2_0, or vs / ps)
    def register_profile_semantic(self, c): return f"{c[1].value}({c[3].value}, {c[5].value})"
    # `: packoffset(c1.y)`: a register and a lane (builder._registers reads it)
    def component_semantic(self, c): return f"{c[1].value}({c[3].value}.{c[5].value})"
    def semantics(self, c): return c
    def storage(self, c): return c
    def dims(self, c): return c
    def expr_dim(self, c): return ("expr", c[1])
    def unsized_dim(self, c): return ("unsized", c[0])

    def declarator(self, c): return c

    def param_decl(self, c):
        storage, type_tok, declarators = c[0], c[1], c[2::2]
        return [RawParam(storage, type_tok, d[0], d[1], d[2], d[3] or [], d[4])
                for d in declarators]

    def typedef(self, c): return ("typedef", c)

    def func_def(self, c): return ("function", c)
    def func_decl(self, c): return c[-1]   # the ';': `items` keeps nothing for it
    def struct_def(self, c): return ("struct", c)
    def cbuffer(self, c):
        """Its members' declarators, as `items` takes a list; a tbuffer's know its name."""
        if c[0].value == "tbuffer":
            for raw in c[4]:
                if isinstance(raw, RawParam):
                    raw.tbuffer = c[1].value
        return c[4]

    def struct_vars(self, c):
        """`struct S { ... } a, b = { ... };`: the struct (its text ends at its body), then a
        parameter of it per declarator, as `S a, b = { ... };` declares them."""
        struct_tok, name_tok, body = c[0], c[1], c[2]
        return [("struct", [struct_tok, name_tok, body, body])] + [
            RawParam([], name_tok, d[0], d[1], d[2], d[3] or [], d[4]) for d in c[3::2]]

    def anonymous_struct_vars(self, c):
        """`struct { float f; int i; } s = { ... };` (fxc takes an unnamed struct type for
        the variables it declares): the struct under a name no source can spell, as
        `typedef struct { ... } NAME;` would name it, then the variables as struct_vars."""
        struct_tok, body = c[0], c[1]
        name_tok = Token.new_borrow_pos("NAME", anonymous_struct_name(struct_tok), struct_tok)
        return [("typedef_struct", [None, struct_tok, None, body, name_tok, None])] + [
            RawParam([], name_tok, d[0], d[1], d[2], d[3] or [], d[4]) for d in c[2::2]]

    def typedef_struct(self, c): return ("typedef_struct", c)


def anonymous_struct_name(at: Token) -> str:
    """The name an unnamed struct type goes by (in messages too): where it was declared."""
    return f"__unnamed_struct_{at.line}_{at.column}"


_ESCAPES = {"n": "\n", "t": "\t", "r": "\r", "\\": "\\", '"': '"', "'": "'", "0": "\0"}


def _unescape(body: str) -> str:
    if "\\" not in body:
        return body
    return re.sub(r"\\(.)", lambda m: _ESCAPES.get(m.group(1), m.group(1)), body)


_GRAMMAR_PATH = Path(__file__).with_name("grammar") / "effect.lark"
_parser: Lark | None = None


def lark_parser() -> Lark:
    """The LALR parser, built once per process; lark also caches its tables on disk
    (`cache=True`, keyed by the grammar text), which makes the first load ~15x faster."""
    global _parser
    if _parser is None:
        _parser = Lark(_GRAMMAR_PATH.read_text(), parser="lalr", lexer=LexerAdapter,
                       transformer=Shapes(), maybe_placeholders=True, cache=True)
    return _parser

