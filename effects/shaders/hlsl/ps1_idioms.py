"""The HLSL idioms ps_1_x expresses as modifiers instead of instructions, as rows.

fxc folded these into the instruction that reads (a source modifier) or writes (a result
shift, `_sat`) the value; without them a DX8 shader does not fit its 8 arithmetic slots and
the [-1, 1] constant range (docs/reference/semantics.md §2.2–2.3, "Modifiers for ps_1_X"):

    2*x - 1, x*2 - 1, (x - 0.5)*2   ->  x_bx2        (expand a [0, 1] normal map to [-1, 1])
    x - 0.5                         ->  x_bias
    1 - x                           ->  1-x          (invert)
    x * 2                           ->  x_x2         (a source modifier in ps_1_4 only)
    y * 2^k, k in the version's shifts  ->  op_x2 / _x4 / _x8 / _d2 / _d4 / _d8 on y's instruction
    saturate(y)                     ->  op_sat on y's instruction

Each SOURCE_IDIOMS row: (modifier, node op, argument pattern, versions). A pattern names what
each argument must be: a float (a constant, all lanes equal), "x" (the operand modified), or
("mul"|"add", pattern) for an argument that is itself such a node (read through its swizzle).
Commutative ops (add, mul) are tried both ways round.
"""
from __future__ import annotations

from typing import Any

from effects.shaders.hlsl.dag import Node, Operand

SOURCE_IDIOMS: list[tuple[str, str, tuple[Any, ...], str]] = [
    ("bx2", "mad", ("x", 2.0, -1.0), "all"),
    ("bx2", "mad", (2.0, "x", -1.0), "all"),
    ("bx2", "add", (("mul", ("x", 2.0)), -1.0), "all"),
    ("bx2", "mul", (("add", ("x", -0.5)), 2.0), "all"),
    ("bias", "add", ("x", -0.5), "all"),
    ("invert", "add", (1.0, "-x"), "all"),
    ("x2", "mul", ("x", 2.0), "ps_1_4"),
]

_COMMUTATIVE = {"add", "mul"}


def _const_is(op: Operand, value: float) -> bool:
    vals = op.const_values()
    return vals is not None and all(v == value for v in vals)


def _match(op: Operand, pattern: Any, found: list[Operand]) -> bool:
    """Whether `op` fits `pattern`; the modified operand is appended to `found`."""
    if isinstance(pattern, float):
        return _const_is(op, pattern)
    if pattern in ("x", "-x"):
        if op.node.op == "const" or (pattern == "-x") != op.negate:
            return False
        found.append(op.neg() if op.negate else op)
        return True
    name, args = pattern
    if op.negate or op.node.op != name:
        return False
    inner: list[Operand] = []
    if not _match_args(op.node, args, inner):
        return False
    found.append(inner[0].pick(op.swizzle))
    return True


def _match_args(node: Node, pattern: tuple[Any, ...], found: list[Operand]) -> bool:
    orders = [node.args]
    if node.op in _COMMUTATIVE:
        orders.append(tuple(reversed(node.args)))
    for args in orders:
        got: list[Operand] = []
        if len(args) == len(pattern) and all(_match(a, p, got) for a, p in zip(args, pattern)):
            found.extend(got)
            return True
    return False


def source_idiom(node: Node, version: str) -> tuple[Operand, str] | None:
    """(the operand x, modifier) when `node` is one of the idioms the version folds into a
    source modifier; x reads the node's lanes in the node's own order."""
    for mod, op, pattern, versions in SOURCE_IDIOMS:
        if node.op != op or (versions != "all" and versions != version):
            continue
        found: list[Operand] = []
        if _match_args(node, pattern, found) and found[0].node.op != "const":
            return found[0], mod
    return None


def power_of_two(values: tuple[float, ...] | None, shifts: tuple[int, ...]) -> int | None:
    """The result shift k (2^k) when every lane is the same power of two the version shifts by."""
    if not values or any(v != values[0] for v in values):
        return None
    import math
    v = values[0]
    if not (0 < v < math.inf):          # NaN and inf are no power of two
        return None
    k = math.log2(v)
    return int(k) if k == int(k) and int(k) in shifts and k != 0 else None
