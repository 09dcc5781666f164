"""Effect-level expressions (D3DX's preshaders): state assignments and parameter initialisers
written as HLSL expressions, evaluated on the host from the parameters' current values when
the pass is lowered. Values are worked out by hand in each test; pictures on both back ends.
"""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.program.backend import create_backend
from effects.d3d9.caps import load_profile
from effects.d3d9.device import pass_states
from effects.base.errors import EffectError
from effects.lower.passes import lower_pass
from effects.lower.preshaders import evaluate_expressions

BACKENDS = ("numpy", "gl")
QUAD = {"mesh": "quad", "size": [8, 8]}


@pytest.fixture(scope="module", params=BACKENDS)
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


def render(fx: effects.Effect, backend, params: dict | None = None) -> np.ndarray:
    return effects.render(fx, "radeon9700", technique="T", backend=backend, scene=QUAD,
                          params=params).astype(int)


def evaluated_state(text: str):
    fx = effects.load_effect(text)
    (_, state), = pass_states(fx, fx.techniques[0].passes)
    return fx, evaluate_expressions(fx, state)


CONSTANT = """
float4 Light = {1.0, 0.5, 0.25, 1.0};
technique T { pass P {
  VertexShaderConstant[4] = <Light> * 0.5;
  VertexShader = asm { vs_1_1
    dcl_position v0
    mov oPos, v0
    mov oD0, c4 };
  PixelShader = asm { ps_1_1
    mov r0, v0 };
} }"""


def test_vertex_shader_constant_from_an_expression_is_read_by_an_asm_shader(backend):
    fx = effects.load_effect(CONSTANT)
    # c4 = Light * 0.5 = (0.5, 0.25, 0.125, 0.5): 127.5, 63.75, 31.875, 127.5 stored
    np.testing.assert_array_equal(render(fx, backend), np.broadcast_to([128, 64, 32, 128], (8, 8, 4)))
    # a new value of Light changes the constant on the next frame: (0.1, 0.2, 0.3, 0.4)
    image = render(fx, backend, {"Light": [0.2, 0.4, 0.6, 0.8]})
    np.testing.assert_allclose(image[4, 4], [25.5, 51, 76.5, 102], atol=0.5)


TRANSFORM = """
float4x4 A = {1,0,0,0, 0,1,0,0, 0,0,1,0, 0.5,0.25,0,1};
float4x4 B = {0.5,0,0,0, 0,0.5,0,0, 0,0,1,0, 0,0,0,1};
technique T { pass P {
  TextureTransformFlags[0] = Count2;
  TextureTransform[0] = mul(A, B);
  PixelShader = asm { ps_2_0
    def c0, 0, 0, 0, 1
    dcl t0.xy
    mov r0, c0
    mov r0.xy, t0
    mov oC0, r0 };
} }"""


def test_texture_transform_from_mul_of_two_parameters(backend):
    """mul(A, B) = A B: scale 0.5, translation (0.5, 0.25) * 0.5 = (0.25, 0.125). The quad's
    texcoord at pixel (x, y) is (x / 8, y / 8), so the colour is (u/2 + 1/4, v/2 + 1/8)."""
    fx = effects.load_effect(TRANSFORM)
    image = render(fx, backend)
    for x, y in ((0, 0), (4, 4), (7, 2)):
        u, v = x / 8, y / 8
        expected = np.rint(np.array([u / 2 + 0.25, v / 2 + 0.125, 0, 1]) * 255)
        np.testing.assert_allclose(image[y, x], expected, atol=1)
    # B becomes the identity: the colour is (u + 1/2, v + 1/4)
    image = render(fx, backend, {"B": np.eye(4)})
    np.testing.assert_allclose(image[4, 2], np.rint(np.array([0.75, 0.75, 0, 1]) * 255), atol=1)


FOG = """
float Distance = 0.5;
technique T {{ pass P {{ Lighting = FALSE; CullMode = None;
  FogEnable = TRUE; FogColor = 0x000000ff; FogTableMode = Exp; FogDensity = {density};
  TextureFactor = 0xffff0000;
  ColorOp[0] = SelectArg1; ColorArg1[0] = TFactor; AlphaOp[0] = SelectArg1; AlphaArg1[0] = TFactor;
}} }}"""


def test_fog_density_from_a_division_matches_its_value(backend):
    """FogDensity = 1.0 / Distance draws what the literal 1 / Distance draws, and follows
    a new Distance."""
    fx = effects.load_effect(FOG.format(density="1.0 / Distance"))
    fogged = render(fx, backend)
    assert (fogged[..., 2] > 0).all() and (fogged[..., 0] < 255).all()   # the fog is visible
    np.testing.assert_array_equal(fogged, render(effects.load_effect(FOG.format(density="2.0")), backend))
    thinner = render(fx, backend, {"Distance": 4.0})
    np.testing.assert_array_equal(thinner, render(effects.load_effect(FOG.format(density="0.25")), backend))
    assert thinner[4, 4, 0] > fogged[4, 4, 0]


def test_point_size_and_a_parameter_initialiser_read_as_numbers():
    """PointSize = Size * 2 reads 6 (points are not drawn by the back ends; the state is);
    FogDensity = <Density> with `float Density = 1.0 / Distance;` reads 0.25."""
    fx, state = evaluated_state("""
float Size = 3.0;
float Distance = 4.0;
float Density = 1.0 / Distance;
float4 Tint = float4(Size, 1, 2, 3) * 0.5;
technique T { pass P { PointSize = Size * 2; FogDensity = <Density>; FogStart = Size > 2 ? 10 : 20;
                       VertexShaderConstant[0] = <Tint>; } }""")
    assert state.get_float("PointSize") == 6.0
    assert state.get_float("FogDensity") == 0.25
    assert state.get_float("FogStart") == 10.0
    rows = list(state._constant_rows("VertexShaderConstant"))
    np.testing.assert_array_equal(rows[0][1], [1.5, 0.5, 1.0, 1.5])
    fx.parameter("Size").value = np.float64(1.0)
    (_, again), = pass_states(fx, fx.techniques[0].passes)
    again = evaluate_expressions(fx, again)
    assert again.get_float("PointSize") == 2.0 and again.get_float("FogStart") == 20.0


def lowering_error(states: str, params: str = "") -> EffectError:
    fx = effects.load_effect(f"{params}\ntechnique T {{ pass P {{ {states} }} }}")
    with pytest.raises(EffectError) as info:
        lower_pass(fx, fx.techniques[0], 0, load_profile("radeon9700"))
    return info.value


def test_an_undeclared_name_is_located():
    err = lowering_error("FogDensity = Missing * 2;")
    assert "X3004" in str(err) and "Missing" in str(err)
    assert (err.location.line, err.location.column) == (2, 37)   # Missing


def test_a_sampler_read_is_not_a_host_constant():
    err = lowering_error("FogDensity = tex2D(S, float2(0.5, 0.5)).x * 2;",
                         "texture Tex; sampler S = sampler_state { Texture = <Tex>; };")
    assert "X3013" in str(err) and err.location.line == 2


def test_an_ill_typed_expression_is_located():
    err = lowering_error("FogDensity = V.w;", "float3 V = {1, 2, 3};")
    assert err.location.line == 2 and err.location.column >= 37, err
    err = lowering_error("FogDensity = V * 1;", "float3 V = {1, 2, 3};")
    assert "X3017" in str(err) and "FogDensity takes 1 value(s)" in str(err)
    assert (err.location.line, err.location.column) == (2, 37)


def test_a_matrix_state_given_three_numbers_is_located():
    err = lowering_error("TextureTransform[0] = V * 2; TextureTransformFlags[0] = Count2;",
                         "float3 V = {1, 2, 3};")
    assert "takes 16 value(s)" in str(err) and "has 3" in str(err) and err.location.line == 2


def test_an_initialiser_that_refers_to_itself_is_located():
    err = lowering_error("FogDensity = <D>;", "float D = D * 2;")
    assert "X3013" in str(err) and err.location.line == 1


INITIALISER = """
float4 Light = {1.0, 0.5, 0.25, 1.0};
float4 Half = Light * 0.5;
float4 PS() : COLOR { return Half; }
technique T { pass P { PixelShader = compile ps_2_0 PS(); } }"""


def test_a_uniform_initialised_from_another_follows_it(backend):
    """`float4 Half = Light * 0.5;` read by a compiled ps_2_0: D3DX's preshader computed
    the register from Light's current value."""
    fx = effects.load_effect(INITIALISER)
    np.testing.assert_array_equal(render(fx, backend)[4, 4], [128, 64, 32, 128])
    np.testing.assert_array_equal(render(fx, backend, {"Light": [0.5] * 4})[4, 4], [64] * 4)


def test_sampler_state_expressions_of_a_compiled_shaders_sampler():
    fx = effects.load_effect("""
float Bias = 0.5;
texture Tex;
sampler S = sampler_state { Texture = <Tex>; MipMapLodBias = Bias * 2; MaxAnisotropy = Bias * 8; };
float4 PS(float2 uv : TEXCOORD0) : COLOR { return tex2D(S, uv); }
technique T { pass P { PixelShader = compile ps_2_0 PS(); } }""")
    profile = load_profile("radeon9700")
    binding, = lower_pass(fx, fx.techniques[0], 0, profile).textures
    assert (binding.mip_lod_bias, binding.max_anisotropy) == (1.0, 4)
    fx.parameter("Bias").value = np.array(0.25)
    binding, = lower_pass(fx, fx.techniques[0], 0, profile).textures   # the cache sees the set
    assert (binding.mip_lod_bias, binding.max_anisotropy) == (0.5, 2)


def test_set_value_on_one_runtime_changes_the_next_frame(backend):
    """ID3DXEffect::SetValue between frames of the same Runtime (the viewer's path): the pass
    lowered for the first frame is not reused once a parameter its expressions read moved."""
    from effects.host.runtime import Runtime
    runtime = Runtime(effects.load_effect(CONSTANT), "radeon9700", scene=QUAD, backend=backend)
    first = runtime.render("T").image.astype(int)
    np.testing.assert_array_equal(first[4, 4], [128, 64, 32, 128])
    runtime.set_value("Light", [1.0, 1.0, 1.0, 1.0])     # c4 = (0.5, 0.5, 0.5, 0.5)
    np.testing.assert_array_equal(runtime.render("T").image[4, 4], [128] * 4)
    runtime.set_value("Light", [1.0, 0.5, 0.25, 1.0])    # back: the first frame again
    np.testing.assert_array_equal(runtime.render("T").image, first)


COLOR_WRITE = """
int Mask = 3;
float4 PS() : COLOR { return float4(0.5, 0.5, 0.5, 0.5); }
technique T { pass P { ColorWriteEnable = Mask | Blue; PixelShader = compile ps_2_0 PS(); } }"""


def test_flags_ored_with_a_parameter_are_an_expression(backend):
    """ColorWriteEnable = Mask | Blue: RED 1, GREEN 2, BLUE 4, ALPHA 8 (D3DCOLORWRITEENABLE);
    Mask 3 writes red, green and blue (alpha keeps the clear's 0), Mask 8 blue and alpha."""
    fx = effects.load_effect(COLOR_WRITE)
    assert fx.techniques[0].passes[0].states[0].value.text == "Mask | 4"
    np.testing.assert_array_equal(render(fx, backend)[4, 4], [128, 128, 128, 0])
    np.testing.assert_array_equal(render(fx, backend, {"Mask": 8})[4, 4], [0, 0, 128, 128])


def test_a_flag_name_that_is_neither_flag_nor_parameter_is_still_refused():
    with pytest.raises(EffectError, match="'Bleu' is not one"):
        effects.load_effect("int Mask = 3;\ntechnique T { pass P { ColorWriteEnable = Mask | Bleu; } }")
