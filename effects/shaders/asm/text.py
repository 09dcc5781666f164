"""An AsmProgram as assembly text that the assembler (parser.py) reads back to an equal
program: what the bytecode disassembler prints (effects/shaders/d3dbc), in fxc's spelling
(`dcl_texcoord v0`, `c[a0.x + 5]`, `(!p0.x) add`, `+mov`, `texld_pp`), and the HLSL
compiler's listing (`Spelling` LISTING: `def` numbers to nine digits, `c5[aL]`, `mul_x4_sat`). A swizzle or
mask is printed as the operand spells it (`swizzle_text`, ps_1_x's `.rgb` and `.a`), else in
its shortest form.
"""
from __future__ import annotations

import struct
from dataclasses import dataclass
from typing import Callable, Iterator

from effects.shaders.asm.program import (COMPONENTS, AsmProgram, ConstantDef, Declaration,
                                         Instruction, Operand)
from effects.shaders.asm.versions import IDENTITY

_SHIFT_NAMES = {1: "_x2", 2: "_x4", 3: "_x8", -1: "_d2", -2: "_d4", -3: "_d8"}


def canonical_swizzle_text(swizzle: tuple[int, ...]) -> str:
    """The shortest letters the assembler reads as `swizzle` ('' for .xyzw, 'w' for .wwww)."""
    if tuple(swizzle) == IDENTITY:
        return ""
    n = 4
    while n > 1 and swizzle[n - 1] == swizzle[n - 2]:
        n -= 1
    return "".join(COMPONENTS[c] for c in swizzle[:n])


@dataclass(frozen=True)
class Spelling:
    """How numbers and aL-relative registers are written: the disassembler's way (the
    shortest float32 decimal, `c[aL + 5]`) or the HLSL compiler's listing (`LISTING`)."""

    number: Callable[[float], str]
    al_first: bool = False             # c5[aL] rather than c[aL + 5]
    shift_first: bool = False          # mul_x4_sat rather than mul_sat_x4


def listing_number(value: float) -> str:
    """A def number as the HLSL compiler's listing writes it: a whole number as one, else
    nine significant digits (enough for any float32; fxc's listings print `%g` to nine)."""
    value = float(value)
    if abs(value) < 1e7 and value == int(value):   # never inf or NaN in compiled code
        return f"{int(value)}"
    return f"{value:.9g}"


def program_lines(program: AsmProgram, spelling: "Spelling | None" = None
                  ) -> Iterator[tuple[str, Instruction | None]]:
    """The program as assembly, one statement a line, the version first, each line with the
    instruction it writes (None for the version, defs, declarations and `phase`)."""
    sp = spelling or DISASSEMBLY
    yield program.name, None
    for d in program.def_statements:
        if not d.after_code:
            yield constant_text(d, sp), None
    for dcl in program.dcls:
        if not dcl.after_code and not dcl.from_decl:
            yield declaration_text(dcl), None
    phases = len(program.phase_locations)
    for ins in program.instructions:
        if phases and ins.phase == 2:
            for _ in range(phases):
                yield "phase", None
            phases = 0
        yield instruction_text(ins, sp), ins
    for _ in range(phases):
        yield "phase", None
    for d in program.def_statements:
        if d.after_code:
            yield constant_text(d, sp), None
    for dcl in program.dcls:
        if dcl.after_code and not dcl.from_decl:
            yield declaration_text(dcl), None


def program_text(program: AsmProgram, spelling: "Spelling | None" = None) -> str:
    """The program as assembly, one statement a line, the version first."""
    return "\n".join(line for line, _ in program_lines(program, spelling)) + "\n"


def _number(value: float) -> str:
    """The shortest decimal that is the same float32 (0.8, not 0.800000011920929): a def
    register holds a float32, so that is all the text must keep."""
    value = float(value)
    if value != value or value in (float("inf"), float("-inf")):
        return repr(value)
    try:
        bits = struct.pack("<f", value)
    except OverflowError:
        return repr(value)
    for digits in range(1, 18):
        text = f"{value:.{digits}g}"
        if struct.pack("<f", float(text)) == bits:
            break
    return text


DISASSEMBLY = Spelling(_number)
LISTING = Spelling(listing_number, al_first=True, shift_first=True)


def constant_text(d: ConstantDef, spelling: Spelling = DISASSEMBLY) -> str:
    reg = d.register
    if reg.kind == "i":
        return f"defi {reg.name}, " + ", ".join(str(int(v)) for v in d.values)
    if reg.kind == "b":
        return f"defb {reg.name}, {'true' if d.values and d.values[0] else 'false'}"
    return f"def {reg.name}, " + ", ".join(spelling.number(v) for v in d.values)


def declaration_text(d: Declaration) -> str:
    word = "dcl"
    if d.sampler_type:
        word += f"_{d.sampler_type}"
    elif d.usage:
        word += f"_{d.usage}{d.usage_index or ''}"
    word += "_pp" * d.partial_precision + "_centroid" * d.centroid
    return f"{word} {operand_text(d.register, dst=True)}"


def instruction_text(ins: Instruction, spelling: Spelling = DISASSEMBLY) -> str:
    word = ins.opcode + (f"_{ins.comparison}" if ins.comparison else "")
    shift = _SHIFT_NAMES.get(ins.shift, "")
    word += (shift * spelling.shift_first + "_sat" * ins.saturate + "_pp" * ins.partial_precision
             + "_centroid" * ins.centroid + shift * (not spelling.shift_first))
    if ins.predicate is not None:
        word = f"({operand_text(ins.predicate, spelling=spelling)}) {word}"
    if ins.coissue:
        word = "+" + word
    ops = ([operand_text(ins.dst, dst=True, spelling=spelling)] if ins.dst is not None else [])
    ops += [operand_text(s, spelling=spelling) for s in ins.srcs]
    return word + (" " + ", ".join(ops) if ops else "")


def operand_text(op: Operand, dst: bool = False, spelling: Spelling = DISASSEMBLY) -> str:
    if op.kind == "imm":
        return op.text
    if op.relative is not None:
        rel = op.relative
        mod = f"_{op.modifier}" if op.modifier and op.modifier != "invert" else ""
        if rel.kind == "aL" and spelling.al_first:
            reg = f"{op.kind}{op.index or 0}{mod}[aL]"
        else:
            address = "aL" if rel.kind == "aL" else f"a{rel.index}.{'xyzw'[rel.component]}"
            offset = f" + {op.index}" if op.index else ""
            reg = f"{op.kind}{mod}[{address}{offset}]"
    else:
        reg = op.name + (f"_{op.modifier}" if op.modifier and op.modifier != "invert" else "")
    if dst:
        return reg + (f".{op.swizzle_text or op.mask_text}" if op.mask is not None else "")
    swizzle = op.swizzle_text or canonical_swizzle_text(op.swizzle)
    prefix = "1-" if op.modifier == "invert" else ("!" if op.negate and op.kind in "bp" else
                                                   "-" if op.negate else "")
    return prefix + reg + (f".{swizzle}" if swizzle else "")
