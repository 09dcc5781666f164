"""Input declarations as fxc wrote them (issue 31): a pixel shader's input is declared with the
components of its type (`dcl t0.xy` for a float2 TEXCOORD0, `dcl v0` for a float4 COLOR0: SDL 2's
ps_2_0 bytecode in tests/data/d3dbc), a vertex shader's with all four (`dcl_normal v1` for a
float3 NORMAL: Wine's vs_2_0). Slot-neutral: the listing and the bytecode change, not the code."""
from __future__ import annotations

import pytest

import effects
from effects.shaders.asm import check
from effects.shaders.d3dbc import read_header, read_shader, write_shader
from effects.shaders.hlsl import compile_shader
from tests.paths import TESTS

DATA = TESTS / "data" / "d3dbc"


def _dcls(program) -> dict[str, tuple | None]:
    """register -> its declared mask (None: all four), samplers left out."""
    return {d.register.text: d.register.mask for d in program.dcls
            if d.register.kind != "s"}


def _compiled(src: str, entry: str, target: str):
    fx = effects.load_effect(src + "\ntechnique T { pass P { } }\n")
    shader = compile_shader(fx, entry, target)
    assert check(shader.program) == []
    return shader


# SDL's YUV shader's inputs and what it does with them, in Direct3D 9 syntax (its own HLSL is
# Direct3D 10's, which the front end does not read yet): three planes, one colour
SDL_LIKE = """
sampler Y : register(s0); sampler U : register(s1); sampler V : register(s2);
struct PixelShaderInput { float4 pos : POSITION; float2 tex : TEXCOORD0; float4 color : COLOR0; };
float4 main(PixelShaderInput input) : COLOR
{
    float3 yuv = float3(tex2D(Y, input.tex).r, tex2D(U, input.tex).r, tex2D(V, input.tex).r);
    return float4(yuv, 1) * input.color;
}"""


def test_the_pixel_inputs_are_declared_as_fxc_declared_sdl_s():
    fxc = read_shader(dict(read_header((DATA / "sdl" / "SDL_shaders_d3d.c").read_text()))
                      ["D3D9_PixelShader_YUV_JPEG"]).program
    assert _dcls(fxc) == {"t0": (0, 1), "v0": None}
    shader = _compiled(SDL_LIKE, "main", "ps_2_0")
    assert [line for line in shader.text.splitlines() if line.startswith("dcl ")] == [
        "dcl t0.xy", "dcl v0"]
    # the same tokens in our bytecode as in fxc's
    ours = read_shader(write_shader(shader.program, shader)).program
    assert _dcls(ours) == _dcls(fxc)


@pytest.mark.parametrize("target, decl", [
    ("ps_2_0", ["dcl t0.xy", "dcl t1.xyz", "dcl v0", "dcl v1.x"]),
    ("ps_3_0", ["dcl_texcoord v0.xy", "dcl_texcoord1 v1.xyz", "dcl_color v2",
                "dcl_color1 v3.x"])])
def test_a_pixel_input_declares_the_components_of_its_type(target, decl):
    src = ("float4 PS(float2 uv : TEXCOORD0, float3 n : TEXCOORD1, float4 c : COLOR0, "
           "float f : COLOR1) : COLOR { return float4(uv, n.z, f) * c; }")
    shader = _compiled(src, "PS", target)
    assert [line for line in shader.text.splitlines() if line.startswith("dcl")] == decl


def test_one_register_read_as_two_types_declares_the_wider():
    src = ("float4 PS(float2 a : TEXCOORD0, float3 b : TEXCOORD0) : COLOR "
           "{ return float4(a, b.z, 1); }")
    assert "dcl_texcoord v0.xyz" in _compiled(src, "PS", "ps_3_0").text


def test_a_vertex_input_declares_all_four_as_fxc_declared_wine_s():
    wine = DATA / "wine" / "d3d10core_test_create_shader.c"
    fxc = read_shader(read_header(wine.read_text())[0][1]).program
    assert _dcls(fxc) == {"v0": None, "v1": None}        # float4 POSITION, float3 NORMAL
    src = ("float4 light; float4x4 mat;\n"
           "float4 VS(float4 p : POSITION, float3 n : NORMAL, out float4 d : COLOR) : POSITION\n"
           "{ d = dot((float3)light, n); return mul(p, mat); }")
    shader = _compiled(src, "VS", "vs_2_0")
    assert _dcls(read_shader(write_shader(shader.program, shader)).program) == _dcls(fxc)
