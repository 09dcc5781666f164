"""The one writer (effects/shaders/hlsl/writer.py), alone: generated instructions built by hand
become the assembler's own records, which the assembler's checks accept, whose listing is the
text written out by hand, and which equal what the assembler makes of that text."""
from __future__ import annotations

from effects.base.errors import Location
from effects.model import ShaderBlock
from effects.shaders.asm import assemble, check
from effects.shaders.asm.versions import VERSIONS
from effects.shaders.hlsl.records import FULL, fixed, instruction, reg, replicated, temp
from effects.shaders.hlsl.writer import Code, declaration, listing, write

HERE = Location("w.fx", 7, 1)
ENTRY = Location("w.fx", 3, 1)


def _same_as_assembled(program, text, target):
    """The records equal the assembler's reading of their listing (dataclass equality: what
    the checks, slot counts and lowering read)."""
    parsed = assemble(ShaderBlock("pixel", target, text))
    assert parsed.instructions == program.instructions
    assert parsed.dcls == program.dcls and parsed.def_statements == program.def_statements
    assert parsed.defs == program.defs


def test_ps_2_0_code_as_records_and_its_listing():
    # as legalize.code_of hands them over: swizzles chosen, the sampler numbered
    vr = temp
    instrs = [instruction("texld", vr(0), FULL, [fixed(reg("t", 0), FULL)], "ps_2_0", HERE,
                          sampler="Tex"),
              instruction("mul", vr(1), (0, 1, 2), [fixed(vr(0), FULL),
                                                    fixed(reg("c", 1), (0, 0, 0, 0), True)],
                          "ps_2_0", HERE),
              instruction("mov", vr(1), (3,), [fixed(reg("c", 0), (3, 3, 3, 3))], "ps_2_0", HERE),
              instruction("mov", vr(2), FULL, [fixed(vr(1), FULL)], "ps_2_0", HERE),
              instruction("mov", reg("oC", 0), FULL, [fixed(vr(2), FULL)], "ps_2_0", HERE,
                          saturate=True)]
    instrs[0].srcs[1].index = 0
    alloc = {0: 0, 1: 0, 2: 0}     # vr2 = vr1 in r0: `mov r0, r0` is left out
    code = Code(instrs, alloc, defs={0: (0.5, 0.25, 0.0, 1.0)},
                dcls=[declaration("t", 0), declaration("s", 0, sampler_type="2d")])
    program, generated_at = write(code, VERSIONS["ps_2_0"], ENTRY)
    assert check(program) == []
    text, lines = listing(program, generated_at)
    assert text == ("ps_2_0\ndef c0, 0.5, 0.25, 0, 1\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0\n"
                    "mul r0.xyz, r0, -c1.x\nmov r0.w, c0.w\nmov_sat oC0, r0\n")
    assert lines[4:] == [HERE] * 4 and all(not loc.line for loc in lines[:4])
    assert [i.location for i in program.instructions] == [HERE] * 4
    assert program.stats.arithmetic_slots == 3 and program.stats.texture_slots == 1
    _same_as_assembled(program, text, "ps_2_0")


def test_ps_1_1_code_keeps_its_letters_modifiers_and_co_issue():
    t0, c0 = reg("t", 0), reg("c", 0)
    instrs = [instruction("tex", t0, FULL, [], "ps_1_1", HERE),
              instruction("mul", temp(0), (0, 1, 2), [replicated(t0), replicated(c0, None, "bx2")],
                          "ps_1_1", HERE, saturate=True, shift=1),
              instruction("mov", temp(0), (3,), [replicated(t0, 2, "invert")], "ps_1_1", HERE)]
    instrs[2].coissue = True
    alloc = {0: 0}
    program, generated_at = write(Code(instrs, alloc, letters="rgba"), VERSIONS["ps_1_1"], ENTRY)
    assert check(program) == []
    text, _ = listing(program, generated_at)
    assert text == "ps_1_1\ntex t0\nmul_x2_sat r0.rgb, t0, c0_bx2\n+mov r0.a, 1-t0.b\n"
    assert program.stats.total_slots == 2          # the co-issued pair is one slot
    _same_as_assembled(program, text, "ps_1_1")


def test_a_copy_onto_itself_is_left_out_and_its_co_issued_pair_stands_alone():
    instrs = [instruction("mov", temp(1), (0, 1, 2), [replicated(temp(0))], "ps_1_1", HERE),
              instruction("mov", temp(1), (3,), [replicated(reg("c", 0), 3)], "ps_1_1", HERE)]
    instrs[1].coissue = True
    alloc = {0: 0, 1: 0}
    program, _ = write(Code(instrs, alloc, letters="rgba"), VERSIONS["ps_1_1"], ENTRY)
    assert [(i.opcode, i.coissue) for i in program.instructions] == [("mov", False)]
    assert program.instructions[0].srcs[0].swizzle_text == "a"
