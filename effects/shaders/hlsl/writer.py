"""The one writer of the HLSL compiler. The code generators emit the assembler's own records
(`Instruction`, `Operand`: effects/shaders/asm/program.py, made by records.py) on virtual
temporaries; once they are allocated, the writer renames each temporary to its r#, spells each
operand, and adds the `def` constants and the declarations, making an `AsmProgram` that the
assembler's checks, the slot counts and the lowering read as they read a hand-written shader.
No record is converted and no text is parsed: text is printed from the records for listings
(`listing`, in the HLSL compiler's spelling: effects/shaders/asm/text.py).

A `mov` of a temporary into the same register, as read, is left out (the allocation made it a
copy onto itself), and an instruction co-issued with it stands alone.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from effects.base.errors import Location, UNKNOWN_LOCATION
from effects.shaders.asm.instructions import lookup, rows_named
from effects.shaders.asm.program import AsmProgram, ConstantDef, Declaration, Instruction, Operand
from effects.shaders.asm.text import LISTING, canonical_swizzle_text, listing_number, program_lines
from effects.shaders.asm.versions import IDENTITY, VersionRules
from effects.shaders.hlsl.parse import HlslError

XYZW = "xyzw"


@dataclass
class Code:
    """What a code generator made, allocated: the instructions (their swizzles chosen and
    samplers numbered), their temporaries' registers, the constants it defined and the
    declarations of what it reads, and the tables the pass needs (parameter -> first c# and
    count, sampler -> s#, int -> i#, bool -> b#)."""

    instrs: list[Instruction]
    alloc: dict[int, int]                        # virtual temporary -> r#
    defs: dict[int, tuple[float, ...]] = field(default_factory=dict)
    int_defs: dict[int, tuple[int, ...]] = field(default_factory=dict)
    dcls: list[Declaration] = field(default_factory=list)
    constants: dict[str, tuple[int, int]] = field(default_factory=dict)
    samplers: dict[str, int] = field(default_factory=dict)
    int_registers: dict[str, int] = field(default_factory=dict)
    bool_registers: dict[str, int] = field(default_factory=dict)
    # registers of an int or bool parameter from its first (one per component read:
    # components.py); absent, one
    register_counts: dict[str, int] = field(default_factory=dict)
    letters: str = XYZW                          # how masks are spelt (ps_1_x: rgba)


_SWIZZLE_TEXT: dict[tuple[int, ...], str] = {}


def declaration(kind: str, index: int | None, usage: str | None = None, usage_index: int = 0,
                mask: tuple[int, ...] | None = None, sampler_type: str | None = None,
                centroid: bool = False) -> Declaration:
    """`dcl_texcoord1 v1`, `dcl t0`, `dcl vPos.xy`, `dcl_2d s0` as a record."""
    reg = Operand(kind, index, text=f"{kind}{'' if index is None else index}", mask=mask,
                  swizzle_text="".join(XYZW[c] for c in mask) if mask else "")
    return Declaration(reg, usage, usage_index, sampler_type, centroid=centroid)


def write(code: Code, rules: VersionRules, entry_loc: Location
          ) -> tuple[AsmProgram, dict[int, Location]]:
    """The records of `code` for the version `rules`, each instruction located at the HLSL
    line it comes from (the entry point's definition, `entry_loc`, where it has none); also
    each record's own location as generated (by id: `listing` shows the lines that have one)."""
    generated_at: dict[int, Location] = {}
    prog = AsmProgram(kind=rules.kind, version=(rules.major, rules.minor), name=rules.name,
                      rules=rules, location=entry_loc,
                      origin=Location(entry_loc.path, 0, 1))
    for reg in sorted(code.defs):
        # the value the listing's nine digits give back: a shader read back from its text
        # (the on-disk compile cache, store.py) holds the same numbers
        values = tuple(float(listing_number(v)) for v in code.defs[reg])
        prog.def_statements.append(ConstantDef(_at(Operand("c", reg, text=f"c{reg}"), entry_loc),
                                               values, entry_loc))
        prog.defs[reg] = values  # type: ignore[assignment]
    for reg in sorted(code.int_defs):
        values = tuple(int(v) for v in code.int_defs[reg])
        prog.def_statements.append(ConstantDef(_at(Operand("i", reg, text=f"i{reg}"), entry_loc),
                                               values, entry_loc))
        prog.int_defs[reg] = values  # type: ignore[assignment]
    for d in code.dcls:
        d.location = d.register.location = entry_loc
        prog.dcls.append(d)
    ps14 = rules.is_ps14
    phase = 1 if ps14 and any(i.opcode == "phase" for i in code.instrs) else 2 if ps14 else None
    dropped = False
    for ins in code.instrs:
        if ins.opcode == "phase":
            prog.phase_locations.append(entry_loc)
            phase = 2
            continue
        generated = ins.location
        record = finish(code, ins, rules, entry_loc)
        if _copy_onto_itself(record):
            dropped = True
            continue
        if dropped and record.coissue:
            record.coissue = False         # its pair was the copy left out: alone now
        dropped = False
        record.phase = phase
        prog.instructions.append(record)
        generated_at[id(record)] = generated
    return prog, generated_at


def finish(code: Code, ins: Instruction, rules: VersionRules, entry_loc: Location
           ) -> Instruction:
    """`ins` as the assembler has it, in place: its temporaries renamed to the registers
    allocated, each operand spelt, a full mask as none, the row of the version's table, located
    at its HLSL line."""
    alloc = code.alloc
    for op in ins.srcs:
        if op.kind == "vr":
            op.kind, op.index = "r", alloc[op.index]  # type: ignore[index]
        op.text = op.name
        if not op.swizzle_text:
            op.swizzle_text = _swizzle_text(op.swizzle)
    dst = ins.dst
    if dst is not None:
        if dst.kind == "vr":
            dst.kind, dst.index = "r", alloc[dst.index]  # type: ignore[index]
        dst.text = dst.name
        mask = tuple(dst.mask) if dst.mask is not None else IDENTITY
        if list(mask) != sorted(set(mask)):
            raise HlslError(f"internal: the generated {rules.name} code writes the mask "
                            f"{mask} of {dst.name}", ins.location or entry_loc)
        if mask == IDENTITY:
            dst.mask = None
        else:
            dst.mask = mask
            dst.swizzle_text = "".join(code.letters[c] for c in mask)
    info = lookup(ins.opcode, rules.name)
    if info is None:        # a generator bug: the checks say the version lacks it
        info = next((r for r in rows_named(ins.opcode)
                     if len(r.operands) == len(ins.operands)), None)
        if info is None:
            raise HlslError(f"internal: the generated {rules.name} code uses '{ins.opcode}'",
                            ins.location or entry_loc)
    ins.info = info
    if dst is not None and not info.has_dst:   # ps_2_0's texkill names its register as a source
        dst.mask, dst.swizzle_text = None, ""
        ins.srcs.insert(0, dst)
        ins.dst = None
    loc = ins.location if ins.location.line else entry_loc
    ins.location = loc
    for op in ins.operands:
        op.location = loc
    return ins


def _swizzle_text(swizzle: tuple[int, ...]) -> str:
    text = _SWIZZLE_TEXT.get(swizzle)
    if text is None:
        text = _SWIZZLE_TEXT[swizzle] = canonical_swizzle_text(swizzle)
    return text


def _at(op: Operand, loc: Location) -> Operand:
    op.location = loc
    return op


def _copy_onto_itself(ins: Instruction) -> bool:
    """`mov r0.xyz, r0`: a copy the register allocation made into the register it reads."""
    if ins.opcode != "mov" or ins.saturate or ins.shift or ins.coissue or ins.dst is None \
            or ins.dst.kind != "r":
        return False
    s = ins.srcs[0]
    return s.kind == "r" and s.index == ins.dst.index and not s.negate and s.modifier is None \
        and s.relative is None and s.swizzle == IDENTITY


def listing(program: AsmProgram, generated_at: dict[int, Location]) -> tuple[str, list[Location]]:
    """The program's text in the HLSL compiler's spelling, and per line the HLSL location of
    the instruction it writes (`generated_at`, by the record's id; unknown for the rest)."""
    lines: list[str] = []
    locs: list[Location] = []
    for text, ins in program_lines(program, LISTING):
        lines.append(text)
        locs.append(generated_at.get(id(ins), UNKNOWN_LOCATION) if ins is not None
                    else UNKNOWN_LOCATION)
    return "\n".join(lines) + "\n", locs
