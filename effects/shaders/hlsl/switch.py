"""`switch`, as fxc compiled it for Direct3D 9 targets, which have no switch instruction: one
flattened `if` per case, the selector compared with each case's values (selects, or constant
folding where the selector is known).

What fxc accepted (the rules vkd3d's tests/hlsl/switch.shader_test checks against native
d3dcompiler for shader models below 4): an integer scalar selector (a float one is refused);
case values that are constant expressions of literals (`1+1`, `2.1f` as 2), none twice and one
`default` at most, anywhere; cases fall through only when empty (`case 0: case 1: ...`), so
every case that has statements ends in `break` or `return` on every path, else X3533 at its
first label (`if (true) break;` ends it, as fxc folded it); `break` leaves the switch;
`continue` directly in a switch is refused; an empty switch is refused. The checks run before
anything is evaluated, so a broken switch is refused whatever its selector.

A once-through `Loop` (values.Loop with `switch`) carries the `break`s: the statements after a
break in a case run under its predicate, as in a loop. The cases' values are distinct, so at
most one case runs for a pixel and each case starts with no break taken.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import lark

from effects.shaders.hlsl.values import Loop

NO_CODE = "(no X code: fxc's wording for this was not found)"
# what a case value may be made of: literals and operators (fxc refuses `1+a` for a local `a`)
_LITERAL_TREES = frozenset({"int_lit", "float_lit", "bool_lit", "binary", "prefix", "cast",
                            "builtin_type", "ternary"})


@dataclass
class _Case:
    """A run of labels and the statements after them."""

    first: Any                                   # its first label's tree (where errors point)
    values: list[int] = field(default_factory=list)
    default: bool = False
    statements: list[Any] = field(default_factory=list)


def switch_statement(ev: Any, tree: lark.Tree) -> None:
    _attrs, _keyword, selector_tree, *items = tree.children
    cases = _cases(ev, items, tree)
    selector = _selector(ev, selector_tree)
    loc = ev.at(tree)
    labelled = [ev.a.compare("==", [selector], [ev.g.const((float(k),))], loc)[0]
                for case in cases for k in case.values]
    unmatched = ev._not(_any(ev, labelled))
    loop = Loop(switch=True)
    saved = ev.mask
    ev.loops.append(loop)
    ev.scopes.append({})              # the body is one scope, as C's
    try:
        k = 0
        for case in cases:
            matches = labelled[k:k + len(case.values)]
            k += len(case.values)
            cond = _any(ev, matches + ([unmatched] if case.default else []))
            known = cond.const_values()
            if known is not None and not known[0]:
                continue
            loop.broken = None
            ev.mask = saved if known is not None else ev._and(saved, cond)
            for stmt in case.statements:
                if ev.dead():
                    break
                ev.stmt(stmt)
    finally:
        ev.scopes.pop()
        ev.loops.pop()
        ev.mask = saved


def _any(ev: Any, conds: list[Any]) -> Any:
    """1 where any of the 0/1 `conds` is (0 for none)."""
    out = ev.g.const((0.0,))
    for c in conds:
        out = c if out.const_values() == (0.0,) else ev._or(out, c)
    return out


def _selector(ev: Any, tree: Any) -> Any:
    v = ev.expr(tree)
    if not v.type.numeric or v.type.size != 1 or v.type.base not in ("int", "uint"):
        raise ev.error(f"X3020: a switch needs a scalar int or uint selector, not '{v.type}'",
                       tree)
    return v.comps[0]


def _cases(ev: Any, items: list[Any], tree: Any) -> list[_Case]:
    """The body's labels and statements as cases, checked as fxc checked them."""
    cases: list[_Case] = []
    seen: dict[int, Any] = {}
    default_at = None
    for item in items:
        kind = item.data if isinstance(item, lark.Tree) else None
        if kind in ("case_label", "default_label"):
            if not cases or cases[-1].statements:
                cases.append(_Case(item))
            case = cases[-1]
            if kind == "default_label":
                if default_at is not None:
                    raise ev.error(f"a switch has one default label (the first is at line "
                                   f"{ev.at(default_at).line}) {NO_CODE}", item, language=True)
                default_at, case.default = item, True
                continue
            value = _case_value(ev, item.children[1])
            if value in seen:
                raise ev.error(f"duplicate case value {value} (first at line "
                               f"{ev.at(seen[value]).line}) {NO_CODE}", item, language=True)
            seen[value] = item
            case.values.append(value)
        elif not cases:
            raise ev.error(f"a statement in a switch before its first case label {NO_CODE}",
                           item, language=True)
        else:
            cases[-1].statements.append(item)
    if not cases:
        raise ev.error(f"a switch needs at least one case label {NO_CODE}", tree, language=True)
    for case in cases:
        if not case.statements:      # only the last can be empty: the others fell through
            raise ev.error(f"the last case of a switch has no statements; end it with break "
                           f"{NO_CODE}", case.first, language=True)
        if not any(_ends(ev, s) for s in case.statements):
            raise ev.error("X3533: non-empty case statements must have break or return",
                           case.first)
    return cases


def _case_value(ev: Any, tree: Any) -> int:
    """A case's value: a constant expression of literals, as the selector's integer."""
    parts = [tree, *tree.iter_subtrees()] if isinstance(tree, lark.Tree) else [tree]
    values = None
    if all(not isinstance(p, lark.Tree) or p.data in _LITERAL_TREES for p in parts):
        values = ev.expr(tree).const_values()
    if values is None:
        raise ev.error(f"a case value must be a literal expression {NO_CODE}", tree,
                       language=True)
    return int(values[0])       # toward zero, as a float literal converts to int


def _ends(ev: Any, stmt: Any) -> bool:
    """Whether every path through `stmt` ends in a break or return: what fxc asked of a case
    (its condition folded: `if (true) break;` ends, `if (false) break;` does not)."""
    if not isinstance(stmt, lark.Tree):
        return False
    kind = stmt.data
    if kind in ("break_stmt", "return_stmt"):
        return True
    if kind == "block":             # what follows an ending statement is never reached
        return any(_ends(ev, s) for s in stmt.children)
    if kind in ("if_stmt", "if_else"):
        cond = _literal_truth(ev, stmt.children[2])
        then = _ends(ev, stmt.children[3])
        other = _ends(ev, stmt.children[5]) if kind == "if_else" else False
        if cond is None:
            return then and other
        return then if cond else other
    return False


def _literal_truth(ev: Any, tree: Any) -> bool | None:
    """A condition's truth where it is a literal (`true`, `1`), None otherwise."""
    if isinstance(tree, lark.Tree) and tree.data in ("bool_lit", "int_lit", "float_lit"):
        values = ev.expr(tree).const_values()
        return bool(values[0]) if values is not None else None
    return None
