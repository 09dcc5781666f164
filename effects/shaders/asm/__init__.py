"""Direct3D shader assembly (vs_1_1–vs_3_0, ps_1_0–ps_3_0): parse, table, validate.

    program = assemble(block)        # AsmError at the first syntax error
    errors = check(program)          # every rule of the version the program breaks
    program.stats                    # slots, registers, dependent-read depth ... for the caps

`INSTRUCTIONS` is the per-instruction table (instructions.py) and `VERSIONS` the per-version
limits (versions.py); the lowering reads `Instruction.info` to know what each one computes.
"""
from effects.shaders.asm.check import check, check_cached
from effects.shaders.asm.instructions import TABLE as INSTRUCTIONS
from effects.shaders.asm.instructions import InstrInfo, lookup
from effects.shaders.asm.limits import assemble_cached, card_limit_violations
from effects.shaders.asm.parser import NOT_ASSEMBLY, assemble
from effects.shaders.asm.program import AsmProgram, ConstantDef, Declaration, Instruction, Operand, RelativeAddress
from effects.shaders.asm.stats import AsmStats
from effects.shaders.asm.versions import VERSIONS, VersionRules, canonical_version

__all__ = [
    "AsmProgram", "AsmStats", "ConstantDef", "Declaration", "INSTRUCTIONS", "InstrInfo",
    "Instruction", "NOT_ASSEMBLY", "Operand", "RelativeAddress", "VERSIONS", "VersionRules",
    "assemble", "assemble_cached", "canonical_version", "card_limit_violations", "check",
    "check_cached", "lookup",
]
