"""What a `compile` state compiles to (`CompiledShader`), without the compiler: a shader the
compile cache holds (in memory, or on disk for the command line: store.py) is handed out by
cache.compile_state without importing the HLSL front end, its grammar or lark.

`assemble_generated` turns a compiled shader's listing, as the on-disk store keeps it, back into
the located program the compiler's writer (writer.py) made.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from effects.base.errors import AsmError, EffectWarning, Location
from effects.model import ShaderBlock
from effects.shaders.asm import AsmProgram, assemble

if TYPE_CHECKING:  # pragma: no cover
    from effects.shaders.hlsl.types import HType


PRESHADER_NAME = "<preshader {}>"   # a preshader register's name in the constant table:
                                    # never a parameter's (not an identifier)


@dataclass(frozen=True)
class ShaderPreshader:
    """One constant register the host fills before a draw (preshader.preshade_ps1). `steps`
    run in order and the last is the value (`width` floats): ("uniform", name, row, width)
    reads a parameter's register row, ("const", values) a literal, (op, width, args) a DAG op
    on earlier steps, each argument (step, swizzle, negate), computed as the compiler folds
    constants (`dag.fold`; registers.preshader_numbers)."""

    steps: tuple
    width: int

    def uniforms(self) -> set[str]:
        """The parameters (uniform names) it reads."""
        return {step[1] for step in self.steps if step[0] == "uniform"}

    def _width(self, k: int) -> int:
        """How many floats step k makes."""
        step = self.steps[k]
        return step[3] if step[0] == "uniform" else len(step[1]) if step[0] == "const" else step[1]

    def expression(self) -> str:
        """The value as assembly-like text, for listings: `mul(K1, Scale.xxxx)`, `-LightDir`."""
        def text(k: int) -> str:
            step = self.steps[k]
            if step[0] == "const":
                numbers = ", ".join(f"{v:g}" for v in step[1])
                return f"({numbers})" if len(step[1]) > 1 else numbers
            if step[0] == "uniform":
                return step[1] if step[2] == 0 else f"{step[1]}[{step[2]}]"
            args = []
            for index, swizzle, negate in step[2]:
                picked = "" if tuple(swizzle) == tuple(range(self._width(index))) else \
                    "." + "".join("xyzw"[i] for i in swizzle)
                args.append(f"{'-' if negate else ''}{text(index)}{picked}")
            if step[0] == "mov":
                return args[0]
            return f"{step[0]}({', '.join(args)})"
        return text(len(self.steps) - 1)


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
    # constant-table names -> what the host computes into them
    preshaders: dict[str, ShaderPreshader] = field(default_factory=dict)
    # an int or bool parameter's registers from its first, one per component (absent: one)
    register_counts: dict[str, int] = field(default_factory=dict)

    def register_count(self, name: str) -> int:
        return self.register_counts.get(name, 1)

    def sampler_table(self) -> dict[str, tuple[int, int]]:
        """The register table's samplers, name -> (first s#, count): an array's elements
        (`S[1]`) as the array itself, from its first element's register up to the last
        element read, as fxc lists them (`samplers_array` s0 count 2 where the code reads
        samplers_array[1]: tests/data/fxo/wine/test_effect_preshader_effect_blob.fxo)."""
        out: dict[str, tuple[int, int]] = {}
        for name, register in self.samplers.items():
            base, _, index = name[:-1].partition("[") if name.endswith("]") else (name, "", "0")
            k = int(index) if index.isdigit() else 0
            first, count = out.get(base, (register - k, 0))
            out[base] = (first, max(count, k + 1))
        return out

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
    # what only text has (the words as written, the generated line) is left as the writer
    # (writer.py) leaves it, so the program read back is the program compiled
    for ins in program.instructions:
        ins.location = relocate(ins.location)
        ins.opcode_text, ins.source_line = "", None
        for op in ins.operands:
            op.location = ins.location
            op.text = op.name
    for d in program.dcls:
        d.location = entry_loc
        d.register.location = entry_loc
        d.register.text = d.register.name
    for cd in program.def_statements:
        cd.location = entry_loc
        cd.register.location = entry_loc
        cd.register.text = cd.register.name
    program.phase_locations = [entry_loc] * len(program.phase_locations)
    program.location = entry_loc
    program.origin = Location(entry_loc.path, 0, 1)
    program.source_lines = ()
    return program
