"""ps_1_x homes, co-issue pairing, and the code handed to the writer.

codegen_ps1 emits the assembler's records (records.py: `replicated` sources, one lane and a
modifier) on virtual registers (kind 'vr'); this mixin pairs them for co-issue and has the one
allocator (allocate.py) give them r0-r1 (r0-r5 in ps_1_4), with the result pinned to r0 and,
in ps_1_4, each texld destination pinned to its stage; the writer (writer.py) renames them.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from effects.base.errors import Location, UNKNOWN_LOCATION
from effects.shaders.asm.program import Instruction, Operand
from effects.shaders.asm.ps1_rules import coissue_split
from effects.shaders.hlsl.allocate import OutOfRegisters, allocate
from effects.shaders.hlsl.parse import HlslError
from effects.shaders.hlsl.records import same, written
from effects.shaders.hlsl.writer import Code

RGBA = "rgba"


@dataclass
class Home:
    reg: Operand
    scalar: bool = False           # replicated in every lane
    phase: int = 2
    lanes: int = 4                 # lanes that hold the value (texcrd: .rgb)
    mask: tuple[int, ...] | None = None   # the mask it is written with (coalesced outputs)


class Ps1Emit:
    """Mixin of Ps1CodeGen, which holds these."""

    instrs: list[Instruction]
    optional: set[int]             # id() of moves left out when nothing reads their result
    precolor: dict[int, int]
    vr_loc: dict[int, Location]
    defs: dict[int, list[float | None]]
    rules: Any
    v: str
    const_regs: dict[str, int]
    sizes: dict[str, int]
    used_uniforms: set[str]
    samplers: dict[str, int]

    def _pair(self) -> None:
        """Co-issue an .a-only instruction with the .rgb-only one before it (one slot for the
        two, as DX8 shaders did, where the version row has co-issue and its pairing rule
        holds); both read the registers as they were before the pair."""
        if not self.rules.coissue:
            return
        prev = None
        for ins in self.instrs:
            if prev is not None and ins.is_arithmetic and prev.is_arithmetic \
                    and not prev.coissue and coissue_split(written(prev), written(ins)) \
                    and (0, 1, 2) in (written(prev), written(ins)) \
                    and not _cnd_coissued_on_colour(ins, self.rules) \
                    and not any(same(s, prev.dst) for s in ins.srcs) \
                    and not any(same(s, ins.dst) for s in prev.srcs):
                ins.coissue = True
                prev = None
                continue
            prev = ins

    def _code(self) -> Code:
        """Instructions nothing reads left out, co-issue pairs made, then the temporaries
        allocated (allocate.py: pinned ones first; r0-r1, r0-r5 in ps_1_4), for the writer."""
        read = {s.index for ins in self.instrs for s in ins.srcs if s.kind == "vr"}
        self.instrs = [ins for ins in self.instrs if id(ins) not in self.optional or
                       (ins.dst is not None and ins.dst.index in read)]
        self._pair()
        count = self.rules.registers["r"]
        try:
            # ps_1_x instructions read their sources before they write: a range ending where
            # another starts may share its register. Two pinned values live at once raise
            # allocate.RegisterConflict (Ps1CodeGen.generate retries, then refuses).
            alloc = allocate(self.instrs, lambda ins, vr: True, self.precolor, count)
        except OutOfRegisters as full:
            raise HlslError(f"X4532: cannot map expression to pixel shader instruction set: "
                            f"{self.v} has {count} temporary registers (r0-r{count - 1}) and "
                            "this value needs another one",
                            self.vr_loc.get(full.vr, UNKNOWN_LOCATION)) from None
        constants = {n: (self.const_regs[n], self.sizes.get(n, 1)) for n in self.const_regs
                     if n in self.used_uniforms}
        return Code(self.instrs, alloc,
                    {r: tuple(0.0 if v is None else v for v in vals) for r, vals in self.defs.items()},
                    constants=constants, samplers=dict(self.samplers), letters=RGBA)


def _cnd_coissued_on_colour(ins: Instruction, rules: Any) -> bool:
    # a co-issued cnd writing .rgb in ps_1_1-1_3 always returns its first choice
    # (docs/reference/semantics.md 2.4)
    return rules.is_ps11_13 and ins.opcode == "cnd" and written(ins) != (3,)
