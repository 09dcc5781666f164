"""The compiler's bounds (issue 33): deep but legal programs compile to their hand values, folding
follows IEEE and fxc's integer rules, and each bound is a located error naming its fxc code or
its limit, as the user sees it (`str(error)`).

Hand values: 1 + 2 + ... + n = n(n + 1) / 2; the integer rules are 32-bit two's complement with
a shift count's low five bits (1 << -1 = 1 << 31 = -2^31, 1 << 34 = 4); D3D's log and rsq take
|x| and its pow |a|^b, so log2(-4) = 2, sqrt(-4) = 1 / rsq(4) = 2, pow(-2, 2) = 4.
"""
from __future__ import annotations


import numpy as np
import pytest

import effects
from effects.base import limits
from effects.base.errors import EffectError
from effects.shaders.hlsl.compiler import compile_shader
from effects.shaders.hlsl.preshader import state_value


def asm(body: str, target: str = "ps_2_0", pre: str = "") -> str:
    semantic = "COLOR" if target.startswith("ps") else "POSITION"
    text = f"{pre}\nfloat4 f(float2 uv : TEXCOORD0) : {semantic}\n{{\n{body}\n}}\n"
    return compile_shader(effects.load_effect(text), "f", target).text


def error(body: str, target: str = "ps_2_0", pre: str = "") -> str:
    with pytest.raises(EffectError) as err:
        asm(body, target, pre)
    return str(err.value)


def constant(body: str, pre: str = "") -> list[float]:
    """The values of a shader that returns one folded constant: its `def c0`."""
    text = asm(body, pre=pre)
    lines = text.splitlines()
    # the constant is read in place (issue 31: no copy through a temporary)
    assert lines[1].startswith("def c0, ") and len(lines) == 3 and \
        lines[2].startswith("mov oC0, c0"), text
    return [float(x) for x in lines[1][len("def c0, "):].split(", ")]


# -- deep but legal -------------------------------------------------------------------------

def test_a_flat_sum_of_5000_terms_compiles():
    assert constant("return " + " + ".join(str(k) for k in range(1, 5001)) + ";")[0] == \
        5000 * 5001 / 2
    # a sum the code computes: 400 terms are 399 additions, each adding the input v0, the
    # last writing the colour (its x in every lane: `add oC0, r0.x, v0.x`)
    text = asm("return " + " + ".join(["uv.x"] * 400) + ";", "ps_3_0")
    adds = [line for line in text.splitlines() if line.startswith("add ")]
    assert len(adds) == 399 and all(line.endswith(", v0") for line in adds[:-1]), adds[:2]
    assert adds[-1] == "add oC0, r0.x, v0.x"


def test_a_1000_deep_nested_expression_compiles():
    text = "0"
    for k in range(1000):
        text = f"({text} + 1)" if k % 2 == 0 else f"({text} * 2)"
    # x -> (x + 1) * 2, 500 times from 0: 2^501 - 2, far past float32: refused where it is read
    with pytest.raises(EffectError, match="a constant here folds to 6.5"):
        asm(f"return {text};")
    text = "0"
    for k in range(1000):
        text = f"({text} + 1)" if k % 2 == 0 else f"({text} * 1)"
    assert constant(f"return {text};")[0] == 500
    assert asm("return " + "-(" * 1000 + "uv.x" + ")" * 1000 + ";").splitlines()[1:] == \
        ["dcl t0.xy", "mov oC0, t0.x"]
    # g(g(...g(0)...)) with g(x) = x / 2 + 1/2, 1,000 deep: 1 - 2^-1000, which is 1 in float64
    assert constant("return " + "g(" * 1000 + "0" + ")" * 1000 + ";",
                    "float g(float x) { return x * 0.5 + 0.5; }")[0] == 1.0


def test_500_chained_initializers_evaluate():
    pre = "float P0 = 0.25;\n" + "".join(f"float P{k} = P{k - 1} + 1;\n" for k in range(1, 500))
    effect = effects.load_effect(pre + "technique t { pass p { FogDensity = P499 * 0.001; } }")
    [a] = effect.techniques[0].passes[0].states
    assert state_value("FogDensity", None, a.value.text, a.value.location, effect) == \
        pytest.approx((0.25 + 499) * 0.001)
    static = pre.replace("float P", "static float P")
    assert constant("return P499;", static)[0] == 499.25


def test_an_initializer_cycle_names_its_cycle():
    effect = effects.load_effect("float A = B + 1;\nfloat B = C * 2;\nfloat C = A * 1;\n"
                                 "technique t { pass p { FogDensity = A * 1; } }")
    [a] = effect.techniques[0].passes[0].states
    with pytest.raises(EffectError) as err:
        state_value("FogDensity", None, a.value.text, a.value.location, effect)
    assert str(err.value) == ("<string>:3:11: error: X3013: the initializer of 'A' refers to "
                              "itself (A -> B -> C -> A)")


def test_a_derived_parameter_in_a_state_is_judged_at_its_value():
    # Size0 = 100, Size = 200: PointSize = 400 is above the Modern profile's MaxPointSize 256
    fx = effects.load_effect("float Size0 = 100; float Size = Size0 * 2;\n"
                             "technique T { pass P { PointSize = Size * 2; } }")
    validation = fx.validate("T", effects.load_profile("modern"))
    [warning] = validation.warnings
    assert warning.message.endswith("PointSize = Size * 2 is 400 at the parameters' current "
                                    "values (Size = 200, Size0 = 100)")


# -- loops ----------------------------------------------------------------------------------

def test_a_loop_of_exactly_1024_iterations_unrolls():
    assert constant("float s = 0; for (int i = 0; i < 1024; i++) s += 1; return s;")[0] == 1024
    assert constant("float s = 0; [unroll(1024)] for (int i = 0; i < 1024; i++) s += 2; "
                    "return s;")[0] == 2048
    assert error("float s = 0; for (int i = 0; i < 1025; i++) s += 1; return s;") == (
        "<string>:4:14: error: X3511: unable to unroll loop, loop does not appear to terminate "
        "in a timely manner (1024 iterations)")


def test_a_loop_that_never_ends_is_refused_at_once():
    limits.reset_meter()
    message = error("float4 s = uv.xyxy; for (int i = 0; i < 10; i += 0) "
                    "{ s = s * s + sin(s) * cos(s) + normalize(s); } return s;")
    # at once: a few hundred steps of the 50,000 hlsl_work allows (work, not the clock)
    assert 0 < limits.meter().largest["hlsl_work"] < 1_000
    assert message == ("<string>:4:21: error: X3511: unable to unroll loop, loop does not appear "
                       "to terminate in a timely manner (its condition and step come back to "
                       "values they had after 2 iteration(s), so it never ends)")
    # a loop the body ends (a break at k == 5) still unrolls: s^(2^5)
    text = asm("float4 s = uv.xyxy; int k = 0; while (true) { s = s * s; k++; if (k == 5) break; } "
               "return s;")
    assert sum(line.startswith("mul ") for line in text.splitlines()) == 5


def test_a_nest_of_loops_runs_out_of_work_not_of_time():
    limits.reset_meter()
    message = error("float s = 0; for (int i = 0; i < 1000; i++) for (int j = 0; j < 1000; j++) "
                    "s += 1; return s;")
    # each addition is a step and the budget is checked after each: the first one past
    assert limits.meter().largest["hlsl_work"] == limits.meter().refused["hlsl_work"] == 50_001
    assert "error: evaluating this HLSL (unrolled loop iterations x inlined calls x components) " \
        "has 50,00" in message
    assert message.endswith("steps; the limit is 50,000 (limit hlsl_work: raise it with "
                            "EFFECTS_LIMIT_HLSL_WORK=N or effects.base.limits.set_limit("
                            "'hlsl_work', N))")
    # raised, 30 x 30 = 900 additions fold to 900
    body = "float s = 0; for (int i = 0; i < 30; i++) for (int j = 0; j < 30; j++) s += 1; return s;"
    with limits.raised(hlsl_work=1000):
        assert "limit hlsl_work" in error(body)
    assert constant(body)[0] == 900


def test_an_l_value_index_is_evaluated_once():
    # a[i++] += 1 writes a[0] and steps i once; a[i++] = 2 writes a[1]: i ends at 2
    assert constant("float a[4] = {0, 0, 0, 0}; int i = 0; a[i++] += 1; a[i++] = 2; "
                    "return float4(a[0], a[1], a[2], i);") == [1, 2, 0, 2]
    # v.w++ is read (2) then stepped (3) before v.x is written
    assert constant("float4 v = 0; v.zw = float2(1, 2); v.x = v.w++; return v;") == [2, 0, 1, 3]


# -- folding --------------------------------------------------------------------------------

@pytest.mark.parametrize("expression, value", [
    ("1 << -1", -2 ** 31), ("1 << 34", 4), ("1 << 31", -2 ** 31), ("-8 >> 1", -4),
    ("(uint)8 >> 1", 4), ("5 & 3", 1), ("5 | 3", 7), ("5 ^ 3", 6), ("~5", -6), ("~(uint)5", 2 ** 32 - 6),
    ("7 / 2", 3), ("-7 / 2", -3), ("0x7fffffff + 1", 2 ** 31), ("~(int)(1e300 * 1e300)", -2 ** 31),
])
def test_integer_folding_follows_fxc(expression, value):
    # the constant goes out as a float: a value past 2^24 keeps 9 significant digits
    assert constant(f"return {expression};")[0] == pytest.approx(value, rel=1e-8)


def test_folding_follows_the_renderers_ieee_rules():
    # D3D log and rsq of |x|, pow of |a|; 2^-1; nrm of a zero vector scales by FLT_MAX: 0
    assert constant("return float4(log2(-4), sqrt(-4), pow(-2, 2), exp2(-1));") == [2, 2, 4, 0.5]
    assert constant("float3 z = 0; return float4(normalize(z), 1);") == [0, 0, 0, 1]


@pytest.mark.parametrize("body, message", [
    ("float z = 0; return frac(z / z);",
     "<string>:4:21: error: a constant here folds to nan, which a ps_2_0 constant register cannot "
     "hold (Direct3D 9 shader constants are finite float32: at most 3.4e38, no infinity or NaN)"),
    ("return uv.x * 1e39;", "<string>:4:15: error: a constant here folds to 1e+39, which a ps_2_0"),
    ("return exp(1e30);", "<string>:4:8: error: a constant here folds to inf, which a ps_2_0"),
    ("int a = 7; int b = 0; return a / b;",
     "<string>:4:32: error: integer division by zero ('/' with a constant 0 divisor)"),
    ("float z = 0; float a[2] = {1, 2}; return a[z / z];",
     "<string>:4:44: error: X3504: array index nan out of bounds (the size is 2)"),
    ("return " + "7" * 250 + ";",
     "<string>:4:8: error: an integer literal has 250 digits; the limit is 200 (limit "
     "literal_digits: raise it with EFFECTS_LIMIT_LITERAL_DIGITS=N or "
     "effects.base.limits.set_limit('literal_digits', N))"),
])
def test_values_a_shader_cannot_hold_are_located_errors(body, message):
    assert error(body).startswith(message)


# -- types and storage ----------------------------------------------------------------------

@pytest.mark.parametrize("body, message", [
    ("vector<float, 0> v; return 1;",
     "<string>:4:15: error: X3052: vector dimension must be between 1 and 4, not 0"),
    ("vector<float, 2147483647> v; return v.x;",
     "<string>:4:15: error: X3052: vector dimension must be between 1 and 4, not 2147483647"),
    ("matrix<float, 9, 9> m; return 1;",
     "<string>:4:15: error: X3053: matrix dimensions must be between 1 and 4, not 9"),
    ("return vector<float, 5>(1, 2, 3, 4, 5).x;",
     "<string>:4:22: error: X3052: vector dimension must be between 1 and 4, not 5"),
    ("float4x4 m = 0; return m._m00_m01_m02_m03_m10;",
     "<string>:4:26: error: X3018: invalid subscript '_m00_m01_m02_m03_m10'"),
    ("float a[1000000000]; return a[0];",
     "<string>:4:8: error: X3059: array dimension must be between 1 and 65536 ('a': 1e+09)"),
    ("float4 a[65536]; return a[0];",
     "<string>:4:9: error: the type of 'a' has 262,144 components; the limit is 65,536 (limit "
     "hlsl_components: raise it with EFFECTS_LIMIT_HLSL_COMPONENTS=N or "
     "effects.base.limits.set_limit('hlsl_components', N))"),
    ("float s = uv.x; " + "{" * 65 + "s += 1;" + "}" * 65 + " return s;",
     "<string>:4:81: error: the HLSL nesting here (blocks, ifs, loops and calls inside one "
     "another) has 65 levels; the limit is 64 (limit hlsl_nesting: raise it with "
     "EFFECTS_LIMIT_HLSL_NESTING=N or effects.base.limits.set_limit('hlsl_nesting', N))"),
])
def test_types_and_storage_past_their_bounds_are_located_errors(body, message):
    assert error(body).startswith(message)


def test_a_4_component_matrix_swizzle_still_reads():
    assert constant("float4x4 m = 0; m._m00_m11_m22_m33 = float4(1, 2, 3, 4); "
                    "return m._m00_m11_m22_m33;") == [1, 2, 3, 4]


def test_nesting_a_raised_limit_allows():
    body = "float s = 1; " + "{" * 80 + "s += 1;" + "}" * 80 + " return s;"
    with limits.raised(hlsl_nesting=100):
        assert constant(body)[0] == 2
    # recursion is refused whatever the limit; a chain of distinct calls is not recursion
    assert "X3500: recursive call to 'r'" in error(
        "return r(uv.x);", pre="float r(float x) { if (x > 0) return r(x - 1); return 0; }")
    chain = "float g0(float x) { return x + 1; }\n" + "".join(
        f"float g{k}(float x) {{ return g{k - 1}(x) + 1; }}\n" for k in range(1, 30))
    assert constant("return g29(0);", chain)[0] == 30


def test_a_struct_that_doubles_per_level_is_refused_before_it_is_built():
    pre = "struct S0 { float4 a; float4 b; };\n" + "".join(
        f"struct S{k} {{ S{k - 1} a; S{k - 1} b; }};\n" for k in range(1, 30))
    limits.reset_meter()
    # S13 holds 8 x 2^13 = 65,536 numbers; S14 twice that
    assert error("S29 s = (S29)0; return 1;", pre=pre).startswith(
        "<string>:15:1: error: the type of struct 'S14' has 131,072 components; the limit is "
        "65,536 (limit hlsl_components")
    # before it is built: the type's size is refused, no evaluation work spent on it
    assert limits.meter().refused == {"hlsl_components": 131_072}
    assert limits.meter().largest.get("hlsl_work", 0) < 100


# -- sampler arrays -------------------------------------------------------------------------

def test_a_sampler_array_read_by_a_constant_index():
    text = asm("return tex2D(SA[1], uv) + tex2D(SA[0], uv) * 0.5;", pre="sampler SA[2];")
    assert "texld r0, t0, s1" in text and "texld r1, t0, s0" in text
    # bound: the elements follow the array's register
    text = asm("return tex2D(SA[1], uv);", pre="sampler SA[2] : register(s4);")
    assert "dcl_2d s5" in text and "texld r0, t0, s5" in text


def test_a_sampler_array_renders_each_element_with_its_texture():
    from effects.assets.textures import make_texture
    fx = effects.load_effect("""
texture T0; texture T1;
sampler SA[2] = { sampler_state { Texture = <T0>; }, sampler_state { Texture = <T1>; } };
float4 PS(float2 uv : TEXCOORD0) : COLOR { return tex2D(SA[1], uv) * 0.5 + tex2D(SA[0], uv) * 0.25; }
technique T { pass P { PixelShader = compile ps_2_0 PS(); } }""")
    red = make_texture(np.full((4, 4, 4), (1.0, 0.0, 0.0, 1.0)), mips=False)
    green = make_texture(np.full((4, 4, 4), (0.0, 1.0, 0.0, 1.0)), mips=False)
    img = effects.render(fx, "radeon9700", technique="T", size=(4, 4),
                         scene={"mesh": "quad"}, params={"T0": red, "T1": green})
    # 0.25 of red (SA[0]) and 0.5 of green (SA[1]); alpha 0.25 + 0.5
    assert np.abs(img[2, 2].astype(int) - [64, 128, 0, 191]).max() <= 1, img[2, 2]


def test_a_compile_refused_at_a_limit_is_compiled_again_when_the_limit_is_raised():
    # the compile cache keys the limits the compiler reads: validation says why, then passes
    fx = effects.load_effect("float4 PS(float2 uv : TEXCOORD0) : COLOR { float s = uv.x; "
                             + "{" * 70 + "s += 1;" + "}" * 70 + " return s; }\n"
                             "technique T { pass P { PixelShader = compile ps_2_0 PS(); } }")
    card = effects.load_profile("radeon9700")
    [reason] = fx.validate("T", card).reasons
    assert "has 65 levels; the limit is 64 (limit hlsl_nesting" in reason.message
    with limits.raised(hlsl_nesting=80):
        assert fx.validate("T", card).ok
