"""Tokens worked out by hand from the format (tokens.py's sources), and fxc's own where we
have them (SDL 2's fxc 6.3 shaders, tests/data/d3dbc), for one instruction of each shape; and
the instruction table's opcode column answers every (opcode, version) pair with its own row."""
from __future__ import annotations

import struct

import pytest

from effects.shaders.asm import INSTRUCTIONS, assemble
from effects.shaders.asm.instructions import by_code
from effects.shaders.d3dbc import read_shader, write_shader
from tests.shaders.d3dbc.programs import block

CASES = [
    # (version, statement, its tokens)
    # fxc 6.3 (SDL 2's D3D9_PixelShader_YUV_JPEG, tests/data/d3dbc/sdl/SDL_shaders_d3d.c)
    ("ps_2_0", "texld r0, t0, s0", [0x03000042, 0x800F0000, 0xB0E40000, 0xA0E40800]),
    ("ps_2_0", "dp2add r1.z, r0, c3, c3.z", [0x0400005A, 0x80040001, 0x80E40000, 0xA0E40003,
                                             0xA0AA0003]),
    ("ps_2_0", "add r0.xyz, r0, c0", [0x03000002, 0x80070000, 0x80E40000, 0xA0E40000]),
    ("ps_2_0", "dcl_2d s1", [0x0200001F, 0x90000000, 0xA00F0801]),
    ("ps_2_0", "dcl t0.xy", [0x0200001F, 0x80000000, 0xB0030000]),
    ("ps_2_0", "mov oC0, r0", [0x02000001, 0x800F0800, 0x80E40000]),
    # by hand: 1_x has no length; co-issue is bit 30; bx2 = 4, invert = 6, _x2 shift = 1
    ("ps_1_1", "mul_x2 r0.rgb, t0_bx2, 1-v0", [0x00000005, 0x81070000, 0xB4E40000, 0x96E40000]),
    ("ps_1_1", "+add_sat r0.a, r0, v1.a", [0x40000002, 0x80180000, 0x80E40000, 0x90FF0001]),
    # vs_1_1 relative addressing: bit 13, a0.x implied, no address token
    ("vs_1_1", "mov r0, c[a0.x + 5]", [0x00000001, 0x800F0000, 0xA0E42005]),
    # vs_2_0: an address token follows (a0.y: replicate swizzle y = 0x55)
    ("vs_2_0", "mov r0, c[a0.y + 3]", [0x03000001, 0x800F0000, 0xA0E42003, 0xB0550000]),
    # ps_3_0 aL: register type 15, bits 28-30 = 7, bits 11-12 = 1
    ("ps_3_0", "mov r0, c[aL + 2]", [0x03000001, 0x800F0000, 0xA0E42002, 0xF0E40800]),
    # predication: bit 28, the predicate after the destination; NOT is modifier 13
    ("ps_2_x", "(!p0.x) mov r1, c1", [0x13000001, 0x800F0001, 0xBD001000, 0xA0E40001]),
    # breakp p0.w: the predicate an ordinary source (Wine's assembler tests: 01000060 b0ff1000)
    ("ps_3_0", "breakp p0.w", [0x01000060, 0xB0FF1000]),
    # comparisons in bits 16-18: gt = 1, ne = 5
    ("ps_3_0", "if_gt r0.x, c0.y", [0x02010029, 0x80000000, 0xA0550000]),
    ("ps_3_0", "setp_ne p0.x, r0, c0", [0x0305005E, 0xB0011000, 0x80E40000, 0xA0E40000]),
    # texldp: D3DSIO_TEX with control 1; texldb 2
    ("ps_2_0", "texldp r0, t0, s0", [0x03010042, 0x800F0000, 0xB0E40000, 0xA0E40800]),
    # ps_3_0 input with a usage (fxc writes it: texcoord 5, index 2 in bits 16-19)
    ("ps_3_0", "dcl_texcoord2_centroid v1.xy", [0x0200001F, 0x80020005, 0x90430001]),
    ("vs_3_0", "defb b3, true", [0x0200002F, 0xE00F0803, 0x00000001]),
    ("vs_3_0", "defi i1, 2, -1, 1, 0", [0x05000030, 0xF00F0001, 2, 0xFFFFFFFF, 1, 0]),
    ("vs_1_1", "def c95, 1.5, 0, 0, 1", [0x00000051, 0xA00F005F, 0x3FC00000, 0, 0,
                                          0x3F800000]),
]


def _tokens(version: str, statement: str) -> list[int]:
    prefix = {"ps_3_0": "dcl_texcoord0 v0\n"}.get(version, "")
    data = write_shader(assemble(block(f"{version}\n{prefix}{statement}\n")), table=False)
    words = list(struct.unpack(f"<{len(data) // 4}I", data))[1:-1]
    skip = 3 if prefix else 0                  # the dcl the prefix adds
    return words[skip:]


@pytest.mark.parametrize("version, statement, tokens", CASES, ids=[c[1] for c in CASES])
def test_tokens_by_hand(version, statement, tokens):
    assert _tokens(version, statement) == tokens


def test_constants_past_2047_use_the_second_bank():
    # c2048 and up live in CONST2 (register type 11: bits 28-30 = 3, bits 11-12 = 1)
    words = _tokens("vs_3_0", "mov r0, c2049")
    assert words[2] == 0x80000000 | (11 & 7) << 28 | (11 & 0x18) << 8 | 0xE40000 | 1
    back = read_shader(write_shader(assemble(block("vs_3_0\nmov r0, c2049\n")), table=False))
    assert back.program.instructions[0].srcs[0].index == 2049


def test_every_row_answers_its_own_opcode_in_every_version():
    for row in INSTRUCTIONS:
        for version in row.versions.names:
            found = by_code(row.code, row.control, version)
            assert found is not None and found.name == row.name, (row.name, version)
            if row.compare_code is not None:
                assert by_code(row.compare_code, 0, version).name == row.name
