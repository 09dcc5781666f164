"""The ps_1_x-only rules: ps_1_1–1_3 texture-address sequencing and ps_1_4 phases.

Sources: the ps_1_x instruction pages of the DirectX 9 reference (texbem: "m > n" and "register
data read by texbem cannot be read later"; texm3x2pad "must be combined with texm3x2tex or
texm3x2depth"; texld ps_1_4: r# coordinates only in phase 2, initialised in phase 1; phase:
"instructions before phase are phase 1"), and the ps_1_x registers page (t# in ps_1_4 are
read-only coordinates, v# only in phase 2).

`PS1Rules` is a mixin of the checker: it uses its `p` (program), `v` (version name) and `err`.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # pragma: no cover
    from effects.base.errors import Location
    from effects.shaders.asm.program import AsmProgram

_PS1_TEXM_FINAL3 = ("texm3x3tex", "texm3x3spec", "texm3x3vspec", "texm3x3")


def coissue_split(first: tuple[int, ...], second: tuple[int, ...]) -> bool:
    """Whether two write masks split the work as a co-issued (+) pair must: one writes .a
    alone, the other colour lanes only (the ps_1_x instruction-pairing rule; the checker and
    the HLSL compiler's pairing both ask it)."""
    masks = {tuple(first), tuple(second)}
    return len(masks) == 2 and (3,) in masks and not any(3 in m for m in masks if m != (3,))


class PS1Rules:
    p: "AsmProgram"
    v: str

    def err(self, message: str, location: "Location") -> None:  # provided by the checker
        raise NotImplementedError

    # -- ps_1_1-1_3 texture-address rules --------------------------------------------------------
    def _ps11_texture_rules(self) -> None:
        instrs = self.p.instructions
        loaded: dict[int, str] = {}        # t index → 'tex' (readable) | 'pad'
        bem_read: set[int] = set()
        seen_arith = False
        for pos, ins in enumerate(instrs):
            if self.v not in ins.info.versions:
                # already reported as unavailable; take its write as given (no cascade)
                if ins.dst is not None and ins.dst.kind == "t":
                    loaded[ins.dst.index] = "tex"
                continue
            if ins.is_texture:
                if seen_arith:
                    self.err(f"{ins.opcode} must come before the arithmetic instructions "
                             f"(in {self.v} all texture instructions come first)", ins.location)
                self._ps11_texture_instruction(ins, pos, instrs, loaded, bem_read)
                continue
            if ins.is_arithmetic and ins.opcode != "nop":
                seen_arith = True
            for s in ins.srcs:
                if s.kind != "t":
                    continue
                if loaded.get(s.index) != "tex":
                    self.err(f"{s.name} is read but no texture instruction loads it (tex "
                             f"{s.name}, texcoord {s.name} ...)", s.location)
                    loaded[s.index] = "tex"   # report once
                elif s.index in bem_read:
                    self.err(f"{s.name} was read by texbem/texbeml; no other instruction may "
                             "read it", s.location)
            if ins.dst is not None and ins.dst.kind == "t":
                loaded[ins.dst.index] = "tex"

    def _ps11_texture_instruction(self, ins, pos, instrs, loaded, bem_read) -> None:
        d = ins.dst
        if d is None or d.kind != "t":
            return
        m = d.index
        if ins.opcode == "texkill":
            return
        if m in loaded:
            self.err(f"{d.name} is already loaded by an earlier texture instruction; each t "
                     "register can be written by only one", d.location)
        for s in ins.srcs[:1]:
            if s.kind != "t":
                continue
            if loaded.get(s.index) != "tex":
                self.err(f"{ins.opcode} reads {s.name}, which no earlier texture instruction "
                         "loads", s.location)
            elif s.index >= m:
                self.err(f"{ins.opcode} {d.name}, {s.name}: the source must be a lower t "
                         f"register than the destination", s.location)
            if ins.opcode in ("texbem", "texbeml"):
                bem_read.add(s.index)
        is_pad = ins.opcode in ("texm3x2pad", "texm3x3pad")
        loaded[m] = "pad" if is_pad else "tex"
        prev = instrs[pos - 1] if pos > 0 else None
        nxt = instrs[pos + 1] if pos + 1 < len(instrs) else None
        op = ins.opcode
        finals2 = ("texm3x2tex", "texm3x2depth") if self.v == "ps_1_3" else ("texm3x2tex",)
        if op == "texm3x2pad":
            if nxt is None or nxt.opcode not in finals2:
                self.err(f"texm3x2pad must be followed directly by {' or '.join(finals2)}",
                         ins.location)
            elif nxt.dst is not None and nxt.dst.index != m + 1:
                self.err(f"{nxt.opcode} must write t{m + 1}, the register after its "
                         f"texm3x2pad's {d.name}", nxt.dst.location)
        elif op in ("texm3x2tex", "texm3x2depth"):
            if prev is None or prev.opcode != "texm3x2pad":
                self.err(f"{op} must directly follow texm3x2pad", ins.location)
        elif op == "texm3x3pad":
            second = prev is not None and prev.opcode == "texm3x3pad" and (
                pos < 2 or instrs[pos - 2].opcode != "texm3x3pad")
            if second:
                if nxt is None or nxt.opcode not in _PS1_TEXM_FINAL3:
                    self.err("the second texm3x3pad must be followed directly by texm3x3tex, "
                             "texm3x3spec, texm3x3vspec or texm3x3", ins.location)
                elif nxt.dst is not None and nxt.dst.index != m + 1:
                    self.err(f"{nxt.opcode} must write t{m + 1}, the register after the "
                             f"texm3x3pad rows", nxt.dst.location)
            elif nxt is None or nxt.opcode != "texm3x3pad":
                self.err("texm3x3pad must be followed directly by a second texm3x3pad and then "
                         "texm3x3tex, texm3x3spec, texm3x3vspec or texm3x3", ins.location)
            elif nxt.dst is not None and nxt.dst.index != m + 1:
                self.err(f"the second texm3x3pad must write t{m + 1}", nxt.dst.location)
        elif op in _PS1_TEXM_FINAL3:
            if pos < 2 or instrs[pos - 1].opcode != "texm3x3pad" \
                    or instrs[pos - 2].opcode != "texm3x3pad":
                self.err(f"{op} must directly follow two texm3x3pad instructions",
                         ins.location)

    # -- ps_1_4 phases -------------------------------------------------------------------------
    def _ps14_phase_rules(self) -> None:
        for extra in self.p.phase_locations[1:]:
            self.err("ps_1_4 allows only one phase instruction", extra)
        arith_in_phase: set[int] = set()
        written_in: dict[tuple[str, int | None], set[int]] = {}
        for ins in self.p.instructions:
            if self.v not in ins.info.versions:
                continue
            phase = ins.phase or 2
            if ins.is_texture and phase in arith_in_phase:
                self.err(f"{ins.opcode} must come before the arithmetic instructions of its "
                         f"phase (phase {phase})", ins.location)
            if ins.is_arithmetic and ins.opcode != "nop":
                arith_in_phase.add(phase)
            for s in ins.srcs:
                if s.kind == "v" and phase == 1:
                    self.err(f"{s.name} cannot be read in phase 1 of ps_1_4; colour registers "
                             "are available only after the phase instruction", s.location)
                if s.kind == "t" and ins.is_arithmetic:
                    self.err(f"{s.name} can be read only by texld and texcrd in ps_1_4",
                             s.location)
            if ins.opcode == "texld" and ins.srcs and ins.srcs[0].kind == "r":
                s = ins.srcs[0]
                if phase == 1:
                    self.err(f"texld can take coordinates from {s.name} only in phase 2 (a "
                             "dependent read)", s.location)
                elif (s.kind, s.index) in written_in and 1 not in written_in[(s.kind, s.index)]:
                    self.err(f"texld reads coordinates from {s.name}, which phase 1 does not "
                             "write", s.location)
            if ins.opcode == "bem" and phase == 2:
                self.err("bem is allowed only in phase 1 of ps_1_4", ins.location)
            if ins.opcode == "texdepth" and phase == 1:
                self.err("texdepth is allowed only in phase 2 of ps_1_4", ins.location)
            if ins.dst is not None and ins.opcode not in ("texkill", "texdepth"):
                written_in.setdefault((ins.dst.kind, ins.dst.index), set()).add(phase)
