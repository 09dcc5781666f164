"""fxc's compiled preshaders (FXLC) of an fx_2_0 binary's expression states, read and run on the
host as D3DX ran them (`VertexShaderConstant1 = a * b`, `FogDensity = arr[0]`, the index of
`VertexShader = vs_arr[i]`). The binary reader keeps each as a `Preshader` state value; lowering
and validation evaluate it here where a source expression goes through the HLSL evaluator.

The layout, from the public record (Wine `dlls/d3dx9_36/preshader.c`: parse_preshader,
parse_pres_ins, parse_pres_arg, execute_preshader; effect.c: d3dx9_parse_array_selector),
restated:

    u32 version token 0x4658xxxx ('FX'), then comments (u32 0xFFFE | size << 16, size words
    of which the first is a four-character code):
      CTAB  the inputs: a shader constant table (effects.shaders.d3dbc.ctab), parameters by
            name in float4 registers
      CLIT  literals: u32 count (a multiple of 4), count doubles
      FXLC  u32 instruction count; instruction: u32 opcode << 20 | scalar (bit 31) | component
            count (1-4), u32 input count, the inputs, the output
    operand: u32 relative (0, or 1 then the index register's table and offset), u32 table, u32
    offset, counted in components (c3.y is 13). Tables: 1 literals, 2 inputs, 4 outputs,
    5 and 6 bool and int outputs (shader preshaders only), 7 temporaries.

An instruction computes component by component (`scalar`: the first input's first component
for every one), except dot, which writes one component from all of them. The state's value is
the output registers from oc0.x on, as many components as the state takes. D3DX computed in
doubles and kept temporaries and outputs as floats; a relative index past its table wraps (the
input table at the power of two above its size) and reads 0 past the end. An array selector's
resource is u32 size, the array's name (size bytes), then the preshader.

Untrusted input: every read is bounds-checked, every register an instruction names lies in its
table, and errors are `FxlcError` located at the byte offset in the effect binary.
"""
from __future__ import annotations

import struct
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from effects.base.errors import EffectError, Location
from effects.model import Effect, Preshader

VERSION_TAG = 0x4658          # 'FX', the high half of a preshader's version token
IMMEDIATE, INPUT, OUTPUT, BOOL_OUTPUT, INT_OUTPUT, TEMP = 1, 2, 4, 5, 6, 7
TABLE_NAMES = {IMMEDIATE: "imm", INPUT: "c", OUTPUT: "oc", BOOL_OUTPUT: "ob", INT_OUTPUT: "oi",
               TEMP: "r"}
READ_TABLES = (IMMEDIATE, INPUT, OUTPUT, TEMP)
WRITE_TABLES = (OUTPUT, TEMP)


class FxlcError(EffectError):
    """A preshader of an effect binary that cannot be read or run."""


F = np.float64


def _log(a: float) -> float:
    v = abs(a)
    return F(0.0) if v == 0.0 else np.log2(v)


def _rsq(a: float) -> float:
    v = abs(a)
    return F(np.inf) if v == 0.0 else 1.0 / np.sqrt(v)


def _dot(*args: float) -> float:
    half, total = len(args) // 2, F(0.0)
    for k in range(half):             # in order, as D3DX summed
        total += args[k] * args[k + half]
    return total


@dataclass(frozen=True)
class Op:
    """One FXLC instruction: its opcode, how many inputs it takes and what it computes (D3DX's
    kernel, on doubles, IEEE results: 1/0 is inf, asin 2 NaN); a `dot` row takes every
    component of its inputs and writes one."""

    name: str
    code: int
    inputs: int
    kernel: Callable[..., Any]
    dot: bool = False


# one row per instruction (the (opcode, input count) pair names it: d3ds_dotswiz has two)
OPS: tuple[Op, ...] = (
    Op("nop", 0x000, 0, lambda: F(0.0)),
    Op("mov", 0x100, 1, lambda a: a),
    Op("neg", 0x101, 1, lambda a: -a),
    Op("rcp", 0x103, 1, lambda a: 1.0 / a),
    Op("frc", 0x104, 1, lambda a: a - np.floor(a)),
    Op("exp", 0x105, 1, np.exp2),
    Op("log", 0x106, 1, _log),                  # log2 |a|, 0 at 0
    Op("rsq", 0x107, 1, _rsq),                  # 1 / sqrt |a|, +inf at 0
    Op("sin", 0x108, 1, np.sin),
    Op("cos", 0x109, 1, np.cos),
    Op("asin", 0x10A, 1, np.arcsin),
    Op("acos", 0x10B, 1, np.arccos),
    Op("atan", 0x10C, 1, np.arctan),
    Op("min", 0x200, 2, np.fmin),
    Op("max", 0x201, 2, np.fmax),
    Op("lt", 0x202, 2, lambda a, b: F(a < b)),
    Op("ge", 0x203, 2, lambda a, b: F(a >= b)),
    Op("add", 0x204, 2, lambda a, b: a + b),
    Op("mul", 0x205, 2, lambda a, b: a * b),
    Op("atan2", 0x206, 2, np.arctan2),
    # D3DX's div gives 0 whatever its inputs (Wine's tests of native d3dx9); fxc never emits
    # it (rcp and mul instead)
    Op("div", 0x208, 2, lambda a, b: F(0.0)),
    Op("cmp", 0x300, 3, lambda a, b, c: b if a >= 0.0 else c),
    Op("dot", 0x500, 2, _dot, dot=True),
    Op("d3ds_dotswiz", 0x70E, 6, _dot),
    Op("d3ds_dotswiz", 0x70E, 8, _dot),
)
BY_CODE = {(op.code, op.inputs): op for op in OPS}


@dataclass(frozen=True)
class Register:
    table: int
    offset: int                      # in components: c3.y is 13


@dataclass(frozen=True)
class Operand:
    register: Register
    index: Register | None = None    # relative: the register whose value (rounded) adds
                                     # whole registers to the offset


@dataclass(frozen=True)
class Instruction:
    op: Op
    components: int
    scalar: bool                     # the first input's first component for every component
    inputs: tuple[Operand, ...]
    output: Register
    at: int                          # byte offset in the binary


@dataclass(frozen=True)
class Program:
    instructions: tuple[Instruction, ...]
    literals: tuple[float, ...]
    constants: tuple[Any, ...]       # the CTAB's ConstantInfo rows (float4 register set)
    sizes: dict[int, int]            # registers of each table, as D3DX sized them
    ctab_at: int                     # byte offset of the constant table (for its errors)


class _Words:
    def __init__(self, data: bytes, base: int, path: str) -> None:
        self.data, self.base, self.path = data, base, path
        self.n = len(data) // 4

    def fail(self, message: str, word: int) -> FxlcError:
        at = self.base + 4 * word
        return FxlcError(f"preshader: {message} (at byte {at})", Location(self.path, 1, at + 1))

    def word(self, k: int, what: str, end: int | None = None) -> int:
        if k >= (self.n if end is None else end):
            raise self.fail(f"the preshader ends where {what} belongs", k)
        return struct.unpack_from("<I", self.data, 4 * k)[0]


def decode(value: Preshader, path: str) -> Program:
    """The program of a `Preshader` state value (its constant table, literals and
    instructions), every register checked against its table. Raises FxlcError."""
    return decode_bytes(value.data, value.offset, path)


def decode_bytes(data: bytes, offset: int, path: str) -> Program:
    """The program of preshader bytes found at byte `offset` of file `path`: an expression
    state's, or the one a shader carries in its PRES comment (fxc's constant preshader)."""
    from effects.shaders.d3dbc.ctab import read_ctab
    value = Preshader("", data=data, offset=offset)
    w = _Words(value.data, value.offset, path)
    if len(value.data) % 4 or w.n < 1:
        raise w.fail(f"{len(value.data)} bytes are no whole number of 32-bit words", 0)
    token = w.word(0, "the version token")
    if token >> 16 != VERSION_TAG:
        raise w.fail(f"version token 0x{token:08X} is no preshader's (0x4658....)", 0)
    sections: dict[str, tuple[int, int]] = {}          # code -> (first body word, end word)
    k = 1
    while k < w.n and w.word(k, "a comment") & 0xFFFF == 0xFFFE:
        size = w.word(k, "a comment") >> 16
        if size < 1 or k + 1 + size > w.n:
            raise w.fail(f"a comment of {size} words runs past the preshader's {w.n}", k)
        code = struct.pack("<I", w.word(k + 1, "a comment's code")).decode("latin-1")
        sections.setdefault(code, (k + 2, k + 1 + size))
        k += 1 + size
    if "FXLC" not in sections:
        raise w.fail("no FXLC (instructions) comment", 1)
    constants: tuple[Any, ...] = ()
    ctab_at = value.offset
    if "CTAB" in sections:
        start, end = sections["CTAB"]
        ctab_at = value.offset + 4 * start
        table = read_ctab(value.data[4 * start:4 * end], ctab_at, path)
        constants = tuple(c for c in table.constants if c.register_set != "sampler")
        for c in constants:
            if c.register_set != "float4":
                raise w.fail(f"input '{c.name}' in {c.register_set} registers (a preshader "
                             "reads float4 ones)", start)
    literals: tuple[float, ...] = ()
    if "CLIT" in sections:
        start, end = sections["CLIT"]
        count = w.word(start, "the literal count", end)
        if count % 4 or 1 + 2 * count > end - start:
            raise w.fail(f"{count} literals: not a multiple of 4, or more than the CLIT "
                         "comment holds", start)
        literals = struct.unpack_from(f"<{count}d", value.data, 4 * (start + 1))
    sizes = {IMMEDIATE: len(literals) // 4, TEMP: 0, OUTPUT: 0,
             INPUT: max((c.register_index + c.register_count for c in constants), default=0)}
    start, end = sections["FXLC"]
    count = w.word(start, "the instruction count", end)
    if 5 * count > end - start:
        raise w.fail(f"{count} instructions cannot fit in the FXLC comment's "
                     f"{end - start} words", start)
    k = start + 1
    instructions = []
    for _ in range(count):
        ins, k = _instruction(w, k, end, sizes)
        instructions.append(ins)
    return Program(tuple(instructions), tuple(literals), constants, sizes, ctab_at)


def _instruction(w: _Words, k: int, end: int, sizes: dict[int, int]) -> tuple[Instruction, int]:
    at = k
    raw = w.word(k, "an instruction", end)
    code, components, scalar = raw >> 20 & 0x7FF, raw & 0xFFFF, bool(raw & 0x80000000)
    ninputs = w.word(k + 1, "an input count", end)
    op = BY_CODE.get((code, ninputs))
    if op is None:
        raise w.fail(f"opcode 0x{code:03X} with {ninputs} inputs is no preshader instruction "
                     "D3DX knows", at)
    if not 1 <= components <= 4:
        raise w.fail(f"{op.name}: {components} components (1-4)", at)
    k += 2
    inputs = []
    for j in range(ninputs):
        operand, k = _operand(w, k, end, READ_TABLES)
        last = 0 if scalar and j == 0 else components - 1
        reg, table = ((operand.index.offset // 4, operand.index.table) if operand.index else
                      ((operand.register.offset + last) // 4, operand.register.table))
        if reg >= sizes[table]:
            raise w.fail(f"{op.name}: input {j + 1} reads {TABLE_NAMES[table]}{reg}, beyond the "
                         f"{sizes[table]} registers of its table", at)
        inputs.append(operand)
    output, k = _operand(w, k, end, WRITE_TABLES)
    if output.index is not None:
        raise w.fail(f"{op.name}: a relative output register", at)
    reg = output.register
    sizes[reg.table] = max(sizes[reg.table], (reg.offset + components - 1) // 4 + 1)
    return Instruction(op, components, scalar, tuple(inputs), reg, w.base + 4 * at), k


def _operand(w: _Words, k: int, end: int, tables: tuple[int, ...]) -> tuple[Operand, int]:
    relative = w.word(k, "an operand", end)
    if relative not in (0, 1):
        raise w.fail(f"operand flag {relative} (0: direct, 1: relative)", k)
    index = None
    k += 1
    if relative:
        index, k = _register(w, k, end, READ_TABLES), k + 2
    register = _register(w, k, end, tables)
    return Operand(register, index), k + 2


def _register(w: _Words, k: int, end: int, tables: tuple[int, ...]) -> Register:
    table = w.word(k, "a register table", end)
    offset = w.word(k + 1, "a register offset", end)
    if table not in tables:
        names = ", ".join(f"{t} ({TABLE_NAMES[t]})" for t in tables)
        raise w.fail(f"register table {table} is none of {names}", k)
    if offset >= 1 << 20:
        raise w.fail(f"register offset {offset} is beyond any table", k + 1)
    return Register(table, offset)


# ------------------------------------------------------------------------------------------------
# running a program

# a parameter's numbers in declaration order (None: no value), read through the effect (a
# RecordedReads view records them): effects.shaders.hlsl.preshader.parameter_numbers
Numbers = Callable[[str], "list[float] | None"]


def run(program: Program, effect: Effect, values: Numbers) -> np.ndarray:
    """The output registers' components (oc0.x, oc0.y, ...) at the parameters' current values
    (`values`)."""
    tables = {IMMEDIATE: np.asarray(program.literals, dtype=np.float64),
              INPUT: _inputs(program, effect, values)}
    for t in (TEMP, OUTPUT):
        tables[t] = np.zeros(4 * program.sizes[t], dtype=np.float32)
    sizes = program.sizes

    def read(operand: Operand, comp: int) -> np.float64:
        reg = operand.register
        base = 0
        if operand.index is not None:
            v = tables[operand.index.table][operand.index.offset]
            # lrint; a NaN or infinite index is C's INT_MIN, past every table
            base = int(np.rint(v)) if np.isfinite(v) else -(1 << 31)
        offset = (4 * base + reg.offset + comp) & 0xFFFFFFFF
        size = sizes[reg.table]
        if offset // 4 >= size:
            wrap = size if reg.table != INPUT else 1 << max(size - 1, 0).bit_length()
            row = offset // 4 % wrap if wrap else size
            if row >= size:
                return F(0.0)
            offset = 4 * row + offset % 4
        return F(tables[reg.table][offset])

    with np.errstate(all="ignore"):
        for ins in program.instructions:
            out = tables[ins.output.table]
            if ins.op.dot:
                args = [read(x, 0 if ins.scalar and k == 0 else j)
                        for k, x in enumerate(ins.inputs) for j in range(ins.components)]
                out[ins.output.offset] = ins.op.kernel(*args)
                continue
            for j in range(ins.components):
                args = [read(x, 0 if ins.scalar and k == 0 else j)
                        for k, x in enumerate(ins.inputs)]
                out[ins.output.offset + j] = ins.op.kernel(*args)
    return tables[OUTPUT].astype(np.float64)


def _inputs(program: Program, effect: Effect, values: Numbers) -> np.ndarray:
    """The input registers: each constant-table row filled from its parameter's value as fxc
    packs one (effects.shaders.hlsl.registers), a parameter without a value zeros."""
    regs = np.zeros(4 * program.sizes[INPUT], dtype=np.float32)
    for c in program.constants:
        if effect.parameter(c.name) is None:
            raise FxlcError(f"preshader: its constant table names '{c.name}', which the effect "
                            f"does not declare (at byte {program.ctab_at})",
                            Location(effect.path, 1, program.ctab_at + 1))
        flat = values(c.name) or []
        rows = _registers(c.type, list(flat), [0])[:c.register_count]
        for k, row in enumerate(rows):
            regs[4 * (c.register_index + k):4 * (c.register_index + k) + 4] = row
    return regs


def _registers(t: Any, flat: list[float], at: list[int]) -> list[list[float]]:
    """Registers of a constant-table type from its numbers in declaration order (`at[0]`, the
    next number, consumed): each element and struct member starts a register, a matrix takes
    one per row (MATRIX_ROWS) or per column (MATRIX_COLUMNS)."""
    from effects.shaders.d3dbc.ctab import MATRIX_COLUMNS, STRUCT
    out: list[list[float]] = []
    for _ in range(max(1, t.elements)):
        if t.cls == STRUCT:
            for _, member in t.members:
                out += _registers(member, flat, at)
            continue
        n = t.rows * t.columns
        chunk = (flat[at[0]:at[0] + n] + [0.0] * n)[:n]
        at[0] += n
        m = np.asarray(chunk, dtype=np.float64).reshape(t.rows, t.columns)
        for row in (m.T if t.cls == MATRIX_COLUMNS else m):
            out.append((list(row) + [0.0] * 4)[:4])
    return out


def written_registers(program: Program) -> list[int]:
    """The output registers (oc#) the program writes: those D3DX set before a draw."""
    return sorted({(ins.output.offset + j) // 4 for ins in program.instructions
                   if ins.output.table == OUTPUT
                   for j in range(1 if ins.op.dot else ins.components)})


def numbers(value: Preshader, effect: Effect, values: Numbers,
            components: int | None = None) -> np.ndarray:
    """A preshader state's value: its output components, the first `components` of them (all
    when None), as D3DX copied them into the state."""
    out = run(decode(value, effect.path), effect, values)
    return out if components is None else out[:components]


def listing(program: Program) -> str:
    """The program as one line (`mul oc0.xyzw, c0.xyzw, c1.xyzw`), for messages; inputs named
    by the constant table."""
    names = {}
    for c in program.constants:
        for k in range(c.register_count):
            names[c.register_index + k] = c.name if c.register_count == 1 else f"{c.name}+{k}"

    def reg(r: Register, n: int, index: Register | None = None) -> str:
        row, first = r.offset // 4, r.offset % 4
        lanes = "".join("xyzw"[(first + j) % 4] for j in range(n))
        if r.table == IMMEDIATE and index is None:
            return "(" + ", ".join(f"{x:g}" for x in program.literals[r.offset:r.offset + n]) + ")"
        shown = f"{TABLE_NAMES[r.table]}{row}"
        if index is not None:
            shown = (f"{TABLE_NAMES[r.table]}[{row} + {TABLE_NAMES[index.table]}{index.offset // 4}"
                     f".{'xyzw'[index.offset % 4]}]")
        if r.table == INPUT and index is None and row in names:
            shown += f"({names[row]})"
        return f"{shown}.{lanes}"
    lines = []
    for ins in program.instructions:
        n = 1 if ins.op.dot else ins.components
        args = [reg(x.register, 1 if ins.scalar and k == 0 else ins.components, x.index)
                for k, x in enumerate(ins.inputs)]
        lines.append(f"{ins.op.name} {reg(ins.output, n)}" + "".join(", " + a for a in args))
    return "; ".join(lines)


def check_preshaders(effect: Effect) -> None:
    """Decode every preshader state of a loaded effect (pass states, parameters' sampler
    states), so a binary with a bad one fails to load, located, as D3DXCreateEffect failed."""
    for s in effect.every_state():
        if isinstance(s.value, Preshader):
            decode(s.value, effect.path)
