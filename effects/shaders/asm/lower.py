"""Lower assembled Direct3D shaders (vs_1_1-vs_3_0, ps_1_1-ps_1_4, ps_2_0/2_x) to the IR.

    program = lower_pixel_shader(asm, ShaderContext(options))     # stage 'fragment'
    program = lower_vertex_shader(asm, ShaderContext(options))    # stage 'vertex'
    constant_registers(asm)     # the c# the pass must supply as uniforms `c0`, `c1` ...

Instruction by instruction, over a register file of IR values (SSA, so a snapshot is a dict
copy). What each instruction, modifier and macro computes lives in rewrites.py as data; this
module reads operands, picks the row, and writes results. Texture-addressing instructions have
their own small handlers, registered by the table's `op` key.

Decisions (sources: ../shared/reference/semantics.md §2-4, caps.md §1):
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
- Flow control, predication, gradients and texldd raise AsmError: not lowered yet.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping

from effects.errors import AsmError
from effects.ir import COMPONENTS, OUTPUTS, Builder, Program
from effects.model import VertexDeclElement
from effects.precision import LoweringOptions
from effects.shaders.asm.program import AsmProgram, Instruction, Operand
from effects.shaders.asm.rewrites import (INSTRUCTIONS, MATRIX_MACROS, NEGATE, PRE_SWIZZLE_MODIFIERS,
                       RESULT_MODIFIERS, SOURCE_MODIFIERS, Emitter)

__all__ = ["ShaderContext", "constant_registers", "lower_pixel_shader", "lower_vertex_shader",
           "input_name"]

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


def lower_pixel_shader(program: AsmProgram, ctx: ShaderContext) -> Program:
    """The fragment IR of a ps_1_x / ps_2_x (/ ps_3_0 without flow control) program."""
    if program.kind != "ps":
        raise AsmError(f"{program.name} is not a pixel shader", program.location)
    return _Lowering(program, ctx, "fragment").run()


def lower_vertex_shader(program: AsmProgram, ctx: ShaderContext) -> Program:
    """The vertex IR of a vs_1_1 / vs_2_x / vs_3_0 program (without flow control)."""
    if program.kind != "vs":
        raise AsmError(f"{program.name} is not a vertex shader", program.location)
    return _Lowering(program, ctx, "vertex").run()


def constant_registers(program: AsmProgram) -> set[int]:
    """The c# the program reads that it does not `def`: the pass supplies them as uniforms."""
    used: set[int] = set()
    for instr in program.instructions:
        if instr.info.category == "setup":
            continue
        rows = MATRIX_MACROS.get(instr.info.op, (None, 1))[1]
        for k, src in enumerate(instr.srcs):
            if src.kind != "c" or src.index is None:
                continue
            if src.relative is not None:
                used.update(range(_relative_range(program)))
            else:
                used.update(range(src.index, src.index + (rows if k == 1 else 1)))
    return used - set(program.defs)


def input_name(usage: str, index: int) -> str:
    """The IR name of a vertex input (or ps_3_0 varying) declared `dcl_<usage><index>`."""
    return f"{usage}{index}" if usage in ("texcoord", "color") or index else usage


def _relative_range(program: AsmProgram) -> int:
    return program.rules.constants_min or program.rules.registers.get("c", 0)


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

    # -- driver
    def run(self) -> Program:
        instrs = self.p.instructions
        i = 0
        while i < len(instrs):
            group = [instrs[i]]
            while i + len(group) < len(instrs) and instrs[i + len(group)].coissue:
                group.append(instrs[i + len(group)])
            snapshot = dict(self.regs)             # co-issued halves read the pre-pair state
            for instr in group:
                self.lower(instr, snapshot)
            i += len(group)
        self.outputs()
        return self.b.build()

    def lower(self, instr: Instruction, reads: dict[tuple[str, int], int]) -> None:
        info = instr.info
        if info.category == "setup" or info.op == "nop":
            return
        if info.category == "flow":
            raise AsmError(f"{instr.opcode}: flow control is not lowered yet", instr.location)
        if instr.predicate is not None:
            raise AsmError(f"{instr.opcode}: predication is not lowered yet", instr.location)
        handler = TEXTURE_HANDLERS.get(info.op) if info.category == "tex" else None
        if handler is not None:
            handler(self, instr, reads)
        elif info.op in MATRIX_MACROS:
            self.matrix(instr, reads)
        elif info.op in ARITH_NOT_LOWERED or info.category == "tex":
            raise AsmError(f"{instr.opcode}: not lowered yet", instr.location)
        else:
            self.arithmetic(instr, reads)

    # -- reading operands
    def source(self, op: Operand, reads: dict, *, scalar: bool = False) -> int:
        """An operand's value: register (or relative constant), dz/dw, swizzle, modifier,
        negate; a scalar source then replicates its selected component (w after the swizzle,
        so .x gives x and no swizzle gives w: semantics.md §4)."""
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
        if op.relative is not None and kind != "c":
            raise AsmError(f"relative addressing of {op.name} is not lowered yet", op.location)
        if kind == "c":
            if op.relative is not None:
                return self.relative_constant(op, reads)
            return self.constant(index)
        if kind == "v":
            return self.varying_input(index)
        if kind == "t" and not self.rules.is_ps11_13:
            return self.texcoord(index)
        if kind in ("r", "t", "a"):
            value = reads.get((kind, index))
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
        IR); outside the range reads (0, 0, 0, 0)."""
        rel = op.relative
        if rel.kind != "a":
            raise AsmError("aL-relative addressing is not lowered yet", op.location)
        a0 = reads.get(("a", 0))
        address = self.e.swizzle(self.e.const(ZERO) if a0 is None else a0,
                                 COMPONENTS[rel.component] * 4)
        address = self.b.add(address, self.e.const(float(op.index)))
        result = self.e.const(ZERO)
        for k in range(_relative_range(self.p)):
            off = self.b.neg(self.b.abs(self.b.sub(address, self.e.const(float(k)))))
            result = self.b.cmp(off, self.constant(k), result)   # -|addr - k| >= 0 iff equal
        return result

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
        switches = {"shift": instr.shift != 0, "saturate": instr.saturate,
                    "range": computed and self.precision.range is not None,
                    "quantize": computed and self.precision.grid is not None}
        if self.precision.range is not None:
            env.update(range=self.precision.range, neg_range=-self.precision.range)
        if self.precision.grid is not None:
            env["grid"] = self.precision.grid
        for name, tree in RESULT_MODIFIERS:
            if switches[name]:
                env["x"] = self.e.emit(tree, env)
        self.store(instr.dst, env["x"], mask or self.mask(instr))

    def mask(self, instr: Instruction) -> str:
        dst = instr.dst
        if dst.mask is not None:
            return "".join(COMPONENTS[c] for c in dst.mask)
        return instr.info.writes or COMPONENTS

    def store(self, dst: Operand, value: int, mask: str) -> None:
        if dst.relative is not None:
            raise AsmError(f"relative addressing of {dst.name} is not lowered yet",
                           dst.location)
        key = (dst.kind, dst.index if dst.index is not None else 0)
        old = self.regs.get(key)
        if old is None:
            if key[0] in ("r", "t", "a", "oC"):
                old = self.e.const(ZERO)
            else:
                old = self.e.const(OUTPUT_DEFAULTS.get(self.output_name(dst), DEFAULT_VARYING))
                self.written.append(key)
        self.regs[key] = self.b.merge(old, value, mask)

    # -- arithmetic
    def arithmetic(self, instr: Instruction, reads: dict) -> None:
        info = instr.info
        roles = info.source_roles
        names = "abc"
        env: dict[str, Any] = {
            names[k]: self.source(src, reads, scalar=roles[k] == "x")
            for k, src in enumerate(instr.srcs[:3]) if roles[k] in "sx"}
        key = self.rule(instr)
        if key == "bem":
            env["bumpenv"] = self.b.uniform(f"bumpenv{instr.dst.index}")
        if key not in INSTRUCTIONS:
            raise AsmError(f"{instr.opcode}: not lowered yet", instr.location)
        self.write(instr, self.e.emit(INSTRUCTIONS[key], env))

    def rule(self, instr: Instruction) -> str:
        """The INSTRUCTIONS row for an instruction: its op key, or a version variant."""
        op = instr.info.op
        for (name, applies), key in RULE_VARIANTS.items():
            if name == op and applies(self, instr):
                return key
        return op

    def matrix(self, instr: Instruction, reads: dict) -> None:
        dot, rows = MATRIX_MACROS[instr.info.op]
        a = self.source(instr.srcs[0], reads)
        m = instr.srcs[1]
        result = None
        for i in range(rows):
            row = self.source(dataclasses.replace(m, index=m.index + i), reads)
            d = getattr(self.b, dot)(a, row)
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
        return self.b.sample(stage, coord, self.sampler_kind(stage, default), **flags)

    def projected_coord(self, stage: int) -> int:
        """tc(stage), divided by w first when that stage is PROJECTED (texbem order)."""
        tc = self.texcoord(stage)
        if self.ctx.projected.get(stage):
            tc = self.b.mul(tc, self.b.rcp(self.e.swizzle(tc, "wwww")))
        return tc


# Version variants of an instruction's row: ((op, test), row key), first match wins.
def _ps11_13(lo: _Lowering, instr: Instruction) -> bool:
    return lo.rules.is_ps11_13


def _coissued_colour(lo: _Lowering, instr: Instruction) -> bool:
    return lo.rules.is_ps11_13 and instr.coissue and lo.mask(instr) != "w"


def _vs1(lo: _Lowering, instr: Instruction) -> bool:
    return lo.rules.kind == "vs" and lo.rules.major == 1


def _to_address(lo: _Lowering, instr: Instruction) -> bool:
    return instr.dst is not None and instr.dst.kind == "a"


RULE_VARIANTS: dict[tuple[str, Callable[[_Lowering, Instruction], bool]], str] = {
    ("cnd", _coissued_colour): "cnd.coissue",
    ("cnd", _ps11_13): "cnd.alpha",
    ("expp", _vs1): "expp.vs1",
    ("logp", _vs1): "logp.vs1",
    ("mov", _to_address): "mov.a0",
}
ARITH_NOT_LOWERED = frozenset({"dsx", "dsy", "setp"})


# --------------------------------------------------------------------------------------------
# Texture-addressing instructions, registered by op key.

TextureHandler = Callable[[_Lowering, Instruction, dict], None]
TEXTURE_HANDLERS: dict[str, TextureHandler] = {}


def _texture(*ops: str) -> Callable[[TextureHandler], TextureHandler]:
    def register(fn: TextureHandler) -> TextureHandler:
        for op in ops:
            TEXTURE_HANDLERS[op] = fn
        return fn
    return register


def _dot_row(lo: _Lowering, instr: Instruction, reads: dict) -> int:
    """tc(m) . t(n).rgb for the texm3x* / texdp3 rows (m = destination register)."""
    return lo.b.dp3(lo.texcoord(instr.dst.index), lo.source(instr.srcs[0], reads))


def _xyz(lo: _Lowering, u: int, v: int, w: int | None = None, fill: int | None = None) -> int:
    coord = lo.b.merge(u, v, "y")
    if w is not None:
        coord = lo.b.merge(coord, w, "z")
    return lo.b.merge(coord, fill, "w") if fill is not None else coord


@_texture("tex")
def _tex(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    m = instr.dst.index
    proj = bool(lo.ctx.projected.get(m))
    lo.write(instr, lo.sample(m, lo.texcoord(m), proj=proj), computed=False)


@_texture("texcoord")
def _texcoord(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    tc = lo.b.saturate(lo.texcoord(instr.dst.index))
    lo.write(instr, lo.b.merge(lo.e.const(ONE), tc, "xyz"))


@_texture("texkill")
def _texkill(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    if lo.rules.is_ps11_13:
        lo.b.kill(lo.texcoord(instr.dst.index), "xyz")
    elif lo.rules.is_ps14:
        lo.b.kill(lo.source(instr.dst, reads), "xyz")
    else:
        lo.b.kill(lo.source(instr.srcs[0], reads), "xyzw")


def _bumped(lo: _Lowering, instr: Instruction, reads: dict) -> tuple[int, int]:
    """texbem: sample stage m at tc(m).uv + M(m) (t(n).r, t(n).g); also returns t(n)."""
    m = instr.dst.index
    src = lo.source(instr.srcs[0], reads)
    bumpenv = lo.b.uniform(f"bumpenv{m}")
    offset = lo.e.emit(INSTRUCTIONS["bem"], {"a": lo.e.const(ZERO), "b": src,
                                             "bumpenv": bumpenv})
    tc = lo.projected_coord(m)
    coord = lo.b.merge(tc, lo.b.add(tc, offset), "xy")
    return lo.sample(m, coord), src


@_texture("texbem")
def _texbem(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    texel, _ = _bumped(lo, instr, reads)
    lo.write(instr, texel, computed=False)


@_texture("texbeml")
def _texbeml(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    # L = sat(t(n).b * LSCALE(m) + LOFFSET(m)); clamped as the FF path and DXVK do (2.5)
    texel, src = _bumped(lo, instr, reads)
    scale_offset = lo.b.uniform(f"bumpenvl{instr.dst.index}")
    lum = lo.b.saturate(lo.b.mad(lo.e.swizzle(src, "zzzz"), lo.e.swizzle(scale_offset, "xxxx"),
                                 lo.e.swizzle(scale_offset, "yyyy")))
    lo.write(instr, lo.b.mul(texel, lum))


_REG2 = {"texreg2ar": "wxxx", "texreg2gb": "yzzz", "texreg2rgb": "xyzz"}


@_texture(*_REG2)
def _texreg2(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    coord = lo.e.swizzle(lo.source(instr.srcs[0], reads), _REG2[instr.info.op])
    default = "3d" if instr.info.op == "texreg2rgb" else "2d"
    lo.write(instr, lo.sample(instr.dst.index, coord, default), computed=False)


@_texture("texm3x2pad", "texm3x3pad")
def _pad(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    if instr.info.op == "texm3x2pad" or not lo.pending_rows or len(lo.pending_rows) >= 2:
        lo.pending_rows = []
    lo.pending_rows.append(_dot_row(lo, instr, reads))


def _rows(lo: _Lowering, instr: Instruction, count: int) -> list[int]:
    rows, lo.pending_rows = lo.pending_rows, []
    if len(rows) != count:
        raise AsmError(f"{instr.opcode} needs {count} pad instruction(s) before it",
                       instr.location)
    return rows


@_texture("texm3x2tex")
def _texm3x2tex(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    (u,) = _rows(lo, instr, 1)
    coord = _xyz(lo, u, _dot_row(lo, instr, reads))
    lo.write(instr, lo.sample(instr.dst.index, coord), computed=False)


@_texture("texm3x2depth")
def _texm3x2depth(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    (u,) = _rows(lo, instr, 1)
    w = _dot_row(lo, instr, reads)
    ratio = lo.b.saturate(lo.b.mul(u, lo.b.rcp(w)))
    lo.depth = lo.b.cmp(lo.b.neg(lo.b.abs(w)), lo.e.const(ONE), ratio)   # w == 0 gives 1


@_texture("texm3x3tex", "texm3x3", "texm3x3spec", "texm3x3vspec")
def _texm3x3(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    u, v = _rows(lo, instr, 2)
    n = _xyz(lo, u, v, _dot_row(lo, instr, reads))
    m = instr.dst.index
    op = instr.info.op
    if op == "texm3x3":
        lo.write(instr, lo.b.merge(n, lo.e.const(ONE), "w"))
        return
    if op == "texm3x3tex":
        lo.write(instr, lo.sample(m, n, "cube"), computed=False)
        return
    if op == "texm3x3spec":
        eye = lo.source(instr.srcs[1], reads)
    else:   # the eye vector rides in the w of the three rows' texture coordinates
        eye = _xyz(lo, *(lo.e.swizzle(lo.texcoord(m - 2 + k), "wwww") for k in range(3)))
    # R = 2 N (N.E) / (N.N) - E
    b = lo.b
    factor = b.mul(lo.e.const(2.0), b.mul(b.dp3(n, eye), b.rcp(b.dp3(n, n))))
    lo.write(instr, lo.sample(m, b.sub(b.mul(n, factor), eye), "cube"), computed=False)


@_texture("texdp3")
def _texdp3(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    lo.write(instr, _dot_row(lo, instr, reads))


@_texture("texdp3tex")
def _texdp3tex(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    coord = lo.b.merge(lo.e.const(ZERO), _dot_row(lo, instr, reads), "x")
    lo.write(instr, lo.sample(instr.dst.index, coord), computed=False)


@_texture("texdepth")
def _texdepth(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    # depth = sat(r5.r / min(r5.g, 1)); g == 0 gives 1 (semantics.md 2.6, Wine's formula)
    b, r5 = lo.b, lo.source(instr.dst, reads)
    g = lo.e.swizzle(r5, "yyyy")
    ratio = b.saturate(b.mul(lo.e.swizzle(r5, "xxxx"), b.rcp(b.min(g, lo.e.const(ONE)))))
    lo.depth = b.cmp(b.neg(b.abs(g)), lo.e.const(ONE), ratio)


@_texture("texcrd")
def _texcrd(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    lo.write(instr, lo.source(instr.srcs[0], reads))


@_texture("texld", "texldp", "texldb", "texldl")
def _texld(lo: _Lowering, instr: Instruction, reads: dict) -> None:
    coord = lo.source(instr.srcs[0], reads)
    if lo.rules.is_ps14:                           # stage = destination register number
        lo.write(instr, lo.sample(instr.dst.index, coord), computed=False)
        return
    flags = {"texldp": {"proj": True}, "texldb": {"bias": True},
             "texldl": {"lod": True}}.get(instr.info.op, {})
    lo.write(instr, lo.sample(instr.srcs[1].index, coord, **flags), computed=False)

