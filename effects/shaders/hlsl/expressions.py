"""Expressions: literals, names (locals, then the effect's globals), operators, swizzles,
indexing, constructors, casts, assignment (read-modify-write of the named variable, merged
under the current predicate) and calls (user functions first, then intrinsics)."""
from __future__ import annotations

from typing import Any, Generator

import lark
import numpy as np

from effects.model import Expression, ParamRef
from effects.shaders.hlsl.budget import enter_level, leave_level, over_budget
from effects.shaders.hlsl.context import (int_literal, parameter_type, resolve_type, sized_type,
                                          static_value)
from effects.shaders.hlsl.folding import bitwise_not
from effects.shaders.hlsl.parse import Origin, parse
from effects.shaders.hlsl.dag import Operand
from effects.shaders.hlsl.types import BOOL, INT, HType, builtin, scalar
from effects.shaders.hlsl.arith import INTEGRAL
from effects.shaders.hlsl.calls import resolve_overload
from effects.shaders.hlsl.intrinsics import INTRINSICS, call_intrinsic, texture_method
from effects.shaders.hlsl.loops import al_element
from effects.shaders.hlsl.lvalues import const_index, element_of, member_of, pick_element, store
from effects.shaders.hlsl.values import Value, build_value



def evaluate_expr(ev: Any, tree: Any) -> Value:
    """The value of expression `tree`, evaluated without recursion: a handler that needs a
    subexpression's value yields its tree and is sent the value back, so a 5,000-term sum or a
    1,000-deep nesting takes no Python stack (an explicit stack of the handlers waiting).
    Re-entering (an l-value's index, an `out` argument written back) counts one level of
    hlsl_nesting; each node evaluated is checked against the work budget."""
    ctx = ev.ctx
    # a statement's own expression takes no level; one re-entered from inside another does
    levels = 1 if ev.in_expression else 0
    enter_level(ev, tree, levels)
    ev.in_expression += 1
    try:
        waiting: list[Generator[Any, Value, Value]] = []
        value: Value | None = None
        pending: Any = tree
        while True:
            if pending is not None:
                item = _start(ev, pending)
                if isinstance(item, Value):
                    value, pending = item, None
                else:
                    waiting.append(item)
                    value = None
            if pending is None and not waiting:
                return value  # type: ignore[return-value]
            try:
                pending = waiting[-1].send(value)   # the next subexpression it needs
                continue
            except StopIteration as done:
                waiting.pop()
                value, pending = done.value, None
            if ctx.graph.work > ctx.work_cap:
                raise over_budget(ev, tree)
    finally:
        ev.in_expression -= 1
        leave_level(ev, levels)


def _start(ev: Any, tree: Any) -> Value | Generator[Any, Value, Value]:
    """A leaf's value, or the handler (a generator) of a node with subexpressions."""
    if isinstance(tree, lark.Token):
        raise ev.error(f"X3000: unexpected '{tree}'", tree)
    handler = _HANDLERS.get(tree.data)
    if handler is None:
        raise ev.error(f"X3000: unsupported expression '{tree.data}'", tree)
    return handler(ev, tree)


def _comma(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    """`(a, b)`: C's comma operator, each evaluated in order, the value the last one's."""
    value = None
    for item in tree.children:
        if isinstance(item, lark.Token):      # its opening parenthesis
            continue
        value = yield item
    return value  # type: ignore[return-value]


def _float(ev: Any, tree: lark.Tree) -> Value:
    # `L` is the reference's suffix for a 64-bit literal (its Grammar page): a double, which
    # shader models 1 to 3 hold as float
    text = str(tree.children[0]).rstrip("fFhHlL")
    base = "half" if str(tree.children[0])[-1:] in "hH" else "float"
    # located: a literal that cannot be a constant register (1e39) is refused where it is
    return Value(scalar("float" if base == "float" else "half"),
                 [ev.g.const((float(text),), ev.at(tree))])


def _int(ev: Any, tree: lark.Tree) -> Value:
    text = str(tree.children[0])
    n = int_literal(text, lambda m: ev.error(m, tree), ev.ctx.digits_cap)
    # a `u` suffix makes the literal unsigned, so integer folding treats it as uint: fxc folds
    # `1U << 31` to 2147483648 (dxwrapper's FixUpVertexShader, whose vs_2_0 bytecode holds
    # +2.1474836e+09), where an int shift would wrap to -2147483648
    return Value(scalar("uint") if text[-1:] in "uU" else INT, [ev.g.const((float(n),))])


def _bool(ev: Any, tree: lark.Tree) -> Value:
    return Value(BOOL, [ev.g.const((1.0 if str(tree.children[0]) == "true" else 0.0,))])


def _var(ev: Any, tree: lark.Tree) -> Value:
    name = str(tree.children[0])
    var = ev.lookup(name)
    if var is not None:
        return var.value
    return global_value(ev, name, tree)


def global_value(ev: Any, name: str, where: Any) -> Value:
    ctx = ev.ctx
    cache = ctx.global_values
    if name in cache:
        return cache[name]
    param = ctx.effect.parameter(name)
    if param is None:
        raise ev.error(f"X3004: undeclared identifier '{name}'", where)
    t = parameter_type(ctx, param)
    if t.kind == "sampler":
        value = Value(t, sampler=name)
        ctx.samplers_used.setdefault(name, t.base)
    elif t.kind == "array" and t.element is not None and t.element.kind == "sampler":
        # `sampler S[2]`: an element read by a constant index is a sampler of its own,
        # "S[k]" (its register follows the array's: compiler.sampler_registers)
        value = Value(t, elements=[Value(t.element, sampler=f"{name}[{k}]")
                                   for k in range(t.length)])
    elif t.kind in ("texture", "string"):
        # a value no operator or conversion takes: `return Tex;` is fxc's X3017 "cannot
        # implicitly convert from 'string' to 'float4'" (DXC's tests record the text), an
        # operator on it X3022, tex2D(Tex, uv) X3013 (the first argument must be a sampler);
        # a texture keeps its name for `Tex.Sample(S, uv)` (intrinsics.texture_method)
        value = Value(t, sampler=name if t.kind == "texture" else None)
    elif "static" in param.storage or ctx.host_values:
        # A static's initialiser; in a preshader (host_values) any global's current value
        numbers = static_value(param)
        if numbers is None and initializer_text(param) is not None:
            numbers = _initialized(ev, name, where)
        n = t.components
        flat = list(numbers) if numbers is not None else [0.0] * n
        flat = (flat + [0.0] * n)[:n]
        value = build_value(t, [ev.g.const((float(x),)) for x in flat])
    else:
        if param.tbuffer:
            # fxc's X3546, "reading from texture buffers is unsupported on the specified
            # target" (its error list): a texture buffer is shader model 4's
            raise ev.error(f"X3546: reading from texture buffers is unsupported on "
                           f"{ctx.target.name}: '{name}' is a member of tbuffer "
                           f"'{param.tbuffer}' (shader model 4 reads texture buffers; a "
                           f"cbuffer's members are uniforms on every target)", where)
        value = uniform_value(ev, name, t, 0)
        ctx.uniforms_used.setdefault(name, t)
    cache[name] = value
    return value


def initializer_text(param: Any) -> Expression | None:
    """A global's initialiser as text to evaluate: an expression the loader kept as text, or a
    bare reference to another parameter (`float C = A;`, `float D = G[1];`); None for none."""
    value = param.value
    if isinstance(value, Expression):
        return value
    if isinstance(value, ParamRef):
        text = value.name if value.index is None else f"{value.name}[{value.index}]"
        return Expression(text, value.location)
    return None


class _Needs(Exception):
    """Raised inside an initialiser's evaluation: it reads `name`, whose own initialiser has
    not been evaluated yet (_initialized evaluates that one first, then this one again)."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.name = name


def _initialized(ev: Any, name: str, where: Any) -> np.ndarray:
    """The numbers of global `name`'s initialiser (kept as text). Initialisers that read each
    other (`float P1 = P0 * 2; float P2 = P1 * 2; ...`) are evaluated from the one that
    depends on nothing up, with an explicit stack: a chain of any length takes no Python
    stack, and a cycle is a located error naming it."""
    ctx = ev.ctx
    done: dict[str, np.ndarray] = ctx.initialized
    if name in done:
        return done[name]
    if ctx.initializing is not None:          # inside an initialiser: that one waits for this one
        raise _Needs(name)
    stack = [name]
    ctx.initializing = stack
    try:
        while stack:
            top = stack[-1]
            try:
                done[top] = _initializer(ev, top)
                stack.pop()
            except _Needs as need:
                if need.name in stack:
                    cycle = " -> ".join(stack[stack.index(need.name):] + [need.name])
                    init = initializer_text(ctx.effect.parameter(top))
                    raise Origin(init.location, init.text).error(
                        f"X3013: the initializer of '{need.name}' refers to itself "
                        f"({cycle})" if need.name != top else
                        f"X3013: the initializer of '{top}' refers to '{top}' itself",
                        init.location) from None
                stack.append(need.name)
    finally:
        ctx.initializing = None
    return done[name]


def _initializer(ev: Any, name: str) -> np.ndarray:
    """A global's initialiser kept as text, evaluated (raises _Needs for a global whose own
    initialiser comes first). In a preshader every component must fold (X3013); a compile
    keeps the old reading of a non-constant component as 0."""
    ctx = ev.ctx
    init = initializer_text(ctx.effect.parameter(name))
    origin = Origin(init.location, init.text)
    tree = parse(init.text, "initializer", origin, ctx.type_names)
    comps = ev.spawn(origin).flatten_list(tree)
    values = [c.const_values() for c in comps]
    if ctx.host_values and any(v is None for v in values):
        raise origin.error(f"X3013: the initializer of '{name}' is not a constant", tree)
    return np.array([v[0] if v else 0.0 for v in values])


def uniform_value(ev: Any, name: str, t: HType, offset: int, address: Operand | None = None,
                  al: Operand | None = None) -> Value:
    """A uniform's value over its constant registers (offsets relative to its first); with
    `address`, read relatively: register offset + k is c[a0.x + first + offset + k] with
    a0.x = address (an array element chosen at run time, vertex shaders only); with `al` (a
    real loop's counter phi, loops.al_element), c[aL + first + offset + k]."""
    from effects.shaders.hlsl.types import register_count
    g = ev.g
    if al is not None:
        reg = lambda k: g.leaf("uniform_al", (name, offset + k), 4, args=(al,))
    elif address is None:
        reg = lambda k: g.leaf("uniform", (name, offset + k), 4)
    else:
        reg = lambda k: g.leaf("uniform_rel", (name, offset + k), 4, args=(address,))
    if t.kind in ("scalar", "vector"):
        r = reg(0)
        return Value(t, [Operand(r.node, (i,)) for i in range(t.size)])
    if t.kind == "matrix":
        if t.row_major:
            regs = [reg(i) for i in range(t.rows)]
            comps = [Operand(regs[i].node, (j,)) for i in range(t.rows) for j in range(t.cols)]
        else:
            regs = [reg(j) for j in range(t.cols)]
            comps = [Operand(regs[j].node, (i,)) for i in range(t.rows) for j in range(t.cols)]
        return Value(t, comps)
    if t.kind == "array":
        size = register_count(t.element)  # type: ignore[arg-type]
        return Value(t, elements=[uniform_value(ev, name, t.element, offset + k * size, address, al)  # type: ignore[arg-type]
                                  for k in range(t.length)])
    if t.kind == "struct":
        out = Value(t)
        k = offset
        for fname, ft, _ in t.fields:
            out.fields[fname] = uniform_value(ev, name, ft, k, address, al)
            k += register_count(ft)
        return out
    return Value(t)


def _binary(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    a, op, b = tree.children
    va = yield a
    vb = yield b
    return ev.a.binary(str(op), va, vb, ev.at(op))


def _prefix(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    op, x = tree.children
    v = yield x
    loc = ev.at(op)
    if not v.type.numeric:
        raise ev.error(f"X3022: operator '{op}' needs a numeric operand, not '{v.type}'", op)
    if str(op) == "-":
        t = v.type.with_base("int") if v.type.base == "bool" else v.type
        return Value(t, [c.neg() for c in v.comps])
    if str(op) == "+":
        return v
    if str(op) == "!":
        b = ev.a.to_bool(v, loc)
        return Value(b.type, ev.a.logical_not(b.comps, loc))
    if v.type.base not in INTEGRAL:
        raise ev.error(f"X3082: int or unsigned int type required ('~' on '{v.type}')", op)
    consts = v.const_values()
    if consts is None:
        raise ev.error(f"X3535: bitwise operation '~' needs integer hardware; "
                       f"{ev.ctx.target.name} has none", op)
    return Value(v.type, [ev.g.const((bitwise_not(c, v.type.base),)) for c in consts])


def _incdec(ev: Any, tree: lark.Tree, post: bool) -> Value:
    target, op = (tree.children[0], tree.children[1]) if post else (tree.children[1], tree.children[0])
    one = Value(INT, [ev.g.const((1.0,))])
    seen: list[Value] = []

    masks: list[Any] = []

    def step(old: Value) -> Value:
        if old.type.numeric and old.type.base == "bool":   # fxc's text (DXC's tests)
            raise ev.error("X3020: operator cannot be used with a bool lvalue", op)
        new = ev.a.binary("+" if str(op) == "++" else "-", old, one, ev.at(op))
        seen.append(old if post else new)
        masks.append(ev.mask)
        return ev.a.convert(new, old.type, ev.at(op))
    store(ev, target, step)         # the target (its indices) evaluated once
    return _written(ev, seen, masks, ev.at(op))


def _written(ev: Any, values: list[Value], masks: list[Any], loc: Any) -> Value:
    """The value of an assignment expression: the one written, or where a run-time index
    wrote each element under its own predicate (lvalues._store_each), the one the index
    chose (each under the predicate it was written with)."""
    out = values[0]
    for v, p in zip(values[1:], masks[1:]):
        out = ev.merge(out, v, p, loc)
    return out


def _assign(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    target, op, rhs = tree.children
    value = yield rhs
    written: list[Value] = []
    masks: list[Any] = []

    def assigned(current: Value) -> Value:
        v = value if str(op) == "=" else ev.a.binary(str(op)[:-1], current, value, ev.at(op))
        written.append(ev.a.convert(v, current.type, ev.at(rhs)))
        masks.append(ev.mask)
        return written[-1]
    store(ev, target, assigned)     # the target (its indices) evaluated once, after the value
    return _written(ev, written, masks, ev.at(op))


def _member(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    base_tree, name = tree.children
    base = yield base_tree
    return member_of(ev, base, name)


def _index(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    base_tree, index_tree = tree.children
    base = yield base_tree
    index = yield index_tree
    if base.type.kind in ("array", "matrix", "vector") and index.type.numeric and \
            index.const_values() is None:
        if base.type.kind == "array":
            got = _relative_element(ev, base_tree, base.type, index, index_tree)
            if got is not None:
                return got
            if not _numbers_only(base.type):      # fxc's wording for a sampler array
                raise ev.error(f"X3512: sampler array index must be a literal expression "
                               f"({ev.ctx.target.name} picks samplers by number only)", index_tree)
        return pick_element(ev, base, index, index_tree)
    if base.type.kind not in ("array", "matrix", "vector"):
        raise ev.error(f"X3121: array, matrix, vector, or indexable object type expected in "
                       f"index expression, not '{base.type}'", tree)
    return element_of(ev, base, const_index(ev, index, index_tree, base.type), tree)


def _numbers_only(t: HType) -> bool:
    """Whether every leaf of `t` is a number (a select chain can pick its elements)."""
    return bool(_leaf_bases(t)) and len(_leaf_bases(t)) == t.components


def _relative_element(ev: Any, base_tree: Any, t: HType, index: Value, where: Any) -> Value | None:
    """`Bones[i]` with i known only at run time: in a vertex shader, an element of a uniform
    array read through the address register (c[a0.x + n]; a0.x = i times the registers an
    element takes, i converted to int first as HLSL does). An address outside the constant
    file reads (0, 0, 0, 0) (the DirectX 9 docs' address-register page); inside it but past
    the array, the registers that follow, as on hardware (no bounds check)."""
    from effects.shaders.hlsl.types import register_count
    target = ev.ctx.target
    name = str(base_tree.children[0]) if isinstance(base_tree, lark.Tree) and base_tree.data == "var" else None
    param = ev.ctx.effect.parameter(name) if name is not None and ev.lookup(name) is None else None
    uniform = param is not None and "static" not in param.storage
    if uniform and index.type.numeric:
        # the innermost real loop's counter: c[aL + n] (loops.al_element), vs_2_0+ and ps_3_0
        i = ev.a.convert_base(index.comps[:1], index.type.base, "int", ev.at(where))[0]
        al = al_element(ev, t, i)
        if al is not None:
            if index.type.size > 1:
                ev.warn("X3206: implicit truncation of vector type", ev.at(where))
            global_value(ev, name, base_tree)            # registers the array as used
            return uniform_value(ev, name, t.element, al[0], al=al[1])  # type: ignore[arg-type]
    if target.kind != "vs" or not uniform:
        return None         # no register addressed by it: a select chain (pick_element)
    if not index.type.numeric:
        raise ev.error(f"X3120: invalid type for index - index must be a scalar, not '{index.type}'", where)
    if index.type.size > 1:
        ev.warn("X3206: implicit truncation of vector type", ev.at(where))
    loc = ev.at(where)
    i = ev.a.convert_base(index.comps[:1], index.type.base, "int", loc)[0]
    stride = register_count(t.element)  # type: ignore[arg-type]
    address = i if stride == 1 else ev.a.op("mul", [i, ev.a.const(float(stride))], loc, 1)
    global_value(ev, name, base_tree)            # registers the array as used
    return uniform_value(ev, name, t.element, 0, address)  # type: ignore[arg-type]


def _construct(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    t = builtin(str(tree.children[0]))
    return (yield from _construct_as(ev, t, tree.children[1], tree))


def _construct_user(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    """`vec4(uv, 0, 1)` with `typedef vector<half, 4> vec4;`: the constructor of the type the
    name stands for (a struct has none: X3037)."""
    t = resolve_type(ev.ctx, lark.Tree("user_type", [tree.children[0]]), ev.origin)
    return (yield from _construct_as(ev, t, tree.children[1], tree))


def _construct_matrix(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    t = sized_type(tree, ev.origin)
    return (yield from _construct_as(ev, t, tree.children[4], tree))


def _construct_vector(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    t = sized_type(tree, ev.origin)
    return (yield from _construct_as(ev, t, tree.children[3], tree))


def _construct_as(ev: Any, t: HType | None, args: Any, tree: Any) -> Generator[Any, Value, Value]:
    if t is None or not t.numeric:
        raise ev.error("X3037: constructors only defined for numeric base types", tree)
    comps: list[Operand] = []
    for a in (args.children if args is not None else []):
        v = yield a
        if not v.type.numeric:
            raise ev.error(f"X3017: cannot convert from '{v.type}' to '{t}'", a)
        comps.extend(ev.a.convert_base(v.comps, v.type.base, t.base, ev.at(a)))
    if len(comps) == 1 and t.size > 1:
        comps = comps * t.size
    if len(comps) != t.size:
        raise ev.error(f"X3014: incorrect number of arguments to numeric-type constructor "
                       f"('{t}' needs {t.size} values, given {len(comps)})", tree)
    return Value(t, comps)


def _cast(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    t = resolve_type(ev.ctx, tree.children[0], ev.origin)
    v = yield tree.children[1]
    if t.numeric and v.type.numeric:
        return ev.a.convert(v, t, ev.at(tree), explicit=True)
    return _cast_flat(ev, v, t, tree)


def _leaves(v: Value) -> list[tuple[Operand, str]]:
    """A value's numbers in declaration order, each with its base type (a struct or array
    walked with an explicit stack: its nesting is bounded, its size by hlsl_components)."""
    out: list[tuple[Operand, str]] = []
    stack = [v]
    while stack:
        x = stack.pop()
        if x.type.numeric:
            out.extend((c, x.type.base) for c in x.comps)
        elif x.type.kind == "struct":
            stack.extend(reversed(list(x.fields.values())))
        else:
            stack.extend(reversed(x.elements))
    return out


def _leaf_bases(t: HType) -> list[str]:
    out: list[str] = []
    stack = [t]
    while stack:
        x = stack.pop()
        if x.numeric:
            out.extend([x.base] * x.size)
        elif x.kind == "struct":
            stack.extend(reversed([ft for _, ft, _ in x.fields]))
        elif x.kind == "array" and x.element is not None:
            stack.extend([x.element] * x.length)
    return out


def _cast_flat(ev: Any, v: Value, t: HType, tree: Any) -> Value:
    """A cast to or from a struct or array, as fxc does it: `(VS_OUTPUT)0` sets every member
    to the scalar; otherwise the numbers are taken in declaration order, the source having at
    least as many as the destination (each converted to its member's base type)."""
    bases = _leaf_bases(t)
    src = _leaves(v) if v.type.numeric or v.type.kind in ("struct", "array") else []
    spread = len(src) == 1 and v.type.numeric        # only a scalar spreads: `(S)0`
    if not bases or not src or (not spread and len(src) < len(bases)):
        raise ev.error(f"X3017: cannot convert from '{v.type}' to '{t}'", tree)
    if spread:
        src = src * len(bases)
    loc = ev.at(tree)
    comps = [ev.a.convert_base([c], base, want, loc)[0] for (c, base), want in zip(src, bases)]
    return build_value(t, comps)


def _ternary(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    cond_tree, a_tree, b_tree = tree.children
    cond = yield cond_tree
    a = yield a_tree
    b = yield b_tree
    loc = ev.at(tree)
    if not (a.type.numeric and b.type.numeric):
        raise ev.error(f"X3020: type mismatch between conditional values ('{a.type}' and "
                       f"'{b.type}')", tree)
    ca, cb, t = ev.a.broadcast(a, b, loc, "?:")
    c = ev.a.to_bool(cond, loc).comps
    if len(c) == 1:
        c = c * len(ca)
    elif len(ca) == 1:                 # scalar values: one per component of the condition
        ca, cb, t = ca * len(c), cb * len(c), cond.type.with_base(t.base)
    elif len(c) != len(ca):            # fxc's text, as DXC's tests record it
        raise ev.error("X3020: dimension of conditional does not match value", tree)
    return Value(t, ev.a.select(c, ca, cb, loc))


def _call(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    name_tok, args = tree.children
    name = str(name_tok)
    arg_trees = list(args.children) if args is not None else []
    values = []
    for a in arg_trees:
        values.append((yield a))
    fdefs = ev.ctx.functions.get(name)
    if fdefs:
        fdef = resolve_overload(ev, fdefs, values, tree)
        if fdef is not None:
            return ev.call_user(fdef, values, arg_trees, tree)
    if name in INTRINSICS:
        return call_intrinsic(ev, name, values, arg_trees, tree)
    if fdefs:
        shown = ", ".join(str(v.type) for v in values)
        raise ev.error(f"X3013: '{name}': no matching {len(values)} parameter function "
                       f"(arguments: {shown})", name_tok)
    raise ev.error(f"X3004: undeclared identifier '{name}'", name_tok)


def _method(ev: Any, tree: lark.Tree) -> Generator[Any, Value, Value]:
    """`Tex.Sample(S, uv)` and the other texture methods (intrinsics.texture_method)."""
    base_tree, name_tok, args = tree.children
    base = yield base_tree
    values = []
    for a in (args.children if args is not None else []):
        values.append((yield a))
    return texture_method(ev, base, str(name_tok), values, name_tok)


_HANDLERS = {
    "float_lit": _float, "int_lit": _int, "bool_lit": _bool, "var": _var, "binary": _binary,
    "prefix": _prefix, "pre_incdec": lambda ev, t: _incdec(ev, t, False),
    "post_incdec": lambda ev, t: _incdec(ev, t, True), "assign": _assign, "member": _member,
    "index": _index, "construct": _construct, "construct_user": _construct_user, "construct_matrix": _construct_matrix,
    "construct_vector": _construct_vector, "cast": _cast, "ternary": _ternary, "call": _call,
    "method": _method,
    "comma": _comma,
}
