"""A shader value as the program it runs: the one place an `asm` block is assembled and an HLSL
`compile` target compiled, for validation, lowering, `effects compile`'s listings and
`effects doctor` alike (`shader_of`).

The answer, `Shader`, also settles the shader's register bindings, the facts validation and
lowering both need: which device sampler each s# the shader samples is (a pixel shader's s#
is sampler s#; a vs_3_0's is the vertex texture sampler D3DVERTEXTEXTURESAMPLER0 + s#, as
D3DX binds it), which sampler parameter the HLSL compiler put there, and the int and bool
registers the compiler gave the parameters a loop counts or an `if` tests. The validator
records the Shader of each pass (`PassReport.shaders`) and lowering binds from it.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Mapping

from effects.base.errors import Location
from effects.model import BytecodeShader, CompileShader, ShaderBlock
from effects.shaders.hlsl.shader import CompiledShader

if TYPE_CHECKING:  # pragma: no cover
    from effects.model import Effect
    from effects.shaders.asm import AsmProgram


@dataclass(frozen=True)
class SamplerBinding:
    """One sampler register of a shader and the device sampler it is."""

    register: int              # s# in the shader (for ps_1_x, the texture stage it samples)
    unit: int                  # the device's sampler: s#, or D3DVERTEXTEXTURESAMPLER0 + s#
    parameter: str | None      # the sampler parameter the HLSL compiler put in s#; None for
                               # assembly (the pass's Sampler[n] / Texture[n] states bind it)
    read_at: Location | None   # the first instruction that samples s# (texld, texldl ...);
                               # None where none names it (ps_1_x reads stages by t#)
    texture: str | None = None  # the texture parameter read through it (`Tex.Sample(S, uv)`
                                # makes the pair `S+Tex` one register): bound on its unit


@dataclass(frozen=True)
class Shader:
    """What a shader value runs: its assembled program, the compiled HLSL shader (register
    table, preshaders, listing text; None for an asm block) and its register bindings."""

    value: Any                                  # the ShaderBlock or CompileShader
    program: "AsmProgram"
    compiled: "CompiledShader | None"
    samplers: tuple[SamplerBinding, ...] = ()   # by register
    int_registers: Mapping[str, int] = field(default_factory=dict)    # parameter -> i#
    bool_registers: Mapping[str, int] = field(default_factory=dict)   # parameter -> b#

    @property
    def kind(self) -> str:
        """'vs' or 'ps'."""
        return self.program.kind


def shader_of(effect: "Effect", value: Any) -> Shader | None:
    """The Shader of an asm block, or of a `compile` state compiled for its target; None for
    any other value (NULL, a parameter reference). Raises the located EffectError of a block
    that does not assemble or a function that does not compile. The assembler's and the
    compiler's caches keep the programs, so asking again costs a lookup."""
    if isinstance(value, BytecodeShader):
        if value._read is None:
            program, compiled = read_bytecode(value)
            value._read = _bound(value, program, compiled)
        return value._read
    if isinstance(value, ShaderBlock):
        from effects.shaders.asm import assemble_cached
        return _bound(value, assemble_cached(value), None)
    if isinstance(value, CompileShader):
        from effects.shaders.hlsl import compile_state
        compiled = compile_state(effect, value)
        _tell(effect, compiled)
        return _bound(value, compiled.program, compiled)
    return None


def _tell(effect: "Effect", compiled: "CompiledShader") -> None:
    """A compile warning the user must see where the effect's load warnings are shown (the
    commands, the viewer): what fxc accepted only in compatibility mode (/Gec). Told once."""
    from effects.shaders.hlsl.lvalues import is_compatibility_warning
    for w in compiled.warnings:
        if is_compatibility_warning(w.message) and w not in effect.warnings:
            effect.warnings.append(w)


def _bound(value: Any, program: "AsmProgram", compiled: "CompiledShader | None") -> Shader:
    from effects.d3d9.states import VERTEX_TEXTURE_SAMPLER0
    base = VERTEX_TEXTURE_SAMPLER0 if program.kind == "vs" else 0
    reads: dict[int, Location] = {}
    for ins in program.instructions:
        # a texture read this version has, its sampler the second source (texld r0, t0, s0)
        if ins.info.is_texture and program.name in ins.info.versions and len(ins.srcs) > 1 \
                and ins.srcs[1].kind == "s":
            reads.setdefault(ins.srcs[1].index, ins.location)
    named = {register: name for name, register in (compiled.samplers if compiled else {}).items()}
    registers = sorted(set(program.stats.samplers_used) | set(reads) | set(named))
    samplers = tuple(_binding(r, base + r, named.get(r), reads.get(r)) for r in registers)
    if compiled is None:
        return Shader(value, program, None, samplers)
    return Shader(value, program, compiled, samplers, dict(compiled.int_registers),
                  dict(compiled.bool_registers))


@dataclass
class PreshadedShader(CompiledShader):
    """A bytecode shader with fxc's constant preshader (its PRES comment): the c# registers
    it writes, computed on the host before each draw (hlsl.registers.constant_values runs it).
    The compile store never holds one: it keeps HLSL results only."""

    fxlc: Any = None


def read_bytecode(value: BytecodeShader) -> tuple["AsmProgram", "CompiledShader | None"]:
    """A bytecode shader's program, and (where its constant table names parameters, as fxc's
    and our compiler's do) a CompiledShader carrying those bindings, so its parameters load
    into their registers and its samplers bind as a compiled HLSL shader's do. Errors are
    located in the file the bytecode came from (its byte offset there)."""
    from effects.base.errors import EffectError
    from effects.shaders.d3dbc import BytecodeError, read_shader
    from effects.shaders.asm.text import program_text
    start = value.location.column - 1 if value.location.line == 1 else 0
    if value.version == "vs_3_sw":
        # Direct3D 9 creates a vs_3_sw shader only on a device that processes vertices in
        # software (D3DCREATE_SOFTWARE_VERTEXPROCESSING); D3DX loaded such an effect and its
        # ValidateTechnique failed on a hardware device. No simulated card is a software device.
        raise BytecodeError("a vs_3_sw shader (version token 0xFFFE03FF) runs only on a device "
                            "created for software vertex processing, which no simulated card "
                            f"is (at byte {start})", Location(value.location.path, 1, start + 1))
    try:
        binary = read_shader(value.data, value.location.path)
    except EffectError as err:
        column = err.location.column + start
        raise type(err)(err.message.replace(f"(at byte {err.location.column - 1})",
                                            f"(at byte {column - 1})"),
                        Location(value.location.path, 1, column)) from None
    program, table = binary.program, binary.table
    pres = None
    for at, code, body in binary.comments:
        if code == "PRES" and pres is None:
            # fxc's preshader (a PRES comment: FXLC code, CLIT literals, its own CTAB) fills
            # constant registers on the host before each draw, as D3DX ran it
            from effects.shaders.fxlc import decode_bytes
            pres = decode_bytes(body[4:], start + at + 8, value.location.path)
    if (table is None or not table.constants) and pres is None:
        return program, None
    constants: dict[str, tuple[int, int]] = {}
    samplers: dict[str, int] = {}
    ints: dict[str, int] = {}
    bools: dict[str, int] = {}
    counts: dict[str, int] = {}          # an int or bool parameter's registers, one a component
    types: dict = {}
    for c in table.constants if table is not None else ():
        if c.register_set == "sampler":
            samplers[c.name] = c.register_index
            continue
        htype = _htype(c.type)
        if htype is not None:
            types[c.name] = htype
        if c.register_set == "float4":
            constants[c.name] = (c.register_index, c.register_count)
        elif c.register_set == "int4":
            ints[c.name] = c.register_index
            counts[c.name] = c.register_count
        elif c.register_set == "bool":
            bools[c.name] = c.register_index
            counts[c.name] = c.register_count
    text = program_text(program)
    made = CompiledShader if pres is None else PreshadedShader
    compiled = made("<bytecode>", program.name, text, program, constants, samplers,
                    [value.location] * (text.count("\n") + 1), types=types, int_registers=ints,
                    bool_registers=bools, register_counts=counts)
    if pres is not None:
        compiled.fxlc = pres
    return program, compiled


def _htype(t: Any) -> Any:
    """The HLSL type (effects/shaders/hlsl/types.py) of a constant table's type info."""
    from effects.shaders.d3dbc.ctab import (MATRIX_COLUMNS, MATRIX_ROWS, PARAMETER_TYPES,
                                            SCALAR, STRUCT, VECTOR)
    from effects.shaders.hlsl.types import HType
    if t.cls == STRUCT:
        fields = []
        for name, member in t.members:
            inner = _htype(member)
            if inner is None:
                return None
            fields.append((name, inner, None))
        one = HType("struct", name="struct", fields=tuple(fields))
    elif t.cls in (SCALAR, VECTOR, MATRIX_ROWS, MATRIX_COLUMNS):
        base = PARAMETER_TYPES[t.type] if t.type < len(PARAMETER_TYPES) else "float"
        base = base if base in ("float", "int", "bool") else "float"
        kind = "scalar" if t.cls == SCALAR else "vector" if t.cls == VECTOR else "matrix"
        one = HType(kind, base, t.rows, t.columns, row_major=t.cls == MATRIX_ROWS)
    else:
        return None
    if t.elements > 1:
        return HType("array", one.base, element=one, length=t.elements)
    return one


def _binding(register: int, unit: int, name: str | None, read_at: Location | None
             ) -> SamplerBinding:
    """The binding of s#, whose compiled name is a sampler parameter's or a pair's
    (`S+Tex`: sampler S's states, texture Tex's picture)."""
    if name is not None and "+" in name:
        sampler, texture = name.split("+", 1)
        return SamplerBinding(register, unit, sampler, read_at, texture)
    return SamplerBinding(register, unit, name, read_at)
