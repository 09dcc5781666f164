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

from effects.base import caches
from effects.base.errors import EffectError, EffectWarning, Location, through_expansion
from effects.shaders.hlsl.lexing import FastContextualLexer


# fxc's errors that no target compiles past: the program is not HLSL (syntax, types, names,
# l-values, calls, flow statements). One row per code; a code not here (X3507 an unknown or
# too old target, X3511 a loop this target must unroll, X3512 a run-time index this target
# cannot make, X3535 integer hardware, X3536 a pixel-only statement in a vertex shader, X4014
# gradients in flow, X4502/X4503/X4530/X4541 the target's semantics, X4532 what ps_1_x cannot
# express, an internal error) is a refusal for the target, which a card's reason reports.
# The codes and texts are fxc's as recorded by DXC's verify tests (`fxc-error {{...}}` notes in
# tools/clang/test/HLSL*), the d3dx9 HLSL compiler's message table, and ReShade's FX parser,
# which reports fxc's codes; each raise says which where it is not obvious.
LANGUAGE_CODES = frozenset({
    "X3000",    # syntax error; an unknown type or struct; a statement or operator not HLSL
    "X3003",    # redefinition of a name in its scope (a local, a parameter, a function of
                # the same signature, a struct or a member)
    "X3004",    # undeclared identifier
    "X3006",    # a local declared 'extern'
    "X3012",    # a const local without an initial value
    "X3013",    # no matching function or intrinsic overload; not a compile-time constant
    "X3014",    # wrong number of arguments to a numeric constructor
    "X3017",    # cannot convert between types
    "X3018",    # invalid subscript (member, swizzle, write mask)
    "X3019",    # a condition (if, while, do, for) that is not a scalar
    "X3020",    # type mismatch (a comparison, a ternary's values or its condition's size)
    "X3022",    # scalar, vector, or matrix expected (an operator on a struct or an object)
    "X3025",    # l-value is const (a global, a uniform, a const local)
    "X3036",    # a local of a function's body named as one of its parameters
    "X3037",    # a constructor of a non-numeric type
    "X3038",    # a void variable, parameter or struct member
    "X3044",    # a parameter without a default after one with a default
    "X3045",    # an out or inout parameter with a default value
    "X3046",    # an out or inout parameter declared 'const'
    "X3047",    # a local declared 'uniform'
    "X3048",    # conflicting usages (row_major with column_major)
    "X3052",    # a vector dimension outside 1 to 4
    "X3053",    # a matrix dimension outside 1 to 4
    "X3058",    # array dimensions of struct members must be literal
    "X3059",    # an array dimension outside 1 to 65536
    "X3067",    # ambiguous function call
    "X3076",    # a void function with a semantic
    "X3077",    # row_major / column_major on a type that is not a matrix
    "X3079",    # a void function returns a value
    "X3080",    # a function must return a value
    "X3082",    # a bitwise operator on a float (int or unsigned int type required)
    "X3120",    # invalid type for an index
    "X3121",    # an index on a type that has no elements
    "X3122",    # a vector<T, n> whose T is not a scalar type
    "X3123",    # a matrix<T, r, c> whose T is not a scalar type
    "X3500",    # recursive call
    "X3501",    # the entry point is not in the file
    "X3504",    # a literal array index out of bounds
    "X3518",    # break outside a loop
    "X3519",    # continue outside a loop
    "X3533",    # a non-empty case of a switch that does not end in break or return
    "X4500",    # two variables read whose register() bindings overlap ("overlapping
                # register semantics not yet implemented": fxc's generic not-yet-implemented
                # code, raised here for the file's bindings only)
    "X4504",    # an output semantic written twice (overlapping output semantics)
})


def is_language_message(message: str) -> bool:
    """Whether `message` (fxc's code first, as every HlslError's is) is a language error."""
    return message[:5] in LANGUAGE_CODES and message[5:6] == ":"


class HlslError(EffectError):
    """An HLSL function does not compile (fxc's error number leads the message). `language`
    (see EffectError) comes from the code's row in LANGUAGE_CODES unless the raise says."""

    def __init__(self, message: str, location: Location | None = None, *,
                 source_line: str | None = None, language: bool | None = None) -> None:
        self.language = is_language_message(message) if language is None else language
        super().__init__(message, location, source_line=source_line)


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
        naming = False                         # past a typedef's first name: `, W` names one
        after_struct = False                   # `struct L { ... }` in a function names L
        for tok in stream:
            named, after_struct = after_struct, False
            if tok.type == "NAME":
                if tok.value in names:
                    tok = lark.Token.new_borrow_pos("TYPENAME", tok.value, tok)
                elif after_typedef:            # `typedef float3 V;`: V names a type from here
                    names.add(tok.value)
                    after_typedef, naming = False, True
                elif named:
                    names.add(tok.value)
            elif tok.type == "STRUCT":
                after_struct = True
            elif tok.type == "TYPEDEF":
                after_typedef = True
            elif tok.type == "SEMICOLON":
                after_typedef = naming = False
            elif tok.type == "COMMA" and naming:   # `typedef float4 C4, Colour;`
                after_typedef = True
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
    struct_stmt = staticmethod(_lead("struct_stmt"))
    inline_struct = staticmethod(_lead("inline_struct"))
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
                                transformer=_Build(), cache=True,
                                _plugins={"ContextualLexer": FastContextualLexer})
        return _PARSER


class Origin:
    """Maps (line, column) in a captured text to the .fx file."""

    def __init__(self, base: Location, text: str, source_lines: dict[str, list[str]] | None = None,
                 row_major: bool = False, expanded: tuple = ()) -> None:
        self.base = base
        self.lines = text.split("\n")
        self.row_major = row_major     # the text stands under `#pragma pack_matrix(row_major)`
        # the lines macro expansion made (`Function.expanded`): their columns lead to the
        # macro call or argument in the file, and an error shows the line as written there
        self.expanded = {k: pieces for k, pieces, _ in expanded}
        self.written = {n: text for _, _, lines in expanded for n, text in lines}
        self._places: dict[int, tuple[Any, Location]] = {}

    def loc(self, line: int, column: int) -> Location:
        col = column + (self.base.column - 1 if line == 1 else 0)
        if self.expanded:
            pieces = self.expanded.get(line)
            if pieces:
                return Location(self.base.path, *through_expansion(pieces, col))
        return Location(self.base.path, self.base.line + line - 1, col)

    def source_line(self, loc: Location) -> str | None:
        """The text of the file line `loc` is on, as written (before macro expansion)."""
        written = self.written.get(loc.line) if self.written else None
        return written if written is not None else self.line_text(loc.line - self.base.line + 1)

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

    def error(self, message: str, item: Any, language: bool | None = None) -> HlslError:
        """A located error; `language` as HlslError's (None: from the message's code)."""
        loc = item if isinstance(item, Location) else self.at(item)
        return HlslError(message, loc, source_line=self.source_line(loc), language=language)

    def warning(self, message: str, loc: Location) -> EffectWarning:
        return EffectWarning(message, loc, self.source_line(loc))


# (tree, its size): a tree holds ~4 KB plus ~80 bytes per character of its text (tracemalloc,
# wood.fx's functions); 512 trees before, 16 MiB holds ~550 of its 300-character functions
_TREES = caches.declare("shaders.hlsl.trees", keys="text, grammar rule, the user type names",
                        max_bytes=16 << 20, size_of=lambda held: held[1])


def parse(text: str, start: str, origin: Origin, type_names: frozenset[str] = frozenset()) -> lark.Tree:
    """The tree of `text`, where `type_names` are the user types declared before it (kept by
    text and names: validation compiles one function for many cards and targets; the
    evaluator never changes a tree)."""
    key = (text, start, type_names)
    hit = _TREES.get(key)
    if hit is not None:
        return hit[0]
    try:
        _LOCAL.names = type_names
        tree = parser().parse(text, start=start)
        _TREES.put(key, (tree, 4096 + 80 * len(text)))
        return tree
    except lark.exceptions.UnexpectedInput as exc:
        line, col = getattr(exc, "line", 1) or 1, getattr(exc, "column", 1) or 1
        token = getattr(exc, "token", None)
        what = f"'{token}'" if token else "end of input" if token is not None else "this"
        if isinstance(exc, lark.exceptions.UnexpectedCharacters):
            what = f"'{text[exc.pos_in_stream]}'" if exc.pos_in_stream < len(text) else "end"
        raise origin.error(f"X3000: syntax error: unexpected {what}", origin.loc(line, col)) from None
