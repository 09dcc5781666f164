"""An AsmProgram as Direct3D 9 shader bytecode (the token stream D3D9's CreatePixelShader /
CreateVertexShader take, and fxc /Fo writes).

The stream: the version token; the comments (the 'CTAB' constant table first, as fxc writes
it); the `def`/`defi`/`defb` constants, the declarations and the instructions in program order
(ps_1_4's `phase` token before the first phase-2 instruction); the end token. From 2_0 on an
instruction token counts the tokens after it; 1_x tokens do not (the reader knows each
instruction's operands). Field numbers: tokens.py.
"""
from __future__ import annotations

import struct
from typing import TYPE_CHECKING, Any, Iterable

from effects.base.errors import EffectError
from effects.shaders.asm.instructions import rows_named
from effects.shaders.asm.program import AsmProgram, Declaration, Instruction, Operand
from effects.shaders.asm.versions import IDENTITY
from effects.shaders.d3dbc import tokens as tk
from effects.shaders.d3dbc.ctab import (MATRIX_COLUMNS, MATRIX_ROWS, OBJECT, PARAMETER_TYPES,
                                        SCALAR, STRUCT, VECTOR, ConstantInfo, ConstantTable,
                                        TypeInfo, write_ctab)

if TYPE_CHECKING:  # pragma: no cover
    from effects.shaders.hlsl.shader import CompiledShader


class EncodeError(EffectError):
    """A program the token format cannot express (a modifier pair no token holds ...)."""


def version_token(program: AsmProgram) -> int:
    base = tk.VS_VERSION if program.kind == "vs" else tk.PS_VERSION
    return base | program.version[0] << 8 | program.version[1]


def comment(body: bytes) -> list[int]:
    """A comment token and its DWORDs (the body padded to whole DWORDs)."""
    body += b"\0" * (-len(body) % 4)
    n = len(body) // 4
    if n > tk.COMMENT_MASK:
        raise EncodeError(f"a comment of {n} DWORDs; a comment holds at most {tk.COMMENT_MASK}")
    return [tk.COMMENT | n << tk.COMMENT_SHIFT, *struct.unpack(f"<{n}I", body)]


def write_program(program: AsmProgram, table: ConstantTable | None = None,
                  comments: Iterable[bytes] = ()) -> bytes:
    """The bytecode of `program`: `table` as its 'CTAB' comment (None: none), then `comments`
    (each a comment's bytes, its four-character code first). Raises EncodeError (located at
    the operand or instruction) for what the format cannot hold."""
    return _Writer(program).tokens(table, comments)


class _Writer:
    def __init__(self, program: AsmProgram) -> None:
        self.p = program
        self.major = program.version[0]
        self.types = tk.kind_types(program.kind, self.major)
        self.out: list[int] = []

    def tokens(self, table: ConstantTable | None, comments: Iterable[bytes]) -> bytes:
        p = self.p
        self.out.append(version_token(p))
        if table is not None:
            self.out += comment(struct.pack("<I", tk.fourcc("CTAB")) + write_ctab(table))
        for body in comments:
            self.out += comment(body)
        for d in p.def_statements:
            if not d.after_code:
                self._def(d)
        for dcl in p.dcls:
            if not dcl.after_code and not dcl.from_decl:
                self._dcl(dcl)
        phases = len(p.phase_locations)
        for ins in p.instructions:
            if phases and ins.phase == 2:
                self.out += [tk.PHASE] * phases
                phases = 0
            self._instruction(ins)
        self.out += [tk.PHASE] * phases
        for d in p.def_statements:
            if d.after_code:
                self._def(d)
        for dcl in p.dcls:
            if dcl.after_code and not dcl.from_decl:
                self._dcl(dcl)
        self.out.append(tk.END)
        return struct.pack(f"<{len(self.out)}I", *self.out)

    # -- instructions ----------------------------------------------------------------------
    def _emit(self, code: int, params: list[int], where: Any, *, control: int = 0,
              predicated: bool = False, coissue: bool = False) -> None:
        token = code | control << tk.CONTROL_SHIFT
        if self.major >= 2:
            if len(params) > tk.LENGTH_MASK:
                raise EncodeError(f"an instruction of {len(params)} tokens; the length field "
                                  f"holds at most {tk.LENGTH_MASK}", where.location)
            token |= len(params) << tk.LENGTH_SHIFT
        if predicated:
            token |= tk.PREDICATED
        if coissue:
            token |= tk.COISSUE
        self.out.append(token)
        self.out += params

    def _instruction(self, ins: Instruction) -> None:
        info = ins.info
        code, control = info.code, info.control
        if ins.comparison:
            control = tk.COMPARISONS[ins.comparison]
            if info.compare_code is not None:
                code = info.compare_code
        params: list[int] = []
        if ins.dst is not None:
            params += self._dst(ins.dst, ins.saturate, ins.partial_precision, ins.centroid,
                                ins.shift, info.writes)
        elif ins.saturate or ins.partial_precision or ins.centroid or ins.shift:
            raise EncodeError(f"{ins.opcode} has no destination to carry its modifiers",
                              ins.location)
        if ins.predicate is not None:
            if self.major < 2:
                raise EncodeError("predication needs version 2_0 or later", ins.location)
            params += self._src(ins.predicate)
        if info.name == "texkill" and ins.dst is None:
            params += self._killed(ins.srcs[0])
        else:
            params += [t for src in ins.srcs for t in self._src(src)]
        if ins.coissue and not (self.p.kind == "ps" and self.major == 1):
            raise EncodeError("co-issue (+) exists in ps_1_x only", ins.location)
        self._emit(code, params, ins, control=control, predicated=ins.predicate is not None,
                   coissue=ins.coissue)

    def _def(self, d: Any) -> None:
        reg = d.register
        base = {"c": "def", "i": "defi", "b": "defb"}.get(reg.kind)
        if base is None:
            raise EncodeError(f"a constant definition of {reg.name}", d.location)
        code = rows_named(base)[0].code
        params = self._dst(reg, False, False, False, 0)
        if base == "def":
            params += struct.unpack("<4I", struct.pack("<4f", *_four(d.values, 0.0)))
        elif base == "defi":
            params += [v & 0xFFFFFFFF for v in _four([int(v) for v in d.values], 0)]
        else:
            params.append(1 if d.values and d.values[0] else 0)
        self._emit(code, params, d)

    def _dcl(self, dcl: Declaration) -> None:
        reg = dcl.register
        if reg.kind == "s":
            token = tk.PARAM | tk.SAMPLER_TYPES.get(dcl.sampler_type or "", 0) << tk.SAMPLER_TYPE_SHIFT
        else:
            usage = tk.USAGES.index(dcl.usage) if dcl.usage else 0
            token = tk.PARAM | usage | dcl.usage_index << tk.USAGE_INDEX_SHIFT
        self._emit(rows_named("dcl")[0].code,
                   [token, *self._dst(reg, False, dcl.partial_precision, dcl.centroid, 0)], dcl)

    # -- parameters -------------------------------------------------------------------------
    def _register(self, op: Operand) -> int:
        rtype = self.types.get(op.kind)
        if rtype is None:
            raise EncodeError(f"{op.name} is no register of a {self.p.name} token", op.location)
        index = op.index or 0
        if op.kind in tk.RASTOUT_KINDS:
            index = tk.RASTOUT_KINDS.index(op.kind)
        elif op.kind in tk.MISC_KINDS:
            index = tk.MISC_KINDS.index(op.kind)
        elif op.kind == "c" and index >= tk.CONST_BANK_SIZE:
            bank = index // tk.CONST_BANK_SIZE
            if bank >= len(tk.CONST_BANKS):
                raise EncodeError(f"c{index} is past the last constant bank (c8191)", op.location)
            rtype, index = tk.CONST_BANKS[bank], index % tk.CONST_BANK_SIZE
        if not 0 <= index <= tk.REG_NUMBER_MASK:
            raise EncodeError(f"register number {index} does not fit a token (0-2047)", op.location)
        return tk.PARAM | tk.register_bits(rtype) | index

    def _relative(self, op: Operand) -> list[int]:
        rel = op.relative
        if rel is None:
            return []
        if self.p.kind == "vs" and self.major == 1:
            if (rel.kind, rel.component) != ("a", 0):
                raise EncodeError("vs_1_1 addresses relative to a0.x only", op.location)
            return []          # bit 13 alone: a0.x is implied, no address token
        if self.p.kind == "ps" and self.major < 3:
            raise EncodeError(f"{self.p.name} has no relative addressing", op.location)
        if rel.kind == "aL":     # a scalar: the identity swizzle (as MojoShader writes it)
            return [tk.PARAM | tk.register_bits(tk.LOOP) | 0xE4 << tk.SWIZZLE_SHIFT]
        return [tk.PARAM | tk.register_bits(tk.ADDR_TEXTURE) | rel.index
                | (rel.component * 0x55) << tk.SWIZZLE_SHIFT]

    def _dst(self, op: Operand, sat: bool, pp: bool, centroid: bool, shift: int,
             writes: str = "") -> list[int]:
        if op.kind == "imm":
            raise EncodeError(f"a number ({op.text}) where a register belongs", op.location)
        mask = 0xF if op.mask is None else sum(1 << c for c in op.mask)
        if op.mask is None and writes:   # m3x3 r0: D3DX writes the .xyz the matrix macro fixes
            mask = sum(1 << "xyzw".index(c) for c in writes)
        token = (self._register(op) | mask << tk.WRITEMASK_SHIFT
                 | (sat * tk.SATURATE | pp * tk.PARTIAL_PRECISION | centroid * tk.CENTROID)
                 << tk.RESULT_SHIFT | tk.shift_bits(shift) << tk.DSTSHIFT_SHIFT)
        rel = self._relative(op)
        return [token | (tk.RELATIVE if op.relative else 0), *rel]

    def _killed(self, op: Operand) -> list[int]:
        """ps_2_0+ `texkill src`: its register is a destination token (all four components),
        as in ps_1_x (MojoShader, Wine and vkd3d-shader read one)."""
        if op.swizzle != IDENTITY or op.negate or op.modifier or op.kind == "imm":
            raise EncodeError("texkill's register is a destination token: no swizzle or "
                              f"modifier fits it ({op.text or op.name})", op.location)
        return self._dst(op, False, False, False, 0)

    def _src(self, op: Operand) -> list[int]:
        if op.kind == "imm":
            raise EncodeError(f"a number ({op.text}) where a register belongs", op.location)
        if op.negate and op.kind in ("b", "p") and op.modifier is None:
            mod = tk.SRCMOD_NOT
        else:
            mod = tk.SRCMODS.get((op.modifier, op.negate))
            if mod is None:
                raise EncodeError(f"no source token holds {'-' if op.negate else ''}"
                                  f"_{op.modifier} together ({op.text or op.name})", op.location)
        swizzle = sum(c << (2 * i) for i, c in enumerate(op.swizzle))
        token = (self._register(op) | swizzle << tk.SWIZZLE_SHIFT | mod << tk.SRCMOD_SHIFT
                 | (tk.RELATIVE if op.relative else 0))
        return [token, *self._relative(op)]


def _four(values: Any, fill: Any) -> list:
    out = list(values)[:4]
    return out + [fill] * (4 - len(out))


# -- the constant table of a compiled shader ------------------------------------------------
def constant_table(program: AsmProgram, compiled: "CompiledShader | None" = None) -> ConstantTable:
    """The 'CTAB' fxc writes for a shader: the compiled HLSL's parameters with their registers
    and types (none for assembly), and the target, which names 2_a / 2_b where the version token
    says only 2_x."""
    constants: list[ConstantInfo] = []
    if compiled is not None:
        for name, (register, size) in compiled.constants.items():
            constants.append(ConstantInfo(name, "float4", register, size,
                                          _type_info(compiled.types.get(name), "float")))
        # an int or bool parameter: a register per component, up to the last read
        for name, register in compiled.int_registers.items():
            constants.append(ConstantInfo(name, "int4", register, compiled.register_count(name),
                                          _type_info(compiled.types.get(name), "int")))
        for name, register in compiled.bool_registers.items():
            constants.append(ConstantInfo(name, "bool", register, compiled.register_count(name),
                                          _type_info(compiled.types.get(name), "bool")))
        for name, (register, count) in compiled.sampler_table().items():
            dcl = program.declaration("s", register + count - 1)
            kind = {"cube": "samplerCUBE", "volume": "sampler3D", "2d": "sampler2D"}.get(
                (dcl.sampler_type if dcl else None) or "", "sampler")
            htype = compiled.types.get(name)
            elements = htype.length if htype is not None and htype.kind == "array" else count
            constants.append(ConstantInfo(name, "sampler", register, count,
                                          TypeInfo(OBJECT, PARAMETER_TYPES.index(kind),
                                                   elements=elements)))
    # fxc lists them by name
    constants.sort(key=lambda c: c.name)
    return ConstantTable(tuple(constants), program.name, version_token(program))


def _type_info(htype: Any, base: str) -> TypeInfo:
    """D3DXSHADER_TYPEINFO of an HLSL type (effects/shaders/hlsl/types.py HType)."""
    if htype is None:
        return TypeInfo(VECTOR, PARAMETER_TYPES.index(base), 1, 4)
    elements = 1
    while htype.kind == "array" and htype.element is not None:
        elements *= max(1, htype.length)
        htype = htype.element
    if htype.kind == "struct":
        members = tuple((name, _type_info(t, base)) for name, t, _ in htype.fields)
        return TypeInfo(STRUCT, 0, 1, sum(m.rows * m.columns * m.elements for _, m in members),
                        elements, members)
    numeric = {"float": "float", "half": "float", "double": "float", "int": "int",
               "uint": "int", "bool": "bool"}.get(htype.base, base)
    cls = {"scalar": SCALAR, "vector": VECTOR}.get(htype.kind)
    if cls is None:
        cls = MATRIX_ROWS if htype.row_major else MATRIX_COLUMNS
    return TypeInfo(cls, PARAMETER_TYPES.index(numeric), htype.rows, htype.cols, elements)
