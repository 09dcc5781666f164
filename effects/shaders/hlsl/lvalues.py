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


def store(ev: Any, target: Any, value: Value | Callable[[Value], Value]) -> None:
    """Write `value` to the l-value `target` (a name, member, swizzle or constant index),
    walked without recursion: `a.b[2].xy` is the variable `a`, then member `b`, element 2,
    lanes xy. The values down that path are read once (an index expression is evaluated
    once: `a[i++] += 1` steps i once); the written one is rebuilt back up, each level a
    shallow copy (the rest is shared: values are never changed in place). `value` may be a
    function of the l-value's current value (`+=`, `++`, an `out` argument's conversion)."""
    path: list[lark.Tree] = []
    root = target
    while isinstance(root, lark.Tree) and root.data in ("member", "index"):
        path.append(root)
        root = root.children[0]
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
        else:
            index_tree = node.children[1]
            if base.type.kind not in ("array", "matrix", "vector"):
                raise ev.error(f"X3121: array, matrix, vector, or indexable object type expected "
                               f"in index expression, not '{base.type}'", node)
            key = const_index(ev, ev.expr(index_tree), index_tree, base.type)
            sub = element_of(ev, base, key, node)
        keys.append(key)
        bases.append(sub)
    if callable(value):
        value = value(bases[-1])
    for node, base, key in zip(reversed(path), reversed(bases[:-1]), reversed(keys)):
        out = base.shallow()
        spend(ev, len(out.comps) + len(out.fields) + len(out.elements), node)
        if node.data == "member":
            if base.type.kind == "struct":
                out.fields[str(node.children[1])] = value
            else:
                v = ev.a.convert(value, vector(base.type.base, len(key)), ev.at(node.children[1]))
                for lane, comp in zip(key, v.comps):
                    out.comps[lane] = comp
        elif base.type.kind == "array":
            out.elements[key] = value
        elif base.type.kind == "matrix":
            out.comps[key * base.type.cols:(key + 1) * base.type.cols] = value.comps
        else:
            out.comps[key] = value.comps[0]
        value = out
    p = None if id(var) in ev.stepping else ev.active()     # an unrolled loop's counter
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
        raise ev.error(f"X3504: array index {v[0] if k is None else k} out of bounds (the "
                       f"size is {n})", tree)
    return k


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


