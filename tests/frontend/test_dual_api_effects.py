"""Effects written for Direct3D 9 and 10 at once, as foo_wave_seekbar's Direct3D 9 front end
hands them to D3DXCreateEffect: a `technique10` next to the `technique`, and Direct3D 10
system-value semantics (SV_POSITION, SV_Target) in shaders compiled for vs_2_0/ps_2_0. D3DX9
loads the `technique` and passes over the other; fxc reads the SV_ semantics by their Direct3D 9
meaning. And ps_3_0's own inputs, VPOS and VFACE, which SV_Position also names there."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.base.errors import ParseError

QUAD = {"mesh": "quad"}

DUAL = """
struct VS_OUT { float4 pos : SV_POSITION; float2 uv : TEXCOORD0; };
VS_OUT VS(float4 p : POSITION, float2 uv : TEXCOORD0)
{
    VS_OUT o = (VS_OUT)0;
    o.pos = p;
    o.uv = uv;
    return o;
}
float4 PS(VS_OUT i) : SV_Target { return float4(i.uv, 0.25, 1); }

technique10 Render10
{
    pass P0
    {
        SetGeometryShader( 0 );
        SetVertexShader( CompileShader( vs_4_0, VS() ) );
        SetPixelShader( CompileShader( ps_4_0, PS() ) );
    }
}

technique Render9
{
    pass { VertexShader = compile vs_2_0 VS(); PixelShader = compile ps_2_0 PS(); }
}
"""


def test_the_direct3d10_technique_is_skipped_with_a_located_warning():
    effect = effects.load_effect(DUAL)
    assert [t.name for t in effect.techniques] == ["Render9"]
    (warning,) = [w for w in effect.warnings if "skipped" in w.message]
    assert (warning.location.line, warning.location.column) == (12, 1)
    assert warning.message.startswith("technique10 'Render10' skipped: a Direct3D 10/11 "
                                      "technique, which D3DX9 passes over")


def test_lines_after_a_skipped_block_keep_their_locations():
    broken = DUAL.replace("PixelShader = compile ps_2_0 PS();", "PixelShader = = 1;")
    line = broken[:broken.index("= = 1")].count("\n") + 1
    with pytest.raises(ParseError) as err:
        effects.load_effect(broken)
    assert err.value.location.line == line == 24


def test_a_file_with_only_direct3d10_techniques_keeps_its_error():
    only10 = DUAL[:DUAL.index("technique Render9")]
    with pytest.raises(ParseError) as err:
        effects.load_effect(only10)
    assert "'technique10' is Direct3D 10/11 effect syntax" in str(err.value)


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_sv_semantics_read_as_position_and_color(backend):
    # the quad's uv runs (0,0) top-left to (1,1) bottom-right; D3D9 samples pixel (x, y) at
    # screen point (x, y) (integer centres, the half-pixel offset), so it sees uv (x / 8, y / 8)
    image = effects.render(effects.load_effect(DUAL), "radeon9700", scene=QUAD, size=(8, 8),
                           backend=backend).astype(int)
    for x, y in [(0, 0), (3, 5), (7, 7)]:
        expected = [round(x / 8 * 255), round(y / 8 * 255), round(0.25 * 255), 255]
        np.testing.assert_allclose(image[y, x], expected, atol=1)


def test_sv_semantics_compile_to_the_direct3d9_registers():
    from effects.model import CompileShader
    from effects.shaders.hlsl import compile_state
    effect = effects.load_effect(DUAL)
    vs, ps = (s.value for s in effect.techniques[0].passes[0].states
              if isinstance(s.value, CompileShader))
    assert "oPos" in compile_state(effect, vs).text
    assert "oC0" in compile_state(effect, ps).text


DEPTH = """
float4 PS(float2 uv : TEXCOORD0, out float depth : SV_Depth) : SV_Target0
{ depth = 0.25; return float4(1, 0, 0, 1); }
technique T { pass P { PixelShader = compile ps_2_0 PS(); } }
"""


def test_sv_depth_is_the_depth_output():
    from effects.model import CompileShader
    from effects.shaders.hlsl import compile_state
    effect = effects.load_effect(DEPTH)
    (ps,) = (s.value for s in effect.techniques[0].passes[0].states
             if isinstance(s.value, CompileShader))
    text = compile_state(effect, ps).text
    assert "oDepth" in text and "oC0" in text


def _misc_effect(semantic: str, body: str) -> str:
    return f"""
float4 VS(float4 p : POSITION) : POSITION {{ return p; }}
float4 PS(float2 p : {semantic}) : COLOR {{ {body} }}
technique T {{ pass P {{ VertexShader = compile vs_3_0 VS();
                         PixelShader = compile ps_3_0 PS(); }} }}
"""


@pytest.mark.parametrize("semantic", ["VPOS", "SV_Position"])
@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_ps3_position_input_is_vpos(semantic, backend):
    # vPos holds D3D9's integer pixel coordinates: frac(x / 8) at x = 1, 2, 5 is 1/8, 2/8, 5/8
    effect = effects.load_effect(_misc_effect(semantic, "return float4(frac(p / 8), 0, 1);"))
    image = effects.render(effect, "radeonx1800", scene=QUAD, size=(8, 8),
                           backend=backend).astype(int)
    for x, y in [(1, 2), (5, 0), (0, 7)]:
        expected = [round(x / 8 * 255), round(y / 8 * 255), 0, 255]
        np.testing.assert_allclose(image[y, x], expected, atol=1)


def test_ps3_vpos_is_declared():
    from effects.model import CompileShader
    from effects.shaders.hlsl import compile_state
    effect = effects.load_effect(_misc_effect("VPOS", "return float4(p, 0, 1);"))
    ps = [s.value for s in effect.techniques[0].passes[0].states
          if isinstance(s.value, CompileShader)][1]
    assert "dcl vPos.xy" in compile_state(effect, ps).text.splitlines()


FACE = """
float4 VS(float4 p : POSITION) : POSITION { return p; }
float4 PS(float face : VFACE) : COLOR { return face > 0 ? float4(0, 1, 0, 1) : float4(1, 0, 0, 1); }
technique T { pass P { CullMode = None; VertexShader = compile vs_3_0 VS();
                       PixelShader = compile ps_3_0 PS(); } }
"""


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_ps3_vface_tells_the_faces_apart(backend):
    # the quad is clockwise on screen, front-facing under D3D's rule: VFACE > 0, green
    image = effects.render(effects.load_effect(FACE), "radeonx1800", scene=QUAD, size=(8, 8),
                           backend=backend).astype(int)
    np.testing.assert_allclose(image[4, 4], [0, 255, 0, 255], atol=1)


def test_many_direct3d10_blocks_load_in_bounded_time():
    # hostile input: thousands of blocks, each warned once, in one scan of the text
    import time
    text = DUAL + "technique10 X { pass { } }\n" * 5000
    start = time.process_time()
    effect = effects.load_effect(text)
    assert time.process_time() - start < 5.0
    assert [t.name for t in effect.techniques] == ["Render9"]
    skipped = [w for w in effect.warnings if "skipped" in w.message]
    assert len(skipped) == 5001 and skipped[-1].location.line == DUAL.count("\n") + 5000


def test_an_unclosed_direct3d10_block_is_the_parsers_error():
    with pytest.raises(ParseError):
        effects.load_effect(DUAL + "technique10 Open { pass {\n")
