"""Whether a loop to unroll ever ends, decided before its body runs.

fxc gives up on a loop after 1,024 iterations (X3511). Unrolling runs the body each time, so
a loop that never ends cost 1,024 runs of its body before it said so (a minute on a real
effect). When the body cannot change how the loop ends (it has no `break` or `return`, and
writes none of the variables the condition and the step name, directly or as a call's
argument), the loop ends exactly when its condition and step alone make the condition a
compile-time false: so they are run alone first, on a copy of the variables, and a loop
that does not end within the count, or whose condition and step come back to values they
had (`i += 0`, `while (true)`, a count that is a uniform), is refused after a few runs of
its body (evaluate.PROBE_AFTER), not 1,024.
"""
from __future__ import annotations

from typing import Any

import lark

from effects.shaders.hlsl.values import Loop

_ENDS_LOOP = frozenset(("break_stmt", "return_stmt"))
_WRITES = frozenset(("assign", "pre_incdec", "post_incdec"))


def never_ends(ev: Any, tree: Any, cond: Any, body: Any, step: Any, test_first: bool,
               own: frozenset[int], cap: int, start: list[tuple[Any, Any]]) -> str | None:
    """Why the loop never ends ('1024 iterations', or that its state repeats), or None when
    it ends or when its body may change that (then the unroll itself counts). `start`: each
    variable in scope with its value when the loop began (the run starts from there; every
    variable is as it was when this returns)."""
    facts = ev.ctx.loop_facts
    key = id(tree)
    if key not in facts:
        names = _names(cond) | _names(step)
        facts[key] = (names, not _may_end(body) and not (_written(body) & names))
    names, decided_by_head = facts[key]
    if not decided_by_head:
        return None
    saved = [(var, var.value) for scope in ev.scopes for var in scope.values()]
    for var, value in start:
        var.value = value
    # the answer depends only on where the named variables start (an inner loop of a nest
    # starts the same way each time: asked once)
    verdicts = ev.ctx.loop_verdicts
    first = (key, tuple(_state(ev, name) for name in sorted(names)))
    if first in verdicts:
        for var, value in saved:
            var.value = value
        return verdicts[first]
    verdicts[first] = verdict = _run_head(ev, cond, step, own, cap, names, saved)
    return verdict


def _run_head(ev: Any, cond: Any, step: Any, own: frozenset[int], cap: int, names: set[str],
              saved: list[tuple[Any, Any]]) -> str | None:
    """The loop's condition and step alone, from the values the variables hold now."""
    kills = len(ev.ctx.kills)
    seen: set[tuple] = set()
    ev.loops.append(Loop())
    try:
        for i in range(cap + 1):
            if cond is not None:
                v = ev.condition(cond, "loop").const_values()
                if v is not None and not v[0]:
                    return None
            if ev.dead():
                return None
            if i == cap:
                return f"{cap} iterations"
            ev.run_step(step, own)
            state = tuple(_state(ev, name) for name in sorted(names))
            if state in seen:
                return (f"its condition and step come back to values they had after {i + 1} "
                        "iteration(s), so it never ends")
            seen.add(state)
        return None
    finally:
        ev.loops.pop()
        for var, value in saved:
            var.value = value
        del ev.ctx.kills[kills:]


def _state(ev: Any, name: str) -> tuple:
    from effects.shaders.hlsl.loops import flat
    var = ev.lookup(name)
    return () if var is None else tuple(flat(var.value))


def _walk(tree: Any):
    """Every subtree of `tree`, with an explicit stack."""
    stack = [tree]
    while stack:
        t = stack.pop()
        if isinstance(t, lark.Tree):
            yield t
            stack.extend(c for c in t.children if isinstance(c, lark.Tree))


def _names(tree: Any) -> set[str]:
    return {str(t.children[0]) for t in _walk(tree) if t.data == "var"} if tree is not None \
        else set()


def _root(t: Any) -> str | None:
    """The variable an l-value (`a`, `a.b`, `a[i].x`) writes."""
    while isinstance(t, lark.Tree) and t.data in ("member", "index"):
        t = t.children[0]
    return str(t.children[0]) if isinstance(t, lark.Tree) and t.data == "var" else None


def _written(body: Any) -> set[str]:
    """The variables `body` may write: assignment and ++/-- targets, and every l-value passed
    to a call (an `out` or `inout` parameter)."""
    out: set[str] = set()
    for t in _walk(body):
        if t.data in _WRITES:
            target = t.children[1] if t.data == "pre_incdec" else t.children[0]
            out.add(_root(target) or "")
        elif t.data == "call" and t.children[1] is not None:
            out.update(name for a in t.children[1].children if (name := _root(a)) is not None)
    return out


def _may_end(body: Any) -> bool:
    return any(t.data in _ENDS_LOOP for t in _walk(body))
