"""What one HLSL evaluation may spend, checked as it grows (limits.py):

- `hlsl_nesting`: the levels the evaluator holds on Python's stack at once: a block, an `if`
  or a loop inside another (one level each), a call inside a call (two: its body's frames
  are twice a block's), an expression evaluated inside another's l-value or `out` argument
  (one). Expressions themselves take no level per operator (expressions.py evaluates them
  with an explicit stack), so a 5,000-term sum or a 1,000-deep nesting of parentheses,
  calls or casts is fine; a `{{{...}}}` 65 deep is a located error. Measured: at most ~5
  Python frames a level (a call: ~10 for its two), so the default 64 stays under ~450 of
  Python's 1,000 frames with the type recursions (two a level), room left for the caller.
- `hlsl_work`: the DAG nodes asked for (dag.Graph.work counts them) plus the components the
  evaluator copies or merges: unrolled iterations x inlined calls x components. Checked after
  every expression node and statement, so a runaway loop nest or call fan-out stops within
  one statement of the limit rather than after minutes or gigabytes. Each check also
  notes the count on limits.py's meter, so what a compile spent can be read (tests/hostile
  asserts work, not seconds).
"""
from __future__ import annotations

from typing import Any

from effects.base import limits
from effects.base.errors import Location
from effects.shaders.hlsl.parse import HlslError



def enter_level(ev: Any, where: Any, levels: int = 1) -> None:
    """`levels` more levels of nesting at `where` (the located error past hlsl_nesting)."""
    ctx = ev.ctx
    if ctx.nesting + levels > ctx.nesting_cap:
        raise ev.error(limits.message("hlsl_nesting", ctx.nesting + levels,
                                      "the HLSL nesting here (blocks, ifs, loops and calls "
                                      "inside one another)"), where)
    ctx.nesting += levels


def leave_level(ev: Any, levels: int = 1) -> None:
    ev.ctx.nesting -= levels


def spend(ev: Any, amount: int, where: Any) -> None:
    """Count `amount` steps of work (components copied or merged) and check the budget."""
    g = ev.ctx.graph
    g.work += amount
    limits.measure("hlsl_work", g.work)
    if g.work > ev.ctx.work_cap:
        raise over_budget(ev, where)


def check(ev: Any, where: Any) -> None:
    limits.measure("hlsl_work", ev.ctx.graph.work)
    if ev.ctx.graph.work > ev.ctx.work_cap:
        raise over_budget(ev, where)


class OverBudget(HlslError):
    """The evaluation ran out of hlsl_work (a loop that cannot unroll reports its own X3511)."""


def over_budget(ev: Any, where: Any) -> Exception:
    loc = ev.at(where)
    return OverBudget(limits.message(
        "hlsl_work", ev.ctx.graph.work,
        "evaluating this HLSL (unrolled loop iterations x inlined calls x components)"), loc,
        source_line=ev.origin.line_text(loc.line - ev.origin.base.line + 1))


def out_of_stack(where: Location, source_line: str | None = None) -> HlslError:
    """The located error for a RecursionError the nesting limit did not prevent (a caller
    already deep in Python's stack, or hlsl_nesting raised past what the stack holds)."""
    return HlslError(f"the HLSL nesting here ran out of Python's stack (limit hlsl_nesting: "
                     f"{limits.get('hlsl_nesting'):,} levels; a caller deep in its own stack "
                     "leaves fewer)", where, source_line=source_line)
