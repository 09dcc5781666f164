"""A texture that feeds a normal, which nothing supplies, is drawn with a flat normal map
(0.5, 0.5, 1), not the checker (issue 32): by its name or its samplers', or by the way a
shader expands what it samples to [-1, 1]."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.host.resources import feeds_a_normal, stand_in_texture
from effects.host.runtime import render_frame

BODY = """
float4x4 WorldViewProj : WORLDVIEWPROJECTION;
texture {tex};
sampler {sampler} = sampler_state {{ Texture = <{tex}>; }};
struct O {{ float4 p : POSITION; float2 uv : TEXCOORD0; }};
O vs(float4 p : POSITION, float2 uv : TEXCOORD0) {{ O o; o.p = mul(p, WorldViewProj); o.uv = uv; return o; }}
float4 ps(float2 uv : TEXCOORD0) : COLOR0 {{ float3 n = {use}; return saturate(n.z); }}
technique T {{ pass P {{ VertexShader = compile vs_2_0 vs(); PixelShader = compile ps_2_0 ps(); }} }}
"""


def effect_with(tmp_path, tex: str, sampler: str, use: str):
    path = tmp_path / "n.fx"
    path.write_text(BODY.format(tex=tex, sampler=sampler, use=use))
    return effects.load_effect(path)


@pytest.mark.parametrize("tex, sampler, use, normal", [
    ("NormalMap", "S", "tex2D(S, uv).xyz", True),              # the texture's name
    ("T", "BumpSampler", "tex2D(BumpSampler, uv).xyz", True),  # the sampler's name
    ("g_MeshNrm", "S", "tex2D(S, uv).xyz", True),
    ("T", "S", "tex2D(S, uv).xyz * 2 - 1", True),              # what the shader does with it
    ("T", "S", "2.0f * tex2D(S, uv).rgb - 1.0", True),
    ("T", "S", "tex2D(S, uv).xyz * 2.0 - 1", True),
    ("DiffuseMap", "S", "tex2D(S, uv).xyz", False),
    ("T", "S", "tex2D(S, uv).xyz * 0.5", False),
])
def test_what_feeds_a_normal(tmp_path, tex, sampler, use, normal):
    effect = effect_with(tmp_path, tex, sampler, use)
    assert feeds_a_normal(effect, effect.parameter(tex)) == normal


def test_an_asm_pass_that_expands_its_stage_with_bx2(tmp_path):
    path = tmp_path / "dot3.fx"
    path.write_text("""texture Surface; texture Base;
technique T { pass P {
    Texture[0] = <Surface>; Texture[1] = <Base>;
    PixelShader = asm { ps.1.1
        tex t0
        tex t1
        dp3_sat r0, t0_bx2, v0_bx2
    };
} }""")
    effect = effects.load_effect(path)
    assert feeds_a_normal(effect, effect.parameter("Surface"))
    assert not feeds_a_normal(effect, effect.parameter("Base"))


def test_the_flat_normal_texels_and_what_they_light(tmp_path):
    texture = stand_in_texture("2d", normal=True)
    assert texture.name == "flat_normal"
    assert np.unique(texture.levels[0].reshape(-1, texture.levels[0].shape[-1]), axis=0).shape[0] == 1
    assert stand_in_texture("cube", normal=True).name != "flat_normal"   # only a 2D map
    # n.z of a flat map, expanded, is 255/255 * 2 - 1 = 1 everywhere on the sphere: white
    # where it is drawn; with the checker it was 1 or -1 in blocks
    effect = effect_with(tmp_path, "T", "S", "tex2D(S, uv).xyz * 2 - 1")
    frame = render_frame(effect, "refrast", size=(32, 32))
    assert "flat_normal" in frame.warnings[0].message
    drawn = frame.image[frame.image[..., 3] > 0][:, :3]
    assert len(drawn) > 100 and (drawn == 255).all()
    plain = effect_with(tmp_path, "T", "S", "tex2D(S, uv).xyz")
    assert "checker" in render_frame(plain, "refrast", size=(32, 32)).warnings[0].message
