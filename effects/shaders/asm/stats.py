"""Resource use of an assembled program, as the caps validator compares it with a card.

Slot counts follow the instruction table (`InstrInfo.slot_cost`); a co-issued ps_1_x
instruction shares its partner's slot. `dependent_read_depth` counts levels of texture reads:
a read from interpolated coordinates is level 1, a read whose coordinates come from a
temporary is first-order dependent (level 2), and so on (texld ps_2_0 page: "a given texture
instruction may be dependent upon, at most, third order" = 4 levels).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from effects.shaders.asm.versions import IDENTITY, PS20_SWIZZLES

if TYPE_CHECKING:  # pragma: no cover
    from effects.shaders.asm.program import AsmProgram, Instruction

# ps_1_1-1_3 texture instructions that sample their stage (texcoord, pads, texm3x3, texdp3
# and texkill only read coordinates).
SAMPLING_PS1 = frozenset({"tex", "texbem", "texbeml", "texreg2ar", "texreg2gb", "texreg2rgb",
                          "texm3x2tex", "texm3x3tex", "texm3x3spec", "texm3x3vspec",
                          "texdp3tex"})
TEXTURE_READS_PS2 = frozenset({"texld", "texldp", "texldb", "texldd", "texldl"})


@dataclass(frozen=True)
class AsmStats:
    texture_slots: int
    arithmetic_slots: int
    flow_slots: int
    total_slots: int
    temps_used: int                  # distinct r#
    constants_used: int              # distinct c# named by instructions or def
    texcoords_used: frozenset[int]   # t# (texture coordinate sets) read
    samplers_used: frozenset[int]    # s# (ps_2_0+) or texture stages sampled (ps_1_x)
    inputs_used: frozenset[int]      # v#
    dependent_read_depth: int        # levels of texture reads (0: no texture read)
    uses_predication: bool
    uses_arbitrary_swizzle: bool     # a ps source swizzle outside the ps_2_0 set
    uses_gradients: bool             # dsx, dsy, texldd
    flow_control_depth: int
    highest: dict[str, int] = field(default_factory=dict)   # highest index per register kind
    phase_slots: dict[int, tuple[int, int]] = field(default_factory=dict)  # ps_1_4 (tex, arith)

    @property
    def samplers(self) -> int:
        return len(self.samplers_used)

    @property
    def texcoords(self) -> int:
        return len(self.texcoords_used)


def instruction_slots(program: "AsmProgram", ins: "Instruction") -> tuple[int, int, int]:
    """(texture, arithmetic, flow) slots one instruction takes in this program's version."""
    if ins.coissue and program.rules.is_ps1:
        return 0, 0, 0
    cost = ins.info.slot_cost(program.name)
    if ins.info.category == "tex":
        return cost, ins.info.extra_arith, 0
    if ins.info.category == "flow":
        return 0, 0, cost
    return 0, cost, 0


# Ops whose result lane L reads lane L of each source (the others, dp3, m4x4, rcp ..., may read
# any lane of a source: every component its swizzle selects counts).
_LANEWISE = frozenset({"mov", "add", "sub", "mul", "mad", "lrp", "cmp", "cnd", "min", "max",
                       "slt", "sge", "frc", "abs", "mova"})
_ALL_LANES = (0, 1, 2, 3)


def texture_read_levels(program: "AsmProgram") -> dict[int, int]:
    """Level of every texture read, by instruction position (1 = not dependent). The checker
    and the stats both ask: they read it once per program, `AsmProgram.read_levels`. Levels
    are kept per register component, so a write mask leaves the other components' levels as
    they were (`add r1.xy, t0, c0` makes r1.xy a plain coordinate again, whatever r1.zw hold):
    fxc reuses registers so, and the reads it makes stay first-order dependent."""
    depends: dict[tuple[str, int | None, int], int] = {}   # register component -> its level
    levels: dict[int, int] = {}
    ps1 = program.rules.is_ps1
    # the coordinate components a texld reads: a 2D sampler's .xy, a cube or volume's .xyz
    # (undeclared: all three); .w too where it projects, biases or sets the LOD
    coordinate = {d.register.index: (0, 1) if d.sampler_type == "2d" else (0, 1, 2)
                  for d in program.dcls if d.register.kind == "s"}

    def read(src, lanes=_ALL_LANES) -> int:
        return max((depends.get((src.kind, src.index, src.swizzle[lane]), 0) for lane in lanes),
                   default=0)

    def write(dst, level: int) -> None:
        for c in dst.components:
            depends[(dst.kind, dst.index, c)] = level

    for pos, ins in enumerate(program.instructions):
        if ins.opcode in ("texkill", "texdepth"):
            continue   # they read coordinates or r5 but write nothing
        if ps1 and ins.info.category == "tex" and ins.dst is not None:
            # texture-address sources are the t(n) read; tex/texcoord read interpolators only
            coord = max((read(s) for s in ins.srcs if s.kind in "tr"), default=0)
            reads = ins.opcode in SAMPLING_PS1 or ins.opcode == "texld"
            level = coord + 1 if reads else coord
            if ins.opcode == "texld" and program.rules.is_ps14 and ins.srcs and \
                    ins.srcs[0].kind == "r":
                level = max(coord, 1) + 1
            if reads:
                levels[pos] = level
            write(ins.dst, level)
            continue
        if ins.opcode in TEXTURE_READS_PS2 and ins.dst is not None:
            # a read at coordinates computed in a temporary is dependent (level 2 at least),
            # one level above what those coordinates derive from
            coord = ins.srcs[0] if ins.srcs else None
            if coord is not None and coord.kind == "r":
                sampler = ins.srcs[1].index if len(ins.srcs) > 1 else None
                lanes = coordinate.get(sampler, (0, 1, 2))
                if ins.opcode in ("texldp", "texldb", "texldl"):
                    lanes = (*lanes, 3)
                level = max(read(coord, lanes), 1) + 1
            else:
                level = 1
            levels[pos] = level
            write(ins.dst, level)
            continue
        if ins.dst is not None:
            lanes = ins.dst.components if ins.opcode in _LANEWISE else _ALL_LANES
            write(ins.dst, max((read(s, lanes) for s in ins.srcs), default=0))
    return levels


def compute_stats(program: "AsmProgram") -> AsmStats:
    rules = program.rules
    tex = arith = flow = 0
    phase_slots: dict[int, list[int]] = {}
    highest: dict[str, int] = {}
    regs: dict[str, set[int]] = {}
    texcoords: set[int] = set()
    samplers: set[int] = set()
    predication = arbitrary = gradients = False
    depth = max_depth = 0

    def note(kind: str, index: int | None) -> None:
        if index is None:
            return
        highest[kind] = max(highest.get(kind, -1), index)
        regs.setdefault(kind, set()).add(index)

    for d in program.dcls:
        note(d.register.kind, d.register.index)
    for cd in program.def_statements:
        note(cd.register.kind, cd.register.index)
    for ins in program.instructions:
        t, a, f = instruction_slots(program, ins)
        tex, arith, flow = tex + t, arith + a, flow + f
        if ins.phase is not None:
            ps = phase_slots.setdefault(ins.phase, [0, 0])
            ps[0] += t
            ps[1] += a
        for op in ins.operands:
            note(op.kind, op.index)
            if op.kind == "p":
                predication = True
        rows = ins.info.matrix_rows
        if rows and len(ins.srcs) > 1 and ins.srcs[1].index is not None:
            for k in range(1, rows):
                note(ins.srcs[1].kind, ins.srcs[1].index + k)
        if ins.predicate is not None or ins.opcode == "setp":
            predication = True
        if ins.opcode in ("dsx", "dsy", "texldd"):
            gradients = True
        if program.kind == "ps" and not rules.is_ps1:
            for s in ins.srcs:
                if s.kind not in ("imm", "s", "l") and s.swizzle != IDENTITY \
                        and not s.is_replicate and s.swizzle not in PS20_SWIZZLES:
                    arbitrary = True
        # texture coordinate sets and samplers
        if rules.is_ps11_13 and ins.is_texture and ins.dst is not None:
            texcoords.add(ins.dst.index)   # each texture instruction consumes tc(m)
            if ins.opcode in SAMPLING_PS1:
                samplers.add(ins.dst.index)
        elif rules.is_ps14 and ins.opcode in ("texld", "texcrd") and ins.dst is not None:
            texcoords.update(s.index for s in ins.srcs if s.kind == "t")
            if ins.opcode == "texld":
                samplers.add(ins.dst.index)
        else:
            texcoords.update(s.index for s in ins.srcs if s.kind == "t")
            samplers.update(s.index for s in ins.srcs if s.kind == "s")
        if ins.opcode in ("if", "loop", "rep"):
            depth += 1
            max_depth = max(max_depth, depth)
        elif ins.opcode in ("endif", "endloop", "endrep"):
            depth = max(0, depth - 1)
    levels = program.read_levels
    return AsmStats(
        texture_slots=tex, arithmetic_slots=arith, flow_slots=flow,
        total_slots=tex + arith + flow,
        temps_used=len(regs.get("r", ())),
        constants_used=len(regs.get("c", ())),
        texcoords_used=frozenset(i for i in texcoords if i is not None),
        samplers_used=frozenset(i for i in samplers if i is not None),
        inputs_used=frozenset(regs.get("v", ())),
        dependent_read_depth=max(levels.values(), default=0),
        uses_predication=predication, uses_arbitrary_swizzle=arbitrary,
        uses_gradients=gradients, flow_control_depth=max_depth, highest=highest,
        phase_slots={k: (v[0], v[1]) for k, v in sorted(phase_slots.items())},
    )
