"""HLSL compiled for its target and rendered on both back ends, values worked out by hand.

Each case is a ps_2_0 (or vs_1_1 + ps_2_0) function on a full-screen quad whose texture
coordinate runs 0..1 left to right (u) and top to bottom (v); the expected colour of a pixel
is computed from the HLSL semantics in the test itself.
"""
from __future__ import annotations

from tests.paths import ROOT

import math

import numpy as np
import pytest

import effects
from effects.program.backend import create_backend
from effects.base.errors import EffectError

BACKENDS = ("numpy", "gl")
SIZE = (8, 8)
QUAD = {"mesh": "quad", "size": list(SIZE)}


@pytest.fixture(scope="module", params=BACKENDS)
def backend(request):
    """Each back end made for this module (not the process-wide shared one)."""
    made = create_backend(request.param)
    yield made
    made.close()


def effect_for(functions: str, ps: str = "compile ps_2_0 PS()", vs: str | None = None,
               params: str = "") -> effects.Effect:
    states = f"PixelShader = {ps};\n"
    if vs:
        states += f"VertexShader = {vs};\n"
    text = f"{params}\n{functions}\ntechnique T {{ pass P {{ {states} }} }}\n"
    return effects.load_effect(text)


def render(effect: effects.Effect, backend: str, params: dict | None = None,
           scene: dict | None = None) -> np.ndarray:
    return effects.render(effect, "radeon9700", technique="T", backend=backend,
                          scene=scene or QUAD, params=params).astype(np.float64) / 255.0


def pixel_uv(x: int, y: int) -> tuple[float, float]:
    """The interpolated texture coordinate at a pixel of the quad: Direct3D 9 samples at the
    pixel's integer position, half a pixel from the centre of the quad's texel grid."""
    return x / SIZE[0], y / SIZE[1]


def test_constant_arithmetic_folds_and_renders(backend):
    fx = effect_for("""
float4 PS() : COLOR
{
    float a = 0.25;
    float2 b = float2(a, a * 2);       // (0.25, 0.5)
    float3 c = float3(b.yx, 1) * 0.5;   // (0.25, 0.125, 0.5)
    return float4(c, 1.0);
}""")
    img = render(fx, backend)
    assert np.allclose(img[3, 3], (0.25, 0.125, 0.5, 1.0), atol=1.5 / 255)


def test_texcoord_input_swizzles_and_write_masks(backend):
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 o = 0;
    o.gr = uv;          // write mask in another order: o.g = u, o.r = v
    o.b = uv.x * uv.y;
    o.a = 1;
    return o;
}""")
    img = render(fx, backend)
    for x, y in ((1, 2), (6, 5)):
        u, v = pixel_uv(x, y)
        assert np.allclose(img[y, x], (v, u, u * v, 1.0), atol=1.5 / 255), (x, y)


def test_if_is_flattened_into_a_select(backend):
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 c;
    if (uv.x < 0.5)
        c = float4(1, 0, 0, 1);
    else
        c = float4(0, 0, 1, 1);
    return c;
}""")
    text = fx_asm(fx, "PS", "ps_2_0")
    assert "cmp" in text
    img = render(fx, backend)
    assert np.allclose(img[4, 1], (1, 0, 0, 1)) and np.allclose(img[4, 6], (0, 0, 1, 1))


def test_loops_unroll_and_user_functions_inline_with_out_parameters(backend):
    fx = effect_for("""
void accumulate(in float x, inout float sum, out float last) { sum += x; last = x; }
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float sum = 0, last = 0;
    [unroll] for (int i = 1; i <= 4; i++)
    {
        if (i == 3) continue;
        accumulate(uv.x * i, sum, last);   // u * (1 + 2 + 4)
    }
    return float4(sum / 8, last / 4, 0, 1);
}""")
    img = render(fx, backend)
    u, _ = pixel_uv(5, 2)
    assert np.allclose(img[2, 5], (u * 7 / 8, u, 0, 1), atol=1.5 / 255)


@pytest.mark.parametrize("layout", ["", "row_major"])
def test_matrix_majorness_and_mul(backend, layout):
    # mul(v, M) with M = [[1,2,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]] / 4: (x/4, (2x + y)/4, ...)
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float4 v = float4(uv, 0.5, 1);
    float4 r = mul(v, M);
    return float4(r.xy, M._m01, M[1][1]);
}""", params=f"{layout} float4x4 M = {{ 0.25, 0.5, 0, 0,  0, 0.25, 0, 0,  0, 0, 0.25, 0,  0, 0, 0, 0.25 }};")
    img = render(fx, backend)
    u, v = pixel_uv(2, 6)
    assert np.allclose(img[6, 2], (u / 4, (2 * u + v) / 4, 0.5, 0.25), atol=1.5 / 255)


def test_structs_and_intrinsics(backend):
    fx = effect_for("""
struct PS_IN { float2 uv : TEXCOORD0; float4 color : COLOR0; };
struct PS_OUT { float4 color : COLOR0; };
PS_OUT PS(PS_IN i)
{
    PS_OUT o;
    float s = smoothstep(0.0, 1.0, i.uv.x);
    o.color = float4(s, saturate(i.uv.y * 2 - 0.5), frac(i.uv.x * 3), lerp(0.2, 0.6, i.uv.y));
    return o;
}""")
    img = render(fx, backend)
    x, y = 5, 1
    u, v = pixel_uv(x, y)
    s = u * u * (3 - 2 * u)
    want = (s, min(max(v * 2 - 0.5, 0), 1), (u * 3) % 1.0, 0.2 + 0.4 * v)
    assert np.allclose(img[y, x], want, atol=1.5 / 255)


def test_wood_renders_for_ps_2_0(backend):
    fx = effects.load_effect(str(ROOT / "fxfiles" / "wood.fx"))
    params = {"ambient_color": "1,1,1", "diffuse_color": "1,1,1", "specular_color": "0.5,0.5,0.5",
              "L": "0.577,0.577,0.577", "I": "0,0,-1"}
    img = effects.render(fx, "radeon9700", backend=backend, params=params, size=(64, 64))
    centre = img[32, 32].astype(int)
    assert img[0, 0, :3].tolist() == [0, 0, 0]          # the clear colour around the sphere
    assert centre[0] > centre[1] > centre[2] > 0          # wood: red > green > blue


def fx_asm(effect: effects.Effect, entry: str, target: str) -> str:
    from effects.shaders.hlsl import compile_shader
    return compile_shader(effect, entry, target).text


def test_undeclared_identifier_is_located_in_the_fx_file():
    fx = effect_for("float4 PS() : COLOR\n{\n    return foo * 2;\n}")
    with pytest.raises(EffectError) as info:
        fx_asm(fx, "PS", "ps_2_0")
    assert info.value.message == "X3004: undeclared identifier 'foo'"
    assert (info.value.line, info.value.column) == (4, 12)


_POSITION_INPUT = """struct VSOut
{
    float4 position : POSITION0;
    float2 uv : TEXCOORD0;
};
float4 PS(VSOut input) : COLOR0
{
    return float4(%s, 0, 1);
}"""


def test_an_unread_position_input_is_accepted_as_fxc_does(backend):
    # XNA effects reuse the vertex-output struct, POSITION0 and all, as the pixel input
    fx = effect_for(_POSITION_INPUT % "input.uv")
    img = render(fx, backend)
    u, v = pixel_uv(3, 5)
    assert np.allclose(img[5, 3], (u, v, 0, 1), atol=1.5 / 255)


def test_a_read_position_input_is_x4502_at_the_entry_point():
    fx = effect_for(_POSITION_INPUT % "input.position.xy")
    with pytest.raises(EffectError) as info:
        fx_asm(fx, "PS", "ps_2_0")
    assert info.value.message == "X4502: invalid ps_2_0 input semantic 'POSITION0'"
    assert (info.value.line, info.value.column) == (7, 1)     # the entry's signature


def test_implicit_truncation_warns_x3206():
    fx = effect_for("float4 PS(float4 c : COLOR0) : COLOR\n{\n    float3 x = c;\n    return float4(x, 1);\n}")
    from effects.shaders.hlsl import compile_shader
    shader = compile_shader(fx, "PS", "ps_2_0")
    assert [str(w) for w in shader.warnings] == ["<string>:4:16: warning: X3206: implicit truncation of vector type"]


def test_over_the_slot_limit_is_a_located_reason():
    # each sin() is a range reduction (mad, frc, mad) and the 8-slot sincos macro: the 8th
    # line's sincos crosses ps_2_0's 64 arithmetic slots, and the reason stands at that line
    body = "\n".join(f"    x = sin(x) * 1.01 + {k}.0 / 64;" for k in range(12))
    fx = effect_for("float4 PS(float2 uv : TEXCOORD0) : COLOR\n{\n    float x = uv.x;\n"
                    + body + "\n    return x;\n}")
    v = fx.validate("T", effects.load_profile("radeon9700"))
    assert not v.ok
    first = v.reasons[0]
    assert first.message == ("ps_2_0 allows 64 arithmetic instruction slots; this sincos takes 8 "
                             "and brings the count to 71")
    assert (first.location.line, first.location.column) == (10, 9)   # the line of k = 5
    assert "the Radeon 9700 has NumInstructionSlots 96" in v.reasons[1].message


# One intrinsic family per row: an HLSL expression of u, v (the texture coordinate at pixel
# (5, 3): u = 5/8, v = 3/8) and the value Python computes for it (kept inside [0, 1]).
U, V = 5 / 8, 3 / 8
INTRINSIC_CASES = [
    ("pow(u, 2.5)", U ** 2.5),
    ("exp2(-u) + log2(1 + v) * 0.25", 2 ** -U + math.log2(1 + V) * 0.25),
    ("sqrt(u) * rsqrt(4 * v)", math.sqrt(U) / math.sqrt(4 * V)),
    ("clamp(u * 2 - 0.5, 0.2, 0.6) + min(u, v) - max(u, v) * 0.5", min(max(U * 2 - .5, .2), .6) + V - U / 2),
    ("step(0.5, u) * 0.5 + step(u, v) * 0.25", 0.5),
    ("abs(v - u) + sign(v - u) * 0.125 + 0.125", abs(V - U) - 0.125 + 0.125),
    ("floor(u * 4) / 8 + ceil(v * 4) / 8", math.floor(U * 4) / 8 + math.ceil(V * 4) / 8),
    ("fmod(u * 3, 0.75)", math.fmod(U * 3, 0.75)),
    ("length(float2(u, v)) * 0.5 + distance(u, v)", math.hypot(U, V) * 0.5 + abs(U - V)),
    ("dot(normalize(float3(u, v, 1)), float3(0, 0, 1))", 1 / math.sqrt(U * U + V * V + 1)),
    ("cross(float3(u, 0, 0), float3(0, v, 0)).z", U * V),
    ("reflect(float3(u, -v, 0), float3(0, 1, 0)).y", V),
    ("sin(u) * 0.5 + cos(v) * 0.25", math.sin(U) * 0.5 + math.cos(V) * 0.25),
    ("determinant(float2x2(u, v, 0.25, 1)) + transpose(float2x2(0, u, v, 0))[0][1]", U - V * 0.25 + V),
    ("lerp(u, v, 0.25) + smoothstep(0.0, 2.0, u)", U + (V - U) * 0.25 + (U / 2) ** 2 * (3 - U)),
    ("(u > v ? 0.75 : 0.25) * (any(float2(0, u)) ? 1 : 0) * (all(float2(0, u)) ? 0 : 1)", 0.75),
    ("round(u * 3) / 4 + trunc(v * 3) / 4", round(U * 3) / 4 + math.trunc(V * 3) / 4),
    ("frac(-u)", (-U) % 1.0),
]


@pytest.mark.parametrize("expression, expected", INTRINSIC_CASES, ids=[c[0] for c in INTRINSIC_CASES])
def test_intrinsic_families(backend, expression, expected):
    fx = effect_for(f"""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{{
    float u = uv.x, v = uv.y;
    return float4({expression}, 0, 0, 1);
}}""")
    img = render(fx, backend)
    assert 0 <= expected <= 1, expected
    assert img[3, 5, 0] == pytest.approx(expected, abs=2.5 / 255), (expression, fx_asm(fx, "PS", "ps_2_0"))


def test_texture_read_through_a_sampler(backend):
    from effects.assets.textures import procedural
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR { return tex2D(Checker, uv * 0.5 + 1.0 / 128) * Scale; }""",
                    params="texture T; float Scale = 0.5;\n"
                           "sampler2D Checker = sampler_state { Texture = <T>; MinFilter = Point; "
                           "MagFilter = Point; MipFilter = None; };")
    checker = procedural("checker")
    img = effects.render(fx, "radeon9700", technique="T", backend=backend, scene=QUAD,
                         params={"T": checker})
    text = fx_asm(fx, "PS", "ps_2_0")
    assert "texld" in text and "dcl_2d s0" in text
    texels = checker.levels[0]   # 64 x 64: pixel x reads texel 4x + 1/2 (a texel centre, no tie)
    for y in range(SIZE[1]):
        for x in range(SIZE[0]):
            want = texels[4 * y, 4 * x] * 0.5
            assert np.allclose(img[y, x] / 255.0, want, atol=1.5 / 255), (x, y, img[y, x], want)


def test_wood_scene_file_supplies_what_the_application_set(backend):
    """fxfiles/wood.yaml gives the same values as the test above, so `effects render
    fxfiles/wood.fx --scene fxfiles/wood.yaml` draws the wood rather than black."""
    from effects.host.scene import load_scene
    fx = effects.load_effect(str(ROOT / "fxfiles" / "wood.fx"))
    scene = load_scene(str(ROOT / "fxfiles" / "wood.yaml"))
    img = effects.render(fx, "radeon9700", backend=backend, scene=scene, size=(64, 64))
    centre = img[32, 32].astype(int)
    assert img[0, 0, :3].tolist() == [0, 0, 0]
    assert centre[0] > centre[1] > centre[2] > 0


def _wood_by_hand(ring) -> tuple[np.ndarray, np.ndarray]:
    """wood.fx at turbulence 0 on the default sphere (128 x 128), 0..255, by hand: the ring
    position r = frac(10 sqrt(y^2 + z^2)) of the object-space point, `ring(r)` the technique's
    grain, then the printed shading with wood.yaml's colours (L, eye -I = +z)."""
    from tests.looks import test_effect_pictures as pictures
    point, n = pictures.POINT, pictures.NORMAL
    g = ring(np.mod(10 * np.sqrt(point[..., 1] ** 2 + point[..., 2] ** 2), 1.0))[..., None]
    light = np.array([0.577, 0.577, 0.577])
    lightwood, darkwood = np.array([0.3, 0.12, 0.03]), np.array([0.05, 0.01, 0.005])
    wood = lightwood + g * (darkwood - lightwood)
    h = pictures.unit(light + np.array([0.0, 0.0, 1.0]))
    spec = 0.5 * np.maximum(n @ h, 0.0)[..., None] ** 10 * 0.6 * (0.3 * g + 0.7)
    colour = (0.2 + 0.4 * (n @ light)[..., None]) * wood + spec
    return np.clip(colour, 0, 1) * 255, pictures.DISC


def _printed_grain(r):
    s2, s3 = r * r, r * r * r
    v1, t1, v2, t2 = 2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + r, -2 * s3 + 3 * s2, s3 - s2
    step = lambda a, b: v1 * a + t1 + v2 * b + t2          # noqa: E731  (the printed helper)
    return step(0.0, 0.8) - step(0.83, 1.0)


def _renderman_grain(r):
    def step(a, b):
        t = np.clip((r - a) / (b - a), 0, 1)
        return t * t * (3 - 2 * t)
    return step(0.0, 0.8) - step(0.83, 1.0)


@pytest.mark.parametrize("technique, ring", [("Wood_ps20", _printed_grain),
                                             ("WoodRings_ps20", _renderman_grain)])
def test_wood_grain_at_turbulence_zero_is_the_formula(backend, technique, ring):
    # The printed smoothstep keeps the grain r in [-0.83, -0.2] (lerp extrapolates past
    # lightwood: a faint sawtooth); RenderMan's gives [0, 1], dark rings with thin light bands.
    # Measured against the formula over the disc: median 0, a few ring-edge pixels off
    from effects.host.scene import load_scene
    fx = effects.load_effect(str(ROOT / "fxfiles" / "wood.fx"))
    scene = load_scene(str(ROOT / "fxfiles" / "wood.yaml"))
    img = effects.render(fx, "radeon9700", technique=technique, backend=backend, scene=scene,
                         size=(128, 128), params={"turbulence": 0.0}).astype(float)
    want, inner = _wood_by_hand(ring)
    err = np.abs(img[..., :3] - want)[inner]
    assert np.median(err) <= 1.0 and np.percentile(err, 90) <= 3.0, (np.median(err), err.max())
    red = img[..., 0][inner]
    if technique == "Wood_ps20":
        assert (_printed_grain(np.linspace(0, 1, 1001)) <= -0.19).all()
    else:
        assert red.max() > 2.5 * np.percentile(red, 10)      # light bands against dark wood
