"""Values the fx_2_0 writer (effects.shaders.fxo) must keep through a compile -> load round
trip: colour states given as four numbers, and the NULL elements of a shader array."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.d3d9.states import lookup_state
from effects.frontend.fxo import read_effect_binary, typed_state_value
from effects.model import NullValue, Preshader
from effects.shaders.fxo import write_effect_binary
from effects.shaders.hlsl.preshader import expression_value

# every colour state of D3DX's table, and how one is written in a pass (or a sampler)
COLOR_STATES = {"FogColor": "FogColor", "TextureFactor": "TextureFactor",
                "Ambient": "Ambient", "BlendFactor": "BlendFactor",
                "Constant": "Constant[1]", "BorderColor": None}


def _round_trip(text):
    source = effects.load_effect(text)
    return source, read_effect_binary(write_effect_binary(source), "rt.fxo")


def _state(effect, name):
    if name == "BorderColor":
        return effect.parameter("S").value.states[0]
    return next(s for s in effect.techniques[0].passes[0].states if s.name == name)


def _effect(name, value):
    if COLOR_STATES[name] is None:
        return (f"float4 c = {{0.2, 0.4, 0.6, 0.8}}; float k = 0.5;\n"
                f"sampler S = sampler_state {{ {name} = {value}; }};\n"
                "technique T { pass P { FogEnable = FALSE; } }")
    return ("float4 c = {0.2, 0.4, 0.6, 0.8}; float k = 0.5;\n"
            f"technique T {{ pass P {{ {COLOR_STATES[name]} = {value}; }} }}")


def test_the_table_of_colour_states_is_complete():
    from effects.d3d9.states import STATES
    assert {s.name for s in STATES if s.type == "color"} == set(COLOR_STATES)


@pytest.mark.parametrize("name", sorted(COLOR_STATES))
def test_a_four_number_colour_state_keeps_every_channel(name):
    # {1, 0.5, 0, 0.2}: A = 0.2 * 255 + 0.5 -> 51 (0x33), R 0xff, G 0.5 * 255 + 0.5 -> 128
    # (0x80), B 0: the D3DCOLOR 0x33ff8000, one DWORD, as fxc types the state
    source, binary = _round_trip(_effect(name, "{1, 0.5, 0, 0.2}"))
    assert _state(source, name).value == _state(binary, name).value == 0x33FF8000


@pytest.mark.parametrize("name", sorted(COLOR_STATES))
def test_a_colour_expression_keeps_its_four_components(name):
    # c * k, written as a preshader: (0.1, 0.2, 0.3, 0.4) by hand, all four after the trip
    # (typed as one DWORD, as fxc typed the state, only 0.1 came back)
    source, binary = _round_trip(_effect(name, "c * k"))
    state = _state(binary, name)
    assert isinstance(state.value, Preshader) and state.value.components == 4
    for effect in (source, binary):
        got = expression_value(name, None, _state(effect, name).value, effect)
        assert np.allclose(got, [0.1, 0.2, 0.3, 0.4])


def test_a_colour_expression_of_three_components_keeps_three():
    source, binary = _round_trip(_effect("FogColor", "c.rgb * 2"))
    got = expression_value("FogColor", None, _state(binary, "FogColor").value, binary)
    assert np.allclose(got, [0.4, 0.8, 1.2])


def test_a_vector_typed_colour_value_reads_as_its_floats():
    # a colour state a binary types as a float4 (vkd3d's fx_2 table gives fxc's Ambient so)
    got = typed_state_value(lookup_state("Ambient"), np.array([0.5, 0.25, 1, 1], np.float32),
                            None, None)
    assert got.tolist() == [0.5, 0.25, 1.0, 1.0]


ARRAYS = """
VertexShader vs_arr[2];
PixelShader ps_arr[3] = { asm { ps_2_0 def c0, 1, 0, 0, 1 mov oC0, c0 }, NULL,
                          asm { ps_2_0 def c0, 0, 1, 0, 1 mov oC0, c0 } };
int i = 1;
technique T { pass P { PixelShader = (ps_arr[i]); } }
"""


def test_the_null_elements_of_a_shader_array_survive_the_round_trip():
    _, binary = _round_trip(ARRAYS)
    assert [type(v).__name__ for v in binary.parameter("vs_arr").value] == ["NullValue"] * 2
    assert [type(v).__name__ for v in binary.parameter("ps_arr").value] == [
        "BytecodeShader", "NullValue", "BytecodeShader"]
    # the pass picks the NULL element at i = 1, as the source does
    from effects.shaders.hlsl.preshader import expression_element
    state = binary.techniques[0].passes[0].state("PixelShader")
    assert expression_element(binary, state.value).index == 1


def test_a_null_shader_element_is_written_as_fxc_wrote_it():
    # Wine's null_shader blob (fxc): `vertexshader vs_arr[2];` gives objects 1 and 2 an empty
    # string entry each: 2 strings, 1 resource, then (1, length 0), (2, length 0)
    import struct
    from tests.paths import TESTS
    entries = struct.pack("<6I", 2, 1, 1, 0, 2, 0)
    fxc = (TESTS / "data" / "fxo" / "wine" / "test_effect_null_shader_blob.fxo").read_bytes()
    assert entries in fxc
    assert entries in write_effect_binary(effects.load_effect(
        TESTS / "data" / "fxo" / "wine" / "test_effect_null_shader_blob.fx"))
