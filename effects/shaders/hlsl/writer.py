"""The one writer of the HLSL compiler: the code generators' instructions (asmcode.Instr on
allocated temporaries) as the assembler's own records, an `AsmProgram` of `Instruction`,
`Operand`, `Declaration` and `ConstantDef` (effects/shaders/asm/program.py), which the
assembler's checks, the slot counts and the lowering read as they read a hand-written shader.
No text is parsed: text is printed from the records for listings (`listing`, in the HLSL
compiler's spelling: effects/shaders/asm/text.py).

Both generators hand their sources over in their own form: vs_1_1-ps_3_0's `Src` (the lanes an
instruction reads, set to a swizzle the version has by `legalize.source_swizzle`) and ps_1_x's
(`ps1_asm.Src`: one replicated lane, a source modifier). A `mov` of a temporary into the same
register, as read, is left out (the allocation made it a copy onto itself), and an instruction
co-issued with it stands alone.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

from effects.base.errors import Location, UNKNOWN_LOCATION
from effects.shaders.asm.instructions import COMPARISONS, lookup, rows_named
from effects.shaders.asm.program import (AsmProgram, ConstantDef, Declaration, Instruction,
                                         Operand, RelativeAddress)
from effects.shaders.asm.text import LISTING, canonical_swizzle_text, listing_number, program_lines
from effects.shaders.asm.versions import IDENTITY, VersionRules
from effects.shaders.hlsl.asmcode import Instr, Reg
from effects.shaders.hlsl.parse import HlslError

XYZW = "xyzw"
RGBA = "rgba"


@dataclass
class Code:
    """What a code generator made, allocated: the instructions, their registers, the
    constants it defined and the declarations of what it reads, and the tables the pass
    needs (parameter -> first c# and count, sampler -> s#, int -> i#, bool -> b#)."""

    instrs: list[Instr]
    alloc: dict[int, int]
    source: Callable[[Any, Instr], Operand]      # a generator's source record as an Operand
    defs: dict[int, tuple[float, ...]] = field(default_factory=dict)
    int_defs: dict[int, tuple[int, ...]] = field(default_factory=dict)
    dcls: list[Declaration] = field(default_factory=list)
    sampler_of: dict[str, int] = field(default_factory=dict)     # sampler named by an Instr
    constants: dict[str, tuple[int, int]] = field(default_factory=dict)
    samplers: dict[str, int] = field(default_factory=dict)
    int_registers: dict[str, int] = field(default_factory=dict)
    bool_registers: dict[str, int] = field(default_factory=dict)
    # registers of an int or bool parameter from its first (one per component read:
    # components.py); absent, one
    register_counts: dict[str, int] = field(default_factory=dict)
    letters: str = XYZW                          # how masks are spelt (ps_1_x: rgba)


def register(reg: Reg, alloc: dict[int, int]) -> Operand:
    """A generator's register as an operand: a temporary as its r#, c_rel as c[a0.? + n],
    c_al as c[aL + n]. (Built positionally: one per operand of every compiled instruction.)"""
    kind = reg.kind
    if kind == "vr":
        index = alloc[reg.index]  # type: ignore[index]
        return Operand("r", index, UNKNOWN_LOCATION, _NAMES.get(index) or f"r{index}")
    if kind == "c_rel":
        return Operand("c", reg.index, UNKNOWN_LOCATION, f"c{reg.index}",
                       relative=RelativeAddress("a", 0, reg.lane))
    if kind == "c_al":
        return Operand("c", reg.index, UNKNOWN_LOCATION, f"c{reg.index}",
                       relative=RelativeAddress("aL", 0, 0))
    return Operand(kind, reg.index, UNKNOWN_LOCATION,
                   f"{kind}{'' if reg.index is None else reg.index}")


_NAMES = {k: f"r{k}" for k in range(32)}
_SWIZZLE_TEXT: dict[tuple[int, ...], str] = {}


def swizzled(op: Operand, swizzle: tuple[int, ...], text: str | None = None) -> Operand:
    """`op` reading `swizzle`, spelt `text` (ps_1_x's letters), else in its shortest form."""
    op.swizzle = swizzle = tuple(swizzle)  # type: ignore[assignment]
    if text is None:
        text = _SWIZZLE_TEXT.get(swizzle)
        if text is None:
            text = _SWIZZLE_TEXT[swizzle] = canonical_swizzle_text(swizzle)
    op.swizzle_text = text
    return op


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
        record = instruction(code, ins, rules, entry_loc)
        if _copy_onto_itself(record):
            dropped = True
            continue
        if dropped and record.coissue:
            record.coissue = False         # its pair was the copy left out: alone now
        dropped = False
        record.phase = phase
        prog.instructions.append(record)
        generated_at[id(record)] = ins.location
    return prog, generated_at


def instruction(code: Code, ins: Instr, rules: VersionRules, entry_loc: Location) -> Instruction:
    base, _, suffix = ins.opcode.partition("_")
    comparison = suffix if suffix in COMPARISONS else None
    if not comparison:
        base = ins.opcode
    srcs = [code.source(s, ins) for s in ins.srcs]
    operands: list[Operand] = []
    if ins.dst is not None:
        dst = register(ins.dst, code.alloc)
        mask = tuple(ins.mask)
        if list(mask) != sorted(set(mask)):
            raise HlslError(f"internal: the generated {rules.name} code writes the mask "
                            f"{mask} of {dst.name}", ins.location or entry_loc)
        if mask != (0, 1, 2, 3):
            dst.mask = mask
            dst.swizzle_text = "".join(code.letters[c] for c in mask)
        operands.append(dst)
    info = lookup(base, rules.name)
    if info is None:        # a generator bug: the checks say the version lacks it
        info = next((r for r in rows_named(base) if len(r.operands) ==
                     len(operands) + len(srcs) + (ins.sampler is not None)), None)
        if info is None:
            raise HlslError(f"internal: the generated {rules.name} code uses '{base}'",
                            ins.location or entry_loc)
    if ins.sampler is not None:
        k = code.sampler_of[ins.sampler]
        srcs.insert(1, Operand("s", k, text=f"s{k}"))
    if operands and not info.has_dst:      # ps_2_0's texkill names its register as a source
        srcs.insert(0, swizzled(operands.pop(), IDENTITY, ""))
        srcs[0].mask = None
    loc = ins.location if ins.location.line else entry_loc
    record = Instruction(base, operands[0] if operands else None, srcs, info, loc,
                         shift=ins.shift, saturate=ins.saturate, coissue=ins.coissue,
                         comparison=comparison)
    for op in record.operands:
        op.location = loc
    return record


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
