"""Values of the symbolic evaluation: a type and, for numbers, one operand per component.

The front end evaluates the entry function over these (inlining every call), so a variable's
value is the list of DAG operands its components hold right now; assigning replaces them.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from effects.shaders.hlsl.dag import Graph, Operand
from effects.shaders.hlsl.types import HType, scalar, vector


@dataclass
class Value:
    type: HType
    comps: list[Operand] = field(default_factory=list)        # numeric: rows*cols, row-major
    fields: dict[str, "Value"] = field(default_factory=dict)   # structs
    elements: list["Value"] = field(default_factory=list)      # arrays
    sampler: str | None = None                                 # samplers, textures: the parameter name

    def copy(self) -> "Value":
        return Value(self.type, list(self.comps), {k: v.copy() for k, v in self.fields.items()},
                     [e.copy() for e in self.elements], self.sampler)

    def shallow(self) -> "Value":
        """A copy whose own lists can be changed; the values inside are shared (store)."""
        return Value(self.type, list(self.comps), dict(self.fields), list(self.elements),
                     self.sampler)

    def const_values(self) -> tuple[float, ...] | None:
        out = []
        for c in self.comps:
            v = c.const_values()
            if v is None:
                return None
            out.append(v[0])
        return tuple(out)


def component(op: Operand, i: int) -> Operand:
    return Operand(op.node, (op.swizzle[i],), op.negate)


def split(op: Operand) -> list[Operand]:
    # component() per lane, inlined: every operator's result is split into its lanes
    node, negate = op.node, op.negate
    return [Operand(node, (lane,), negate) for lane in op.swizzle]


def splat(op: Operand, n: int) -> Operand:
    return Operand(op.node, (op.swizzle[0],) * n, op.negate) if op.width == 1 else op


def numeric(t: HType, op: Operand) -> Value:
    return Value(t, split(op))


def const_value(g: Graph, values: list[float], base: str = "float") -> Value:
    t = vector(base, len(values)) if len(values) > 1 else scalar(base)
    return Value(t, split(g.const(tuple(values))))


def count_components(t: HType) -> int:
    return t.components


def build_value(t: HType, comps: list[Operand]) -> Value:
    if t.numeric:
        return Value(t, list(comps))
    out = Value(t)
    k = 0
    if t.kind == "struct":
        for name, ft, _ in t.fields:
            n = count_components(ft)
            out.fields[name] = build_value(ft, comps[k:k + n])
            k += n
    elif t.kind == "array":
        n = count_components(t.element)  # type: ignore[arg-type]
        out.elements = [build_value(t.element, comps[i * n:(i + 1) * n]) for i in range(t.length)]  # type: ignore[arg-type]
    return out


@dataclass
class Frame:
    """One inlined call: its return value and the predicate 'has returned'."""
    return_type: HType
    retval: Value | None = None
    returned: Operand | None = None


@dataclass
class Loop:
    broken: Operand | None = None
    continued: Operand | None = None
    al: Any = None          # a real loop whose counter may index constants by aL (loops.AL)
    switch: bool = False    # a `switch` (switch.py): `break` leaves it, `continue` may not
    # every 'broken' and 'returned' predicate made while it ran: the lanes that left it
    # (livefold.py: its condition where they are 0)
    left: list[Operand] = field(default_factory=list)
    known: dict = field(default_factory=dict)      # livefold's constants, kept between asks
    zero: dict = field(default_factory=dict)       # `left` as node id -> lanes, so far
    zeroed: int = 0                                # how many of `left` are in `zero`


@dataclass
class Var:
    type: HType
    value: Value
    const: bool = False
