"""What a `compile` state compiles to (`CompiledShader`), without the compiler: a shader the
compile cache holds (in memory, or on disk for the command line: store.py) is handed out by
cache.compile_state without importing the HLSL front end, its grammar or lark.

`assemble_generated` turns the generated assembly into the located program; the compiler and
the on-disk store both call it, so a stored shader's program is made by the same code as a
fresh compile's.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from effects.errors import AsmError, EffectWarning, Location
from effects.model import ShaderBlock
from effects.shaders.asm import AsmProgram, assemble

if TYPE_CHECKING:  # pragma: no cover
    from effects.shaders.hlsl.types import HType


@dataclass
class CompiledShader:
    function: str
    target: str
    text: str
    program: AsmProgram
    constants: dict[str, tuple[int, int]]
    samplers: dict[str, int]
    lines: list[Location]                       # per line of `text`
    warnings: list[EffectWarning] = field(default_factory=list)
    types: dict[str, "HType"] = field(default_factory=dict)
    int_registers: dict[str, int] = field(default_factory=dict)
    bool_registers: dict[str, int] = field(default_factory=dict)

    @property
    def stage(self) -> str:
        return "vertex" if self.target.startswith("vs") else "pixel"


def assemble_generated(text: str, target: str, entry: str, lines: list[str],
                       locations: list[Location | None], entry_loc: Location) -> AsmProgram:
    """The generated assembly `text` for `target` assembled, each instruction located at the
    HLSL line it comes from (`locations`, per line of the text; the entry point's definition,
    `entry_loc`, for lines without one and for declarations). An assembler error here is a
    code generator bug, reported as such."""
    block = ShaderBlock("vertex" if target.startswith("vs") else "pixel", target, text,
                        location=Location(f"<{entry}:{target}>", 1, 1))
    try:
        program = assemble(block)
    except AsmError as err:   # a code generator bug: say where it came from
        from effects.shaders.hlsl.parse import HlslError
        k = err.location.line - 1
        found = locations[k] if 0 <= k < len(locations) else None
        loc = found if found is not None and found.line else entry_loc
        raise HlslError(f"internal: the generated {target} code does not assemble: "
                        f"{err.message} ({lines[k] if 0 <= k < len(lines) else ''})", loc) from None

    def relocate(loc: Location) -> Location:
        k = loc.line - 1
        found = locations[k] if 0 <= k < len(locations) else None
        return found if found is not None and found.line else entry_loc
    for ins in program.instructions:
        ins.location = relocate(ins.location)
        for op in ins.operands:
            op.location = ins.location
    for d in program.dcls:
        d.location = entry_loc
        d.register.location = entry_loc
    for cd in program.def_statements:
        cd.location = entry_loc
        cd.register.location = entry_loc
    program.location = entry_loc
    program.origin = Location(entry_loc.path, 0, 1)
    program.source_lines = ()
    return program
