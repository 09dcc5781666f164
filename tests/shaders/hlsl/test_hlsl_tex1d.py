"""A 1D read's coordinate (issue 31): shader models 2-3 have no 1D textures, a sampler1D is
declared `dcl_2d` and texld reads the coordinate's x and y, so y must hold a value. fxc read an
input's x as `texld r0, v0, s0` and its y as `texld r1, v0.y, s0` (Wine's ps_3_0 sampler test,
tests/data/d3dbc/wine); a computed coordinate had only its x written (`mad r0.x` then
`texld r0, r0, s0` read r0.y, written by nothing). Now ps_3_0 replicates x by the swizzle and
ps_2_0, whose texld takes none, has the producer write x into y too: no slot more."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.shaders.asm import check
from effects.shaders.d3dbc import read_shader
from effects.shaders.hlsl import compile_shader
from tests.shaders.d3dbc.test_wine_d3dx9_shaders import _pairs
from tests.shaders.hlsl.test_hlsl_render import backend, pixel_uv  # noqa: F401


def _texld_coordinates(lines) -> list[str]:
    return [line.split(", ")[1] for line in lines if line.startswith("texld ")]


def _compiled(src: str, target: str):
    fx = effects.load_effect(src + "\ntechnique T { pass P { } }\n")
    shader = compile_shader(fx, "PS", target)
    assert check(shader.program) == []
    return shader


def test_the_coordinates_are_read_as_fxc_read_them_in_wine_s_sampler_shader():
    name, _, hlsl, data = next(p for p in _pairs() if p[0] == "get_shader_samplers_blob")
    from effects.shaders.asm.text import program_text
    fxc = program_text(read_shader(data, name).program).splitlines()
    fx = effects.load_effect(hlsl + "\ntechnique T { pass P { } }\n")
    ours = compile_shader(fx, "main", "ps_3_0").text.splitlines()
    assert _texld_coordinates(ours) == _texld_coordinates(fxc) == ["v0", "v0.y", "v0", "v0",
                                                                   "v0", "v0"]


COMPUTED = ("sampler1D S; float4 PS(float2 uv : TEXCOORD0) : COLOR\n"
            "{ return tex1D(S, uv.x * 0.5 + 0.0625) + tex1D(S, uv.y); }")


def test_a_computed_coordinate_has_its_y_written():
    ps2 = _compiled(COMPUTED, "ps_2_0").text.splitlines()
    assert "mad r0.xy, t0.x, c0.x, c0.y" in ps2 and "mov r1.xy, t0.y" in ps2
    assert _texld_coordinates(ps2) == ["r0", "r1"]
    ps3 = _compiled(COMPUTED, "ps_3_0").text.splitlines()
    assert "mad r0.x, v0, c0.x, c0.y" in ps3
    assert _texld_coordinates(ps3) == ["r0.x", "v0.y"]


def test_a_float_input_read_as_a_1d_coordinate():
    src = "sampler1D S; float4 PS(float u : TEXCOORD0) : COLOR { return tex1D(S, u); }"
    # ps_2_0 reads t0 whole: declared .xy (its y is whatever the vertex shader left there)
    ps2 = _compiled(src, "ps_2_0").text.splitlines()
    assert "dcl t0.xy" in ps2 and _texld_coordinates(ps2) == ["t0"]
    # ps_3_0 reads only what is declared: x, replicated
    ps3 = _compiled(src, "ps_3_0").text.splitlines()
    assert "dcl_texcoord v0.x" in ps3 and _texld_coordinates(ps3) == ["v0.x"]


def test_the_1d_reads_draw_the_texture_s_row(backend):
    # a 4-texel ramp read at u, nearest: the texel's value (x and y of the coordinate equal
    # now, where y was nothing before: a 1D texture has one row, so the picture is the same)
    from effects.assets.textures import make_texture
    src = """
texture Ramp; sampler1D S = sampler_state { Texture = <Ramp>; MinFilter = Point; MagFilter = Point;
    MipFilter = None; AddressU = Clamp; };
float4 PS(float2 uv : TEXCOORD0) : COLOR
{ return float4(tex1D(S, uv.x * 0.5 + 0.25).r, tex1D(S, uv.y).g, 0, 1); }
technique T2 { pass P { PixelShader = compile ps_2_0 PS(); } }
technique T3 { pass P { PixelShader = compile ps_3_0 PS(); } }
"""
    ramp = np.array([[[i / 3, i / 3, 0, 1] for i in range(4)]], np.float32)
    fx = effects.load_effect(src)
    for technique in ("T2", "T3"):
        img = effects.render(fx, "geforce6800", technique=technique, backend=backend,
                             scene={"mesh": "quad", "size": [8, 8]},
                             params={"Ramp": make_texture(ramp, kind="1d", mips=False)})
        img = img.astype(np.float64) / 255
        for x, y in ((1, 2), (6, 5)):
            u, v = pixel_uv(x, y)
            want = (min(int((u * 0.5 + 0.25) * 4), 3) / 3, min(int(v * 4), 3) / 3, 0, 1)
            assert np.allclose(img[y, x], want, atol=1.5 / 255), (technique, x, y, img[y, x])
