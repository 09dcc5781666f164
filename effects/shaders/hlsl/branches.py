"""Real `if`s: `if b#` on a bool uniform, `if_comp` for `[branch]`, where the target has them.

Which `if` stays a branch (fxc's choices, as far as its documentation and listings show):

- `if (B)` / `if (!B)` with `B` a (non-static) `uniform bool` global, or one component of one
  (`vb.z`, `sb.vb.z`: a b# per component, components.py): a *static* branch, `if b#`,
  on every target with static flow control (vs_2_0 and up, ps_2_x, ps_3_0: flowrules.py); the
  parameter gets a b# in the register table (CompiledShader.bool_registers) and lowering sets
  it as VertexShaderConstantB / PixelShaderConstantB. Elsewhere (vs_1_1, ps_2_0/2_a/2_b) the
  bool is a float constant and the `if` is flattened, as fxc does.
- `[branch] if (a < b)` (any comparison, or any condition, compared with 0): a *dynamic*
  branch, `if_lt a, b` / `if_ne c, 0`, where the target has dynamic flow control (vs_2_a,
  vs_3_0, ps_2_x, ps_3_0; `TargetFlow.dynamic`); on any other target it is a located
  error at the `if`.
- `[flatten]`, and an `if` on a run-time value without an attribute, are flattened into
  selects. fxc flattens small `if`s by itself and branches large ones in SM3; flattening is
  always correct and never needs a cap, so without `[branch]` we always flatten.

Evaluation: each side runs once with no predicate; the variables a side changes (numbers, and
structs and arrays of them) become results: the `if` node holds the condition
operands, the then-results and the else-results (the value before the `if` where a side
leaves a variable alone), and each changed variable reads `if_out` nodes after it. codegen
(flowcode.py) places the nodes used only by one side inside it. A side may return, break,
continue and discard: the frame's 'returned' and return value and the loop's 'broken' /
'continued' are carried like variables (flowrules.flow_vars: what follows the if runs under
'not returned' -- an early return by predicate), and a side's discards are held by the `if`
node, so the texkill runs inside the side. A side may change structs and arrays made of
numbers (their numbers are results, as a loop carries them: fxc's ps_3_0 in Wine's preshader
effect keeps `if b4` whose side changes `Output.RGBColor`); one that changes anything else,
or returns a struct, is NotReal (a bool `if` is then flattened; `[branch]` says why).
"""
from __future__ import annotations

import itertools
from typing import Any

import lark

from effects.shaders.hlsl.components import component_register, uniform_component
from effects.shaders.hlsl.dag import Operand
from effects.shaders.hlsl.flowrules import (MAX_DEPTH, Effects, NotReal, TargetFlow, enter,
                                            flow_vars, leave, refusal)
from effects.shaders.hlsl.loops import carried, components, flat, numeric_vars
from effects.shaders.hlsl.values import Value, Var, build_value

_ids = itertools.count()
_COMPARE = {"<": "lt", "<=": "le", ">": "gt", ">=": "ge", "==": "eq", "!=": "ne"}
def bool_uniform(ev: Any, cond: Any) -> tuple[str, int, bool] | None:
    """(parameter, component, negated) when the condition is `B` or `!B` with B one component
    of a uniform bool global (`b`, `vb.z`, `sab[1].vb.z`: components.py)."""
    negated = False
    if isinstance(cond, lark.Tree) and cond.data == "prefix" and str(cond.children[0]) == "!":
        cond, negated = cond.children[1], True
    found = uniform_component(ev, cond, ("bool",))
    return None if found is None else (*found, negated)


def comparison(ev: Any, cond: Any) -> tuple[str, list[Operand]]:
    """('lt', [a, b]) for a scalar comparison; else ('ne', [condition, 0])."""
    if isinstance(cond, lark.Tree) and cond.data == "binary" and str(cond.children[1]) in _COMPARE:
        left, op, right = cond.children
        a, b = ev.expr(left), ev.expr(right)
        if a.type.numeric and b.type.numeric and a.type.size == 1 and b.type.size == 1:
            return _COMPARE[str(op)], [a.comps[0], b.comps[0]]
        c = ev.a.compare(str(op), *_same_width(a.comps, b.comps), ev.at(cond))
        if len(c) > 1:              # a vector comparison is no condition (fxc's X3019)
            raise ev.error(condition_error("if", a.type if a.type.size > 1 else b.type), cond)
        return "ne", [c[0], ev.g.const((0.0,))]
    return "ne", [ev.condition(cond), ev.g.const((0.0,))]


def condition_error(statement: str, t: Any) -> str:
    """fxc's X3019 for a condition that is not a scalar (ReShade's texts for fxc's code: a
    vector is not truncated to its x, as an operand would be)."""
    what = "if statement conditional expressions must evaluate to a scalar" if statement == "if" \
        else "scalar value expected"
    return f"X3019: {what} (not '{t}')"


def _same_width(a: list[Operand], b: list[Operand]) -> tuple[list[Operand], list[Operand]]:
    n = min(len(a), len(b)) if len(a) > 1 and len(b) > 1 else max(len(a), len(b))
    return (a * n)[:n] if len(a) == 1 else a[:n], (b * n)[:n] if len(b) == 1 else b[:n]


def real_if(ev: Any, tree: Any, cond: tuple, then: Any, other: Any, kind: str) -> None:
    """Evaluate an `if` as a real branch. `cond`: ('bool', register) or (comparison,
    [a, b]); raises NotReal with the reason it cannot be one."""
    variables = numeric_vars(ev) + flow_vars(ev)
    initial = {id(v): v.value for v in variables}
    others = [v for v in variables if not carried(v.type)]
    before = {id(v): flat(v.value) for v in others}
    sides: list[dict[int, Value]] = []
    kills: list[list[Operand]] = []
    enter(ev, kind)
    try:
        for branch in (then, other):
            made = Effects.note(ev)
            try:
                if branch is not None:
                    ev.scoped(branch)
            finally:
                kills.append(made.take(ev))
            sides.append({id(v): v.value for v in variables})
            for v in others:
                if flat(v.value) != before[id(v)]:
                    raise NotReal(refusal(v, "inside it", "branch"))
            for v in variables:
                v.value = initial[id(v)]
    except BaseException:
        for v in variables:
            v.value = initial[id(v)]
        raise
    finally:
        leave(ev, kind)
    changed = [v for v in variables if carried(v.type) and any(
        flat(side[id(v)]) != flat(initial[id(v)]) for side in sides)]
    if_id = next(_ids)
    results: list[list[Operand]] = [[], []]
    widths: list[int] = []
    for v in changed:
        # a struct or an array of numbers is its numbers in declaration order, as a loop
        # carries it (loops.components): `Output.RGBColor += ...` in a side is a result
        per_side = [components(side[id(v)]) for side in sides]
        size = len(per_side[0])
        for k in range(0, size, 4):
            widths.append(min(4, size - k))
            for s, comps in enumerate(per_side):
                results[s].append(ev.g.pack(comps[k:k + 4]))
    test, args = cond
    # key: (id, 'bool' or the comparison, condition operands, result groups, b#, discards
    # of the then side); args: the condition, the then- and else-results, the then- and
    # else-discards (flowcode.py places each where its side is)
    breg = args[0] if test == "bool" else None
    conds: tuple[Operand, ...] = () if test == "bool" else tuple(args)
    node = ev.g.leaf("if", (if_id, test, len(conds), len(widths), breg, len(kills[0])), 1,
                     ev.at(tree), conds + tuple(results[0]) + tuple(results[1])
                     + tuple(kills[0]) + tuple(kills[1]))
    if kills[0] or kills[1]:
        ev.ctx.kills.append(node)             # it discards: reached whatever reads it
        node.node.effect = True
    k = 0
    for v in changed:
        comps: list[Operand] = []
        for _ in range(0, len(components(v.value)), 4):
            out = ev.g.leaf("if_out", (if_id, k), widths[k], ev.at(tree), (node,))
            comps.extend(Operand(out.node, (i,)) for i in range(widths[k]))
            k += 1
        v.value = build_value(v.type, comps)


def bool_register(ev: Any, name: str, component: int = 0) -> int:
    """The b# of a bool parameter's component: the parameter's register(b#) binding, else
    the next free run of registers, one per component (components.py), plus `component`."""
    return component_register(ev.ctx, name, "b") + component


__all__ = ["TargetFlow", "bool_uniform", "comparison", "real_if", "bool_register", "enter",
           "leave", "MAX_DEPTH", "Var"]
