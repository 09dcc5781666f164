"""What a compile sees: the target, the effect's globals, structs and functions, the graph.

Globals are the effect's parameters: `static` ones are compile-time values (their
initialisers), the others are uniforms read from constant registers laid out as fxc packs
them (each array element, struct member and matrix column — row, for row_major — takes a
register), samplers bind sampler registers.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

import lark
import numpy as np

from effects.base import limits
from effects.base.errors import EffectWarning, Location
from effects.model import Effect, Function, Parameter
from effects.shaders.asm import lookup
from effects.shaders.asm.versions import VERSIONS, VersionRules
from effects.shaders.hlsl.dag import Graph, Operand
from effects.shaders.hlsl.parse import HlslError, Origin, parse
from effects.shaders.hlsl.types import HType, builtin, matrix, register_count, vector


@dataclass(frozen=True)
class Target:
    name: str                       # 'ps_2_0'
    rules: VersionRules

    @property
    def kind(self) -> str:
        return self.rules.kind

    def has(self, opcode: str) -> bool:
        return lookup(opcode, self.name) is not None


@dataclass
class FunctionDef:
    name: str
    tree: lark.Tree
    origin: Origin
    source: Function


@dataclass
class Context:
    effect: Effect
    target: Target
    graph: Graph = field(default_factory=Graph)
    structs: dict[str, HType] = field(default_factory=dict)
    functions: dict[str, list[FunctionDef]] = field(default_factory=dict)
    warnings: list[EffectWarning] = field(default_factory=list)
    uniforms_used: dict[str, HType] = field(default_factory=dict)   # in order of first use
    samplers_used: dict[str, str] = field(default_factory=dict)     # name -> kind
    kills: list[Operand] = field(default_factory=list)
    struct_origins: dict[str, Origin] = field(default_factory=dict)
    typedefs: dict[str, HType] = field(default_factory=dict)
    type_names: frozenset[str] = frozenset()     # what the HLSL lexer reads as TYPENAME
    # A preshader (an effect-level expression run on the host): uniform globals read as
    # constants, their current values, instead of constant registers
    host_values: bool = False
    # What the evaluator gives out and works out as it goes (none is an argument): int and
    # bool parameters' i# and b#, `defi` values by i#, the globals read by name, and the real
    # flow control's nesting
    int_registers: dict[str, int] = field(default_factory=dict, init=False, repr=False)
    int_defs: dict[int, tuple] = field(default_factory=dict, init=False, repr=False)
    bool_registers: dict[str, int] = field(default_factory=dict, init=False, repr=False)
    # the registers each of those takes: one per component (components.py)
    component_counts: dict[str, int] = field(default_factory=dict, init=False, repr=False)
    # the c# a register(c#) binding holds, read or not, which no literal takes (constant_layout.py)
    reserved_constants: set[int] = field(default_factory=set, init=False, repr=False)
    global_values: dict[str, Any] = field(default_factory=dict, init=False, repr=False)
    # the globals whose initialisers are evaluated, and the chain being evaluated now
    # (expressions._initialized): None outside one
    initialized: dict[str, Any] = field(default_factory=dict, init=False, repr=False)
    initializing: list[str] | None = field(default=None, init=False, repr=False)
    # the functions being inlined (calls.inline_call: one again is recursion, X3500), and what
    # unroll.never_ends learnt of each loop (by the tree's id) and of each start it was asked
    calling: list[Any] = field(default_factory=list, init=False, repr=False)
    # fxc's rule for a `for` over literal bounds with no attribute: unrolled, unless the
    # unrolled code does not fit the target; then a real loop (compiler.compile_shader
    # compiles again with `loops_for_size`). `literal_loops` counts the loops that could be
    # real ones, so a compile without any is not repeated
    loops_for_size: bool = field(default=False, init=False, repr=False)
    literal_loops: int = field(default=0, init=False, repr=False)
    loop_facts: dict[int, tuple] = field(default_factory=dict, init=False, repr=False)
    loop_verdicts: dict[tuple, Any] = field(default_factory=dict, init=False, repr=False)
    flow_depth: dict[str, int] = field(init=False, repr=False, default_factory=lambda: {
        "static": 0, "dynamic": 0, "loop": 0})
    # what the evaluation may spend (budget.py): levels of nesting now, and the limits, read
    # once per compile
    nesting: int = 0
    nesting_cap: int = field(default_factory=lambda: limits.get("hlsl_nesting"))
    work_cap: int = field(default_factory=lambda: limits.get("hlsl_work"))
    digits_cap: int = field(default_factory=lambda: limits.get("literal_digits"))


def type_names(effect: Effect) -> frozenset[str]:
    """The effect's user type names: its structs and global typedefs (both kept, in order, in
    `effect.structs`)."""
    return frozenset(s.name for s in effect.structs)


def load_context(effect: Effect, target_name: str) -> Context:
    rules = VERSIONS.get(target_name)
    if rules is None:
        raise HlslError(f"X3507: unknown compile target '{target_name}'", Location(effect.path, 1, 1))
    ctx = Context(effect, Target(target_name, rules))
    names = ctx.type_names = type_names(effect)
    for s in effect.structs:
        origin = Origin(s.location, s.source, row_major=s.row_major)
        if s.source.lstrip().startswith("typedef"):      # a global `typedef float4 COLOR;`
            tree = parse(s.source, "typedef_decl", origin, names)
            _, mods, spec, *declared = tree.children
            # `typedef float4 C4, Colour;`: each name is an entry with the whole statement
            name, dims = next((n, d) for n, d in zip(declared[::2], declared[1::2])
                              if str(n) == s.name)
            ctx.typedefs[s.name] = array_of(resolve_type(ctx, spec, origin, mods),
                                            literal_sizes(dims, origin),
                                            lambda m: origin.error(m, tree), f"'{name}'")
            continue
        tree = parse(s.source, "struct_def", origin, names)
        if s.name in ctx.structs:                  # d3dx's "redefinition of '%s'"
            raise origin.error(f"X3003: redefinition of '{s.name}'", tree.children[0])
        ctx.structs[s.name] = struct_type(ctx, tree, origin)
        ctx.struct_origins[s.name] = origin
    for f in effect.functions:
        origin = Origin(f.location, f.source, row_major=f.row_major, expanded=f.expanded)
        tree = parse(f.source, "function_def", origin, names)
        if isinstance(tree.children[3], lark.Tree) and tree.children[3].data == "no_params":
            tree.children[3] = None              # `f(void)` is `f()`
        fdef = FunctionDef(f.name, tree, origin, f)
        _check_declaration(ctx, fdef, ctx.functions.get(f.name, ()))
        ctx.functions.setdefault(f.name, []).append(fdef)
    return ctx


def _check_declaration(ctx: Context, fdef: FunctionDef, earlier: Any) -> None:
    """What fxc refuses in a function's declaration whether or not it is called (it compiles
    the whole file): a void function with a semantic (X3076); a parameter that is void (X3038,
    ReShade's text), named twice (X3003), const and out (X3046), out with a default (X3045),
    or without a default after one with one (X3044); a body with no return (X3080) or one that
    falls off its end (X3507); and a second body of the same name and parameter types (X3003).
    d3dx's message table holds the texts of X3003, X3044, X3046, X3076 and X3080."""
    tree, origin = fdef.tree, fdef.origin
    name_tok, semantic = tree.children[2], tree.children[4]
    if semantic is not None and _spells_void(tree.children[1]):
        raise origin.error(f"X3076: '{fdef.name}': void function cannot have a semantic",
                           semantic)
    ret = tree.children[1].children[0]
    if isinstance(ret, lark.Tree) and resolve_type(ctx, ret, origin).kind in _OBJECTS:
        # fxc's text, as DXC's tests record it (tools/clang/test/HLSL/string.hlsl)
        raise origin.error(f"X3038: '{fdef.name}': function return value cannot contain "
                           "Effects objects", name_tok)
    params = tree.children[3]
    seen: set[str] = set()
    defaulted = None
    for p in (params.children if params is not None else []):
        mods, spec, name = p.children[:3]
        default = p.children[5]
        words = {str(m) for m in mods.children} if mods is not None else set()
        if default is not None and words & {"out", "inout"}:     # fxc's error list: X3045
            raise origin.error(f"X3045: '{name}': output parameters cannot have a default "
                               "value", name)
        if default is not None:
            defaulted = name
        elif defaulted is not None:                  # d3dx's message table: X3044
            raise origin.error(f"X3044: '{fdef.name}': missing default value for parameter "
                               f"'{name}'", name)
        if resolve_type(ctx, spec, origin, mods).kind == "void":
            raise origin.error(f"X3038: '{name}': function parameters cannot be void", name)
        if "const" in words and words & {"out", "inout"}:
            raise origin.error(f"X3046: '{name}': output paramaters cannot be declared 'const'",
                               name)
        if str(name) in seen:
            raise origin.error(f"X3003: redefinition of '{name}'", name)
        seen.add(str(name))
    if _has_body(tree) and not _spells_void(tree.children[1]):
        body = tree.children[-1]
        if not _contains(body, "return_stmt"):
            raise origin.error(f"X3080: '{fdef.name}': function must return a value", tree)
        if not _always_returns(body):
            # from memory (fxc's code and text not found in a stored source); a language
            # error, though the code is not in LANGUAGE_CODES (X3507 is a target's there too)
            raise origin.error(f"X3507: '{fdef.name}': Not all control paths return a value",
                               name_tok, language=True)
    if not earlier or not _has_body(tree):
        return
    mine = _signature(ctx, fdef)
    for other in earlier:
        if _has_body(other.tree) and _signature(ctx, other) == mine:
            raise origin.error(f"X3003: redefinition of '{fdef.name}'", name_tok)


# the types a function may not return: "Effects objects" (fxc's X3038 names them so; DXC's
# tests record it for a string, and a texture is one as much)
_OBJECTS = frozenset(("string", "texture"))


# statement -> its parts that must all return for it to (fxc: "not all control paths return
# a value"); a loop, a switch or a discard counts as returning when its body may: the check
# refuses only a function that plainly falls off its end
_PATHS = {"if_else": (3, 5), "for_stmt": (5,), "while_stmt": (3,), "do_stmt": (2,)}


def _always_returns(root: Any) -> bool:
    """Whether every path through statement `root` ends in a return (walked with an explicit
    stack: a 5,000-deep nesting of blocks takes no Python stack)."""
    done: dict[int, bool] = {}
    stack: list[tuple[Any, bool]] = [(root, False)]
    while stack:
        node, ready = stack.pop()
        if not isinstance(node, lark.Tree):
            done[id(node)] = False
            continue
        kind = node.data
        parts = node.children if kind == "block" else \
            [node.children[k] for k in _PATHS.get(kind, ())]
        if not ready:
            stack.append((node, True))
            stack.extend((p, False) for p in parts)
            continue
        if kind in ("return_stmt", "switch_stmt", "discard_stmt"):
            done[id(node)] = True
        elif kind == "block":
            done[id(node)] = any(done[id(p)] for p in parts)
        elif kind == "if_else":
            done[id(node)] = all(done[id(p)] for p in parts)
        elif parts:      # a loop: its body returns, or may
            done[id(node)] = done[id(parts[0])] or _returns_in(parts[0])
        else:
            done[id(node)] = False
    return done[id(root)]


def _returns_in(stmt: Any) -> bool:
    return isinstance(stmt, lark.Tree) and _contains(stmt, "return_stmt")


def _contains(tree: lark.Tree, data: str) -> bool:
    """Whether a node below `tree` (or it) is a `data` node. Last statements first, where a
    body's return usually is: lark's find_data lists every node of the tree before the first."""
    stack = [tree]
    while stack:
        node = stack.pop()
        if node.data == data:
            return True
        stack.extend(c for c in node.children if isinstance(c, lark.Tree))
    return False


def _spells_void(ret: lark.Tree) -> bool:
    spec = ret.children[0]
    return isinstance(spec, lark.Tree) and spec.data == "builtin_type" and \
        str(spec.children[0]) == "void"


def _has_body(tree: lark.Tree) -> bool:
    last = tree.children[-1]
    return isinstance(last, lark.Tree) and last.data == "block"


def _signature(ctx: Context, fdef: FunctionDef) -> tuple:
    """A function's parameter types as overloads tell them apart (array sizes by their text:
    they need the evaluator)."""
    params = fdef.tree.children[3]
    out = []
    for p in (params.children if params is not None else []):
        mods, spec, _name, dims = p.children[:4]
        t = resolve_type(ctx, spec, fdef.origin, mods)
        out.append((t, _text(dims)))
    return tuple(out)


def _text(tree: lark.Tree) -> str:
    return " ".join(str(t) for t in tree.scan_values(lambda v: isinstance(v, lark.Token)))


def struct_type(ctx: Context, tree: lark.Tree, origin: Origin) -> HType:
    name = str(tree.children[0])
    fields: list[tuple[str, HType, str | None]] = []
    for member in tree.children[1:]:
        mods = member.children[0]
        t = resolve_type(ctx, member.children[1], origin, mods)
        rest = member.children[2:]
        # member: NAME dims [semantic] (, NAME dims [semantic])*
        i = 0
        while i < len(rest):
            fname, dims, sem = rest[i], rest[i + 1], rest[i + 2]
            if t.kind == "void":                # ReShade's text for fxc's X3038
                raise origin.error(f"X3038: '{fname}': struct members cannot be void", fname)
            if any(f[0] == str(fname) for f in fields):   # d3dx's "redefinition of '%s'"
                raise origin.error(f"X3003: redefinition of '{fname}'", fname)
            fields.append((str(fname), array_of(t, literal_sizes(dims, origin),
                                                lambda m: origin.error(m, fname),
                                                f"member '{fname}'"),
                           semantic_text(centroid_semantic(mods, sem))))
            i += 3
    return checked(HType("struct", name=name, fields=tuple(fields)),
                   lambda m: origin.error(m, tree), f"struct '{name}'")


def semantic_text(tree: Any) -> str | None:
    if tree is None:
        return None
    if tree.data == "register":
        return None
    return str(tree.children[0])


def centroid_semantic(mods: Any, tree: Any) -> Any:
    """The semantic tree of a member or parameter declared `centroid`: its `_centroid` form,
    which a ps_2_0+ input declares `dcl_texcoord_centroid` (Effekseer's model_unlit_ps.h:
    fxc 9.29 wrote `dcl_texcoord_centroid v0` for `centroid float4 ... : TEXCOORD0`)."""
    words = {str(m) for m in mods.children} if mods is not None else set()
    if "centroid" not in words or tree is None or tree.data == "register":
        return tree
    token = tree.children[0]
    if str(token).lower().endswith("_centroid"):
        return tree
    return lark.Tree(tree.data, [token.update(value=f"{token}_centroid"), *tree.children[1:]],
                     tree.meta if not tree.meta.empty else None)


def register_binding(tree: Any) -> str | None:
    if tree is not None and tree.data == "register":
        return str(tree.children[1]).lower()
    return None


MAX_ARRAY = 65536     # fxc: X3059, array dimension must be between 1 and 65536


def array_of(t: HType, sizes: list[float], fail: Callable[[str], Exception],
             subject: str = "this variable") -> HType:
    """`t[sizes[0]][sizes[1]]...`, each size checked (fxc's X3059) and the whole against
    hlsl_components and hlsl_nesting as it is built, before anything is allocated for it.
    `fail(message)` makes the located error."""
    for n in reversed(sizes):
        if not (n == n and 1 <= n < MAX_ARRAY + 1):     # NaN and inf too (a folded size)
            shown = f"{n:g}" if isinstance(n, float) else str(n)
            raise fail(f"X3059: array dimension must be between 1 and {MAX_ARRAY} "
                       f"({subject}: {shown})")
        t = checked(HType("array", element=t, length=int(n)), fail, subject)
    return t


def checked(t: HType, fail: Callable[[str], Exception], subject: str) -> HType:
    """`t`, or the located error when it holds more numbers than hlsl_components or nests
    deeper than hlsl_nesting (a struct of structs doubling per level, `float a[65536][65536]`):
    each is known from the type alone (HType.components, .depth)."""
    if t.components > limits.get("hlsl_components"):
        raise fail(limits.message("hlsl_components", t.components, f"the type of {subject}"))
    if t.depth > limits.get("hlsl_nesting"):
        raise fail(limits.message("hlsl_nesting", t.depth, f"the type of {subject}"))
    return t


def int_literal(text: str, fail: Callable[[str], Exception], cap: int | None = None) -> int:
    """An HLSL integer literal (`42`, `0x2A`, `7u`, `010` octal: the reference's Grammar
    page), its digits under literal_digits (Python itself refuses more than 4,300; `cap`:
    that limit as a compile read it)."""
    digits = text.rstrip("uUlL")
    if len(digits) > (cap if cap is not None else limits.get("literal_digits")):
        raise fail(limits.message("literal_digits", len(digits), "an integer literal"))
    if digits.lower().startswith("0x"):
        return int(digits, 16)
    if len(digits) > 1 and digits[0] == "0":
        if set(digits) & set("89"):
            raise fail(f"X3000: syntax error: '{text}' is not an octal number (a leading 0 "
                       "makes one)")
        return int(digits, 8)
    return int(digits)


def literal_sizes(dims: lark.Tree, origin: Origin) -> list[int]:
    """Array sizes in a struct member: integer literals (fxc also folds expressions there)."""
    out = []
    for d in dims.children:
        if not (isinstance(d, lark.Tree) and d.data == "int_lit"):
            raise origin.error("X3058: array dimensions of struct members must be literal",
                               d if d is not None else dims)
        out.append(int_literal(str(d.children[0]), lambda m: origin.error(m, d)))
    return out


def sized_type(tree: lark.Tree, origin: Origin) -> HType:
    """`vector<T, n>` / `matrix<T, r, c>` (a type or a constructor's): fxc takes 1 to 4 for
    each size (X3052 for a vector's, X3053 for a matrix's: fxc's codes as recalled, their
    texts not found in a source stored here)."""
    kids = [c for c in tree.children if isinstance(c, lark.Token)]
    base_tok = next(c for c in kids if c.type == "TYPE")
    base = builtin(str(base_tok))
    if base is None or base.kind != "scalar":
        # fxc's texts, as DXC's tests record them (tools/clang/test/HLSL/string.hlsl)
        code, what = ("X3123", "matrix") if "matrix" in tree.data else ("X3122", "vector")
        raise origin.error(f"{code}: {what} element type must be a scalar type", base_tok)
    sizes = [c for c in kids if c.type == "INT"]
    values = [int_literal(str(c), lambda m, c=c: origin.error(m, c)) for c in sizes]
    numeric = base.base if base is not None and base.numeric else "float"
    if len(values) == 1:
        if not 1 <= values[0] <= 4:
            raise origin.error(f"X3052: vector dimension must be between 1 and 4, not "
                               f"{values[0]}", sizes[0])
        return vector(numeric, values[0])
    for tok, n in zip(sizes, values):
        if not 1 <= n <= 4:
            raise origin.error(f"X3053: matrix dimensions must be between 1 and 4, not {n}",
                               tok)
    return matrix(numeric, values[0], values[1])


def resolve_type(ctx: Context, tree: lark.Tree, origin: Origin, mods: Any = None) -> HType:
    said = {str(m) for m in mods.children} if mods is not None else set()
    if {"row_major", "column_major"} <= said:      # fxc's text, as DXC's tests record it
        raise origin.error("X3048: matrix types cannot be both column_major and row_major",
                           mods)
    # an explicit qualifier, else the `#pragma pack_matrix` the text was declared under
    row_major = "row_major" in said or (origin.row_major and "column_major" not in said)
    kind = tree.data
    if kind == "builtin_type":
        t = builtin(str(tree.children[0]))
        assert t is not None
    elif kind in ("matrix_type", "vector_type"):
        t = sized_type(tree, origin)
    elif kind == "inline_struct":             # a member `struct [S] { ... } m;`
        name_tok, *members = tree.children
        if name_tok is None:
            name_tok = lark.Token("NAME", "(anonymous struct)")
        t = struct_type(ctx, lark.Tree("struct_def", [name_tok, *members]), origin)
    else:
        name = str(tree.children[0])
        t = ctx.structs.get(name) or ctx.typedefs.get(name)
        if t is None:
            raise origin.error(f"X3000: unrecognized identifier '{name}' (not a type)", tree)
    if said & {"row_major", "column_major"} and t.numeric and t.kind != "matrix":
        # fxc's text, as DXC's tests record it (a struct or an array of matrices is let be)
        raise origin.error("X3077: non-matrix types cannot be declared 'row_major' or "
                           "'column_major'", mods)
    if row_major and t.kind == "matrix":
        t = HType("matrix", t.base, t.rows, t.cols, row_major=True)
    return t


def parameter_type(ctx: Context, p: Parameter) -> HType:
    spec = p.type
    if spec.struct:
        t = ctx.structs.get(spec.base)
        if t is None:
            raise HlslError(f"X3000: unknown struct '{spec.base}'", p.location)
    elif spec.base in ("sampler",):
        t = HType("sampler", {"1D": "1d", "2D": "2d", "3D": "3d", "CUBE": "cube"}.get(spec.dim, "2d"))
    elif spec.base == "texture":
        t = HType("texture", {"1D": "1d", "2D": "2d", "3D": "3d", "CUBE": "cube"}.get(spec.dim, ""))
    elif spec.base == "string":
        t = HType("string")
    elif spec.is_numeric:
        base = {"dword": "uint"}.get(spec.base, spec.base)
        if spec.rows > 1:
            t = HType("matrix", base, spec.rows, spec.cols, row_major="row_major" in p.storage)
        else:
            t = vector(base, spec.cols)
    else:
        t = HType(spec.base)
    return array_of(t, list(p.array), lambda m: HlslError(m, p.location), f"'{p.name}'")


def static_value(p: Parameter) -> np.ndarray | None:
    """A static/const global's initialiser as numbers (None when it has none)."""
    if isinstance(p.value, (np.ndarray, np.generic, int, float, list, tuple)):
        try:   # an array as loaded; a number or a list as an application set it
            return np.asarray(p.value, dtype=np.float64).reshape(-1)
        except (TypeError, ValueError):
            return None
    return None


def uniform_count(ctx: Context, t: HType) -> int:
    return register_count(t)


def sampler_element(name: str) -> tuple[str, int | None]:
    """`S[k]`, an element of a sampler array as the intrinsics name it, as ('S', k); any other
    name as (name, None)."""
    if name.endswith("]") and "[" in name:
        base, index = name[:-1].split("[", 1)
        return base, int(index)
    return name, None


def explicit_register(ctx: Context, name: str, kind: str) -> int | None:
    """The number of a parameter's `: register(c4)` binding of that kind for the target (4),
    else None; `S[k]`, an element of a sampler array, is the array's register + k. The number's
    digits are under literal_digits."""
    name = name.split("+", 1)[0]      # `S+Tex`, a sampler paired with a texture: S's binding
    base, index = sampler_element(name)
    k = index or 0
    p = ctx.effect.parameter(base)
    register = None if p is None else p.register_for(ctx.target.name, kind)
    if register is None:
        return None
    digits = register[1:]
    if len(digits) > limits.get("literal_digits"):
        raise HlslError(limits.message("literal_digits", len(digits),
                                       f"the register number of '{base}'"), p.location)
    return int(digits) + k
