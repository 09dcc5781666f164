"""The fx_2_0 reader on hand-made binaries: what each table holds (types, defaults, states,
references), and every kind of damage a located FxoError at the byte it concerns."""
from __future__ import annotations

import struct

import numpy as np
import pytest

import effects
from effects import EffectError
from effects.frontend.fxo import FxoError, MAGIC, read_effect_binary
from effects.model import BytecodeShader, EnumValue, NullValue, ParamRef, SamplerState
from effects.shaders.fxo import FxoEncodeError, write_effect_binary

SOURCE = """
float4 Tint : DIFFUSE < string UIName = "tint"; float UIMax = 2; > = {0.5, 0.25, 1, 1};
int Count[3] = {1, 2, 3};
bool Flag = true;
texture Tex;
sampler2D Samp = sampler_state { Texture = <Tex>; MinFilter = Linear; AddressU = Clamp; };
technique T < int Order = 7; > {
    pass P0 {
        Lighting = false; SrcBlend = SrcAlpha; FogStart = 0.25; TextureFactor = 0xff336699;
        Sampler[0] = <Samp>; ColorOp[1] = Modulate; LightDirection[2] = {0, -1, 0};
        PixelShader = asm { ps_1_1 tex t0 mov r0, t0 };
        VertexShader = NULL;
    }
}
"""


def _binary():
    return write_effect_binary(effects.load_effect(SOURCE))


def test_the_tables_read_back_as_the_source_says():
    e = read_effect_binary(_binary(), "t.fxo")
    tint, count, flag, tex, samp = e.parameters
    assert tint.semantic == "DIFFUSE" and tint.type.cols == 4
    assert np.allclose(tint.value, [0.5, 0.25, 1, 1])
    assert [(a.name, a.value) for a in tint.annotations][0] == ("UIName", "tint")
    assert float(tint.annotations[1].value) == 2.0
    assert count.array == (3,) and count.value.tolist() == [1, 2, 3]
    assert flag.value.dtype == bool and bool(flag.value)
    assert tex.type.base == "texture" and tex.value is None
    assert isinstance(samp.value, SamplerState) and samp.type.dim == "2D"
    assert samp.value.get("Texture").value == ParamRef("Tex", True)
    assert samp.value.get("MinFilter").value == EnumValue(("LINEAR",), 2)
    technique = e.techniques[0]
    assert technique.name == "T" and int(technique.annotations[0].value) == 7
    p = technique.passes[0]
    assert p.state("Lighting").value is False
    assert p.state("SrcBlend").value.value == 5                      # D3DBLEND_SRCALPHA
    assert p.state("FogStart").value == 0.25
    assert p.state("TextureFactor").value == 0xff336699
    assert p.state("Sampler", 0).value == ParamRef("Samp", True)
    assert p.state("ColorOp", 1).value.value == 4                    # D3DTOP_MODULATE
    assert p.state("LightDirection", 2).value.tolist() == [0, -1, 0]
    shader = p.state("PixelShader").value
    assert isinstance(shader, BytecodeShader) and shader.version == "ps_1_1"
    assert isinstance(p.state("VertexShader").value, NullValue)


def _fail(data: bytes) -> FxoError:
    with pytest.raises(FxoError) as got:
        read_effect_binary(data, "bad.fxo")
    return got.value


def test_damage_is_located_at_its_byte():
    assert _fail(b"DXBC" + bytes(12)).location.column == 1
    assert "ends where the offset" in _fail(struct.pack("<I", MAGIC)).message
    err = _fail(struct.pack("<2I", MAGIC, 1000))
    assert err.location.column == 5 and "outside the 8-byte effect binary" in err.message
    data = bytearray(_binary())
    start = 8 + struct.unpack_from("<I", data, 4)[0]
    struct.pack_into("<I", data, start, 0x7FFFFFFF)                  # the parameter count
    err = _fail(bytes(data))
    assert err.location.column == start + 1 and "cannot fit" in err.message
    assert "runs past the end" in _fail(_binary()[:-30]).message     # a truncated shader


def test_a_state_number_outside_the_table_is_refused_where_it_is():
    data = bytearray(_binary())
    # the pass's first state: Lighting, D3DX state 48 with index 0
    first = data.find(struct.pack("<2I", 48, 0))
    struct.pack_into("<I", data, first, 300)
    err = _fail(bytes(data))
    assert err.location.column == first + 1 and "state number 300" in err.message


def test_struct_members_nesting_beyond_the_limit_are_refused():
    # a typedef whose struct holds a struct holding ... 40 deep
    names = struct.pack("<I", 0)
    depth = 40
    typedef = b"".join(struct.pack("<6I", 0, 5, 0, 0, 0, 1) for _ in range(depth))
    typedef += struct.pack("<7I", 3, 0, 0, 0, 0, 1, 1)
    blob = names + typedef + struct.pack("<I", 0)
    tables = struct.pack("<4I", 1, 0, 0, 1) + struct.pack("<4I", 4, len(blob) - 4, 0, 0)
    tables += struct.pack("<2I", 0, 0)
    err = _fail(struct.pack("<2I", MAGIC, len(blob)) + blob + tables)
    assert "nest more than 32" in err.message


def test_a_bad_shader_is_located_in_the_file():
    data = bytearray(_binary())
    at = data.find(bytes([0x01, 0x01, 0xFF, 0xFF]))                  # ps_1_1's version token
    struct.pack_into("<I", data, at, 0xFFFF0505)
    err = _fail(bytes(data))
    assert err.location.column == at + 1 and "0xFFFF0505" in err.message
    # a sound version and a broken instruction: the effect loads, the shader's program
    # fails where the instruction is, counted in the file
    data = bytearray(_binary())
    struct.pack_into("<I", data, at + 4, 0x7FFF0042)                 # tex with a bad length
    e = read_effect_binary(bytes(data), "bad.fxo")
    from effects.shaders.shader_value import shader_of
    with pytest.raises(EffectError) as got:
        shader_of(e, e.techniques[0].passes[0].state("PixelShader").value)
    assert got.value.location.path == "bad.fxo" and got.value.location.column > at + 4


def test_what_the_writer_cannot_write_is_a_located_error():
    e = effects.load_effect("float a = 1; float b = a * 2;\n"
                            "technique T { pass P { FogStart = a * 2; } }")
    with pytest.raises(FxoEncodeError) as got:
        write_effect_binary(e)
    assert got.value.location.line == 1 and "FXLC" in got.value.message


def test_a_shader_with_a_bad_fxc_preshader_is_refused_not_drawn_wrong():
    # a ps_2_0 whose PRES comment (fxc's preshader: FXLC code filling c#, run on the host:
    # test_fxlc.py) holds no preshader: without it the shader would read zeros, so it is
    # refused, located where the preshader's version token belongs
    data = bytearray(write_effect_binary(effects.load_effect(
        "technique T { pass P { PixelShader = asm { ps_2_0 mov oC0, c0 }; } }")))
    at = data.find(bytes([0x00, 0x02, 0xFF, 0xFF]))
    # ps_2_0's version token, then our CTAB comment: make its four-character code PRES
    ctab = data.find(b"CTAB", at)
    data[ctab:ctab + 4] = b"PRES"
    e = read_effect_binary(bytes(data), "pres.fxo")
    from effects.shaders.shader_value import shader_of
    with pytest.raises(EffectError) as got:
        shader_of(e, e.techniques[0].passes[0].state("PixelShader").value)
    assert "preshader: version token 0x0000001C" in got.value.message
    assert got.value.location.column == ctab + 4 + 1
    from effects.d3d9.caps import load_profile
    from effects.validate.technique import validate_technique
    assert not validate_technique(e, e.techniques[0], load_profile("modern")).ok


def test_load_effect_takes_a_binary_as_bytes():
    # the contract (DESIGN: `load_effect` takes a compiled .fxo path or bytes)
    from tests.paths import TESTS
    raw = (TESTS / "data/fxo/wine/test_effect_states_effect_blob.fxo").read_bytes()
    effect = effects.load_effect(raw)
    assert [t.name for t in effect.techniques] == ["tech0"] and effect.path == "<bytes>"
    with pytest.raises(effects.EffectError, match="do not start with the fx_2_0 tag") as err:
        effects.load_effect(b"technique T { pass P { } }")
    assert (err.value.path, err.value.line, err.value.column) == ("<bytes>", 1, 1)
