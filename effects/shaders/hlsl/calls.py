"""User function calls: overload resolution as fxc does it, then inlining.

Overloads: a candidate whose parameter count fits (defaults included) is scored by the
conversions its arguments need (exact 0, promotion of the base 1, scalar spread 2,
truncation 3); the lowest total wins, and two candidates with the same score are ambiguous
(X3067). Inlining binds `in` parameters to converted copies of the arguments, starts `out`
parameters at zero, runs the body in a new frame, and writes `out`/`inout` parameters back
to the argument l-values.
"""
from __future__ import annotations

from typing import Any

import lark

from effects.shaders.hlsl.budget import enter_level, leave_level, spend
from effects.shaders.hlsl.context import FunctionDef, centroid_semantic, resolve_type
from effects.shaders.hlsl.lvalues import store
from effects.shaders.hlsl.types import HType
from effects.shaders.hlsl.values import Frame, Value


def parameters(ev: Any, fdef: FunctionDef) -> list[tuple[str, HType, str, Any, Any]]:
    """(name, type, direction, default tree, semantic tree) per parameter."""
    params = fdef.tree.children[3]
    out = []
    for p in (params.children if params is not None else []):
        mods, spec, name, dims, sem, default = p.children
        words = [str(m) for m in mods.children] if mods is not None else []
        direction = "inout" if "inout" in words else "out" if "out" in words else \
            "uniform" if "uniform" in words else "in"
        # (context.load_context checked the declaration: no void, repeated or const out one)
        t = _array_of(ev, fdef, resolve_type(ev.ctx, spec, fdef.origin, mods), dims, name)
        out.append((str(name), t, direction, default, centroid_semantic(mods, sem)))
    return out


def constant_parameters(fdef: FunctionDef) -> frozenset[str]:
    """The parameters a body may not write (fxc's X3025, "l-value specifies const object"):
    `const` ones and `uniform` ones (the constant registers a compile argument or the host
    sets; from memory: no fxc text for writing one was found)."""
    params = fdef.tree.children[3]
    out = set()
    for p in (params.children if params is not None else []):
        mods = p.children[0]
        words = {str(m) for m in mods.children} if mods is not None else set()
        if words & {"const", "uniform"} and not words & {"out", "inout"}:
            out.add(str(p.children[2]))
    return frozenset(out)


def _array_of(ev: Any, fdef: FunctionDef, t: HType, dims: Any, name: Any) -> HType:
    """A parameter's array type: its sizes are constant expressions of the function's text."""
    if not dims.children:
        return t
    return ev.spawn(fdef.origin).array_of(t, dims, f"parameter '{name}'")


def return_type(ctx: Any, fdef: FunctionDef) -> HType:
    spec = fdef.tree.children[1].children[0]
    if isinstance(spec, lark.Token):
        return HType("void")
    return resolve_type(ctx, spec, fdef.origin)


def _cost(arg: HType, param: HType) -> int | None:
    if arg == param:
        return 0
    if not arg.numeric or not param.numeric:
        return 0 if (arg.kind == param.kind and arg.name == param.name) else None
    if arg.size == param.size and arg.kind == param.kind or \
            (arg.size == param.size and {arg.kind, param.kind} <= {"scalar", "vector"}):
        return 0 if arg.base == param.base else 1
    if arg.size == 1:
        return 2
    if arg.size > param.size:
        return 3
    return None


def resolve_overload(ev: Any, fdefs: list[FunctionDef], args: list[Value], where: Any) -> FunctionDef | None:
    scored = []
    for fdef in fdefs:
        params = parameters(ev, fdef)
        required = sum(1 for p in params if p[3] is None)
        if not required <= len(args) <= len(params):
            continue
        costs = [_cost(a.type, p[1]) for a, p in zip(args, params)]
        if any(c is None for c in costs):
            continue
        scored.append((sum(costs), fdef))  # type: ignore[arg-type]
    if not scored:
        return None
    scored.sort(key=lambda s: s[0])
    if len(scored) > 1 and scored[0][0] == scored[1][0]:
        raise ev.error(f"X3067: '{fdefs[0].name}': ambiguous function call", where)
    return scored[0][1]


def inline_call(ev: Any, fdef: FunctionDef, args: list[Value], arg_trees: list[Any], where: Any) -> Value:
    """The call's value, its body evaluated in place (one level of hlsl_nesting; a function
    that is already being inlined is recursion, which fxc refuses whether or not it ends)."""
    calling = ev.ctx.calling
    if any(f is fdef for f in calling):
        raise ev.error(f"X3500: recursive call to '{fdef.name}' (recursion is not allowed)", where)
    enter_level(ev, where, 2)
    calling.append(fdef)
    try:
        return _inline(ev, fdef, args, arg_trees, where)
    finally:
        calling.pop()
        leave_level(ev, 2)


def _inline(ev: Any, fdef: FunctionDef, args: list[Value], arg_trees: list[Any], where: Any) -> Value:
    params = parameters(ev, fdef)
    spend(ev, 1 + sum(t.components for _, t, *_ in params), where)
    callee = ev.spawn(fdef.origin)
    callee.depth = ev.depth + 1
    callee.outer = ev.active()
    ret_type = return_type(ev.ctx, fdef)
    callee.frames.append(Frame(ret_type))
    fixed = constant_parameters(fdef)
    for k, (name, t, direction, default, _sem) in enumerate(params):
        if k < len(args):
            value = args[k]
        else:
            value = callee.expr(default)
        loc = ev.at(arg_trees[k]) if k < len(arg_trees) else fdef.origin.at(default)
        if direction == "out":
            bound = callee.zero(t)
        else:
            bound = ev.a.convert(value, t, loc)
        callee.declare(name, t, bound, const=name in fixed)
    body = fdef.tree.children[-1]
    callee.block_in_frame(body)
    for k, (name, t, direction, _d, _s) in enumerate(params):
        if direction in ("out", "inout") and k < len(arg_trees):
            result = callee.scopes[0][name].value
            target = arg_trees[k]
            store(ev, target, lambda current, result=result, target=target:
                  ev.a.convert(result, current.type, ev.at(target)))
    frame = callee.frames[-1]
    if ret_type.kind != "void" and frame.retval is None:
        raise fdef.origin.error(f"X3080: '{fdef.name}': function must return a value", fdef.tree)
    return frame.retval if frame.retval is not None else Value(ret_type)
