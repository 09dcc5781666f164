"""The later fxc's syntax in shader model 2-3 HLSL (issue 31): `cbuffer` members as uniforms,
`SamplerState` with `Texture2D.Sample`/`SampleLevel`/`SampleBias`/`SampleGrad` and
`TextureCube.Sample` as the DX9 reads they are, the pair (sampler, texture) one sampler
register; what only shader model 4 has refused where it is written. Values worked out by hand,
drawn on both back ends.
"""
from __future__ import annotations

import re

import numpy as np
import pytest

import effects
from effects.assets.textures import make_texture
from effects.base.errors import EffectError, ParseError
from effects.program.backend import create_backend
from effects.shaders.hlsl import compile_shader

SIZE = (8, 8)
QUAD = {"mesh": "quad", "size": list(SIZE)}
# a 2 x 2 texture: red, green / blue, white (u to the right, v down)
TEXELS = np.array([[[1, 0, 0, 1], [0, 1, 0, 1]], [[0, 0, 1, 1], [1, 1, 1, 1]]], np.float32)
POINT = "sampler_state { MinFilter = Point; MagFilter = Point; MipFilter = Point; }"


@pytest.fixture(scope="module", params=("numpy", "gl"))
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


def asm(fx: effects.Effect, entry: str, target: str) -> list[str]:
    return [line.strip() for line in compile_shader(fx, entry, target).text.splitlines()]


def draw(fx: effects.Effect, backend, params: dict) -> np.ndarray:
    return effects.render(fx, "geforce6800", technique="T", backend=backend, scene=QUAD,
                          params=params).astype(np.float64) / 255.0


def texel_at(x: int, y: int) -> np.ndarray:
    """The texel point sampling reads at pixel (x, y) of the 8 x 8 quad, whose uv is x/8, y/8:
    the shaders add 1/32 so that no pixel samples on a texel edge (a tie)."""
    return TEXELS[y * 2 // SIZE[1], x * 2 // SIZE[0]]


# -- cbuffer -------------------------------------------------------------------------------

CBUFFER = """
cbuffer Material : register(b0)
{
    float4 Tint;
    float Gain : packoffset(c3);
    float4 Unused < string UIName = "not read"; > = {1, 2, 3, 4};
};
float4 PS() : COLOR { return Tint * Gain; }
technique T { pass P { PixelShader = compile ps_2_0 PS(); } }
"""


def test_cbuffer_members_are_uniforms_and_packoffset_is_their_register(backend):
    fx = effects.load_effect(CBUFFER)
    assert [p.name for p in fx.parameters] == ["Tint", "Gain", "Unused"]
    assert fx.parameter("Gain").register_for("ps_2_0", "c") == "c3"
    assert fx.parameter("Unused").annotation("UIName").value == "not read"
    # printed as the Direct3D 9 declarations they are, and read back the same
    assert "float Gain : register(c3);" in fx.to_source()
    assert effects.load_effect(fx.to_source()).parameters == fx.parameters
    lines = asm(fx, "PS", "ps_2_0")
    assert "mul r0, c0, c3.x" in lines, lines          # Tint by first use, Gain in c3
    img = draw(fx, backend, {"Tint": [1.0, 0.5, 0.25, 1.0], "Gain": 0.5})
    assert np.allclose(img[4, 4], [0.5, 0.25, 0.125, 0.5], atol=1.5 / 255), img[4, 4]


def test_a_member_packed_into_a_later_lane_is_refused_where_it_is_declared():
    text = "cbuffer B\n{\n    float4 A;\n    float S : packoffset(c1.y);\n};\n"
    with pytest.raises(ParseError) as err:
        effects.load_effect(text)
    assert str(err.value).startswith("<string>:4:11: error: 'S': packoffset(c1.y) has no "
                                     "register in shader models 1-3"), str(err.value)


def test_an_unclosed_cbuffer_is_named_at_the_end_of_the_file():
    with pytest.raises(ParseError) as err:
        effects.load_effect("cbuffer B\n{\n    float4 A;\n")
    assert str(err.value).startswith("<string>:3:14: error: unexpected end of file: missing "
                                     "'}' to close the cbuffer opened at line 2"), str(err.value)


TBUFFER = """
tbuffer Bones : register(t0)
{
    float4 M[2];
    float Scale < string UIName = "scale"; >;
};
float4 Tint;
float4 Reads(float2 uv : TEXCOORD0) : COLOR { return Tint * M[1]; }
float4 PS() : COLOR { return Tint; }
technique T { pass P { PixelShader = compile ps_2_0 PS(); } }
"""


def test_a_tbuffer_declares_its_members_and_a_read_of_one_is_x3546(backend):
    """The later fxc parsed a tbuffer for every target and refused a read of its members on
    those without texture buffers (its error list: X3546, "Reading from texture buffers is
    unsupported on the specified target"): shader models 1-3. A function that reads none
    compiles and draws."""
    fx = effects.load_effect(TBUFFER)
    assert [(p.name, p.tbuffer) for p in fx.parameters] == [("M", "Bones"), ("Scale", "Bones"),
                                                            ("Tint", "")]
    assert fx.parameter("Scale").annotation("UIName").value == "scale"
    assert effects.load_effect(fx.to_source()).parameters == fx.parameters
    for target in ("ps_2_0", "ps_3_0", "ps_1_1"):
        with pytest.raises(EffectError) as err:
            compile_shader(fx, "Reads", target)
        assert str(err.value).startswith(
            f"<string>:8:61: error: X3546: reading from texture buffers is unsupported on "
            f"{target}: 'M' is a member of tbuffer 'Bones'"), str(err.value)
        assert err.value.language is False       # a target's refusal: shader model 4 reads it
    img = draw(fx, backend, {"Tint": [0.25, 0.5, 1.0, 1.0]})
    assert np.allclose(img[4, 4], [0.25, 0.5, 1.0, 1.0], atol=1.5 / 255), img[4, 4]


def test_state_objects_are_still_direct3d10_effect_syntax():
    for text, where, word in [
            ("Texture2D t;\nSamplerState S : IMMUTABLE\n{\n Filter = MIN_MAG_MIP_LINEAR;\n};\n",
             "2:1", "SamplerState")]:
        with pytest.raises(ParseError) as err:
            effects.load_effect(text)
        assert str(err.value).startswith(f"<string>:{where}: error: '{word}' is Direct3D 10/11 "
                                         "effect syntax"), str(err.value)


# -- Texture2D.Sample -----------------------------------------------------------------------

SAMPLE = f"""
Texture2D Tex;
SamplerState Samp = {POINT};
float4 PS(float2 uv : TEXCOORD0) : COLOR {{ return Tex.Sample(Samp, uv + 1.0 / 32) * 0.5; }}
technique T {{ pass P {{ PixelShader = compile ps_2_0 PS(); }} }}
"""


def test_texture_sample_reads_the_texture_through_the_samplers_register(backend):
    fx = effects.load_effect(SAMPLE)
    compiled = compile_shader(fx, "PS", "ps_2_0")
    assert compiled.samplers == {"Samp+Tex": 0}
    lines = asm(fx, "PS", "ps_2_0")
    assert "dcl_2d s0" in lines and "texld r0, r0, s0" in lines, lines
    img = draw(fx, backend, {"Tex": make_texture(TEXELS, mips=False)})
    for y in range(SIZE[1]):
        for x in range(SIZE[0]):
            assert np.allclose(img[y, x], texel_at(x, y) * 0.5, atol=1.5 / 255), (x, y, img[y, x])


def test_the_pair_takes_a_register_before_the_samplers_read_alone(backend):
    """vkd3d's combined-samplers test records native d3dcompiler's placement for shader
    model 1-3: the (sampler, texture) pair's register comes before a sampler read by tex2D,
    whatever order the code reads them in. The sampler alone keeps its sampler_state's texture;
    the pair reads the texture it names."""
    fx = effects.load_effect(f"""
texture Other;
Texture2D Tex;
sampler Samp = sampler_state {{ Texture = <Other>; MinFilter = Point; MagFilter = Point; }};
float4 PS(float2 uv : TEXCOORD0) : COLOR
{{
    return tex2D(Samp, uv + 1.0 / 32) * 0.25 + Tex.Sample(Samp, uv + 1.0 / 32) * 0.5;
}}
technique T {{ pass P {{ PixelShader = compile ps_2_0 PS(); }} }}
""")
    assert compile_shader(fx, "PS", "ps_2_0").samplers == {"Samp+Tex": 0, "Samp": 1}
    grey = np.full((2, 2, 4), 1.0, np.float32)
    img = draw(fx, backend, {"Tex": make_texture(TEXELS, mips=False),
                             "Other": make_texture(grey, mips=False)})
    for y, x in ((0, 0), (1, 6), (6, 1), (7, 7)):
        want = np.minimum(texel_at(x, y) * 0.5 + 0.25, 1.0)
        assert np.allclose(img[y, x], want, atol=1.5 / 255), (x, y, img[y, x], want)


ELEMENT = f"""
Texture2D<float2> Tex < string UIName = "Base"; >;
Texture2D < float > Red;
SamplerState Samp = {POINT};
float4 PS(float2 uv : TEXCOORD0) : COLOR
{{
    return float4(Tex.Sample(Samp, uv + 1.0 / 32), 0.25, 1) * Red.Sample(Samp, uv);
}}
technique T {{ pass P {{ PixelShader = compile ps_2_0 PS(); }} }}
"""


def test_a_texture_with_its_element_type_reads_that_type(backend):
    """`Texture2D<float2>` (the later fxc's template form) reads a float2, `Texture2D<float>`
    a float: the sample's first components. The brackets are the type's, the annotation
    after the name still an annotation."""
    fx = effects.load_effect(ELEMENT)
    assert fx.parameter("Tex").type.dim == "2D" and fx.parameter("Red").type.dim == "2D"
    assert fx.parameter("Tex").annotation("UIName").value == "Base"
    assert effects.load_effect(fx.to_source()).parameters == fx.parameters
    assert compile_shader(fx, "PS", "ps_2_0").samplers == {"Samp+Tex": 0, "Samp+Red": 1}
    half = np.full((2, 2, 4), 0.5, np.float32)          # Red's .x: 0.5 everywhere
    img = draw(fx, backend, {"Tex": make_texture(TEXELS, mips=False),
                             "Red": make_texture(half, mips=False)})
    for y, x in ((0, 0), (1, 6), (6, 1), (7, 7)):
        want = np.array([*texel_at(x, y)[:2], 0.25, 1.0]) * 0.5
        assert np.allclose(img[y, x], want, atol=1.5 / 255), (x, y, img[y, x], want)


def test_a_texture_with_an_element_type_keeps_a_resource_name_and_passes_into_functions():
    fx = effects.load_effect(f"""
Texture2D<float4> Tex < string ResourceName = "stone.png"; >;
SamplerState Samp = {POINT};
float4 Read(Texture2D<float4> t, SamplerState s, float2 uv) {{ return t.Sample(s, uv); }}
float4 PS(float2 uv : TEXCOORD0) : COLOR {{ return Read(Tex, Samp, uv); }}
technique T {{ pass P {{ PixelShader = compile ps_2_0 PS(); }} }}
""")
    assert fx.parameter("Tex").annotation("ResourceName").value == "stone.png"
    assert compile_shader(fx, "PS", "ps_2_0").samplers == {"Samp+Tex": 0}


@pytest.mark.parametrize("element, message", [
    ("float4x4", "X3521: 'Texture2D<float4x4>': the return type of a texture cannot exceed "
                 "four components ('float4x4' has 16)"),
    ("sampler", "X3124: 'Texture2D<sampler>': object element type cannot be an object type"),
    ("Light", "unknown type 'Light' in 'Texture2D<Light>'"),
])
def test_an_element_type_a_texture_cannot_return_is_refused_where_it_is_written(element,
                                                                                 message):
    with pytest.raises(ParseError) as err:
        effects.load_effect(f"float4 k;\nTexture2D<{element}> Tex;\n")
    assert str(err.value).startswith(f"<string>:2:1: error: {message}"), str(err.value)


def test_a_read_of_a_two_component_texture_is_no_float4():
    fx = effects.load_effect(ELEMENT.replace("float4(Tex.Sample(Samp, uv + 1.0 / 32), 0.25, 1)",
                                             "Tex.Sample(Samp, uv)"))
    with pytest.raises(EffectError) as err:
        compile_shader(fx, "PS", "ps_2_0")
    assert "X3017: cannot implicitly convert from 'float2' to 'float4'" in str(err.value)


def test_sample_level_bias_and_grad_are_texldl_texldb_texldd():
    fx = effects.load_effect(f"""
Texture2D Tex;
TextureCube Env;
SamplerState Samp = {POINT};
float Lod;
float4 PS(float2 uv : TEXCOORD0) : COLOR
{{
    return Tex.SampleLevel(Samp, uv, Lod) + Tex.SampleBias(Samp, uv, 0.5)
         + Tex.SampleGrad(Samp, uv, ddx(uv), ddy(uv)) + Env.Sample(Samp, float3(uv, 1));
}}
technique T {{ pass P {{ PixelShader = compile ps_3_0 PS(); }} }}
""")
    lines = asm(fx, "PS", "ps_3_0")
    text = "\n".join(lines)
    assert compile_shader(fx, "PS", "ps_3_0").samplers == {"Samp+Tex": 0, "Samp+Env": 1}
    assert "dcl_2d s0" in lines and "dcl_cube s1" in lines, text
    # the level and the bias ride in .w; the coordinate's unused .z is 0
    assert re.search(r"mov (r\d)\.w, c0\.x\n(texldl r\d, \1, s0)", text), text
    assert re.search(r"mov (r\d)\.zw, c2\ntexldb r\d, \1, s0", text), text
    assert "def c2, 0, 0, 0, 0.5" in lines, text
    assert re.search(r"dsx (r\d)\.xy, v0\ndsy (r\d)\.xy, v0\n(.*\n)*texldd r\d, v0, s0, \1, \2",
                     text), text
    assert any(line.startswith("texld ") and line.endswith(", s1") for line in lines), text


def test_sample_level_picks_the_mip_level(backend):
    """Level 1 of the 2 x 2 texture is its average, (0.5, 0.5, 0.5, 1), at every pixel."""
    fx = effects.load_effect(f"""
Texture2D Tex;
SamplerState Samp = {POINT};
float4 PS(float2 uv : TEXCOORD0) : COLOR {{ return Tex.SampleLevel(Samp, uv, 1); }}
technique T {{ pass P {{ PixelShader = compile ps_3_0 PS(); }} }}
""")
    img = draw(fx, backend, {"Tex": make_texture(TEXELS)})
    assert np.allclose(img[:, :, :3], 0.5, atol=2 / 255), img[0, 0]


def test_textures_and_samplers_pass_into_functions():
    fx = effects.load_effect(f"""
Texture2D Tex;
SamplerState Samp = {POINT};
float4 Read(Texture2D t, SamplerState s, float2 uv) {{ return t.Sample(s, uv); }}
float4 PS(float2 uv : TEXCOORD0) : COLOR {{ return Read(Tex, Samp, uv); }}
technique T {{ pass P {{ PixelShader = compile ps_2_0 PS(); }} }}
""")
    assert compile_shader(fx, "PS", "ps_2_0").samplers == {"Samp+Tex": 0}


def test_a_register_on_the_sampler_places_the_pair():
    fx = effects.load_effect("""
Texture2D Tex : register(t0);
SamplerState Samp : register(s3);
float4 PS(float2 uv : TEXCOORD0) : COLOR { return Tex.Sample(Samp, uv); }
float4 Both(float2 uv : TEXCOORD0) : COLOR { return Tex.Sample(Samp, uv) + tex2D(Samp, uv); }
technique T { pass P { PixelShader = compile ps_2_0 PS(); } }
""")
    assert compile_shader(fx, "PS", "ps_2_0").samplers == {"Samp+Tex": 3}
    with pytest.raises(EffectError) as err:
        compile_shader(fx, "Both", "ps_2_0")
    assert ("X4500: overlapping register semantics not yet implemented 's3': 'Samp' and "
            "'Samp+Tex' are both bound to s3" in str(err.value)) and ":3:" in str(err.value)
    assert err.value.language is True      # the file's binding: every target refuses it


@pytest.mark.parametrize("call, message", [
    ("Tex.Load(int3(0, 0, 0))", "'Tex.Load' needs shader model 4 (vs_4_0/ps_4_0): ps_3_0 has "
                                "no instruction for it"),
    ("Tex.Sample(Samp, uv, int2(1, 0))", "'Tex.Sample' with a texel offset needs shader model 4"),
    ("Tex.Gather(Samp, uv)", "'Tex.Gather' needs shader model 4"),
    ("Tex.Fetch(Samp, uv)", "X3018: invalid subscript 'Fetch'"),
    ("Samp.Sample(Samp, uv)", "X3018: invalid subscript 'Sample': only a texture object"),
    ("Tex.Sample(uv, uv)", "X3013: 'Sample': the first argument must be a sampler"),
    ("Texs[1].Sample(Samp, uv)", "'Sample' of an element of a texture array"),
])
def test_what_shader_model_3_cannot_do_is_refused_where_it_is_written(call, message):
    fx = effects.load_effect(f"""Texture2D Tex; Texture2D Texs[2];
SamplerState Samp;
float4 PS(float2 uv : TEXCOORD0) : COLOR
{{
    return {call};
}}
technique T {{ pass P {{ PixelShader = compile ps_3_0 PS(); }} }}
""")
    with pytest.raises(EffectError) as err:
        compile_shader(fx, "PS", "ps_3_0")
    text = str(err.value)
    assert text.startswith("<string>:5:") and message in text, text


def test_sample_level_on_ps_2_0_says_the_target_has_no_texldl():
    fx = effects.load_effect("""Texture2D Tex;
SamplerState Samp;
float4 PS(float2 uv : TEXCOORD0) : COLOR { return Tex.SampleLevel(Samp, uv, 0); }
technique T { pass P { PixelShader = compile ps_2_0 PS(); } }
""")
    with pytest.raises(EffectError) as err:
        compile_shader(fx, "PS", "ps_2_0")
    assert "ps_2_0 has no texldl" in str(err.value) and ":3:" in str(err.value)


def test_a_vertex_shader_reads_a_level_and_not_an_implicit_one():
    fx = effects.load_effect("""Texture2D Height;
SamplerState Samp;
float4 VS(float4 p : POSITION) : POSITION { return p + Height.SampleLevel(Samp, p.xy, 0).x; }
float4 Bad(float4 p : POSITION) : POSITION { return p + Height.Sample(Samp, p.xy); }
technique T { pass P { VertexShader = compile vs_3_0 VS(); } }
""")
    compiled = compile_shader(fx, "VS", "vs_3_0")
    assert compiled.samplers == {"Samp+Height": 0}
    assert any(line.strip().startswith("texldl ") and line.strip().endswith(", s0")
               for line in compiled.text.splitlines()), compiled.text
    with pytest.raises(EffectError) as err:
        compile_shader(fx, "Bad", "vs_3_0")
    assert str(err.value).startswith(
        "<string>:4:64: error: X4532: cannot map expression to vertex shader instruction set: "
        "'Height.Sample' needs a pixel shader's derivatives"), str(err.value)
    assert err.value.language is True       # every vertex target refuses it
