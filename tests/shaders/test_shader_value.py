"""One route from a shader value to the program it runs (effects.shaders.shader_value), with the
register bindings validation records and lowering binds from."""
from __future__ import annotations

import pytest

import effects
from effects import EffectError
from effects.model import NullValue
from effects.shaders.shader_value import shader_of

SOURCE = """
sampler A; sampler B;
float4 PS(float2 uv : TEXCOORD0) : COLOR0 { return tex2D(A, uv) * tex2D(B, uv); }
technique T {
    pass Asm2 { PixelShader = asm { ps_2_0
        dcl t0
        dcl_2d s1
        dcl_2d s3
        texld r0, t0, s3
        texld r1, t0, s1
        mul r0, r0, r1
        mov oC0, r0 }; }
    pass Asm1 { PixelShader = asm { ps_1_1
        tex t0
        mov r0, t0 }; }
    pass Hlsl { PixelShader = compile ps_2_0 PS(); }
    pass Broken { PixelShader = asm { ps_2_0
        frobnicate oC0, r0 }; }
}
"""


@pytest.fixture(scope="module")
def effect():
    return effects.load_effect(SOURCE)


def _value(effect, name):
    return effect.techniques[0].passes[[p.name for p in effect.techniques[0].passes].index(name)] \
        .state("PixelShader").value


def test_an_asm_block_s_samplers_are_the_registers_it_samples_where_it_first_does(effect):
    shader = shader_of(effect, _value(effect, "Asm2"))
    assert shader.compiled is None and shader.kind == "ps"
    assert [(b.register, b.unit, b.parameter) for b in shader.samplers] == [(1, 1, None), (3, 3, None)]
    # `texld r0, t0, s3` is line 9 of SOURCE, `texld r1, t0, s1` line 10
    assert [b.read_at.line for b in shader.samplers] == [10, 9]


def test_ps_1_x_samples_stages_by_t_register(effect):
    [binding] = shader_of(effect, _value(effect, "Asm1")).samplers
    assert (binding.register, binding.unit, binding.read_at) == (0, 0, None)


def test_an_hlsl_target_names_the_parameter_in_each_register(effect):
    shader = shader_of(effect, _value(effect, "Hlsl"))
    assert shader.compiled is not None and shader.program is shader.compiled.program
    assert {b.parameter: b.unit for b in shader.samplers} == shader.compiled.samplers
    assert set(shader.compiled.samplers) == {"A", "B"}


def test_no_shader_is_none_and_a_broken_one_a_located_error(effect):
    assert shader_of(effect, NullValue()) is None
    with pytest.raises(EffectError) as info:
        shader_of(effect, _value(effect, "Broken"))
    assert str(info.value) == "<string>:18:9: error: unknown instruction 'frobnicate'"
