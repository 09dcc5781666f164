"""Bad shader bytecode is a located EffectError (line 1, the byte offset + 1 as the column),
never a Python exception: truncated streams, wrong instruction lengths, unknown opcodes,
registers the version lacks, broken constant tables, oversize files; and a hostile mutation
fuzz of the round-trip files."""
from __future__ import annotations

import struct

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from effects.base import limits
from effects.base.errors import EffectError
from effects.shaders.asm import check
from effects.shaders.asm.text import program_text
from effects.shaders.d3dbc import (BytecodeError, disassemble, read_shader, write_binary,
                                   write_shader)
from effects.shaders.d3dbc.ctab import ConstantInfo, ConstantTable, TypeInfo, write_ctab
from effects.shaders.d3dbc.writer import comment
from effects.shaders.asm import assemble
from tests.shaders.d3dbc.programs import FEATURES, block, effect_shaders

PS = assemble(block("ps_2_0\ndef c0, 1, 0, 0, 1\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0\n"
                    "mul r0, r0, c0\nmov oC0, r0\n"))
GOOD = write_shader(PS)


def words(data: bytes) -> list[int]:
    return list(struct.unpack(f"<{len(data) // 4}I", data))


def pack(ws: list[int]) -> bytes:
    return struct.pack(f"<{len(ws)}I", *ws)


def error(data: bytes) -> BytecodeError:
    with pytest.raises(EffectError) as info:
        read_shader(data, "bad.pso")
    err = info.value
    assert err.location.path == "bad.pso" and err.location.line == 1
    assert str(err).startswith(f"bad.pso:1:{err.location.column}: error: ")
    return err


def offset_of(data: bytes, token: int) -> int:
    return words(data).index(token) * 4


def test_the_good_one_reads():
    assert read_shader(GOOD).program.instructions[0].opcode == "texld"


def test_truncated_streams_say_where_they_end():
    ws = words(GOOD)
    err = error(pack(ws[:-1]))                        # no end token
    assert "no end token" in err.message and err.location.column == 4 * (len(ws) - 1) + 1
    err = error(GOOD[:-2])                            # half a token
    assert "whole number of 4-byte tokens" in err.message
    err = error(pack(ws[:-3]))                        # mov oC0, r0 cut in its operands
    assert "runs past the end" in err.message
    assert err.location.column == 4 * (len(ws) - 4) + 1     # at the mov's token


def test_a_wrong_instruction_length_is_located_at_its_instruction():
    ws = words(GOOD)
    k = ws.index(0x03000005)                          # mul r0, r0, c0: 3 tokens follow
    ws[k] = 0x02000005
    err = error(pack(ws))
    assert "length field says 2 tokens" in err.message or "no token" in err.message
    assert err.location.column == 4 * k + 1
    ws[k] = 0x04000005
    err = error(pack(ws))
    assert "length field says 4 tokens; its operands take 3" in err.message


def test_unknown_opcodes_and_versions():
    ws = words(GOOD)
    k = ws.index(0x03000005)
    ws[k] = 0x0300007F                                # opcode 127: none
    err = error(pack(ws))
    assert "opcode 127" in err.message and err.location.column == 4 * k + 1
    ws[k] = 0x03000015                                # m4x3 (21) exists, but not in ps_2_0?
    ws2 = words(GOOD)
    ws2[ws2.index(0x03000005)] = 0x0300000C           # slt (12): vertex shaders only
    assert "is no ps_2_0 instruction" in error(pack(ws2)).message
    assert "not a Direct3D 9 shader" in error(pack([0xFFFD0200, 0xFFFF])).message
    assert "none of vs_1_1" in error(pack([0xFFFF0500, 0xFFFF])).message


def test_registers_the_version_lacks_are_out_of_range():
    ws = words(GOOD)
    k = ws.index(0x03000005)
    ws[k + 1] = 0x800F0000 | 40                       # r40 in ps_2_0 (r0-r11)
    err = error(pack(ws))
    assert "r40 is out of range: ps_2_0 has r0-r11" in err.message
    assert err.location.column == 4 * (k + 1) + 1
    ws = words(GOOD)
    ws[k + 1] = 0x800F0000 | 0x10000000 * 4           # rasteriser output in a pixel shader
    assert "has no oPos registers" in error(pack(ws)).message


def test_destination_fields_d3d9_does_not_define():
    ws = words(GOOD)
    k = ws.index(0x03000005)
    for bits, message in ((0x0C000000, "result shift -4"), (0x00800000, "result modifier bits"),
                          (-0x000F0000, "writes no component")):
        bad = list(ws)
        bad[k + 1] = (bad[k + 1] + bits) & 0xFFFFFFFF
        assert message in error(pack(bad)).message


def test_relative_addressing_where_the_version_has_none():
    ws = words(GOOD)
    k = ws.index(0x03000005)
    ws[k + 3] |= 0x2000
    assert "relative addressing in ps_2_0" in error(pack(ws)).message


def _with_table(body: bytes) -> bytes:
    ws = words(GOOD)
    return pack([ws[0], *comment(struct.pack("<I", 0x42415443) + body), *ws[1:]])


def test_broken_constant_tables_are_located():
    t = TypeInfo(1, 3, 1, 4)
    good = write_ctab(ConstantTable((ConstantInfo("Tint", "float4", 0, 1, t),), "ps_2_0",
                                    0xFFFF0200))
    assert read_shader(_with_table(good)).table.constants[0].name == "Tint"
    bad = bytearray(good)
    bad[28:32] = struct.pack("<I", 10_000)            # the name's offset: outside
    err = error(_with_table(bytes(bad)))
    assert "outside the table" in err.message and err.location.column > 8
    bad = bytearray(good)
    bad[12:16] = struct.pack("<I", 0xFFFFFFFF)        # 4 billion constants
    assert "run past the table" in error(_with_table(bytes(bad))).message


def test_a_cyclic_struct_type_is_refused():
    # a struct whose one member's type is the struct itself
    header = struct.pack("<7I", 28, 0, 0xFFFF0200, 1, 28, 0, 0)
    info = struct.pack("<IHHHHII", 68, 2, 0, 1, 0, 48, 0)
    typ = struct.pack("<6HI", 5, 0, 1, 1, 1, 1, 64)     # at 48: members at 64
    member = struct.pack("<II", 68, 48)                  # at 64: name at 68, type at 48
    body = header + info + typ + member + b"S\0\0\0"
    assert "nested more than 16 deep" in error(_with_table(body)).message


def test_other_comments_are_kept_and_written_back():
    ws = words(GOOD)
    end = 2 + (ws[1] >> 16)                       # after the version token and the CTAB
    data = pack([*ws[:end], *comment(b"DBUGsome debug bytes"), *ws[end:]])
    binary = read_shader(data)
    assert [(at, code) for at, code, _ in binary.comments] == [(4 * end, "DBUG")]
    assert write_binary(binary) == data


def test_the_size_limit_comes_first():
    with limits.raised(bytecode_bytes=64):
        err = error(GOOD + b"\0" * 64)
    assert "limit bytecode_bytes" in err.message


def _mutations():
    files = [write_shader(s.program, s.compiled) for _, s in effect_shaders()[:40]]
    files += [write_shader(assemble(block(text))) for text in FEATURES.values()]
    return files


FILES = _mutations()
FUZZ = settings(max_examples=400, deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow])


@FUZZ
@given(which=st.integers(0, len(FILES) - 1),
       edits=st.lists(st.tuples(st.sampled_from(["flip", "word", "cut", "insert", "delete"]),
                                st.integers(0, 1 << 20), st.integers(0, 0xFFFFFFFF)),
                      min_size=1, max_size=4))
def test_hostile_mutations_give_a_program_or_a_located_error(which, edits):
    data = bytearray(FILES[which])
    for kind, where, value in edits:
        if not data:
            break
        k = where % len(data)
        if kind == "flip":
            data[k] ^= 1 << (value % 8)
        elif kind == "word":
            k -= k % 4
            data[k:k + 4] = struct.pack("<I", value)
        elif kind == "cut":
            del data[k:]
        elif kind == "insert":
            data[k:k] = struct.pack("<I", value)
        else:
            del data[k:k + 1 + value % 8]
    try:
        binary = read_shader(bytes(data), "fuzz.pso")
    except EffectError as exc:
        assert exc.location.line == 1 and exc.location.column >= 1
        exc.report()
        return
    # what reads is a program like any other: it checks, prints and writes again
    check(binary.program)
    program_text(binary.program)
    try:
        again = write_binary(binary)
    except EffectError:
        return
    assert read_shader(again).program.name == binary.program.name
    disassemble(again)
