"""The HLSL lexer's loop (lexing.py): the tokens, types and positions lark's contextual lexer
made, and lark's own error where nothing matches."""
from __future__ import annotations

from importlib import resources

import lark
import pytest

from effects.base.errors import Location
from effects.shaders.hlsl import parse as parse_module
from effects.shaders.hlsl.lexing import FastContextualLexer
from effects.shaders.hlsl.parse import HlslError, Origin, parse


def _lark(fast: bool, seen: list) -> lark.Lark:
    """The project's grammar and options, with lark's loop or ours; `seen` gets every token."""
    class Recording(parse_module._TypeNames):
        def process(self, stream):
            for tok in super().process(stream):
                seen.append((tok.type, str(tok), tok.start_pos, tok.line, tok.column,
                             tok.end_line, tok.end_column, tok.end_pos))
                yield tok
    grammar = resources.files("effects.shaders.hlsl").joinpath("grammar/hlsl.lark").read_text()
    return lark.Lark(grammar, parser="lalr", lexer="contextual",
                     start=["function_def", "initializer"], postlex=Recording(),
                     maybe_placeholders=True, transformer=parse_module._Build(),
                     _plugins={"ContextualLexer": FastContextualLexer} if fast else {})


def test_the_parser_uses_the_loop():
    assert type(parse_module.parser().parser.lexer.lexer) is FastContextualLexer


def test_tokens_types_and_positions():
    seen: list = []
    _lark(True, seen).parse("float4 f() {\n  // c\n  static float x = 1;\n  return x >= 2; }",
                            start="function_def")
    assert seen[:4] == [("TYPE", "float4", 0, 1, 1, 1, 7, 6), ("NAME", "f", 7, 1, 8, 1, 9, 8),
                        ("LPAR", "(", 8, 1, 9, 1, 10, 9), ("RPAR", ")", 9, 1, 10, 1, 11, 10)]
    # a comment and two newlines skipped; `static` a VMOD where a statement starts (the
    # state's terminals, not FMOD), `=` the declarator's EQUAL, `return` a keyword NAME
    # retyped, `>=` one RELOP
    assert seen[5:9] == [("VMOD", "static", 22, 3, 3, 3, 9, 28),
                         ("TYPE", "float", 29, 3, 10, 3, 15, 34),
                         ("NAME", "x", 35, 3, 16, 3, 17, 36),
                         ("EQUAL", "=", 37, 3, 18, 3, 19, 38)]
    assert seen[11:14] == [("RETURN", "return", 44, 4, 3, 4, 9, 50),
                           ("NAME", "x", 51, 4, 10, 4, 11, 52),
                           ("RELOP", ">=", 53, 4, 12, 4, 14, 55)]


@pytest.mark.parametrize("text", [
    "float4 f(float2 uv : TEXCOORD0) : COLOR { float4x4 m = (float4x4)0;\n"
    "  for (int i = 0; i < 4; i++) { m[i] += 0x1F * 1.5e-2f; }\n"
    "  if (uv.x >>= 2 && !uv.y) discard; return vector<float, 4>(1, 2, 3, 4); }",
    "float f() { T t = (T)0; typedef float3 V, W; V v; return v.x; }",
    "float f() { return 1 $ 2; }",            # no terminal matches `$`: lark's error
    "float f() { float x = 1 }",              # a token the state does not take
    "float f() { matrix<float, 4, 4.5> m; }",
    "float f() { /* open",
    "float f() { // caf\u00e9\n  return 1; }",   # outside ASCII: the whole alternation
    "float f() { return \u00e9; }",
])
def test_same_tokens_and_errors_as_larks_loop(text):
    results = []
    for fast in (False, True):
        seen: list = []
        parse_module._LOCAL.names = frozenset({"T"})
        try:
            outcome = ("tree", _lark(fast, seen).parse(text, start="function_def"))
        except lark.exceptions.UnexpectedInput as exc:
            outcome = (type(exc).__name__, exc.line, exc.column, str(getattr(exc, "token", "")),
                       getattr(exc, "pos_in_stream", None))
        results.append((outcome, seen))
    assert results[0] == results[1]


def test_an_unknown_character_is_located():
    text = "float f()\n{\n  return 1 $ 2;\n}"
    with pytest.raises(HlslError) as err:
        parse(text, "function_def", Origin(Location("t.fx", 10, 1), text))
    assert "X3000" in str(err.value) and "'$'" in str(err.value)
    assert (err.value.location.line, err.value.location.column) == (12, 12)
