"""The compiler's middle: a hash-consed DAG of vector operations close to shader assembly.

Every node is one assembly-level operation (add, mul, mad, dp3, cmp, lrp, texld ...) on
operands that are (node, swizzle, negate): so source swizzles and negation are free, as in
the assembly, and the code generator turns each node into one instruction. Building a node
whose operands are all constants computes it instead (constant folding and propagation);
an identical node is built once (common subexpressions); code is generated only for what
the outputs reach (dead-code elimination). The front end has already inlined calls, unrolled
loops and turned `if` into selects, so the DAG has no control flow.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Iterable

from effects.base.errors import Location, UNKNOWN_LOCATION
from effects.shaders.hlsl.folding import FOLDS, fold as _fold
from effects.shaders.hlsl.ops import OPAQUE as _OPAQUE


@dataclass(eq=False)
class Node:
    op: str
    args: tuple["Operand", ...]
    width: int
    key: Any = None                  # leaves: ('input', sem) / ('uniform', name, row) / tex
    value: tuple[float, ...] | None = None      # constants
    location: Location = UNKNOWN_LOCATION       # the HLSL expression it comes from
    id: int = 0
    uses: int = field(default=0, repr=False)
    # Marks the later passes set: an if or loop that discards (branches, loops); the flow
    # block it is placed in and a loop's carried groups kept (flowcode); made in the register
    # of the instruction that reads it (codegen)
    effect: bool = field(default=False, repr=False)
    block: Any = field(default=None, repr=False)
    live: frozenset[int] | None = field(default=None, repr=False)
    coalesced: bool = field(default=False, repr=False)

    @property
    def is_const(self) -> bool:
        return self.op == "const"


def reachable(roots: Iterable[Node]) -> list[Node]:
    """Every node the roots depend on (themselves included), once each, in creation order."""
    seen: dict[int, Node] = {}
    stack = list(roots)
    while stack:
        n = stack.pop()
        if n.id in seen:
            continue
        seen[n.id] = n
        stack.extend(a.node for a in n.args)
    return sorted(seen.values(), key=lambda n: n.id)


@dataclass(frozen=True, eq=False)
class Operand:
    node: Node
    swizzle: tuple[int, ...]
    negate: bool = False

    @property
    def width(self) -> int:
        return len(self.swizzle)

    def sig(self) -> tuple:
        return (self.node.id, self.swizzle, self.negate)

    def const_values(self) -> tuple[float, ...] | None:
        if self.node.value is None:
            return None
        v = tuple(self.node.value[i] for i in self.swizzle)
        return tuple(-x for x in v) if self.negate else v

    def neg(self) -> "Operand":
        return Operand(self.node, self.swizzle, not self.negate)

    def pick(self, swizzle: tuple[int, ...]) -> "Operand":
        return Operand(self.node, tuple(self.swizzle[i] for i in swizzle), self.negate)


# Folding: folding.py, the IR's kernels (IEEE results, as the renderer computes them).
# op -> (argument widths or None, result width or None, fold function)
SHAPED = {op: spec for op, spec in FOLDS.items() if spec[1] is not None}
# Leaves, reads and side effects that never fold: the op table's (ops.py)
OPAQUE = _OPAQUE


_RANGES = [tuple(range(n)) for n in range(5)]


@dataclass
class Output:
    """An entry point's output: the register it is written to ('oPos' 'oC0' 'oT1' ...) and
    the operands that make its components."""
    register: str
    comps: list[Operand]
    location: Location = UNKNOWN_LOCATION


class Graph:
    """Builds nodes, folding constants and sharing identical ones."""

    def __init__(self) -> None:
        self.nodes: list[Node] = []
        self._index: dict[tuple, Node] = {}
        # nodes asked for (shared or not) and components copied: the compile's work so far,
        # which the evaluator holds to limits.py's hlsl_work (budget.py)
        self.work = 0
        # dag._prune's results: (node, condition, side, depth) -> the node on that side
        self.pruned: dict[tuple, Operand] = {}
        # (node, condition, side) -> the depth to which _prune found nothing to take there:
        # no shallower look finds anything either
        self.unpruned: dict[tuple, int] = {}

    def _new(self, node: Node, sig: tuple) -> Node:
        self.work += 1
        hit = self._index.get(sig)
        if hit is not None:
            return hit
        node.id = len(self.nodes)
        self.nodes.append(node)
        self._index[sig] = node
        return node

    def const(self, values: tuple[float, ...], location: Location = UNKNOWN_LOCATION) -> Operand:
        values = (float(values[0]) + 0.0,) if len(values) == 1 else \
            tuple(float(v) + 0.0 for v in values)   # -0.0 -> 0.0
        sig = ("const", values)
        node = self._index.get(sig)
        if node is None:
            node = Node("const", (), len(values), value=values, location=location)
        else:
            self.work += 1
            return Operand(node, _RANGES[len(values)] if len(values) < 5 else
                           tuple(range(len(values))))
        node = self._new(node, sig)
        return Operand(node, tuple(range(len(values))))

    def pack(self, comps: list[Operand]) -> Operand:
        """One operand holding `comps` (one lane each) as its lanes: a swizzle of one node
        when they share it, a constant when all are constants, otherwise a `pack` of them."""
        first = comps[0]
        node, negate = first.node, first.negate
        for c in comps:                     # (a loop, not all(...): asked per operator)
            if c.node is not node or c.negate != negate:
                break
        else:
            return Operand(node, tuple([c.swizzle[0] for c in comps]), negate)
        values = [c.const_values() for c in comps]
        if None not in values:
            return self.const(tuple([v[0] for v in values]))  # type: ignore[index]
        return self.leaf("pack", None, len(comps), args=tuple(comps))

    def leaf(self, op: str, key: Any, width: int, location: Location = UNKNOWN_LOCATION,
             args: tuple[Operand, ...] = ()) -> Operand:
        sig = (op, key, width, tuple(a.sig() for a in args))
        node = self._index.get(sig)
        if node is None:
            node = self._new(Node(op, args, width, key=key, location=location), sig)
        else:
            self.work += 1
        return Operand(node, tuple(range(width)))

    def op(self, op: str, args: list[Operand], width: int | None = None,
           location: Location = UNKNOWN_LOCATION) -> Operand:
        """The operand of `op(args)`, folded when every argument is a constant."""
        shaped = SHAPED.get(op)
        if width is None:
            width = shaped[1] if shaped else max(a.width for a in args)  # type: ignore[index]
        consts = [a.const_values() for a in args]
        if op not in OPAQUE and None not in consts:
            return self.const(tuple(fold(op, consts, width)), location)
        simplified = _simplify(self, op, args, consts)
        if simplified is not None:
            return simplified
        sig = (op, width, tuple([a.sig() for a in args]))
        node = self._index.get(sig)
        if node is None:
            node = self._new(Node(op, tuple(args), width, location=location), sig)
        else:
            self.work += 1
        return Operand(node, tuple(range(width)))


def complement_of(x: Operand) -> Operand | None:
    """The `p` that `x` is `1 - p` of (a predicate's `not`, as the evaluator builds it:
    add(1, -p)), or None."""
    n = x.node
    if x.negate or n.op != "add" or len(n.args) != 2 or n.args[0].const_values() != (1.0,):
        return None
    return n.args[1].neg()


def can_fold(op: str) -> bool:
    """Whether `fold` computes `op` (a preshader runs these on the host)."""
    return op not in OPAQUE and op in FOLDS


def host_computable(nodes: list[Node]) -> dict[int, bool]:
    """For each of `nodes` (in creation order, each node's arguments among them: `reachable`),
    whether it computes from uniforms and literals alone by ops `fold` computes: what a
    preshader can take to the host."""
    host: dict[int, bool] = {}
    for node in nodes:
        host[node.id] = node.op in ("const", "uniform") or (
            can_fold(node.op) and all(host[a.node.id] for a in node.args))
    return host


def fold(op: str, consts: list[Any], width: int) -> list[float]:
    """`op` on constant arguments (each its lanes after swizzle and negation)."""
    return _fold(op, consts, width)


def _all(values: tuple[float, ...] | None, x: float) -> bool:
    return values is not None and all(v == x for v in values)


def _simplify(g: Graph, op: str, args: list[Operand], consts: list[Any]) -> Operand | None:
    """x*1, x+0, x*0 and friends (fxc folds them too)."""
    if op == "mul":
        for a, b, cb in ((args[0], args[1], consts[1]), (args[1], args[0], consts[0])):
            if _all(cb, 1.0) and a.width >= b.width:
                return a
            if _all(cb, -1.0) and a.width >= b.width:
                return a.neg()
            if _all(cb, 0.0):
                return g.const((0.0,) * max(a.width, b.width))
    if op == "add":
        for a, b, cb in ((args[0], args[1], consts[1]), (args[1], args[0], consts[0])):
            if _all(cb, 0.0) and a.width >= b.width:
                return a
    if op == "mad":
        if _all(consts[2], 0.0):
            return g.op("mul", args[:2])
        if _all(consts[0], 0.0) or _all(consts[1], 0.0):
            return args[2] if args[2].width >= max(args[0].width, args[1].width) else None
        if _all(consts[1], 1.0) and args[0].width == args[2].width:
            return g.op("add", [args[0], args[2]])
    if op == "mov":
        return args[0]
    if op == "rcp" and args[0].node.op == "rcp" and not args[0].negate:
        return args[0].node.args[0]
    if op == "lrp" and consts[0] is not None:
        if _all(consts[0], 1.0):
            return args[1]
        if _all(consts[0], 0.0):
            return args[2]
    if op in ("cmp", "cnd") and args[1].sig() == args[2].sig():
        return args[1]
    if op == "cmp" and _scalar(args[0]):
        d = Operand(args[0].node, args[0].swizzle[:1], args[0].negate)
        a = _prune(g, args[1], d, 1, _PRUNE_DEPTH)
        b = _prune(g, args[2], d, 2, _PRUNE_DEPTH)
        if a.sig() != args[1].sig() or b.sig() != args[2].sig():
            return g.op("cmp", [args[0], a, b])
    return None


# how deep _prune looks into a select's side: a chain of flattened returns or else-ifs,
# and the arithmetic a side does on the value before it, reach the same test again within
# this; bounded so that a select costs bounded work
_PRUNE_DEPTH = 6


def _scalar(x: Operand) -> bool:
    """Whether every lane of `x` is the same component (a scalar condition, replicated)."""
    return all(i == x.swizzle[0] for i in x.swizzle)


def _prune(g: Graph, x: Operand, d: Operand, side: int, depth: int) -> Operand:
    """`x` as cmp(d, ...) sees it on its side `side` (1: d >= 0, 2: d < 0), for a scalar `d`:
    a cmp on the same `d` inside it takes that side too, through the arithmetic between.
    A flattened `if (p) return a; if (q) return b;` reselects on p under p, and an else side
    computes from the value the then side stored under p (Effekseer's ApplyTextureBlending:
    fxc's one cmp per level). Not through gradients or texture reads (their neighbours may
    take the other side), nor leaves other than a pack of components."""
    node = x.node
    if depth == 0 or (node.op in OPAQUE and node.op != "pack") or not node.args:
        return x
    plain = (node.id, d.sig(), side)
    if g.unpruned.get(plain, 0) >= depth:
        return x
    key = plain + (depth,)
    done = g.pruned.get(key)
    if done is None:
        test = node.args[0]
        if node.op == "cmp" and test.node is d.node and test.negate == d.negate and \
                all(i == d.swizzle[0] for i in test.swizzle):
            done = _prune(g, node.args[side], d, side, depth - 1)
        else:
            args = [_prune(g, a, d, side, depth - 1) for a in node.args]
            if all(a.sig() == b.sig() for a, b in zip(args, node.args)):
                done = Operand(node, tuple(range(node.width)))
            elif node.op == "pack":           # a value put together from components
                done = g.pack(args)
            else:
                done = g.op(node.op, args, node.width, node.location)
        g.pruned[key] = done
    if done.node is node:
        g.unpruned[plain] = max(g.unpruned.get(plain, 0), depth)
        return x
    out = done.pick(x.swizzle)
    return out.neg() if x.negate else out
