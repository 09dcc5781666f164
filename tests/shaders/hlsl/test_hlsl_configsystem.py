"""A ConfigSystem-style effect (tests/data/hlsl/configsystem.fx: one vertex and one pixel
function compiled for vs_2_0/ps_2_0 and vs_1_1/ps_1_1, fixed function last): each card class
gets the shader technique fxc's code fitted (issue 31). Before, the vs_1_1 code took 168 slots
and 15 temporaries, and every card fell to fixed function."""
from __future__ import annotations

from tests.paths import TESTS

import numpy as np
import pytest

import effects
from effects.d3d9.caps import load_profile
from effects.model import CompileShader
from effects.program.backend import create_backend
from effects.shaders.hlsl import compile_state

FX = TESTS / "data" / "hlsl" / "configsystem.fx"


@pytest.fixture(scope="module")
def effect():
    return effects.load_effect(str(FX))


@pytest.mark.parametrize("card, technique", [
    ("geforce3", "Config_dx8"), ("geforce4ti", "Config_dx8"), ("radeon8500", "Config_dx8"),
    ("radeon9700", "Config_dx9"), ("geforce2", "Config_ff")])
def test_each_card_class_selects_its_technique(effect, card, technique):
    assert effect.find_valid_technique(load_profile(card)).name == technique


def vertex_shader(effect, technique: str):
    state = next(s for p in effect.technique(technique).passes for s in p.states
                 if s.name == "VertexShader")
    assert isinstance(state.value, CompileShader)
    return compile_state(effect, state.value)


def test_the_vs_1_1_code_fits_vs_1_1(effect):
    stats = vertex_shader(effect, "Config_dx8").program.stats
    # the listing: 12 slots for P, N and E, 20 a light (the vector to it, its length and
    # attenuation, the half vector, one lit, the two sums), 14 for the outputs. Before: 168
    # slots (a log and an exp of 10 each per light for lit's pow) and 15 temporaries
    assert stats.total_slots <= 128 and stats.temps_used <= 12
    assert (stats.total_slots, stats.temps_used) == (86, 10)
    assert vertex_shader(effect, "Config_dx8").text.count("lit r") == 3


@pytest.fixture(scope="module", params=("numpy", "gl"))
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


def test_the_dx8_and_dx9_techniques_draw_the_same_vertex_lighting(effect, backend):
    dx9 = effects.render(effect, load_profile("radeon9700"), backend=backend, size=(48, 48))
    dx8 = effects.render(effect, load_profile("geforce3"), backend=backend, size=(48, 48))
    lit = dx9[..., :3].max(axis=2) > 40
    assert lit.sum() > 400                                   # the sphere is there, lit
    # the same LightVS, compiled for vs_2_0 and for vs_1_1; ps_1_1 computes at 8 bits
    assert np.abs(dx9.astype(int) - dx8).max() <= 3


LIT = """
float4x4 WorldViewProjection : WORLDVIEWPROJECTION;
float4 K = { 0.5, 0.8, 0.0, 2.0 };
float4 K2 = { 0.5, -0.3, 0.0, 2.0 };
struct O { float4 p : POSITION; float4 a : COLOR0; float4 b : COLOR1; };
O VS(float4 p : POSITION)
{
    O o;
    o.p = mul(p, WorldViewProjection);
    o.a = lit(K.x, K.y, K.w);
    o.b = lit(K2.x, K2.y, K2.w);
    return o;
}
float4 PS(float4 a : COLOR0, float4 b : COLOR1, uniform int which) : COLOR
{
    return which ? b : a;
}
technique A { pass P { VertexShader = compile vs_1_1 VS(); PixelShader = compile ps_1_1 PS(0); } }
technique B { pass P { VertexShader = compile vs_1_1 VS(); PixelShader = compile ps_1_1 PS(1); } }
"""


def test_lit_is_the_vertex_lit_instruction_and_computes_hlsl_lit(backend):
    fx = effects.load_effect(LIT)
    assert "lit r" in vertex_shader(fx, "A").text
    scene = {"mesh": "quad", "size": [8, 8]}
    a = effects.render(fx, "geforce3", technique="A", backend=backend, scene=scene)
    b = effects.render(fx, "geforce3", technique="B", backend=backend, scene=scene)
    # lit(0.5, 0.8, 2) = (1, 0.5, 0.8^2, 1); lit(0.5, -0.3, 2) = (1, 0.5, 0, 1)
    assert np.allclose(a[4, 4] / 255.0, (1, 0.5, 0.64, 1), atol=1.5 / 255)
    assert np.allclose(b[4, 4] / 255.0, (1, 0.5, 0.0, 1), atol=1.5 / 255)


DIFFUSE_ONLY = """
float4 K = { 0.5, 0.8, 0.0, 2.0 };
float4 VS(float4 p : POSITION, out float4 c : COLOR0) : POSITION
{
    float4 l = lit(dot(p.xyz, K.xyz), K.y, K.w);
    c = float4(l.%s, 0, 1);
    return p;
}
"""


@pytest.mark.parametrize("lanes, ops", [("yy", ["max"]), ("yz", ["lit"]), ("zz", ["lit"])])
def test_lit_costs_a_lit_only_where_its_specular_term_is_read(lanes, ops):
    fx = effects.load_effect(DIFFUSE_ONLY % lanes + "technique T { pass P { } }")
    from effects.shaders.hlsl import compile_shader
    text = compile_shader(fx, "VS", "vs_1_1").text
    used = [op for op in ("max", "lit") if f"\n{op} " in text]
    assert used == ops, text
