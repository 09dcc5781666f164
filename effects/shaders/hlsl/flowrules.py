"""Which flow control a target's code may use, and how deep it may nest (one table for
loops.py and branches.py)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

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
    depth = ev.ctx.__dict__.setdefault("flow_depth", {"static": 0, "dynamic": 0, "loop": 0})
    if depth[kind] >= MAX_DEPTH[kind]:
        raise NotReal(f"it would nest {_DEPTH_WHAT[kind]} {MAX_DEPTH[kind] + 1} deep, and "
                      f"{ev.ctx.target.name} allows {MAX_DEPTH[kind]}")
    depth[kind] += 1


def leave(ev: Any, kind: str) -> None:
    ev.ctx.__dict__["flow_depth"][kind] -= 1


@dataclass
class Escapes:
    """What a real branch side or rep body cannot hold yet, noted before it runs: how many
    discards were made and the enclosing function's return state. `refuse` names what the
    body added; `undo` puts both back (the caller then flattens or unrolls instead)."""

    kills: int
    frame: Any
    returned: Any

    @classmethod
    def note(cls, ev: Any) -> "Escapes":
        frame = ev.frames[-1] if ev.frames else None
        return cls(len(ev.ctx.kills), frame, frame.returned if frame is not None else None)

    def refuse(self, ev: Any, where: str, place: str) -> None:
        if len(ev.ctx.kills) != self.kills:
            raise NotReal(f"discard or clip {where} is not generated in a {place} yet")
        if self.frame is not None and self.frame.returned is not self.returned:
            raise NotReal(f"return {where} is not generated in a {place} yet")

    def undo(self, ev: Any) -> None:
        del ev.ctx.kills[self.kills:]
        if self.frame is not None:
            self.frame.returned = self.returned


__all__ = ["DYNAMIC_TARGETS", "Escapes", "NotReal", "MAX_DEPTH", "TargetFlow", "enter", "leave"]
