"""Texture reads in vertex shaders (issue 31): fxc's vertex code generator has texldl alone
(vs_3_0), so tex2D, tex2Dbias, tex2Dproj, texCUBE, tex2Dgrad ... in a vertex function are
"X4532: cannot map expression to vertex shader instruction set" (fxc 9.29 for tex1D in the SDK's
Skinning10 vertex function compiled for vs_3_0) for every vertex target: a language error, at
the call. tex2Dlod compiles for vs_3_0 (texldl) and is a refusal for vs_1_1/vs_2_0 only; its
pictures on both back ends are tests/validate/test_vertex_textures.py's."""
from __future__ import annotations

import pytest

import effects
from effects.base.errors import EffectError
from effects.shaders.hlsl import compile_shader

VS = """sampler S;
samplerCUBE C;
float4 VS(float4 uv : TEXCOORD0) : POSITION
{{
    return {call};
}}
technique T {{ pass P {{ VertexShader = compile vs_3_0 VS(); }} }}
"""
PREFIX = "X4532: cannot map expression to vertex shader instruction set: "


def refusal(call: str, target: str) -> EffectError:
    fx = effects.load_effect(VS.format(call=call))
    with pytest.raises(EffectError) as info:
        compile_shader(fx, "VS", target)
    return info.value


@pytest.mark.parametrize("call, named, source, lod", [
    ("tex2D(S, uv.xy)", "tex2D", "derivatives", "tex2Dlod"),
    ("tex2Dbias(S, uv)", "tex2Dbias", "derivatives", "tex2Dlod"),
    ("tex2Dproj(S, uv)", "tex2Dproj", "derivatives", "tex2Dlod"),
    ("tex1D(S, uv.x)", "tex1D", "derivatives", "tex1Dlod"),
    ("texCUBE(C, uv.xyz)", "texCUBE", "derivatives", "texCUBElod"),
    ("tex2Dgrad(S, uv.xy, uv.xy, uv.xy)", "tex2Dgrad", "gradients", "tex2Dlod"),
    ("tex2D(S, uv.xy, uv.xy, uv.xy)", "tex2Dgrad", "gradients", "tex2Dlod"),
])
@pytest.mark.parametrize("target", ["vs_3_0", "vs_2_0", "vs_1_1"])
def test_a_read_at_a_level_pixels_choose_is_a_language_error_in_a_vertex_shader(
        call, named, source, lod, target):
    err = refusal(call, target)
    assert str(err).split("\n")[0] == (
        f"<string>:5:12: error: {PREFIX}{named} needs a pixel shader (the level of its read "
        f"comes from {source} between pixels); a vertex shader reads a level it names with "
        f"{lod} (texldl, vs_3_0)")
    assert err.language is True


@pytest.mark.parametrize("target", ["vs_2_0", "vs_1_1"])
def test_tex2dlod_before_vs_3_0_is_a_refusal_for_the_target(target):
    err = refusal("tex2Dlod(S, uv)", target)
    assert err.message == (f"{PREFIX}{target} cannot sample textures (tex2Dlod: vertex texture "
                           "fetch needs vs_3_0)")
    assert err.language is False and (err.location.line, err.location.column) == (5, 12)


def test_tex2dlod_in_vs_3_0_is_texldl():
    fx = effects.load_effect(VS.format(call="tex2Dlod(S, uv) + texCUBElod(C, uv)"))
    lines = [line.strip() for line in compile_shader(fx, "VS", "vs_3_0").text.splitlines()]
    assert "texldl r0, v0, s0" in lines and "texldl r1, v0, s1" in lines, lines
    assert not any(line.startswith(("texld ", "texldb", "texldp", "texldd")) for line in lines)
