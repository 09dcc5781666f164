"""Write-mask liveness: for every node of the DAG, the components some reader reads.

fxc wrote only the lanes a later instruction reads (`add r0.xy` where `.x` and `.y` are read,
`mul r0.x` where only `.x` is): a narrower write mask costs nothing, and what it leaves out
can save slots. A component-wise source needs only the lanes its instruction writes, so a
ps_2_0 swizzle the version refuses over four lanes may be legal over one (no copy to move it
into place); a vector assembled from pieces (`pack`) needs no `mov` for a lane nobody reads,
and a node whose every lane is unread is not computed at all. The code generator asks
`LiveLanes.of(node)` where it builds a write mask (codegen.py: component-wise instructions
and packs); the rest of the generation is as before.

The pass walks the nodes from the outputs back (the list is in topological order): a node's
live components decide, by its shape in the op table (ops.py), which lanes of each argument
it reads:
- `lanes` (add, mul, mad, cmp, lrp ...): instruction lane c reads argument lane c, through
  the operand's swizzle;
- `scalar` (rcp, rsq, exp, log, pow): the one component its operand names;
- `reduce` (dp3, dp4, dp2add): the first `reads` lanes of its two vectors (dp2add's third
  source one component), whatever of its result is read;
- `pack`: argument i where lane i of the vector is read;
- everything else (texture reads, shaped macros such as nrm, crs and lit, relative reads,
  flow): every lane its operands name, as the instruction reads whole registers.
Code with real flow control (`loop`, `if`: values carried between blocks) is left as it was:
`analyse` answers None and every lane counts as live.
"""
from __future__ import annotations

from dataclasses import dataclass

from effects.shaders.hlsl.dag import Node, Operand
from effects.shaders.hlsl.ops import OPS, REDUCE

# ops whose blocks carry values the walk below does not follow (flowcode.py)
_FLOW = frozenset({"loop", "if", "loop_out", "if_out", "phi"})


@dataclass(frozen=True)
class LiveLanes:
    """The live components of each node, by node id."""

    lanes: dict[int, frozenset[int]]

    def of(self, node: Node) -> frozenset[int]:
        """The components of `node` some reader reads (none: nothing reads it)."""
        return self.lanes.get(node.id, frozenset())

    def keeps(self, node: Node, component: int) -> bool:
        return component in self.lanes.get(node.id, ())


# how each shape's arguments are read (the op table's shapes; anything else reads whole
# registers): "lanes" through the live lanes, "pack" its own lane, "scalar" one component,
# "reduce" the first `reads` lanes of its vectors
_BY_LANE, _BY_INDEX, _ONE, _FIRST, _WHOLE = range(5)
_HOW = {name: {"lanes": _BY_LANE, "scalar": _ONE, "reduce": _FIRST}.get(row.shape, _WHOLE)
        for name, row in OPS.items()}
_HOW["pack"] = _BY_INDEX


def _read(node: Node, live: set[int], into: dict[int, set[int]]) -> None:
    """Add to `into` the argument components `node` reads when its components `live` are."""
    how = _HOW.get(node.op, _WHOLE)
    for i, a in enumerate(node.args):
        sw = a.swizzle
        if how == _BY_LANE:
            last = len(sw) - 1
            comps = {sw[c if c < last else last] for c in live}
        elif how == _BY_INDEX:
            if i not in live:
                continue
            comps = {sw[0]}
        elif how == _ONE or (how == _FIRST and i >= 2):
            comps = {sw[0]}
        elif how == _FIRST:
            last = len(sw) - 1
            comps = {sw[j if j < last else last] for j in range(REDUCE[node.op])}
        else:
            comps = set(sw)
        got = into.get(a.node.id)
        if got is None:
            into[a.node.id] = comps
        else:
            got |= comps


def analyse(nodes: list[Node], roots: list[Operand]) -> LiveLanes | None:
    """The live components of `nodes` (topologically ordered) given the operands the program
    finally reads (`roots`: its outputs' components, its discards); None for code with real
    flow control, where every lane counts as live."""
    if any(n.op in _FLOW for n in nodes):
        return None
    live: dict[int, set[int]] = {}
    for r in roots:
        live.setdefault(r.node.id, set()).update(r.swizzle)
    for n in reversed(nodes):
        mine = live.get(n.id)
        if mine:
            _read(n, mine, live)
    return LiveLanes({k: frozenset(v) for k, v in live.items()})
