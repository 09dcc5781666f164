"""A value folded "in the lanes still running a loop": the DAG below an operand evaluated with
the predicates of the lanes that left (a loop's 'broken', a function's 'returned') taken as 0.

An unrolled loop ends when its condition is a constant false. After a run-time `break`
(`while (i < 4) { if (x) break; i++; }`) the counter is a select between the lanes that broke
and the ones still counting, not a constant; where no lane broke it is 1, 2, 3, 4 as fxc
counted it, and the loop ends there for every lane still in it (the others already left).
"""
from __future__ import annotations

from typing import Any

from effects.shaders.hlsl.folding import FOLDS, fold


# nodes one question may walk that earlier ones did not: an unrolled loop asks once an
# iteration, so a condition over a large DAG is given up on (the loop runs on as before)
# instead of walking it a thousand times
MAX_NEW_NODES = 512


def fold_assuming_zero(root: Any, zero: dict[int, set[int]],
                       known: dict[int, tuple[float, ...]] | None = None) -> tuple[float, ...] | None:
    """The lanes of Operand `root` when the node lanes in `zero` (node id -> lanes) are 0,
    folded through the ops folding.py knows (a `pack` gathers its arguments); None when a
    lane depends on anything else (an input, a uniform, a texture read). The DAG is walked
    with an explicit stack, each node once; `known` keeps the nodes found constant for the
    next question about the same loop (more zeros later change no constant: a constant
    depends on no unknown lane), and a question walking over MAX_NEW_NODES others is None."""
    known = {} if known is None else known
    memo: dict[int, tuple[float | None, ...]] = dict(known)
    stack = [root.node]
    walked = 0
    while stack:
        n = stack[-1]
        if n.id in memo:
            stack.pop()
            continue
        if n.value is None and (n.op in FOLDS or n.op == "pack"):
            waiting = [a.node for a in n.args if a.node.id not in memo]
            if waiting:
                stack.extend(waiting)
                continue
        stack.pop()
        walked += 1
        if walked > MAX_NEW_NODES:
            return None
        lanes = _lanes(n, memo, zero.get(n.id, ()))
        memo[n.id] = lanes
        if None not in lanes:
            known[n.id] = lanes       # type: ignore[assignment]
    return _pick(root, memo[root.node.id])


def _pick(op: Any, lanes: tuple[float | None, ...]) -> tuple[float, ...] | None:
    out = [lanes[i] if i < len(lanes) else None for i in op.swizzle]
    if any(x is None for x in out):
        return None
    return tuple(-x if op.negate else x for x in out)   # type: ignore[operator]


def _lanes(n: Any, memo: dict[int, tuple[float | None, ...]], zeros: Any) -> tuple[float | None, ...]:
    if n.value is not None:
        lanes: list[float | None] = list(n.value)
    elif n.op == "pack":
        lanes = []
        for a in n.args:
            got = _pick(a, memo[a.node.id])
            lanes.extend(got if got is not None else [None] * a.width)
    elif n.op in FOLDS:
        args = [_pick(a, memo[a.node.id]) for a in n.args]
        lanes = list(fold(n.op, args, n.width)) if all(a is not None for a in args) \
            else [None] * n.width
    else:
        lanes = [None] * max(n.width, 1)
    for k in zeros:
        if k < len(lanes):
            lanes[k] = 0.0
    return tuple(lanes)
