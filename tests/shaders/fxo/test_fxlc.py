"""fxc's preshaders (FXLC) in Wine's fx_2_0 blobs (tests/data/fxo/MANIFEST.md), read by
`effects.load_effect` and run on the host (effects.shaders.fxlc): every expected number below is
worked by hand from the parameter values the test sets or the .fx beside the blob declares.
Bad preshader bytes are a located `EffectError` at their byte offset."""
from __future__ import annotations

import math
import struct

import numpy as np
import pytest

import effects
from effects.model import Preshader
from effects.shaders import fxlc
from effects.shaders.hlsl.preshader import expression_element, expression_value
from tests.paths import TESTS

DATA = TESTS / "data" / "fxo" / "wine"
OPS = DATA / "test_effect_preshader_ops_blob.fxo"
EFFECT = DATA / "test_effect_preshader_effect_blob.fxo"


def _states(effect, name):
    """The preshader states of pass 0 of technique 0 named `name`, by index."""
    return {s.index: s for s in effect.techniques[0].passes[0].states
            if s.name == name and isinstance(s.value, Preshader)}


def _value(effect, state):
    return np.asarray(expression_value(state.name, state.index, state.value, effect), dtype=float)


def _set(effect, name, value):
    effect.parameter(name).value = np.asarray(value, dtype=np.float32)


def test_each_instruction_of_the_ops_blob_computes_what_d3dx_did():
    # the blob's source writes exp, log, asin, acos, atan, atan2, mul to LightDiffuse[0-6];
    # Wine hand-edited LightDiffuse[7] to div and LightAmbient[0] to cmp
    effect = effects.load_effect(OPS)
    _set(effect, "opvect1", [1, -0.5, 0.5, 0])
    _set(effect, "opvect2", [1, -1, 2, 4])
    _set(effect, "opvect3", [5, 6, 7, 8])
    diffuse, ambient = _states(effect, "LightDiffuse"), _states(effect, "LightAmbient")
    pi = math.pi
    expected = {
        0: [2, 2 ** -0.5, 2 ** 0.5, 1],                      # exp: 2^x
        1: [0, -1, -1, 0],                                    # log: log2|x|, 0 at 0
        2: [pi / 2, -pi / 6, pi / 6, 0],                      # asin
        3: [0, 2 * pi / 3, pi / 3, pi / 2],                   # acos
        4: [pi / 4, -math.atan(0.5), math.atan(0.5), 0],      # atan
        5: [pi / 4, math.atan(0.5) - pi, math.atan(0.25), 0],  # atan2(v1, v2)
        6: [1, 0.5, 1, 0],                                    # mul
        7: [0, 0, 0, 0],                                      # div: 0 in D3DX, whatever it reads
    }
    for index, want in expected.items():
        assert _value(effect, diffuse[index]) == pytest.approx(want, rel=1e-6, abs=1e-7), index
    # cmp: v1 >= 0 ? v2 : v3 (-0.5 is the one below 0)
    assert _value(effect, ambient[0]).tolist() == [1, 6, 2, 4]


def test_the_preshader_effect_blob_reads_structs_matrices_and_relative_addressing():
    # the .fx: g_iVect = {4, 3, 2, 1}, opvect1 = {0, -0, -2.2, FLT_MAX}, opvect2 = {1, 2, -3, 4},
    # g_Selector = {0, 10, 5001 ...}, vec3 = {1001, 1002, 1003}, ts2/ts3 structs
    effect = effects.load_effect(EFFECT)
    specular = _states(effect, "LightSpecular")
    f32 = float(np.float32(-2.2))
    # float4(dot(v1.zx, v2.xy), dot(v1.zzx, v2.xyz), dot(v1.zzzx, v2.xxyy), 0)
    assert _value(effect, specular[0]) == pytest.approx([f32, 3 * f32, 4 * f32, 0], rel=1e-6)
    # float4(v1[2], g_iVect[2 + 1], g_Selector[5].x + g_Selector[8].y,
    #        g_Selector[1].x + g_Selector[4].y): past g_Selector's 3 registers lie c5 (no
    # parameter: 0) and c8 (opvect1: y is -0), and c4 (0)
    assert _value(effect, specular[1]) == pytest.approx([f32, 1, 0, 10])
    # float4(dot(m4x4[5], m4x4[2]), ts3.ts[4].fv, vec3[2], float3(1, 2, 3)[1]): row 5 and
    # ts[4] lie past their tables (0, as D3DX read them)
    assert _value(effect, specular[2]).tolist() == [0, 0, 1003, 2]
    fog = {s.name: s for s in effect.techniques[0].passes[0].states
           if isinstance(s.value, Preshader)}
    assert _value(effect, fog["FogDensity"]) == 0          # ts2[0].fv
    assert _value(effect, fog["FogStart"]) == 4            # ts2[1].fv
    assert _value(effect, fog["PointScale_A"]) == 4        # ts3.ts[0].fv
    assert _value(effect, fog["PointScale_B"]) == 12       # ts3.ts[1].fv
    # the sampler states of `sampler1`: MinFilter = g_iVect.y, MagFilter = vect_sampler.x + .y
    sampler = effect.parameter("sampler1").value
    got = {s.name: _value(effect, s) for s in sampler.states if isinstance(s.value, Preshader)}
    assert got == {"MinFilter": 3, "MagFilter": 3}


def test_a_shader_array_selected_by_an_expression_follows_the_parameter():
    effect = effects.load_effect(EFFECT)
    p0 = {s.name: s.value for s in effect.techniques[0].passes[0].states}
    p1 = {s.name: s.value for s in effect.techniques[0].passes[1].states}
    # p0: vs_arr2[g_iVect.w - 1], ps_arr[g_iVect.w - 1]; p1: vs_arr[g_iVect.z]
    assert p1["VertexShader"].selects == "vs_arr"
    assert expression_element(effect, p0["VertexShader"]).index == 0
    assert expression_element(effect, p0["PixelShader"]).index == 0
    assert expression_element(effect, p1["VertexShader"]).index == 2
    _set(effect, "g_iVect", [4, 3, 1, 2])
    assert expression_element(effect, p1["VertexShader"]).index == 1
    assert expression_element(effect, p0["VertexShader"]).index == 1
    _set(effect, "g_iVect", [4, 3, 7, 2])        # one past the array: a located error
    with pytest.raises(effects.EffectError, match=r"picks vs_arr\[7\].*holds 3 shaders"):
        expression_element(effect, p1["VertexShader"])


def test_validation_judges_the_value_a_preshader_gives():
    # PointScale_A = v4 (skip_constants): a parameter without a value reads 0; validation
    # evaluates it like a source expression and says which parameters it read
    effect = effects.load_effect(DATA / "test_effect_skip_constants_blob.fxo")
    state = next(s for p in effect.techniques[0].passes for s in p.states
                 if isinstance(s.value, Preshader))
    assert _value(effect, state) == 0
    _set(effect, "v4", 2.5)
    assert _value(effect, state) == 2.5


@pytest.mark.parametrize("find,replace,shift,message", [
    # LightAmbient[0]'s cmp (opcode 0x300, 4 components) made opcode 0x7FF
    (0x30000004, 0x7FF00004, 0, "opcode 0x7FF with 3 inputs is no preshader instruction"),
    (0x30000004, 0x30000009, 0, "cmp: 9 components"),
    # its instruction count (1, after 'FXLC') made 9: more than the comment holds
    (0x434C5846, None, 4, "9 instructions cannot fit"),
], ids=["opcode", "components", "count"])
def test_bad_preshader_bytes_are_located(tmp_path, find, replace, shift, message):
    data = bytearray(OPS.read_bytes())
    at = data.find(struct.pack("<I", find)) + shift
    data[at:at + 4] = struct.pack("<I", 9 if replace is None else replace)
    path = tmp_path / "bad.fxo"
    path.write_bytes(bytes(data))
    with pytest.raises(effects.EffectError, match=message) as err:
        effects.load_effect(path)
    assert (err.value.line, err.value.column) == (1, at + 1)
    assert f"(at byte {at})" in str(err.value)


def test_a_register_past_its_table_is_located(tmp_path):
    # cmp's third input, c2 (offset 8 components) of the 3 input registers, made c16
    data = bytearray(OPS.read_bytes())
    code = data.find(struct.pack("<I", 0x30000004))
    operand = code + 4 * (2 + 3 + 3 + 1 + 1)      # raw, count, two inputs, flag, table
    assert struct.unpack_from("<I", data, operand)[0] == 8
    data[operand:operand + 4] = struct.pack("<I", 64)
    path = tmp_path / "bad.fxo"
    path.write_bytes(bytes(data))
    with pytest.raises(effects.EffectError, match=r"cmp: input 3 reads c16, beyond the 3 "
                                                   r"registers") as err:
        effects.load_effect(path)
    assert err.value.column == code + 1


def test_the_listing_names_each_instruction_and_its_parameters():
    effect = effects.load_effect(OPS)
    state = _states(effect, "LightAmbient")[0]
    program = fxlc.decode(state.value, effect.path)
    assert fxlc.listing(program) == \
        "cmp oc0.xyzw, c0(opvect1).xyzw, c1(opvect2).xyzw, c2(opvect3).xyzw"


def test_a_shaders_constant_preshader_fills_the_registers_it_writes():
    # vs_arr2[0] = compile vs_3_0 RenderSceneVS(1, true): fxc took
    # `g_Selector[1].y > 0.5 ? -g_Pos1 * 2 - float4(-4, -5, -6, -7)
    #                        : -g_Pos2 * 3 - float4(-4, -5, -6, -7)` out of the shader into its
    # PRES preshader, which writes c33
    from effects.shaders.hlsl.registers import constant_values
    from effects.shaders.shader_value import shader_of
    effect = effects.load_effect(EFFECT)
    compiled = shader_of(effect, effect.parameter("vs_arr2").value[0]).compiled
    assert fxlc.written_registers(compiled.fxlc) == [33]
    _set(effect, "g_Pos1", [1, 2, 3, 4])
    # g_Selector[1].y = 10 > 0.5: -2 * (1, 2, 3, 4) + (4, 5, 6, 7)
    assert constant_values(effect, compiled)[33] == (2, 1, 0, -1)
    _set(effect, "g_Selector", [[0, 0, 0, 0], [10, 0, 10, 10], [0, 0, 0, 0]])
    _set(effect, "g_Pos2", [1, 1, 1, 1])
    # .y = 0: -3 * (1, 1, 1, 1) + (4, 5, 6, 7)
    assert constant_values(effect, compiled)[33] == (1, 2, 3, 4)
    # the parameters the shader reads itself keep their registers: arr2 (92, 93) at c29, c30
    assert constant_values(effect, compiled)[29][0] == 92


@pytest.mark.parametrize("stem", ["test_effect_preshader_ops_blob",
                                  "test_effect_skip_constants_blob",
                                  "test_effect_shared_parameters_blob",
                                  "test_effect_states_effect_blob", "test_effect_null_shader_blob"])
def test_a_binarys_preshaders_are_written_back_as_they_came(stem):
    # read, written (effects compile X.fxo -o Y.fxo), read again: the same states, each
    # preshader the same bytes (an array selector with its array), the same values
    import re
    from effects.frontend.fxo import read_effect_binary
    from effects.shaders.fxo import listing, write_effect_binary
    first = effects.load_effect(DATA / f"{stem}.fxo")
    again = read_effect_binary(write_effect_binary(first), str(DATA / f"{stem}.fxo"))

    def states(effect):
        return [(s.name, s.index, (s.value.data, s.value.components, s.value.selects)
                 if isinstance(s.value, Preshader) else repr(s.value).split("location")[0])
                for t in effect.techniques for p in t.passes for s in p.states]
    assert states(again) == states(first)
    assert any(isinstance(s.value, Preshader) for t in again.techniques for p in t.passes
               for s in p.states)

    def techniques(effect):      # the listing's techniques, byte offsets aside
        text = listing(effect)
        return re.sub(r"at byte \d+", "", text[text.index("\ntechnique"):])
    assert techniques(again) == techniques(first)


SOURCE = """
float a = 2;
float4 v = {1, 2, 3, 4};
float4x4 m = {1, 2, 3, 4,  5, 6, 7, 8,  9, 10, 11, 12,  13, 14, 15, 16};
int idx = 1;
pixelshader PS[2] = { asm { ps_2_0 def c0, 1, 0, 0, 1 mov oC0, c0 },
                      asm { ps_2_0 def c0, 0, 1, 0, 1 mov oC0, c0 } };
sampler S = sampler_state { MaxAnisotropy = a * 2; };
technique T { pass P {
    FogDensity = a * 3;
    FogStart = 1.0 / a + v.y;
    FogEnd = dot(v, v) - m[1].z;
    PointSize = pow(a, 3) + abs(-v.x) + saturate(v.w);
    PointScale_A = a > 1 ? 5 : 7;
    LightDiffuse[0] = lerp(v, v * 2, 0.25);
    PixelShader = (PS[idx]);
} }
"""


def test_source_expression_states_are_written_as_preshaders():
    # effects compile X.fx -o X.fxo: each expression state becomes the FXLC fxc would have
    # written; read back, it computes what the source computes, at any parameter values
    from effects.frontend.fxo import read_effect_binary
    from effects.shaders.fxo import write_effect_binary
    source = effects.load_effect(SOURCE)
    binary = read_effect_binary(write_effect_binary(source), "src.fxo")
    states = {s.name: s for s in binary.techniques[0].passes[0].states}
    assert all(isinstance(s.value, Preshader) for s in states.values())

    def values(effect):
        got = {s.name: expression_value(s.name, s.index, s.value, effect)
               for s in effect.techniques[0].passes[0].states if s.name != "PixelShader"}
        got["PixelShader"] = expression_element(
            effect, effect.techniques[0].passes[0].state("PixelShader").value).index
        got["MaxAnisotropy"] = expression_value(
            "MaxAnisotropy", None, effect.parameter("S").value.states[0].value, effect)
        return {k: np.asarray(v, dtype=float).tolist() for k, v in got.items()}
    # by hand at a = 2, v = (1, 2, 3, 4), m[1].z = 7 (row 1: 5, 6, 7, 8), idx = 1
    want = {"FogDensity": 6, "FogStart": 2.5, "FogEnd": 30 - 7, "PointSize": 8 + 1 + 1,
            "PointScale_A": 5, "LightDiffuse": [1.25, 2.5, 3.75, 5], "PixelShader": 1,
            "MaxAnisotropy": 4}
    assert values(binary) == values(source) == want
    for effect in (source, binary):
        _set(effect, "a", 0.5)
        _set(effect, "v", [-2, 0, 0, 0.5])
        effect.parameter("idx").value = np.int32(0)
    # a = 0.5, v = (-2, 0, 0, 0.5): 1.5; 2 + 0; 4.25 - 7; 0.125 + 2 + 0.5; 7 (a <= 1);
    # lerp(v, 2v, 0.25) = 1.25 v; PS[0]; 1
    want = {"FogDensity": 1.5, "FogStart": 2, "FogEnd": -2.75, "PointSize": 2.625,
            "PointScale_A": 7, "LightDiffuse": [-2.5, 0, 0, 0.625], "PixelShader": 0,
            "MaxAnisotropy": 1}
    assert values(binary) == values(source) == want


def test_an_expression_fxlc_cannot_say_is_refused_by_the_writer_located():
    from effects.shaders.fxo import write_effect_binary
    effect = effects.load_effect("float3 v = {1, 0, 0};\n"
                                 "technique T { pass P { FogDensity = length(cross(v, v)); } }")
    with pytest.raises(effects.EffectError, match="not written as an FXLC preshader") as err:
        write_effect_binary(effect)
    assert err.value.line == 2


def test_a_preshaders_infinities_pass_on_as_d3dx_set_them():
    # opvect1 = (0, -0, -2.2, FLT_MAX), opvect2 = (1, 2, -3, 4). D3DX set the lights to these
    # float32 bits (Wine's test_effect_preshader_op_expected): 1 / op, rsq, mul; 1e-2 / op
    # (a denormal kept); dot. No refusal: the pass validates
    effect = effects.load_effect(EFFECT)
    diffuse, ambient = _states(effect, "LightDiffuse"), _states(effect, "LightAmbient")

    def bits(state):
        return [f"{x:08x}" for x in np.asarray(_value(effect, state), np.float32).view(np.uint32)]
    assert bits(diffuse[0]) == ["7f800000", "ff800000", "bee8ba2e", "00200000"]
    assert bits(diffuse[2]) == ["00000000", "80000000", "40d33334", "7f800000"]
    assert bits(ambient[5]) == ["7f800000", "ff800000", "bb94f209", "000051ec"]
    assert bits(ambient[6]) == ["00000000", "7f800000", "41f00000", "00000000"]
    rsq = np.asarray(_value(effect, diffuse[1]), np.float32)
    assert rsq[:2].tolist() == [math.inf, math.inf]
    # the pass's only reason on a ps_3_0 card is p1's shader mix, not a value
    verdict = effect.validate("tech0", effects.load_profile("modern"))
    assert [r for r in verdict.reasons if "X3013" in str(r)] == []
    assert verdict.reasons and all("pass p1" in str(r) for r in verdict.reasons)


def test_the_same_expression_in_source_is_refused_naming_its_numbers():
    effect = effects.load_effect("float4 v = {0, -0, -2.2, 1};\n"
                                 "technique T { pass P { LightDiffuse[0] = 1 / v; } }")
    verdict = effect.validate("T", effects.load_profile("modern"))
    assert "X3013" in str(verdict.reasons[0]) and "inf" in str(verdict.reasons[0])
