"""Wine's fx_2_0 blobs whose source our front end refuses (test_fxo_wine.SOURCE_REFUSED) or whose
reading took a decision of its own, checked against values read by hand from the .fx beside
each blob (tests/data/fxo/MANIFEST.md)."""
from __future__ import annotations

import numpy as np

import effects
from effects.model import NullValue, ParamRef, Preshader
from effects.shaders.hlsl.preshader import expression_value
from tests.paths import TESTS

DATA = TESTS / "data" / "fxo" / "wine"


def _pass_states(effect, technique=0, pass_=0):
    return [(s.name, s.index, s.value) for s in effect.techniques[technique].passes[pass_].states]


def test_states_effect_blob_holds_the_states_the_source_writes():
    effect = effects.load_effect(DATA / "test_effect_states_effect_blob.fxo")
    states = {(n, i): v for n, i, v in _pass_states(effect)}
    assert states[("VertexShader", None)] == ParamRef("vs_arr1", True, 1)
    assert states[("VertexShaderConstant1", 1)].tolist() == [3.0]
    assert states[("VertexShaderConstant4", 2)].tolist() == [1.0]
    assert states[("VertexShaderConstant1", 3)].tolist() == [2, 2, 2, 2]
    # nine numbers to a float4 register array: fxc's 9x1 value
    assert states[("VertexShaderConstant4", 4)].tolist() == [4, 4, 4, 4, 5, 5, 5, 5, 6]
    assert states[("BlendOp", None)].names == ("SUBTRACT",)        # 2
    assert states[("AlphaOp", 3)].names == ("MODULATE",)           # 4
    assert states[("WorldTransform", 1)].tolist() == [2] + [0] * 14 + [4]
    # ViewTransform = (camera): a preshader copying camera's registers, diag(4, 0, 0, 6)
    view = states[("ViewTransform", None)]
    assert isinstance(view, Preshader) and view.components == 16
    # (diagonal, as in Wine's test: whether D3DX transposed a non-symmetric one, its constant
    # table packing camera by columns into a state typed by rows, the blobs do not show)
    got = expression_value("ViewTransform", None, view, effect)
    assert got.tolist() == [4] + [0] * 14 + [6]
    effect.parameter("camera").value = np.diag([1, 2, 3, 5]).astype(np.float32)
    assert expression_value("ViewTransform", None, view, effect).tolist() == \
        [1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 5]
    assert states[("LightPosition", 2)].tolist() == [4, 5, 6]


def test_variable_names_blob_reads_struct_annotations():
    effect = effects.load_effect(DATA / "test_effect_variable_names_blob.fxo")
    # float i <s k[1] = {4};>; technique t <s l[1] = {5};> { pass p <s m[1] = {6};> { } }
    (k,) = effect.parameter("i").annotations
    assert (k.name, k.type.struct, k.value.text) == ("k", True, "{ { 4.0 } }")
    (l,) = effect.techniques[0].annotations
    assert (l.name, l.value.text) == ("l", "{ { 5.0 } }")
    (m,) = effect.techniques[0].passes[0].annotations
    assert (m.name, m.value.text) == ("m", "{ { 6.0 } }")
    assert effect.parameter("a").value == np.float32(2.1)
    assert [a.value.tolist() for a in effect.parameter("g").annotations] == [[3.0]]


def test_a_null_shader_written_as_a_number_is_null():
    effect = effects.load_effect(DATA / "test_effect_null_shader_blob.fxo")
    ((name, _, value),) = _pass_states(effect)
    assert name == "VertexShader" and isinstance(value, NullValue)
    # vertexshader vs_arr[2]; without initialiser: two NULL shaders
    assert [type(v) for v in effect.parameter("vs_arr").value] == [NullValue, NullValue]


def test_vs_3_sw_loads_and_no_hardware_card_validates_it():
    # D3DX loaded the effect; a vs_3_sw shader is created only on a software vertex
    # processing device, so ValidateTechnique failed for tech0 (vs_arr[1]) on hardware
    effect = effects.load_effect(DATA / "test_effect_unsupported_shader_blob.fxo")
    assert effect.parameter("vs_arr").value[1].version == "vs_3_sw"
    for card in effects.list_profiles():
        result = effect.validate("tech0", effects.load_profile(card))
        assert not result.ok
        assert any("vs_3_sw" in str(r) and "software vertex processing" in str(r)
                   for r in result.reasons), card
    # tech1 (vs_arr[i], i = 0) picks the vs_3_0 shader: no vs_3_sw reason
    result = effect.validate("tech1", effects.load_profile("modern"))
    assert not any("vs_3_sw" in str(r) for r in result.reasons)
