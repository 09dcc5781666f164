"""Real loops: `for (int i = 0; i < Count; i++)` with `int Count;` a uniform, as `rep i#`.

A loop whose bound is an int parameter cannot be unrolled (its count is known only when the
shader runs). In a target with static flow control (vs_2_0 and up, ps_2_x, ps_3_0) fxc emits
`rep i#` and puts the parameter in an integer register the effect sets; so does this:

- the body (with the step) is evaluated once over *phi* leaves, one per group of up to four
  components of each variable the body changes (found by a first evaluation over phis for
  every numeric variable in scope: a variable whose value comes back as its own phi is not
  changed). Nodes that do not depend on a phi are loop-invariant and computed before the loop;
  the rest is the loop's region, emitted once between `rep` and `endrep` (codegen.py);
- a `loop` node holds the initial values and the body's results (what the next iteration
  starts from); after the loop each changed variable reads `loop_out` nodes, which share the
  phi's register;
- the counter is one of the changed variables (a float register counting 0, 1, 2 ...), so
  the body may read it (a vertex shader indexes a uniform array through a0 by it).

`continue` and `break` in the body run what follows them under their predicates (selects); a
break leaves the rep with `break_ne` at the end of the iteration where the target has dynamic
flow control (see _run_body). Loops nest (a uniform loop inside another is a region inside
the outer one's), up to the 4 levels of rep / loop nesting of 2_x / 3_0 code (flowrules.py).
What the region cannot hold yet is refused with its reason, and the loop is then unrolled as
before (which succeeds when a `break` on a constant ends it): return / discard in the body,
a break where the target has no break_comp, arrays or structs the body changes, nesting past
the limit. `[unroll]` always unrolls.
"""
from __future__ import annotations

import itertools
from typing import Any

import lark

from effects.shaders.hlsl.dag import Operand
from effects.shaders.hlsl.flowrules import DYNAMIC_TARGETS, Escapes, NotReal, TargetFlow, enter, leave
from effects.shaders.hlsl.types import HType
from effects.shaders.hlsl.values import Loop, Value, Var, build_value, operand

_ids = itertools.count()




def bound_of(ev: Any, tree: lark.Tree, cond: Any, step: Any) -> tuple[str, str] | None:
    """(counter name, int parameter name) when the loop is `for (int i = 0; i < P; i++)`
    (or `++i`, `i += 1`) with P a uniform int scalar parameter; otherwise None."""
    if cond is None or step is None or not isinstance(cond, lark.Tree) or cond.data != "binary":
        return None
    left, op, right = cond.children
    if str(op) != "<" or not _is_var(left) or not _is_var(right):
        return None
    counter, bound = str(left.children[0]), str(right.children[0])
    var = ev.lookup(counter)
    if var is None or var.type.kind != "scalar" or var.type.base not in ("int", "uint"):
        return None
    if var.value.const_values() != (0.0,) or ev.lookup(bound) is not None:
        return None
    param = ev.ctx.effect.parameter(bound)
    if param is None or "static" in param.storage or param.type.base not in ("int", "uint", "dword") \
            or param.type.rows != 1 or param.type.cols != 1 or param.array:
        return None
    if len(step.children) != 1 or not _increments(step.children[0], counter):
        return None
    return counter, bound


def _is_var(t: Any) -> bool:
    return isinstance(t, lark.Tree) and t.data == "var"


def _increments(e: Any, name: str) -> bool:
    if not isinstance(e, lark.Tree):
        return False
    if e.data in ("post_incdec", "pre_incdec"):
        target, op = (e.children[0], e.children[1]) if e.data == "post_incdec" else \
            (e.children[1], e.children[0])
        return str(op) == "++" and _is_var(target) and str(target.children[0]) == name
    if e.data == "assign":
        target, op, rhs = e.children
        return str(op) == "+=" and _is_var(target) and str(target.children[0]) == name and \
            isinstance(rhs, lark.Tree) and rhs.data == "int_lit" and str(rhs.children[0]) == "1"
    return False


def numeric_vars(ev: Any) -> list[Var]:
    """The variables in scope, innermost name first (shadowed ones stay as they are)."""
    seen: dict[str, Var] = {}
    for scope in reversed(ev.scopes):
        for name, var in scope.items():
            seen.setdefault(name, var)
    return list(seen.values())


def _phis(ev: Any, loop_id: int, var: Var, start: int) -> tuple[Value, list[Operand]]:
    """`var`'s value as phi leaves (groups of up to 4 components), and the group operands."""
    comps: list[Operand] = []
    groups: list[Operand] = []
    n = var.type.size
    for k in range(0, n, 4):
        width = min(4, n - k)
        phi = ev.g.leaf("phi", (loop_id, start + len(groups)), width)
        groups.append(phi)
        comps.extend(Operand(phi.node, (i,)) for i in range(width))
    return build_value(var.type, comps), groups


def flat(v: Value) -> list[tuple]:
    if v.type.numeric:
        return [c.sig() for c in v.comps]
    out: list[tuple] = []
    for f in v.fields.values():
        out.extend(flat(f))
    for e in v.elements:
        out.extend(flat(e))
    return out


def real_loop(ev: Any, tree: Any, body: Any, step: Any, counter: str, bound: str) -> None:
    """Evaluate the loop as a `rep` region (raises NotReal with the reason it cannot)."""
    ctx = ev.ctx
    # the count's i#, given before the body (so an outer loop's count comes first); given
    # back when the loop cannot be a rep
    ints = ctx.__dict__.setdefault("int_registers", {})
    fresh = bound not in ints
    register = ints.setdefault(bound, len(ints))
    try:
        _real_loop(ev, tree, body, step, register)
    except NotReal:
        if fresh:
            del ints[bound]
        raise


def _real_loop(ev: Any, tree: Any, body: Any, step: Any, register: int) -> None:
    ctx = ev.ctx
    variables = numeric_vars(ev)
    initial = {id(v): v.value for v in variables}
    others = [v for v in variables if not v.type.numeric]
    before = {id(v): flat(v.value) for v in others}
    # pass 1: every numeric variable over phis, to see which the body changes
    trial = next(_ids)
    changed: list[Var] = []
    phi_values: dict[int, Value] = {}
    k = 0
    for v in variables:
        if v.type.numeric:
            phi_values[id(v)], groups = _phis(ev, trial, v, k)
            k += len(groups)
            v.value = phi_values[id(v)]
    try:
        _run_body(ev, tree, body, step)     # raises NotReal (nothing to restore but values)
        for v in variables:
            if v.type.numeric and flat(v.value) != flat(phi_values[id(v)]):
                changed.append(v)
            elif not v.type.numeric and flat(v.value) != before[id(v)]:
                raise NotReal("the body changes an array or a struct (not carried yet)")
    finally:
        for v in variables:
            v.value = initial[id(v)]
    # pass 2: only the changed variables over phis; their new values are the results
    loop_id = next(_ids)
    inits: list[Operand] = []
    phis: list[Operand] = []
    carried: list[tuple[Var, list[Operand]]] = []
    for v in changed:
        value, groups = _phis(ev, loop_id, v, len(phis))
        inits.extend(_groups(ev, v.value, len(groups)))
        phis.extend(groups)
        carried.append((v, groups))
        v.value = value
    try:
        broken = _run_body(ev, tree, body, step)
        moved = {id(v) for v in changed}
        for v in variables:
            if id(v) not in moved and flat(v.value) != flat(initial[id(v)]):
                raise NotReal("the variables the body changes are not the same on a second look")
        results = [g for v, _ in carried for g in _groups(ev, v.value, -(-v.type.size // 4))]
    except BaseException:
        for v in variables:
            v.value = initial[id(v)]
        raise
    # a break: the iteration's results are moved back, then `break_ne broken, 0` leaves
    extra = (broken,) if broken is not None else ()
    loop = ev.g.leaf("loop", (loop_id, register, len(phis), bool(extra)), 1, ev.at(tree),
                     tuple(inits + results) + extra)
    k = 0
    for v, groups in carried:
        comps: list[Operand] = []
        for group in groups:
            out = ev.g.leaf("loop_out", (loop_id, k), group.width, ev.at(tree), (loop,))
            comps.extend(Operand(out.node, (i,)) for i in range(group.width))
            k += 1
        v.value = build_value(v.type, comps)


def _groups(ev: Any, value: Value, count: int) -> list[Operand]:
    return [operand(ev.g, value.comps[k * 4:k * 4 + 4]) for k in range(count)]


def _run_body(ev: Any, tree: Any, body: Any, step: Any) -> Operand | None:
    """The body and the step once, with nothing the region cannot hold; the predicate 'the
    body broke out' (None: it never does).

    continue: the rest of the body runs under its predicate (selects), the step does not.
    break: the rest of the body and the step run under its predicate, so the results are the
    values the loop had when it broke; the loop leaves at the end of the iteration, after the
    results are moved back, by `break_ne` (dynamic flow control: vs_2_a, vs_3_0, ps_3_0). Return and discard inside stay refused."""
    ctx = ev.ctx
    escapes = Escapes.note(ev)
    loop = Loop()
    enter(ev, "loop")
    ev.loops.append(loop)
    try:
        ev.scoped(body)
        escapes.refuse(ev, "in the body", "rep")
        loop.continued = None
        broken = loop.broken
        if broken is not None and not TargetFlow.of(ctx.target).dynamic:
            raise NotReal(f"break in the body needs break_comp, which {ctx.target.name} does not "
                          f"have ({DYNAMIC_TARGETS} do)")
        for e in step.children:
            ev.expr(e)
        if broken is not None and broken.const_values() is not None:
            raise NotReal("the body always breaks")
        return broken
    finally:
        leave(ev, "loop")
        ev.loops.pop()
        escapes.undo(ev)


def has_attribute(attrs: Any, name: str) -> bool:
    return attrs is not None and any(str(a.children[0]).lower() == name for a in attrs.children)


__all__ = ["NotReal", "bound_of", "real_loop", "has_attribute", "HType"]
