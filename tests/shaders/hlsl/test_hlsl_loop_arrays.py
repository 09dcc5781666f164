"""A loop counted by a uniform int whose body writes a local array or struct is a real loop
(issue 31: X3511 before; fxc emitted `rep i0` / `loop aL, i0`): the array's numbers are carried
round the loop in registers like any variable's."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.program.backend import create_backend
from effects.shaders.hlsl import compile_shader

LOOP = """
int numLights = 2;
float4 lightDir[4] = { {0, 0, 1, 0}, {0.6, 0, 0.8, 0}, {0, 0, 0, 0}, {0, 0, 0, 0} };
struct Sum { float diffuse; float2 pair[2]; };
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float3 n = normalize(float3(uv - 0.5, 1));
    float2 acc[2] = { {0, 0}, {0, 0} };
    Sum s = (Sum)0;
    for (int i = 0; i < numLights; i++)
    {
        float d = saturate(dot(n, lightDir[i].xyz));
        acc[0].x += d * 0.5;
        acc[1].y += d * d * 0.5;
        s.pair[1].x = s.pair[1].x + 0.25;
    }
    return float4(acc[0].x, acc[1].y, s.pair[1].x, 1);
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


def test_a_uniform_loop_writing_an_array_and_a_struct_is_a_real_loop():
    shader = compile_shader(effects.load_effect(LOOP), "PS", "ps_3_0")
    assert "loop aL, i0" in shader.text and "endloop" in shader.text
    assert shader.int_registers == {"numLights": 0}


@pytest.fixture(scope="module", params=("numpy", "gl"))
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


@pytest.mark.parametrize("count", [0, 1, 2])
def test_the_loop_sums_what_the_formula_says(backend, count):
    img = effects.render(effects.load_effect(LOOP), "refrast", technique="T", backend=backend,
                         scene={"mesh": "quad", "size": [16, 16]},
                         params={"numLights": count}).astype(np.float64) / 255
    x, y = 4, 11                          # u = x / 16, v = y / 16 (test_hlsl_render)
    n = np.array([x / 16 - 0.5, y / 16 - 0.5, 1.0])
    n /= np.linalg.norm(n)
    dirs = np.array([[0, 0, 1.0], [0.6, 0, 0.8]])[:count]
    d = np.clip(dirs @ n, 0, 1)
    want = (0.5 * d.sum(), 0.5 * (d * d).sum(), 0.25 * count, 1)
    assert np.allclose(img[y, x], want, atol=1.5 / 255), (img[y, x], want)
