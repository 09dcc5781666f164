"""The code generators' records: the assembler's own `Instruction` and `Operand`
(effects/shaders/asm/program.py), made on virtual temporaries before allocation.

One record from the first instruction selected to the listing: codegen.py and codegen_ps1.py
emit these, the passes after them (peephole.py, legalize.py, flowcode.py) rewrite them in place,
and the writer (writer.py) only renames registers and adds the declarations, so the assembler's
checks and the slot counts read them as they read a hand-written shader. Before the writer:

- a temporary is kind 'vr' (`VIRTUAL`), its index a value's number; allocate.py gives each an
  r#, which the writer writes into the record;
- a source may read lanes, not a swizzle (`Operand.lanes`: instruction lane -> register lane,
  as selection knows them); legalize.source_swizzle picks a swizzle the version has;
- a destination's mask is always a tuple (the writer spells all four as none);
- a sampler is an `s` operand named by its HLSL sampler (`text`), numbered once the samplers
  a shader reads are known (legalize.code_of);
- `if_gt`, `break_ne` are the opcode and its `comparison`, as the assembler parses them.
"""
from __future__ import annotations

from effects.base.errors import Location, UNKNOWN_LOCATION
from effects.shaders.asm.instructions import COMPARISONS, InstrInfo, lookup, rows_named
from effects.shaders.asm.program import Instruction, Operand, RelativeAddress

VIRTUAL = "vr"
FULL = (0, 1, 2, 3)


def reg(kind: str, index: int | None = None, relative: RelativeAddress | None = None) -> Operand:
    """A register as a generator holds it (a value's home): c3, v0, oPos, a0, vr7,
    c[a0.y + 5] (`relative`)."""
    return Operand(kind, index, relative=relative)


def temp(n: int) -> Operand:
    """Virtual temporary number `n`."""
    return Operand(VIRTUAL, n)


def read(r: Operand, lanes: dict[int, int], negate: bool = False) -> Operand:
    """A source reading `r`: instruction lane -> the register lane it reads (the swizzle is
    chosen later, legalize.source_swizzle)."""
    return Operand(r.kind, r.index, negate=negate, relative=r.relative, lanes=lanes)


def fixed(r: Operand, swizzle: tuple[int, ...], negate: bool = False) -> Operand:
    """A source reading `r` with a swizzle of its own (a scalar's replicate, a constant row)."""
    return Operand(r.kind, r.index, swizzle=tuple(swizzle), negate=negate,  # type: ignore[arg-type]
                   relative=r.relative)


def replicated(r: Operand, lane: int | None = None, modifier: str = "",
               negate: bool = False) -> Operand:
    """A ps_1_x source: `r` as held (`lane` None) or one lane replicated (`.a`, `.b`; `.r`,
    `.g` in ps_1_4, spelt in rgba as ps_1_x code is written), with its modifier (bx2 bias x2
    invert) and sign."""
    if lane is None:
        return Operand(r.kind, r.index, negate=negate, modifier=modifier or None)
    return Operand(r.kind, r.index, swizzle=(lane,) * 4, swizzle_text="rgba"[lane],
                   negate=negate, modifier=modifier or None)


def fix(op: Operand, swizzle: tuple[int, ...]) -> None:
    """`op` reads `swizzle` whatever lanes it read."""
    op.swizzle = tuple(swizzle)  # type: ignore[assignment]
    op.lanes = None


def needed(op: Operand) -> dict[int, int]:
    """Instruction lane -> the register lane `op` reads there."""
    if op.lanes is None:
        sw = op.swizzle
        return {0: sw[0], 1: sw[1], 2: sw[2], 3: sw[3]}
    return dict(op.lanes)


def same(a: Operand, b: Operand) -> bool:
    """One register (c5 and c[a0.x + 5] are two)."""
    return a.kind == b.kind and a.index == b.index and a.relative == b.relative


def is_flow(ins: Instruction) -> bool:
    """rep, loop, if, else, break ...: the instructions without a destination but texkill
    (which reads its operand)."""
    return ins.dst is None and ins.opcode != "texkill"


def written(ins: Instruction) -> tuple[int, ...]:
    """The lanes `ins` writes (none for flow instructions and texkill)."""
    d = ins.dst
    if d is None:
        return ()
    return d.mask if d.mask is not None else FULL


def row(opcode: str, version: str) -> InstrInfo:
    """The table row of `opcode` in `version` (any row of that name where the version lacks
    it: the writer refuses it, as a generator bug)."""
    info = lookup(opcode, version)
    if info is None:
        rows = rows_named(opcode)
        if not rows:
            raise KeyError(opcode)
        info = rows[0]
    return info


def instruction(opcode: str, dst: Operand | None, mask: tuple[int, ...], srcs: list[Operand],
                version: str, loc: Location = UNKNOWN_LOCATION, saturate: bool = False,
                sampler: str | None = None, shift: int = 0) -> Instruction:
    """`opcode` (`if_gt`: `if` comparing) writing `mask` of `dst` (a fresh operand: homes are
    shared, records are not), reading `srcs` (and `sampler`, named, as the second source)."""
    base, _, suffix = opcode.partition("_")
    comparison = suffix if suffix in COMPARISONS else None
    if comparison is None:
        base = opcode
    if sampler is not None:
        srcs.insert(1, Operand("s", None, text=sampler))
    d = None if dst is None else Operand(dst.kind, dst.index, relative=dst.relative,
                                         mask=tuple(mask))
    return Instruction(base, d, srcs, row(base, version), loc, shift=shift, saturate=saturate,
                       comparison=comparison)
