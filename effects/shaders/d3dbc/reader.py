"""Direct3D 9 shader bytecode read into the AsmProgram the assembler gives for the same
shader, so a compiled shader is checked per card, listed and lowered like assembly.

Untrusted input: every token is bounds-checked before it is used; a bad stream (truncated,
wrong instruction lengths, unknown opcodes, registers the version does not have) is a
`BytecodeError` located at the offending token's byte offset (line 1, the offset as the
column, byte 0 being column 1), and the whole stream is first held against the `bytecode_bytes` limit
(effects/base/limits.py). The token fields: tokens.py; the opcodes: the instruction table.
"""
from __future__ import annotations

import struct
from dataclasses import dataclass, field

from effects.base import limits
from effects.base.errors import EffectError, Location
from effects.shaders.asm.instructions import by_code, rows_named
from effects.shaders.asm.program import (COMPONENTS, AsmProgram, ConstantDef, Declaration,
                                         Instruction, Operand, RelativeAddress)
from effects.shaders.asm.text import canonical_swizzle_text
from effects.shaders.asm.versions import VERSIONS, VersionRules
from effects.shaders.d3dbc import tokens as tk
from effects.shaders.d3dbc.ctab import ConstantTable, read_ctab

_COMPARING_CODES = {rows_named("if")[0].compare_code, rows_named("break")[0].compare_code,
                    rows_named("setp")[0].code}
_DEF_CODES = {rows_named(n)[0].code: n for n in ("def", "defi", "defb")}
_DCL = rows_named("dcl")[0].code


class BytecodeError(EffectError):
    """Shader bytecode that is not a valid token stream."""


@dataclass
class ShaderBinary:
    """A read shader: its program, its constant table (None when it has none) and its other
    comments as (byte offset, four-character code, bytes)."""

    program: AsmProgram
    table: ConstantTable | None = None
    comments: list[tuple[int, str, bytes]] = field(default_factory=list)


def version_names(kind: str, major: int, minor: int) -> list[str]:
    """The versions a version token may stand for: 2_x, 2_a and 2_b share 2.1."""
    return [v.name for v in VERSIONS.values()
            if (v.kind, v.major, v.minor) == (kind, major, minor)]


def read_shader(data: bytes, path: str = "<bytecode>") -> ShaderBinary:
    """Read shader bytecode. Raises BytecodeError (located by byte offset)."""
    limits.check("bytecode_bytes", len(data), Location(path, 1, 1), "the shader bytecode",
                 BytecodeError)
    return _Reader(bytes(data), path).read()


class _Reader:
    def __init__(self, data: bytes, path: str) -> None:
        self.data, self.path = data, path
        self.n = len(data) // 4
        self.words = struct.unpack(f"<{self.n}I", data[:self.n * 4])
        self.pos = 0

    def loc(self, word: int) -> Location:
        """Line 1, the token's byte offset as the column (1-based, as columns are: byte 0 is
        column 1)."""
        return Location(self.path, 1, 4 * word + 1)

    def fail(self, message: str, word: int) -> BytecodeError:
        return BytecodeError(f"{message} (at byte {4 * word})", self.loc(word))

    def word(self, what: str) -> int:
        if self.pos >= self.n:
            raise self.fail(f"the bytecode ends where {what} belongs (no end token)", self.pos)
        self.pos += 1
        return self.words[self.pos - 1]

    # -- the stream -------------------------------------------------------------------------
    def read(self) -> ShaderBinary:
        if len(self.data) % 4:
            raise self.fail(f"{len(self.data)} bytes is not a whole number of 4-byte tokens",
                            self.n)
        version = self.word("the version token")
        kind = {tk.VS_VERSION >> 16: "vs", tk.PS_VERSION >> 16: "ps"}.get(version >> 16)
        major, minor = version >> 8 & 0xFF, version & 0xFF
        names = version_names(kind, major, minor) if kind else []
        if not names:
            raise self.fail(f"not a Direct3D 9 shader: version token 0x{version:08X} is none "
                            "of vs_1_1-vs_3_0, ps_1_0-ps_3_0", 0)
        self.kind, self.major, self.minor = kind, major, minor
        self.names = names
        self.binary = ShaderBinary(program=None)  # type: ignore[arg-type]
        self.program: AsmProgram | None = None
        self.phase_at: int | None = None
        while True:
            at = self.pos
            token = self.word("an instruction")
            if token == tk.END:
                break
            opcode = token & tk.OPCODE_MASK
            if opcode == tk.COMMENT and not token & tk.PARAM:
                self._comment(token, at)
                continue
            prog = self._program(at)
            if opcode == tk.PHASE and not token & tk.PARAM:
                if not prog.rules.is_ps14:
                    raise self.fail(f"a phase token in {prog.name} (ps_1_4 only)", at)
                if self.phase_at is None:
                    self.phase_at = len(prog.instructions)
                prog.phase_locations.append(self.loc(at))
                continue
            if token & tk.PARAM:
                raise self.fail(f"0x{token:08X} is a parameter token where an instruction "
                                "token belongs", at)
            self._instruction(prog, token, at)
        if self.pos != self.n:
            raise self.fail(f"{4 * (self.n - self.pos)} bytes after the end token", self.pos)
        prog = self._program(self.pos - 1)
        if prog.rules.is_ps14:
            for k, ins in enumerate(prog.instructions):
                ins.phase = 1 if self.phase_at is not None and k < self.phase_at else 2
        self.binary.program = prog
        return self.binary

    def _program(self, at: int) -> AsmProgram:
        """The program, made at the first token that is no comment: by then the constant
        table has said which of 2_x / 2_a / 2_b a 2.1 token means."""
        if self.program is None:
            table = self.binary.table
            name = table.target if table is not None and table.target in self.names \
                else self.names[0]
            rules: VersionRules = VERSIONS[name]
            self.program = AsmProgram(kind=rules.kind, version=(rules.major, rules.minor),
                                      name=name, rules=rules, location=self.loc(0),
                                      origin=self.loc(0))
        return self.program

    def _comment(self, token: int, at: int) -> None:
        size = token >> tk.COMMENT_SHIFT & tk.COMMENT_MASK
        if self.pos + size > self.n:
            raise self.fail(f"a comment of {size} tokens runs past the end of the bytecode", at)
        body = self.data[4 * self.pos:4 * (self.pos + size)]
        self.pos += size
        code = body[:4].decode("latin-1")
        if code == "CTAB" and self.binary.table is None:
            self.binary.table = read_ctab(body[4:], 4 * (at + 2), self.path)
        else:
            self.binary.comments.append((4 * at, code, body))

    # -- instructions -----------------------------------------------------------------------
    def _instruction(self, prog: AsmProgram, token: int, at: int) -> None:
        code = token & tk.OPCODE_MASK
        control = token >> tk.CONTROL_SHIFT & tk.CONTROL_MASK
        comparison = None
        if code in _COMPARING_CODES:
            comparison = tk.COMPARISON_NAMES.get(control)
            if comparison is None:
                raise self.fail(f"comparison {control} is none of gt, eq, ge, lt, ne, le", at)
            control = 0
        if code in _DEF_CODES:
            info = rows_named(_DEF_CODES[code])[0]
            info = info if prog.name in info.versions else None
        elif code == _DCL:
            info = rows_named("dcl")[0] if prog.name in rows_named("dcl")[0].versions else None
        else:
            info = by_code(code, control, prog.name)
        if info is None:
            raise self.fail(f"opcode {code} (control {control}) is no {prog.name} instruction",
                            at)
        start = self.pos
        if self.major >= 2:
            length = token >> tk.LENGTH_SHIFT & tk.LENGTH_MASK
            end = start + length
            if end > self.n:
                raise self.fail(f"a {info.name} of {length} tokens runs past the end of the "
                                "bytecode", at)
        else:
            end = None
        self.end = end
        self.at = at
        predicated = bool(token & tk.PREDICATED)
        if predicated and self.major < 2:
            raise self.fail("a predicated instruction in a 1_x shader", at)
        coissue = bool(token & tk.COISSUE)
        if coissue and not (prog.kind == "ps" and self.major == 1):
            raise self.fail("a co-issued instruction outside ps_1_x", at)
        if code == _DCL:
            self._dcl(prog, at)
        elif code in _DEF_CODES:
            self._def(prog, info.name, at)
        else:
            roles = "ss" if comparison and info.name in ("if", "break") else info.operands
            dst = None
            srcs: list[Operand] = []
            sat = pp = centroid = False
            shift = 0
            if roles.startswith("d"):
                dst, sat, pp, centroid, shift = self._dst()
                roles = roles[1:]
            predicate = self._src() if predicated else None
            if info.name == "texkill" and roles == "s":    # a destination token (writer.py)
                killed = self._dst()[0]
                killed.mask, killed.swizzle_text = None, ""
                srcs.append(killed)
                roles = ""
            for _ in roles:
                srcs.append(self._src())
            prog.instructions.append(Instruction(
                opcode=info.name, dst=dst, srcs=srcs, info=info, location=self.loc(at),
                shift=shift, saturate=sat, partial_precision=pp, centroid=centroid,
                coissue=coissue, comparison=comparison, predicate=predicate,
                opcode_text=info.name))
        if end is not None and self.pos != end:
            raise self.fail(f"{info.name}'s length field says {end - start} tokens; its "
                            f"operands take {self.pos - start}", at)

    def _param(self, what: str) -> tuple[int, int]:
        if self.end is not None and self.pos >= self.end:
            raise self.fail(f"the instruction's length leaves no token for its {what}", self.at)
        at = self.pos
        # bit 31 is set in every parameter token fxc writes; not checked, as other compilers
        # (the Source engine's) leave it clear in destinations and DXVK and Wine read them
        return self.word(f"the instruction's {what}"), at

    def _register(self, token: int, at: int) -> tuple[str, int | None]:
        rtype = tk.register_type(token)
        number = token & tk.REG_NUMBER_MASK
        prog = self.program
        assert prog is not None
        if rtype == tk.RASTOUT:
            if number >= len(tk.RASTOUT_KINDS):
                raise self.fail(f"rasteriser output {number} is none of oPos, oFog, oPts", at)
            kind, index = tk.RASTOUT_KINDS[number], None
        elif rtype == tk.MISCTYPE:
            if number >= len(tk.MISC_KINDS):
                raise self.fail(f"misc register {number} is neither vPos nor vFace", at)
            kind, index = tk.MISC_KINDS[number], None
        elif rtype in tk.CONST_BANKS:
            kind, index = "c", number + tk.CONST_BANKS.index(rtype) * tk.CONST_BANK_SIZE
        else:
            kind = tk.register_kinds(prog.kind, self.major).get(rtype)  # type: ignore[assignment]
            if kind is None:
                raise self.fail(f"register type {rtype} is none {prog.name} has", at)
            index = None if kind in ("aL", "oDepth") else number   # the assembler names no number
        count = prog.rules.registers.get(kind)
        if kind != "l" and count is None:
            raise self.fail(f"{prog.name} has no {kind} registers", at)
        if index is not None and count is not None and index >= count:
            raise self.fail(f"{kind}{index} is out of range: {prog.name} has {kind}0-"
                            f"{kind}{count - 1}", at)
        return kind, index

    def _relative(self, token: int, at: int) -> RelativeAddress | None:
        if not token & tk.RELATIVE:
            return None
        prog = self.program
        assert prog is not None
        if prog.kind == "vs" and self.major == 1:
            return RelativeAddress("a", 0, 0)
        if prog.kind == "ps" and self.major < 3:
            raise self.fail(f"relative addressing in {prog.name}", at)
        rel, rel_at = self._param("relative address")
        rtype = tk.register_type(rel)
        kind = {tk.ADDR_TEXTURE: "a", tk.LOOP: "aL"}.get(rtype)
        if kind is None or (kind == "a" and prog.kind == "ps"):
            raise self.fail("a relative address names neither a0 nor aL", rel_at)
        return RelativeAddress(kind, 0, 0 if kind == "aL" else rel >> tk.SWIZZLE_SHIFT & 3)

    def _dst(self) -> tuple[Operand, bool, bool, bool, int]:
        token, at = self._param("destination")
        kind, index = self._register(token, at)
        bits = token >> tk.WRITEMASK_SHIFT & 0xF
        if not bits:
            raise self.fail("a destination that writes no component (write mask 0)", at)
        mask = None if bits == 0xF else tuple(c for c in range(4) if bits >> c & 1)
        result = token >> tk.RESULT_SHIFT & 0xF
        if result & ~(tk.SATURATE | tk.PARTIAL_PRECISION | tk.CENTROID):
            raise self.fail(f"result modifier bits 0x{result:X}: D3D9 defines saturate (1), "
                            "partial precision (2) and centroid (4)", at)
        shift = tk.shift_value(token >> tk.DSTSHIFT_SHIFT & 0xF)
        if shift not in tk.SHIFTS:
            raise self.fail(f"result shift {shift} is none of _x2, _x4, _x8, _d2, _d4, _d8", at)
        op = Operand(kind, index, self.loc(at), mask=mask,
                     swizzle_text="" if mask is None else "".join(COMPONENTS[c] for c in mask))
        op.text = op.name
        op.relative = self._relative(token, at)
        return (op, bool(result & tk.SATURATE), bool(result & tk.PARTIAL_PRECISION),
                bool(result & tk.CENTROID), shift)

    def _src(self) -> Operand:
        token, at = self._param("source")
        kind, index = self._register(token, at)
        swizzle = tuple(token >> (tk.SWIZZLE_SHIFT + 2 * i) & 3 for i in range(4))
        mod = token >> tk.SRCMOD_SHIFT & 0xF
        if mod == tk.SRCMOD_NOT:
            modifier, negate = None, True
        elif mod in tk.SRCMOD_NAMES:
            modifier, negate = tk.SRCMOD_NAMES[mod]
        else:
            raise self.fail(f"source modifier {mod} is none D3D9 defines", at)
        op = Operand(kind, index, self.loc(at), swizzle=swizzle,  # type: ignore[arg-type]
                     swizzle_text=canonical_swizzle_text(swizzle), negate=negate,
                     modifier=modifier)
        op.text = op.name
        op.relative = self._relative(token, at)
        return op

    def _raw(self) -> int:
        if self.end is not None and self.pos >= self.end:
            raise self.fail("the instruction's length leaves no token for its value", self.at)
        return self.word("a constant's value")

    def _def(self, prog: AsmProgram, name: str, at: int) -> None:
        reg, *_ = self._dst()
        want = {"def": "c", "defi": "i", "defb": "b"}[name]
        if reg.kind != want or reg.relative is not None:
            raise self.fail(f"{name} defines {reg.name}; it defines {want}# registers", at)
        if name == "def":
            raw = [self._raw() for _ in range(4)]
            values: tuple = struct.unpack("<4f", struct.pack("<4I", *raw))
            prog.defs[reg.index or 0] = values  # type: ignore[assignment]
        elif name == "defi":
            values = struct.unpack("<4i", struct.pack("<4I", *[self._raw() for _ in range(4)]))
            prog.int_defs[reg.index or 0] = values  # type: ignore[assignment]
        else:
            values = (bool(self._raw()),)
            prog.bool_defs[reg.index or 0] = values[0]
        reg.mask, reg.swizzle_text = None, ""
        prog.def_statements.append(ConstantDef(reg, values, self.loc(at),
                                               after_code=bool(prog.instructions)))

    def _dcl(self, prog: AsmProgram, at: int) -> None:
        if self.end is not None and self.pos >= self.end:
            raise self.fail("the dcl's length leaves no token for its usage", at)
        usage_token = self.word("a declaration's usage")
        reg, _, pp, centroid, _ = self._dst()
        usage, usage_index, sampler_type = None, 0, None
        if reg.kind == "s":
            number = usage_token >> tk.SAMPLER_TYPE_SHIFT & 0xF
            sampler_type = tk.SAMPLER_TYPE_NAMES.get(number)
            if number and sampler_type is None:
                raise self.fail(f"sampler type {number} is none of 2d, cube, volume", at)
        else:
            number = usage_token & 0x1F
            if number >= len(tk.USAGES):
                raise self.fail(f"declaration usage {number} is none D3DDECLUSAGE has", at)
            usage_index = usage_token >> tk.USAGE_INDEX_SHIFT & 0xF
            # ps_2_x inputs carry no usage (0); vs and ps_3_0 name one, vPos/vFace excepted
            plain = (prog.kind == "ps" and prog.version[0] < 3) or reg.kind in tk.MISC_KINDS
            usage = None if plain and number == 0 else tk.USAGES[number]
        prog.dcls.append(Declaration(reg, usage, usage_index, sampler_type, pp, centroid,
                                     self.loc(at), after_code=bool(prog.instructions)))
