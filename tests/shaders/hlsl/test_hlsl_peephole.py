"""The back half's rewrites (issue 31: code as tight as fxc's), each shown by the code it makes
with and without it (the instruction count drops) and by what the code computes, on both back
ends: effects/shaders/hlsl/peephole.py (copies, clamp -> _sat, folding into the producer),
fusion.py (mad, lrp), intrinsics' pow, legalize's temporaries and codegen's packing."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

import effects
from effects.program.backend import create_backend
from effects.shaders.asm import check
from effects.shaders.asm.versions import VERSIONS
from effects.shaders.hlsl import codegen, compile_shader, peephole
from effects.shaders.asm.program import Instruction as Instr, Operand as Reg
from effects.shaders.hlsl.records import fixed, instruction, read, reg, same, written


def compiled(functions: str, entry: str, target: str):
    fx = effects.load_effect(functions + "\ntechnique T { pass P { } }\n")
    shader = compile_shader(fx, entry, target)
    assert check(shader.program) == []
    return shader


def body(shader) -> list[str]:
    """The instructions (no version, def or dcl lines)."""
    return [line for line in shader.text.splitlines()[1:]
            if not line.startswith(("def", "dcl"))]


def drawn(text: str, card: str, backend: str) -> np.ndarray:
    """The effect drawn on an 8x8 quad, freshly compiled (after a pass was left out too)."""
    effects.clear_caches()
    img = effects.render(effects.load_effect(text), card, technique="T", backend=backend,
                         scene={"mesh": "quad", "size": [8, 8]})
    effects.clear_caches()
    return img.astype(np.float64) / 255.0


def without(monkeypatch, name: str) -> None:
    """Run the compiler with one peephole pass left out."""
    monkeypatch.setattr(peephole, "PASSES", tuple(p for p in peephole.PASSES if p[0] != name))


CONSTANT_OUT = "float4 C; float4 PS() : COLOR { return C; }"


@pytest.mark.parametrize("left_out", ["propagate copies", "fold into producer"])
def test_a_constant_is_read_in_place_not_copied_through_a_temporary(monkeypatch, left_out):
    assert body(compiled(CONSTANT_OUT, "PS", "ps_2_0")) == ["mov oC0, c0"]
    without(monkeypatch, left_out)              # either pass alone does it
    assert body(compiled(CONSTANT_OUT, "PS", "ps_2_0")) == ["mov oC0, c0"]
    without(monkeypatch, "propagate copies" if left_out != "propagate copies" else
            "fold into producer")
    assert body(compiled(CONSTANT_OUT, "PS", "ps_2_0")) == ["mov r0, c0", "mov oC0, r0"]


PACKED = ("float4x4 W; float4x4 VP; float4 Eye;\n"
          "struct O { float4 p : POSITION; float3 e : TEXCOORD0; };\n"
          "O VS(float4 p : POSITION) { O o; float3 w = mul(p, W).xyz;\n"
          "o.p = mul(float4(w, 1), VP); o.e = Eye.xyz - w; return o; }")


def test_a_gathered_register_is_read_in_place_with_its_sign(monkeypatch):
    assert body(compiled(PACKED, "VS", "vs_1_1"))[-1] == "add oT0.xyz, c7, -r0"
    without(monkeypatch, "propagate copies")
    assert body(compiled(PACKED, "VS", "vs_1_1"))[-2:] == ["mov r0.xyz, -r0", "add oT0.xyz, c7, r0"]


def test_a_copy_stays_where_the_read_ports_need_it():
    # ps_2_0 reads one v# an instruction: v1 goes through a temporary (fxc's code too)
    shader = compiled("float4 C; float4 PS(float4 a : COLOR0, float4 b : COLOR1) : COLOR "
                      "{ return a * b + C; }", "PS", "ps_2_0")
    assert body(shader) == ["mov r0, v1", "mad r0, v0, r0, c0", "mov oC0, r0"]
    # vs_1_1 reads one c# an instruction
    shader = compiled("float4 A, B; float4 VS(float4 p : POSITION) : POSITION "
                      "{ return p * A + B; }", "VS", "vs_1_1")
    assert body(shader) == ["mov r0, c1", "mad oPos, v0, c0, r0"]


CLAMPED = ("float4 C; float4 PS(float4 a : COLOR0, float4 b : COLOR1) : COLOR "
           "{ return clamp(a * b + C, 0, 1); }")


def test_clamp_0_1_is_a_saturate_on_the_producing_instruction(monkeypatch):
    assert body(compiled(CLAMPED, "PS", "ps_2_0")) == [
        "mov r0, v1", "mad_sat r0, v0, r0, c0", "mov oC0, r0"]
    assert body(compiled(CLAMPED, "PS", "ps_3_0")) == ["mad_sat oC0, v0, v1, c0"]
    without(monkeypatch, "clamp to saturate")
    assert len(body(compiled(CLAMPED, "PS", "ps_2_0"))) == 5     # mad, max, min, mov + copy


def test_clamp_stays_max_min_where_the_version_has_no_saturate():
    text = body(compiled("float4 VS(float4 p : POSITION) : POSITION "
                         "{ return clamp(p, 0, 1); }", "VS", "vs_2_0"))
    assert [line.split()[0] for line in text] == ["max", "min"]


def test_a_result_is_written_where_the_mov_after_it_would_put_it(monkeypatch):
    src = "float4 C; float4 PS(float4 a : COLOR0) : COLOR { return a * C; }"
    assert body(compiled(src, "PS", "ps_3_0")) == ["mul oC0, v0, c0"]
    # ps_2_0 writes oC0 with mov only (the checker holds it)
    assert body(compiled(src, "PS", "ps_2_0")) == ["mul r0, v0, c0", "mov oC0, r0"]
    without(monkeypatch, "fold into producer")
    assert body(compiled(src, "PS", "ps_3_0")) == ["mul r0, v0, c0", "mov oC0, r0"]


LERPS = {
    "x*(1-a) + y*a": "a * (1 - f) + b * f",
    "(1-a)*x + a*y": "(1 - f) * a + f * b",
    "x + (y-x)*a": "a + (b - a) * f",
}


@pytest.mark.parametrize("expr", LERPS.values(), ids=list(LERPS))
def test_lerp_written_out_is_one_lrp(expr, monkeypatch):
    src = (f"float4 PS(float4 a : COLOR0, float4 b : COLOR1, float f : TEXCOORD0) : COLOR "
           f"{{ return {expr}; }}")
    assert body(compiled(src, "PS", "ps_3_0")) == ["lrp oC0, v2.x, v1, v0"]
    monkeypatch.setattr(codegen, "fuse_lrp", lambda nodes, uses: 0)
    assert len(body(compiled(src, "PS", "ps_3_0"))) == (2 if "(b - a)" in expr else 3)


def test_lerp_written_out_stays_arithmetic_on_vs_1_1():
    src = ("float4 VS(float4 a : POSITION, float4 b : COLOR1, float f : TEXCOORD0) : POSITION "
           "{ return a * (1 - f) + b * f; }")
    assert "lrp" not in compiled(src, "VS", "vs_1_1").text


def test_pow_by_a_small_whole_number_is_multiplication():
    src = "float4 PS(float4 a : COLOR0) : COLOR { return pow(a, %s); }"
    assert body(compiled(src % "4", "PS", "ps_2_0")) == [
        "mul r0, v0, v0", "mul r0, r0, r0", "mov oC0, r0"]
    assert body(compiled(src % "3", "PS", "ps_2_0")) == [
        "mul r0, v0, v0", "mul r0, v0, r0", "mov oC0, r0"]


def test_vector_pow_is_log_per_lane_one_mul_exp_per_lane():
    shader = compiled("float E; float4 PS(float4 a : COLOR0) : COLOR "
                      "{ return float4(pow(a.xyz, E), 1); }", "PS", "ps_2_0")
    ops = [line.split()[0] for line in body(shader)]
    assert ops == ["log"] * 3 + ["mul"] + ["exp"] * 3 + ["mov", "mov"]
    assert shader.program.stats.arithmetic_slots == 9      # three pow macros: 9 + 2


def test_scalar_pow_stays_the_macro():
    shader = compiled("float E; float4 PS(float4 a : COLOR0) : COLOR { return pow(a.x, E); }",
                      "PS", "ps_2_0")
    assert body(shader)[0] == "pow r0.x, v0.x, c0.x"


def test_a_temporary_whose_last_read_is_an_instruction_is_its_destination():
    shader = compiled("float4 C; float4 PS(float4 a : COLOR0) : COLOR "
                      "{ float4 x = a * C; x = x * x + C; x = x * a; return x; }", "PS", "ps_2_0")
    assert body(shader) == ["mul r0, v0, c0", "mad r0, r0, r0, c0", "mul r0, r0, v0",
                            "mov oC0, r0"]
    assert shader.program.stats.temps_used == 1


def test_one_lane_results_read_twice_are_packed_into_one_register():
    # w's three dp4 land in r0.xyz, which both the position and Eye - w read (sdk9_style's
    # MarbleVS: 35 slots before, 29 now); before, each was a register of its own, copied
    # lane by lane into float4(w, 1) and into -w. VP is c0-c3, W (three columns read) c4-c6
    assert body(compiled(PACKED, "VS", "vs_1_1")) == [
        "dp4 r0.x, v0, c4", "dp4 r0.y, v0, c5", "dp4 r0.z, v0, c6", "mov r0.w, c8.x",
        "dp4 oPos.x, r0, c0", "dp4 oPos.y, r0, c1", "dp4 oPos.z, r0, c2", "dp4 oPos.w, r0, c3",
        "add oT0.xyz, c7, -r0"]


@pytest.fixture(scope="module", params=("numpy", "gl"))
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


def test_the_rewritten_code_computes_what_the_hlsl_says(backend):
    # u = x / 8 and v = y / 8 at pixel (x, y) (test_hlsl_render's pixel_uv)
    fx = effects.load_effect("""
float4 K = {0.25, 0.5, 2.0, 0.0};
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float3 a = float3(uv, 1);
    float3 b = float3(1 - uv.x, 0.5, 0.25);
    float3 l = a * (1 - K.x) + b * K.x;             // lrp
    float3 p = pow(a, K.z);                           // log, mul, exp
    float  q = pow(uv.y, 3);                          // two muls
    return float4(clamp(l * K.z - 0.5, 0, 1).xy, p.x * 2, q + K.w);   // _sat
}
technique T { pass P { PixelShader = compile ps_2_0 PS(); } }
""")
    img = effects.render(fx, "radeon9700", technique="T", backend=backend,
                         scene={"mesh": "quad", "size": [8, 8]}).astype(np.float64) / 255.0
    for x, y in ((1, 2), (6, 5)):
        u, v = x / 8, y / 8
        lx = u * 0.75 + (1 - u) * 0.25
        ly = v * 0.75 + 0.5 * 0.25
        want = (min(max(lx * 2 - 0.5, 0), 1), min(max(ly * 2 - 0.5, 0), 1),
                min(u * u * 2, 1), v ** 3)
        assert np.allclose(img[y, x], want, atol=1.5 / 255), (x, y, img[y, x], want)


def test_one_lane_ops_over_lanes_of_one_register_are_one_vector_op(monkeypatch):
    src = ("float K; float4 PS(float4 a : COLOR0) : COLOR\n"
           "{ float s = a.x * K; float t = a.z * K; return float4(s, t, s + t, 1); }")
    ops = [line.split()[0] for line in body(compiled(src, "PS", "ps_3_0"))]
    assert ops.count("mul") == 1                    # mul r0.xy, v0.xz, c0.x
    monkeypatch.setattr(codegen, "pack_scalars", lambda *a: 0)
    ops = [line.split()[0] for line in body(compiled(src, "PS", "ps_3_0"))]
    assert ops.count("mul") == 2


def test_packing_keeps_to_ps_2_0_swizzles():
    # .xz is no ps_2_0 swizzle: the two muls stay apart rather than need a copy
    src = ("float K; float4 PS(float4 a : COLOR0) : COLOR\n"
           "{ float s = a.x * K; float t = a.z * K; return float4(s, t, s + t, 1); }")
    ops = [line.split()[0] for line in body(compiled(src, "PS", "ps_2_0"))]
    assert ops.count("mul") == 2


@pytest.mark.parametrize("exponent", ["(0.0 / 0)", "1e39 * 1e39"])
def test_pow_by_a_constant_that_is_no_number_is_the_located_constant_error(exponent):
    # the whole-exponent test once took int() of NaN (the fuzzed state expressions found it)
    fx = effects.load_effect(f"float4 A; float4 PS() : COLOR {{ return pow(A, {exponent}); }}\n"
                             "technique T { pass P { } }\n")
    with pytest.raises(effects.EffectError) as err:
        compile_shader(fx, "PS", "ps_2_0")
    assert "which a ps_2_0 constant register cannot hold" in err.value.message


# -- fold_into_producer's lanes: a replicated result spread, a lane-wise one's lanes moved --------

def _fold(target: str, prod: Instr, mov: Instr) -> list[Instr]:
    cg = SimpleNamespace(instrs=[prod, mov], rules=VERSIONS[target], defs={})
    peephole.fold_into_producer(cg)
    return cg.instrs


def _vr(k: int) -> Reg:
    return reg("vr", k)


def _ins(opcode: str, dst: Reg | None, mask: tuple[int, ...], srcs: list[Reg],
         saturate: bool = False) -> Instr:
    """A generated instruction as codegen emits it (the ps_3_0 row: the passes read opcodes)."""
    return instruction(opcode, dst, mask, srcs, "ps_3_0", saturate=saturate)


def test_the_rule_writes_a_replicated_result_to_every_lane_the_copy_fills():
    dp3 = _ins("dp3", _vr(0), (0,), [read(reg("c", 4), {0: 0, 1: 1, 2: 2}),
                                      read(reg("v", 1), {0: 0, 1: 1, 2: 2})])
    mov = _ins("mov", reg("oD", 0), (0, 1, 2, 3), [fixed(_vr(0), (0, 0, 0, 0))])
    for target in ("vs_1_1", "vs_2_0"):
        out = _fold(target, dp3, mov)
        assert len(out) == 1 and out[0].opcode == "dp3" and same(out[0].dst, reg("oD", 0))
        assert written(out[0]) == (0, 1, 2, 3)
        dp3.dst = Reg("vr", 0, mask=(0,))
    # a result in .y read as .x is no copy of it; a macro writes a temporary only (pow's page)
    mov.srcs = [fixed(_vr(0), (1, 1, 1, 1))]
    assert len(_fold("vs_2_0", dp3, mov)) == 2
    pow_ = _ins("pow", _vr(0), (0,), [fixed(reg("c", 0), (0,) * 4)] * 2)
    mov.srcs = [fixed(_vr(0), (0, 0, 0, 0))]
    assert len(_fold("vs_2_0", pow_, mov)) == 2


def test_the_rule_moves_a_lane_wise_result_with_its_sources_lanes():
    mad = _ins("mad", _vr(0), (0,), [read(reg("t", 0), {0: 0}), read(reg("t", 0), {0: 0}),
                                      read(_vr(1), {0: 0})])
    mov = _ins("mov", _vr(2), (3,), [read(_vr(0), {3: 0})], saturate=True)
    out = _fold("ps_2_0", mad, mov)
    assert len(out) == 1 and same(out[0].dst, _vr(2)) and written(out[0]) == (3,) and out[0].saturate
    assert [s.lanes for s in out[0].srcs] == [{3: 0}, {3: 0}, {3: 0}]
    # ps_2_0 has no swizzle .xy?x (.y into lane 2 besides .x into lane 0): the mov stays
    add = _ins("add", _vr(0), (0, 1), [read(reg("t", 0), {0: 0, 1: 1}), read(reg("c", 0), {0: 0, 1: 1})])
    mov = _ins("mov", _vr(2), (0, 2), [read(_vr(0), {0: 0, 2: 1})])
    assert len(_fold("ps_2_0", add, mov)) == 2
    assert len(_fold("ps_3_0", add, mov)) == 1          # any swizzle: add r2.xz, t0.xzy?, ..
    # one lane spread over several: each computes it again from the same source lanes
    add = _ins("add", _vr(0), (0,), [read(_vr(1), {0: 0}), read(reg("v", 0), {0: 0})])
    mov = _ins("mov", reg("oC", 0), (0, 1, 2, 3), [fixed(_vr(0), (0, 0, 0, 0))])
    out = _fold("ps_3_0", add, mov)
    assert len(out) == 1 and same(out[0].dst, reg("oC", 0)) and written(out[0]) == (0, 1, 2, 3)
    assert [s.lanes for s in out[0].srcs] == [{0: 0, 1: 0, 2: 0, 3: 0}] * 2


def test_a_sum_s_last_add_writes_the_colour_in_every_lane(monkeypatch):
    src = "float4 PS(float2 uv : TEXCOORD0) : COLOR { return uv.x + uv.x + uv.x; }"
    assert body(compiled(src, "PS", "ps_3_0")) == ["add r0.x, v0, v0", "add oC0, r0.x, v0.x"]
    without(monkeypatch, "fold into producer")
    assert body(compiled(src, "PS", "ps_3_0"))[-1] == "mov oC0, r0.x"


# Wine's d3d10core test shader (tests/data/d3dbc/wine): fxc wrote `dp3 oD0, c4, v1`
DOT_TO_COLOR = ("float4 light; float4x4 mat;\n"
                "struct O { float4 position : POSITION; float4 diffuse : COLOR; };\n"
                "O VS(float4 p : POSITION, float3 n : NORMAL) { O o; o.position = mul(p, mat);\n"
                "o.diffuse = dot((float3)light, n); return o; }")


@pytest.mark.parametrize("target, out", [("vs_1_1", "oD0"), ("vs_2_0", "oD0"), ("vs_3_0", "o1")])
def test_a_dot_copied_to_an_output_is_written_there(monkeypatch, target, out):
    assert body(compiled(DOT_TO_COLOR, "VS", target))[-1] == f"dp3 {out}, c4, v1"
    without(monkeypatch, "fold into producer")
    assert body(compiled(DOT_TO_COLOR, "VS", target))[-2:] == [
        "dp3 r0.x, c4, v1", f"mov {out}, r0.x"]


FOLDED = """
float4 K = {0.25, 0.5, 0.125, 0.5};
struct O { float4 p : POSITION; float2 t : TEXCOORD0; float4 c : COLOR0; };
O VS(float4 p : POSITION, float2 uv : TEXCOORD0)
{ O o; o.p = p; o.t = uv; o.c = dot(K.xyz, float3(uv, 1)); return o; }
float4 PS(float2 uv : TEXCOORD0, float4 c : COLOR0) : COLOR
{ float s = uv.x * uv.x; return float4(c.x, uv.y, 0, saturate(s * s + uv.y * K.w)); }
technique T { pass P { VertexShader = compile vs_2_0 VS(); PixelShader = compile ps_2_0 PS(); } }
"""


def test_the_folded_code_draws_what_the_hlsl_says(backend, monkeypatch):
    def draw():
        return drawn(FOLDED, "radeon9700", backend)

    fx = effects.load_effect(FOLDED)
    assert "dp3 oD0, c0, r0" in body(compile_shader(fx, "VS", "vs_2_0"))
    assert "mad_sat r0.w, r0.x, r0.x, r1.x" in body(compile_shader(fx, "PS", "ps_2_0"))
    folded = draw()
    for x, y in ((1, 2), (6, 5)):
        u, v = x / 8, y / 8
        want = (0.25 * u + 0.5 * v + 0.125, v, 0, min(u ** 4 + v * 0.5, 1))
        assert np.allclose(folded[y, x], want, atol=1.5 / 255), (x, y, folded[y, x], want)
    without(monkeypatch, "fold into producer")
    assert np.abs(draw() - folded).max() == 0


# -- abs read as the _abs source modifier (vs_3_0, ps_3_0) ------------------------------------

def _abs_then_add() -> list[Instr]:
    # abs vr0.w, -v0.w ; add vr1, -vr0.w, c0.x
    return [_ins("abs", _vr(0), (3,), [read(reg("v", 0), {3: 3}, True)]),
            _ins("add", _vr(1), (0, 1, 2, 3), [fixed(_vr(0), (3, 3, 3, 3), True),
                                               fixed(reg("c", 0), (0, 0, 0, 0))])]


@pytest.mark.parametrize("target, kept", [("ps_3_0", 1), ("vs_3_0", 1), ("ps_2_0", 2),
                                          ("vs_2_0", 2), ("vs_1_1", 2)])
def test_the_rule_reads_an_abs_as_its_source_modifier(target, kept):
    cg = SimpleNamespace(instrs=_abs_then_add(), rules=VERSIONS[target], defs={})
    assert peephole.abs_into_sources(cg) == 2 - kept
    if kept == 1:          # -|(-v0.w)| = -v0_abs.w: the abs's own sign goes, the reader's stays
        (add,) = cg.instrs
        s = add.srcs[0]
        assert (s.kind, s.index, s.modifier, s.negate, s.swizzle) == ("v", 0, "abs", True,
                                                                       (3, 3, 3, 3))
    else:                  # no _abs before shader model 3: the instruction stays
        assert [i.opcode for i in cg.instrs] == ["abs", "add"]


def test_an_abs_read_by_an_instruction_without_modifiers_stays():
    code = _abs_then_add()
    code[1] = instruction("texld", _vr(1), (0, 1, 2, 3), [read(_vr(0), {0: 3, 1: 3})],
                          "ps_3_0", sampler="S")
    cg = SimpleNamespace(instrs=code, rules=VERSIONS["ps_3_0"], defs={})
    assert peephole.abs_into_sources(cg) == 0 and len(cg.instrs) == 2


ABS = """
struct V { float4 p : POSITION; float2 t : TEXCOORD0; };
V VS(float4 p : POSITION, float2 uv : TEXCOORD0) { V o; o.p = p; o.t = uv * 2 - 1; return o; }
float4 PS(float2 t : TEXCOORD0) : COLOR
{ return float4(abs(t.x) * 0.5 + abs(t.y) * 0.25, abs(t.y) > 0.5 ? 1 : 0, pow(abs(t.x), 2), 1); }
technique T { pass P { VertexShader = compile vs_3_0 VS(); PixelShader = compile ps_3_0 PS(); } }
"""


def test_abs_as_a_modifier_draws_what_the_hlsl_says(backend, monkeypatch):
    # fxc's listing of Effekseer's sprite_unlit_ps: `cmp r1, -r0_abs.w, c0.x, c0.y`
    def draw():
        return drawn(ABS, "geforce6800", backend)

    fx = effects.load_effect(ABS)
    code = body(compile_shader(fx, "PS", "ps_3_0"))
    assert not any(line.startswith("abs") for line in code) and "v0_abs" in " ".join(code)
    modified = draw()
    for x, y in ((1, 2), (6, 5), (3, 7)):
        tx, ty = 2 * x / 8 - 1, 2 * y / 8 - 1
        want = (abs(tx) * 0.5 + abs(ty) * 0.25, 1.0 if abs(ty) > 0.5 else 0.0, tx * tx, 1)
        assert np.allclose(modified[y, x], want, atol=1.5 / 255), (x, y, modified[y, x], want)
    without(monkeypatch, "abs into sources")
    effects.clear_caches()
    code = body(compile_shader(effects.load_effect(ABS), "PS", "ps_3_0"))
    assert any(line.startswith("abs") for line in code)
    assert np.abs(draw() - modified).max() == 0


# -- a swizzle ps_2_0 lacks, built with the fewest movs ---------------------------------------

@pytest.mark.parametrize("lanes, movs", [
    # .xyzy: the lanes that keep their component in one mov, .y into w (fxc's two movs)
    ({0: 0, 1: 1, 2: 2, 3: 1}, [((0, 1, 2), {0: 0, 1: 1, 2: 2}), ((3,), (1, 1, 1, 1))]),
    # .yxzw: z and w in one, then x and y each replicated
    ({0: 1, 1: 0, 2: 2, 3: 3}, [((2, 3), {2: 2, 3: 3}), ((0,), (1, 1, 1, 1)),
                                ((1,), (0, 0, 0, 0))]),
    # .xxyy: a mov per component is two, as few as the plain one and another would be
    ({0: 0, 1: 0, 2: 1, 3: 1}, [((0, 1), (0, 0, 0, 0)), ((2, 3), (1, 1, 1, 1))]),
])
def test_the_rule_builds_a_swizzle_with_the_fewest_movs(lanes, movs):
    from effects.base.errors import UNKNOWN_LOCATION
    from effects.base.errors import UNKNOWN_LOCATION
    from effects.shaders.hlsl.legalize import _copy
    cg = SimpleNamespace(rules=VERSIONS["ps_2_0"])
    out: list[Instr] = []
    _copy(cg, out, _vr(9), read(reg("t", 0), lanes), UNKNOWN_LOCATION, "ps20")
    got = [(written(i), i.srcs[0].lanes if i.srcs[0].lanes is not None else i.srcs[0].swizzle)
           for i in out]
    assert got == movs and all(i.opcode == "mov" and same(i.dst, _vr(9)) for i in out)


SWIZZLED = """
float4 K = {0.5, 0.25, 0, 1};
float4 PS(float2 uv : TEXCOORD0) : COLOR
{ float4 c = float4(uv, uv.x * uv.y, 1) + K; return c.xyzy * K.x; }
technique T { pass P { PixelShader = compile ps_2_0 PS(); } }
"""


def test_a_swizzle_built_in_two_movs_draws_what_the_hlsl_says(backend):
    # Pale Moon's LayerManagerD3D9 shader as fxc wrote it: mov r1.xyz, r0 / mov r1.w, r0.y
    fx = effects.load_effect(SWIZZLED)
    code = body(compile_shader(fx, "PS", "ps_2_0"))
    assert code[-4:] == ["mov r1.xyz, r0", "mov r1.w, r0.y", "mul r0, r1, c0.x", "mov oC0, r0"]
    img = effects.render(fx, "radeon9700", technique="T", backend=backend,
                         scene={"mesh": "quad", "size": [8, 8]}).astype(np.float64) / 255.0
    for x, y in ((1, 2), (6, 5)):
        u, v = x / 8, y / 8
        want = ((u + 0.5) / 2, (v + 0.25) / 2, u * v / 2, (v + 0.25) / 2)
        assert np.allclose(img[y, x], want, atol=1.5 / 255), (x, y, img[y, x], want)


# -- one copy for every read past the read ports --------------------------------------------

def _legalized(target: str, code: list[Instr]) -> list[str]:
    from effects.shaders.hlsl.legalize import legalize, source_swizzle
    from effects.shaders.asm.text import instruction_text
    count = iter(range(100, 200))
    cg = SimpleNamespace(instrs=code, rules=VERSIONS[target], temp=lambda: _vr(next(count)))
    legalize(cg)
    source_swizzle(cg.instrs, "any")          # as code_of hands them on
    return [instruction_text(ins) for ins in cg.instrs]


def _dp3(dst: int, a: int, b: int) -> Instr:
    # dp3 vr<dst>.<dst lane>, c<a>, c<b>
    xyz = {0: 0, 1: 1, 2: 2}
    return _ins("dp3", _vr(9), (dst,), [read(reg("c", a), xyz), read(reg("c", b), xyz)])


def test_the_rule_copies_the_register_three_instructions_read_once():
    # c7 read by three dp3 past vs_1_1's one constant port: copied once, as fxc did
    code = [_dp3(0, 7, 4), _dp3(1, 7, 5), _dp3(2, 7, 6)]
    assert _legalized("vs_1_1", code) == [
        "mov vr100.xyz, c7", "dp3 vr9.x, vr100, c4", "dp3 vr9.y, vr100, c5",
        "dp3 vr9.z, vr100, c6"]
    # vs_2_0 reads two constants at once: nothing to copy
    code = [_dp3(0, 7, 4), _dp3(1, 7, 5), _dp3(2, 7, 6)]
    assert len(_legalized("vs_2_0", code)) == 3
    # a flow instruction between: the code after it makes its own copy
    code = [_dp3(0, 7, 4), _ins("rep", None, (), [fixed(reg("i", 0), (0, 1, 2, 3))]),
            _dp3(1, 7, 5), _ins("endrep", None, (), [])]
    assert [t.split()[0] for t in _legalized("vs_1_1", code)] == [
        "mov", "dp3", "rep", "mov", "dp3", "endrep"]


def test_one_copy_serves_every_read_of_the_register_in_an_instruction():
    # mad d, c0, c1.x, c1.y: c1 copied once (.xy), both sources read the copy
    code = [_ins("mad", _vr(9), (0, 1, 2, 3), [read(reg("c", 0), {i: i for i in range(4)}),
                                               fixed(reg("c", 1), (0, 0, 0, 0)),
                                               fixed(reg("c", 1), (1, 1, 1, 1))])]
    assert _legalized("vs_1_1", code) == ["mov vr100.xy, c1",
                                          "mad vr9.xyzw, c0, vr100.x, vr100.y"]


PORTS = """
float3 Light; float3x3 Basis;
struct O { float4 p : POSITION; float4 c : COLOR0; };
O VS(float4 p : POSITION) { O o; o.p = p; o.c = float4(mul(Basis, Light) * 0.5 + 0.5, 1); return o; }
float4 PS(float4 c : COLOR0) : COLOR { return c; }
technique T { pass P { VertexShader = compile vs_1_1 VS(); PixelShader = compile ps_2_0 PS(); } }
"""


def test_a_constant_copied_once_draws_what_the_hlsl_says(backend):
    fx = effects.load_effect(PORTS)
    code = body(compile_shader(fx, "VS", "vs_1_1"))
    assert code[:4] == ["mov r0.xyz, c3", "mul r1.xyz, c0, r0.x", "mad r1.xyz, c1, r0.y, r1",
                        "mad r0.xyz, c2, r0.z, r1"]
    light = [0.5, -0.25, 0.75]
    basis = [[0.2, 0.4, 0.0], [-0.6, 0.2, 0.4], [0.0, 0.8, -0.2]]
    img = effects.render(fx, "radeon9700", technique="T", backend=backend,
                         scene={"mesh": "quad", "size": [8, 8]},
                         params={"Light": light, "Basis": basis}).astype(np.float64) / 255.0
    d = [sum(basis[r][k] * light[k] for k in range(3)) for r in range(3)]
    want = (d[0] * 0.5 + 0.5, d[1] * 0.5 + 0.5, d[2] * 0.5 + 0.5, 1)
    for x, y in ((1, 2), (6, 5)):
        assert np.allclose(img[y, x], want, atol=1.5 / 255), (x, y, img[y, x], want)


# -- loops: a dead counter, a carried vector updated in place ------------------------------------

def _run(target: str, name: str, instrs: list[Instr]) -> list[Instr]:
    cg = SimpleNamespace(instrs=instrs, rules=VERSIONS[target], defs={})
    dict(peephole.PASSES)[name](cg)
    return cg.instrs


def test_the_rule_drops_what_only_feeds_itself():
    count = fixed(reg("i", 0), (0, 1, 2, 3))
    kept = _ins("mov", _vr(1), (0, 1, 2, 3), [read(reg("c", 2), {0: 0, 1: 1, 2: 2, 3: 3})])
    code = [_ins("mov", _vr(0), (0,), [fixed(reg("c", 0), (0,) * 4)]),
            kept,
            _ins("rep", None, (), [count]),
            _ins("add", _vr(0), (0,), [read(_vr(0), {0: 0}), read(reg("c", 1), {0: 0})]),
            _ins("endrep", None, (), []),
            _ins("mov", _vr(2), (0,), [read(_vr(0), {0: 0})]),       # read by nothing
            _ins("mov", reg("oC", 0), (0, 1, 2, 3), [read(_vr(1), {0: 0, 1: 1, 2: 2, 3: 3})])]
    assert [i.opcode for i in _run("ps_3_0", "drop dead writes", code)] == [
        "mov", "rep", "endrep", "mov"]
    # read where an output is written: kept, round the loop too
    code[-1].srcs.append(read(_vr(2), {0: 0}))
    code[-1].opcode = "add"
    assert len(_run("ps_3_0", "drop dead writes", code)) == len(code)


def _updated(between: list[Instr]) -> list[Instr]:
    c, x = _vr(0), _vr(1)
    return [_ins("mad", x, (0,), [read(reg("v", 0), {0: 0}), read(reg("c", 0), {0: 0}),
                                   read(c, {0: 0})]),
            *between,
            _ins("mov", x, (1, 2, 3), [read(c, {1: 1, 2: 2, 3: 3})]),
            _ins("mov", c, (0, 1, 2, 3), [read(x, {0: 0, 1: 1, 2: 2, 3: 3})])]


def test_the_rule_updates_a_register_built_from_its_own_lanes_in_place():
    out = _run("vs_3_0", "build in place", _updated([]))
    assert len(out) == 1 and out[0].opcode == "mad" and same(out[0].dst, _vr(0))
    # something reads the old x between: the copy stays
    reader = _ins("add", _vr(5), (0,), [read(_vr(0), {0: 0}), read(reg("c", 1), {0: 0})])
    assert len(_run("vs_3_0", "build in place", _updated([reader]))) == 4
    # something writes the register between: the order would matter, the copy stays
    writer = _ins("mov", _vr(0), (2,), [read(reg("c", 1), {2: 2})])
    assert len(_run("vs_3_0", "build in place", _updated([writer]))) == 4


def test_wine_s_loop_shader_is_as_tight_as_fxc_s(monkeypatch):
    from tests.shaders.d3dbc.test_wine_d3dx9_shaders import _pairs
    from effects.shaders.asm.stats import compute_stats
    from effects.shaders.d3dbc import read_shader
    name, target, hlsl, data = next(p for p in _pairs() if p[0] == "registerset_blob_scalar")
    assert compute_stats(read_shader(data, name).program).total_slots == 25     # fxc's

    def slots() -> int:
        effects.clear_caches()
        return compiled(hlsl, "main", target).program.stats.total_slots

    assert slots() == 24
    without(monkeypatch, "build in place")
    assert slots() == 28
    without(monkeypatch, "drop dead writes")
    assert slots() == 34
    effects.clear_caches()


LOOPS = """
int n = 3; float f = 0.125; bool b = true;
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 tmp = float4(0, 0, 0, 1);
    int i;
    if (b) for (i = 0; i < n; i++) tmp.x += uv.x * f;
    else for (i = 0; i < n; i++) tmp.y += uv.y * f;
    return tmp;
}
technique T { pass P { PixelShader = compile ps_3_0 PS(); } }
"""


@pytest.mark.parametrize("b", [True, False])
def test_the_loops_updated_in_place_draw_what_the_hlsl_says(backend, monkeypatch, b):
    def draw():
        effects.clear_caches()
        img = effects.render(effects.load_effect(LOOPS), "geforce6800", technique="T",
                             backend=backend, scene={"mesh": "quad", "size": [8, 8]},
                             params={"b": b})
        effects.clear_caches()
        return img.astype(np.float64) / 255.0

    text = body(compiled(LOOPS.split("technique")[0], "PS", "ps_3_0"))
    assert text == ["if b0", "mov r0, c1", "rep i0", "mad r0.x, v0, c0, r0", "endrep", "else",
                    "mov r1, c1", "rep i0", "mad r1.y, v0, c0.x, r1", "endrep", "mov r0, r1",
                    "endif", "mov oC0, r0"]
    tight = draw()
    for x, y in ((1, 2), (6, 5)):
        u, v = x / 8, y / 8
        want = (3 * u * 0.125, 0, 0, 1) if b else (0, 3 * v * 0.125, 0, 1)
        assert np.allclose(tight[y, x], want, atol=1.5 / 255), (x, y, tight[y, x], want)
    without(monkeypatch, "build in place")
    without(monkeypatch, "drop dead writes")
    assert np.abs(draw() - tight).max() == 0
