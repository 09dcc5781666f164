"""Flow control in the generated code: where each node goes, and rep / if blocks emitted.

The DAG has `loop` nodes (loops.py: phis, initial values, results, a break predicate; c[aL + n]
reads, `uniform_al`, hang off the counter's phi, so they stay inside) and
`if` nodes (branches.py: condition operands, then-results, else-results). Each reached node
is placed in a *block*: the main program (None), a loop body ('loop', id), or a side of an
if ('then', id) / ('else', id); a block's parent is the block its loop / if node sits in.

Placement, from the last node to the first (a node's users come after it):
- a node goes to the innermost block holding all its uses: a use by an if's then-result
  counts as inside 'then' (so what only one side needs is computed only there, the point of
  a branch), a loop's result or break predicate as inside its body;
- then it is lifted out of every loop whose phis it does not depend on (loop-invariant code
  is computed once, before the loop; it stays inside the innermost loop it depends on), and in pixel shaders a gradient operation (texld,
  texldb, texldp, dsx, dsy) is lifted out of dynamic branches (gradients are undefined where
  neighbouring pixels diverge), its coordinates with it; one that depends on a loop with a
  break (which pixels leave apart) cannot leave it: X4014 at it. A discard (`kill`, held by
  the if / loop whose side or body made it) and an if / loop holding one are never lifted:
  a loop may run no iteration.
A block's nodes are emitted in creation order, which is topological; a nested block is
emitted where its loop / if node is.
"""
from __future__ import annotations

from typing import Any

from effects.shaders.asm.versions import IDENTITY
from effects.shaders.asm.program import Operand as Register
from effects.shaders.hlsl.dag import Node, Operand, reachable
from effects.shaders.hlsl.parse import HlslError
from effects.shaders.hlsl.records import fix, fixed, read, reg

Label = tuple | None
_GRADIENT = {"tex", "texldp", "texldb", "dsx", "dsy"}


def needed(roots: list[Node]) -> list[Node]:
    """dag.reachable, less the dead carried groups of loops where there are loops."""
    nodes = reachable(roots)
    return live_nodes(roots) if any(n.op == "loop" for n in nodes) else nodes


def live_nodes(roots: list[Node]) -> list[Node]:
    """What the roots need, in creation order, without a loop's dead carried groups: a group
    (phi, initial value, result, loop_out) is kept only where something kept reads its
    loop_out or its phi, a c[aL + n] read (`uniform_al`, whose phi argument only ties it to
    the loop) aside. So a counter that only indexes through aL is not carried; its phi stays
    as the read's anchor. Loops' `live` attribute: the kept group numbers."""
    seen: dict[int, Node] = {}
    groups: dict[int, set[int]] = {}          # loop id -> live groups
    loops: dict[int, Node] = {}               # loop id -> its (live) loop node
    anchors: list[Node] = []
    stack = list(roots)

    def group(loop_id: int, k: int) -> None:
        live = groups.setdefault(loop_id, set())
        if k not in live:
            live.add(k)
            if loop_id in loops:
                _push_group(loops[loop_id], k)

    def _push_group(loop: Node, k: int) -> None:
        count = loop.key[2]
        stack.extend((loop.args[k].node, loop.args[count + k].node))

    while stack:
        n = stack.pop()
        if n.id in seen:
            continue
        seen[n.id] = n
        op = n.op
        if op == "loop":
            loops[n.key[0]] = n
            count = n.key[2]
            stack.extend(a.node for a in n.args[2 * count:])          # the break predicate
            for k in groups.get(n.key[0], ()):
                _push_group(n, k)
        elif op == "phi":
            group(*n.key)
        elif op == "loop_out":
            stack.append(n.args[0].node)
            group(*n.key)
        elif op == "uniform_al":
            anchors.extend(a.node for a in n.args)
        else:
            stack.extend(a.node for a in n.args)
    for n in anchors:
        seen.setdefault(n.id, n)
    for loop_id, n in loops.items():
        n.live = frozenset(groups.get(loop_id, ()))
    return sorted(seen.values(), key=lambda n: n.id)


def _slot_label(c: Node, k: int, labels: dict[int, Label]) -> Label:
    if c.op == "loop":
        return labels[c.id] if k < c.key[2] else ("loop", c.key[0])
    if c.op == "if":
        ncond, groups, then_kills = c.key[2], c.key[3], c.key[5]
        if k < ncond:
            return labels[c.id]
        k -= ncond
        then = k < groups or 2 * groups <= k < 2 * groups + then_kills
        return ("then", c.key[0]) if then else ("else", c.key[0])
    return labels[c.id]


def place(cg: Any, nodes: list[Node]) -> dict[Label, list[Node]]:
    """Each node's block (see the module note); the blocks' nodes in creation order."""
    if not any(n.op in ("loop", "if") for n in nodes):
        # straight-line code: every node is in the program's own block
        cg.loop_phis = {}
        for n in nodes:
            n.block = None
        return {None: list(nodes)} if nodes else {}
    deps: dict[int, frozenset] = {}
    empty: frozenset = frozenset()
    for n in nodes:
        if n.op == "phi":
            deps[n.id] = frozenset({n.key[0]})
            continue
        # most nodes depend on no loop: no set is built for them (a union per node was a
        # tenth of a 150-line function's compile time)
        d = empty
        for a in n.args:
            x = deps.get(a.node.id)
            if x:
                d = x if not d else d | x
        deps[n.id] = d - {n.key[0]} if n.op == "loop" else d
    users: dict[int, list[tuple[Node, int]]] = {}
    for n in nodes:
        for k, a in enumerate(n.args):
            users.setdefault(a.node.id, []).append((n, k))
    roots = {c.node.id for o in cg.outputs for c in o.comps} | {k.node.id for k in cg.ctx.kills}
    parent: dict[Label, Label] = {}
    dynamic: set[Label] = set()
    labels: dict[int, Label] = {}

    def chain(label: Label) -> list[Label]:
        out = [label]
        while label is not None:
            label = parent[label]
            out.append(label)
        return out

    lift_gradients = cg.target.kind == "ps"
    for n in reversed(nodes):
        uses = [None] if n.id in roots else []
        uses += [_slot_label(c, k, labels) for c, k in users.get(n.id, [])]
        if n.op == "phi":
            label: Label = ("loop", n.key[0])
        else:
            common = chain(uses[0]) if uses else [None]
            for u in uses[1:]:
                seen = set(chain(u))
                common = [x for x in common if x in seen]
            label = common[0]
            # from the outermost block in, past the innermost loop it depends on (it stays
            # inside that one): out of the first loop it does not depend on
            outer_first = list(reversed(chain(label)[:-1]))
            start = max((i + 1 for i, x in enumerate(outer_first)
                         if x[0] == "loop" and x[1] in deps[n.id]), default=0)
            # a discard (or a block holding one) stays where it is: a loop may run 0 times
            effect = n.op == "kill" or n.effect
            for x in outer_first[start:]:
                if x[0] == "loop" and not effect or \
                        lift_gradients and n.op in _GRADIENT and x in dynamic:
                    label = parent[x]
                    break
        labels[n.id] = label
        n.block = label
        if lift_gradients and n.op in _GRADIENT and any(x in dynamic for x in chain(label)[:-1]):
            # it reads the loop's values, so it cannot leave the loop, whose pixels diverge
            raise HlslError("X4014: cannot have gradient operations inside loops with "
                            "divergent flow control (a break the pixels take apart; compute "
                            "it before the loop, or use tex2Dlod / tex2Dgrad)", n.location)
        if n.op == "loop":
            parent[("loop", n.key[0])] = label
            if n.key[3]:
                dynamic.add(("loop", n.key[0]))
        elif n.op == "if":
            parent[("then", n.key[0])] = parent[("else", n.key[0])] = label
            if n.key[1] != "bool":
                dynamic.update({("then", n.key[0]), ("else", n.key[0])})
    blocks: dict[Label, list[Node]] = {}
    cg.loop_phis = {}
    for n in nodes:
        blocks.setdefault(labels[n.id], []).append(n)
        if n.op == "phi":
            cg.loop_phis.setdefault(n.key[0], {})[n.key[1]] = n
    return blocks


def emit_kill(cg: Any, n: Node) -> None:
    """texkill of a discard's operand (its four lanes, the last repeated)."""
    src_op = n.args[0]
    temp = cg.temp()
    width = src_op.width
    src = cg.place(src_op, [min(i, width - 1) for i in range(4)])
    if src.lanes is not None:
        src.lanes = {i: src.lanes.get(min(i, width - 1), 0) for i in range(4)}
    cg.emit("mov", temp, (0, 1, 2, 3), [src], n.location)
    cg.emit("texkill", None, (), [fixed(temp, IDENTITY)], n.location)


def emit_block(cg: Any, label: Label) -> None:
    for n in cg.blocks.get(label, []):
        cg.node(n)


def _scalar(cg: Any, op: Operand) -> Register:
    src = cg.place(op, [0])
    if src.lanes is not None:
        fix(src, (src.lanes[0],) * 4)
    return src


def emit_loop(cg: Any, n: Node) -> None:
    """`rep i#` (`loop aL, i#` where the body reads c[aL + n]): the carried registers take
    the initial values, the body, the results moved back (staged when read from a carried
    register, so a swap holds), a break, `endrep` / `endloop`."""
    loop_id, register, count, has_break, uses_al = n.key
    phis = cg.loop_phis.get(loop_id, {})
    inits, results = n.args[:count], n.args[count:2 * count]
    live = range(count) if n.live is None else n.live   # live_nodes: the groups kept
    carried: list[Register] = []
    for k in range(count):
        home = cg.temp()
        carried.append(home)
        if k not in live:
            continue
        if k in phis:
            cg.home[phis[k].id] = (home, {c: c for c in range(phis[k].width)})
        cg._move(home, inits[k], n.location)
    cg.loop_regs[loop_id] = carried
    cg.a0 = None                          # the body may load a0 itself
    count_src = fixed(reg("i", register), IDENTITY)
    if uses_al:
        cg.emit("loop", None, (), [fixed(reg("aL"), IDENTITY), count_src],
                n.location)
    else:
        cg.emit("rep", None, (), [count_src], n.location)
    emit_block(cg, ("loop", loop_id))
    staged: list[Operand | Register | None] = []
    for k, res in enumerate(results):
        if k not in live:
            staged.append(None)
            continue
        home = cg.home.get(res.node.id)
        if res.node.op != "const" and home is not None and any(home[0] is c for c in carried):
            tmp = cg.temp()
            cg._move(tmp, res, n.location)
            staged.append(tmp)
        else:
            staged.append(res)
    for home, res, width in zip(carried, staged, [r.width for r in results]):
        if res is None:
            continue
        if isinstance(res, Register):
            cg.emit("mov", home, tuple(range(width)), [read(res, {c: c for c in range(width)})],
                    n.location)
        else:
            cg._move(home, res, n.location)
    if has_break:
        cg.emit("break_ne", None, (), [_scalar(cg, n.args[2 * count]),
                                       cg.const_src([0.0])], n.location)
    cg.a0 = None
    cg.emit("endloop" if uses_al else "endrep", None, (), [], n.location)


def emit_if(cg: Any, n: Node) -> None:
    """`if b#` or `if_<cmp> a, b`; each side's nodes, its results moved into the registers
    the `if_out` nodes read; `else` only where the else side computes something (otherwise
    its results, computed before, are moved in before the `if`)."""
    if_id, test, ncond, groups, breg, _ = n.key
    conds = n.args[:ncond]
    then_res, else_res = n.args[ncond:ncond + groups], n.args[ncond + groups:ncond + 2 * groups]
    regs = [cg.temp() for _ in range(groups)]
    cg.if_regs[if_id] = regs
    before = not cg.blocks.get(("else", if_id))
    if before:
        for home, res in zip(regs, else_res):
            cg._move(home, res, n.location)
    if test == "bool":
        cg.emit("if", None, (), [fixed(reg("b", breg), IDENTITY)], n.location)
    else:
        cg.emit(f"if_{test}", None, (), [_scalar(cg, c) for c in conds], n.location)
    cg.a0 = None
    emit_block(cg, ("then", if_id))
    for home, res in zip(regs, then_res):
        cg._move(home, res, n.location)
    if not before:
        cg.emit("else", None, (), [], n.location)
        cg.a0 = None
        emit_block(cg, ("else", if_id))
        for home, res in zip(regs, else_res):
            cg._move(home, res, n.location)
    cg.emit("endif", None, (), [], n.location)
    cg.a0 = None


__all__ = ["needed", "live_nodes", "place", "emit_block", "emit_kill", "emit_loop", "emit_if"]
