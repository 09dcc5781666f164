"""What a compile sees: the target, the effect's globals, structs and functions, the graph.

Globals are the effect's parameters: `static` ones are compile-time values (their
initialisers), the others are uniforms read from constant registers laid out as fxc packs
them (each array element, struct member and matrix column — row, for row_major — takes a
register), samplers bind sampler registers.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import lark
import numpy as np

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
    # bool parameters' i# and b#, `defi` values by i#, the globals read and those being
    # initialised, by name, and the real flow control's nesting
    int_registers: dict[str, int] = field(default_factory=dict, init=False, repr=False)
    int_defs: dict[int, tuple] = field(default_factory=dict, init=False, repr=False)
    bool_registers: dict[str, int] = field(default_factory=dict, init=False, repr=False)
    global_values: dict[str, Any] = field(default_factory=dict, init=False, repr=False)
    initializing: set[str] = field(default_factory=set, init=False, repr=False)
    flow_depth: dict[str, int] = field(init=False, repr=False, default_factory=lambda: {
        "static": 0, "dynamic": 0, "loop": 0})


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
            _, mods, spec, name, dims = tree.children
            ctx.typedefs[s.name] = array_of(resolve_type(ctx, spec, origin, mods),
                                            literal_sizes(dims, origin))
            continue
        tree = parse(s.source, "struct_def", origin, names)
        ctx.structs[s.name] = struct_type(ctx, tree, origin)
        ctx.struct_origins[s.name] = origin
    for f in effect.functions:
        origin = Origin(f.location, f.source, row_major=f.row_major, expanded=f.expanded)
        tree = parse(f.source, "function_def", origin, names)
        ctx.functions.setdefault(f.name, []).append(FunctionDef(f.name, tree, origin, f))
    return ctx


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
            fields.append((str(fname), array_of(t, literal_sizes(dims, origin)), semantic_text(sem)))
            i += 3
    return HType("struct", name=name, fields=tuple(fields))


def semantic_text(tree: Any) -> str | None:
    if tree is None:
        return None
    if tree.data == "register":
        return None
    return str(tree.children[0])


def register_binding(tree: Any) -> str | None:
    if tree is not None and tree.data == "register":
        return str(tree.children[1]).lower()
    return None


def array_of(t: HType, sizes: list[int]) -> HType:
    for n in reversed(sizes):
        t = HType("array", element=t, length=n)
    return t


def literal_sizes(dims: lark.Tree, origin: Origin) -> list[int]:
    """Array sizes in a struct member: integer literals (fxc also folds expressions there)."""
    out = []
    for d in dims.children:
        if not (isinstance(d, lark.Tree) and d.data == "int_lit"):
            raise origin.error("X3058: array dimensions of struct members must be literal",
                               d if d is not None else dims)
        out.append(int(str(d.children[0]).rstrip("uUlL"), 0))
    return out


def resolve_type(ctx: Context, tree: lark.Tree, origin: Origin, mods: Any = None) -> HType:
    said = {str(m) for m in mods.children} if mods is not None else set()
    # an explicit qualifier, else the `#pragma pack_matrix` the text was declared under
    row_major = "row_major" in said or (origin.row_major and "column_major" not in said)
    kind = tree.data
    if kind == "builtin_type":
        t = builtin(str(tree.children[0]))
        assert t is not None
    elif kind == "matrix_type":
        base = builtin(str(tree.children[1]))
        t = matrix(base.base if base else "float", int(tree.children[2]), int(tree.children[3]))
    elif kind == "vector_type":
        base = builtin(str(tree.children[1]))
        t = vector(base.base if base else "float", int(tree.children[2]))
    else:
        name = str(tree.children[0])
        t = ctx.structs.get(name) or ctx.typedefs.get(name)
        if t is None:
            raise origin.error(f"X3000: unrecognized identifier '{name}' (not a type)", tree)
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
        t = HType("texture")
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
    for n in reversed(p.array):
        t = HType("array", element=t, length=n)
    return t


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


def explicit_register(ctx: Context, name: str, kind: str) -> str | None:
    """A parameter's `: register(c4)` binding of that kind for the target ('c4'), else None."""
    p = ctx.effect.parameter(name)
    return None if p is None else p.register_for(ctx.target.name, kind)
