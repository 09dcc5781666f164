"""Real loops: `for (int i = 0; i < Count; i++)` with `int Count;` a uniform, as `rep i#` or
`loop aL, i#`.

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
  the body may read it (a vertex shader indexes a uniform array through a0 by it);
- where the target has `loop` (vs_2_0 and up, ps_3_0) and the body indexes a uniform array
  by the counter (plus a literal), the read is c[aL + n] and the loop is `loop aL, i#`, as
  fxc compiles `for (int i = 0; i < NumLights; i++) c += Lights[i].Color`: aL runs
  0, 1, ... (the effect sets the parameter's i# to (N, 0, 1, 0), as D3DX's constant table
  does: lower/passes._int_constants), so the element must take one register; a vertex
  shader reads a larger one through a0 in a `rep`. The float counter is then carried only
  where the body reads it as a number (flowcode.live_nodes).
- `[loop] for (int i = A; i < B; i++)` over compile-time integers is a real loop too, its
  count in a `defi` (B - A, first aL, aL step = the element's registers, 0): `rep` or
  `loop aL`. Where it cannot be one it is unrolled, with a warning that says why.

`continue` and `break` in the body run what follows them under their predicates (selects); a
break leaves the rep with `break_ne` at the end of the iteration where the target has dynamic
flow control (see _run_body). Loops nest (a uniform loop inside another is a region inside
the outer one's), up to the 4 levels of rep / loop nesting of 2_x / 3_0 code (flowrules.py).
What the region cannot hold yet is refused with its reason, and the loop is then unrolled as
before (which succeeds when a `break` on a constant ends it): return / discard in the body,
a break where the target has no break_comp, a sampler the body changes, nesting past the
limit. Arrays and structs of numbers the body changes are carried like numbers (`carried`).
A `for` over literal bounds with no attribute is unrolled, and a real loop only where the
unrolled code does not fit (compiler.compile_shader asks again). `[unroll]` always unrolls.
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Any

import lark

from effects.shaders.hlsl.components import component_register, taken_registers, uniform_component
from effects.shaders.hlsl.dag import Operand
from effects.shaders.hlsl.flowrules import (DYNAMIC_TARGETS, Effects, NotReal, TargetFlow, enter,
                                            flow_vars, leave, refusal)
from effects.shaders.hlsl.types import HType
from effects.shaders.hlsl.values import Loop, Value, Var, build_value, count_components

_ids = itertools.count()




@dataclass(frozen=True)
class Bound:
    """A loop that can run as real flow control: `for (int i = start; i < P; i++)` with P a
    uniform int parameter's scalar component (`param`, `component`: `n`, `vn.z`, `an[1]`;
    start 0), or `[loop] for (int i = A; i < B; i++)` with A, B compile-time integers
    (`param` None, `count` = B - A iterations)."""
    counter: str
    param: str | None
    start: int = 0
    count: int | None = None
    component: int = 0

    def why(self) -> str:
        """What makes the loop one that cannot be unrolled (the head of an X3511 reason)."""
        if self.param is not None:
            return f"its count is the uniform '{self.param}', known only when the shader runs"
        return "it is marked [loop]"


def bound_of(ev: Any, tree: lark.Tree, cond: Any, step: Any, attrs: Any = None) -> Bound | None:
    """The loop's Bound when it is `for (int i = 0; i < P; i++)` (or `++i`, `i += 1`; `i` may be
    declared before the loop) with P one component of a uniform int parameter, read through
    literal indices, members and swizzles (components.py), or a `[loop]` for over
    compile-time integer bounds (count 0..255, start 0..255: what an integer constant holds);
    otherwise None."""
    if cond is None or step is None or not isinstance(cond, lark.Tree) or cond.data != "binary":
        return None
    left, op, right = cond.children
    if str(op) != "<" or not _is_var(left):
        return None
    counter = str(left.children[0])
    var = ev.lookup(counter)
    if var is None or var.type.kind != "scalar" or var.type.base not in ("int", "uint"):
        return None
    if len(step.children) != 1 or not _increments(step.children[0], counter):
        return None
    first = var.value.const_values()
    if first is None:
        return None
    found = uniform_component(ev, right, ("int", "uint"))
    if found is not None:
        return Bound(counter, found[0], component=found[1]) if first == (0.0,) else None
    asked = has_attribute(attrs, "loop") or ev.ctx.loops_for_size
    if not asked and not TargetFlow.of(ev.ctx.target).static:
        return None
    last = ev.expr(right).const_values()
    if last is None or len(last) != 1 or not all(math.isfinite(x) for x in (first[0], last[0])) \
            or last[0] != int(last[0]) or first[0] != int(first[0]):
        return None
    start, count = int(first[0]), int(last[0]) - int(first[0])
    if not (0 <= start <= 255 and 0 <= count <= 255):
        return None
    if not asked:                 # unrolled first; a real loop if that does not fit
        ev.ctx.literal_loops += 1
        return None
    return Bound(counter, None, start, count)


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


def carried(t: HType) -> bool:
    """Whether a variable of type `t` can be carried round a real loop in registers: numbers,
    and arrays and structs made of them (the body writes `acc[1].y += d`; issue 31: fxc
    emitted `rep i0` for such loops). Samplers and the like stay what they were."""
    if t.numeric:
        return True
    if t.kind == "array" and t.element is not None:
        return carried(t.element)
    return t.kind == "struct" and all(carried(ft) for _, ft, _ in t.fields)


def components(v: Value) -> list[Operand]:
    """Every number of a carried value, in declaration order (build_value's order)."""
    if v.type.numeric:
        return list(v.comps)
    out: list[Operand] = []
    if v.type.kind == "struct":
        for name, _, _ in v.type.fields:
            out.extend(components(v.fields[name]))
    else:
        for e in v.elements:
            out.extend(components(e))
    return out


def _phis(ev: Any, loop_id: int, var: Var, start: int) -> tuple[Value, list[Operand]]:
    """`var`'s value as phi leaves (groups of up to 4 components), and the group operands."""
    comps: list[Operand] = []
    groups: list[Operand] = []
    n = count_components(var.type)
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


@dataclass
class AL:
    """The loop counter register of a real loop whose counter indexes uniform arrays: such a
    read is c[aL + n] (a `uniform_al` node), and the loop is `loop aL, i#` instead of
    `rep i#`. aL runs stride * i: from stride * start by stride (an integer constant holds
    (count, first aL, aL step, 0)). A loop counted by an int uniform has stride 1: D3DX sets
    an int parameter's i# to (N, 0, 1, 0) (the constant table's int4 registers: the value,
    then 0, 1, 0 in the components it does not give), so aL runs 0, 1, ... N - 1."""
    counter: Operand            # the counter's phi in this evaluation of the body
    start: int
    fixed_step: bool            # counted by an int uniform: aL steps by 1
    stride: int | None = None   # registers an element takes (the aL step), from the first use
    used: bool = False


def al_element(ev: Any, t: HType, index: Operand) -> tuple[int, Operand] | None:
    """For `Array[i + k]` (k >= 0 a literal, i the innermost real loop's counter, read in its
    body or in a loop unrolled there) of a uniform
    array of type `t`: (the element's register offset from aL, the counter's phi), to read
    it as c[aL + n] (expressions.uniform_value), where the target has `loop` (vs_2_0 and up,
    ps_3_0: the DirectX 9 relative-addressing page: aL indexes c# there) and the element
    size fits the loop (one register for a loop counted by a uniform). None otherwise."""
    from effects.shaders.hlsl.types import register_count
    # the innermost real loop (an unrolled one inside it makes no block, so aL is still its
    # counter); a real loop inside it has its own AL, whose counter is not this index
    al = next((loop.al for loop in reversed(ev.loops) if loop.al is not None), None)
    if al is None:
        return None
    k = _counter_offset(al.counter, index)
    if k is None:
        return None
    stride = register_count(t.element)  # type: ignore[arg-type]
    if al.stride is None:
        if (al.fixed_step and stride != 1) or stride > 127 or stride * al.start > 255:
            return None
        al.stride = stride
    elif al.stride != stride:
        return None
    al.used = True
    return k * stride, al.counter


def _counter_offset(counter: Operand, index: Operand) -> int | None:
    """k when `index` is the counter plus a literal k >= 0."""
    if index.sig() == counter.sig():
        return 0
    n = index.node
    if n.op != "add" or index.negate or index.swizzle != (0,) or n.width != 1:
        return None
    for a, b in ((n.args[0], n.args[1]), (n.args[1], n.args[0])):
        k = b.const_values()
        if a.sig() == counter.sig() and k is not None and 0 <= k[0] < 1e9 and k[0] == int(k[0]):
            return int(k[0])
    return None


def _free_int(ctx: Any) -> int:
    taken = taken_registers(ctx, "i")
    k = 0
    while k in taken:
        k += 1
    return k


def real_loop(ev: Any, tree: Any, body: Any, step: Any, bound: Bound) -> None:
    """Evaluate the loop as a `rep` / `loop` region (raises NotReal with the reason it
    cannot)."""
    ctx = ev.ctx
    # a uniform count's i#, given before the body (so an outer loop's count comes first); a
    # literal count's `defi` register once the body says rep or loop; given back when the
    # loop cannot be real
    ints = ctx.int_registers
    defs = ctx.int_defs
    had = set(defs)
    fresh = bound.param is not None and bound.param not in ints
    if fresh:
        component_register(ctx, bound.param, "i")
    try:
        _real_loop(ev, tree, body, step, bound)
    except NotReal:
        if fresh:
            del ints[bound.param]
            del ctx.component_counts[bound.param]
        for k in set(defs) - had:
            del defs[k]
        raise


def _real_loop(ev: Any, tree: Any, body: Any, step: Any, bound: Bound) -> None:
    ctx = ev.ctx
    variables = numeric_vars(ev) + flow_vars(ev)
    initial = {id(v): v.value for v in variables}
    others = [v for v in variables if not carried(v.type)]
    before = {id(v): flat(v.value) for v in others}
    # pass 1: every numeric variable over phis, to see which the body changes
    trial = next(_ids)
    changed: list[Var] = []
    phi_values: dict[int, Value] = {}
    k = 0
    for v in variables:
        if carried(v.type):
            phi_values[id(v)], groups = _phis(ev, trial, v, k)
            k += len(groups)
            v.value = phi_values[id(v)]
    try:
        _run_body(ev, tree, body, step, bound)   # raises NotReal (nothing to restore but values)
        for v in variables:
            if carried(v.type) and flat(v.value) != flat(phi_values[id(v)]):
                changed.append(v)
            elif not carried(v.type) and flat(v.value) != before[id(v)]:
                raise NotReal(refusal(v, "in the body", "rep"))
    finally:
        for v in variables:
            v.value = initial[id(v)]
    # pass 2: only the changed variables over phis; their new values are the results
    loop_id = next(_ids)
    inits: list[Operand] = []
    phis: list[Operand] = []
    moving: list[tuple[Var, list[Operand]]] = []
    for v in changed:
        value, groups = _phis(ev, loop_id, v, len(phis))
        inits.extend(_groups(ev, v.value, len(groups)))
        phis.extend(groups)
        moving.append((v, groups))
        v.value = value
    try:
        broken, al, kills = _run_body(ev, tree, body, step, bound)
        moved = {id(v) for v in changed}
        for v in variables:
            if id(v) not in moved and flat(v.value) != flat(initial[id(v)]):
                raise NotReal("the variables the body changes are not the same on a second look")
        results = [g for v, _ in moving for g in
                   _groups(ev, v.value, -(-count_components(v.type) // 4))]
    except BaseException:
        for v in variables:
            v.value = initial[id(v)]
        raise
    uses_al = al is not None and al.used
    if bound.param is not None:
        register = ctx.int_registers[bound.param] + bound.component
    else:
        register = _free_int(ctx)
        s = al.stride if uses_al else 0
        ctx.int_defs[register] = (bound.count, s * bound.start, s, 0) if uses_al else \
            (bound.count, 0, 0, 0)
    # a break: the iteration's results are moved back, then `break_ne broken, 0` leaves;
    # the body's discards after (flowcode.py emits them in the body)
    extra = (broken,) if broken is not None else ()
    loop = ev.g.leaf("loop", (loop_id, register, len(phis), bool(extra), uses_al), 1,
                     ev.at(tree), tuple(inits + results) + extra + tuple(kills))
    if kills:
        ctx.kills.append(loop)                # it discards: reached whatever reads it
        loop.node.effect = True
    k = 0
    for v, groups in moving:
        comps: list[Operand] = []
        for group in groups:
            out = ev.g.leaf("loop_out", (loop_id, k), group.width, ev.at(tree), (loop,))
            comps.extend(Operand(out.node, (i,)) for i in range(group.width))
            k += 1
        v.value = build_value(v.type, comps)


def _groups(ev: Any, value: Value, count: int) -> list[Operand]:
    comps = components(value)
    return [ev.g.pack(comps[k * 4:k * 4 + 4]) for k in range(count)]


def _run_body(ev: Any, tree: Any, body: Any, step: Any, bound: Bound
              ) -> tuple[Operand | None, AL | None, list[Operand]]:
    """The body and the step once, with nothing the region cannot hold; the predicate 'the
    loop leaves after this iteration' (None: it never does), the loop's AL (None: the target
    has no aL) and the discards the body made (held by the loop node).

    continue: the rest of the body runs under its predicate (selects), the step does not.
    break: the rest of the body and the step run under its predicate, so the results are the
    values the loop had when it broke; the loop leaves at the end of the iteration, after the
    results are moved back, by `break_ne` (dynamic flow control: vs_2_a, vs_3_0, ps_3_0).
    return: the frame's 'returned' and return value are carried like variables (real_loop's
    flow_vars), the rest of the body and later iterations run under 'not returned', and where
    the target has break_comp the loop also leaves once it returned. discard: a texkill in
    the body. The body must not change the counter (a rep / loop runs its count whatever the
    counter holds; aL steps by itself)."""
    ctx = ev.ctx
    made = Effects.note(ev)
    frame = ev.frames[-1] if ev.frames else None
    returned = frame.returned if frame is not None else None
    loop = Loop()
    counter = ev.lookup(bound.counter)
    first = flat(counter.value) if counter is not None else None
    if ctx.target.has("loop") and counter is not None and counter.type.size == 1:
        loop.al = AL(counter.value.comps[0], bound.start, bound.param is not None)
    enter(ev, "loop")
    ev.loops.append(loop)
    try:
        ev.scoped(body)
        loop.continued = None
        broken = loop.broken
        if broken is not None and not TargetFlow.of(ctx.target).dynamic:
            raise NotReal(f"break in the body needs break_comp, which {ctx.target.name} does not "
                          f"have ({DYNAMIC_TARGETS} do)")
        al = loop.al
        if counter is not None and flat(counter.value) != first:
            raise NotReal(f"the body changes the counter '{bound.counter}' (the loop runs the "
                          "count it was given, and aL steps by itself)")
        for e in step.children:
            ev.expr(e)
        if frame is not None and frame.returned is not returned and \
                TargetFlow.of(ctx.target).dynamic:
            broken = ev._or(broken, frame.returned)      # leave once it returned
        if broken is not None and broken.const_values() is not None:
            raise NotReal("the body always breaks" if loop.broken is not None else
                          "the body always returns")
        return broken, al, made.take(ev)
    finally:
        leave(ev, "loop")
        ev.loops.pop()
        made.take(ev)             # a body that cannot be real: its discards are dropped


def has_attribute(attrs: Any, name: str) -> bool:
    return attrs is not None and any(str(a.children[0]).lower() == name for a in attrs.children)


__all__ = ["AL", "Bound", "NotReal", "al_element", "bound_of", "real_loop", "has_attribute", "HType"]
