"""`#if` and `#elif` expressions: C integer expressions, evaluated by a small parser.

The line is macro-expanded first (the operand of `defined` excepted), then evaluated by
precedence climbing in signed 64-bit arithmetic (the `u` suffix is accepted but does not make
a value unsigned); never Python's eval. Not done, on purpose: `'c'` character constants.
"""
from __future__ import annotations

import operator
import re
from typing import Callable, Mapping

from effects.base import limits
from effects.base.errors import Location, PreprocessError
from effects.frontend.macros import MacroTable
from effects.frontend.preprocess_tokens import Span, Token, next_solid, tokenize

MAX_EXPRESSION_NESTING = 64     # parentheses and ?: in an #if expression (C guarantees 63)

_INTEGER = re.compile(r"(0[xX][0-9a-fA-F]+|0[0-7]*|[1-9][0-9]*)(?:[uU](?:ll|LL|[lL])?|(?:ll|LL|[lL])[uU]?)?")

ErrorMaker = Callable[[str, Location], PreprocessError]

_BINARY_PRECEDENCE = {"||": 1, "&&": 2, "|": 3, "^": 4, "&": 5, "==": 6, "!=": 6,
                      "<": 7, ">": 7, "<=": 7, ">=": 7, "<<": 8, ">>": 8,
                      "+": 9, "-": 9, "*": 10, "/": 10, "%": 10}
_UNARY = frozenset({"!", "~", "-", "+"})
_ARITHMETIC = {"+": operator.add, "-": operator.sub, "*": operator.mul, "|": operator.or_,
               "^": operator.xor, "&": operator.and_, "==": operator.eq, "!=": operator.ne,
               "<": operator.lt, ">": operator.gt, "<=": operator.le, ">=": operator.ge}


def _int64(value: int) -> int:
    value &= (1 << 64) - 1
    return value - (1 << 64) if value >= 1 << 63 else value


class _Expression:
    """Precedence climbing over the tokens of an #if line; never Python's eval.

    `live` is False inside the operand C does not evaluate (`0 && x`, `1 || x`, the unused
    arm of `?:`), where division by zero is no error.
    """

    def __init__(self, tokens: list[Token], defined: Mapping[str, object], error: ErrorMaker,
                 span: Span, directive: str) -> None:
        self.tokens, self.defined, self.error, self.span = tokens, defined, error, span
        self.where = f"#{directive} expression"
        self.i = 0

    def fail(self, message: str, tok: Token | None = None) -> PreprocessError:
        """An error at `tok`, or just after the end of the line without one."""
        pos = tok.pos if tok is not None else len(self.span.text.rstrip())
        return self.error(message, self.span.location(pos))

    def peek(self) -> str | None:
        if self.i < len(self.tokens):
            tok = self.tokens[self.i]
            return tok.text if tok.kind == "punct" else None
        return None

    def value(self) -> int:
        result = self.conditional(True, 0)
        if self.i < len(self.tokens):
            tok = self.tokens[self.i]
            raise self.fail(f"unexpected '{tok.text[:40]}' in {self.where}", tok)
        return result

    def conditional(self, live: bool, nesting: int) -> int:
        if nesting > MAX_EXPRESSION_NESTING:
            raise self.fail(f"{self.where} nests too deeply", self.tokens[self.i - 1])  # at ( ? or :
        cond = self.binary(1, live, nesting)
        if self.peek() != "?":
            return cond
        self.i += 1
        then = self.conditional(live and cond != 0, nesting + 1)
        self.expect(":")
        other = self.conditional(live and cond == 0, nesting + 1)
        return then if cond != 0 else other

    def expect(self, text: str) -> None:
        if self.peek() != text:
            tok = self.tokens[self.i] if self.i < len(self.tokens) else None
            raise self.fail(f"expected '{text}' in {self.where}", tok)
        self.i += 1

    def binary(self, min_precedence: int, live: bool, nesting: int) -> int:
        left = self.unary(live, nesting)
        while True:
            op = self.peek()
            precedence = _BINARY_PRECEDENCE.get(op)
            if precedence is None or precedence < min_precedence:
                return left
            op_tok = self.tokens[self.i]
            self.i += 1
            if op == "&&":
                right = self.binary(precedence + 1, live and left != 0, nesting)
                left = int(left != 0 and right != 0)
            elif op == "||":
                right = self.binary(precedence + 1, live and left == 0, nesting)
                left = int(left != 0 or right != 0)
            else:
                right = self.binary(precedence + 1, live, nesting)
                left = self.apply(op, left, right, live, op_tok)

    def apply(self, op: str, a: int, b: int, live: bool, tok: Token) -> int:
        if op in ("/", "%"):
            if b == 0:
                if live:
                    raise self.fail(f"division by zero in {self.where}", tok)
                return 0
            quotient = abs(a) // abs(b) * (1 if (a < 0) == (b < 0) else -1)  # C truncates
            return _int64(quotient if op == "/" else a - b * quotient)
        if op in ("<<", ">>"):
            if b < 0:
                if live:
                    raise self.fail(f"negative shift count in {self.where}", tok)
                return 0
            b = min(b, 64)
            return _int64(a << b if op == "<<" else a >> b)
        return _int64(int(_ARITHMETIC[op](a, b)))

    def unary(self, live: bool, nesting: int) -> int:
        ops = []
        while self.peek() in _UNARY:
            ops.append(self.tokens[self.i].text)
            self.i += 1
        value = self.primary(live, nesting)
        for op in reversed(ops):
            value = int(value == 0) if op == "!" else ~value if op == "~" else _int64(-value) if op == "-" else value
        return value

    def primary(self, live: bool, nesting: int) -> int:
        if self.i >= len(self.tokens):
            raise self.fail(f"unexpected end of {self.where}")
        tok = self.tokens[self.i]
        if tok.kind == "punct" and tok.text == "(":
            self.i += 1
            value = self.conditional(live, nesting + 1)
            self.expect(")")
            return value
        if tok.kind == "num":
            match = _INTEGER.fullmatch(tok.text)
            if match is None:
                raise self.fail(f"invalid integer constant '{tok.text[:40]}' in {self.where}", tok)
            digits = match.group(1)
            if len(digits) > limits.get("literal_digits"):
                raise self.fail(limits.message("literal_digits", len(digits), f"an integer in {self.where}"), tok)
            base = 16 if digits[:2] in ("0x", "0X") else 8 if len(digits) > 1 and digits[0] == "0" else 10
            self.i += 1
            return _int64(int(digits, base))
        if tok.kind == "id":
            self.i += 1
            if tok.text != "defined":
                return 0  # an identifier left after expansion counts as 0, as in C
            parens = self.peek() == "("
            if parens:
                self.i += 1
            if self.i >= len(self.tokens) or self.tokens[self.i].kind != "id":
                raise self.fail("'defined' expects a macro name",
                                self.tokens[self.i] if self.i < len(self.tokens) else None)
            name = self.tokens[self.i].text
            self.i += 1
            if parens:
                self.expect(")")
            return int(name in self.defined)
        raise self.fail(f"unexpected '{tok.text[:40]}' in {self.where}", tok)


def evaluate_condition(text: str, rest: int, span: Span, directive: str, macros: MacroTable) -> bool:
    """Whether the expression of the #if or #elif line `text` (from offset `rest`) is true;
    its errors are made by `macros.error`."""
    error = macros.error
    tokens = tokenize(text, rest)
    # The operand of `defined` is a name, not something to expand: hide it from itself.
    for k, tok in enumerate(tokens):
        if tok.kind == "id" and tok.text == "defined":
            k = next_solid(tokens, k + 1)
            if k < len(tokens) and tokens[k].text == "(":
                k = next_solid(tokens, k + 1)
            if k < len(tokens) and tokens[k].kind == "id":
                tokens[k] = tokens[k]._replace(hide=frozenset((tokens[k].text,)))
    tokens = [t for t in macros.expand(tokens, span, 0, top=False) if t.kind != "ws"]
    if not tokens:
        raise error(f"#{directive} with no expression", span.location(rest))
    try:
        return _Expression(tokens, macros.defined, error, span, directive).value() != 0
    except RecursionError:
        raise error(f"#{directive} expression nests too deeply",
                    span.location(tokens[0].pos)) from None

