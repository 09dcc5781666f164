"""Lower assembled Direct3D shaders (vs_1_1-vs_3_0, ps_1_1-ps_1_4, ps_2_0/2_x) to the IR.

    program = lower_pixel_shader(asm, ShaderContext(options))     # stage 'fragment'
    program = lower_vertex_shader(asm, ShaderContext(options))    # stage 'vertex'
    constant_registers(asm)     # the c# the pass must supply as uniforms `c0`, `c1` ...

Instruction by instruction, over a register file of IR values (SSA, so a snapshot is a dict
copy). What each instruction, modifier and macro computes lives in rewrites.py as data; this
module reads operands, does what the instruction's row says (`InstrInfo.lowers`: a rewrite
tree, a handler from texture_ops.py, or nothing), and writes results. `lowering_problems`
lists, located, what the rows and this module do not lower; validation reports them.

Decisions (sources: docs/reference/semantics.md §2-4, docs/reference/caps.md §1):
- A register read before any write is (0, 0, 0, 0) (the checker rejects such reads anyway).
- Write masks merge into the register's previous value. Co-issued pairs (`+`) read the state
  from before the pair.
- Precision is explicit: after each ps_1_1-1_3 (ps_1_4) instruction that computes a value, the
  result is shifted, saturated (`_sat`), clamped to ±ps1x_range (ps14_range) and quantised to
  ps1x_bits (ps14_bits) fraction bits when the options set them (a signed grid of
  bits + 1 + ceil(log2 range) bits over [-range, range]: 8 bits, range 1 is steps of 1/255).
  Texels written by texture instructions keep the texture's precision. ps_2_0+ and vertex
  shaders are float (fp16/fp24 rounding of ps_2_0 is not modelled).
- Constant registers the pass supplies are uniforms `c#`; `def` constants are literals.
  ps_1_x reads clamp to [-constant_range, constant_range] (a literal is clamped when lowered,
  a uniform on every read, as DXVK does); ps_2_0 and vertex constants are not clamped.
- ps_1_x: r0 is saturated on output as `color0`. ps_1_4 r# alpha surviving `phase` is not
  modelled (it survives). ps_1_4 texld samples stage n = destination register number;
  TTFF_PROJECTED (ctx.projected) applies to ps_1_1-1_3 `tex`/`texbem(l)` only (1.4 uses _dw).
- ps_1_x t# in 1.1-1.3 holds what texture instructions wrote; in 1.4 and ps_2_0 a t# source is
  the interpolated texture coordinate `texcoord#`. v# are `color0`/`color1`.
- vs_3_0 samples (texldl) its s0-s3 as IR samplers 257-260 (D3DVERTEXTEXTURESAMPLER0-3, the
  numbers a pass binds them by), never the pixel samplers of the same register number.
- Sampler kinds: ps_2_0+ from dcl_2d/dcl_cube/dcl_volume; ps_1_x from ctx.sampler_kinds,
  defaulting to '2d', or 'cube' for the texm3x3tex/spec/vspec family.
- Vertex inputs are named by their dcl usage (position, normal, texcoord0, color0 ...; an
  index > 0 is appended for the others, e.g. position1); without dcl by the Direct3D 8 fixed
  register mapping (D3DVSDE_*): v0 position, v1 blendweight, v2 blendindices, v3 normal, v4 psize,
  v5 color0, v6 color1, v7-v14 texcoord0-7, v15 position1 (POSITION2 = usage POSITION index 1),
  v16 normal1. A DX8 decl{} element gives the input its component count.
- Vertex outputs: oPos position, oD0/oD1 color0/color1 (saturated below vs_3_0), oT# texcoord#,
  oFog fog, oPts psize; vs_3_0 o# by their dcl usage. An output the shader never writes is not
  emitted: the back end supplies D3D's vertex defaults (color0 (1,1,1,1), color1 (0,0,0,0),
  others (0,0,0,1)). Components a partial write leaves unwritten hold those same defaults
  (the D3D docs leave them undefined).
- Relative constant addressing c[a0.x + n] selects among c0 .. c(constants_min - 1) of the
  version (96 for vs_1_1, 256 for vs_2_0+); an index outside reads (0, 0, 0, 0). A program
  that addresses relatively needs all of those registers (`constant_registers`).
- Flow control (flow.py) lowers to the IR's structured blocks; predicated instructions write
  only where the predicate holds; dsx/dsy are the IR's ddx/ddy and texldd samples with
  explicit gradients. Integer and boolean registers the pass sets (ctx.int_constants /
  bool_constants) are static: their values are lowered in, so the pass is lowered again when
  they change (lower_pass' parameter check), as a driver recompiles on a static-branch change.
  An early ret (inside a block) leaves its body through a one-iteration IR loop (flow.ret).
  `lowering_problems` names what does not lower: relative addressing of v# / o#, gradients
  inside dynamic flow control (X4014, counting what follows an early ret inside a dynamic
  block), and any row marked NotLowered.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any, Mapping

from effects.base.errors import AsmError
from effects.program.ir import COMPONENTS, OUTPUTS, Builder, Program
from effects.model import VertexDeclElement
from effects.d3d9.precision import LoweringOptions
from effects.d3d9.states import VERTEX_TEXTURE_SAMPLER0
from effects.shaders.asm import flow
from effects.shaders.asm.instructions import Handler, NoCode, NotLowered, Rewrite
from effects.shaders.asm.program import AsmProgram, Instruction, Operand
from effects.shaders.asm.rewrites import (NEGATE, PRE_SWIZZLE_MODIFIERS, RESULT_MODIFIERS,
                                          SOURCE_MODIFIERS, Emitter)

__all__ = ["ShaderContext", "constant_registers", "lower_pixel_shader", "lower_vertex_shader",
           "input_name", "lowering_problems"]

ZERO = (0.0, 0.0, 0.0, 0.0)
ONE = (1.0, 1.0, 1.0, 1.0)
DEFAULT_VARYING = (0.0, 0.0, 0.0, 1.0)
# Direct3D 8 fixed vertex input registers (d3d8types.h D3DVSDE_*).
DX8_INPUTS = {0: "position", 1: "blendweight", 2: "blendindices", 3: "normal", 4: "psize",
              5: "color0", 6: "color1", **{7 + i: f"texcoord{i}" for i in range(8)},
              15: "position1", 16: "normal1"}
SAMPLER_TYPES = {"2d": "2d", "cube": "cube", "volume": "3d"}
# Vertex output registers -> IR output names, and the default a partial write fills in.
VS_OUTPUTS = {"oPos": "position", "oFog": "fog", "oPts": "psize"}
OUTPUT_DEFAULTS = {"color0": ONE, "color1": ZERO}
VS3_USAGE_OUTPUTS = {"position": "position", "fog": "fog", "psize": "psize"}


@dataclass(frozen=True)
class ShaderContext:
    """What lowering needs besides the program: the profile's precision and the pass state
    shaders of this era depend on."""

    options: LoweringOptions
    sampler_kinds: Mapping[int, str] = field(default_factory=dict)  # stage -> 2d|cube|3d
    projected: Mapping[int, bool] = field(default_factory=dict)     # ps_1_x TTFF_PROJECTED
    decl: tuple[VertexDeclElement, ...] | None = None               # DX8 decl{} elements
    # Uniform name of constant register n is f"{constant_prefix}{n}". A pass lowering both a
    # vertex and a pixel shader gives them different prefixes: their c# are separate files.
    constant_prefix: str = "c"
    # Integer and boolean registers the pass sets (VertexShaderConstantI/B, PixelShader...):
    # i# -> (x, y, z, w), b# -> bool. A shader's own defi / defb win, as on the device while
    # it runs; a register neither sets reads (0, 0, 0, 0) / FALSE.
    int_constants: Mapping[int, tuple[int, int, int, int]] = field(default_factory=dict)
    bool_constants: Mapping[int, bool] = field(default_factory=dict)


def lower_pixel_shader(program: AsmProgram, ctx: ShaderContext) -> Program:
    """The fragment IR of a ps_1_x / ps_2_x / ps_3_0 program."""
    if program.kind != "ps":
        raise AsmError(f"{program.name} is not a pixel shader", program.location)
    return _Lowering(program, ctx, "fragment").run()


def lower_vertex_shader(program: AsmProgram, ctx: ShaderContext) -> Program:
    """The vertex IR of a vs_1_1 / vs_2_x / vs_3_0 program."""
    if program.kind != "vs":
        raise AsmError(f"{program.name} is not a vertex shader", program.location)
    return _Lowering(program, ctx, "vertex").run()


def constant_registers(program: AsmProgram) -> set[int]:
    """The c# the program reads that it does not `def`: the pass supplies them as uniforms."""
    used: set[int] = set()
    for instr in program.instructions:
        if instr.info.category == "setup":
            continue
        rows = instr.info.matrix_rows or 1
        for k, src in enumerate(instr.srcs):
            if src.kind != "c" or src.index is None:
                continue
            if src.relative is not None:
                used.update(range(_relative_range(program)))
            else:
                used.update(range(src.index, src.index + (rows if k == 1 else 1)))
    return used - set(program.defs)


# Registers a source may read in the lowering; ps_3_0 vPos / vFace are fragment builtins.
_READABLE = frozenset({"c", "v", "t", "r", "a", "aL", "p", "b", "vPos", "vFace"})
_BUILTINS = {"vPos": "vpos", "vFace": "vface"}


def _written(instrs: list, body: range, labels: dict[int, int], relative_targets: Any,
             seen: frozenset = frozenset()) -> dict[tuple[str, int], Operand]:
    """The registers the instructions in `body` (and the subroutines they call) write; a
    subroutine's body ends at its ret (flow.body_end). `relative_targets(dst)`: the registers
    an o[aL + n] write may reach."""
    found: dict[tuple[str, int], Operand] = {}
    for k in body:
        instr = instrs[k]
        if instr.dst is not None and not isinstance(instr.info.lowers, NoCode):
            for dst in (relative_targets(instr.dst) if instr.dst.relative is not None
                        else (instr.dst,)):
                found.setdefault((dst.kind, dst.index or 0), dst)
        if instr.opcode in ("call", "callnz") and instr.srcs:
            start = labels.get(instr.srcs[0].index)
            if start is not None and start not in seen:
                found.update(_written(instrs, range(start + 1, flow.body_end(instrs, start + 1)),
                                      labels, relative_targets, seen | {start}))
    return found


def lowering_problems(program: AsmProgram,
                      int_constants: Mapping[int, tuple[int, int, int, int]] | None = None
                      ) -> list[AsmError]:
    """Every instruction of `program` that does not lower, located, with the reason: its
    row says `NotLowered`, or it uses a register, an addressing form or a flow-control form
    the lowering does not handle. Empty means `lower_*_shader` lowers it. A program the
    checker rejects (an unclosed block ...) gets the checker's reason instead.
    `int_constants`: the i# the pass sets (ShaderContext.int_constants), whose loop counts
    count against the iteration limit."""
    from effects.shaders.asm.check import check_cached
    errors = check_cached(program)
    if errors:
        return list(errors)
    problems = (flow.iteration_problems(program, int_constants or {})
                + flow.call_problems(program.instructions))
    dynamic = flow.dynamic_blocks(program.instructions)
    for pos, instr in enumerate(program.instructions):
        lowers = instr.info.lowers
        if instr.info.gradient and program.kind == "ps" and any(
                start < pos < end for start, end in dynamic):
            problems.append(AsmError(
                f"{instr.opcode}: gradients inside dynamic flow control are undefined (X4014: "
                "move it out of the if or loop, or use texldl / texldd)", instr.location))
        elif isinstance(lowers, NotLowered):
            problems.append(AsmError(f"{instr.opcode}: {lowers.reason}", instr.location))
        elif isinstance(lowers, NoCode):
            continue
        elif instr.predicate is not None and instr.info.category == "flow":
            problems.append(AsmError(f"{instr.opcode}: a predicated flow-control instruction "
                                     "is not lowered yet", instr.location))
        else:
            problems += _operand_problems(program, instr)
    return problems


def _operand_problems(program: AsmProgram, instr: Instruction) -> list[AsmError]:
    found = []
    roles = instr.info.source_roles
    for k, op in enumerate(instr.srcs):
        if k < len(roles) and roles[k] not in "sx":
            continue
        if op.relative is not None and not (op.kind == "c" or (
                op.kind == "v" and op.relative.kind == "aL")):
            found.append(AsmError(f"relative addressing of {op.kind}# registers "
                                  f"({op.kind}[{op.relative.kind}]) is not lowered",
                                  op.location))
        elif op.kind not in _READABLE:
            found.append(AsmError(f"reading {op.name} is not lowered yet", op.location))
    dst = instr.dst
    if dst is not None and dst.relative is not None and not (
            dst.kind == "o" and dst.relative.kind == "aL"):
        found.append(AsmError(f"relative addressing of {dst.name} ({dst.kind}[{dst.relative.kind}])"
                              " is not lowered", dst.location))
    return found


def input_name(usage: str, index: int) -> str:
    """The IR name of a vertex input (or ps_3_0 varying) declared `dcl_<usage><index>`."""
    return f"{usage}{index}" if usage in ("texcoord", "color") or index else usage


def _relative_range(program: AsmProgram) -> int:
    return program.rules.constants_min or program.rules.registers.get("c", 0)


@dataclass(frozen=True)
class _WriteFacts:
    """What the result modifiers' conditions read (rewrites.RESULT_MODIFIERS)."""

    shift: int
    saturate: bool
    computed: bool
    range: float | None
    grid: tuple[int, bool, float] | None


@dataclass(frozen=True)
class _Precision:
    """Where a register write lands: register range and fixed-point grid (None = float)."""

    range: float | None = None
    grid: tuple[int, bool, float] | None = None      # quantize (bits, signed, scale)


def _precision(program: AsmProgram, options: LoweringOptions) -> _Precision:
    """The options' register grid for this program's model (ps_2_0+ and vertex: float)."""
    rules = program.rules
    model = "ps_1_x" if rules.is_ps11_13 else "ps_1_4" if rules.is_ps14 else None
    return _Precision() if model is None else _Precision(*options.register_grid(model))


class _Lowering:
    def __init__(self, program: AsmProgram, ctx: ShaderContext, stage: str) -> None:
        self.p = program
        self.ctx = ctx
        self.rules = program.rules
        self.b = Builder(stage)
        self.e = Emitter(self.b)
        self.regs: dict[tuple[str, int], int] = {}
        self.precision = _precision(program, ctx.options)
        self.pending_rows: list[int] = []        # texm3x2pad / texm3x3pad dot products
        self.depth: int | None = None
        self.written: list[tuple[str, int]] = []  # output registers in first-write order
        # flow control (flow.py): registers held in IR variables, open loops (None for rep,
        # else (aL variable, outer aL, start, step, count)), the instruction being lowered,
        # the predicate of a predicated instruction, subroutines being inlined
        self.variables: dict[tuple[str, int], int] = {}
        self.loops: list[Any] = []
        self.pos = 0
        self.pred: int | None = None
        self.calls: list[int] = []
        self.returns: list[tuple[int, int]] = []   # bodies with early rets: (flag, loops open)
        self._reads: dict = {}                     # the register reads of the instruction
        self.labels = {ins.srcs[0].index: k for k, ins in enumerate(program.instructions)
                       if ins.opcode == "label" and ins.srcs}

    # -- driver
    def run(self) -> Program:
        problems = flow.iteration_problems(self.p, self.ctx.int_constants)
        if problems:              # counts the pass set at render time, past the limit
            raise problems[0]
        self.lower_body(0)
        self.outputs()
        return self.b.build()

    def lower_body(self, start: int) -> None:
        """Lower the body (main program or subroutine) from `start` to its end (flow.body_end).
        A body with an early ret runs inside a one-iteration loop the rets break out of
        (flow.ret); the registers it writes become variables first."""
        instrs = self.p.instructions
        end = flow.body_end(instrs, start)
        wrapped = bool(flow.early_returns(instrs, start))
        if wrapped:
            self.enter_range(range(start, end))
            self.returns.append((self.b.var(self.e.const(0.0)), len(self.loops)))
            self.b.loop(1)
        self.lower_from(start, end)
        if wrapped:
            self.b.endloop()
            self.returns.pop()

    def lower_from(self, start: int, end: int) -> None:
        """Lower instructions start .. end - 1 (co-issued pairs together)."""
        instrs = self.p.instructions
        i = start
        while i < end:
            group = [instrs[i]]
            while i + len(group) < len(instrs) and instrs[i + len(group)].coissue:
                group.append(instrs[i + len(group)])
            snapshot = dict(self.regs)             # co-issued halves read the pre-pair state
            for k, instr in enumerate(group):
                self.pos = i + k
                self.lower(instr, snapshot)
            i += len(group)

    def inline(self, label: Operand) -> None:
        """The body of subroutine `label`, lowered here (call / callnz)."""
        start = self.labels.get(label.index)
        if start is None:
            raise AsmError(f"l{label.index} has no label", label.location)
        if start in self.calls or len(self.calls) >= flow.MAX_CALL_DEPTH:
            raise AsmError(f"call l{label.index}: recursive or too deep", label.location)
        self.calls.append(start)
        pos = self.pos
        self.lower_body(start + 1)
        self.pos = pos
        self.calls.pop()

    def enter_block(self, pos: int, subroutine: Operand | None = None) -> None:
        """Before a block opens: every register the block (or the subroutine) may write is
        moved into an IR variable, so its writes inside are assignments."""
        instrs = self.p.instructions
        if subroutine is None:
            body = range(pos + 1, flow.block_end(instrs, pos))
        else:
            start = self.labels.get(subroutine.index, len(instrs)) + 1
            body = range(start, flow.body_end(instrs, start))
        self.enter_range(body)

    def enter_range(self, body: range) -> None:
        """Every register the instructions in `body` (and what they call) may write, moved
        into an IR variable."""
        instrs = self.p.instructions
        for key, dst in _written(instrs, body, self.labels, self.declared_targets).items():
            if key in self.variables:
                continue
            self.regs[key] = self.variables[key] = self.b.var(self.initial(key, dst))

    def lower(self, instr: Instruction, reads: dict[tuple[str, int], int]) -> None:
        """What the instruction's row says: nothing, a rewrite, a handler."""
        lowers = instr.info.lowers
        if isinstance(lowers, NoCode):
            return
        if isinstance(lowers, NotLowered):   # validation rejects these first
            raise AsmError(f"{instr.opcode}: {lowers.reason}", instr.location)
        self.pred = (None if instr.predicate is None
                     else flow.predicate(self, instr.predicate, reads))
        self._reads = reads
        if isinstance(lowers, Handler):
            lowers.fn(self, instr, reads)
        elif instr.info.matrix_rows:
            self.matrix(instr, reads, lowers)
        else:
            self.arithmetic(instr, reads, lowers)

    # -- reading operands
    def source(self, op: Operand, reads: dict, *, scalar: bool = False) -> int:
        """An operand's value: register (or relative constant), dz/dw, swizzle, modifier,
        negate; a scalar source then replicates its selected component (w after the swizzle,
        so .x gives x and no swizzle gives w: docs/reference/semantics.md §4)."""
        value = self.register(op, reads)
        if op.modifier in PRE_SWIZZLE_MODIFIERS:
            value = self.e.emit(SOURCE_MODIFIERS[op.modifier], {"x": value})
        value = self.e.swizzle(value, "".join(COMPONENTS[c] for c in op.swizzle))
        if op.modifier not in PRE_SWIZZLE_MODIFIERS:
            value = self.e.emit(SOURCE_MODIFIERS[op.modifier], {"x": value})
        if op.negate:
            value = self.e.emit(NEGATE, {"x": value})
        return self.e.swizzle(value, "wwww") if scalar else value

    def register(self, op: Operand, reads: dict) -> int:
        kind, index = op.kind, op.index
        if op.relative is not None and kind == "v":
            return self.relative_select(op, reads, self.relative_targets(op), self.varying_input)
        if op.relative is not None and kind != "c":
            raise AsmError(f"relative addressing of {op.name} is not lowered", op.location)
        if kind in _BUILTINS and self.b.stage == "fragment":
            return self.b.builtin(_BUILTINS[kind])
        if kind == "c":
            if op.relative is not None:
                return self.relative_constant(op, reads)
            return self.constant(index)
        if kind == "v":
            return self.varying_input(index)
        if kind == "t" and not self.rules.is_ps11_13:
            return self.texcoord(index)
        if kind in ("r", "t", "a", "aL", "p"):
            value = reads.get((kind, index or 0))
            return self.e.const(ZERO) if value is None else value
        raise AsmError(f"reading {op.name} is not lowered yet", op.location)

    def constant(self, index: int) -> int:
        limit = self.ctx.options.constant_range if self.rules.is_ps1 else None
        if index in self.p.defs:
            values = self.p.defs[index]
            if limit is not None:
                values = tuple(min(max(v, -limit), limit) for v in values)
            return self.e.const(values)
        value = self.b.uniform(f"{self.ctx.constant_prefix}{index}")
        return self.b.clamp(value, -limit, limit) if limit is not None else value

    def relative_constant(self, op: Operand, reads: dict) -> int:
        """c[a0.x + n]: a select over every addressable register (no indexed uniforms in the
        IR); outside the range reads (0, 0, 0, 0). c[aL + n] reaches only what the innermost
        loop's aL runs through."""
        reach = (range(_relative_range(self.p)) if op.relative.kind == "a"
                 else flow.aL_candidates(self, op.index, _relative_range(self.p)))
        return self.relative_select(op, reads, [dataclasses.replace(op, index=k, relative=None)
                                                for k in reach],
                                    lambda k: self.constant(k))

    def address(self, op: Operand, reads: dict) -> int:
        """The register number a relative operand names: a0.c or aL, plus its offset."""
        rel = op.relative
        index_register = reads.get(("a", 0) if rel.kind == "a" else ("aL", 0))
        address = self.e.swizzle(self.e.const(ZERO) if index_register is None
                                 else index_register, COMPONENTS[rel.component] * 4)
        return self.b.add(address, self.e.const(float(op.index)))

    def relative_select(self, op: Operand, reads: dict, targets: list, read: Any) -> int:
        """The register of `targets` (operands with fixed numbers) the relative operand `op`
        addresses, by a select on its number: -|address - k| >= 0 only where they are equal.
        An address outside them reads (0, 0, 0, 0)."""
        address = self.address(op, reads)
        result = self.e.const(ZERO)
        for target in targets:
            off = self.b.neg(self.b.abs(self.b.sub(address, self.e.const(float(target.index)))))
            result = self.b.cmp(off, read(target.index), result)
        return result

    def relative_targets(self, op: Operand) -> list[Operand]:
        """The declared v# / o# registers v[aL + n] / o[aL + n] can reach in the innermost
        loop (its aL runs start, start + step, ...), as fixed operands."""
        limit = self.rules.registers.get(op.kind, 12)
        reach = flow.aL_candidates(self, op.index, limit)
        return [dataclasses.replace(op, index=k, relative=None) for k in reach
                if self.p.declaration(op.kind, k) is not None]

    def declared_targets(self, op: Operand) -> list[Operand]:
        """Every declared register of the kind a relative operand addresses (what a block
        holding an o[aL + n] write may write, whatever its loop)."""
        return [dataclasses.replace(op, index=d.register.index, relative=None)
                for d in self.p.dcls if d.register.kind == op.kind]

    def varying_input(self, index: int) -> int:
        if self.b.stage == "fragment":
            if self.rules.major >= 3:
                d = self.p.declaration("v", index)
                if d is None or d.usage is None:
                    raise AsmError(f"v{index} has no dcl_<usage>", self.p.location)
                name = input_name(d.usage, d.usage_index)
                return self.b.varying(name, name.upper())
            return self.b.varying(f"color{index}", f"COLOR{index}")
        name, components = self.vertex_input(index)
        return self.b.varying(name, name.upper(), components)

    def vertex_input(self, index: int) -> tuple[str, int]:
        d = self.p.declaration("v", index)
        if d is not None and d.usage is not None:
            return input_name(d.usage, d.usage_index), 4
        components = 4
        for el in self.ctx.decl or ():
            if el.register == index:
                components = max(1, min(4, el.count))
        if index not in DX8_INPUTS:
            raise AsmError(f"v{index} has no dcl_<usage> and no Direct3D 8 meaning",
                           self.p.location)
        return DX8_INPUTS[index], components

    def texcoord(self, index: int) -> int:
        return self.b.varying(f"texcoord{index}", f"TEXCOORD{index}")

    # -- writing results
    def write(self, instr: Instruction, value: int, *, computed: bool = True,
              mask: str | None = None) -> None:
        """Apply the instruction modifiers (shift, _sat) and, for computed values, the
        register precision; then merge into the destination under its write mask."""
        env = {"x": value, "scale": float(2.0 ** instr.shift)}
        facts = _WriteFacts(instr.shift, instr.saturate, computed, self.precision.range,
                            self.precision.grid)
        if self.precision.range is not None:
            env.update(range=self.precision.range, neg_range=-self.precision.range)
        if self.precision.grid is not None:
            env["grid"] = self.precision.grid
        for _, applies, tree in RESULT_MODIFIERS:
            if applies(facts):
                env["x"] = self.e.emit(tree, env)
        self.store(instr.dst, env["x"], mask or self.mask(instr))

    def mask(self, instr: Instruction) -> str:
        dst = instr.dst
        if dst.mask is not None:
            return "".join(COMPONENTS[c] for c in dst.mask)
        return instr.info.writes or COMPONENTS

    def initial(self, key: tuple[str, int], dst: Operand) -> int:
        """A register's value before any write: its current value, zero for temporaries,
        D3D's default for an output (which then counts as written)."""
        old = self.regs.get(key)
        if old is not None:
            return old
        if key[0] in ("r", "t", "a", "oC", "p"):
            return self.e.const(ZERO)
        self.written.append(key)
        return self.e.const(OUTPUT_DEFAULTS.get(self.output_name(dst), DEFAULT_VARYING))

    def store(self, dst: Operand, value: int, mask: str) -> None:
        """Merge under the write mask (and the predicate of a predicated instruction); a
        register held in a variable is assigned."""
        if dst.relative is not None:          # o[aL + n]: each register it may reach
            address = self.address(dst, self._reads)
            for target in self.relative_targets(dst):
                old = self.initial((target.kind, target.index), target)
                off = self.b.neg(self.b.abs(self.b.sub(address,
                                                       self.e.const(float(target.index)))))
                self.store(target, self.b.cmp(off, self.b.merge(old, value, mask), old), mask)
            return
        key = (dst.kind, dst.index if dst.index is not None else 0)
        old = self.initial(key, dst)
        new = self.b.merge(old, value, mask)
        if self.pred is not None:     # per component: new where the predicate holds
            new = self.b.cmp(self.b.sub(self.pred, self.e.const(0.5)), new, old)
        variable = self.variables.get(key)
        if variable is not None:
            self.b.assign(variable, new)
        else:
            self.regs[key] = new

    def kill(self, value: int, components: str) -> None:
        """texkill, only where the predicate (if any) holds."""
        if self.pred is not None:
            value = self.b.cmp(self.b.sub(self.pred, self.e.const(0.5)), value,
                               self.e.const(ZERO))
        self.b.kill(value, components)

    # -- arithmetic
    def arithmetic(self, instr: Instruction, reads: dict, rewrite: Rewrite) -> None:
        roles = instr.info.source_roles
        names = "abc"
        env: dict[str, Any] = {
            names[k]: self.source(src, reads, scalar=roles[k] == "x")
            for k, src in enumerate(instr.srcs[:3]) if roles[k] in "sx"}
        if rewrite.dst_uniform is not None:
            name, prefix = rewrite.dst_uniform
            env[name] = self.b.uniform(f"{prefix}{instr.dst.index}")
        self.write(instr, self.e.emit(self.tree(instr, rewrite), env))

    def tree(self, instr: Instruction, rewrite: Rewrite) -> Any:
        """The rewrite's tree, or the first variant whose condition holds."""
        mask = self.mask(instr) if instr.dst is not None else ""
        for applies, tree in rewrite.variants:
            if applies(instr, mask):
                return tree
        return rewrite.tree

    def matrix(self, instr: Instruction, reads: dict, rewrite: Rewrite) -> None:
        """A matrix macro: the row's rewrite (a dot product) once per consecutive register
        of the second source, into successive components."""
        a = self.source(instr.srcs[0], reads)
        m = instr.srcs[1]
        result = None
        for i in range(instr.info.matrix_rows):
            row = self.source(dataclasses.replace(m, index=m.index + i), reads)
            d = self.e.emit(rewrite.tree, {"a": a, "b": row})
            result = d if result is None else self.b.merge(result, d, COMPONENTS[i])
        self.write(instr, result)

    # -- outputs
    def output_name(self, dst: Operand) -> str:
        kind, index = dst.kind, dst.index
        if kind in VS_OUTPUTS:
            return VS_OUTPUTS[kind]
        if kind == "oD":
            return f"color{index}"
        if kind == "oT":
            return f"texcoord{index}"
        if kind == "o":
            d = self.p.declaration("o", index)
            if d is None or d.usage is None:
                raise AsmError(f"o{index} has no dcl_<usage>", dst.location)
            name = VS3_USAGE_OUTPUTS.get(d.usage, input_name(d.usage, d.usage_index))
            if name not in OUTPUTS["vertex"]:
                raise AsmError(f"o{index} (dcl_{d.usage}{d.usage_index or ''}) is not an "
                               "output this framework passes on", dst.location)
            return name
        if kind == "oC":
            return f"color{index}"
        if kind == "oDepth":
            return "depth"
        raise AsmError(f"{dst.name} is not an output register", dst.location)

    def outputs(self) -> None:
        b = self.b
        if self.b.stage == "vertex":
            saturate = self.rules.major < 3
            b.clamp_colors = saturate        # SM3 colour interpolators are not clamped
            for key in self.written:
                name = self.output_name(Operand(key[0], key[1]))
                value = self.regs[key]
                b.output(name, b.saturate(value) if saturate and name.startswith("color")
                         else value)
            return
        if self.rules.is_ps1:
            r0 = self.regs.get(("r", 0))
            b.output("color0", b.saturate(self.e.const(ZERO) if r0 is None else r0))
        else:
            for (kind, index), value in self.regs.items():
                if kind == "oC":
                    b.output(f"color{index}", value)
                elif kind == "oDepth":
                    b.output("depth", value)
        if self.depth is not None:
            b.output("depth", self.depth)

    # -- texture helpers
    def sampler_kind(self, stage: int, default: str = "2d") -> str:
        d = self.p.declaration("s", stage)
        if d is not None and d.sampler_type:
            return SAMPLER_TYPES[d.sampler_type]
        return self.ctx.sampler_kinds.get(stage, default)

    def sample(self, stage: int, coord: int, default: str = "2d", **flags: bool) -> int:
        return self.b.sample(self.sampler_index(stage), coord, self.sampler_kind(stage, default),
                             **flags)

    def sampler_index(self, register: int) -> int:
        """The IR sampler of s#: the pixel sampler of that number, or in a vertex shader the
        vertex texture sampler D3DVERTEXTEXTURESAMPLER0 + n (257 + n), a separate unit."""
        return register + VERTEX_TEXTURE_SAMPLER0 if self.b.stage == "vertex" else register

    def projected_coord(self, stage: int) -> int:
        """tc(stage), divided by w first when that stage is PROJECTED (texbem order)."""
        tc = self.texcoord(stage)
        if self.ctx.projected.get(stage):
            tc = self.b.mul(tc, self.b.rcp(self.e.swizzle(tc, "wwww")))
        return tc
