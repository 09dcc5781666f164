"""ps_1_x code records, register allocation, co-issue pairing and the assembly text.

codegen_ps1 emits `Instr` records (asmcode's, with ps_1_x sources) on virtual registers (kind 'vr'); this mixin gives them r0-r1 (r0-r5 in
ps_1_4) by live range, with the result pinned to r0 and, in ps_1_4, each texld destination
pinned to its stage, then prints the text the assembler reads.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from effects.base.errors import Location, UNKNOWN_LOCATION
from effects.shaders.hlsl.asmcode import Generated, Instr, Reg
from effects.shaders.hlsl.parse import HlslError

RGBA = "rgba"
FULL = (0, 1, 2, 3)
_SHIFT_TEXT = {1: "_x2", 2: "_x4", 3: "_x8", -1: "_d2", -2: "_d4", -3: "_d8"}


class RegisterConflict(Exception):
    """Two values pinned to one register are live at once (retried with r0 written last)."""

    def __init__(self, location: Location = UNKNOWN_LOCATION) -> None:
        super().__init__()
        self.location = location


@dataclass
class Src:
    reg: Reg
    lane: int | None = None        # a replicated lane (.a, .b; .r/.g in ps_1_4); None: as held
    mod: str = ""                  # bx2 | bias | x2 | invert
    neg: bool = False


@dataclass
class Home:
    reg: Reg
    scalar: bool = False           # replicated in every lane
    phase: int = 2
    lanes: int = 4                 # lanes that hold the value (texcrd: .rgb)
    mask: tuple[int, ...] | None = None   # the mask it is written with (coalesced outputs)


class Ps1Emit:
    """Mixin of Ps1CodeGen, which holds these."""

    instrs: list[Instr]
    precolor: dict[int, int]
    vr_loc: dict[int, Location]
    defs: dict[int, list[float | None]]
    rules: Any
    v: str
    const_regs: dict[str, int]
    sizes: dict[str, int]
    used_uniforms: set[str]
    samplers: dict[str, int]

    def _allocate(self) -> dict[int, int]:
        first: dict[int, int] = {}
        last: dict[int, int] = {}
        for i, ins in enumerate(self.instrs):
            for reg in [ins.dst] + [s.reg for s in ins.srcs]:
                if reg is not None and reg.kind == "vr":
                    first.setdefault(reg.index, i)  # type: ignore[arg-type]
                    last[reg.index] = i  # type: ignore[index]
        count = self.rules.registers["r"]
        alloc: dict[int, int] = {}

        def clash(vr: int, phys: int) -> bool:
            return any(p == phys and first[o] < last[vr] and first[vr] < last[o]
                       for o, p in alloc.items())
        order = sorted(first, key=lambda v: (v not in self.precolor, first[v], v))
        for vr in order:
            if vr in self.precolor:
                if clash(vr, self.precolor[vr]):
                    raise RegisterConflict(self.vr_loc.get(vr, UNKNOWN_LOCATION))
                alloc[vr] = self.precolor[vr]
                continue
            phys = next((p for p in range(count) if not clash(vr, p)), None)
            if phys is None:
                raise HlslError(f"X4532: cannot map expression to pixel shader instruction set: "
                                f"{self.v} has {count} temporary registers (r0-r{count - 1}) and "
                                "this value needs another one", self.vr_loc.get(vr, UNKNOWN_LOCATION))
            alloc[vr] = phys
        return alloc

    def _pair(self) -> None:
        """Co-issue an .a-only instruction with the .rgb-only one before it (one slot for the
        two, as DX8 shaders did); both read the registers as they were before the pair."""
        prev = None
        for ins in self.instrs:
            masks = {tuple(ins.mask), tuple(prev.mask)} if prev is not None else set()
            if prev is not None and not ins.texture and not prev.texture and not prev.coissue \
                    and masks == {(3,), (0, 1, 2)} and not _cnd_coissued_on_colour(ins, self.rules) \
                    and all(s.reg != prev.dst for s in ins.srcs) \
                    and all(s.reg != ins.dst for s in prev.srcs):
                ins.coissue = True
                prev = None
                continue
            prev = ins

    def _text(self) -> Generated:
        read = {s.reg.index for ins in self.instrs for s in ins.srcs if s.reg.kind == "vr"}
        self.instrs = [ins for ins in self.instrs if not ins.optional or
                       (ins.dst is not None and ins.dst.index in read)]
        self._pair()
        alloc = self._allocate()
        lines = [self.v]
        locs = [UNKNOWN_LOCATION]
        for reg in sorted(self.defs):
            vals = [0.0 if v is None else v for v in self.defs[reg]]
            lines.append(f"def c{reg}, " + ", ".join(_num(v) for v in vals))
            locs.append(UNKNOWN_LOCATION)
        dropped = False
        for ins in self.instrs:
            if _no_op(ins, alloc):
                dropped = True
                continue
            if dropped and ins.coissue:
                ins.coissue = False         # its pair was the no-op left out: alone now
            dropped = False
            lines.append(_ins_text(ins, alloc))
            locs.append(ins.location)
        constants = {n: (self.const_regs[n], self.sizes.get(n, 1)) for n in self.const_regs
                     if n in self.used_uniforms}
        return Generated(lines, locs, constants, dict(self.samplers),
                         {r: tuple(0.0 if v is None else v for v in vals) for r, vals in self.defs.items()})


def _cnd_coissued_on_colour(ins: Instr, rules: Any) -> bool:
    # a co-issued cnd writing .rgb in ps_1_1-1_3 always returns its first choice
    # (docs/reference/semantics.md 2.4)
    return rules.is_ps11_13 and ins.opcode == "cnd" and tuple(ins.mask) != (3,)


def _no_op(ins: Instr, alloc: dict[int, int]) -> bool:
    """mov r#, r# of the same register, as read: left by r0 being both a sample and the result."""
    if ins.opcode != "mov" or ins.shift or ins.saturate or ins.coissue or len(ins.srcs) != 1:
        return False
    s, d = ins.srcs[0], ins.dst
    return (d is not None and s.reg.kind == d.kind == "vr" and alloc[s.reg.index] == alloc[d.index]  # type: ignore[index]
            and s.lane is None and not s.mod and not s.neg)


def _src_text(s: Src, alloc: dict[int, int]) -> str:
    reg = f"r{alloc[s.reg.index]}" if s.reg.kind == "vr" else f"{s.reg.kind}{s.reg.index}"  # type: ignore[index]
    if s.mod == "invert":
        text = f"1-{reg}"
    else:
        text = reg + (f"_{s.mod}" if s.mod else "")
    if s.lane is not None:
        text += "." + RGBA[s.lane]
    return ("-" if s.neg else "") + text


def _ins_text(ins: Instr, alloc: dict[int, int]) -> str:
    if ins.opcode == "phase":
        return "phase"
    dst = ""
    if ins.dst is not None:
        dst = f"r{alloc[ins.dst.index]}" if ins.dst.kind == "vr" else f"{ins.dst.kind}{ins.dst.index}"  # type: ignore[index]
        if tuple(ins.mask) != FULL:
            dst += "." + "".join(RGBA[i] for i in ins.mask)
    op = ins.opcode + _SHIFT_TEXT.get(ins.shift, "") + ("_sat" if ins.saturate else "")
    parts = [dst] + [_src_text(s, alloc) for s in ins.srcs]
    return ("+" if ins.coissue else "") + f"{op} " + ", ".join(parts)


def _num(v: float) -> str:
    if abs(v) < 1e7 and v == int(v):      # never inf or NaN here (compiler._finite_constants)
        return f"{int(v)}"
    return f"{v:.9g}"
