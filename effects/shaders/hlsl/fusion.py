"""Rewrites of the DAG before code generation: several nodes that one instruction computes.

- `fuse_mad`: `add(mul(a, b), c)`, the mul read nowhere else, is `mad(a, b, c)`;
- `fuse_lrp`: `x*(1 - a) + y*a` and `x + (y - x)*a`, written out by hand, are `lrp(a, y, x)`
  where the target has lrp (ps_2_0 and up, vs_2_0 and up: fxc's listings show it; one
  instruction for the three, issue 31);
- `share_lit_diffuse`: `max(n.l, 0)` beside a `lit` of the same n.l is the lit's .y (lit()
  builds both, so the diffuse term alone costs one max);
- `pack_scalars`: one-lane nodes of one op over lanes of the same nodes become one vector
  node (`mul r0.xy`).

Each takes the nodes the outputs reach (creation order, so arguments first) and `uses`
(node id -> readers, outputs and discards counted), rewrites nodes in place and returns how
many it rewrote.
"""
from __future__ import annotations

import itertools
from typing import Any, Callable

from effects.shaders.hlsl.dag import Node, Operand
from effects.shaders.hlsl.ops import LANEWISE, OPAQUE


def fuse_mad(nodes: list[Node], uses: dict[int, int]) -> int:
    done = 0
    for n in nodes:
        if n.op != "add":
            continue
        for k in (0, 1):
            m = n.args[k]
            if m.node.op == "mul" and uses.get(m.node.id) == 1 and m.node.width >= m.width:
                a, b = m.node.args
                a2, b2 = a.pick(m.swizzle), b.pick(m.swizzle)
                if m.negate:
                    a2 = a2.neg()
                n.op, n.args = "mad", (a2, b2, n.args[1 - k])
                uses[m.node.id] = 0
                done += 1
                break
    return done


def _lanes(o: Operand) -> tuple[Operand, ...] | None:
    """The arguments of the lanewise node `o` reads, seen through o's swizzle (None where an
    argument is narrower than its node: a broadcast)."""
    if any(a.width != o.node.width for a in o.node.args):
        return None
    return tuple(a.pick(o.swizzle) for a in o.node.args)


def _one_minus(o: Operand) -> Operand | None:
    """`a` where `o` reads `1 - a` (an add of a constant 1 and a negated operand)."""
    if o.node.op != "add" or o.negate:
        return None
    args = _lanes(o)
    if args is None:
        return None
    for k in (0, 1):
        c = args[k].const_values()
        if c is not None and all(v == 1.0 for v in c) and args[1 - k].node.op != "const":
            return args[1 - k].neg()
    return None


def _factors(o: Operand, uses: dict[int, int]) -> tuple[Operand, Operand] | None:
    """The two factors of a mul read only here, through o's swizzle and sign."""
    if o.node.op != "mul" or uses.get(o.node.id) != 1:
        return None
    args = _lanes(o)
    if args is None:
        return None
    a, b = args
    return (a.neg(), b) if o.negate else (a, b)


def _difference(o: Operand, uses: dict[int, int]) -> tuple[Operand, Operand] | None:
    """(y, x) where `o` reads `y - x`, an add read only here."""
    if o.node.op != "add" or uses.get(o.node.id) != 1 or o.negate:
        return None
    args = _lanes(o)
    if args is None:
        return None
    p, q = args
    return (p, q.neg())


def _match(n: Node, uses: dict[int, int]) -> tuple[Operand, Operand, Operand] | None:
    """(a, y, x) where the add `n` computes lerp(x, y, a) written out."""
    for first, second in ((n.args[0], n.args[1]), (n.args[1], n.args[0])):
        if first.width != n.width or second.width != n.width:
            return None
        # x*(1 - a) + y*a
        fx, fy = _factors(first, uses), _factors(second, uses)
        if fx is not None and fy is not None:
            for x, w in (fx, fx[::-1]):
                a = _one_minus(w)
                if a is None:
                    continue
                for y, a2 in (fy, fy[::-1]):
                    if a2.sig() == a.sig():
                        return a, y, x
        # x + (y - x)*a
        fd = _factors(second, uses)
        if fd is not None:
            for d, a in (fd, fd[::-1]):
                yx = _difference(d, uses)
                if yx is not None and yx[1].sig() == first.sig():
                    return a, yx[0], first
    return None


def fuse_lrp(nodes: list[Node], uses: dict[int, int]) -> int:
    done = 0
    for n in nodes:
        if n.op != "add":
            continue
        found = _match(n, uses)
        if found is None:
            continue
        for arg in n.args:               # the muls (and a difference) now read by nobody
            uses[arg.node.id] = uses.get(arg.node.id, 1) - 1
        n.op, n.args = "lrp", found
        done += 1
    return done


def _lane(o: Operand, i: int) -> Operand:
    """Lane i of `o` as a one-lane operand of the node that makes it (through a pack)."""
    if o.node.op == "pack":
        c = o.node.args[o.swizzle[i]]
        return c.neg() if o.negate else c
    return Operand(o.node, (o.swizzle[i],), o.negate)


def share_lit_diffuse(nodes: list[Node], roots: list[list[Operand]]) -> int:
    """Readers of `max(x, 0)` read `lit(x, ...).y` instead where both are reached: the lit's
    .y is that max (the lit page: dest.y = src.x > 0 ? src.x : 0). `roots`: the outputs' and
    discards' operand lists, rewritten in place like the nodes' arguments."""
    lits = {_lane(n.args[0], 0).sig(): n for n in nodes if n.op == "lit"}
    if not lits:
        return 0
    swap: dict[int, tuple[Node, int]] = {}
    for n in nodes:
        if n.op != "max" or n.width != 1:
            continue
        for k in (0, 1):
            c = n.args[1 - k].const_values()
            lit = lits.get(n.args[k].sig())
            if lit is not None and c is not None and all(v == 0.0 for v in c):
                swap[n.id] = (lit, 1)
                break
    return _redirect(nodes, roots, swap)


def _redirect(nodes: list[Node], roots: list[list[Operand]],
              swap: dict[int, tuple[Node, int]]) -> int:
    """Readers of each node in `swap` read lane `i` of its `(node, i)` instead, in the nodes'
    arguments and the `roots`; returns how many nodes were replaced."""
    if not swap:
        return 0

    def read(o: Operand) -> Operand:
        hit = swap.get(o.node.id)
        return o if hit is None else Operand(hit[0], (hit[1],) * o.width, o.negate)

    for n in nodes:
        if any(a.node.id in swap for a in n.args):
            n.args = tuple(read(a) for a in n.args)
    for comps in roots:
        comps[:] = [read(c) for c in comps]
    return len(swap)


def pack_scalars(nodes: list[Node], roots: list[list[Operand]],
                 swizzle_ok: Callable[[dict[int, int]], bool]) -> int:
    """One-lane component-wise nodes of one op whose arguments are lanes of the same nodes
    (or constants), `mul(a.x, 3)` and `mul(a.y, 3)`, become one vector node, `mul(a.xy, 3)`,
    whose lanes their readers read (fxc's `mul r0.xy` before `mova a0.xy`; issue 31's
    swizzle-aware packing). Up to four a node; the node made first takes the others' place,
    so every reader still comes after it. Constants that differ between the members become
    one vector constant: `x - 1`, `x - 2`, `x - 3` are `add r0.xyz, x, c(-1, -2, -3)` and
    `k < x` for seven k two `slt` (fxc's listings, Effekseer's blend-type tests and
    dxwrapper's texCount). Repeated while it packs, so that the readers of packed lanes
    (`abs` of each difference) pack too. Code without flow control only (a node's block
    follows its readers there: flowcode.place). `swizzle_ok`: whether the target reads a
    source with that lane map (ps_2_0's fixed swizzles). `roots` as in share_lit_diffuse."""
    done = 0
    while True:
        swap = _pack_once(nodes, swizzle_ok)
        if not swap:
            return done
        done += _redirect(nodes, roots, swap)
        nodes = [n for n in nodes if n.id not in swap]


# ids of the vector constants pack_scalars makes: below every Graph node's (creation order
# puts them before their readers; code generation places a constant by its values)
_const_ids = itertools.count(-1, -1)


def _pack_once(nodes: list[Node], swizzle_ok: Callable[[dict[int, int]], bool]
               ) -> dict[int, tuple[Node, int]]:
    groups: dict[tuple, list[Node]] = {}
    for n in nodes:
        if n.width != 1 or n.op not in LANEWISE or n.op in OPAQUE or n.coalesced:
            continue
        key: list[Any] = [n.op]
        for a in n.args:
            if a.width != 1:
                break
            key.append("const" if a.node.op == "const" else (a.node.id, a.negate))
        else:
            if any(k != "const" for k in key[1:]):     # something to compute
                groups.setdefault(tuple(key), []).append(n)
    swap: dict[int, tuple[Node, int]] = {}
    for members in groups.values():
        while len(members) > 1:
            chunk, members = members[:4], members[4:]
            if len(chunk) < 2:
                break
            first = chunk[0]
            args: list[Operand] = []
            for p, a in enumerate(first.args):
                if a.node.op == "const":
                    values = tuple(m.args[p].const_values()[0] for m in chunk)  # type: ignore[index]
                    if len(set(values)) == 1:   # read replicated
                        args.append(Operand(a.node, (a.swizzle[0],) * len(chunk), a.negate))
                    else:
                        made = Node("const", (), len(chunk), value=tuple(v + 0.0 for v in values),
                                    location=a.node.location, id=next(_const_ids))
                        args.append(Operand(made, tuple(range(len(chunk)))))
                    continue
                lanes = {i: m.args[p].swizzle[0] for i, m in enumerate(chunk)}
                if not swizzle_ok(lanes):
                    break
                args.append(Operand(a.node, tuple(lanes[i] for i in range(len(chunk))),
                                    a.negate))
            else:
                first.args, first.width = tuple(args), len(chunk)
                for i, m in enumerate(chunk[1:], 1):
                    swap[m.id] = (first, i)
    return swap
