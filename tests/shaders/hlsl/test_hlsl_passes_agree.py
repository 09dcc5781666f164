"""The back half's rewrites change the code, not what it computes: shaders with real loops,
branches, relative addressing, swizzles and clamps drawn with every rewrite (peephole.py,
fusion.py's lrp, a temporary reused as the destination of its last reader) and without any,
on both back ends, give the same picture."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.program.backend import create_backend
from effects.shaders.hlsl import allocate, codegen, compile_shader

SHADERS = {
    "ps_3_0 loop and branch": ("""
int Count = 3;
float4 Colors[4] = { {0.2, 0.1, 0.05, 1}, {0.1, 0.3, 0.1, 1}, {0.05, 0.1, 0.4, 1}, {1, 1, 1, 1} };
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float3 acc = 0;
    for (int i = 0; i < Count; i++)
    {
        float w = saturate(uv.x * (i + 1) - uv.y);
        acc = acc * (1 - w) + Colors[i].rgb * w;
        [branch] if (acc.r > 0.15)
            acc.g = clamp(acc.g * 2, 0, 1);
    }
    return float4(pow(acc + 0.1, 2.2), 1);
}""", "vs_3_0", "ps_3_0"),
    "ps_2_0 swizzles and clamps": ("""
float4 K = { 0.3, 0.6, 0.9, 0.5 };
float4 PS(float2 uv : TEXCOORD0, float4 c : COLOR0) : COLOR
{
    float4 a = float4(uv, uv.yx) * K.wzyx;
    float3 b = lerp(a.xyz, K.zyx, uv.y);
    float d = dot(b, a.wzy);
    return float4(clamp(b.zxy * d, 0, 1), saturate(pow(a.w, 4) + d * 0.1));
}""", "vs_2_0", "ps_2_0"),
}

VERTEX = {
    "vs_3_0": """
float4x4 WorldViewProjection : WORLDVIEWPROJECTION;
float4 Bones[3] = { {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0} };
void VS(float4 p : POSITION, float2 uv : TEXCOORD0, out float4 o : POSITION,
        out float2 t : TEXCOORD0)
{
    int k = (int)(uv.x * 2.99);
    float4 q = p + Bones[k] * 0.0;
    o = mul(q, WorldViewProjection);
    t = uv;
}""",
    "vs_2_0": """
float4x4 WorldViewProjection : WORLDVIEWPROJECTION;
struct O { float4 p : POSITION; float2 t : TEXCOORD0; float4 c : COLOR0; };
O VS(float4 p : POSITION, float2 uv : TEXCOORD0)
{
    O o;
    o.p = mul(p, WorldViewProjection);
    o.t = uv;
    float4 l = lit(uv.x - 0.2, uv.y, 8);
    o.c = saturate(float4(l.yzw, 1) * 0.5 + float4(pow(uv.xyx, 3), 0));
    return o;
}""",
}


def effect(name: str) -> effects.Effect:
    body, vs, ps = SHADERS[name]
    return effects.load_effect(VERTEX[vs] + body + f"""
technique T {{ pass P {{ VertexShader = compile {vs} VS(); PixelShader = compile {ps} PS(); }} }}
""")


@pytest.fixture(scope="module", params=("numpy", "gl"))
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


def slots(name: str) -> int:
    vs, ps = SHADERS[name][1:]
    fx = effect(name)
    return sum(compile_shader(fx, entry, target).program.stats.total_slots
               for entry, target in (("VS", vs), ("PS", ps)))


def draw(name: str, backend) -> np.ndarray:
    effects.clear_caches()
    return effects.render(effect(name), "refrast", technique="T", backend=backend,
                          scene={"mesh": "quad", "size": [16, 16]}).astype(int)


@pytest.mark.parametrize("name", list(SHADERS))
def test_rewritten_and_plain_code_draw_the_same(name, backend, monkeypatch):
    tight, tight_slots = draw(name, backend), slots(name)
    assert tight[..., :3].max() > 40
    monkeypatch.setattr(codegen, "optimise", lambda cg: {})
    monkeypatch.setattr(codegen, "fuse_lrp", lambda nodes, uses: 0)
    monkeypatch.setattr(allocate, "dies_into_destination", lambda ins, vr: False)
    plain, plain_slots = draw(name, backend), slots(name)
    effects.clear_caches()
    assert plain_slots > tight_slots                # the rewrites did something here
    assert np.abs(tight - plain).max() <= 1
