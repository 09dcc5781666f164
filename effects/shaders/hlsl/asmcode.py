"""The code generators' instructions on virtual temporaries, before allocation: codegen.py and
legalize.py (vs_1_1-ps_3_0), and the ps_1_x generator (codegen_ps1.py, ps1_asm.py,
ps1_textures.py), whose sources are ps1_asm.Src (one replicated lane and a source modifier) and
whose instructions use the ps_1_x fields at the end of `Instr`. The writer (writer.py) makes
the assembler's records (effects/shaders/asm/program.py) of them once they are allocated."""
from __future__ import annotations

from dataclasses import dataclass

from typing import Any

from effects.base.errors import Location, UNKNOWN_LOCATION

_SAMPLER_DCL = {"2d": "2d", "1d": "2d", "3d": "volume", "cube": "cube"}


@dataclass
class Reg:
    """A register: kind 'r' (virtual until allocated), 'c', 'v', 't', 's', 'o...', 'a' (a0),
    'c_rel' (c[a0.x + index]), 'c_al' (c[aL + index])."""
    kind: str
    index: int | None
    lane: int = 0                  # c_rel: the component of a0 that indexes (c[a0.y + n])

    def text(self, alloc: dict[int, int]) -> str:
        if self.kind == "vr":
            return f"r{alloc[self.index]}"  # type: ignore[index]
        if self.kind == "c_rel":
            a0 = f"a0.{'xyzw'[self.lane]}"
            return f"c[{a0} + {self.index}]" if self.index else f"c[{a0}]"
        if self.kind == "c_al":
            return f"c{self.index}[aL]"
        return f"{self.kind}{'' if self.index is None else self.index}"


@dataclass
class Src:
    reg: Reg
    lanes: dict[int, int]          # instruction lane -> register lane
    negate: bool = False
    fixed: tuple[int, ...] | None = None   # full swizzle when the lanes do not say (scalars)


@dataclass
class Instr:
    opcode: str
    dst: Reg | None
    mask: tuple[int, ...]
    srcs: list[Any]                # Src; ps1_asm.Src in ps_1_x code
    location: Location = UNKNOWN_LOCATION
    saturate: bool = False
    sampler: str | None = None
    # ps_1_x only
    shift: int = 0                 # result shift: _x2 _x4 _x8 (1..3), _d2 _d4 _d8 (-1..-3)
    texture: bool = False          # a texture-address instruction (tex, texld, texcrd, phase)
    coissue: bool = False          # paired with the instruction before (`+`)
    optional: bool = False         # left out when nothing reads its result


@dataclass
class Output:
    register: str                   # 'oPos' 'oC0' 'oT1' ...
    comps: list[Any]             # dag Operands
    location: Location = UNKNOWN_LOCATION
