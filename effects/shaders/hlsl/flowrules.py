"""Which flow control a target's code may use, and how deep it may nest (one table for
loops.py and branches.py)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from effects.shaders.hlsl.types import FLOAT
from effects.shaders.hlsl.values import Value

# Nesting limits of the flow-control instructions in 2_x / 3_0 code (the DirectX 9 "Flow
# Control Limitations" pages): static if b# 24, dynamic if_comp / break_comp 24, rep / loop 4.
MAX_DEPTH = {"static": 24, "dynamic": 24, "loop": 4}
_DEPTH_WHAT = {"static": "static branches (if b#)", "dynamic": "dynamic branches (if_comp, "
               "break_comp)", "loop": "loops (rep, loop)"}


# The HLSL profiles' flow control (D3DXGetPixelShaderProfile / D3DXGetVertexShaderProfile
# and the vs_2_0 / ps_2_x reference pages): vs_2_0 has static flow control (if b#, rep, loop)
# only; vs_2_a adds dynamic flow control (if_comp, break_comp) and predication; ps_2_a and
# ps_2_b are ps_2_0 plus swizzles / temps / texture limits, with no flow control at all;
# ps_2_x (the assembly version, caps-decided) and the 3_0 models have both.
_STATIC = frozenset({"vs_2_0", "vs_2_a", "vs_2_x", "vs_3_0", "ps_2_x", "ps_3_0"})
_DYNAMIC = frozenset({"vs_2_a", "vs_2_x", "vs_3_0", "ps_2_x", "ps_3_0"})
DYNAMIC_TARGETS = "vs_2_a, vs_3_0 and ps_3_0"


@dataclass(frozen=True)
class TargetFlow:
    """What flow control a target's code may use: static (if b#, rep) and dynamic (if_comp,
    break_comp)."""
    static: bool
    dynamic: bool

    @staticmethod
    def of(target: Any) -> "TargetFlow":
        return TargetFlow(target.name in _STATIC, target.name in _DYNAMIC)


class NotReal(Exception):
    """The construct matches a real flow-control form but cannot be one (the reason); the
    caller unrolls, flattens, or reports the reason at the construct."""


def enter(ev: Any, kind: str) -> None:
    """Count one more level of `kind` flow control (NotReal past the limit)."""
    depth = ev.ctx.flow_depth
    if depth[kind] >= MAX_DEPTH[kind]:
        raise NotReal(f"it would nest {_DEPTH_WHAT[kind]} {MAX_DEPTH[kind] + 1} deep, and "
                      f"{ev.ctx.target.name} allows {MAX_DEPTH[kind]}")
    depth[kind] += 1


def leave(ev: Any, kind: str) -> None:
    ev.ctx.flow_depth[kind] -= 1


class Flag:
    """A predicate the evaluator keeps beside the variables (a frame's `returned`, a loop's
    `broken` / `continued`) seen as a float variable of 0 / 1, so that a real if or loop
    carries it as it carries a variable: a `return` in a branch side is the side's result
    'returned = 1', and what follows the if runs under 'not returned' (an early return by
    predicate). None (never set) reads as 0 and 0 is written back as None."""

    const = False

    def __init__(self, ev: Any, owner: Any, attr: str) -> None:
        self.owner, self.attr, self.g = owner, attr, ev.g
        self.type = FLOAT

    @property
    def value(self) -> Value:
        op = getattr(self.owner, self.attr)
        return Value(FLOAT, [op if op is not None else self.g.const((0.0,))])

    @value.setter
    def value(self, v: Value) -> None:
        op = v.comps[0]
        setattr(self.owner, self.attr, None if op.const_values() == (0.0,) else op)


class RetVal:
    """A frame's return value seen as a variable (before any return: a zero value of the
    return type, written back as None). A struct return type is not carried (`refusal`)."""

    const = False

    def __init__(self, ev: Any, frame: Any) -> None:
        self.frame = frame
        self.type = frame.return_type
        self._unset = ev.zero(frame.return_type)
        self.refusal = "return of a struct {where} is not generated in a {place} yet"

    @property
    def value(self) -> Value:
        return self.frame.retval if self.frame.retval is not None else self._unset

    @value.setter
    def value(self, v: Value) -> None:
        self.frame.retval = None if v is self._unset else v


def flow_vars(ev: Any) -> list[Any]:
    """The predicates and return value a real if / loop carries besides the variables: the
    innermost frame's return value and 'returned', the innermost loop's 'broken' and
    'continued' (the loop a real loop's own body makes is not there yet)."""
    out: list[Any] = []
    if ev.frames:
        frame = ev.frames[-1]
        out.append(Flag(ev, frame, "returned"))
        if frame.return_type.kind != "void":
            out.append(RetVal(ev, frame))
    if ev.loops:
        out += [Flag(ev, ev.loops[-1], "broken"), Flag(ev, ev.loops[-1], "continued")]
    return out


def refusal(v: Any, where: str, place: str) -> str:
    """Why a changed array / struct variable (or struct return value) cannot be carried."""
    text = getattr(v, "refusal", None)
    if text is not None:
        return text.format(where=where, place=place)
    return f"{'a side' if place == 'branch' else 'the body'} changes an array or a struct " \
        "(not carried yet)"


@dataclass
class Effects:
    """The discards (and the real ifs / loops holding some) a branch side or a loop body
    makes: taken off the program's list (ctx.kills) when it ends, to be held by the if / loop
    node, so the texkill runs inside the block (codegen places it there); the node then goes
    on the list in their place."""

    start: int

    @classmethod
    def note(cls, ev: Any) -> "Effects":
        return cls(len(ev.ctx.kills))

    def take(self, ev: Any) -> list[Any]:
        made = ev.ctx.kills[self.start:]
        del ev.ctx.kills[self.start:]
        return made


__all__ = ["DYNAMIC_TARGETS", "Effects", "Flag", "RetVal", "flow_vars", "refusal", "NotReal", "MAX_DEPTH", "TargetFlow", "enter", "leave"]
