"""Valid HLSL that fxc compiled (issue 30, the constructs valid programs failed on): run-time
indices into arrays in pixel shaders (select chains), casts on the left of an assignment,
`return` inside loops, the intrinsics rcp/mad/dst/isnan/isinf/isfinite, 1xN matrices as
vectors, names that differ from a keyword only in case, tex2D with a wider coordinate.
Rendered on both back ends, values worked out by hand.

The quad's texture coordinate is u = x / 8, v = y / 8 at pixel (x, y) (pixel_uv), so
`(int)(uv.x * 4 + 0.25)` is x // 2, a quarter away from the next integer (a back end's u may
be a rounding below x / 8).
"""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.assets.textures import make_texture
from effects.shaders.hlsl import compile_shader
from tests.shaders.hlsl.test_hlsl_render import backend, effect_for, fx_asm, pixel_uv, render  # noqa: F401

TOL = 1.5 / 255
C4 = np.array([(0.1, 0.2, 0.3, 1), (0.4, 0.5, 0.6, 1), (0.7, 0.8, 0.9, 1), (1.0, 0.5, 0.0, 1)])
C4_TEXT = "float4 C[4] = { " + ", ".join(f"{x:g}" for x in C4.reshape(-1)) + " };"


def k_of(x: int) -> int:
    """(int)(u * 4 + 0.25) at pixel column x."""
    return x // 2


# -- run-time indices: select chains -------------------------------------------------------------

@pytest.mark.parametrize("target, card", [("ps_2_0", "radeon9700"), ("ps_3_0", "geforce6800")])
def test_a_uniform_array_read_by_a_run_time_index_in_a_pixel_shader(backend, target, card):
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    int k = (int)(uv.x * 4 + 0.25);
    return float4(C[k].xy, C[3 - k].z, 1);
}""", ps=f"compile {target} PS()", params=C4_TEXT)
    text = fx_asm(fx, "PS", target)
    assert "cmp" in text and "a0" not in text and "aL" not in text, text
    img = effects.render(fx, card, technique="T", backend=backend,
                         scene={"mesh": "quad", "size": [8, 8]}).astype(np.float64) / 255
    for x in range(8):
        k = k_of(x)
        want = (C4[k][0], C4[k][1], C4[3 - k][2], 1)
        assert np.allclose(img[3, x], want, atol=TOL), (x, img[3, x], want)


def test_a_float_index_is_truncated_and_the_chain_clamps_at_the_ends(backend):
    fx = effect_for("""
float W[3] = { 0.25, 0.5, 0.75 };
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    return float4(W[uv.x * 4 + 0.25], W[uv.x * 4 - 1.75], 0, 1);
}""")
    img = render(fx, backend)
    w = (0.25, 0.5, 0.75)
    for x in range(8):
        # x // 2 is 3 at x = 6, 7: past the end, the last element; x // 2 - 2 below 0: the first
        first = w[min(k_of(x), 2)]
        second = w[max(min(int(x / 8 * 4 - 1.75), 2), 0)]   # truncated toward zero
        assert np.allclose(img[5, x, :2], (first, second), atol=TOL), (x, img[5, x])


def test_local_arrays_read_and_written_by_a_run_time_index(backend):
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float a[4] = { 0.1, 0.3, 0.6, 0.9 };
    float4 b[4] = { (float4)0, (float4)0, (float4)0, (float4)0 };
    int k = (int)(uv.x * 4 + 0.25);
    b[k] = float4(a[k], uv.y, 0.5, 1);     // one element written, per pixel
    b[k].z += 0.25;                        // a read-modify-write through the index
    return b[2] * 0.5 + b[k] * 0.5;        // b[2] is zero unless k is 2
}""")
    img = render(fx, backend)
    a = (0.1, 0.3, 0.6, 0.9)
    for x, y in ((0, 1), (3, 6), (4, 2), (7, 7)):
        k, (_, v) = k_of(x), pixel_uv(x, y)
        want = np.array((a[k], v, 0.75, 1)) * (1.0 if k == 2 else 0.5)
        assert np.allclose(img[y, x], want, atol=TOL), (x, y, img[y, x], want)


def test_a_matrix_row_and_a_vector_lane_by_a_run_time_index(backend):
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    int k = (int)(uv.x * 4 + 0.25);
    float4 lanes = float4(0.2, 0.4, 0.6, 0.8);
    return float4(M[k].x, M[k].w * 0.5, lanes[k], 1);
}""", params="float4x4 M = " + C4_TEXT[C4_TEXT.index("{"):])
    img = render(fx, backend)
    for x in range(8):
        k = k_of(x)
        assert np.allclose(img[2, x], (C4[k][0], C4[k][3] * 0.5, 0.2 * (k + 1), 1), atol=TOL), x


def test_a_chain_too_long_for_ps_2_0_is_a_card_reason_not_an_error():
    # three run-time reads of 24 registers: a cmp per register each (104 slots; two reads of
    # 20 fit in 64 once the index's differences are computed four at a time, pack_scalars)
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    return Big[uv.x * 24] * Big[uv.y * 24] + Big[uv.x * uv.y * 24];
}
float4 Plain(float2 uv : TEXCOORD0) : COLOR { return uv.xyxy; }
technique Fallback { pass P { PixelShader = compile ps_2_0 Plain(); } }""", params="float4 Big[24];")
    radeon = fx.validate("T", effects.load_profile("radeon9700"))
    assert not radeon.ok
    assert any("64 arithmetic instruction slots" in r.message for r in radeon.reasons), radeon.reasons
    assert fx.find_valid_technique(effects.load_profile("radeon9700")).name == "Fallback"
    # the same function compiled for ps_3_0 (512 slots) runs
    fx3 = effect_for("float4 PS(float2 uv : TEXCOORD0) : COLOR "
                     "{ return Big[uv.x * 20] * Big[uv.y * 20]; }", ps="compile ps_3_0 PS()",
                     params="float4 Big[20];")
    assert "cmp" in fx_asm(fx3, "PS", "ps_3_0")


# -- casts on the left ---------------------------------------------------------------------------------

def test_casts_on_the_left_write_the_components_they_name(backend):
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 a = 1;
    (float3)a = float3(uv, 0.5);           // a = (u, v, 0.5, 1)
    float4 b = 0.5;
    ((float2)b).y = uv.x;                  // b = (0.5, u, 0.5, 0.5)
    ((float3)b).yz += 0.25;                // b = (0.5, u + 0.25, 0.75, 0.5)
    float4 c = 0.25;
    (float)c = uv.y;                       // c = (v, 0.25, 0.25, 0.25)
    return float4(a.y, b.y, b.z * c.y * 4, c.x * a.a);
}""")
    img = render(fx, backend)
    for x, y in ((1, 6), (6, 3)):
        u, v = pixel_uv(x, y)
        assert np.allclose(img[y, x], (v, u + 0.25, 0.75, v), atol=TOL), (x, y, img[y, x])


def test_a_cast_that_widens_is_not_an_l_value():
    from effects.base.errors import EffectError
    fx = effect_for("float4 PS(float2 uv : TEXCOORD0) : COLOR\n{\n    float2 t = 0;\n"
                    "    (float4)t = 1;\n    return t.xyxy;\n}")
    with pytest.raises(EffectError) as info:
        fx_asm(fx, "PS", "ps_2_0")
    assert info.value.message.startswith("X3025:")
    assert (info.value.line, info.value.column) == (5, 5)


# -- return inside loops ---------------------------------------------------------------------------------

def test_return_inside_while_and_do_loops_with_a_counter(backend):
    fx = effect_for("""
float Find(float x)                     // the first multiple of 1/8 past x + 1/16
{
    float t = 0;
    int i = 0;
    while (i < 8) { t += 0.125; if (t > x + 0.0625) return t; i++; }
    return 0;                           // an int returned as float
}
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    int j = 0;
    do { if (j * 0.25 >= uv.y + 0.0625) return float4(Find(uv.x), j * 0.25, 0, 1); j++; }
    while (j < 4);
    return 0.5;                         // a scalar returned as float4
}""")
    img = render(fx, backend)
    for x, y in ((0, 0), (3, 2), (6, 5), (2, 7)):
        u, v = pixel_uv(x, y)
        if v + 0.0625 > 0.75:
            want = (0.5, 0.5, 0.5, 0.5)
        else:
            found = np.floor((u + 0.0625) * 8) / 8 + 0.125
            want = (found if found <= 1 else 0, np.ceil((v + 0.0625) * 4) * 0.25, 0, 1)
        assert np.allclose(img[y, x], want, atol=TOL), (x, y, img[y, x], want)


def test_an_out_parameter_is_not_written_after_its_function_returned(backend):
    fx = effect_for("""
void Fill(float2 uv, out float4 c)
{
    c = float4(uv, 0, 1);
    int i = 0;
    while (i < 2) { if (uv.x < 0.5) return; c.b += 0.25; i++; }
}
float4 PS(float2 uv : TEXCOORD0) : COLOR { float4 c; Fill(uv, c); return c; }""")
    img = render(fx, backend)
    for x, y in ((1, 3), (6, 4)):
        u, v = pixel_uv(x, y)
        assert np.allclose(img[y, x], (u, v, 0 if u < 0.5 else 0.5, 1), atol=TOL), (x, y)


# -- intrinsics ---------------------------------------------------------------------------------------

def test_rcp_mad_and_dst(backend):
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 d = dst(float4(9, uv.x, 0.25, 9), float4(9, 0.5, 9, 0.75));   // (1, u/2, 0.25, 0.75)
    float2 m = mad(uv, 0.5, 0.25);                                         // uv/2 + 1/4
    return float4(rcp(uv.x + 2) * 2 - 0.5, m.y, d.y + d.z, d.w * d.x);
}""")
    img = render(fx, backend)
    for x, y in ((0, 5), (5, 2)):
        u, v = pixel_uv(x, y)
        assert np.allclose(img[y, x], (2 / (u + 2) - 0.5, v / 2 + 0.25, u / 2 + 0.25, 0.75),
                           atol=TOL), (x, y, img[y, x])


def test_isnan_isinf_isfinite_on_a_run_time_infinity_and_nan(backend):
    fx = effect_for("""
float Zero = 0;
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float inf = 1 / Zero;                  // rcp(0): +infinity
    float nan = inf * Zero;                // infinity times 0
    return float4(isinf(inf) + isinf(uv.x) * 2, isnan(nan) + isnan(uv.y) * 2,
                  isfinite(uv.x) * 0.5 + isfinite(inf) * 0.25, 1);
}""")
    img = render(fx, backend)
    assert np.allclose(img[4, 4], (1, 1, 0.5, 1), atol=TOL), img[4, 4]


# -- conversions ----------------------------------------------------------------------------------------

def test_a_1xn_matrix_converts_to_a_shorter_vector(backend):
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float1x3 m = { uv, 0.5 };
    float2 a = (float2)m;                  // explicit: (u, v)
    float b = m;                           // implicit: u (X3206)
    return float4(a.y, b, m._m02, 1);
}""")
    assert any("X3206" in w.message for w in compile_shader(fx, "PS", "ps_2_0").warnings)
    img = render(fx, backend)
    u, v = pixel_uv(5, 3)
    assert np.allclose(img[3, 5], (v, u, 0.5, 1), atol=TOL)


def test_tex2d_with_a_float4_coordinate_reads_its_xy_and_warns(backend):
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR { return tex2D(S, float4(uv, 0.75, 1)); }""", params="""
texture T;
sampler2D S = sampler_state { Texture = <T>; MinFilter = Point; MagFilter = Point;
                              MipFilter = None; AddressU = Clamp; AddressV = Clamp; };""")
    warnings = compile_shader(fx, "PS", "ps_2_0").warnings
    assert [w.message for w in warnings] == ["X3206: implicit truncation of vector type"]
    texels = np.array([[[0.25 + 0.5 * c, 0.25 + 0.5 * r, 0.5, 1.0] for c in range(2)]
                       for r in range(2)])
    img = render(fx, backend, params={"T": make_texture(texels, mips=False)})
    for x, y in ((1, 2), (6, 5)):
        u, v = pixel_uv(x, y)
        assert np.allclose(img[y, x], texels[int(v * 2), int(u * 2)], atol=TOL), (x, y)


# -- names that differ from a keyword only in case -------------------------------------------------------

def test_names_that_differ_from_hlsl_keywords_only_in_case(backend):
    text = """float Shared = 0.25;
float4 Static = { 0, 0.5, 0, 0 };
struct Struct { float Uniform; };
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    Struct s = { 0.75 };
    float Sampler = uv.x;
    return float4(Shared, Static.y, s.Uniform, Sampler);
}
technique Shared { pass P { PixelShader = compile ps_2_0 PS(); } }
"""
    fx = effects.load_effect(text)
    assert [p.name for p in fx.parameters] == ["Shared", "Static"]
    assert fx.parameter("Shared").storage == ()
    img = effects.render(fx, "radeon9700", technique="Shared", backend=backend,
                         scene={"mesh": "quad", "size": [8, 8]}).astype(np.float64) / 255
    u, _ = pixel_uv(6, 1)
    assert np.allclose(img[1, 6], (0.25, 0.5, 0.75, u), atol=TOL)


def test_lowercase_storage_classes_are_still_keywords():
    fx = effects.load_effect("shared float4 A;\nstatic const float B = 2;\n"
                             "float4 PS() : COLOR { return A * B; }\n"
                             "technique T { pass P { PixelShader = compile ps_2_0 PS(); } }\n")
    assert fx.parameter("A").storage == ("shared",)
    assert "static" in fx.parameter("B").storage


# -- typedefs naming several types ---------------------------------------------------------------

def test_a_typedef_names_several_types_globally_and_locally(backend):
    fx = effect_for("""
typedef float4 C4, Colour;
typedef float F2[2], One;
C4 PS(float2 uv : TEXCOORD0) : COLOR
{
    typedef float2 P, Q[2];
    Q q = { uv, uv.yx };                   // q[1] = (v, u)
    F2 f = { 0.25, 0.5 };
    One o = f[1];
    Colour c = float4(q[1], f[0], 1);
    return c * o * 2;                      // (v, u, 0.25, 1)
}""")
    assert [s.name for s in fx.structs] == ["C4", "Colour", "F2", "One"]
    again = effects.load_effect(fx.to_source())           # printed once, read back the same
    assert fx.to_source().count("typedef float4 C4, Colour;") == 1
    assert [s.name for s in again.structs] == ["C4", "Colour", "F2", "One"]
    img = render(fx, backend)
    u, v = pixel_uv(2, 5)
    assert np.allclose(img[5, 2], (v, u, 0.25, 1), atol=TOL)


# -- from an XNA game's effects (DungeonQuest's NormalMapping.fx, 2007) ------------------------------

def test_an_array_with_a_semantic_takes_the_next_indices_out_and_in(backend):
    # `float4 lightVecs[3] : TEXCOORD2` in a vertex-output struct: TEXCOORD2, 3, 4
    fx = effect_for("""
struct V2P { float4 pos : POSITION; float4 vecs[2] : TEXCOORD1; float2 uv : TEXCOORD0; };
V2P VS(float4 p : POSITION, float2 uv : TEXCOORD0)
{
    V2P o = (V2P)0;
    o.pos = p;
    o.uv = uv;
    o.vecs[0] = float4(0.25, 0, 0, 0);
    o.vecs[1] = float4(0, 0.5, 0, 0);
    return o;
}
float4 PS(float4 vecs[2] : TEXCOORD1, float2 uv : TEXCOORD0) : COLOR
{
    return float4(vecs[0].x, vecs[1].y, uv.x, 1);
}""", vs="compile vs_2_0 VS()")
    vs_text, ps_text = fx_asm(fx, "VS", "vs_2_0"), fx_asm(fx, "PS", "ps_2_0")
    assert "oT1" in vs_text and "oT2" in vs_text and "dcl t2" in ps_text, (vs_text, ps_text)
    img = render(fx, backend)
    u, _ = pixel_uv(5, 2)
    assert np.allclose(img[2, 5], (0.25, 0.5, u, 1), atol=TOL), img[2, 5]


def test_a_unary_plus_in_a_parameter_initializer():
    fx = effects.load_effect("float3 L[2] = { {-1.0f, +1.0f, -1.0f}, {+2, 0, +0.5} };\n"
                             "float K = +0.25;\n")
    assert np.allclose(np.asarray(fx.parameter("L").value, np.float64).reshape(-1),
                       (-1, 1, -1, 2, 0, 0.5))
    assert fx.parameter("K").value == pytest.approx(0.25)


# -- loops that count on in the lanes that did not break ------------------------------------------------

def _count_until(u: float, limit: int = 4) -> int:
    i = 0
    while i < limit:
        if u < i * 0.25 + 0.0625:
            break
        i += 1
    return i


@pytest.mark.parametrize("target", ["ps_2_0", "ps_3_0"])
def test_a_while_loop_with_a_run_time_break_unrolls_to_its_count(backend, target):
    # the counter is a select after the break (the lanes that broke keep theirs) but 0, 1, 2,
    # 3, 4 where none did: the loop ends there for every lane still in it (livefold.py)
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    int i = 0;
    while (i < 4) { if (uv.x < i * 0.25 + 0.0625) break; i++; }
    float s = 0;
    for (int j = 0; j < 8; j++) { if (j >= i + 1) break; s += 0.125; }   // counts i + 1
    return float4(i * 0.25, s, 0, 1);
}""", ps=f"compile {target} PS()")
    card = "radeon9700" if target == "ps_2_0" else "geforce6800"
    img = effects.render(fx, card, technique="T", backend=backend,
                         scene={"mesh": "quad", "size": [8, 8]}).astype(np.float64) / 255
    for x in range(8):
        i = _count_until(x / 8)
        assert np.allclose(img[1, x], (i * 0.25, (i + 1) * 0.125, 0, 1), atol=TOL), (x, img[1, x])


def test_a_loop_whose_count_depends_on_the_pixel_is_still_x3511():
    from effects.base.errors import EffectError
    fx = effect_for("float4 PS(float2 uv : TEXCOORD0) : COLOR\n{\n    float t = 0;\n"
                    "    while (t < uv.x) t += 0.125;\n    return t;\n}")
    with pytest.raises(EffectError) as info:
        fx_asm(fx, "PS", "ps_2_0")
    assert info.value.message.startswith("X3511:")


def test_frexp_splits_a_number_into_mantissa_and_exponent(backend):
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float e, z;
    float m = frexp(uv.x + 1, e);          // 1 + u = m * 2^e, m in [0.5, 1): e = 1
    float2 e2;
    float2 m2 = frexp(float2(uv.y * 4 + 4, 0), e2);   // 4 + 4v in [4, 8): e = 3; 0: 0, 0
    float n = frexp(0, z);
    return float4(m, e * 0.25, m2.x, e2.x * 0.125 + e2.y + m2.y + n + z);
}""")
    img = render(fx, backend)
    for x, y in ((3, 1), (5, 6)):
        u, v = pixel_uv(x, y)
        assert np.allclose(img[y, x], ((1 + u) / 2, 0.25, (4 + 4 * v) / 8, 0.375), atol=TOL), \
            (x, y, img[y, x])


def test_tex2d_with_gradients_is_a_texldd():
    fx = effect_for("float4 PS(float2 uv : TEXCOORD0) : COLOR { return tex2D(S, uv, ddx(uv), ddy(uv)); }",
                    ps="compile ps_3_0 PS()", params="sampler2D S;")
    assert "texldd" in fx_asm(fx, "PS", "ps_3_0")


def test_a_select_chain_over_a_huge_array_is_refused_by_the_work_budget():
    from effects.base.errors import EffectError
    fx = effect_for("float4 PS(float2 uv : TEXCOORD0) : COLOR { return Big[uv.x * 16000]; }",
                    ps="compile ps_3_0 PS()", params="float4 Big[16000];")
    with pytest.raises(EffectError) as info:
        fx_asm(fx, "PS", "ps_3_0")
    assert "limit hlsl_work" in info.value.message
    assert (info.value.line, info.value.column) == (2, 55)        # at the index
