"""fxc's rule for a `for` over literal bounds without an attribute (issue 31): unrolled when
the unrolled code fits the target, a real loop (`loop aL, i#` reading c[aL + n]) when it does
not; [unroll] and [loop] decide where written. The loop draws what the unrolled code draws."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.d3d9.caps import load_profile
from effects.program.backend import create_backend
from effects.shaders.hlsl import compile_shader

# an XNA-style toon shader over 30 lights: 27 slots an iteration, 800-odd unrolled
TOON = """
float4 lightPositions[30];
float4 lightColors[30];
float3 eyePosition = { 0, 0, 3 };
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float3 worldPos = float3(uv * 2 - 1, 0);
    float3 N = float3(0, 0, 1);
    float3 E = normalize(eyePosition - worldPos);
    float3 total = 0;
    %s for (int i = 0; i < %d; ++i)
    {
        float3 L = lightPositions[i].xyz - worldPos;
        float atten = saturate(1 - dot(L, L) * lightPositions[i].w);
        L = normalize(L);
        float d = saturate(dot(N, L));
        d = d > 0.5 ? 1 : (d > 0.1 ? 0.5 : 0.1);
        float s = pow(saturate(dot(N, normalize(L + E))), 16) > 0.5 ? 1 : 0;
        total += lightColors[i].rgb * (d + s) * atten;
    }
    return float4(total, 1);
}
float4x4 WorldViewProjection : WORLDVIEWPROJECTION;
void VS(float4 p : POSITION, float2 uv : TEXCOORD0, out float4 o : POSITION,
        out float2 t : TEXCOORD0)
{
    o = mul(p, WorldViewProjection);
    t = uv;
}
technique T { pass P { VertexShader = compile vs_3_0 VS(); PixelShader = compile ps_3_0 PS(); } }
"""


def toon(count: int = 30, attribute: str = "") -> effects.Effect:
    return effects.load_effect(TOON % (attribute, count))


def test_a_loop_that_does_not_fit_unrolled_stays_a_loop():
    shader = compile_shader(toon(), "PS", "ps_3_0")
    # lightPositions c0-c29 and lightColors c30-c59, the largest first (constant_layout.py)
    assert "loop aL, i0" in shader.text and "c0[aL]" in shader.text and "c30[aL]" in shader.text
    assert shader.program.stats.total_slots < 64
    assert not shader.warnings


def test_a_loop_that_fits_unrolled_is_unrolled():
    shader = compile_shader(toon(4), "PS", "ps_3_0")
    assert "loop" not in shader.text and shader.program.stats.total_slots > 4 * 20


def test_unroll_written_keeps_the_unrolled_code_that_does_not_fit():
    shader = compile_shader(toon(30, "[unroll]"), "PS", "ps_3_0")
    assert "loop" not in shader.text and shader.program.stats.total_slots > 512


def test_the_loop_runs_on_a_512_slot_card_and_the_unrolled_code_does_not():
    assert toon().find_valid_technique(load_profile("geforce6800")).name == "T"
    assert toon(30, "[unroll]").find_valid_technique(load_profile("geforce6800")) is None


@pytest.fixture(scope="module", params=("numpy", "gl"))
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


def test_the_loop_draws_what_the_unrolled_code_draws(backend):
    rng = np.random.default_rng(31)
    positions = np.concatenate([rng.uniform(-2, 2, (30, 2)), rng.uniform(0.2, 2, (30, 1)),
                                rng.uniform(0.02, 0.2, (30, 1))], axis=1)
    colors = np.concatenate([rng.uniform(0, 0.08, (30, 3)), np.ones((30, 1))], axis=1)
    params = {"lightPositions": positions.astype(np.float32),
              "lightColors": colors.astype(np.float32)}
    scene = {"mesh": "quad", "size": [16, 16]}
    looped = effects.render(toon(), "refrast", technique="T", backend=backend, scene=scene,
                            params=params).astype(int)
    unrolled = effects.render(toon(30, "[unroll]"), "refrast", technique="T", backend=backend,
                              scene=scene, params=params).astype(int)
    assert np.abs(looped - unrolled).max() <= 1
    assert looped[..., :3].max() > 60                  # lights reach the quad
    # one pixel by the formula: u = x / 16, v = y / 16 (test_hlsl_render's pixel_uv)
    x, y = 5, 11
    p = np.array([x / 16 * 2 - 1, y / 16 * 2 - 1, 0.0])
    e = np.array([0, 0, 3.0]) - p
    e /= np.linalg.norm(e)
    total = np.zeros(3)
    for pos, col in zip(positions.astype(np.float32), colors.astype(np.float32)):
        v = pos[:3] - p
        atten = np.clip(1 - v.dot(v) * pos[3], 0, 1)
        v /= np.linalg.norm(v)
        d = np.clip(v[2], 0, 1)
        d = 1 if d > 0.5 else (0.5 if d > 0.1 else 0.1)
        h = v + e
        s = 1 if np.clip(h[2] / np.linalg.norm(h), 0, 1) ** 16 > 0.5 else 0
        total += col[:3] * (d + s) * atten
    want = np.rint(np.clip(total, 0, 1) * 255)
    assert np.abs(looped[y, x, :3] - want).max() <= 2, (looped[y, x], want)
