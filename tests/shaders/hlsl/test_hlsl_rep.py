"""A `for` loop counted by an int uniform (`for (int i = 0; i < NumLights; i++)`) compiles to
`rep i#` where the target has static flow control (vs_2_0 and up, ps_3_0): the int parameter
gets an i# in the register table, the pass sets it from the parameter (as D3DX does), and the
body is compiled once. Rendered on both back ends for several counts, values worked out by
hand; targets without loops (vs_1_1, ps_2_0) keep X3511 with the reason, located at the loop."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.shaders.listing import listing
from effects.base.errors import EffectError
from effects.shaders.hlsl import compile_shader
from tests.shaders.hlsl.test_hlsl_render import QUAD, backend, effect_for, fx_asm, render  # noqa: F401

TOL = 1.5 / 255
PS = "float4 PS(float4 c : COLOR0) : COLOR { return c; }"
ACCUMULATE = """
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    float4 acc = float4(0.0, 0.0, 0.0, 1.0);
    float k = 0.5;
    for (int i = 0; i < NumLights; i++) {
        acc.x += 0.125;
        acc.y += Step.y * i;
        k = k * 0.5;
    }
    acc.z = k;
    c = acc;
    return p;
}
""" + PS
PARAMS = "int NumLights = 3;\nfloat4 Step = {0, 0.0625, 0, 0};"


def accumulate_by_hand(n: int) -> tuple[float, float, float, float]:
    """n iterations: red n/8, green 1/16 * (0 + 1 + ... + n-1), blue 0.5 halved n times."""
    return (0.125 * n, 0.0625 * n * (n - 1) / 2, 0.5 * 0.5 ** n, 1.0)


def test_the_hand_values():
    assert accumulate_by_hand(3) == (0.375, 0.1875, 0.0625, 1.0)
    assert accumulate_by_hand(0) == (0.0, 0.0, 0.5, 1.0)


@pytest.mark.parametrize("target", ["vs_2_0", "vs_3_0"])
def test_the_loop_is_a_rep_on_an_int_register(target):
    fx = effect_for(ACCUMULATE, vs=f"compile {target} VS()", params=PARAMS)
    shader = compile_shader(fx, "VS", target)
    text = shader.text
    assert text.count("rep i0") == 1 and text.count("endrep") == 1, text
    assert "defi" not in text, text                 # the effect sets i0, not the shader
    assert shader.int_registers == {"NumLights": 0}
    assert "NumLights" not in shader.constants      # read only as the count
    body = text[text.index("rep i0"):text.index("endrep")]
    assert body.count("add") + body.count("mad") + body.count("mul") <= 6, text
    assert any("NumLights" in line and "i0" in line for line in listing(fx, shader))


@pytest.mark.parametrize("count", [0, 1, 3, 5])
def test_accumulators_and_the_counter_carried_across_iterations(backend, count):
    fx = effect_for(ACCUMULATE, vs="compile vs_2_0 VS()", params=PARAMS)
    img = render(fx, backend, params={"NumLights": count})
    want = accumulate_by_hand(count)
    assert np.allclose(img[4, 4], want, atol=TOL), (img[4, 4], want)


def test_the_parameters_default_is_the_count(backend):
    fx = effect_for(ACCUMULATE, vs="compile vs_2_0 VS()", params=PARAMS)
    assert np.allclose(render(fx, backend)[4, 4], accumulate_by_hand(3), atol=TOL)


PALETTE = ("int NumLights = 2;\nfloat4 Palette[4] = {0.125,0,0,0, 0,0.25,0,0, 0,0,0.5,0, "
           "0.25,0.25,0.25,0};")


@pytest.mark.parametrize("count, want", [(0, (0, 0, 0, 0)), (2, (0.125, 0.25, 0, 0)),
                                         (4, (0.375, 0.5, 0.75, 0))])
def test_a_uniform_array_indexed_by_the_counter(backend, count, want):
    # element i as c0[aL] inside `loop aL, i0` (as fxc compiles it: the effect sets i0 to
    # (N, 0, 1, 0), so aL runs 0 .. N - 1): the sum of the first `count` elements
    fx = effect_for("""
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    float4 acc = 0;
    for (int i = 0; i < NumLights; i++)
        acc += Palette[i];
    c = acc;
    return p;
}
""" + PS, vs="compile vs_2_0 VS()", params=PALETTE)
    text = fx_asm(fx, "VS", "vs_2_0")
    assert text.index("loop aL, i0") < text.index("c0[aL]") < text.index("endloop"), text
    assert "mova" not in text and "rep" not in text, text
    img = render(fx, backend, params={"NumLights": count})
    assert np.allclose(img[4, 4], want, atol=TOL), (img[4, 4], want)


PAIRS = ("int NumLights = 2;\nstruct Pair { float4 a; float4 b; };\n"
         "Pair Pairs[3] = {0.125,0,0,0, 0,0,0.0625,0, 0,0.25,0,0, 0,0,0.125,0, "
         "0.25,0.25,0,0, 0,0,0.25,0};")


@pytest.mark.parametrize("count, want", [(0, (0, 0, 0, 0)), (1, (0.125, 0, 0.0625, 0)),
                                         (3, (0.375, 0.5, 0.4375, 0))])
def test_an_element_of_two_registers_goes_through_a0_in_a_rep(backend, count, want):
    # aL steps by the i#'s z, which D3DX sets to 1 for an int parameter: an element of two
    # registers (a struct of two float4) is read through a0 = 2i instead (mova in the rep);
    # want: the sum of a + b over the first `count` pairs
    fx = effect_for("""
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    float4 acc = 0;
    for (int i = 0; i < NumLights; i++)
        acc += Pairs[i].a + Pairs[i].b;
    c = acc;
    return p;
}
""" + PS, vs="compile vs_2_0 VS()", params=PAIRS)
    text = fx_asm(fx, "VS", "vs_2_0")
    assert text.index("rep i0") < text.index("mova a0.x") < text.index("endrep"), text
    img = render(fx, backend, params={"NumLights": count})
    assert np.allclose(img[4, 4], want, atol=TOL), (img[4, 4], want)


SWAP = """
float4 VS(float4 p : POSITION, float2 uv : TEXCOORD0, out float2 t : TEXCOORD0) : POSITION
{ t = uv; return p; }
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float a = 1;
    float b = 0;
    float s = 0;
    for (int i = 0; i < Count; i++) { float t = a; a = b; b = t; s += uv.x * 0.25; }
    return float4(a, b, s, 1);
}
"""


@pytest.mark.parametrize("count", [0, 1, 2, 3])
def test_a_pixel_shader_rep_swapping_two_values(backend, count):
    # ps_3_0 on the GeForce 6800: a swap each iteration (a = 1, b = 0 after an even count,
    # swapped after an odd one), and s = count * uv.x / 4 from the interpolated coordinate
    fx = effects.load_effect("int Count = 1;\n" + SWAP + "technique T { pass P { "
                             "VertexShader = compile vs_3_0 VS(); "
                             "PixelShader = compile ps_3_0 PS(); } }\n")
    assert "rep i0" in fx_asm(fx, "PS", "ps_3_0")
    img = effects.render(fx, "geforce6800", technique="T", backend=backend, scene=QUAD,
                         params={"Count": count}).astype(np.float64) / 255.0
    odd = count % 2
    for x, y in ((1, 1), (6, 3)):
        u = x / 8
        want = (float(not odd), float(odd), count * u * 0.25, 1.0)
        assert np.allclose(img[y, x], want, atol=TOL), (x, y, img[y, x], want)


@pytest.mark.parametrize("target, reason", [
    ("vs_1_1", "vs_1_1 has no loops (rep needs vs_2_0, ps_2_x or ps_3_0)"),
])
def test_a_target_without_loops_says_why_at_the_loop(target, reason):
    fx = effect_for(ACCUMULATE, vs=f"compile {target} VS()", params=PARAMS)
    with pytest.raises(EffectError) as err:
        compile_shader(fx, "VS", target)
    assert err.value.message == ("X3511: unable to unroll loop: its count is the uniform "
                                 f"'NumLights', known only when the shader runs, and {reason}")
    text = PARAMS + "\n" + ACCUMULATE
    line = next(k for k, t in enumerate(text.split("\n")) if "for (" in t) + 1
    assert (err.value.location.line, err.value.location.column) == (line, 5)


def test_ps_2_0_has_no_loops_either():
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float s = 0;
    for (int i = 0; i < Count; i++) s += 0.25;
    return s;
}""", params="int Count = 2;")
    with pytest.raises(EffectError, match="ps_2_0 has no loops"):
        compile_shader(fx, "PS", "ps_2_0")


def test_unroll_asks_for_unrolling():
    fx = effect_for(ACCUMULATE.replace("for (", "[unroll] for ("), vs="compile vs_2_0 VS()",
                    params=PARAMS)
    with pytest.raises(EffectError, match="X3511: unable to unroll loop, loop does not appear"):
        compile_shader(fx, "VS", "vs_2_0")


def test_a_break_in_the_body_needs_break_comp_and_vs_2_0_says_so():
    # vs_2_0 has static flow control only (no break_comp): the break is refused at the loop;
    # tests/shaders/hlsl/test_hlsl_flow.py renders the same loop as a rep with break_ne on vs_2_a
    fx = effect_for("""
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    float4 acc = 0;
    for (int i = 0; i < NumLights; i++) {
        if (acc.x > 1) break;
        acc.x += 0.25;
    }
    c = acc;
    return p;
}
""" + PS, vs="compile vs_2_0 VS()", params="int NumLights = 1;")
    with pytest.raises(EffectError, match="cannot be a rep: break in the body needs break_comp, "
                                          "which vs_2_0 does not have"):
        compile_shader(fx, "VS", "vs_2_0")
