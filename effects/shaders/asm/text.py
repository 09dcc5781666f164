"""An AsmProgram as assembly text that the assembler (parser.py) reads back to an equal
program: what the bytecode disassembler prints (effects/shaders/d3dbc), in fxc's spelling
(`dcl_texcoord v0`, `c[a0.x + 5]`, `(!p0.x) add`, `+mov`, `texld_pp`)."""
from __future__ import annotations

import struct

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


def program_text(program: AsmProgram) -> str:
    """The program as assembly, one statement a line, the version first."""
    lines = [program.name]
    lines += [constant_text(d) for d in program.def_statements if not d.after_code]
    lines += [declaration_text(d) for d in program.dcls if not d.after_code and not d.from_decl]
    phases = len(program.phase_locations)
    for ins in program.instructions:
        if phases and ins.phase == 2:
            lines += ["phase"] * phases
            phases = 0
        lines.append(instruction_text(ins))
    lines += ["phase"] * phases
    lines += [constant_text(d) for d in program.def_statements if d.after_code]
    lines += [declaration_text(d) for d in program.dcls if d.after_code and not d.from_decl]
    return "\n".join(lines) + "\n"


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


def constant_text(d: ConstantDef) -> str:
    reg = d.register
    if reg.kind == "i":
        return f"defi {reg.name}, " + ", ".join(str(int(v)) for v in d.values)
    if reg.kind == "b":
        return f"defb {reg.name}, {'true' if d.values and d.values[0] else 'false'}"
    return f"def {reg.name}, " + ", ".join(_number(v) for v in d.values)


def declaration_text(d: Declaration) -> str:
    word = "dcl"
    if d.sampler_type:
        word += f"_{d.sampler_type}"
    elif d.usage:
        word += f"_{d.usage}{d.usage_index or ''}"
    word += "_pp" * d.partial_precision + "_centroid" * d.centroid
    return f"{word} {operand_text(d.register, dst=True)}"


def instruction_text(ins: Instruction) -> str:
    word = ins.opcode + (f"_{ins.comparison}" if ins.comparison else "")
    word += ("_sat" * ins.saturate + "_pp" * ins.partial_precision
             + "_centroid" * ins.centroid + _SHIFT_NAMES.get(ins.shift, ""))
    if ins.predicate is not None:
        word = f"({operand_text(ins.predicate)}) {word}"
    if ins.coissue:
        word = "+" + word
    ops = ([operand_text(ins.dst, dst=True)] if ins.dst is not None else [])
    ops += [operand_text(s) for s in ins.srcs]
    return word + (" " + ", ".join(ops) if ops else "")


def operand_text(op: Operand, dst: bool = False) -> str:
    if op.kind == "imm":
        return op.text
    if op.relative is not None:
        rel = op.relative
        address = "aL" if rel.kind == "aL" else f"a{rel.index}.{'xyzw'[rel.component]}"
        offset = f" + {op.index}" if op.index else ""
        reg = f"{op.kind}{'_' + op.modifier if op.modifier and op.modifier != 'invert' else ''}" \
              f"[{address}{offset}]"
    else:
        reg = op.name + (f"_{op.modifier}" if op.modifier and op.modifier != "invert" else "")
    if dst:
        return reg + (f".{op.mask_text}" if op.mask is not None else "")
    swizzle = canonical_swizzle_text(op.swizzle)
    prefix = "1-" if op.modifier == "invert" else ("!" if op.negate and op.kind in "bp" else
                                                   "-" if op.negate else "")
    return prefix + reg + (f".{swizzle}" if swizzle else "")
