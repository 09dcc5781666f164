"""The HLSL grammar (grammar/hlsl.lark), built once, and located syntax errors.

A captured function's text starts at `Function.location`; the preprocessor keeps directive
lines as blank lines, so line k of the text is file line `location.line + k - 1` (column
offset on the first line only).
"""
from __future__ import annotations

import threading
from importlib import resources
from typing import Any

import lark

from effects.base.errors import EffectError, EffectWarning, Location


class HlslError(EffectError):
    """An HLSL function does not compile (fxc's error number leads the message)."""


_LOCK = threading.Lock()
_PARSER: lark.Lark | None = None
_LOCAL = threading.local()     # the type names of the text being parsed now


class _TypeNames:
    """fxc's lexer knows the user type names (structs and typedefs declared so far): a NAME
    that is one becomes TYPENAME, so `(VS_OUTPUT)0` is a cast and `(x)` stays an expression.
    A `typedef` in the text adds its name for the rest of the text."""

    always_accept = ("NAME",)

    def process(self, stream):
        names = set(getattr(_LOCAL, "names", ()))
        after_typedef = False
        for tok in stream:
            if tok.type == "NAME":
                if tok.value in names:
                    tok = lark.Token.new_borrow_pos("TYPENAME", tok.value, tok)
                elif after_typedef:            # `typedef float3 V;`: V names a type from here
                    names.add(tok.value)
                    after_typedef = False
            elif tok.type == "TYPEDEF":
                after_typedef = True
            elif tok.type == "SEMICOLON":
                after_typedef = False
            yield tok


# C's binary precedence, loosest first: the grammar reads `a op b op c ...` as one flat chain
# and `_Build.binchain` nests it into the `binary` trees a rule per level would have built.
_PRECEDENCE = {name: k for k, name in enumerate(
    ("OROR", "ANDAND", "BAR", "CARET", "AMP", "EQOP", "RELOP", "SHIFTOP", "ADDOP", "MULOP"))}
# The punctuation tokens the grammar keeps only to place the rule they open (see `_lead`).
_LEADS = frozenset(("STRUCT", "LPAR", "LBRACE", "LSQB", "COLON", "SEMICOLON"))


def _place(tree: lark.Tree, tok: lark.Token) -> lark.Tree:
    meta = tree.meta
    meta.line, meta.column, meta.empty = tok.line, tok.column, False
    return tree


def _lead(data: str):
    """The callback of a rule that opens with punctuation (`{ ... }`, `[n]`, `: SEM`, `(T)x`,
    `;`, `struct`): the tree without those tokens, placed at the first one."""
    def build(children: list[Any]) -> lark.Tree:
        first = children[0] if children else None
        kept = [c for c in children if not (isinstance(c, lark.Token) and c.type in _LEADS)]
        tree = lark.Tree(data, kept)
        if isinstance(first, lark.Token) and first.type in _LEADS:
            _place(tree, first)
        return tree
    return build


class _Build:
    """Callbacks lark runs as it reduces (LALR's embedded transformer). Positions: lark's
    propagate_positions set a Meta on every node at every reduction, most of the parse's time;
    here a node is placed when asked (`start_of`), from its first token, as lark placed it."""

    struct_def = staticmethod(_lead("struct_def"))
    semantic = staticmethod(_lead("semantic"))
    register = staticmethod(_lead("register"))
    dims = staticmethod(_lead("dims"))
    block = staticmethod(_lead("block"))
    empty = staticmethod(_lead("empty"))
    attr = staticmethod(_lead("attr"))
    cast = staticmethod(_lead("cast"))

    @staticmethod
    def init_list(children: list[Any]) -> lark.Tree:
        # one name for `{ a, b }` (opens with its brace) and the list inside it
        return _lead("init_list")(children)

    @staticmethod
    def paren(children: list[Any]) -> lark.Tree:
        """`(e)` is e's tree, which starts at its parenthesis for the node that holds it."""
        tok, tree = children
        meta = tree.meta
        meta.container_line, meta.container_column = tok.line, tok.column
        return tree

    @staticmethod
    def binchain(items: list[Any]) -> lark.Tree:
        operands, ops = [items[0]], []
        for k in range(1, len(items), 2):
            op = items[k]
            level = _PRECEDENCE[op.type]
            while ops and _PRECEDENCE[ops[-1].type] >= level:     # left-associative
                b = operands.pop()
                operands.append(lark.Tree("binary", [operands.pop(), ops.pop(), b]))
            ops.append(op)
            operands.append(items[k + 1])
        while ops:
            b = operands.pop()
            operands.append(lark.Tree("binary", [operands.pop(), ops.pop(), b]))
        return operands[0]


def start_of(tree: lark.Tree) -> tuple[int, int] | None:
    """(line, column) where `tree` starts, None for one without tokens (an empty `dims`): its
    first child's start, a parenthesised child at its parenthesis (lark's rule for
    propagate_positions, which this replaces). Kept on the node once found (and on the nodes
    walked to find it). Walked with an explicit stack: a 5,000-term sum is a tree 5,000 deep
    down its left side."""
    # each frame: [tree, index of the next child to look at]; a child's start, once found,
    # is its parents' start too
    stack: list[list[Any]] = [[tree, 0]]
    found: tuple[int, int] | None = None
    while stack:
        frame = stack[-1]
        node, k = frame
        meta = node.meta
        if found is None and not meta.empty:
            found = (meta.line, meta.column)
        if found is not None:
            meta.line, meta.column = found
            meta.empty = False
            stack.pop()
            continue
        if k >= len(node.children):
            stack.pop()                      # no token below it: its parent looks further on
            continue
        frame[1] = k + 1
        child = node.children[k]
        if child is None:
            continue
        if isinstance(child, lark.Token):
            found = (child.line, child.column)
            continue
        cm = child.meta
        if hasattr(cm, "container_line"):
            found = (cm.container_line, cm.container_column)
            continue
        stack.append([child, 0])
    return found


def parser() -> lark.Lark:
    global _PARSER
    with _LOCK:
        if _PARSER is None:
            text = resources.files("effects.shaders.hlsl").joinpath("grammar/hlsl.lark").read_text()
            _PARSER = lark.Lark(text, parser="lalr", lexer="contextual",
                                start=["function_def", "struct_def", "typedef_decl",
                                       "initializer"], postlex=_TypeNames(),
                                maybe_placeholders=True,
                                transformer=_Build(), cache=True)
        return _PARSER


class Origin:
    """Maps (line, column) in a captured text to the .fx file."""

    def __init__(self, base: Location, text: str, source_lines: dict[str, list[str]] | None = None,
                 row_major: bool = False) -> None:
        self.base = base
        self.lines = text.split("\n")
        self.row_major = row_major     # the text stands under `#pragma pack_matrix(row_major)`
        self._places: dict[int, tuple[Any, Location]] = {}

    def loc(self, line: int, column: int) -> Location:
        col = column + (self.base.column - 1 if line == 1 else 0)
        return Location(self.base.path, self.base.line + line - 1, col)

    def line_text(self, line: int) -> str | None:
        if 1 <= line <= len(self.lines):
            pad = " " * (self.base.column - 1) if line == 1 else ""
            return pad + self.lines[line - 1]
        return None

    def at(self, item: Any) -> Location:
        """The file location of a lark Token or Tree (kept: an unrolled loop asks again for
        the same tokens' places thousands of times)."""
        hit = self._places.get(id(item))
        if hit is not None and hit[0] is item:
            return hit[1]
        if isinstance(item, lark.Token):
            loc = self.loc(item.line or 1, item.column or 1)
        else:
            pos = start_of(item) if isinstance(item, lark.Tree) else None
            loc = self.loc(*pos) if pos is not None else self.loc(1, 1)
        self._places[id(item)] = (item, loc)      # the item kept with it: its id stays its own
        return loc

    def error(self, message: str, item: Any) -> HlslError:
        loc = item if isinstance(item, Location) else self.at(item)
        return HlslError(message, loc, source_line=self.line_text(loc.line - self.base.line + 1))

    def warning(self, message: str, loc: Location) -> EffectWarning:
        return EffectWarning(message, loc, self.line_text(loc.line - self.base.line + 1))


_TREES: dict[tuple[str, str, frozenset[str]], lark.Tree] = {}
TREE_CACHE = 512


def parse(text: str, start: str, origin: Origin, type_names: frozenset[str] = frozenset()) -> lark.Tree:
    """The tree of `text`, where `type_names` are the user types declared before it (kept by
    text and names: validation compiles one function for many cards and targets; the
    evaluator never changes a tree)."""
    key = (text, start, type_names)
    hit = _TREES.get(key)
    if hit is not None:
        return hit
    try:
        _LOCAL.names = type_names
        tree = parser().parse(text, start=start)
        with _LOCK:
            if len(_TREES) >= TREE_CACHE:
                _TREES.pop(next(iter(_TREES)))
            _TREES[key] = tree
        return tree
    except lark.exceptions.UnexpectedInput as exc:
        line, col = getattr(exc, "line", 1) or 1, getattr(exc, "column", 1) or 1
        token = getattr(exc, "token", None)
        what = f"'{token}'" if token else "end of input" if token is not None else "this"
        if isinstance(exc, lark.exceptions.UnexpectedCharacters):
            what = f"'{text[exc.pos_in_stream]}'" if exc.pos_in_stream < len(text) else "end"
        raise origin.error(f"X3000: syntax error: unexpected {what}", origin.loc(line, col)) from None
