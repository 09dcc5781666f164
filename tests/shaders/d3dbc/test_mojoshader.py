"""MojoShader, a real consumer of Direct3D 9 bytecode (Debian's libmojoshader0, installed by
.ci/setup), reads every shader we write, and its assembler and our writer give the same
tokens for the same assembly where both define them.

What MojoShader refuses for reasons of its own is listed in KNOWN with the reason; every other
message fails the test."""
from __future__ import annotations

import dataclasses
import re
import struct

import pytest

from effects.shaders.asm.text import program_text
from effects.shaders.d3dbc import write_shader
from tests.shaders.d3dbc import mojoshader
from tests.shaders.d3dbc.programs import effect_shaders, feature_programs, instruction_programs

LIB = mojoshader.load()
pytestmark = pytest.mark.skipif(LIB is None, reason="libmojoshader0 is not installed (apt-get "
                                "install libmojoshader0; .ci/setup does)")

PROGRAMS = [(name, shader.program, shader.compiled) for name, shader in effect_shaders()] + [
    (name, program, None) for name, program in instruction_programs() + feature_programs()]

KNOWN = {
    # mojoshader.c parse_instruction_token reads the predicate token after the sources; Wine,
    # vkd3d-shader and DXVK read it after the destination, as we write it
    "Predicated instruction but not predicate register!": "predicate token order",
    # its GLSL back end translates neither ps_1_4's texld/texcrd nor most ps_1_x texture ops
    "unimplemented": "no GLSL for this instruction",
    # it needs the constant table to name the array an asm shader indexes (fxc's HLSL has one)
    "relative addressing of indeterminate array": "asm shaders carry no constant arrays",
    "relative addressing of input registers not supported": "v[aL] (ps_3_0) unsupported",
    "Relative addressing of dest tokens is unsupported": "o[aL] (vs_3_0) unsupported",
    # rules of its own about the generated one-instruction programs, not about their tokens:
    # sincos's scratch registers in r#, texkill of c#, texm3x3 after a 2D tex
    "SINCOS src2 must be constfloat": "program", "TEXKILL must use a temp or texture": "program",
    "TEXM3X3 needs a 3D or Cubemap sampler": "program",
}


def _unknown(errors: list[str]) -> list[str]:
    return [e for e in errors if not any(k in e for k in KNOWN)]


@pytest.mark.parametrize("profile", ["bytecode", "glsl"])
def test_mojoshader_parses_every_shader_we_write(profile):
    refused, accepted = [], 0
    for name, program, compiled in PROGRAMS:
        errors, output, version = mojoshader.parse(LIB, write_shader(program, compiled), profile)
        refused += [f"{name}: {e}" for e in _unknown(errors)]
        if not errors:
            accepted += 1
            assert version == program.version, name
            assert output, name
    assert not refused
    assert accepted >= 0.9 * len(PROGRAMS)


def _without_comments(data: bytes) -> bytes:
    words = list(struct.unpack(f"<{len(data) // 4}I", data))
    out, k = [words[0]], 1
    while k < len(words):
        if words[k] & 0xFFFF == 0xFFFE and not words[k] & 0x80000000:
            k += 1 + (words[k] >> 16 & 0x7FFF)
            continue
        out.append(words[k])
        k += 1
    return struct.pack(f"<{len(out)}I", *out)


def _mojo_dcls(program):
    """MojoShader's assembler writes no usage into a ps_3_0 input's dcl token (0x80000000 for
    dcl_texcoord v0); fxc writes it (0x80000005), as we do: the program as it assembles it."""
    if program.name != "ps_3_0":
        return program
    dcls = [dataclasses.replace(d, usage=None, usage_index=0) if d.register.kind == "v" else d
            for d in program.dcls]
    return dataclasses.replace(program, dcls=dcls)


def test_mojoshader_assembles_the_same_tokens():
    same, differ, unassembled = 0, [], 0
    for name, program, _ in PROGRAMS:
        text = program_text(program)
        # MojoShader knows the 2.1 versions by their token's name only
        text = re.sub(r"^(ps|vs)_2_[ab]", r"\1_2_x", text)
        if program.name == "vs_1_1" and "[a0" in text:
            continue        # its assembler (hg 1314) crashes on vs_1_1's c[a0.x]
        errors, output = mojoshader.assemble(LIB, text)
        if errors:
            unassembled += 1
            continue
        if _without_comments(output) == write_shader(_mojo_dcls(program), table=False):
            same += 1
        else:
            differ.append(name)
    assert not differ, differ
    assert same >= 0.5 * len(PROGRAMS), (same, unassembled)
