"""Shader bytecode round trips: every shader of every bundled effect (assembly and compiled
HLSL), a program for every instruction of every version and hand-written programs for the
token format's corners, written as bytecode and read back, give the same AsmProgram; the
disassembly assembles back to the same bytes."""
from __future__ import annotations

import pytest

from effects.shaders.d3dbc import disassemble, read_shader, write_shader
from effects.shaders.asm import assemble
from tests.shaders.d3dbc.programs import (block, effect_shaders, feature_programs,
                                          instruction_programs, normalized)

PROGRAMS = [(name, shader.program, shader.compiled) for name, shader in effect_shaders()] + [
    (name, program, None) for name, program in instruction_programs() + feature_programs()]


def test_the_corpus_covers_every_version_and_both_sources():
    names = {program.name for _, program, _ in PROGRAMS}
    assert names >= {"vs_1_1", "vs_2_0", "vs_2_x", "vs_2_a", "vs_3_0", "ps_1_1", "ps_1_2",
                     "ps_1_3", "ps_1_4", "ps_2_0", "ps_2_x", "ps_2_a", "ps_2_b", "ps_3_0"}
    assert sum(compiled is not None for *_, compiled in PROGRAMS) >= 10
    assert len(effect_shaders()) >= 60


@pytest.mark.parametrize("name, program, compiled", PROGRAMS, ids=[p[0] for p in PROGRAMS])
def test_write_then_read_gives_the_same_program(name, program, compiled):
    data = write_shader(program, compiled)
    back = read_shader(data, "x.pso")
    assert normalized(back.program) == normalized(program)
    assert back.table is not None and back.table.target == program.name
    if compiled is not None:
        assert {c.name for c in back.table.constants} == (
            set(compiled.constants) | set(compiled.samplers) | set(compiled.int_registers)
            | set(compiled.bool_registers))
    text = disassemble(data, "x.pso")
    again = assemble(block(text))
    assert write_shader(again, compiled) == data, text
