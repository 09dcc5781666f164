"""Framework fixes found opening real effect files (tests/data/realfx/<origin>/): globals as
`compile` arguments, CgFX sampler spellings, XNA-style binding by name, Direct3D 10/11
effects named as such, stand-ins of the kind the sampler reads, DX8 dcl-less registers fed by
VertexStreams. Each with its located error or warning."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.cli.main import main
from effects.base.errors import ParseError, StateError
from effects.host.runtime import render_frame
from effects.host.scene import Scene
from effects.host.semantics import bind_scene, name_semantic

QUAD = {"mesh": "quad"}

# -- a global passed as a compile argument ----------------------------------------------------

GLOBAL_ARGUMENT = """
float4 Tint = {0.25, 0.5, 0.75, 1.0};
float4 PS(uniform float4 colour) : COLOR { return colour; }
technique T { pass P { PixelShader = compile ps_2_0 PS(Tint); } }
"""


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_a_global_compile_argument_reads_the_parameter(backend):
    effect = effects.load_effect(GLOBAL_ARGUMENT)
    image = effects.render(effect, "radeon9700", scene=QUAD, size=(8, 8), backend=backend)
    np.testing.assert_allclose(image[4, 4], (64, 128, 191, 255), atol=1)
    # a uniform read, not a folded constant: setting the parameter changes the picture
    image = effects.render(effect, "radeon9700", scene=QUAD, size=(8, 8), backend=backend,
                           params={"Tint": "1, 0, 0, 1"})
    np.testing.assert_allclose(image[4, 4], (255, 0, 0, 255), atol=1)


def test_a_literal_compile_argument_still_folds():
    effect = effects.load_effect(GLOBAL_ARGUMENT.replace("PS(Tint)", "PS(float4(0, 1, 0, 1))"))
    image = effects.render(effect, "radeon9700", scene=QUAD, size=(8, 8),
                           params={"Tint": "1, 0, 0, 1"})
    assert tuple(image[4, 4]) == (0, 255, 0, 255)


def test_a_compile_argument_naming_nothing_is_a_located_error():
    text = GLOBAL_ARGUMENT.replace("PS(Tint)", "PS(Tnit)")
    effect = effects.load_effect(text)
    validation = effect.validate("T", effects.load_profile("radeon9700"))
    assert not validation.ok and "Tnit" in str(validation.reasons[0])


# -- CgFX (OpenGL) sampler-state spellings ----------------------------------------------------

CGFX_SAMPLER = """texture T;
sampler2D S = sampler_state
{
   Texture = <T>;
   MinFilter = Nearest;
   MagFilter = LinearMipMapLinear;
   WrapS = Repeat;
   WrapT = ClampToEdge;
};
"""


def test_cgfx_sampler_spellings_read_as_direct3d_with_warnings():
    effect = effects.load_effect(CGFX_SAMPLER)
    states = {s.name: s.value for s in effect.parameter("S").value.states}
    assert {k: str(v.names[0] if hasattr(v, "names") else v) for k, v in states.items()
            if k != "Texture"} == {"MinFilter": "POINT", "MagFilter": "LINEAR",
                                   "AddressU": "WRAP", "AddressV": "CLAMP"}
    texts = [str(w) for w in effect.warnings]
    assert texts[0] == ("<string>:5:16: warning: MinFilter = Nearest: 'Nearest' is CgFX's "
                        "(OpenGL's) spelling; D3DX's effect compiler rejects it; read as Point")
    assert texts[2] == ("<string>:7:4: warning: 'WrapS' is CgFX's (OpenGL's) name for "
                        "AddressU; D3DX's effect compiler rejects it; read as AddressU")
    assert len(texts) == 6


def test_cgfx_sampler_spellings_are_errors_when_strict():
    with pytest.raises(StateError) as err:
        effects.load_effect(CGFX_SAMPLER, strict=True)
    assert str(err.value).startswith("<string>:5:16: error: MinFilter = Nearest: 'Nearest' is "
                                     "CgFX's")


def test_a_cgfx_word_outside_a_sampler_or_unknown_stays_an_error():
    with pytest.raises(StateError) as err:
        effects.load_effect("texture T; sampler2D S = sampler_state { MinFilter = Nearst; };")
    assert "'Nearst' is not one" in str(err.value)
    effect = effects.load_effect("technique X { pass P { WrapS[0] = Clamp; } }")
    assert [str(w).split(": warning: ")[1] for w in effect.warnings] == [
        "unknown state 'WrapS' (did you mean 'Wrap0'?)"]     # a pass state: not translated


# -- XNA convention: parameters without semantics bound by name -------------------------------

@pytest.mark.parametrize("name, semantic", [
    ("World", "WORLD"), ("view", "VIEW"), ("PROJECTION", "PROJECTION"),
    ("WorldView", "WORLDVIEW"), ("ViewProjection", "VIEWPROJECTION"), ("ViewProj", "VIEWPROJECTION"),
    ("WorldViewProjection", "WORLDVIEWPROJECTION"), ("WVP", "WORLDVIEWPROJECTION"),
    ("g_mWorldViewProjection", "WORLDVIEWPROJECTION"), ("xWorld", "WORLD"), ("matView", "VIEW"),
    ("WorldInverseTranspose", "WORLDINVERSETRANSPOSE"), ("gWorldIT", "WORLDINVERSETRANSPOSE"),
    ("mInvWorld", "WORLDINVERSE"), ("mTransWorld", "WORLDTRANSPOSE"),
    ("CameraPosition", "CAMERAPOSITION"), ("xLightPos", "LIGHTPOSITION"),
    ("LightDirection", "LIGHTDIRECTION"), ("LightColor", "LIGHTCOLOR"),
    ("Tint", None), ("Worldly", None), ("Material", None), ("Time", None), ("matrix", None)])
def test_name_convention(name, semantic):
    assert name_semantic(name) == semantic


XNA = """float4x4 World, View, Projection;
float4x4 Other : VIEW;
float4x4 Given;
float3 LightPosition = {1, 2, 3};
float4 PS() : COLOR { return 1; }
float4 VS(float4 p : POSITION) : POSITION { return mul(mul(mul(p, World), View), Projection); }
technique T { pass P { VertexShader = compile vs_2_0 VS(); PixelShader = compile ps_2_0 PS(); } }
"""


def test_xna_matrices_are_bound_by_name_and_a_semantic_wins():
    effect = effects.load_effect(XNA)
    scene = Scene()
    m = scene.matrices((64, 64))
    bound = bind_scene(effect, scene, (64, 64))
    np.testing.assert_allclose(bound["World"], m["world"])
    np.testing.assert_allclose(bound["View"], m["view"])
    np.testing.assert_allclose(bound["Projection"], m["projection"])
    np.testing.assert_allclose(bound["Other"], m["view"])          # its semantic
    assert "Given" not in bound
    # a light by name keeps the file's own value unless the scene places a light, as by semantic
    assert "LightPosition" not in bound
    assert bind_scene(effect, Scene(light_given=True), (64, 64))["LightPosition"].tolist() == \
        [2, 2, 2]


def test_xna_effect_draws_the_sphere_without_set():
    frame = render_frame(effects.load_effect(XNA), "radeon9700", size=(64, 64))
    covered = frame.image[..., 3] > 0
    assert covered.mean() == pytest.approx(0.573, abs=0.03)       # the camera's sphere, not black


def test_a_value_the_user_sets_wins_over_the_name(tmp_path):
    identity = ",".join(str(float(i % 5 == 0)) for i in range(16))
    frame = render_frame(effects.load_effect(XNA), "radeon9700", size=(64, 64),
                         scene=QUAD, params={"World": identity, "View": identity,
                                             "Projection": identity})
    assert (frame.image[..., 3] > 0).mean() > 0.95                 # the quad fills the frame


def test_doctor_says_bound_by_name(capsys, tmp_path):
    path = tmp_path / "xna.fx"
    path.write_text(XNA)
    assert main(["doctor", str(path), "--profile", "radeon9700"]) in (0, 1)
    out = capsys.readouterr().out
    assert "World <- bound by name (XNA convention) as WORLD" in out
    assert "Projection <- bound by name (XNA convention) as PROJECTION" in out
    assert "Other <- semantic VIEW" in out
    # set by nothing, and no shader of T reads it (VS reads World, View, Projection)
    assert "  set by nothing, but T does not read them: Given\n" in out


# -- Direct3D 10/11 effects -------------------------------------------------------------------

def test_technique11_is_named_where_it_starts():
    text = "float4 PS() : SV_Target { return 1; }\ntechnique11 T\n{ pass P0 { SetPixelShader(" \
           "CompileShader(ps_4_0, PS())); } };\n"
    with pytest.raises(ParseError) as err:
        effects.load_effect(text)
    assert str(err.value).startswith("<string>:2:1: error: 'technique11' is Direct3D 10/11 "
                                     "effect syntax: this is a Direct3D 10/11 effect")


@pytest.mark.parametrize("text, where, word", [
    ("fxgroup g\n{\n technique11 T { pass P { } }\n}\n", "1:1", "fxgroup"),
    ("texture2D t;\nSamplerState S\n{\n Filter = MIN_MAG_MIP_LINEAR;\n};\n", "2:1", "SamplerState"),
    ("BlendState B { BlendEnable[0] = FALSE; };", "1:1", "BlendState"),
])
def test_direct3d10_constructs(text, where, word):
    with pytest.raises(ParseError) as err:
        effects.load_effect(text)
    assert str(err.value).startswith(f"<string>:{where}: error: '{word}' is Direct3D 10/11")


def test_an_error_before_any_direct3d10_word_is_reported_as_it_was():
    with pytest.raises(ParseError) as err:
        effects.load_effect("float4 a = ;\nBlendState B { BlendEnable[0] = FALSE; };\n")
    assert str(err.value).startswith("<string>:1:") and "Direct3D 10" not in str(err.value)
    # a word in a string is not syntax
    with pytest.raises(ParseError) as err:
        effects.load_effect('string s = "BlendState";\nfloat4 a = ;\n')
    assert "Direct3D 10" not in str(err.value)


def test_sv_semantics_in_an_effect_with_techniques_are_not_flagged():
    effect = effects.load_effect("float4 PS() : SV_Target { return 1; }\n"
                                 "technique T { pass P { PixelShader = compile ps_2_0 PS(); } }")
    assert not effect.warnings


# -- stand-ins of the sampler's kind, DX8 registers fed by VertexStreams -----------------------

def test_an_untyped_texture_sampled_as_a_volume_gets_the_volume_stand_in():
    text = """texture T; sampler3D S = sampler_state { Texture = <T>; };
float4 PS(float3 uvw : TEXCOORD0) : COLOR { return tex3D(S, uvw); }
technique X { pass P { PixelShader = compile ps_2_0 PS(); } }"""
    frame = render_frame(effects.load_effect(text), "radeon9700", size=(16, 16))
    assert [w.message.rsplit("(", 1)[1] for w in frame.warnings] == ["noise_volume, 3d)"]


def test_vertex_streams_feed_dcl_less_dx8_registers():
    # v1 is BLENDWEIGHT in Direct3D 8's fixed mapping; an engine's declaration put the normal there
    text = """string VertexStreams = "blendweight=normal";
float4x4 Wvp : WORLDVIEWPROJECTION;
technique X { pass P {
    VertexShaderConstant4[0] = <Wvp>;
    VertexShader = asm { vs.1.1
        m4x4 oPos, v0, c0
        mad oD0, v1, c4.x, c4.x };
    VertexShaderConstant1[4] = {0.5, 0.5, 0.5, 0.5};
    ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse; } }"""
    image = render_frame(effects.load_effect(text), "geforce3", size=(64, 64)).image.astype(int)
    # the normal facing the camera (0, 0, 1) as a colour: (0.5, 0.5, 1.0) at the centre
    np.testing.assert_allclose(image[31:33, 31:33, :3].reshape(-1, 3).mean(0), (128, 128, 255),
                               atol=6)
    with pytest.raises(effects.EffectError) as err:
        render_frame(effects.load_effect(text.replace("blendweight=normal", "blendwieght=normal")),
                     "geforce3", size=(16, 16))
    assert "unknown vertex stream 'blendwieght'" in str(err.value)


# -- mul(column_major M, v): columns scaled and summed, as fxc emits ---------------------------

COLUMN_VECTOR = """float4x4 M : WORLDVIEWPROJECTIONTRANSPOSE;
float4x4 R : WORLDVIEWPROJECTION;
float4 VS(float3 p : POSITION) : POSITION { return mul(M, float4(p, 1)); }
float4 VSRow(float3 p : POSITION) : POSITION { return mul(float4(p, 1), R); }
float4 PS() : COLOR { return float4(0, 1, 0, 1); }
technique Col { pass P { VertexShader = compile vs_2_0 VS(); PixelShader = compile ps_2_0 PS(); } }
technique Row { pass P { VertexShader = compile vs_2_0 VSRow(); PixelShader = compile ps_2_0 PS(); } }
"""


def test_matrix_times_column_vector_is_a_mul_and_mads_over_the_columns():
    from effects.shaders.hlsl import compile_state
    effect = effects.load_effect(COLUMN_VECTOR)
    shader = compile_state(effect, effect.technique("Col").passes[0].state("VertexShader").value)
    body = [line.strip() for line in shader.text.splitlines()
            if line.strip() and not line.strip().startswith(("vs_", "dcl", "//", "def"))]
    # w = 1 folds the last mad into an add; no movs gathering a row of the matrix
    assert body == ["mul r0, c0, v0.x", "mad r0, c1, v0.y, r0", "mad r0, c2, v0.z, r0",
                    "add oPos, c3, r0"]
    # the same picture as the row-vector form with the untransposed matrix
    col = render_frame(effect, "radeon9700", technique="Col", size=(32, 32)).image
    row = render_frame(effect, "radeon9700", technique="Row", size=(32, 32)).image
    assert (col == row).all() and (col[..., 1] == 255).mean() > 0.5
