"""The one writer (effects/shaders/hlsl/writer.py), alone: generated instructions built by hand
become the assembler's own records, which the assembler's checks accept, whose listing is the
text written out by hand, and which equal what the assembler makes of that text."""
from __future__ import annotations

from effects.base.errors import Location
from effects.model import ShaderBlock
from effects.shaders.asm import assemble, check
from effects.shaders.asm.versions import VERSIONS
from effects.shaders.hlsl.asmcode import Instr, Reg, Src
from effects.shaders.hlsl.ps1_asm import Src as Ps1Src, ps1_source
from effects.shaders.hlsl.writer import Code, declaration, listing, register, swizzled, write

HERE = Location("w.fx", 7, 1)
ENTRY = Location("w.fx", 3, 1)


def _ps20_source(alloc):
    def source(s, ins):
        op = swizzled(register(s.reg, alloc), tuple(s.fixed or (0, 1, 2, 3)))
        op.negate = s.negate
        return op
    return source


def _same_as_assembled(program, text, target):
    """The records equal the assembler's reading of their listing (dataclass equality: what
    the checks, slot counts and lowering read)."""
    parsed = assemble(ShaderBlock("pixel", target, text))
    assert parsed.instructions == program.instructions
    assert parsed.dcls == program.dcls and parsed.def_statements == program.def_statements
    assert parsed.defs == program.defs


def test_ps_2_0_code_as_records_and_its_listing():
    instrs = [Instr("texld", Reg("vr", 0), (0, 1, 2, 3), [Src(Reg("t", 0), {})], HERE,
                    sampler="Tex"),
              Instr("mul", Reg("vr", 1), (0, 1, 2), [Src(Reg("vr", 0), {}),
                                                    Src(Reg("c", 1), {}, True, fixed=(0, 0, 0, 0))], HERE),
              Instr("mov", Reg("vr", 1), (3,), [Src(Reg("c", 0), {}, fixed=(3, 3, 3, 3))], HERE),
              Instr("mov", Reg("vr", 2), (0, 1, 2, 3), [Src(Reg("vr", 1), {})], HERE),
              Instr("mov", Reg("oC", 0), (0, 1, 2, 3), [Src(Reg("vr", 2), {})], HERE, saturate=True)]
    alloc = {0: 0, 1: 0, 2: 0}     # vr2 = vr1 in r0: `mov r0, r0` is left out
    code = Code(instrs, alloc, _ps20_source(alloc), defs={0: (0.5, 0.25, 0.0, 1.0)},
                dcls=[declaration("t", 0), declaration("s", 0, sampler_type="2d")],
                sampler_of={"Tex": 0})
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
    instrs = [Instr("tex", Reg("t", 0), (0, 1, 2, 3), [], HERE),
              Instr("mul", Reg("vr", 0), (0, 1, 2), [Ps1Src(Reg("t", 0)), Ps1Src(Reg("c", 0), None, "bx2")],
                    HERE, shift=1, saturate=True),
              Instr("mov", Reg("vr", 0), (3,), [Ps1Src(Reg("t", 0), 2, "invert")], HERE, coissue=True)]
    alloc = {0: 0}
    source = ps1_source(alloc)
    program, generated_at = write(Code(instrs, alloc, source, letters="rgba"), VERSIONS["ps_1_1"], ENTRY)
    assert check(program) == []
    text, _ = listing(program, generated_at)
    assert text == "ps_1_1\ntex t0\nmul_x2_sat r0.rgb, t0, c0_bx2\n+mov r0.a, 1-t0.b\n"
    assert program.stats.total_slots == 2          # the co-issued pair is one slot
    _same_as_assembled(program, text, "ps_1_1")


def test_a_copy_onto_itself_is_left_out_and_its_co_issued_pair_stands_alone():
    instrs = [Instr("mov", Reg("vr", 1), (0, 1, 2), [Ps1Src(Reg("vr", 0))], HERE),
              Instr("mov", Reg("vr", 1), (3,), [Ps1Src(Reg("c", 0), 3)], HERE, coissue=True)]
    alloc = {0: 0, 1: 0}
    program, _ = write(Code(instrs, alloc, ps1_source(alloc), letters="rgba"),
                       VERSIONS["ps_1_1"], ENTRY)
    assert [(i.opcode, i.coissue) for i in program.instructions] == [("mov", False)]
    assert program.instructions[0].srcs[0].swizzle_text == "a"
