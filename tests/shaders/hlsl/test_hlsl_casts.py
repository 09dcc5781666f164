"""HLSL casts and user type names: `(VS_OUTPUT)0`, `(float3x3)World`, struct <-> vector casts,
global and local typedefs; rendered on both back ends, values worked out by hand."""
from __future__ import annotations

import numpy as np
import pytest

from effects.base.errors import EffectError
from tests.shaders.hlsl.test_hlsl_render import backend, effect_for, fx_asm, pixel_uv, render  # noqa: F401

TOL = 1.5 / 255

@pytest.mark.parametrize("target", ["vs_1_1", "vs_2_0"])
def test_struct_cast_of_a_scalar_sets_every_member(backend, target):
    fx = effect_for("""
struct VS_OUTPUT { float4 pos : POSITION; float4 col : COLOR0; float2 uv : TEXCOORD0; };
VS_OUTPUT VS(float4 p : POSITION, float2 uv : TEXCOORD0)
{
    VS_OUTPUT o = (VS_OUTPUT)0.25;     // col = (0.25, 0.25, 0.25, 0.25), uv = (0.25, 0.25)
    o.pos = p;
    o.col.b = uv.x;
    return o;
}
float4 PS(float4 c : COLOR0, float2 t : TEXCOORD0) : COLOR { return float4(c.rgb, t.y * 2); }""",
                    vs=f"compile {target} VS()")
    img = render(fx, backend)
    for x, y in ((1, 1), (6, 4)):
        u, _ = pixel_uv(x, y)
        assert np.allclose(img[y, x], (0.25, 0.25, u, 0.5), atol=TOL), (x, y, img[y, x])


def test_matrix_cast_keeps_the_upper_left_3x3(backend):
    m = np.array([[0.5, 0.25, 0.0, 9.0], [0.0, 0.5, 0.25, 9.0], [0.25, 0.0, 0.5, 9.0],
                  [9.0, 9.0, 9.0, 9.0]])
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float3 n = mul(float3(uv, 1), (float3x3)W);   // row vector times the 3x3: W's 9s unused
    return float4(n, 1);
}""", params="float4x4 W = {" + ", ".join(f"{x:g}" for x in m.reshape(-1)) + "};")
    img = render(fx, backend)
    for x, y in ((2, 5), (7, 0)):
        u, v = pixel_uv(x, y)
        want = np.array([u, v, 1.0]) @ m[:3, :3]
        assert np.allclose(img[y, x, :3], want, atol=TOL), (x, y)


def test_struct_and_vector_casts_take_the_numbers_in_order(backend):
    fx = effect_for("""
struct PAIR { float2 a; float2 b; };
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    PAIR p = (PAIR)float4(uv.x, 0.5, uv.y, 0.25);   // a = (u, 0.5), b = (v, 0.25)
    float4 back = (float4)p;                        // (u, 0.5, v, 0.25)
    return float4(p.b.x, back.y, back.x, p.b.y);
}""")
    img = render(fx, backend)
    u, v = pixel_uv(3, 6)
    assert np.allclose(img[6, 3], (v, 0.5, u, 0.25), atol=TOL)


def test_global_and_local_typedefs_name_types(backend):
    fx = effect_for("""
typedef float4 COLOR4;
COLOR4 PS(float2 uv : TEXCOORD0) : COLOR
{
    typedef int WHOLE;
    COLOR4 c = (COLOR4)0;
    c.r = (WHOLE)(uv.x * 4) / 4.0;                 // truncated: floor(4u) / 4 for u >= 0
    c.g = (float)(WHOLE)(uv.y * 2.0) * 0.5;
    c.a = 1;
    return c;
}""")
    img = render(fx, backend)
    for x, y in ((3, 3), (5, 6)):
        u, v = pixel_uv(x, y)
        assert np.allclose(img[y, x], (np.floor(4 * u) / 4, np.floor(2 * v) * 0.5, 0, 1),
                           atol=TOL), (x, y)


def test_a_typedef_survives_printing_and_reloading():
    import effects
    from effects.frontend.printer import print_effect
    fx = effect_for("typedef float4 C4;\nC4 PS() : COLOR { return (C4)0.5; }")
    again = effects.load_effect(print_effect(fx))
    assert [s.name for s in again.structs] == ["C4"]
    assert "mov oC0" in fx_asm(again, "PS", "ps_2_0")


def _error(functions: str) -> EffectError:
    fx = effect_for(functions)
    with pytest.raises(EffectError) as info:
        fx_asm(fx, "PS", "ps_2_0")
    return info.value


def test_a_cast_between_sizes_that_do_not_fit_is_x3017_at_the_cast():
    err = _error("struct S { float4 a; float b; };\nfloat4 PS() : COLOR\n{\n"
                 "    S s = (S)float2(1, 2);\n    return s.a;\n}")
    assert err.message == "X3017: cannot convert from 'float2' to 'S'"
    assert (err.line, err.column) == (5, 11)


def test_a_cast_to_an_undeclared_type_is_a_located_syntax_error():
    err = _error("float4 PS() : COLOR\n{\n    return (NOTATYPE)0;\n}")
    assert err.message == "X3000: syntax error: unexpected '0'"
    assert (err.line, err.column) == (4, 22)


def test_a_struct_is_not_a_number_in_arithmetic():
    err = _error("struct S { float4 a; };\nfloat4 PS() : COLOR\n{\n"
                 "    return 2 * (S)0;\n}")
    # fxc's code for arithmetic on a struct (DXC's tests record it: X3022)
    assert err.message.startswith("X3022: scalar, vector, or matrix expected")
    assert (err.line, err.column) == (5, 14)


# -- #pragma pack_matrix --------------------------------------------------------------------

M = np.array([[0.25, 0.5, 0.0, 0.0], [0.0, 0.25, 0.5, 0.0], [0.5, 0.0, 0.25, 0.0],
              [0.0, 0.125, 0.0, 0.5]])
M_TEXT = "{" + ", ".join(f"{x:g}" for x in M.reshape(-1)) + "}"
PACKED = """#pragma pack_matrix(%s)
float4x4 A = %s;
%s float4x4 B = %s;
struct HOLDER { float4x4 m; };
HOLDER H = { %s };
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 v = float4(uv, 0.5, 1);
    return float4(mul(v, A).x, mul(v, B).y, mul(v, H.m).z, 1);
}"""


@pytest.mark.parametrize("pragma, qualifier", [("row_major", ""), ("row_major", "column_major"),
                                                ("column_major", "row_major")])
def test_pack_matrix_sets_the_default_layout_and_mul_follows_it(backend, pragma, qualifier):
    fx = effect_for(PACKED % (pragma, M_TEXT, qualifier, M_TEXT, M_TEXT))
    row = {p.name: "row_major" in p.storage for p in fx.parameters if p.name in "AB"}
    assert row == {"A": pragma == "row_major", "B": (qualifier or pragma) == "row_major"}
    text = fx_asm(fx, "PS", "ps_2_0")
    # a row-major matrix's registers are its rows: mul(v, M) = sum v_i * row_i (mul/mad);
    # column-major: one dp4 per column
    assert ("dp4" in text) == (pragma == "column_major" or qualifier == "column_major"), text
    img = render(fx, backend)
    for x, y in ((1, 6), (6, 2)):
        u, v = pixel_uv(x, y)
        want = np.array([u, v, 0.5, 1.0]) @ M
        assert np.allclose(img[y, x, :3], want[:3], atol=TOL), (x, y, img[y, x], want)


def test_pack_matrix_applies_to_functions_declared_after_it():
    fx = effect_for("""float4x4 W;
#pragma pack_matrix(row_major)
float4 PS(float4 p : TEXCOORD0, uniform float4x4 U) : COLOR { return mul(p, U) + mul(p, W); }""")
    text = fx_asm(fx, "PS", "ps_2_0")
    assert text.count("dp4") == 4 and text.count("mad") >= 3     # W by columns, U by rows
    assert [f.row_major for f in fx.functions] == [True]


def test_a_bad_pack_matrix_pragma_is_located():
    import effects
    with pytest.raises(EffectError) as info:
        effects.load_effect("float4 x;\n  #pragma pack_matrix(diagonal)\n")
    assert info.value.message == "#pragma pack_matrix expects (row_major) or (column_major)"
    assert (info.value.line, info.value.column) == (2, 11)


def test_a_member_may_share_a_type_name(backend):
    fx = effect_for("""
struct Material { float4 Diffuse : COLOR0; };
typedef Material MAT;
struct Holder { Material Material; float4 Pos; };
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    Holder h = (Holder)0.5;
    MAT m = (MAT)0;
    m.Diffuse.xy = uv;
    h.Material.Diffuse.x = 0.25;
    return m.Diffuse + h.Material.Diffuse * float4(1, 0, 1, 2);   // (u + .25, v, .5, 1)
}""")
    img = render(fx, backend)
    u, v = pixel_uv(2, 5)
    assert np.allclose(img[5, 2], (u + 0.25, v, 0.5, 1), atol=TOL)
