"""L-values: writing a variable, member, swizzle (write mask) or constant element, and the
subscripts they share with reads (swizzles incl. matrix `._m00_m11`, constant indices)."""
from __future__ import annotations

import re
from typing import Any

import lark

from effects.shaders.hlsl.types import HType, vector
from effects.shaders.hlsl.values import Value

_LETTERS = {c: i for i, c in enumerate("xyzw")} | {c: i for i, c in enumerate("rgba")}
_MATRIX_SWIZZLE = re.compile(r"^(?:_m([0-3])([0-3]))+$|^(?:_([1-4])([1-4]))+$")


def store(ev: Any, target: Any, value: Value) -> None:
    """Write `value` to the l-value `target` (a name, member, swizzle or constant index)."""
    kind = target.data if isinstance(target, lark.Tree) else ""
    if kind == "var":
        name = str(target.children[0])
        var = ev.lookup(name)
        if var is None:
            if ev.ctx.effect.parameter(name) is not None:
                raise ev.error(f"X3025: global variables are implicitly constant; '{name}' "
                               "cannot be written in a shader (copy it to a local)", target)
            raise ev.error(f"X3004: undeclared identifier '{name}'", target)
        if var.const:
            raise ev.error(f"X3025: l-value specifies const object '{name}'", target)
        p = None if id(var) in ev.stepping else ev.active()     # an unrolled loop's counter
        var.value = ev.merge(var.value, value, p, ev.at(target))
        return
    if kind == "member":
        base_tree, name = target.children
        base = ev.expr(base_tree).copy()
        if base.type.kind == "struct":
            base.fields[str(name)] = value
        else:
            lanes = swizzle_lanes(ev, base.type, str(name), name, write=True)
            v = ev.a.convert(value, vector(base.type.base, len(lanes)), ev.at(name))
            for lane, comp in zip(lanes, v.comps):
                base.comps[lane] = comp
        store(ev, base_tree, base)
        return
    if kind == "index":
        base_tree, index_tree = target.children
        base = ev.expr(base_tree).copy()
        k = const_index(ev, index_tree, base.type)
        if base.type.kind == "array":
            base.elements[k] = value
        elif base.type.kind == "matrix":
            base.comps[k * base.type.cols:(k + 1) * base.type.cols] = value.comps
        else:
            base.comps[k] = value.comps[0]
        store(ev, base_tree, base)
        return
    raise ev.error("X3025: l-value expected (a variable, member, swizzle or element)", target)


def const_index(ev: Any, tree: Any, t: HType) -> int:
    v = ev.expr(tree).const_values()
    if v is None:
        raise ev.error(f"X3512: array index must be a literal expression on {ev.ctx.target.name} "
                       "(only uniform arrays read in vertex shaders take a run-time index)", tree)
    k = int(v[0])
    n = t.length if t.kind == "array" else t.rows if t.kind == "matrix" else t.size
    if not 0 <= k < n:
        raise ev.error(f"X3504: array index {k} out of bounds (the size is {n})", tree)
    return k


def swizzle_lanes(ev: Any, t: HType, name: str, where: Any, write: bool = False) -> list[int]:
    if t.kind == "matrix":
        m = _MATRIX_SWIZZLE.match(name)
        if not m:
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
        raise ev.error(f"X3018: invalid subscript '{name}' (a write mask names each component once)",
                       where)
    return lanes


