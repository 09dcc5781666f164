"""Lowering Direct3D assembly to the IR, checked by evaluating the IR on chosen inputs.

Expected values are worked out by hand from the formulas in docs/reference/semantics.md
§2-4 (each case says how). Golden printed IR for the 18 seed listings lives in
tests/golden/ir/asm_<name>.txt; regenerate with `UPDATE_GOLDEN=1 pytest tests/shaders/asm/test_asm_lower.py`
after checking the diff.
"""
from __future__ import annotations

from tests.paths import TESTS

import os
import re

import numpy as np
import pytest

from backends.reference.evaluate import evaluate
from effects.shaders.asm import assemble, check
from effects.shaders.asm.lower import (ShaderContext, constant_registers, lower_pixel_shader,
                                       lower_vertex_shader, lowering_problems)
from effects.base.errors import AsmError, Location
from effects.model import ShaderBlock, VertexDeclElement
from effects.d3d9.precision import LoweringOptions
from tests.shaders.asm.test_asm_parse import SEEDS, VALID

FLOAT = LoweringOptions()
GEFORCE3 = LoweringOptions(ps1x_bits=8, ps1x_range=1.0, ps14_bits=8, ps14_range=1.0)
GOLDEN = TESTS / "golden" / "ir"


def assemble_valid(src: str, stage: str = "pixel", decl=None):
    prog = assemble(ShaderBlock(stage, None, src, decl=decl, location=Location("t.fx", 1, 1)))
    assert [str(e) for e in check(prog)] == []
    return prog


def ps(src: str, options: LoweringOptions = FLOAT, **ctx):
    return lower_pixel_shader(assemble_valid(src), ShaderContext(options, **ctx))


def vs(src: str, options: LoweringOptions = FLOAT, decl=None):
    return lower_vertex_shader(assemble_valid(src, "vertex", decl),
                               ShaderContext(options, decl=decl))


def run(program, values=None, samplers=None, count=None):
    values = dict(values or {})
    per_row = any(np.ndim(values[i.name]) == 2 for i in program.inputs if i.name in values)
    inputs = {}
    for item in program.inputs:
        assert item.name in values, f"test gives no value for {item.name}"
        inputs[item.name] = np.asarray(values[item.name], dtype=np.float32)
    return evaluate(program, inputs, samplers or {}, count=count or (None if per_row else 1))


def out(program, values=None, samplers=None, name="color0"):
    return run(program, values, samplers).outputs[name][0]


def identity_sampler(coord, kind, bias, lod):
    return np.array(coord, dtype=np.float32)


def constant_sampler(texel):
    def sample(coord, kind, bias, lod):
        return np.broadcast_to(np.array(texel, np.float32), (coord.shape[0], 4))
    return sample


def approx(values, rel=1e-5, abs=1e-6):
    return pytest.approx(np.asarray(values, dtype=np.float64), rel=rel, abs=abs)


# -- arithmetic instructions (ps_2_0, float) -------------------------------------------------

C0, C1, C2 = (0.5, -0.25, 2.0, 0.75), (0.25, 0.5, -1.0, 4.0), (1.0, 0.0, 0.5, -2.0)
ARITH = [
    ("add r0, c0, c1", (0.75, 0.25, 1.0, 4.75)),
    ("sub r0, c0, c1", (0.25, -0.75, 3.0, -3.25)),
    ("mul r0, c0, c1", (0.125, -0.125, -2.0, 3.0)),
    ("mad r0, c0, c1, r2", (1.125, -0.125, -1.5, 1.0)),
    ("dp3 r0, c0, c1", (0.125 - 0.125 - 2.0,) * 4),
    ("dp4 r0, c0, c1", (0.125 - 0.125 - 2.0 + 3.0,) * 4),
    ("min r0, c0, c1", (0.25, -0.25, -1.0, 0.75)),
    ("max r0, c0, c1", (0.5, 0.5, 2.0, 4.0)),
    ("lrp r0, c0, c1, r2", (0.5 * 0.25 + 0.5 * 1.0, -0.25 * 0.5 + 1.25 * 0.0,
                            2.0 * -1.0 - 1.0 * 0.5, 0.75 * 4.0 + 0.25 * -2.0)),
    ("cmp r0, c1, c0, r2", (0.5, -0.25, 0.5, 0.75)),
    ("rcp r0, c1.w", (0.25,) * 4),
    ("rsq r0, c1.w", (0.5,) * 4),
    ("exp r0, c0.z", (4.0,) * 4),
    ("log r0, c1.w", (2.0,) * 4),
    ("pow r0, c1.w, c0.x", (2.0,) * 4),              # |4| ^ 0.5
    ("frc r0, r2", (0.0, 0.0, 0.5, 0.0)),
    ("abs r0, c0", (0.5, 0.25, 2.0, 0.75)),
    ("nrm r0, r2", np.array(C2) / np.sqrt(1.25)),     # w scaled as well
    # r0.w written too: a ps_2_0 shader reads no component before it is written (check.py)
    ("crs r0.xyz, c0, c1\nmov r0.w, c2.y", (-0.25 * -1.0 - 2.0 * 0.5, 2.0 * 0.25 - 0.5 * -1.0,
                                           0.5 * 0.5 - (-0.25) * 0.25, 0.0)),
    ("dp2add r0, c0, c1, r2.z", (0.125 - 0.125 + 0.5,) * 4),
    ("mov r0, -c0.wzyx", (-0.75, -2.0, 0.25, -0.5)),
]


@pytest.mark.parametrize("text,expected", ARITH, ids=[a[0] for a in ARITH])
def test_ps20_arithmetic(text, expected):
    prog = ps(f"ps_2_0\nmov r2, c2\n{text}\nmov oC0, r0")
    assert out(prog, {"c0": C0, "c1": C1, "c2": C2}) == approx(expected)


def test_vs20_sgn_is_minus_one_zero_or_one():
    # sgn r0, c0, r1, r2 with c0 = (-2, 0, 3, -0.5): (-1, 0, 1, -1)
    prog = vs("vs_2_0\ndcl_position v0\ndef c0, -2, 0, 3, -0.5\nmov r1, v0\nmov r2, v0\n"
              "sgn r0, c0, r1, r2\nmov oPos, r0")
    assert out(prog, {"position": (0, 0, 0, 1)}, name="position") == approx((-1, 0, 1, -1))


def test_ps20_sincos_writes_cos_and_sin():
    prog = ps("ps_2_0\nmov r1, c0\nsincos r0.xy, r1.x, c1, c2\nmov r0.zw, c0.y\nmov oC0, r0")
    got = out(prog, {"c0": (np.pi / 3, 0, 0, 0), "c1": C1, "c2": C2})
    assert got == approx((0.5, np.sqrt(3) / 2, 0.0, 0.0))   # zw: c0.y


def test_ps20_constants_are_not_clamped_but_ps11_reads_are():
    # Wine's test: c1 = (1.25, -.5, -1.5, 1), c2 = (-.5, 1.25, 2, 1). ps_1_1 clamps every read
    # to [-1, 1]: (1, -.5, -1, 1) + (-.5, 1, 1, 1) = (.5, .5, 0, 2 -> saturated 1).
    values = {"c1": (1.25, -0.5, -1.5, 1.0), "c2": (-0.5, 1.25, 2.0, 1.0)}
    assert out(ps("ps.1.1\nadd r0, c1, c2"), values) == approx((0.5, 0.5, 0.0, 1.0))
    # ps_2_0: (0.75, 0.75, 0.5, 2); the render target clamps later, not the program
    assert out(ps("ps_2_0\nadd r0, c1, c2\nmov oC0, r0"), values) == approx((0.75, 0.75, 0.5, 2))
    # a def'd ps_1_x constant is clamped too: c0 = 1.25 reads 1.0
    d = ps("ps.1.1\ndef c0, 1.25, -3.0, 0.5, 0.0\nmov r1, c2\nmad r0, c0, c1, r1")
    got = out(d, {"c1": (0.5, 0.25, 1, 1), "c2": (0.0, 1.0, 0, 0.5)})
    assert got == approx((0.5, 0.75, 0.5, 0.5))      # (1*.5, -1*.25 + 1, .5, 0 + .5)


# -- source and instruction modifiers (ps_1_4, float) ----------------------------------------

# r0 = r1 / 8 + 1/2 keeps results in [0, 1] so the output saturate hides nothing.
CX = (0.25, 0.75, 1.0, 0.0)
MODIFIERS = [
    ("c0", CX),
    ("-c0", (-0.25, -0.75, -1.0, 0.0)),
    ("c0_bias", (-0.25, 0.25, 0.5, -0.5)),             # x - 0.5
    ("-c0_bias", (0.25, -0.25, -0.5, 0.5)),
    ("c0_bx2", (-0.5, 0.5, 1.0, -1.0)),                # 2 (x - 0.5)
    ("-c0_bx2", (0.5, -0.5, -1.0, 1.0)),
    ("c0_x2", (0.5, 1.5, 2.0, 0.0)),                   # 2 x (ps_1_4 only)
    ("-c0_x2", (-0.5, -1.5, -2.0, 0.0)),
    ("1-c0", (0.75, 0.25, 0.0, 1.0)),                  # 1 - x
    ("c0.b", (1.0,) * 4),                              # blue replicate
    ("c0.g", (0.75,) * 4),                             # green replicate (1.4)
    ("c0_bx2.a", (-1.0,) * 4),                         # selector, then modifier
]


@pytest.mark.parametrize("operand,expected", MODIFIERS, ids=[m[0] for m in MODIFIERS])
def test_ps14_source_modifiers(operand, expected):
    # ps_1_4 allows no modifiers on c#: the constant goes through r2 first
    prog = ps(f"ps.1.4\nmov r2, c0\nmov r1, {operand.replace('c0', 'r2')}\n"
              "mad r0, r1, c7, c6")
    got = out(prog, {"c0": CX, "c7": (0.125,) * 4, "c6": (0.5,) * 4})
    assert got == approx(np.array(expected) / 8 + 0.5)


def test_ps11_modifiers_on_a_dot_product():
    # dp3_sat r0, t1_bx2, v1_bx2 (Boyd's specular): t1 = (1, .5, .75) -> (1, 0, .5);
    # v1 = (.5, .5, 1) -> (0, 0, 1); dot = .5
    prog = ps("ps.1.1\ntex t1\ndp3_sat r0, t1_bx2, v1_bx2", sampler_kinds={1: "2d"})
    got = out(prog, {"texcoord1": (0, 0, 0, 1), "color1": (0.5, 0.5, 1.0, 0.2)},
              {1: constant_sampler((1.0, 0.5, 0.75, 1.0))})
    assert got == approx((0.5,) * 4)


@pytest.mark.parametrize("text,expected", [
    ("mul_x4_sat r0, c0, c1", 1.0),          # .375 * 4 = 1.5 -> 1
    ("mul_d2 r0, c0, c1", 0.1875),           # .375 / 2
    ("mul_x8 r0, c0, c2", 0.5),              # .0625 * 8 (x8 is ps_1_4 only)
    ("mul_d8 r0, c0, c1", 0.046875),         # .375 / 8
    ("add_d2_sat r0, c3, c4", 0.8),          # shift first: 1.6 / 2 = .8 (sat first gives .5)
    ("add_x2_sat r0, c0, -r1", 0.0),         # (.5 - .75) * 2 = -.5 -> 0
])
def test_ps14_instruction_modifiers_shift_then_saturate(text, expected):
    prog = ps(f"ps.1.4\nmov r1, c1\n{text}")
    values = {"c0": (0.5,) * 4, "c1": (0.75,) * 4, "c2": (0.125,) * 4, "c3": (1.0,) * 4,
              "c4": (0.6,) * 4}
    assert out(prog, values) == approx((expected,) * 4)


def test_write_masks_merge_into_the_old_value():
    prog = ps("ps.1.4\nmov r0, c0\nmov r0.gb, c1\nmov r0.r, c2")
    got = out(prog, {"c0": (0.1, 0.2, 0.3, 0.4), "c1": (0.5, 0.6, 0.7, 0.8),
                     "c2": (0.9, 0.0, 0.0, 0.0)})
    assert got == approx((0.9, 0.6, 0.7, 0.4))


def test_coissued_pair_reads_the_state_before_the_pair():
    # add r0.rgb = (.6, .7, .8); +mov r0.a, r0.b reads the old blue .3, not .8
    prog = ps("ps.1.1\nmov r0, c0\nadd r0.rgb, r0, c1\n+mov r0.a, r0.b")
    got = out(prog, {"c0": (0.1, 0.2, 0.3, 0.9), "c1": (0.5,) * 4})
    assert got == approx((0.6, 0.7, 0.8, 0.3))


def test_ps11_final_r0_is_saturated():
    prog = ps("ps.1.1\nadd r0, c0, c0")
    assert out(prog, {"c0": (0.75, -0.5, 0.25, 1.0)}) == approx((1.0, 0.0, 0.5, 1.0))


# -- cnd and cmp -----------------------------------------------------------------------------

@pytest.mark.parametrize("alpha,picks", [(0.6, "c1"), (0.5, "c2"), (0.0, "c2")])
def test_ps11_cnd_tests_r0_alpha_strictly_above_half(alpha, picks):
    prog = ps("ps.1.1\nmov r0, c0\ncnd r0, r0.a, c1, c2")
    values = {"c0": (0.9, 0.9, 0.9, alpha), "c1": (0.1, 0.2, 0.3, 0.4),
              "c2": (0.5, 0.6, 0.7, 0.8)}
    assert out(prog, values) == approx(values[picks])


def test_ps14_cnd_is_per_component():
    prog = ps("ps.1.4\nmov r1, c2\ncnd r0, c0, c1, r1")
    got = out(prog, {"c0": (0.6, 0.5, 0.4, 1.0), "c1": (0.1, 0.2, 0.3, 0.4),
                     "c2": (0.5, 0.6, 0.7, 0.8)})
    assert got == approx((0.1, 0.6, 0.7, 0.4))


def test_ps11_coissued_cnd_writing_colour_always_returns_src1():
    # r0.a is 0 before the pair, so a plain cnd would pick c2; the co-issued one picks c1
    prog = ps("ps.1.1\nmov r0, c0\nmov r0.a, c3\n+cnd r0.rgb, r0.a, c1, c2")
    values = {"c0": (0.0,) * 4, "c1": (0.1, 0.2, 0.3, 0.4), "c2": (0.5, 0.6, 0.7, 0.8),
              "c3": (0.9,) * 4}
    assert out(prog, values) == approx((0.1, 0.2, 0.3, 0.9))
    # a co-issued cnd writing alpha behaves normally: r0.a = 0 -> c2.a
    alpha = ps("ps.1.1\nmov r0, c0\nmov r0.rgb, c3\n+cnd r0.a, r0.a, c1, c2")
    assert out(alpha, values) == approx((0.9, 0.9, 0.9, 0.8))


def test_cmp_takes_the_first_choice_at_zero():
    prog = ps("ps_2_0\nmov r1, c2\ncmp r0, c0, c1, r1\nmov oC0, r0")
    got = out(prog, {"c0": (0.0, -0.25, 0.25, -1.0), "c1": (1.0, 2.0, 3.0, 4.0),
                     "c2": (5.0, 6.0, 7.0, 8.0)})
    assert got == approx((1.0, 6.0, 3.0, 8.0))


def test_ps11_lrp():
    prog = ps("ps.1.1\nmov r1, c2\nlrp r0, c0, c1, r1")
    got = out(prog, {"c0": (0.25, 1.0, 0.0, 0.5), "c1": (1.0,) * 4, "c2": (0.2,) * 4})
    assert got == approx((0.4, 1.0, 0.2, 0.6))        # f + (1 - f) .2


# -- ps_1_1-1_3 texture addressing -----------------------------------------------------------

def test_tex_samples_its_stage_and_honours_projection():
    prog = ps("ps.1.1\ntex t2\nmov r0, t2", projected={2: True})
    got = out(prog, {"texcoord2": (0.2, 0.4, 0.5, 2.0)}, {2: identity_sampler})
    assert got == approx((0.1, 0.2, 0.25, 1.0))


def test_texcoord_saturates_and_sets_w_to_one():
    prog = ps("ps.1.1\ntexcoord t0\nmov r0, t0")
    assert out(prog, {"texcoord0": (-0.5, 0.5, 1.5, 0.3)}) == approx((0.0, 0.5, 1.0, 1.0))


def test_texkill_tests_xyz_in_ps11_and_xyzw_in_ps20():
    coords = np.array([(1, 1, 1, -1), (1, -0.1, 1, 1), (0, 0, 0, 0)], np.float32)
    p11 = run(ps("ps.1.1\ntexkill t0\nmov r0, c0"), {"texcoord0": coords, "c0": (1,) * 4})
    assert p11.killed.tolist() == [False, True, False]
    p20 = run(ps("ps_2_0\ndcl t0\ntexkill t0\nmov oC0, c0"), {"texcoord0": coords,
                                                              "c0": (1,) * 4})
    assert p20.killed.tolist() == [True, True, False]


BUMP = (0.5, -0.25, 0.5, 1.0)            # du, dv, L
BUMPENV1 = (0.5, 0.25, -0.5, 1.0)        # M00, M01, M10, M11 (asymmetric)


def test_texbem_uses_the_destination_stage_matrix():
    # u' = .25 + M00 du + M10 dv = .25 + .25 + .125 = .625
    # v' = .5 + M01 du + M11 dv = .5 + .125 - .25 = .375   (the transpose would give .4375, .5)
    prog = ps("ps.1.1\ntex t0\ntexbem t1, t0\nmov r0, t1")
    assert "bumpenv1" in {i.name for i in prog.inputs}
    assert "bumpenv0" not in {i.name for i in prog.inputs}
    got = out(prog, {"texcoord0": (0, 0, 0, 1), "texcoord1": (0.25, 0.5, 0.0, 1.0),
                     "bumpenv1": BUMPENV1},
              {0: constant_sampler(BUMP), 1: identity_sampler})
    assert got == approx((0.625, 0.375, 0.0, 1.0))


def test_texbem_projected_divides_before_the_offset():
    prog = ps("ps.1.1\ntex t0\ntexbem t1, t0\nmov r0, t1", projected={1: True})
    got = out(prog, {"texcoord0": (0, 0, 0, 1), "texcoord1": (0.5, 1.0, 0.0, 2.0),
                     "bumpenv1": BUMPENV1},
              {0: constant_sampler(BUMP), 1: identity_sampler})
    assert got[:2] == approx((0.625, 0.375))          # (.25, .5) + offset


def test_texbeml_scales_by_clamped_luminance():
    # L' = sat(.5 * .5 + .1) = .35; texel (.625, .375, 0, 1) * .35
    prog = ps("ps.1.1\ntex t0\ntexbeml t1, t0\nmov r0, t1")
    values = {"texcoord0": (0, 0, 0, 1), "texcoord1": (0.25, 0.5, 0.0, 1.0),
              "bumpenv1": BUMPENV1, "bumpenvl1": (0.5, 0.1, 0, 0)}
    samplers = {0: constant_sampler(BUMP), 1: identity_sampler}
    assert out(prog, values, samplers) == approx(np.array((0.625, 0.375, 0.0, 1.0)) * 0.35)
    values["bumpenvl1"] = (10.0, 10.0, 0, 0)           # 15 -> clamped to 1
    assert out(prog, values, samplers) == approx((0.625, 0.375, 0.0, 1.0))


def test_texm3x2tex_coordinates_are_two_dot_products():
    # t0_bx2 = (.5, 0, 1); u = tc1 . n = .1 + .3 = .4; v = tc2 . n = .3 + .2 = .5
    prog = ps("ps.1.1\ntex t0\ntexm3x2pad t1, t0_bx2\ntexm3x2tex t2, t0_bx2\nmov r0, t2")
    got = out(prog, {"texcoord0": (0, 0, 0, 1), "texcoord1": (0.2, 0.4, 0.3, 1),
                     "texcoord2": (0.6, 0.1, 0.2, 1)},
              {0: constant_sampler((0.75, 0.5, 1.0, 1.0)), 2: identity_sampler})
    assert got[:2] == approx((0.4, 0.5))


def _cube_as_colour(seen):
    def sample(coord, kind, bias, lod):
        seen.append(kind)
        return np.array(coord, np.float32) * 0.5 + 0.5
    return sample


@pytest.mark.parametrize("variant", ["spec", "vspec"])
def test_texm3x3spec_reflects_the_eye_vector(variant):
    # t0 = (0, 0, 1) picks tc.z as each row: N = (0, 0, 2); E = (.6, 0, .8)
    # R = 2 N (N.E) / (N.N) - E = 2 (0, 0, 2) 1.6 / 4 - E = (-.6, 0, .8) -> colour (.2, .5, .9)
    extra = ", c0" if variant == "spec" else ""
    prog = ps(f"ps.1.1\ntex t0\ntexm3x3pad t1, t0\ntexm3x3pad t2, t0\n"
              f"texm3x3{variant} t3, t0{extra}\nmov r0, t3")
    seen: list[str] = []
    got = out(prog, {"texcoord0": (0, 0, 0, 1), "texcoord1": (0.3, 0.1, 0.0, 0.6),
                     "texcoord2": (0.2, 0.7, 0.0, 0.0), "texcoord3": (0.9, 0.4, 2.0, 0.8),
                     "c0": (0.6, 0.0, 0.8, 0.0)},
              {0: constant_sampler((0, 0, 1, 1)), 3: _cube_as_colour(seen)})
    assert got[:3] == approx((0.2, 0.5, 0.9))
    assert seen == ["cube"]


def test_texm3x3_texdp3_and_texreg2():
    prog = ps("ps.1.2\ntex t0\ntexm3x3pad t1, t0\ntexm3x3pad t2, t0\ntexm3x3 t3, t0\n"
              "mov r0, t3")
    got = out(prog, {"texcoord0": (0, 0, 0, 1), "texcoord1": (0.1, 0.2, 0.3, 0),
                     "texcoord2": (0.4, 0.5, 0.6, 0), "texcoord3": (0.7, 0.8, 0.9, 0)},
              {0: constant_sampler((1.0, 0.0, 0.5, 1.0))})
    assert got == approx((0.25, 0.7, 1.0, 1.0))       # (x + z/2 per row, 1); 1.15 saturates
    dp3 = ps("ps.1.2\ntex t0\ntexdp3 t1, t0\nmov r0, t1")
    got = out(dp3, {"texcoord0": (0, 0, 0, 1), "texcoord1": (0.2, 0.4, 0.6, 0.0)},
              {0: constant_sampler((0.5, 0.25, 0.5, 1.0))})
    assert got == approx((0.5,) * 4)                  # .1 + .1 + .3
    reg = ps("ps.1.1\ntex t0\ntexreg2ar t1, t0\ntexreg2gb t2, t0\nadd r0, t1, t2")
    seen = []

    def record(coord, kind, bias, lod):
        seen.append(coord[0, :2].tolist())
        return np.zeros_like(coord)
    out(reg, {"texcoord0": (0, 0, 0, 1)}, {0: constant_sampler((0.1, 0.2, 0.3, 0.4)),
                                           1: record, 2: record})
    assert seen == [approx((0.4, 0.1)), approx((0.2, 0.3))]   # (a, r) and (g, b)


def test_depth_from_texm3x2depth_and_texdepth():
    # texm3x2depth: z = tc1 . t0 = .3, w = tc2 . t0 = .6 -> depth .5; w = 0 gives 1
    prog = ps("ps.1.3\ntex t0\ntexm3x2pad t1, t0\ntexm3x2depth t2, t0\nmov r0, c0")
    tc2 = np.array([(0.6, 0, 0, 0), (0, 0, 0, 0)], np.float32)
    res = run(prog, {"texcoord0": np.zeros((2, 4)), "texcoord1": np.tile((0.3, 0, 0, 0), (2, 1)),
                     "texcoord2": tc2, "c0": (1,) * 4},
              {0: constant_sampler((1, 0, 0, 1))})
    assert res.outputs["depth"][:, 0] == approx((0.5, 1.0))
    # texdepth r5: sat(r / min(g, 1)), g = 0 gives 1 (docs/reference/semantics.md 2.6's four probes)
    td = ps("ps.1.4\ntexcrd r5.rgb, t0\nphase\ntexdepth r5\nmov r0, c0")
    rg = np.array([(0.25, 2, 0, 0), (-0.25, -0.5, 0, 0), (-1, 0.1, 0, 0), (0.5, 0, 0, 0)],
                  np.float32)
    res = run(td, {"texcoord0": rg, "c0": (1,) * 4})
    assert res.outputs["depth"][:, 0] == approx((0.25, 0.5, 0.0, 1.0))


# -- ps_1_4 and ps_2_0 texture loads ----------------------------------------------------------

def test_ps14_texld_samples_the_stage_of_its_destination_and_dz_divides():
    prog = ps("ps.1.4\ntexld r2, t0\ntexcrd r3.rgb, t1\nphase\ntexld r1, r3_dz\n"
              "add r0, r2, r1")
    seen = {}

    def at(stage):
        def sample(coord, kind, bias, lod):
            seen[stage] = coord[0].tolist()
            return np.zeros_like(coord)
        return sample
    out(prog, {"texcoord0": (0.1, 0.2, 0.3, 1), "texcoord1": (0.2, 0.4, 0.5, 1)},
        {2: at(2), 1: at(1)})
    assert seen[2] == approx((0.1, 0.2, 0.3, 1.0))
    assert seen[1][:2] == approx((0.4, 0.8))           # (x / z, y / z)


def test_ps14_texcrd_is_unclamped_and_bem_perturbs():
    # bem r1.rg: (.25, .5) + M1 (du, dv) = (.625, .375) as texbem; phase 2 samples stage 1 there
    prog = ps("ps.1.4\ntexld r0, t0\ntexcrd r1.rgb, t1\nbem r1.rg, r1, r0\nphase\n"
              "texld r1, r1\nmov r0, r1")
    got = out(prog, {"texcoord0": (0, 0, 0, 1), "texcoord1": (0.25, 0.5, 0.0, 1.0),
                     "bumpenv1": BUMPENV1},
              {0: constant_sampler(BUMP), 1: identity_sampler})
    assert got[:2] == approx((0.625, 0.375))
    crd = ps("ps.1.4\ntexcrd r0.rgb, t0\nmul r0, r0, c0")
    assert out(crd, {"texcoord0": (3.0, -2.0, 1.5, 1), "c0": (0.25,) * 4})[:3] == approx(
        (0.75, 0.0, 0.375))                            # 3 * .25 (no clamp), -.5 -> 0 at output


def test_ps20_texld_texldp_texldb_and_sampler_kinds():
    prog = ps("ps_2_0\ndcl t0\ndcl_2d s0\ndcl_cube s1\ndcl_volume s2\ntexld r0, t0, s0\n"
              "texldp r1, t0, s0\ntexldb r2, t0, s2\ntexld r3, t0, s1\nadd r0, r0, r1\n"
              "add r0, r0, r2\nadd r0, r0, r3\nmov oC0, r0")
    assert {s.index: s.kind for s in prog.samplers} == {0: "2d", 1: "cube", 2: "3d"}
    calls = []

    def record(coord, kind, bias, lod):
        calls.append((kind, coord[0].tolist(), None if bias is None else float(bias[0])))
        return np.zeros_like(coord)
    out(prog, {"texcoord0": (0.5, 1.0, 1.5, 2.0)}, {0: record, 1: record, 2: record})
    assert ("2d", [0.5, 1.0, 1.5, 2.0], None) in calls
    assert ("2d", [0.25, 0.5, 0.75, 1.0], None) in calls      # texldp: / w
    assert ("3d", [0.5, 1.0, 1.5, 2.0], 2.0) in calls         # texldb: bias = w
    assert ("cube", [0.5, 1.0, 1.5, 2.0], None) in calls


# -- vertex shaders ---------------------------------------------------------------------------

@pytest.mark.parametrize("text,expected", [
    ("rcp r0, c0", 0.5),                 # no swizzle: w = 2 -> .5 (Wine: 0x80)
    ("rsq r0, c0", 1 / np.sqrt(2)),      # 0xb4
    ("rcp r0, c0.x", 4.0),               # the selected component
    ("exp r1, c0\nrcp r0, r1", 0.25),    # 2^2 = 4 -> .25 (0x40)
    ("log r0, c0", 1.0),                 # log2 2 (0xff)
])
def test_vs11_scalar_ops_read_w_by_default(text, expected):
    prog = vs(f"vs.1.1\n{text}\nmov oPos, c0\nmov oT0, r0")
    got = run(prog, {"c0": (0.25, 0.5, 1.0, 2.0)}).outputs["texcoord0"][0]
    assert got == approx((expected,) * 4)


def _relative_values(address: float, extra=None):
    values = {f"c{k}": (float(k),) * 4 for k in range(256)}
    values["c90"] = (address, 0.0, 0.0, 0.0)
    return values


@pytest.mark.parametrize("address,register", [(-2.4, 2), (-0.4, 4), (1.6, 6), (0.0, 5)])
def test_vs11_mov_a0_floors(address, register):
    # c[a0.x + 5] with a0.x = floor(address): -3 -> c2, -1 -> c4, 1 -> c6
    prog = vs("vs.1.1\nmov a0.x, c90.x\nmov oPos, c0\nmov oT0, c[a0.x + 5]")
    got = run(prog, _relative_values(address)).outputs["texcoord0"][0]
    assert got == approx((register,) * 4)


@pytest.mark.parametrize("address,register", [(-2.4, 3), (-1.6, 3), (1.6, 7), (-0.5, 4)])
def test_vs20_mova_rounds_half_away_from_zero(address, register):
    # -2.4 -> -2, -1.6 -> -2, 1.6 -> 2, -0.5 -> -1; offset 5
    prog = vs("vs_2_0\ndcl_position v0\nmova a0.x, c90.x\nmov oPos, v0\nmov oT0, c[a0.x + 5]")
    values = _relative_values(address)
    values["position"] = (0, 0, 0, 1)
    got = run(prog, values).outputs["texcoord0"][0]
    assert got == approx((register,) * 4)


def test_relative_address_out_of_range_reads_zero():
    prog = vs("vs.1.1\nmov a0.x, c90.x\nmov oPos, c0\nmov oT0, c[a0.x + 5]")
    got = run(prog, _relative_values(-10.0)).outputs["texcoord0"][0]
    assert got == approx((0, 0, 0, 0))
    assert constant_registers(assemble_valid(
        "vs.1.1\nmov a0.x, c90.x\nmov oPos, c0\nmov oT0, c[a0.x + 5]", "vertex")) == set(range(96))


def test_vs_matrix_macros_match_numpy():
    rng = np.random.default_rng(7)
    m = rng.uniform(-2, 2, (4, 4)).astype(np.float32)
    pos = rng.uniform(-3, 3, (5, 4)).astype(np.float32)
    prog = vs("vs.1.1\ndcl_position v0\nm4x4 oPos, v0, c4\nm3x3 r0.xyz, v0, c4\nmov oT0, r0\n"
              "m3x2 oT1.xy, v0, c5")
    values = {"position": pos, **{f"c{4 + i}": m[i] for i in range(4)}}
    res = run(prog, values)
    assert res.outputs["position"] == approx(pos @ m.T, rel=1e-5, abs=1e-5)
    m3 = pos[:, :3] @ m[:3, :3].T
    assert res.outputs["texcoord0"][:, :3] == approx(m3, rel=1e-5, abs=1e-5)
    assert res.outputs["texcoord0"][:, 3] == approx(np.zeros(5))       # r0.w never written
    assert res.outputs["texcoord1"][:, :2] == approx(pos[:, :3] @ m[1:3, :3].T, abs=1e-5)
    assert res.outputs["texcoord1"][:, 2:] == approx(np.tile((0, 1), (5, 1)))  # default z, w


@pytest.mark.parametrize("c0,expected", [
    ((0.5, 0.25, 0.0, 2.0), (1.0, 0.5, 0.0625, 1.0)),    # .25 ^ 2
    ((-0.5, 0.25, 0.0, 2.0), (1.0, 0.0, 0.0, 1.0)),      # n.l <= 0: no specular
    ((0.5, -0.25, 0.0, 2.0), (1.0, 0.5, 0.0, 1.0)),      # max(n.h, 0) = 0
    ((1.0, 0.5, 0.0, 200.0), (1.0, 1.0, 0.5 ** 128, 1.0)),   # power clamped to 128
])
def test_vs_lit(c0, expected):
    prog = vs("vs.1.1\nmov oPos, c0\nlit oT0, c0")
    got = run(prog, {"c0": c0}).outputs["texcoord0"][0]
    assert got == approx(expected, rel=1e-5, abs=1e-30)


def test_vs11_dst_expp_logp_frc_sge_slt():
    # vs_1_1 reads one c# per instruction: c0 goes through r0
    prog = vs("vs.1.1\nmov oPos, c0\nmov r0, c0\ndst oT0, r0, c1\nexpp oT1, c2.x\n"
              "logp oT2, c2.y\nfrc oT3.xy, c2\nsge oT4, r0, c1\nslt oT5, r0, c1")
    res = run(prog, {"c0": (9.0, 2.0, 3.0, 4.0), "c1": (5.0, 6.0, 7.0, 8.0),
                     "c2": (2.5, -10.0, 0.0, 0.0)}).outputs
    assert res["texcoord0"][0] == approx((1.0, 12.0, 3.0, 8.0))         # (1, a.y b.y, a.z, b.w)
    assert res["texcoord1"][0] == approx((4.0, 0.5, 2 ** 2.5, 1.0))      # 2^floor, frac, 2^x
    assert res["texcoord2"][0] == approx((3.0, 1.25, np.log2(10), 1.0))  # |-10| = 1.25 * 2^3
    assert res["texcoord3"][0] == approx((0.5, 0.0, 0.0, 1.0))          # frc (2.5, -10)
    assert res["texcoord4"][0] == approx((1.0, 0.0, 0.0, 0.0))
    assert res["texcoord5"][0] == approx((0.0, 1.0, 1.0, 1.0))


def test_vs_outputs_colours_saturated_and_defaults_filled():
    prog = vs("vs.1.1\ndcl_position v0\ndcl_texcoord0 v7\nmov oPos, v0\nmov oD0, c0\n"
              "mov oD1.xyz, c0\nmov oT0.xy, v7.xy\nmov oFog, c1.y\nmov oPts, c1.x")
    assert [name for name, _ in prog.outputs] == ["position", "color0", "color1", "texcoord0",
                                                  "fog", "psize"]
    res = run(prog, {"position": (1, 2, 3, 1), "texcoord0": (0.25, 0.75, 0.5, 0.5),
                     "c0": (2.0, -1.0, 0.5, 0.25), "c1": (4.0, 0.5, 0, 0)}).outputs
    assert res["color0"][0] == approx((1.0, 0.0, 0.5, 0.25))
    assert res["color1"][0] == approx((1.0, 0.0, 0.5, 0.0))       # default alpha 0 (specular)
    assert res["texcoord0"][0] == approx((0.25, 0.75, 0.0, 1.0))  # unwritten zw: (.., 0, 1)
    assert res["fog"][0][0] == approx(0.5) and res["psize"][0][0] == approx(4.0)
    v3 = vs("vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_color0 o1\nmov o0, v0\nmov o1, c0")
    got = run(v3, {"position": (0, 0, 0, 1), "c0": (2.0, -1.0, 0.5, 0.25)}).outputs
    assert got["color0"][0] == approx((2.0, -1.0, 0.5, 0.25))     # vs_3_0 does not saturate


def test_vertex_inputs_named_by_usage_or_by_the_dx8_registers():
    named = vs("vs_2_0\ndcl_position v0\ndcl_texcoord3 v4\ndcl_normal1 v2\n"
               "mov oPos, v0\nmov r0, v2\nadd oT0, v4, r0")
    assert {i.name for i in named.inputs} == {"position", "texcoord3", "normal1"}
    fixed = vs("vs.1.1\nmov oPos, v0\nmov oT0, v3\nmov oT1, v5\nmov oT2, v6\nmov oT3, v7\n"
               "mov oT4, v14")
    assert {i.name for i in fixed.inputs} == {"position", "normal", "color0", "color1",
                                              "texcoord0", "texcoord7"}
    decl = tuple(VertexDeclElement(0, "float", r, n) for r, n in ((0, 3), (3, 3), (7, 2)))
    dx8 = vs("vs.1.1\nmov oPos, v0\nmov oT0, v3\nmov oT1, v7", decl=decl)
    assert {(i.name, i.components) for i in dx8.inputs} == {
        ("position", 3), ("normal", 3), ("texcoord0", 2)}


def test_constant_registers_lists_what_the_pass_supplies():
    by_name = {s[0]: s for s in SEEDS}
    _, src, stage, decl, _ = by_name["boyd brdf vs"]
    # m4x4 c4-c7, m4x4 and m3x3 c0-c3, c10, c16, c9
    assert constant_registers(assemble_valid(src, stage, decl)) == {*range(8), 9, 10, 16}
    _, src, stage, decl, _ = by_name["persson shadow vs"]
    # c0-c3 matrix, c4 camera, c5 light; c8-c10 are def'd
    assert constant_registers(assemble_valid(src, stage, decl)) == {0, 1, 2, 3, 4, 5}
    _, src, stage, decl, _ = by_name["persson final ps"]
    assert constant_registers(assemble_valid(src, stage, decl)) == {2}


# -- precision --------------------------------------------------------------------------------

X16 = "ps.1.1\nmov r0, c0\nmul r1, r0, r0\nmul r0, r1, r1\nmul r1, r0, r0\nmul r0, r1, r1"


def test_repeated_squaring_bands_on_the_geforce3_grid():
    # 8 fraction bits, range 1: every result rounds to n/255. x = 230/255:
    # 230^2/255 = 207.45 -> 207; 207^2/255 = 168.04 -> 168; 168^2/255 = 110.68 -> 111;
    # 111^2/255 = 48.32 -> 48. Float: (230/255)^16 = 0.19188
    x = 230 / 255
    fixed = out(ps(X16, GEFORCE3), {"c0": (x,) * 4})
    assert fixed == approx((48 / 255,) * 4, rel=0, abs=1e-6)
    exact = out(ps(X16, FLOAT), {"c0": (x,) * 4})
    assert exact == approx((x ** 16,) * 4, rel=1e-5)
    assert abs(x ** 16 - 48 / 255) > 0.9 / 255


def test_repeated_squaring_matches_integer_arithmetic_on_the_grid():
    # An independent integer model of the 8-bit grid: n/255 squared is round(n * n / 255)/255
    # (halves away from zero). x^16 is four squarings after the exact mov.
    def square(n: int) -> int:
        return (2 * n * n + 255) // 510
    codes = np.arange(180, 256)
    expected = []
    for n in codes:
        for _ in range(4):
            n = square(int(n))
        expected.append(n / 255)
    prog = ps(X16, GEFORCE3)
    res = run(prog, {"c0": np.repeat((codes / 255)[:, None], 4, axis=1)},
              count=len(codes)).outputs["color0"]
    assert res[:, 0] == approx(expected, rel=0, abs=1e-6)
    # banding: 76 distinct inputs give far fewer distinct outputs than the float pipeline
    assert len(set(expected)) < 60
    assert len(set(np.round(res[:, 0], 6))) == len(set(expected))


def test_geforce3_register_range_clamps_intermediates():
    # .75 + .75 = 1.5 clamps to 1 in the register, then 1 - .5 = .5, which lies halfway
    # between grid steps 127/255 and 128/255 and rounds up to 128/255 (float: 1.0)
    prog = "ps.1.1\nadd r0, c0, c0\nsub r0, r0, c1"
    values = {"c0": (0.75,) * 4, "c1": (0.5,) * 4}
    assert out(ps(prog, GEFORCE3), values) == approx((128 / 255,) * 4)
    assert out(ps(prog, FLOAT), values) == approx((1.0,) * 4)


def test_ps14_grid_includes_the_integer_range():
    # 12 fraction bits over [-8, 8]: quantize bits 12 + 3 + 1 (sign) = 16, scale 8
    prog = ps("ps.1.4\nadd r0, c0, c0", LoweringOptions(ps14_bits=12, ps14_range=8.0))
    q = [i for i in prog.instrs if i.op == "quantize"]
    assert [(i.attr("bits"), i.attr("signed"), i.attr("scale")) for i in q] == [(16, True, 8.0)]
    assert not any(i.op == "quantize" for i in ps(
        "ps_2_0\nadd r0, c0, c0\nmov oC0, r0", GEFORCE3).instrs)   # ps_2_0 stays float


# -- errors -----------------------------------------------------------------------------------

def test_vertex_if_on_a_boolean_constant_lowers():
    # defb b0, true: the if's block runs, so oD0 = v0 (saturated below vs_3_0)
    prog = vs("vs_2_0\ndcl_position v0\ndefb b0, true\nmov oPos, v0\nif b0\n"
              "mov oD0, v0\nendif")
    got = run(prog, {"position": (0.25, 2.0, 0.5, 1.0)}).outputs
    assert got["color0"][0] == approx((0.25, 1.0, 0.5, 1.0))


def test_wrong_stage_is_an_error():
    with pytest.raises(AsmError, match="not a vertex shader"):
        lower_vertex_shader(assemble_valid("ps.1.1\nmov r0, c0"), ShaderContext(FLOAT))


# -- golden printed IR of the seed listings ---------------------------------------------------

def _golden_name(name: str) -> str:
    return "asm_" + re.sub(r"[^a-z0-9]+", "_", name.lower()).strip("_") + ".txt"


@pytest.mark.parametrize("name,src,stage,decl,version", SEEDS, ids=[s[0] for s in SEEDS])
def test_seed_listing_golden_ir(name, src, stage, decl, version):
    # ps_1_x listings are lowered at the GeForce3's precision (8 bits, range 1), the rest float
    prog = assemble_valid(src, stage, decl)
    fixed = stage == "pixel" and version.startswith("ps_1")
    ctx = ShaderContext(GEFORCE3 if fixed else FLOAT, decl=decl)
    lower = lower_pixel_shader if stage == "pixel" else lower_vertex_shader
    text = f"; {name} ({version}, {'geforce3 precision' if fixed else 'float'})\n{lower(prog, ctx)}"
    path = GOLDEN / _golden_name(name)
    if os.environ.get("UPDATE_GOLDEN"):
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    assert path.exists(), f"{path} missing: run with UPDATE_GOLDEN=1"
    assert text == path.read_text()


def test_boyd_specular_on_the_geforce3_shows_banding():
    # Boyd's x^16 specular, lowered from the listing: n.h = .9 gives (quantised) 48/255 ...
    by_name = {s[0]: s for s in SEEDS}
    src = by_name["boyd specular ps"][1]
    prog = ps(src, GEFORCE3)
    # t1 = (1, .5, .5) -> bx2 (1, 0, 0); v1 bx2 = 2 (v - .5): v1.x = 230/255 ... choose
    # v1 = (.5 + 115/255, .5, .5) so the dot is 230/255 exactly on the grid
    v1 = (0.5 + 115 / 255, 0.5, 0.5, 1.0)
    got = out(prog, {"texcoord0": (0, 0, 0, 1), "texcoord1": (0, 0, 0, 1), "color1": v1},
              {0: constant_sampler((1, 1, 1, 1)), 1: constant_sampler((1.0, 0.5, 0.5, 1.0))})
    assert got[:3] == approx((48 / 255,) * 3, rel=0, abs=1e-6)


def test_relative_inputs_lower_to_a_select_over_the_declared_ones():
    # v[aL] with aL = 0, 1 reaches v0 (declared) and v1 (not declared: never selected, reads
    # 0); hand values on both back ends are in test_flow.test_inputs_and_outputs_addressed_by_al
    prog = assemble_valid("vs_3_0\ndcl_position v0\ndcl_position o0\ndefi i0, 2, 0, 1, 0\n"
                          "mov r0, v0\nloop aL, i0\nadd r0, r0, v[aL]\nendloop\nmov o0, r0",
                          "vertex")
    assert lowering_problems(prog) == []
    vertex = lower_vertex_shader(prog, ShaderContext(LoweringOptions()))
    assert [i.name for i in vertex.inputs] == ["position"]


@pytest.mark.parametrize("name,src", VALID, ids=[v[0] for v in VALID])
def test_every_valid_program_lowers_or_says_what_is_not_lowered(name, src):
    # `lowering_problems` (what validation rejects) is exactly what the lowering refuses.
    stage = "vertex" if src.startswith("vs") else "pixel"
    prog = assemble_valid(src, stage)
    lower = lower_vertex_shader if stage == "vertex" else lower_pixel_shader
    problems = lowering_problems(prog)
    try:
        program = lower(prog, ShaderContext(GEFORCE3))
    except AsmError as err:
        assert "not lowered yet" in str(err) and err.location.line > 1
        assert str(err) in [str(p) for p in problems]
        return
    assert not problems
    assert program.outputs            # a program that writes nothing would be a lowering bug


def test_every_row_says_how_it_lowers():
    from effects.shaders.asm import INSTRUCTIONS
    from effects.shaders.asm.instructions import Handler, NoCode, NotLowered, Rewrite
    for row in INSTRUCTIONS:
        assert isinstance(row.lowers, (Rewrite, Handler, NoCode, NotLowered)), row.name
        assert bool(row.matrix_rows) == (row.name.startswith("m") and row.name[1:2].isdigit())
        if row.category == "setup":
            assert isinstance(row.lowers, NoCode), row.name


def test_validation_rejects_what_does_not_lower():
    # A vs_2_0 loop validates and lowers on a Radeon 9700, and so does a rep on an integer
    # constant the application sets (the pass's VertexShaderConstantI, here unset: 0
    # iterations).
    from effects import load_effect, load_profile
    text = ("technique T { pass P { VertexShader = asm {\n"
            "vs_2_0\ndcl_position v0\ndefi i0, 3, 0, 1, 0\nmov r0, v0\n"
            "loop aL, i0\nadd r0, r0, c0\nendloop\nrep i1\nendrep\n"
            "mov oPos, r0\n}; } }")
    assert load_effect(text).validate("T", load_profile("radeon9700")).ok
    # what does not lower (a gradient inside a dynamic if, X4014) makes a shader invalid
    effect = load_effect("technique T { pass P { PixelShader = asm {\n"
                         "ps_3_0\ndcl vPos.xy\ndef c0, 4, 0, 0, 0\nif_lt vPos.x, c0.x\n"
                         "dsx r0, vPos\nendif\nmov oC0, c0\n};\n"
                         "VertexShader = asm { vs_3_0\ndcl_position v0\ndcl_position o0\n"
                         "mov o0, v0 }; } }")
    result = effect.validate("T", load_profile("refrast"))
    assert not result.ok
    assert [str(r) for r in result.reasons] == [
        "pass P (line 6): dsx: gradients inside dynamic flow control are undefined (X4014: "
        "move it out of the if or loop, or use texldl / texldd)"]
