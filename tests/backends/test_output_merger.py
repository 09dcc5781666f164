"""The output merger: every blend factor and op against hand arithmetic, alpha test at the
boundary, depth and stencil tests and ops, colour write mask, the UNORM8 write, float targets,
and exact draw-order merging of fragments that overlap within one draw."""
from dataclasses import replace

import numpy as np
import pytest

from effects.program.backend import DrawError
from backends.reference.output import Framebuffer, alpha_test, layers, merge
from effects.program.passprogram import RenderState

# Source and destination chosen as multiples of 1/255 apart from where noted, so the 8-bit
# destination holds them exactly.
SRC = np.array([0.6, 0.4, 0.2, 0.35], np.float32)
DST = np.array([51, 102, 255, 204], np.float32) / 255          # (0.2, 0.4, 1.0, 0.8)
FACTOR = (0.4, 0.3, 1.0, 0.75)


def blended(**state):
    """The stored (8-bit) result of blending SRC over DST with the given states."""
    fb = Framebuffer.create((1, 1), clear_color=DST)
    rs = RenderState(alpha_blend_enable=True, blend_factor=FACTOR, **state)
    merge(fb, rs, np.array([0]), SRC[None], np.array([0.5], np.float32), np.array([True]))
    return fb.values()[0, 0]


def unorm(x):
    return np.rint(np.clip(np.asarray(x, np.float64), 0, 1) * 255) / 255


s_r, s_g, s_b, s_a = SRC
d_r, d_g, d_b, d_a = DST
FACTORS = {
    "ZERO": [0, 0, 0, 0],
    "ONE": [1, 1, 1, 1],
    "SRCCOLOR": [s_r, s_g, s_b, s_a],
    "INVSRCCOLOR": [1 - s_r, 1 - s_g, 1 - s_b, 1 - s_a],
    "SRCALPHA": [s_a] * 4,
    "INVSRCALPHA": [1 - s_a] * 4,
    "DESTALPHA": [d_a] * 4,
    "INVDESTALPHA": [1 - d_a] * 4,
    "DESTCOLOR": [d_r, d_g, d_b, d_a],
    "INVDESTCOLOR": [1 - d_r, 1 - d_g, 1 - d_b, 1 - d_a],
    "SRCALPHASAT": [min(s_a, 1 - d_a)] * 3 + [1],     # f = min(As, 1 - Ad) = 0.2; alpha 1
    "BLENDFACTOR": list(FACTOR),
    "INVBLENDFACTOR": [1 - f for f in FACTOR],
}


@pytest.mark.parametrize("name", sorted(FACTORS))
def test_each_source_blend_factor(name):
    # src * factor + dst * 0
    expected = unorm(SRC * np.array(FACTORS[name]))
    np.testing.assert_allclose(blended(src_blend=name, dest_blend="ZERO"), expected, atol=1e-6)


@pytest.mark.parametrize("name", sorted(FACTORS))
def test_each_destination_blend_factor(name):
    # src * 0 + dst * factor
    expected = unorm(DST * np.array(FACTORS[name]))
    np.testing.assert_allclose(blended(src_blend="ZERO", dest_blend=name), expected, atol=1e-6)


def test_both_src_alpha_factors_set_the_destination_too():
    # BOTHSRCALPHA: src * As + dst * (1 - As), whatever DestBlend says
    expected = unorm(SRC * s_a + DST * (1 - s_a))
    np.testing.assert_allclose(blended(src_blend="BOTHSRCALPHA", dest_blend="ONE"), expected,
                               atol=1e-6)
    expected = unorm(SRC * (1 - s_a) + DST * s_a)
    np.testing.assert_allclose(blended(src_blend="BOTHINVSRCALPHA", dest_blend="ZERO"),
                               expected, atol=1e-6)


@pytest.mark.parametrize("op, expected", [
    ("ADD", SRC * s_a + DST * (1 - s_a)),
    ("SUBTRACT", SRC * s_a - DST * (1 - s_a)),          # clamps to 0 where negative
    ("REVSUBTRACT", DST * (1 - s_a) - SRC * s_a),
    ("MIN", np.minimum(SRC, DST)),                      # factors ignored
    ("MAX", np.maximum(SRC, DST)),
])
def test_each_blend_op(op, expected):
    got = blended(src_blend="SRCALPHA", dest_blend="INVSRCALPHA", blend_op=op)
    np.testing.assert_allclose(got, unorm(expected), atol=1e-6)


def test_separate_alpha_blend():
    got = blended(src_blend="ONE", dest_blend="ONE", separate_alpha_blend_enable=True,
                  src_blend_alpha="ZERO", dest_blend_alpha="DESTALPHA",
                  blend_op_alpha="ADD")
    # rgb: src + dst (saturating), alpha: dst.a * dst.a
    np.testing.assert_allclose(got[:3], unorm(SRC[:3] + DST[:3]), atol=1e-6)
    np.testing.assert_allclose(got[3], unorm(d_a * d_a), atol=1e-6)
    # without the separate flag the alpha channel follows the colour factors
    got = blended(src_blend="ONE", dest_blend="ONE", src_blend_alpha="ZERO",
                  dest_blend_alpha="DESTALPHA")
    np.testing.assert_allclose(got[3], unorm(s_a + d_a), atol=1e-6)


def test_unorm_source_is_saturated_before_blending():
    fb = Framebuffer.create((1, 1), clear_color=(0.5, 0.5, 0.5, 0.5))
    rs = RenderState(alpha_blend_enable=True, src_blend="ONE", dest_blend="ONE",
                     blend_op="REVSUBTRACT")
    # the clear stores 0.5 as 128/255; dst - sat(src): 128/255 - 1 -> 0 (clamped),
    # 128/255 - 0 (src -2 saturated to 0), 128/255 - 0.25
    merge(fb, rs, np.array([0]), np.array([[3.0, -2.0, 0.25, 0.25]], np.float32),
          np.array([0.5], np.float32), np.array([True]))
    half = 128 / 255
    np.testing.assert_allclose(fb.values()[0, 0], unorm([0, half, half - 0.25, half - 0.25]),
                               atol=1e-6)


def test_unorm_write_rounds_to_nearest():
    fb = Framebuffer.create((4, 1))
    colours = np.array([[0.1, 0.0019, 0.002, 1.5], [-1, 0.5 + 1e-3, 254.6 / 255, 0.25]] * 2,
                       np.float32)
    merge(fb, RenderState(), np.arange(4), colours, np.full(4, 0.5, np.float32),
          np.ones(4, bool))
    image = fb.image()
    # round(0.1*255 = 25.5) = 26 (0.1 is a hair above in float32), 0.0019*255 = 0.48 -> 0,
    # 0.51 -> 1, 1.5 -> 255; -1 -> 0, 127.76 -> 128, 254.6 -> 255, 63.75 -> 64
    np.testing.assert_array_equal(image[0, 0], [26, 0, 1, 255])
    np.testing.assert_array_equal(image[0, 1], [0, 128, 255, 64])


@pytest.mark.parametrize("func, passes", [
    # fragment alpha 128/255 -> 128, 127/255 -> 127, 129/255 -> 129 against AlphaRef 128
    ("NEVER", [False, False, False]), ("LESS", [False, True, False]),
    ("EQUAL", [True, False, False]), ("LESSEQUAL", [True, True, False]),
    ("GREATER", [False, False, True]), ("NOTEQUAL", [False, True, True]),
    ("GREATEREQUAL", [True, False, True]), ("ALWAYS", [True, True, True]),
])
def test_alpha_test_at_the_boundary(func, passes):
    alpha = np.array([128, 127, 129], np.float32) / 255
    np.testing.assert_array_equal(alpha_test(alpha, func, 128), passes)
    fb = Framebuffer.create((3, 1))
    rs = RenderState(alpha_test_enable=True, alpha_func=func, alpha_ref=128)
    colours = np.column_stack([np.ones((3, 3), np.float32), alpha])
    merge(fb, rs, np.arange(3), colours, np.full(3, 0.5, np.float32), np.ones(3, bool))
    np.testing.assert_array_equal(fb.image()[0, :, 0] == 255, passes)


def test_colour_write_mask():
    fb = Framebuffer.create((1, 1), clear_color=DST)
    merge(fb, RenderState(color_write_enable=0b0101), np.array([0]), SRC[None],
          np.array([0.5], np.float32), np.array([True]))
    # red (bit 0) and blue (bit 2) written; green and alpha keep the destination
    np.testing.assert_allclose(fb.values()[0, 0], unorm([s_r, d_g, s_b, d_a]), atol=1e-6)
    fb = Framebuffer.create((1, 1), clear_color=DST)
    merge(fb, RenderState(color_write_enable=0), np.array([0]), SRC[None],
          np.array([0.5], np.float32), np.array([True]))
    np.testing.assert_allclose(fb.values()[0, 0], DST, atol=1e-6)


def draw_depth(fb, rs, value, z):
    n = fb.color.shape[0] * fb.color.shape[1]
    merge(fb, rs, np.arange(n), np.tile(np.array(value, np.float32), (n, 1)),
          np.full(n, z, np.float32), np.ones(n, bool))


@pytest.mark.parametrize("func, z, written", [
    ("LESSEQUAL", 0.5, True), ("LESSEQUAL", 0.6, False), ("LESS", 0.5, False),
    ("LESS", 0.4, True), ("EQUAL", 0.5, True), ("GREATER", 0.6, True), ("NEVER", 0.0, False),
    ("ALWAYS", 0.9, True), ("NOTEQUAL", 0.5, False), ("GREATEREQUAL", 0.4, False),
])
def test_depth_functions(func, z, written):
    fb = Framebuffer.create((2, 2), clear_depth=0.5)
    draw_depth(fb, RenderState(z_func=func), (1, 1, 1, 1), z)
    assert (fb.image()[..., 0] == 255).all() == written
    np.testing.assert_array_equal(fb.depth, np.float32(z if written else 0.5))


def test_depth_write_disable_and_z_enable_off():
    fb = Framebuffer.create((2, 2), clear_depth=0.5)
    draw_depth(fb, RenderState(z_write_enable=False), (1, 0, 0, 1), 0.25)
    assert (fb.image()[..., 0] == 255).all() and (fb.depth == 0.5).all()
    # ZEnable off: the test passes whatever the depth and nothing is written
    draw_depth(fb, RenderState(z_enable=False), (0, 1, 0, 1), 0.9)
    assert (fb.image()[..., 1] == 255).all() and (fb.depth == 0.5).all()


def stencil_pass(fb, rs, pixels, value=(1, 1, 1, 1), front=True, z=0.5):
    n = len(pixels)
    merge(fb, rs, np.asarray(pixels), np.tile(np.array(value, np.float32), (n, 1)),
          np.full(n, z, np.float32), np.full(n, front))


def test_stencil_increment_then_test():
    fb = Framebuffer.create((4, 1))
    inc = RenderState(stencil_enable=True, stencil_pass="INCR", color_write_enable=0)
    stencil_pass(fb, inc, [1, 2])
    stencil_pass(fb, inc, [2, 3])
    np.testing.assert_array_equal(fb.stencil[0], [0, 1, 2, 1])
    test = RenderState(stencil_enable=True, stencil_func="EQUAL", stencil_ref=1)
    stencil_pass(fb, test, [0, 1, 2, 3])
    np.testing.assert_array_equal(fb.image()[0, :, 0], [0, 255, 0, 255])


def test_stencil_ops_masks_and_depth_fail():
    fb = Framebuffer.create((8, 1), clear_stencil=0b1010_0101, clear_depth=0.5)
    ops = ["KEEP", "ZERO", "REPLACE", "INCRSAT", "DECRSAT", "INVERT", "INCR", "DECR"]
    v = 0b1010_0101
    expected = [v, 0, 0x3C, v + 1, v - 1, (~v) & 0xFF, v + 1, v - 1]
    for i, op in enumerate(ops):
        stencil_pass(fb, RenderState(stencil_enable=True, stencil_pass=op, stencil_ref=0x3C),
                     [i])
    np.testing.assert_array_equal(fb.stencil[0], expected)
    # saturation and wrap at the ends
    fb = Framebuffer.create((4, 1), clear_stencil=255)
    for i, op in enumerate(["INCRSAT", "INCR"]):
        stencil_pass(fb, RenderState(stencil_enable=True, stencil_pass=op), [i])
    fb.stencil[0, 2:] = 0
    for i, op in enumerate(["DECRSAT", "DECR"]):
        stencil_pass(fb, RenderState(stencil_enable=True, stencil_pass=op), [2 + i])
    np.testing.assert_array_equal(fb.stencil[0], [255, 0, 0, 255])
    # write mask 0x0F: only the low bits change; read mask on the test: (ref & mask) vs
    # (stencil & mask)
    fb = Framebuffer.create((2, 1), clear_stencil=0xA5)
    rs = RenderState(stencil_enable=True, stencil_pass="ZERO", stencil_write_mask=0x0F,
                     stencil_func="EQUAL", stencil_ref=0x05, stencil_mask=0x0F)
    stencil_pass(fb, rs, [0])
    assert fb.stencil[0, 0] == 0xA0
    # stencil fail and depth fail pick their own ops
    fb = Framebuffer.create((2, 1), clear_depth=0.5)
    rs = RenderState(stencil_enable=True, stencil_func="EQUAL", stencil_ref=1,
                     stencil_fail="REPLACE", stencil_zfail="INVERT", stencil_pass="ZERO")
    stencil_pass(fb, rs, [0])                           # stencil 0 != 1 -> fail -> REPLACE
    assert fb.stencil[0, 0] == 1 and fb.image()[0, 0, 0] == 0
    stencil_pass(fb, rs, [0], z=0.9)                    # passes stencil, fails depth -> INVERT
    assert fb.stencil[0, 0] == 0xFE and fb.image()[0, 0, 0] == 0


def test_two_sided_stencil_uses_the_ccw_ops_for_back_faces():
    fb = Framebuffer.create((2, 1))
    rs = RenderState(stencil_enable=True, two_sided_stencil_mode=True, stencil_pass="INCR",
                     ccw_stencil_pass="DECR", color_write_enable=0)
    stencil_pass(fb, rs, [0], front=True)
    stencil_pass(fb, rs, [1], front=False)
    np.testing.assert_array_equal(fb.stencil[0], [1, 255])


def test_fragments_overlapping_in_one_draw_merge_in_draw_order():
    # Three fragments on pixel 0 and one on pixel 1, in draw order; blend dst*0.5 + src
    fb = Framebuffer.create((2, 1))
    rs = RenderState(alpha_blend_enable=True, src_blend="ONE", dest_blend="SRCALPHA",
                     z_enable=False)
    colours = np.array([[0.8, 0, 0, 0.5], [0, 0.8, 0, 0.5], [0.2, 0, 0, 0.5],
                        [0, 0, 0.4, 0.5]], np.float32)
    merge(fb, rs, np.array([0, 0, 1, 0]), colours[[0, 1, 3, 2]], np.full(4, 0.5, np.float32),
          np.ones(4, bool))
    # pixel 0: r = 0.8 -> 0.8*0.5 + 0 = 0.4 -> 0.2 + 0.2 = 0.4; g = 0.8*0.5 = 0.4
    r = unorm(0.2 + unorm(unorm(0.8) * 0.5) * 0.5)
    g = unorm(unorm(0.8) * 0.5)
    np.testing.assert_allclose(fb.values()[0, 0, :2], [r, g], atol=1e-6)
    np.testing.assert_allclose(fb.values()[0, 1, 2], unorm(0.4), atol=1e-6)


def test_layers_split_by_pixel_occurrence():
    pieces = layers(np.array([5, 3, 5, 5, 3, 7]), 8)
    assert [p.tolist() for p in pieces] == [[0, 1, 5], [2, 4], [3]]
    assert [p.tolist() for p in layers(np.array([2, 0, 1]), 3)] == [[0, 1, 2]]


def test_float_targets_keep_values_outside_0_1():
    fb = Framebuffer.create((2, 1), format="R32F")
    merge(fb, RenderState(), np.array([0, 1]), np.array([[12.5, 3, 4, 5], [-0.25, 0, 0, 0]],
                                                        np.float32),
          np.full(2, 0.5, np.float32), np.ones(2, bool))
    image = fb.image()
    assert image.dtype == np.float32
    # R32F stores red only; the other channels read 1, as an R32F texture samples
    np.testing.assert_array_equal(image[0], [[12.5, 1, 1, 1], [-0.25, 1, 1, 1]])
    fb = Framebuffer.create((1, 1), format="A16B16G16R16F")
    merge(fb, RenderState(), np.array([0]), np.array([[1 / 3, 2.0, 1000.7, -1]], np.float32),
          np.full(1, 0.5, np.float32), np.ones(1, bool))
    np.testing.assert_array_equal(fb.image()[0, 0],
                                  np.array([1 / 3, 2.0, 1000.7, -1], np.float16))


def test_render_state_errors_are_draw_errors():
    fb = Framebuffer.create((1, 1))
    with pytest.raises(DrawError):
        merge(fb, RenderState(z_func="SOMETIMES"), np.array([0]), SRC[None],
              np.array([0.5], np.float32), np.array([True]))
    with pytest.raises(DrawError):
        Framebuffer.create((1, 1), format="D24S8")
    with pytest.raises(DrawError):
        blended(src_blend="SRCALPHA", dest_blend="HALF")
    assert replace(RenderState(), z_func="LESS").z_func == "LESS"
