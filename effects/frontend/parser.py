"""The effect-file parser: preprocessed text → `Effect` model.

Three steps, one module each:

1. `effects.frontend.lexer.EffectLexer` turns text into lark tokens (hand-written: opaque
   balanced parts, case-insensitive keywords, nesting limits, open-brace bookkeeping).
2. The LALR grammar in `grammar/effect.lark`, with `effects.frontend.shapes.Shapes` as lark's
   inline transformer, builds light raw records carrying positions.
3. `effects.frontend.builder.Builder` turns the records into model objects.

`parse_effect` is the only public entry; every problem becomes a located `ParseError` /
`StateError`, never a lark exception or a Python traceback. The syntax-error messages, which
read the lexer's open-brace bookkeeping, are here.
"""
from __future__ import annotations

import gc

from lark import Token
from lark.exceptions import LarkError, UnexpectedInput, UnexpectedToken, VisitError

from effects.base.errors import EffectError, ParseError
from effects.model import Effect
from effects.frontend.builder import Builder
from effects.frontend.d3d10 import d3d10_error, d3d10_shader_warning, skip_d3d10_techniques
from effects.frontend.lexer import MAX_NESTING, PUNCT, EffectLexer, Located
from effects.frontend.shapes import lark_parser
from effects.frontend.source import Preprocessed
from effects.frontend.types import resolve_type, type_shape

__all__ = ["parse_effect", "EffectLexer", "TERMINAL_WORDS", "MAX_NESTING", "resolve_type",
           "type_shape"]


# =============================================================================================
# Entry point


def parse_effect(pre: Preprocessed, *, strict: bool = False,
                 effect_type: type[Effect] = Effect) -> Effect:
    """Parse preprocessed effect text into an `Effect`.

    Unknown state names become warnings in `effect.warnings` (a `StateError` when `strict`).
    Raises `ParseError` / `StateError` located in the original files for bad input.
    """
    # Parsing allocates many small objects and frees none of them until the end; the cyclic
    # collector's passes over them would cost about a tenth of the time, for nothing.
    collecting = gc.isenabled()
    gc.disable()
    try:
        return _parse(pre, strict, effect_type)
    finally:
        if collecting:
            gc.enable()


def _parse(pre: Preprocessed, strict: bool, effect_type: type[Effect]) -> Effect:
    pre, skipped = skip_d3d10_techniques(pre)
    try:
        effect = _parse_d3d9(pre, strict, effect_type)
    except ParseError as exc:
        # a Direct3D 10/11 effect fails at its first fx_4_0 construct: say that, there
        raise d3d10_error(pre, exc) from None
    effect.warnings[:0] = skipped
    if not effect.techniques:
        warning = d3d10_shader_warning(pre)
        if warning is not None:
            effect.warnings.append(warning)
    return effect


def _parse_d3d9(pre: Preprocessed, strict: bool, effect_type: type[Effect]) -> Effect:
    lexer = EffectLexer(pre.text)
    try:
        items = lark_parser().parse(lexer)
    except Located as exc:
        raise pre.source_map.error(ParseError, exc.message, exc.line, exc.column) from None
    except UnexpectedToken as exc:
        message, line, col = syntax_message(exc, lexer)
        raise pre.source_map.error(ParseError, message, line, col) from None
    except VisitError as exc:  # not raised by the inline transformer, kept for safety
        inner = exc.orig_exc
        if isinstance(inner, Located):
            raise pre.source_map.error(ParseError, inner.message, inner.line,
                                       inner.column) from None
        raise pre.source_map.error(ParseError, f"cannot parse: {inner}", 1, 1) from None
    except (UnexpectedInput, LarkError) as exc:
        line, col = getattr(exc, "line", 1), getattr(exc, "column", 1)
        if not isinstance(line, int) or not isinstance(col, int):
            line, col = lexer.end_position()
        raise pre.source_map.error(ParseError, f"syntax error: {exc}", line, col) from None
    try:
        return Builder(pre, lexer, strict).build(items, effect_type)
    except EffectError as exc:  # errors from the states table come without the source line
        if exc.source_line is None:
            exc.source_line = pre.source_map.source_line(exc.location)
        raise


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
    "TYPEDEF": "'typedef'", "CBUFFER": "'cbuffer'", "CAST": "a cast such as (float4)",
    **{v: f"'{k}'" for k, v in PUNCT.items()}, "OP2": "an operator",
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


def syntax_message(exc: UnexpectedToken, lexer: EffectLexer) -> tuple[str, int, int]:
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
    # An array size may follow a declared name (`float a[4]`, `[N]`, `[]`) and an index a
    # reference (`<L[0]>`): true, but not what a user who forgot the '=', ';' or '>' needs
    # to hear (a state's index stays: `Lighting TRUE` may have meant `Lighting[0]`).
    if expected & {"INDEX", "LSQB"} and tok.type not in ("LSQB", "INDEX") and (
            ctx in ("top", "annotation") or "GT" in expected):
        expected -= {"INDEX", "LSQB"}
    # LALR merges look-aheads of similar states: drop closers that cannot close anything here.
    closers = {"RBRACE", "RPAR", "RSQB"}
    keep = {inner.closer} if inner is not None else set()
    expected -= closers - keep

    if {"FUNC_BODY", "SEMI"} <= expected:   # `float4 PS(...)` then neither `{` nor `;`
        name = f" of '{lexer.decl_name}'" if lexer.decl_name else ""
        return (f"expected a function body or ';' (a prototype) after the parameter list"
                f"{name}, found {found}"), line, col
    # An array size may follow any declared name (`float a[4]`, `[N]`, `[]`): true, but not
    # what a user who forgot the '=' or the ';' needs to hear.
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

