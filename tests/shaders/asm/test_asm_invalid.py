"""Invalid Direct3D assembly: each program breaks one rule, and the test asserts the exact
message and the LINE:COL a user sees in the .fx file.

Every block starts at t.fx line 10, column 9 (as if `asm {` stood before it on that line), so
block line k is file line 10 + k, and only line 0 is shifted by 8 columns.
"""
from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from effects.shaders.asm import NOT_ASSEMBLY, assemble, check
from effects.base.errors import AsmError, Location
from effects.model import ShaderBlock, VertexDeclElement

LOC = Location("t.fx", 10, 9)


def block(src: str, stage: str | None = None, decl=None) -> ShaderBlock:
    if stage is None:
        stage = "vertex" if src.lower().startswith("vs") else "pixel"
    return ShaderBlock(stage, None, src, decl=decl, location=LOC)


def problems(src: str, stage: str | None = None, decl=None) -> list[str]:
    return [f"{e.line}:{e.column}: {e.message}" for e in check(assemble(block(src, stage, decl)))]


def lines(*rows: str) -> str:
    return "\n".join(rows)


def repeat(n: int, row: str) -> list[str]:
    return [row] * n


INVALID = [
    # -- slot limits (one over) --------------------------------------------------------------
    ("ps11 nine arithmetic", lines("ps.1.1", "tex t0", *repeat(9, "mov r0, t0")),
     # the 9th mov stands on block line 10 → file line 20
     ["20:1: ps_1_1 allows 8 arithmetic instructions; this is the 9th"]),
    ("ps11 five texture", lines("ps.1.1", "tex t0", "tex t1", "tex t2", "tex t3", "texkill t0",
                                "mov r0, t0"),
     ["15:1: ps_1_1 allows 4 texture instructions; this is the 5th"]),
    ("ps20 65 arithmetic", lines("ps_2_0", "dcl t0", *repeat(65, "mov r0, t0"), "mov oC0, r0"),
     # 65th mov: block line 1 + 65 = 66 → file 76
     ["76:1: ps_2_0 allows 64 arithmetic instruction slots; this instruction is the 65th"]),
    ("ps20 m4x4 crosses", lines("ps_2_0", "dcl t0", *repeat(62, "mov r0, t0"),
                                "m4x4 r1, r0, c0", "mov oC0, r1"),
     ["74:1: ps_2_0 allows 64 arithmetic instruction slots; this m4x4 takes 4 and brings the "
      "count to 66"]),
    ("vs11 129 slots", lines("vs.1.1", "mov oPos, v0", *repeat(128, "mov r0, v0")),
     ["139:1: vs_1_1 allows 128 instruction slots; this instruction is the 129th"]),
    ("vs11 m4x4 crosses", lines("vs.1.1", "mov oPos, v0", *repeat(124, "mov r0, v0"),
                                "m4x4 r1, v0, c0"),
     # 125 slots before it; the m4x4 (4 slots) makes 129
     ["136:1: vs_1_1 allows 128 instruction slots; this m4x4 takes 4 and brings the count to "
      "129"]),
    ("ps14 nine arithmetic in phase 2", lines("ps.1.4", "texld r0, t0",
                                              *repeat(9, "mov r0, r0")),
     ["20:1: ps_1_4 allows 8 arithmetic instructions per phase; this is the 9th in phase 2"]),
    ("ps14 seven texld in phase 1", lines("ps.1.4", *repeat(7, "texld r0, t0"), "phase",
                                          "mov r0, r0"),
     ["17:1: ps_1_4 allows 6 texture instructions per phase; this is the 7th in phase 1"]),
    # -- register kinds and ranges -----------------------------------------------------------
    ("sampler in ps11", lines("ps.1.1", "mov r0, s0"),
     ["11:9: ps_1_1 has no sampler registers (s0)"]),
    ("r2 in ps11", lines("ps.1.1", "tex t0", "mov r2, t0", "mov r0, t0"),
     ["12:5: r2 is out of range: ps_1_1 has 2 temporary registers (r0–r1)"]),
    # each register past the range once, at its first use (not once per instruction)
    ("r12 and r13 in vs20, each used twice", lines("vs_2_0", "dcl_position v0", "mov r12, v0",
                                                   "add r12, r12, v0", "mov r13, r12",
                                                   "mov oPos, r13"),
     ["12:5: r12 is out of range: vs_2_0 has 12 temporary registers (r0–r11)",
      "14:5: r13 is out of range: vs_2_0 has 12 temporary registers (r0–r11)"]),
    ("c8 in ps11", lines("ps.1.1", "mov r0, c8"),
     ["11:9: c8 is out of range: ps_1_1 has 8 constant registers (c0–c7)"]),
    ("v16 in vs11", lines("vs.1.1", "mov oPos, v16"),
     ["11:11: v16 is out of range: vs_1_1 has 16 input registers (v0–v15)"]),
    ("m4x4 rows past c31", lines("ps_2_0", "dcl t0", "m4x4 r0, t0, c30", "mov oC0, r0"),
     ["12:14: m4x4 reads c30–c33; ps_2_0 has 32 constant registers (c0–c31)"]),
    ("write an input", lines("vs.1.1", "mov oPos, v0", "mov v0, r0"),
     ["12:5: v0 is read-only in vs_1_1; it cannot be written"]),
    ("read an output", lines("vs.1.1", "mov oPos, v0", "mov r0, oPos"),
     ["12:9: oPos is an output register; it cannot be read"]),
    ("relative addressing in ps20", lines("ps_2_0", "mov r0, c[a0.x]", "mov oC0, r0"),
     ["11:9: relative addressing is not available in ps_2_0"]),
    # -- read ports --------------------------------------------------------------------------
    ("three constants in ps11", lines("ps.1.1", "mad r0, c0, c1, c2"),
     ["11:17: ps_1_1 lets one instruction read 2 different constant registers; this one reads "
      "c0, c1, c2"]),
    ("two constants in vs11", lines("vs.1.1", "mov oPos, v0", "add r0, c0, c1"),
     ["12:13: vs_1_1 lets one instruction read 1 constant register; this one reads c0, c1"]),
    ("two inputs in vs11", lines("vs.1.1", "add oPos, v0, v1"),
     ["11:15: vs_1_1 lets one instruction read 1 input register; this one reads v0, v1"]),
    # -- ps_1_1-1_3 texture-address rules ----------------------------------------------------
    ("texture after arithmetic", lines("ps.1.1", "tex t0", "mov r0, t0", "tex t1"),
     ["13:1: tex must come before the arithmetic instructions (in ps_1_1 all texture "
      "instructions come first)"]),
    ("texm3x2pad alone", lines("ps.1.1", "tex t0", "texm3x2pad t1, t0_bx2", "mov r0, t0"),
     ["12:1: texm3x2pad must be followed directly by texm3x2tex"]),
    ("texm3x2tex without pad", lines("ps.1.1", "tex t0", "texm3x2tex t1, t0_bx2",
                                     "mov r0, t1"),
     ["12:1: texm3x2tex must directly follow texm3x2pad"]),
    ("texm3x3 with one pad", lines("ps.1.1", "tex t0", "texm3x3pad t1, t0_bx2",
                                   "texm3x3tex t2, t0_bx2", "mov r0, t2"),
     ["12:1: texm3x3pad must be followed directly by a second texm3x3pad and then texm3x3tex, "
      "texm3x3spec, texm3x3vspec or texm3x3",
      "13:1: texm3x3tex must directly follow two texm3x3pad instructions"]),
    ("texbem from a higher register", lines("ps.1.1", "tex t1", "texbem t0, t1", "mov r0, t0"),
     ["12:12: texbem t0, t1: the source must be a lower t register than the destination"]),
    ("t register loaded twice", lines("ps.1.1", "tex t0", "tex t0", "mov r0, t0"),
     ["12:5: t0 is already loaded by an earlier texture instruction; each t register can be "
      "written by only one"]),
    ("texbem source read again", lines("ps.1.1", "tex t0", "texbem t1, t0", "add r0, t1, t0"),
     ["13:13: t0 was read by texbem/texbeml; no other instruction may read it"]),
    ("t read but never loaded", lines("ps.1.1", "tex t0", "mul r0, t0, t3"),
     ["12:13: t3 is read but no texture instruction loads it (tex t3, texcoord t3 ...)"]),
    ("cnd without r0.a", lines("ps.1.1", "tex t0", "mov r1, t0", "cnd r0, r1.a, t0, v0"),
     ["13:9: cnd in ps_1_1 must use r0.a as its first source"]),
    # -- ps_1_4 phases -----------------------------------------------------------------------
    ("two phase markers", lines("ps.1.4", "texld r0, t0", "phase", "texld r1, t1", "phase",
                                "mov r0, r1"),
     ["14:1: ps_1_4 allows only one phase instruction"]),
    ("v0 in phase 1", lines("ps.1.4", "texld r0, t0", "mul r0, r0, v0", "phase", "mov r0, r0"),
     ["12:13: v0 cannot be read in phase 1 of ps_1_4; colour registers are available only "
      "after the phase instruction"]),
    ("texld after arithmetic", lines("ps.1.4", "mov r1, c0", "texld r0, t0", "mul r0, r0, r1"),
     ["12:1: texld must come before the arithmetic instructions of its phase (phase 2)"]),
    ("bem in phase 2", lines("ps.1.4", "texld r0, t0", "phase", "texld r1, t1",
                             "bem r2.rg, r0, r1", "mov r0.rg, r2"),
     ["14:1: bem is allowed only in phase 1 of ps_1_4"]),
    ("t read by arithmetic in ps14", lines("ps.1.4", "mov r0, t0"),
     ["11:9: t0 can be read only by texld and texcrd in ps_1_4"]),
    ("dependent texld in phase 1", lines("ps.1.4", "texcrd r1.rgb, t1", "texld r0, r1",
                                         "phase", "mov r0, r0"),
     ["12:11: texld can take coordinates from r1 only in phase 2 (a dependent read)"]),
    ("dependent texld on a phase-2 value", lines("ps.1.4", "texld r0, t0", "phase",
                                                 "texcrd r2.rgb, t1", "texld r1, r2",
                                                 "mov r0, r1"),
     ["14:11: texld reads coordinates from r2, which phase 1 does not write"]),
    ("constant with a modifier in ps14", lines("ps.1.4", "texld r1, t0", "add r0, c0_bx2, r1"),
     ["12:9: ps_1_4 allows no source modifiers on constants (c0_bx2)"]),
    # -- ps_2_0 ------------------------------------------------------------------------------
    ("five levels of dependent reads", lines(
        "ps_2_0", "dcl t0", "dcl_2d s0", "texld r0, t0, s0", "texld r1, r0, s0",
        "texld r2, r1, s0", "texld r3, r2, s0", "texld r4, r3, s0", "mov oC0, r4"),
     ["17:1: this texld is a 4th-order dependent read (5 levels of texture reads); ps_2_0 "
      "allows at most 4 levels"]),
    ("undeclared texcoord", lines("ps_2_0", "dcl_2d s0", "texld r0, t0, s0", "mov oC0, r0"),
     ["12:11: t0 is used but not declared (add dcl t0)"]),
    ("undeclared sampler", lines("ps_2_0", "dcl t0", "texld r0, t0, s0", "mov oC0, r0"),
     ["12:15: s0 is used but not declared (add dcl_2d s0, dcl_cube s0 or dcl_volume s0)"]),
    ("texld with a write mask", lines("ps_2_0", "dcl t0", "dcl_2d s0", "texld r0.xy, t0, s0",
                                      "mov oC0, r0"),
     ["13:7: texld writes all four components in ps_2_0; remove the write mask .xy"]),
    ("oC0 by add", lines("ps_2_0", "dcl t0", "add oC0, t0, t0"),
     ["12:1: oC0 can be written only by mov"]),
    ("arbitrary swizzle in ps20", lines("ps_2_0", "dcl t0", "mov r0, t0.yx", "mov oC0, r0"),
     ["12:9: ps_2_0 does not support the swizzle .yx; arbitrary swizzles need ps_2_x with "
      "D3DPS20CAPS_ARBITRARYSWIZZLE, ps_2_a or ps_3_0"]),
    ("scalar source without replicate", lines("ps_2_0", "dcl t0", "rcp r0, t0", "mov oC0, r0"),
     ["12:9: rcp reads one component: give t0 a replicate swizzle (.x, .y, .z or .w)"]),
    # -- instructions of another version -----------------------------------------------------
    ("ps_2_0 texld in ps11", lines("ps.1.1", "texld r0, t0, s0"),
     ["11:1: texld is not available in ps_1_1 (it exists in ps_1_4, ps_2_0, ps_2_x, ps_2_a, "
      "ps_2_b, ps_3_0)"]),
    ("dp4 in ps11", lines("ps.1.1", "tex t0", "dp4 r0, t0, t0"),
     ["12:1: dp4 is not available in ps_1_1 (it exists in ps_1_2, ps_1_3, ps_1_4, ps_2_0, "
      "ps_2_x, ps_2_a, ps_2_b, ps_3_0)"]),
    ("texreg2rgb in ps11", lines("ps.1.1", "tex t0", "texreg2rgb t1, t0", "mov r0, t1"),
     ["12:1: texreg2rgb is not available in ps_1_1 (it exists in ps_1_2, ps_1_3)"]),
    ("vertex instruction in ps20", lines("ps_2_0", "dcl t0", "sge r0, t0, t0", "mov oC0, r0"),
     ["12:1: sge is not available in ps_2_0 (it is a vertex shader instruction)"]),
    ("flow control in ps20", lines("ps_2_0", "dcl t0", "rep i0", "mov r0, t0", "endrep",
                                   "mov oC0, r0"),
     ["12:1: rep is not available in ps_2_0 (it exists in ps_2_x, ps_2_a, ps_2_b, ps_3_0)",
      "14:1: endrep is not available in ps_2_0 (it exists in ps_2_x, ps_2_a, ps_2_b, ps_3_0)"]),
    # -- modifiers, swizzles and masks for the version ----------------------------------------
    ("_x2 source in ps11", lines("ps.1.1", "tex t0", "add r0, t0_x2, v0"),
     ["12:9: the _x2 source modifier needs ps_1_4 (this program is ps_1_1)"]),
    ("_x8 result in ps11", lines("ps.1.1", "tex t0", "add_x8 r0, t0, v0"),
     ["12:1: the _x8 instruction modifier is not available in ps_1_1 (it has _d2, _x2, _x4)"]),
    ("result shift in ps20", lines("ps_2_0", "dcl t0", "add_x2 r0, t0, t0", "mov oC0, r0"),
     ["12:1: ps_2_0 has no result shift modifiers (_x2)"]),
    ("_bias in ps20", lines("ps_2_0", "dcl t0", "add r0, t0_bias, t0", "mov oC0, r0"),
     ["12:9: the _bias source modifier exists only in ps_1_x, not in ps_2_0"]),
    ("_abs in ps20", lines("ps_2_0", "dcl t0", "mov r0, t0_abs", "mov oC0, r0"),
     ["12:9: the _abs source modifier needs a 3_0 shader (this program is ps_2_0); use the abs "
      "instruction"]),
    ("_pp in ps11", lines("ps.1.1", "tex t0", "mov_pp r0, t0"),
     ["12:1: the _pp modifier needs ps_2_0 or later (this program is ps_1_1)"]),
    ("_sat in vs11", lines("vs.1.1", "mov_sat oPos, v0"),
     ["11:1: the _sat modifier is not available in vs_1_1"]),
    ("modifier on texbem", lines("ps.1.1", "tex t0", "texbem_sat t1, t0", "mov r0, t1"),
     ["12:1: texbem takes no instruction modifiers (_sat)"]),
    ("_bx2 on texbem in ps11", lines("ps.1.1", "tex t0", "texbem t1, t0_bx2", "mov r0, t1"),
     ["12:12: in ps_1_1 _bx2 is allowed only on texm* sources, not on texbem"]),
    (".r replicate in ps11", lines("ps.1.1", "tex t0", "mov r0, t0.r"),
     ["12:9: ps_1_1 does not support the swizzle .r; sources take only the .a selector (and "
      ".b in alpha-only instructions)"]),
    (".b outside an alpha instruction", lines("ps.1.1", "tex t0", "mov r0, t0.b"),
     ["12:9: the .b (blue replicate) selector is allowed in ps_1_1 only when the instruction "
      "writes .a alone"]),
    ("write mask .xy in ps11", lines("ps.1.1", "tex t0", "mov r0.xy, t0", "mov r0, t0"),
     ["12:5: ps_1_1 allows only the write masks .rgba, .rgb and .a; .xy is not one of them"]),
    ("dp3 writing .a in ps11", lines("ps.1.1", "tex t0", "mov r0, t0", "dp3 r0.a, t0, v0"),
     ["13:5: dp3 in ps_1_1 must write .rgb or .rgba"]),
    ("co-issue with nothing before", lines("ps.1.1", "tex t0", "+mov r0.a, t0",
                                           "mov r0.rgb, t0"),
     ["12:2: a co-issued (+) instruction must pair with the arithmetic instruction just "
      "before it"]),
    ("co-issue of two colour writes", lines("ps.1.1", "tex t0", "mov r0.rgb, t0",
                                            "+mov r1.rgb, t0"),
     ["13:2: co-issued instructions must split the work: one writes .rgb (colour), the other "
      ".a (alpha)"]),
    ("a0 without .x in vs11", lines("vs.1.1", "mov a0, v0", "mov oPos, c[a0.x]"),
     ["11:5: a0 can be written only as a0.x in vs_1_1"]),
    ("def after code", lines("ps.1.1", "tex t0", "mov r0, t0", "def c0, 1, 1, 1, 1"),
     ["13:1: def must come before the first instruction"]),
    # -- uninitialised reads, declarations, outputs ------------------------------------------
    ("r1 read before written", lines("ps.1.1", "tex t0", "mul r0, t0, r1"),
     ["12:13: r1 is read before it is written"]),
    ("vs temp read before written", lines("vs.1.1", "mov oPos, r0"),
     ["11:11: r0 is read before it is written"]),
    # a pixel shader's temporaries by component (the reference's ps temporary register page)
    ("ps20 component read before written", lines("ps_2_0", "mov r0.x, c0", "add r1, r0, c1",
                                                 "mov oC0, r1"),
     ["12:9: r0.yzw is read before it is written (only r0.x is written before here)"]),
    ("ps20 dp3 reads xyz", lines("ps_2_0", "mov r0.xy, c0", "dp3 r1, r0, c1", "mov oC0, r1"),
     ["12:9: r0.z is read before it is written (only r0.xy is written before here)"]),
    ("ps30 swizzle names the unwritten lane", lines("ps_3_0", "mov r0.xy, c0",
                                                    "mov r1.xy, r0.yz", "mov r1.zw, c0",
                                                    "mov oC0, r1"),
     ["12:12: r0.z is read before it is written (only r0.xy is written before here)"]),
    ("ps20 texld 2d reads its sampler's xy", lines("ps_2_0", "dcl_cube s0", "mov r0.xy, c0",
                                                   "texld r1, r0, s0", "mov oC0, r1"),
     ["13:11: r0.z is read before it is written (only r0.xy is written before here)"]),
    ("ps20 texldp reads w", lines("ps_2_0", "dcl_2d s0", "mov r0.xy, c0",
                                  "texldp r1, r0, s0", "mov oC0, r1"),
     ["13:12: r0.w is read before it is written (only r0.xy is written before here)"]),
    ("no r0 write in ps11", lines("ps.1.1", "tex t0", "mov r1, t0"),
     ["10:9: the shader never writes r0, its output colour"]),
    ("no oC0 write in ps20", lines("ps_2_0", "dcl t0", "mov r0, t0"),
     ["10:9: the shader never writes oC0, its output colour"]),
    ("no oPos write in vs11", lines("vs.1.1", "mov oD0, v0"),
     ["10:9: the shader never writes oPos, the position output"]),
    ("if without endif", lines("vs_2_0", "dcl_position v0", "if b0", "mov oPos, v0"),
     ["12:1: if is never closed by endif"]),
]


@pytest.mark.parametrize("name,src,expected", [c for c in INVALID if c[2]],
                         ids=[c[0] for c in INVALID if c[2]])
def test_invalid_program_reports_exactly(name, src, expected):
    assert problems(src) == expected


def test_dependent_read_levels_follow_each_component():
    """fxc reuses a register for the next tap's coordinate with a write mask (`add r1.xy, t0,
    c1` into an r1 whose .zw came from a texture): each such read is first-order dependent
    (level 2), not one level above the last (a 6-tap blur was '5 levels' and rejected)."""
    taps = ["texld r0, t0, s0"]
    for k in range(6):
        src, dst = ("r0", "r1") if k % 2 == 0 else ("r1", "r0")
        taps += [f"add {dst}.xy, t0, c{k}", f"texld r2, {dst}, s0", f"add {dst}, {src}, r2"]
    program = assemble(block(lines("ps_2_0", "dcl t0", "dcl_2d s0", *taps, "mov oC0, r1")))
    assert check(program) == []
    assert sorted(set(program.read_levels.values())) == [1, 2]
    # a component still carrying a texel moves the read up a level: r1.z (from r0) is read
    # by a cube map's coordinate, not by a 2D one's .xy
    chain = assemble(block(lines("ps_2_0", "dcl t0", "dcl_2d s0", "dcl_cube s1",
                                 "texld r0, t0, s0", "mov r1, r0", "add r1.xy, t0, c0",
                                 "texld r2, r1, s0", "texld r3, r2, s0", "texld r4, r3, s1",
                                 "mov oC0, r4")))
    assert list(chain.read_levels.values()) == [1, 2, 3, 4]


@pytest.mark.parametrize("src", [
    # each reads only components written before it
    lines("ps_2_0", "mov r0.x, c0", "add r1.x, r0, c1", "mov r1.yzw, c1", "mov oC0, r1"),
    lines("ps_2_0", "mov r0.x, c0", "rcp r1, r0.x", "mov oC0, r1"),
    lines("ps_2_0", "mov r0.xyz, c0", "dp3 r1, r0, c1", "nrm r2.xyz, r0", "mov r2.w, r1.x",
          "mov oC0, r2"),
    lines("ps_2_0", "dcl_2d s0", "mov r0.xy, c0", "texld r1, r0, s0", "mov oC0, r1"),
    lines("ps_2_0", "dcl_2d s0", "mov r0.xy, c0", "mov r0.w, c1.x", "texldb r1, r0, s0",
          "mov oC0, r1"),
    lines("ps_3_0", "mov r0.xy, c0", "mov r1, r0.xyyy", "mov oC0, r1"),
    # a vertex shader's temporary: the register written first is enough (its page); ps_1_x's
    lines("vs_1_1", "dcl_position v0", "mov r0.x, v0", "mov oPos, r0"),
    lines("ps.1.4", "texld r1, t0", "mov r0.rgb, r1", "mov r0.a, r0"),
])
def test_reads_of_components_written_before_them_pass(src):
    assert problems(src) == []


def test_dp4_takes_two_slots_in_ps12():
    # six movs (6) + dp4 (2) = 8 fills ps_1_2; one more mov is the 9th slot
    src = lines("ps.1.2", "tex t0", *repeat(6, "mov r0, t0"), "dp4 r1, t0, t0", "mov r0, r1")
    assert problems(src) == [
        "19:1: ps_1_2 allows 8 arithmetic instructions; this is the 9th"]
    # in ps_1_4 dp4 takes one slot: 6 + 1 + 1 = 8 fits
    ps14 = lines("ps.1.4", "texld r0, t0", *repeat(6, "mov r1, r0"), "dp4 r1, r0, r0",
                 "mov r0, r1")
    assert problems(ps14) == []


def test_undeclared_input_with_a_dx8_decl_block():
    decl = (VertexDeclElement(0, "float", 0, 3),)
    assert problems(lines("vs.1.1", "mov oPos, v1"), "vertex", decl) == [
        "11:11: v1 is read but not declared (by a dcl_usage or the decl{} block)"]


SYNTAX = [
    ("arb fragment program", "!!ARBfp1.0\nTEMP r0;\nTEX r0, fragment.texcoord[0], "
     "texture[0], 2D;\nEND", None, f"10:9: {NOT_ASSEMBLY}"),
    ("random words", "hello world", None, f"10:9: {NOT_ASSEMBLY}"),
    ("glsl", "void main() { gl_FragColor = vec4(1.0); }", None, f"10:9: {NOT_ASSEMBLY}"),
    ("empty block", "", None, f"10:9: {NOT_ASSEMBLY}"),
    ("pixel version in a vertex block", "ps.1.1\ntex t0\nmov r0, t0", "vertex",
     "10:9: a vertex shader must start with a vs version token; this one starts with ps.1.1"),
    ("unknown version", "ps.1.5\nmov r0, v0", None,
     "10:9: unknown shader version 'ps.1.5' (known: ps_1_0, ps_1_1, ps_1_2, ps_1_3, ps_1_4, "
     "ps_2_0, ps_2_x, ps_2_a, ps_2_b, ps_3_0, vs_1_1, vs_2_0, vs_2_x, vs_2_a, vs_3_0)"),
    ("unknown instruction", "ps.1.1\nfoo r0, v0", None, "11:1: unknown instruction 'foo'"),
    ("too few operands", "ps.1.1\n  mad r0, v0, v1", None,
     "11:3: mad takes 4 operands (dst, src0, src1, src2); found 3"),
    ("write mask out of order", "vs.1.1\nmov r0.yx, v0", None,
     "11:5: write mask '.yx' must name each component at most once, in the order x, y, z, w"),
    ("second version token", "ps.1.1\nps.1.1\nmov r0, v0", None,
     "11:1: a second version token 'ps.1.1'; the version must come first and only once"),
    ("stray character", "ps.1.1\nmov r0, v0 #", None, "11:12: unexpected character '#'"),
    ("unknown source modifier", "ps.1.1\nmov r0, v0_foo", None,
     "11:9: unknown source modifier '_foo' on 'v0_foo'"),
    ("unknown instruction modifier", "ps.1.1\nmov_x3 r0, v0", None,
     "11:1: unknown or repeated instruction modifier '_x3' in 'mov_x3'"),
    ("not a register", "ps.1.1 mov r0, q7", None, "10:24: 'q7' is not a register"),
    ("bad swizzle", "ps_2_0\nmov oC0, c0.xq", None,
     "11:12: '.xq' is not a swizzle or write mask (use up to four of x, y, z, w or r, g, b, a)"),
    ("invert combined", "ps.1.1\nmov r0, 1-v0_bx2", None,
     "11:11: the invert modifier 1-reg cannot be combined with _bx2"),
]


@pytest.mark.parametrize("name,src,stage,expected", SYNTAX, ids=[s[0] for s in SYNTAX])
def test_syntax_errors_raise_located_asm_errors(name, src, stage, expected):
    with pytest.raises(AsmError) as info:
        assemble(block(src, stage))
    e = info.value
    assert f"{e.line}:{e.column}: {e.message}" == expected
    assert e.path == "t.fx"


def test_error_report_shows_the_file_line_and_a_caret():
    prog = assemble(block("ps.1.1\ntex t0\nmul r0, t0, r1"))
    (err,) = check(prog)
    assert err.report() == ("t.fx:12:13: error: r1 is read before it is written\n"
                            "mul r0, t0, r1\n"
                            "            ^")
    with pytest.raises(AsmError) as info:
        assemble(block("hello"))
    # line 0 of the block starts at column 9 of the file line
    assert info.value.report().splitlines()[1:] == ["        hello", "        ^"]


def test_at_least_forty_invalid_programs():
    assert len(INVALID) + len(SYNTAX) + 2 >= 40


_VOCAB = ["ps.1.1", "ps_1_4", "ps_2_0", "vs.1.1", "vs_2_0", "tex", "texld", "mov", "mad",
          "dp3_sat", "add_x2", "texm3x2pad", "phase", "def", "dcl_2d", "dcl", "if", "endif",
          "r0", "r1", "t0", "v0", "c0", "s0", "oC0", "oPos", "a0.x", "c[a0.x + 2]", ",", ".",
          "-", "1-", "+", "_bx2", ".rgb", ".a", "\n", ";", "//", "(", ")", "[", "]", "!",
          "1.5", "#", "{", "}", "\t"]


@settings(max_examples=400, deadline=None)
@given(st.sampled_from(["", "ps.1.1", "ps.1.3", "ps.1.4", "ps_2_0", "ps_2_x", "ps_3_0", "vs.1.1",
                        "vs_2_0", "vs_3_0"]),
       st.lists(st.sampled_from(_VOCAB), max_size=40), st.sampled_from(["pixel", "vertex"]))
def test_any_text_gives_errors_never_a_crash(version, words, stage):
    text = version + "\n" + " ".join(words)
    try:
        prog = assemble(block(text, stage))
    except AsmError as e:
        assert e.line >= 10 and e.column >= 1 and e.message
        return
    for e in check(prog):
        assert isinstance(e, AsmError) and e.line >= 10 and e.message
    assert prog.stats.total_slots >= 0
