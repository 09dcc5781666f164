"""Shaders for the bytecode tests: every shader of every bundled effect (assembly and compiled
HLSL), a program for every instruction of every version (the generator of
tests/shaders/asm/test_every_instruction.py), and hand-written programs for what those leave
out (relative addressing, predicates, co-issue, phase, flow control, modifiers, declarations).
`normalized` is a program as bytecode holds it."""
from __future__ import annotations

import dataclasses
import struct
from functools import lru_cache

import effects
from effects.base.errors import UNKNOWN_LOCATION, Location
from effects.model import CompileShader, ShaderBlock
from effects.shaders.asm import AsmProgram, assemble
from effects.shaders.asm.program import Operand
from effects.shaders.asm.text import canonical_swizzle_text
from effects.shaders.shader_value import shader_of
from tests.paths import ROOT, TESTS
from tests.shaders.asm.test_every_instruction import PAIRS, _row, program_text

EFFECT_FILES = sorted((ROOT / "fxfiles").glob("*.fx")) + sorted(
    (TESTS / "data" / "realfx").rglob("*.fx"))

FEATURES = {
    "vs11_relative": """vs_1_1
dcl_position v0
dcl_normal v3
dcl_texcoord1 v7
def c95, 1.5, -2.25, 0.1, 1e-7
mov a0.x, v7.x
mov r0, c[a0.x + 5]
m4x4 oPos, v0, c0
expp r1, v3.x
logp r1.y, v3.w
frc r2.xy, r0
mov oFog, r0.x
mov oPts, r0.y
mad oD0, -r0.wzyx, c95.x, v3
mov oT7.xyz, c[a0.x]
""",
    "ps11_coissue": """ps_1_1
def c0, 0.5, 0.25, 1, 0
tex t0
tex t1
mul r0.rgb, t0_bx2, v0
+add r0.a, 1-t1.a, v1_bias
mul_x2 r1, r0, c0
mad_d2 r1.rgb, -t0, v0, r1
+mov_sat r1.a, c0.b
cnd r0, r0.a, r1, t0
""",
    "ps14_phase": """ps_1_4
def c0, 0.5, 0.25, 1, 0
texld r0, t0
texcrd r1.rgb, t1.xyw
mul_x8 r0, r0_x2, c0
phase
texld r2, r0_dz.xyz
texld r3, r1
add_d8 r0, r2, r3.b
mov_sat r0.a, -r2_bx2.a
""",
    "ps2a_predicate": """ps_2_a
defi i0, 4, 0, 1, 0
def c1, 0, 0, 0, 0
dcl t0.xy
dcl_pp t1
dcl_2d s0
dcl_cube s1
dcl_volume s2
setp_gt p0, t0, c1
(p0) add r1, t0, c1
(!p0.x) mov r1, c1
if_gt t0.x, c1.y
texldp_pp r2, t0, s0
else
texldb r2, t1, s1
endif
rep i0
texldd r3, t0, s2, t1, t0
break_ne r3.x, c1.x
endrep
dsx r4, t0
dsy_sat r5.yz, t1.wzyx
abs r6, -r5
mov oC0, r2
mov oDepth, r4.x
""",
    "ps30_loop": """ps_3_0
defi i0, 3, 0, 1, 0
defb b0, true
def c2, 1, 2, 3, 4
dcl_texcoord0_centroid v0.xy
dcl_color1 v1
dcl vFace
dcl vPos.xy
dcl_2d s0
loop aL, i0
mov r0, c[aL + 2]
add r1, r0_abs, -v[aL]
endloop
if b0
call l0
endif
callnz l1, !b0
sincos r2.xy, r0.x
texldl r3, v0, s0
mov_pp oC0, r3
mov oC1, vPos
cmp oDepth, vFace, r1.x, c2.y
ret
label l0
mov r4, c2
ret
label l1
ret
""",
    "vs30_outputs": """vs_3_0
dcl_position v0
dcl_texcoord3 v1
dcl_position o0
dcl_texcoord2 o1.xy
dcl_fog o2.x
dcl_2d s0
defi i1, 2, 0, 1, 0
mova a0.xy, v1
mov r0, c[a0.y + 3]
texldl r1, v1, s0
loop aL, i1
mov o[aL + 1].xy, r0
endloop
mov o0, v0
mov_sat o2.x, r1_abs.y
""",
    "vs20_flow": """vs_2_0
dcl_position v0
dcl_blendweight v1
dcl_blendindices v2
defb b3, false
defi i15, 255, 255, 1, 0
def c0, -1.5258789e-005, -0.0013888889, 0.041666668, -0.5
def c1, -0.020833334, -0.125, 1, 0.5
mova a0.x, v2.x
sincos r0.xy, v1.x, c0, c1
lit r1, v1
dst r2, r1, v1
crs r3.xyz, v1, v2
nrm r4, v1
pow r5, r1.x, v1.y
mov r7, v0
mov r8, v0
sgn r6, v1, r7, r8
m3x2 r9.xy, v0, c[a0.x + 10]
rep i15
loop aL, i15
add r1, r1, c[aL + 4]
endloop
endrep
if b3
mov oPos, v0
else
m4x3 oPos.xyz, v0, c4
mov oPos.w, c1.z
endif
mov oD1.xyz, r0
""",
    "vs11_big_constants": """vs_1_1
dcl_position v0
mov oPos, c95
""",
}


def block(text: str, name: str = "t") -> ShaderBlock:
    """An asm block of `text` (its stage from its version token, after any // comments)."""
    first = next(line for line in text.splitlines() if line.strip() and
                 not line.lstrip().startswith("//"))
    stage = "pixel" if first.lstrip().lower().startswith("ps") else "vertex"
    return ShaderBlock(stage, None, text, location=Location(f"{name}.fx", 1, 1))


def _values(effect):
    for p in effect.parameters:
        v = p.value
        for x in (v if isinstance(v, (list, tuple)) else [v]):
            if isinstance(x, (CompileShader, ShaderBlock)):
                yield x
    for t in effect.techniques:
        for ps in t.passes:
            for state in ("VertexShader", "PixelShader"):
                a = ps.state(state)
                if a is not None and isinstance(a.value, (CompileShader, ShaderBlock)):
                    yield a.value


@lru_cache(maxsize=None)
def effect_shaders() -> list[tuple[str, object]]:
    """(name, Shader) of every shader of every bundled and corpus effect that assembles or
    compiles (those that do not are other tests' business)."""
    out = []
    for path in EFFECT_FILES:
        try:
            effect = effects.load_effect(path)
        except effects.EffectError:     # D3D10 syntax in the corpus: rejected on purpose
            continue
        seen = set()
        for k, value in enumerate(_values(effect)):
            if id(value) in seen:
                continue
            seen.add(id(value))
            try:
                shader = shader_of(effect, value)
            except effects.EffectError:
                continue
            if shader is not None:
                out.append((f"{path.relative_to(ROOT)}#{k}", shader))
    return out


@lru_cache(maxsize=None)
def instruction_programs() -> list[tuple[str, AsmProgram]]:
    out = []
    for name, version in PAIRS:
        text = program_text(_row(name, version), version)
        if text is not None:
            out.append((f"{name}-{version}", assemble(block(text))))
    return out


def feature_programs() -> list[tuple[str, AsmProgram]]:
    return [(name, assemble(block(text, name))) for name, text in FEATURES.items()]


def _operand(op: Operand | None, dst: bool = False) -> Operand | None:
    if op is None:
        return None
    if dst or op.mask is not None:
        mask = None if op.mask == (0, 1, 2, 3) else op.mask
        text = "" if mask is None else "".join("xyzw"[c] for c in mask)
        return dataclasses.replace(op, mask=mask, swizzle_text=text, location=UNKNOWN_LOCATION)
    return dataclasses.replace(op, swizzle_text=canonical_swizzle_text(op.swizzle),
                               location=UNKNOWN_LOCATION)


def _f32(values) -> tuple:
    return tuple(struct.unpack("<4f", struct.pack("<4f", *values))) if len(values) == 4 \
        else tuple(values)


def _fixed_mask(ins) -> Operand | None:
    """`m3x3 r0` writes the .xyz its row fixes: bytecode spells that mask out."""
    if ins.dst is None or ins.dst.mask is not None or not ins.info.writes:
        return ins.dst
    return dataclasses.replace(ins.dst, mask=tuple("xyzw".index(c) for c in ins.info.writes))


def normalized(p: AsmProgram) -> AsmProgram:
    """`p` as bytecode holds it: no source positions, a swizzle in its shortest spelling, a
    .xyzw write mask as none, a matrix macro's missing mask as the one it writes, def values as float32, no DX8 decl{} inputs (a vertex
    declaration, not shader tokens)."""
    instructions = [dataclasses.replace(
        ins, dst=_operand(_fixed_mask(ins), dst=True), srcs=[_operand(s) for s in ins.srcs],
        predicate=_operand(ins.predicate)) for ins in p.instructions]
    defs = [dataclasses.replace(d, register=_operand(d.register, dst=True),
                                values=_f32(d.values) if d.register.kind == "c" else d.values)
            for d in p.def_statements]
    dcls = [dataclasses.replace(d, register=_operand(d.register, dst=True))
            for d in p.dcls if not d.from_decl]
    return AsmProgram(kind=p.kind, version=p.version, name=p.name, rules=p.rules,
                      instructions=instructions, defs={k: _f32(v) for k, v in p.defs.items()},
                      int_defs=dict(p.int_defs), bool_defs=dict(p.bool_defs), dcls=dcls,
                      def_statements=defs, phase_locations=[UNKNOWN_LOCATION] * len(
                          p.phase_locations))
