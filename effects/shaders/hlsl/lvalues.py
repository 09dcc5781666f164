"""L-values: writing a variable, member, swizzle (write mask) or constant element, and the
subscripts they share with reads (swizzles incl. matrix `._m00_m11`, constant indices)."""
from __future__ import annotations

import math
import re
from typing import Any, Callable

import lark

from effects.shaders.hlsl.budget import spend
from effects.shaders.hlsl.types import HType, scalar, vector
from effects.shaders.hlsl.values import Value

_LETTERS = {c: i for i, c in enumerate("xyzw")} | {c: i for i, c in enumerate("rgba")}
_MATRIX_SWIZZLE = re.compile(r"^(?:_m([0-3])([0-3]))+$|^(?:_([1-4])([1-4]))+$")


def store(ev: Any, target: Any, value: Value | Callable[[Value], Value],
          fixed: dict[int, int] | None = None) -> None:
    """Write `value` to the l-value `target` (a name, member, swizzle or constant index),
    walked without recursion: `a.b[2].xy` is the variable `a`, then member `b`, element 2,
    lanes xy. The values down that path are read once (an index expression is evaluated
    once: `a[i++] += 1` steps i once); the written one is rebuilt back up, each level a
    shallow copy (the rest is shared: values are never changed in place). `value` may be a
    function of the l-value's current value (`+=`, `++`, an `out` argument's conversion).

    An index known only at run time (`a[k] = v`, fxc's pixel-shader arrays) writes every
    element, each under the predicate "k is its index" (`fixed`: the indices already chosen
    so, by the index node's id). A cast on the left (`(float3)v = ...`, `((float2)v).x = ...`,
    as fxc allowed) writes the components the cast reads (cast_lanes)."""
    path: list[lark.Tree] = []
    root = target
    while isinstance(root, lark.Tree) and root.data in ("member", "index", "cast", "paren"):
        if root.data != "paren":
            path.append(root)
        root = root.children[-1] if root.data == "cast" else root.children[0]
    path.reverse()                                   # from the variable out
    if not (isinstance(root, lark.Tree) and root.data == "var"):
        raise ev.error("X3025: l-value expected (a variable, member, swizzle or element)", root)
    name = str(root.children[0])
    var = ev.lookup(name)
    written_global = var is None
    if var is None:
        var = _global_copy(ev, name, root)
    if var.const:
        raise ev.error(f"X3025: l-value specifies const object '{name}'", root)
    bases: list[Value] = [var.value]
    keys: list[Any] = []
    for node in path:
        base = bases[-1]
        if node.data == "member":
            key = node.children[1]
            if base.type.kind != "struct" and base.type.numeric:
                key = swizzle_lanes(ev, base.type, str(key), key, write=True)
            sub = member_of(ev, base, node.children[1])
        elif node.data == "cast":
            t = resolve_cast_type(ev, node)
            key = cast_lanes(ev, base.type, t, node)
            sub = ev.a.convert(base, t, ev.at(node), explicit=True)
        else:
            index_tree = node.children[1]
            if base.type.kind not in ("array", "matrix", "vector"):
                raise ev.error(f"X3121: array, matrix, vector, or indexable object type expected "
                               f"in index expression, not '{base.type}'", node)
            if fixed is not None and id(node) in fixed:
                key = fixed[id(node)]
            else:
                index = ev.expr(index_tree)
                if index.type.numeric and index.const_values() is None:
                    _store_each(ev, target, value, node, base.type, index, fixed or {})
                    return
                key = const_index(ev, index, index_tree, base.type)
            sub = element_of(ev, base, key, node)
        keys.append(key)
        bases.append(sub)
    if callable(value):
        value = value(bases[-1])
    for node, base, key in zip(reversed(path), reversed(bases[:-1]), reversed(keys)):
        out = base.shallow()
        spend(ev, len(out.comps) + len(out.fields) + len(out.elements), node)
        if node.data == "member" or node.data == "cast":
            if base.type.kind == "struct":
                out.fields[str(node.children[1])] = value
            else:
                where = node.children[1] if node.data == "member" else node
                v = ev.a.convert(value, vector(base.type.base, len(key)), ev.at(where))
                for lane, comp in zip(key, v.comps):
                    out.comps[lane] = comp
        elif base.type.kind == "array":
            out.elements[key] = value
        elif base.type.kind == "matrix":
            out.comps[key * base.type.cols:(key + 1) * base.type.cols] = value.comps
        else:
            out.comps[key] = value.comps[0]
        value = out
    # an unrolled loop's counter is written whatever the predicate; a local of this
    # function (not a parameter: an out one is copied back) under its own only (active); a
    # global's copy is read by every function after this one, so its write keeps every predicate
    local = not written_global and all(v is not var for v in ev.scopes[0].values())
    p = None if id(var) in ev.stepping else ev.active(local=local)
    var.value = ev.merge(var.value, value, p, ev.at(target))
    if written_global:         # every later read of the global, in any function, sees it
        ev.ctx.global_values[name] = var.value


# fxc's text for a write to a global that is not static (DXC's tests record it); fxc's
# backwards-compatibility mode (/Gec, D3DXSHADER_ENABLE_BACKWARDS_COMPATIBILITY), which hosts
# such as MikuMikuDance compiled with, allowed it
GLOBAL_WRITE = "X3025: global variables are implicitly constant, enable compatibility mode to " \
    "allow modification"


_AS_GEC = "is written as fxc's /Gec compiled it, a private copy initialised from the uniform"
_STRICT = "cannot be written: a strict load compiles as fxc did without /Gec"


def is_compatibility_warning(message: str) -> bool:
    """Whether a compile warning is a write fxc allowed only in compatibility mode (/Gec): a
    strict load refuses it as the error fxc gave without the flag (validate.verdicts)."""
    return message.startswith(GLOBAL_WRITE)


def strict_message(message: str) -> str:
    """The error a strict load gives for the compatibility warning `message`."""
    return message.replace(_AS_GEC, _STRICT)


def _global_copy(ev: Any, name: str, root: Any) -> Any:
    """The variable a write to global `name` writes. A static global is the shader's own; a
    uniform one is written as /Gec compiled it: a private copy, first the uniform's value
    (the constant registers read once, then the copy), with a located warning naming X3025.
    A const global, or an object (sampler, texture, string), is no l-value (X3025)."""
    from effects.shaders.hlsl.context import parameter_type
    from effects.shaders.hlsl.values import Var
    param = ev.ctx.effect.parameter(name)
    if param is None:
        raise ev.error(f"X3004: undeclared identifier '{name}'", root)
    t = parameter_type(ev.ctx, param)
    if "const" in param.storage or not (t.numeric or t.kind in ("struct", "array")) or \
            (t.kind == "array" and t.element is not None and t.element.kind == "sampler"):
        raise ev.error(f"X3025: l-value specifies const object '{name}'", root)
    if "static" not in param.storage:
        ev.warn(f"{GLOBAL_WRITE}: '{name}' {_AS_GEC}", ev.at(root))
    return Var(t, ev.expr(root))       # its value now: the uniform's, or a written copy's


def _store_each(ev: Any, target: Any, value: Any, node: Any, t: HType, index: Value,
                fixed: dict[int, int]) -> None:
    """`a[k] = value` with k known only at run time: element j written under "k == j" for
    each j (k truncated to an integer, as HLSL converts an index), the predicate of the
    statement kept. fxc wrote a pixel shader's arrays so, one compare and select each."""
    loc = ev.at(node.children[1])
    if index.type.size > 1:
        ev.warn("X3206: implicit truncation of vector type", loc)
    i = ev.a.convert_base(index.comps[:1], index.type.base, "int", loc)[0]
    n = t.length if t.kind == "array" else t.rows if t.kind == "matrix" else t.size
    spend(ev, n * max(t.element.components if t.kind == "array" else 4, 1), node)  # type: ignore[union-attr]
    saved = ev.mask
    try:
        for j in range(n):
            hit = ev.a.compare("==", [i], [ev.a.const(float(j))], loc)[0]
            ev.mask = ev._and(saved, hit)
            store(ev, target, value, {**fixed, id(node): j})
    finally:
        ev.mask = saved


def pick_element(ev: Any, base: Value, index: Value, where: Any) -> Value:
    """`base[k]` with k known only at run time, where no register is addressed by it (a pixel
    shader's arrays, a local array, a matrix's rows, a vector's lanes): a select chain over
    the elements, as fxc compiled it for ps_2_0 -- element 0, then for each j > 0 "k >= j ?
    element j : so far" (one compare and select each; an index past the end reads the last
    element, a negative one the first). k is truncated to an integer as HLSL converts it."""
    t = base.type
    loc = ev.at(where)
    if not index.type.numeric:
        raise ev.error(f"X3120: invalid type for index - index must be a scalar, not "
                       f"'{index.type}'", where)
    if index.type.size > 1:
        ev.warn("X3206: implicit truncation of vector type", loc)
    i = ev.a.convert_base(index.comps[:1], index.type.base, "int", loc)[0]
    n = t.length if t.kind == "array" else t.rows if t.kind == "matrix" else t.size
    # a compare and a select per element, each its components: the work budget's (a chain
    # over a huge array is refused before it is built, not after)
    spend(ev, n * (t.element.components if t.kind == "array" else t.cols) * 2, where)  # type: ignore[union-attr]
    picked = element_of(ev, base, 0, where)
    for j in range(1, n):
        hit = ev.a.compare(">=", [i], [ev.a.const(float(j))], loc)[0]
        picked = ev.merge(picked, element_of(ev, base, j, where), hit, loc)
    return picked


def cast_lanes(ev: Any, src: HType, t: HType, where: Any) -> list[int]:
    """The components of a `src` value that a cast to `t` on the left of an assignment
    names, in t's order: the first t.size numbers (a matrix cast keeps the upper-left
    rows and columns). Only numeric casts that drop or keep components are l-values."""
    if not (src.numeric and t.numeric) or t.size > src.size:
        raise ev.error(f"X3025: l-value expected: a cast from '{src}' to '{t}' cannot be "
                       "written", where)
    if src.kind == "matrix" and t.kind == "matrix":
        return [r * src.cols + c for r in range(t.rows) for c in range(t.cols)]
    return list(range(t.size))


def resolve_cast_type(ev: Any, node: Any) -> HType:
    from effects.shaders.hlsl.context import resolve_type
    return resolve_type(ev.ctx, node.children[0], ev.origin)


def member_of(ev: Any, base: Value, name: Any) -> Value:
    """`base.name`: a struct member or a swizzle (a matrix's `._m00_m11`)."""
    if base.type.kind == "struct":
        if str(name) not in base.fields:
            raise ev.error(f"X3018: invalid subscript '{name}'", name)
        return base.fields[str(name)]
    if not base.type.numeric:
        raise ev.error(f"X3018: invalid subscript '{name}' on '{base.type}'", name)
    lanes = swizzle_lanes(ev, base.type, str(name), name)
    return Value(vector(base.type.base, len(lanes)), [base.comps[k] for k in lanes])


def element_of(ev: Any, base: Value, k: int, tree: Any) -> Value:
    """`base[k]` for a constant k (const_index checked it against the size)."""
    t = base.type
    if t.kind == "array":
        return base.elements[k]
    if t.kind == "matrix":
        return Value(vector(t.base, t.cols), base.comps[k * t.cols:(k + 1) * t.cols])
    if t.kind == "vector":
        return Value(scalar(t.base), [base.comps[k]])
    raise ev.error(f"X3121: array, matrix, vector, or indexable object type expected in index "
                   f"expression, not '{t}'", tree)


def const_index(ev: Any, index: Value, tree: Any, t: HType) -> int:
    """The constant `index` (an expression's value) into a value of type `t`, checked
    against its size: an index known only at run time is X3512, one outside X3504 (an
    infinite or NaN index is outside)."""
    if not index.type.numeric:
        raise ev.error(f"X3120: invalid type for index - index must be a scalar, not "
                       f"'{index.type}'", tree)
    v = index.const_values()
    if v is None:
        raise ev.error(f"X3512: array index must be a literal expression on {ev.ctx.target.name} "
                       "(only uniform arrays read in vertex shaders take a run-time index)", tree)
    n = t.length if t.kind == "array" else t.rows if t.kind == "matrix" else t.size
    k = int(v[0]) if math.isfinite(v[0]) else None        # truncated, as HLSL converts
    if k is None or not 0 <= k < n:
        if getattr(ev, "literal_bounds_only", False) and not _is_literal(tree):
            # the whole-file check (check.py): fxc's bound check of a folded index ran as it
            # optimised the code it compiled; only a literal one is the text's own error
            return 0
        raise ev.error(f"X3504: array index {v[0] if k is None else k} out of bounds (the "
                       f"size is {n})", tree)
    return k


def _is_literal(tree: Any) -> bool:
    """Whether an index is written as a number (`a[2]`, `a[-1]`)."""
    while isinstance(tree, lark.Tree) and tree.data == "prefix":
        tree = tree.children[1]
    return isinstance(tree, lark.Tree) and tree.data in ("int_lit", "float_lit")


def swizzle_lanes(ev: Any, t: HType, name: str, where: Any, write: bool = False) -> list[int]:
    if t.kind == "matrix":
        m = _MATRIX_SWIZZLE.match(name) if len(name) <= 16 else None
        if not m:     # at most four components, as a vector swizzle (`._m00_m01_m02_m03`)
            raise ev.error(f"X3018: invalid subscript '{name}'", where)
        pairs = re.findall(r"_m([0-3])([0-3])|_([1-4])([1-4])", name)
        lanes = []
        for a, b, c, d in pairs:
            r, col = (int(a), int(b)) if a else (int(c) - 1, int(d) - 1)
            if r >= t.rows or col >= t.cols:
                raise ev.error(f"X3018: invalid subscript '{name}'", where)
            lanes.append(r * t.cols + col)
    else:
        if len(name) > 4 or any(ch not in _LETTERS for ch in name) or \
                len({ch in "xyzw" for ch in name}) > 1:
            raise ev.error(f"X3018: invalid subscript '{name}'", where)
        lanes = [_LETTERS[ch] for ch in name]
        if any(k >= t.size for k in lanes):
            raise ev.error(f"X3018: invalid subscript '{name}'", where)
    if write and len(set(lanes)) != len(lanes):
        # a swizzle naming a component twice is a value, not an l-value: fxc's X3025 (DXC's
        # tests record "l-value specifies const object" for `f.xx = 2`)
        raise ev.error(f"X3025: l-value specifies const object ('{name}' names a component "
                       "twice)", where)
    return lanes


