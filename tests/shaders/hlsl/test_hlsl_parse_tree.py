"""The HLSL parse trees: binary operators nested by C's precedence (the grammar reads them as
one flat chain, parse.py nests it), and node positions found from tokens (no lark
propagate_positions) where lark placed them: a node at its first token, a parenthesised operand
at its parenthesis, a rule that opens with punctuation (`{`, `[`, `:`, `(T)`) at it."""
from __future__ import annotations

import lark
import pytest

from effects.base.errors import Location
from effects.shaders.hlsl.parse import HlslError, Origin, parse, start_of


def _tree(text: str, start: str = "initializer") -> lark.Tree:
    return parse(text, start, Origin(Location("t.fx", 1, 1), text))


def _shape(t) -> str:
    """Fully parenthesised text of a binary/prefix tree of names."""
    if isinstance(t, lark.Token):
        return str(t)
    if t.data == "binary":
        a, op, b = t.children
        return f"({_shape(a)} {op} {_shape(b)})"
    if t.data == "prefix":
        return f"({t.children[0]}{_shape(t.children[1])})"
    if t.data == "var":
        return str(t.children[0])
    if t.data == "ternary":
        return "(" + " ? ".join(_shape(c) for c in t.children) + ")"
    if t.data == "assign":
        a, op, b = t.children
        return f"({_shape(a)} {op} {_shape(b)})"
    raise AssertionError(t.data)


@pytest.mark.parametrize("text, shape", [
    ("a + b * c", "(a + (b * c))"),
    ("a * b + c", "((a * b) + c)"),
    ("a - b - c", "((a - b) - c)"),                       # left-associative
    ("a / b * c % d", "(((a / b) * c) % d)"),
    ("a || b && c | d ^ e & f == g < h << i + j * k",
     "(a || (b && (c | (d ^ (e & (f == (g < (h << (i + (j * k))))))))))"),
    ("a * b + c << d < e == f & g ^ h | i && j || k",
     "((((((((((a * b) + c) << d) < e) == f) & g) ^ h) | i) && j) || k)"),
    ("a < b == c > d", "((a < b) == (c > d))"),
    ("-a * b", "((-a) * b)"),
    ("a + -b * !c", "(a + ((-b) * (!c)))"),
    ("a ? b + c : d * e", "(a ? (b + c) ? (d * e))"),
    ("a = b = c + d", "(a = (b = (c + d)))"),
    ("a || b ? c : d && e", "((a || b) ? c ? (d && e))"),
    ("a + (b + c) * d", "(a + ((b + c) * d))"),
])
def test_binary_operators_nest_by_c_precedence(text, shape):
    assert _shape(_tree(text)) == shape


def test_positions_come_from_the_first_token_and_parentheses():
    text = "x +\n  (y + z) * w"
    t = _tree(text)                          # (x + ((y + z) * w))
    assert start_of(t) == (1, 1)
    mul = t.children[2]
    assert mul.data == "binary" and str(mul.children[1]) == "*"
    assert start_of(mul) == (2, 3)           # at the parenthesis, as lark placed it
    inner = mul.children[0]
    assert str(inner.children[1]) == "+" and start_of(inner) == (2, 4)   # itself: at y


def test_rules_opening_with_punctuation_are_placed_at_it():
    fn = _tree("float4 F(float2 uv : TEXCOORD0) : COLOR\n{\n    float a[2] = { 1, 2 };\n"
               "    ;\n    return (float4)a[0];\n}", "function_def")
    block = fn.children[-1]
    assert block.data == "block" and start_of(block) == (2, 1)
    decl, empty, ret = block.children
    declarator = decl.children[-1]
    dims = declarator.children[1]
    assert dims.data == "dims" and start_of(dims) == (3, 12)
    init = declarator.children[3]
    assert init.data == "init_list" and start_of(init) == (3, 18)
    assert empty.data == "empty" and start_of(empty) == (4, 5)
    cast = ret.children[1]
    assert cast.data == "cast" and start_of(cast) == (5, 12)
    semantic = fn.children[4]
    assert semantic.data == "semantic" and start_of(semantic) == (1, 33)
    assert start_of(fn) == (1, 1)


def test_an_empty_dims_has_no_position_and_locates_at_the_text_start():
    fn = _tree("float F() { float a; return a; }", "function_def")
    dims = fn.children[-1].children[0].children[-1].children[1]
    assert dims.data == "dims" and dims.children == [] and start_of(dims) is None
    assert Origin(Location("t.fx", 7, 3), "").at(dims) == Location("t.fx", 7, 3)


# where the level-per-rule grammar put them (an unclosed parenthesis: at the last token)
@pytest.mark.parametrize("text, where", [("a + * b", (1, 5)), ("(a + b", (1, 6)),
                                         ("a b", (1, 3)), ("a + b)", (1, 6))])
def test_syntax_errors_are_where_the_level_per_rule_grammar_put_them(text, where):
    with pytest.raises(HlslError) as info:
        _tree(text)
    assert (info.value.location.line, info.value.location.column) == where
