"""`register()` bindings of parameters as HLSL writes them (the DirectX docs' "register" page:
`: register([shader_profile,] Type#)`, several on one variable): one per stage, as XNA's stock
effects declare their constants (`float4 DiffuseColor : register(vs, c0) : register(ps, c1);`),
a target-specific one, and a register next to a semantic (`: WORLD : register(c4)`, whose
register was dropped before)."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.model import CompileShader
from effects.shaders.hlsl import compile_state

QUAD = {"mesh": "quad"}

BOUND = """
float4 DiffuseColor : register(vs, c0) : register(ps, c1) = {0.25, 0.5, 0.75, 1};
float4 Tint : register(ps, c2) : register(ps_2_b, c6) : register(c3) = {1, 1, 1, 1};
float4x4 World : WORLD : register(c4);
float4 VS(float4 p : POSITION, out float4 colour : COLOR0) : SV_Position
{ colour = DiffuseColor; return mul(p, World); }
float4 PS(float4 colour : COLOR0) : SV_Target0 { return colour * DiffuseColor * Tint; }
technique T { pass { VertexShader = compile vs_2_0 VS(); PixelShader = compile ps_2_0 PS(); } }
technique B { pass { VertexShader = compile vs_2_0 VS(); PixelShader = compile ps_2_b PS(); } }
"""


def _compiled(effect, technique: str):
    states = effect.technique(technique).passes[0].states
    return [compile_state(effect, s.value) for s in states if isinstance(s.value, CompileShader)]


def test_each_stage_reads_its_own_binding():
    effect = effects.load_effect(BOUND)
    vs, ps = _compiled(effect, "T")
    assert vs.constants["DiffuseColor"][0] == 0 and vs.constants["World"][0] == 4
    assert ps.constants["DiffuseColor"][0] == 1 and ps.constants["Tint"][0] == 2


def test_a_target_binding_wins_over_its_stage_and_the_unqualified_one():
    effect = effects.load_effect(BOUND)
    _, ps_2_b = _compiled(effect, "B")
    assert ps_2_b.constants["Tint"][0] == 6


def test_a_register_beside_a_semantic_keeps_both():
    world = effects.load_effect(BOUND).parameter("World")
    assert world.semantic == "WORLD"
    assert world.registers == (("", "c4"),)
    assert world.register_for("vs_2_0", "c") == "c4"
    assert world.register_for("vs_2_0", "s") is None


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_the_bound_registers_carry_the_values(backend):
    # colour = DiffuseColor (vs c0), times DiffuseColor (ps c1) times Tint (ps c2):
    # (0.25, 0.5, 0.75, 1)^2 = 0.0625, 0.25, 0.5625, 1 -> 16, 64, 143, 255
    image = effects.render(effects.load_effect(BOUND), "radeon9700", scene=QUAD, size=(8, 8),
                           backend=backend, technique="T")
    np.testing.assert_allclose(image[4, 4].astype(int), (16, 64, 143, 255), atol=1)


def test_registers_are_part_of_the_compile_cache_key():
    first = effects.load_effect(BOUND)
    moved = effects.load_effect(BOUND.replace("register(ps, c1)", "register(ps, c5)"))
    assert _compiled(first, "T")[1].constants["DiffuseColor"][0] == 1
    assert _compiled(moved, "T")[1].constants["DiffuseColor"][0] == 5


def test_bindings_survive_printing_and_loading_again():
    effect = effects.load_effect(BOUND)
    again = effects.load_effect(effect.to_source())
    for name in ("DiffuseColor", "Tint", "World"):
        assert again.parameter(name).registers == effect.parameter(name).registers
        assert again.parameter(name).semantic == effect.parameter(name).semantic


def test_a_register_binding_is_no_semantic_for_the_host():
    # XNA's stock effects bind every constant to a register and no semantic: the host sets
    # World / WorldViewProj / EyePosition by name, as XNA's BasicEffect class did
    from effects.host.semantics import binding_source
    effect = effects.load_effect(BOUND.replace("float4x4 World : WORLD : register(c4);",
                                               "float4x4 World : register(vs, c4);"))
    assert binding_source(effect.parameter("World")) == ("WORLD", "XNA name")
    assert binding_source(effect.parameter("DiffuseColor")) == ("", "")
