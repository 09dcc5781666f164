"""One rendering suite, every back end: the same scene-level tests run on the NumPy reference
and on the GL back end (the `backend` fixture), each pixel checked against a value worked out
by hand from the Direct3D 9 rules (docs/design.md habit 8).

Covered: D3D9 pixel centres, the top-left fill rule and shared edges, depth order and depth
functions, clip-space depth range, each blend factor, op and separate alpha blend, the alpha
test, colour write mask, stencil, cull modes and vface, flat shading, colour saturation,
point/bilinear/mip-mapped texture filtering with every address mode, cube faces (sampling and
rendering into), volume, 1D and projected lookups, sRGB textures, kill, vpos, vertex
programs, fog and specular add, float targets, multipass accumulation, and a lit surface
against the lighting formula, the registry and bad draw calls. What only one back end has
(GL's program cache and buffer reuse; the reference's threads and fast paths) is tested in
tests/backends/test_gl_renderer.py and tests/backends/test_reference_renderer.py.

GL is required: without a context the gl cases fail with GLUnavailable; nothing is skipped.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import effects
from effects.program.backend import (Backend, DrawError, UnknownBackend, available_backends,
                           create_backend, render_cube_faces)
from backends.gl import GLBackend
from backends.reference.renderer import ReferenceBackend
from effects.d3d9.caps import load_profile
from effects.base.errors import EffectError
from effects.lower.passes import lower_pass
from effects.program.ir import Builder
from effects.program.passprogram import PassProgram, RenderState, TextureBinding
from effects.program.texture import Texture

BACKENDS = ("numpy", "gl")


@pytest.fixture(scope="module", params=BACKENDS)
def backend(request):
    """Each back end, made once for the module (a GL context is costly)."""
    made = create_backend(request.param)
    yield made
    made.close()


NO_CULL = RenderState(cull_mode="NONE")
FLOAT = "A32B32G32R32F"


# --------------------------------------------------------------------------------------------
# Building passes and geometry


def constant(color, state: RenderState = NO_CULL) -> PassProgram:
    b = Builder("fragment")
    b.output("color0", b.const(tuple(float(c) for c in color)))
    return PassProgram(b.build(), render_state=state)


def show(name: str, state: RenderState = NO_CULL, **kwargs) -> PassProgram:
    """A pass that outputs the varying `name` as its colour."""
    b = Builder("fragment")
    b.output("color0", b.varying(name))
    return PassProgram(b.build(), render_state=state, **kwargs)


def quad(x0=-1.0, y0=-1.0, x1=1.0, y1=1.0, z=0.5, **attrs):
    """A rectangle in clip space as a strip, clockwise on screen (D3D's front face), with
    texcoord0 = (u, v) running 0..1 left to right and top to bottom across it, and any other
    per-vertex attributes given as (4, k) arrays in the order top-left, top-right,
    bottom-left, bottom-right."""
    position = np.array([[x0, y1, z], [x1, y1, z], [x0, y0, z], [x1, y0, z]], np.float32)
    streams = {"position": position,
               "texcoord0": np.array([[0, 0], [1, 0], [0, 1], [1, 1]], np.float32)}
    streams.update({k: np.asarray(v, np.float32) for k, v in attrs.items()})
    return streams, np.arange(4), "strip"


def render(backend, draws, size=(8, 8), clear=(0.0, 0.0, 0.0, 0.0), format="A8R8G8B8",
           textures=None):
    backend.begin_frame(size, clear, 1.0, 0, format=format)
    for program, (streams, indices, primitive) in draws:
        backend.draw(program, streams, indices, primitive, textures or {})
    return backend.end_frame()


def u8(values) -> np.ndarray:
    """What an A8R8G8B8 target stores for colour values."""
    return np.rint(np.clip(np.asarray(values, np.float64), 0, 1) * 255).astype(int)


def assert_close_u8(actual, expected, tolerance=1):
    diff = np.abs(np.asarray(actual, int) - np.asarray(expected, int))
    assert diff.max() <= tolerance, f"{actual} != {expected}"


# --------------------------------------------------------------------------------------------
# Pixel centres, coverage, depth


def test_texcoord_at_d3d_pixel_centres_is_px_over_width(backend):
    """D3D9 samples pixel (px, py) at (px, py): across a full-screen quad u = px/W, v = py/H
    (GL's own centres would give (px + 0.5)/W)."""
    image = render(backend, [(show("texcoord0"), quad())], size=(16, 8), format=FLOAT)
    px, py = np.meshgrid(np.arange(16), np.arange(8))
    np.testing.assert_allclose(image[..., 0], px / 16, atol=1e-5)
    np.testing.assert_allclose(image[..., 1], py / 8, atol=1e-5)
    # the absent components read (0, 0, 0, 1)
    np.testing.assert_array_equal(image[..., 2:], np.broadcast_to([0.0, 1.0], (8, 16, 2)))


def test_top_left_rule_on_edges_through_pixel_centres(backend):
    """NDC [-0.5, 0.5] on 8 pixels spans window [2, 6): centres 2..5 are inside (the left and
    top edges own their centres, the right and bottom ones do not)."""
    image = render(backend, [(constant((1, 1, 1, 1)), quad(-0.5, -0.5, 0.5, 0.5))])
    expected = np.zeros((8, 8), int)
    expected[2:6, 2:6] = 255
    np.testing.assert_array_equal(image[..., 0], expected)


GREEN, RED = (0, 1, 0, 1), (1, 0, 0, 1)


@pytest.mark.parametrize("state, first_z, second_z, winner", [
    (RenderState(cull_mode="NONE"), 0.3, 0.7, GREEN),                   # LESSEQUAL: near wins
    (RenderState(cull_mode="NONE"), 0.7, 0.3, RED),
    (RenderState(cull_mode="NONE"), 0.5, 0.5, RED),                     # equal passes <=
    (RenderState(cull_mode="NONE", z_func="LESS"), 0.5, 0.5, GREEN),
    (RenderState(cull_mode="NONE", z_func="GREATER"), 0.3, 0.7, GREEN),  # fails vs clear 1.0
    (RenderState(cull_mode="NONE", z_func="ALWAYS"), 0.3, 0.7, RED),
    (RenderState(cull_mode="NONE", z_enable=False), 0.3, 0.7, RED),
    (RenderState(cull_mode="NONE", z_write_enable=False), 0.3, 0.7, RED),
])
def test_depth_order(backend, state, first_z, second_z, winner):
    image = render(backend, [(constant(GREEN, state), quad(z=first_z)),
                        (constant(RED, state), quad(z=second_z))], size=(4, 4))
    if state.z_func == "GREATER":
        winner = (0, 0, 0, 0)  # nothing is farther than the cleared 1.0
    np.testing.assert_array_equal(image, np.broadcast_to(u8(winner), (4, 4, 4)))


@pytest.mark.parametrize("z, visible", [(-0.01, False), (0.001, True), (0.999, True),
                                        (1.01, False)])
def test_clip_space_depth_range_is_zero_to_w(backend, z, visible):
    """D3D clips to 0 <= z <= w (GL's own range, -w..w, would keep z = -0.01)."""
    state = RenderState(cull_mode="NONE", z_enable=False)
    image = render(backend, [(constant((1, 1, 1, 1), state), quad(z=z))], size=(4, 4))
    assert (image[..., 0] == 255).all() if visible else (image[..., 0] == 0).all()


def test_depth_is_z_over_w_with_perspective(backend):
    """A quad with w = 2 and z = 0.8 has depth 0.4: it hides one at depth 0.5 drawn later."""
    far = quad(z=0.5)
    near_streams, idx, prim = quad()
    xy = near_streams["position"][:, :2] * 2
    near_streams["position"] = np.concatenate([xy, np.tile([0.8, 2.0], (4, 1))], axis=1)
    image = render(backend, [(constant(GREEN), (near_streams, idx, prim)), (constant(RED), far)],
                   size=(4, 4))
    np.testing.assert_array_equal(image[..., :3], np.broadcast_to([0, 255, 0], (4, 4, 3)))


def test_depth_bias_moves_a_coplanar_pass_in_front(backend):
    """DepthBias -0.1 on a second pass at the same z lets it pass a LESS test."""
    second = RenderState(cull_mode="NONE", z_func="LESS", depth_bias=-0.1)
    image = render(backend, [(constant(GREEN), quad(z=0.5)), (constant(RED, second), quad(z=0.5))],
                   size=(4, 4))
    np.testing.assert_array_equal(image[..., 0], np.full((4, 4), 255))


# --------------------------------------------------------------------------------------------
# Faces


# Clockwise on screen (D3D's front face): top-left, top-right, bottom-left.
CLOCKWISE = np.array([[-1, 1, 0.5], [1, 1, 0.5], [-1, -1, 0.5]], np.float32)
COUNTER = CLOCKWISE[[0, 2, 1]]


@pytest.mark.parametrize("cull, clockwise_visible, counter_visible", [
    ("NONE", True, True), ("CCW", True, False), ("CW", False, True)])
def test_cull_mode_culls_the_named_winding(backend, cull, clockwise_visible, counter_visible):
    b = Builder("fragment")
    b.output("color0", b.builtin("vface"))  # +1 on front faces, -1 on back faces
    program = PassProgram(b.build(), render_state=RenderState(cull_mode=cull))
    for triangle, visible, face in ((CLOCKWISE, clockwise_visible, 255),
                                    (COUNTER, counter_visible, 0)):
        image = render(backend, [(program, ({"position": triangle}, np.arange(3), "list"))],
                       size=(4, 4), clear=(0.5, 0.5, 0.5, 0.5))
        corner = image[0, 0]  # the top-left pixel is inside both triangles
        assert corner[0] == (face if visible else 128), (cull, corner)


def test_vpos_is_the_integer_pixel_position(backend):
    b = Builder("fragment")
    b.output("color0", b.builtin("vpos"))
    image = render(backend, [(PassProgram(b.build(), render_state=NO_CULL), quad())], size=(6, 4),
                   format=FLOAT)
    px, py = np.meshgrid(np.arange(6), np.arange(4))
    np.testing.assert_array_equal(image[..., 0], px)
    np.testing.assert_array_equal(image[..., 1], py)
    np.testing.assert_array_equal(image[..., 3], np.ones((4, 6)))


def test_flat_shading_takes_the_first_vertex_colour(backend):
    colours = np.array([[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1]], np.float32)
    streams = {"position": CLOCKWISE, "color0": colours}
    flat = render(backend, [(show("color0", RenderState(shade_mode="FLAT")),
                        (streams, np.arange(3), "list"))], size=(4, 4))
    inside = np.tril(np.ones((4, 4), bool))[::-1]  # pixels with px + py <= 3
    inside[np.add.outer(np.arange(4), np.arange(4)) == 3] = False  # the diagonal edge
    assert (flat[inside] == [255, 0, 0, 255]).all()
    smooth = render(backend, [(show("color0", RenderState()), (streams, np.arange(3), "list"))],
                    size=(4, 4))
    assert not (smooth[inside] == [255, 0, 0, 255]).all()


def test_colour_varyings_are_saturated_before_interpolation(backend):
    streams, idx, prim = quad(color0=np.full((4, 4), 2.0), texcoord1=np.full((4, 4), 2.0))
    b = Builder("fragment")
    half = b.const(0.25)
    b.output("color0", b.merge(b.mul(b.varying("color0"), half),
                               b.mul(b.varying("texcoord1"), half), "y"))
    image = render(backend, [(PassProgram(b.build(), render_state=NO_CULL), (streams, idx, prim))],
                   size=(2, 2), format=FLOAT)
    np.testing.assert_allclose(image[0, 0, :2], [0.25, 0.5])  # colour clamped to 1, texcoord not
    # red 2 on the left edge, 0 on the right: sat(2) = 1 interpolated is 1 - u = 1 - px/8
    # (interpolating first, then saturating, would give min(2 - 2u, 1): 1 up to px = 4)
    red_left = np.array([[2, 0, 0, 1], [0, 0, 0, 1], [2, 0, 0, 1], [0, 0, 0, 1]])
    image = render(backend, [(show("color0"), quad(color0=red_left))])
    assert_unorm(image[0, :, 0], 1 - np.arange(8) / 8)


# --------------------------------------------------------------------------------------------
# Output merger


S = (0.8, 0.4, 0.2, 0.6)                                   # source colour
D = (51 / 255, 128 / 255, 255 / 255, 102 / 255)            # destination (exact 8-bit values)
C = (0.25, 0.5, 0.75, 1.0)                                 # BlendFactor


def _factor(name):
    """D3DBLEND factors from the documentation's table, per channel (r, g, b, a)."""
    s, d, c = np.array(S), np.array(D), np.array(C)
    sat = min(S[3], 1 - D[3])
    return {
        "ZERO": np.zeros(4), "ONE": np.ones(4),
        "SRCCOLOR": s, "INVSRCCOLOR": 1 - s,
        "SRCALPHA": np.full(4, S[3]), "INVSRCALPHA": np.full(4, 1 - S[3]),
        "DESTALPHA": np.full(4, D[3]), "INVDESTALPHA": np.full(4, 1 - D[3]),
        "DESTCOLOR": d, "INVDESTCOLOR": 1 - d,
        "SRCALPHASAT": np.array([sat, sat, sat, 1.0]),
        "BLENDFACTOR": c, "INVBLENDFACTOR": 1 - c,
    }[name]


FACTOR_NAMES = ["ZERO", "ONE", "SRCCOLOR", "INVSRCCOLOR", "SRCALPHA", "INVSRCALPHA",
                "DESTALPHA", "INVDESTALPHA", "DESTCOLOR", "INVDESTCOLOR", "SRCALPHASAT",
                "BLENDFACTOR", "INVBLENDFACTOR"]


def _blend(backend, **states):
    state = RenderState(cull_mode="NONE", alpha_blend_enable=True, blend_factor=C, **states)
    return render(backend, [(constant(S, state), quad())], size=(2, 2), clear=D)[0, 0]


@pytest.mark.parametrize("factor", FACTOR_NAMES)
def test_each_blend_factor_as_source(backend, factor):
    assert_close_u8(_blend(backend, src_blend=factor, dest_blend="ZERO"),
                    u8(np.array(S) * _factor(factor)))


@pytest.mark.parametrize("factor", [f for f in FACTOR_NAMES if f != "SRCALPHASAT"])
def test_each_blend_factor_as_destination(backend, factor):
    assert_close_u8(_blend(backend, src_blend="ZERO", dest_blend=factor),
                    u8(np.array(D) * _factor(factor)))


@pytest.mark.parametrize("src, expected", [
    ("BOTHSRCALPHA", np.array(S) * S[3] + np.array(D) * (1 - S[3])),
    ("BOTHINVSRCALPHA", np.array(S) * (1 - S[3]) + np.array(D) * S[3])])
def test_both_blend_factors_set_the_destination_too(backend, src, expected):
    assert_close_u8(_blend(backend, src_blend=src, dest_blend="ONE"), u8(expected))


@pytest.mark.parametrize("op, expected", [
    ("ADD", np.array(S) + np.array(D)), ("SUBTRACT", np.array(S) - np.array(D)),
    ("REVSUBTRACT", np.array(D) - np.array(S)), ("MIN", np.minimum(S, D)),
    ("MAX", np.maximum(S, D))])
def test_blend_ops(backend, op, expected):
    assert_close_u8(_blend(backend, src_blend="ONE", dest_blend="ONE", blend_op=op), u8(expected))


def test_separate_alpha_blend(backend):
    out = _blend(backend, src_blend="ONE", dest_blend="ZERO", separate_alpha_blend_enable=True,
                 src_blend_alpha="ZERO", dest_blend_alpha="ONE")
    assert_close_u8(out, u8([S[0], S[1], S[2], D[3]]))


@pytest.mark.parametrize("func", ["NEVER", "LESS", "EQUAL", "LESSEQUAL", "GREATER",
                                  "NOTEQUAL", "GREATEREQUAL", "ALWAYS"])
@pytest.mark.parametrize("ref", [127, 128, 129])
def test_alpha_test_compares_the_8bit_alpha_with_the_reference(backend, func, ref):
    alpha8 = 128
    passes = {"NEVER": False, "LESS": alpha8 < ref, "EQUAL": alpha8 == ref,
              "LESSEQUAL": alpha8 <= ref, "GREATER": alpha8 > ref, "NOTEQUAL": alpha8 != ref,
              "GREATEREQUAL": alpha8 >= ref, "ALWAYS": True}[func]
    state = RenderState(cull_mode="NONE", alpha_test_enable=True, alpha_func=func,
                        alpha_ref=ref)
    image = render(backend, [(constant((1, 1, 1, alpha8 / 255), state), quad())], size=(2, 2))
    assert image[0, 0, 0] == (255 if passes else 0)


def test_colour_write_mask(backend):
    state = RenderState(cull_mode="NONE", color_write_enable=1 | 4)  # red and blue
    image = render(backend, [(constant((1, 1, 1, 1), state), quad())], size=(2, 2),
                   clear=(0.2, 0.4, 0.6, 0.8))
    np.testing.assert_array_equal(image[0, 0], [255, 102, 255, 204])


def test_stencil_masks_a_second_pass(backend):
    """Pass 1 writes stencil 3 on the left half (no colour); pass 2 draws where it equals 3."""
    mark = RenderState(cull_mode="NONE", z_enable=False, color_write_enable=0,
                       stencil_enable=True, stencil_func="ALWAYS", stencil_pass="REPLACE",
                       stencil_ref=3)
    test = RenderState(cull_mode="NONE", z_enable=False, stencil_enable=True,
                       stencil_func="EQUAL", stencil_ref=3)
    image = render(backend, [(constant((1, 1, 1, 1), mark), quad(-1, -1, 0, 1)),
                        (constant(GREEN, test), quad())], size=(4, 2))
    np.testing.assert_array_equal(image[..., 1], [[255, 255, 0, 0]] * 2)


def test_stencil_increments_saturate_and_wrap(backend):
    """Three INCRSAT passes from 254 leave 255; three INCR passes wrap 254 to 1."""
    for op, expected in (("INCRSAT", 255), ("INCR", 1)):
        bump = RenderState(cull_mode="NONE", z_enable=False, color_write_enable=0,
                           stencil_enable=True, stencil_pass=op)
        check = RenderState(cull_mode="NONE", z_enable=False, stencil_enable=True,
                            stencil_func="EQUAL", stencil_ref=expected)
        backend.begin_frame((2, 2), (0, 0, 0, 0), 1.0, 254)
        for _ in range(3):
            backend.draw(constant((1, 1, 1, 1), bump), *quad(), {})
        backend.draw(constant(GREEN, check), *quad(), {})
        assert backend.end_frame()[0, 0, 1] == 255, op


def test_two_sided_stencil_uses_the_ccw_states_for_back_faces(backend):
    write = RenderState(cull_mode="NONE", z_enable=False, color_write_enable=0,
                        stencil_enable=True, two_sided_stencil_mode=True, stencil_ref=5,
                        stencil_pass="REPLACE", ccw_stencil_pass="INCR")
    check = RenderState(cull_mode="NONE", z_enable=False, stencil_enable=True,
                        stencil_func="EQUAL", stencil_ref=5)
    for triangle, expected in ((CLOCKWISE, 255), (COUNTER, 0)):  # back faces leave 1, not 5
        image = render(backend, [(constant((1, 1, 1, 1), write),
                             ({"position": triangle}, np.arange(3), "list")),
                            (constant(GREEN, check), quad())], size=(4, 4))
        assert image[0, 0, 1] == expected


# --------------------------------------------------------------------------------------------
# Textures


TEXELS_4x4 = np.zeros((4, 4, 4), np.float32)
TEXELS_4x4[..., 0] = np.arange(4)[None, :] * 0.25 + 0.1    # red by column
TEXELS_4x4[..., 1] = np.arange(4)[:, None] * 0.25 + 0.1    # green by row
TEXELS_4x4[..., 3] = 1


def _sampled(backend, binding: TextureBinding, texture: Texture, size=(8, 8), kind="2d"):
    b = Builder("fragment")
    b.output("color0", b.sample(0, b.varying("texcoord0"), kind=kind))
    program = PassProgram(b.build(), render_state=NO_CULL, textures=(binding,))
    return render(backend, [(program, quad())], size=size, format=FLOAT,
                  textures={binding.texture: texture})


def test_point_sampling_picks_the_texel_under_the_pixel_centre(backend):
    image = _sampled(backend, TextureBinding(0, "t"), Texture("2d", "A32B32G32R32F", [TEXELS_4x4]))
    px = np.arange(8)
    # u = px/8 falls in texel floor(u*4) = px // 2
    np.testing.assert_allclose(image[0, :, 0], (px // 2) * 0.25 + 0.1, atol=1e-6)
    np.testing.assert_allclose(image[:, 0, 1], (px // 2) * 0.25 + 0.1, atol=1e-6)
    # Inside the quad, even pixels lie exactly on texel edges (u * 4 = px / 2), where the
    # interpolated u may fall either side; odd pixels sample texel centres: there every
    # pixel reads texel (py // 2, px // 2), red by column and green by row.
    odd = image[1::2, 1::2]
    texel = (px[1::2] // 2) * 0.25 + 0.1
    np.testing.assert_allclose(odd[..., 0], np.broadcast_to(texel, (4, 4)), atol=1e-6)
    np.testing.assert_allclose(odd[..., 1], np.broadcast_to(texel[:, None], (4, 4)), atol=1e-6)


@pytest.mark.parametrize("mode, left_neighbour", [
    ("WRAP", 3 * 0.25 + 0.1), ("CLAMP", 0.1), ("MIRROR", 0.1), ("MIRRORONCE", 0.1),
    ("BORDER", 0.9)])
def test_linear_sampling_and_address_modes(backend, mode, left_neighbour):
    """Bilinear at u = px/8 on 4 texels: position u*4 - 0.5 = px/2 - 0.5 between texel
    centres; pixel 0 lies half-way between texel -1 (addressed by `mode`) and texel 0."""
    binding = TextureBinding(0, "t", mag_filter="LINEAR", min_filter="LINEAR", address_u=mode,
                             border_color=(0.9, 0.9, 0.9, 0.9))
    image = _sampled(backend, binding, Texture("2d", "A32B32G32R32F", [TEXELS_4x4]))
    column = TEXELS_4x4[0, :, 0]
    expected = []
    for px in range(8):
        x = px / 2 - 0.5
        i = math.floor(x)
        a = x - i
        left = left_neighbour if i < 0 else column[i]
        expected.append(left * (1 - a) + column[min(i + 1, 3)] * a)
    np.testing.assert_allclose(image[4, :, 0], expected, atol=2e-3)


def _mip_texture() -> Texture:
    levels = [np.full((8 >> k, 8 >> k, 4), value, np.float32) for k, value in
              enumerate((0.2, 0.5, 0.8, 0.9))]
    return Texture("2d", "A32B32G32R32F", levels)


@pytest.mark.parametrize("size, states, expected", [
    ((4, 4), dict(mip_filter="POINT"), 0.5),          # 2 texels per pixel: LOD 1
    ((4, 4), dict(mip_filter="NONE"), 0.2),           # no mipmapping: level 0
    ((8, 8), dict(mip_filter="POINT"), 0.2),          # LOD 0: level 0
    ((4, 4), dict(mip_filter="POINT", mip_lod_bias=1.0), 0.8),
    ((4, 4), dict(mip_filter="LINEAR", mip_lod_bias=0.5), 0.65),   # half-way 1 -> 2
    ((8, 8), dict(mip_filter="POINT", max_mip_level=2), 0.8),       # level >= 2
    ((4, 4), dict(mip_filter="NONE", max_mip_level=1), 0.5),
])
def test_mip_level_selection(backend, size, states, expected):
    binding = TextureBinding(0, "t", min_filter="LINEAR", mag_filter="LINEAR", **states)
    image = _sampled(backend, binding, _mip_texture(), size=size)
    np.testing.assert_allclose(image[..., 0], np.full(image.shape[:2], expected), atol=2e-3)


def test_cube_face_selection_and_face_orientation(backend):
    """Six 2x2 regions, each with one direction; each face's 2x2 texels are distinct. The
    expected face and (u, v) come from the D3D9 cube-map table by hand."""
    faces = np.zeros((6, 2, 2, 4), np.float32)
    for f in range(6):
        for row in range(2):
            for col in range(2):
                faces[f, row, col] = (f / 8, (row * 2 + col) / 8, 0.5, 1)
    cases = [((1, 0.5, 0.5), 0, 0, 0), ((-1, 0.5, 0.5), 1, 0, 1), ((0.5, 1, 0.5), 2, 1, 1),
             ((0.5, -1, 0.5), 3, 0, 1), ((0.5, 0.5, 1), 4, 0, 1), ((0.5, -0.5, -1), 5, 1, 0)]
    b = Builder("fragment")
    b.output("color0", b.sample(0, b.varying("texcoord0"), kind="cube"))
    program = PassProgram(b.build(), render_state=NO_CULL,
                          textures=(TextureBinding(0, "env", kind="cube"),))
    draws = []
    for n, (direction, _, _, _) in enumerate(cases):
        x0 = -1 + n * 2 / 6
        streams, idx, prim = quad(x0, -1, x0 + 2 / 6, 1)
        streams["texcoord0"] = np.tile(np.array(direction, np.float32), (4, 1))
        draws.append((program, (streams, idx, prim)))
    image = render(backend, draws, size=(12, 2), format=FLOAT,
                   textures={"env": Texture("cube", "A32B32G32R32F", [faces])})
    for n, (_, face, row, col) in enumerate(cases):
        np.testing.assert_allclose(image[0, 2 * n, :2], [face / 8, (row * 2 + col) / 8],
                                   err_msg=f"direction {cases[n][0]}")


def test_volume_texture_slices(backend):
    volume = np.zeros((4, 1, 1, 4), np.float32)
    volume[:, 0, 0, 0] = [0.1, 0.3, 0.6, 0.9]
    b = Builder("fragment")
    b.output("color0", b.sample(0, b.varying("texcoord1"), kind="3d"))
    program = PassProgram(b.build(), render_state=NO_CULL,
                          textures=(TextureBinding(0, "v", kind="3d"),))
    for slice_, w in enumerate((0.1, 0.3, 0.6, 0.9)):
        streams, idx, prim = quad(texcoord1=np.tile([0.5, 0.5, (slice_ + 0.5) / 4], (4, 1)))
        image = render(backend, [(program, (streams, idx, prim))], size=(2, 2), format=FLOAT,
                       textures={"v": Texture("3d", "A32B32G32R32F", [volume])})
        assert image[0, 0, 0] == pytest.approx(w)


def test_1d_texture_and_projected_lookup(backend):
    ramp = np.zeros((1, 4, 4), np.float32)
    ramp[0, :, 0] = [0.1, 0.3, 0.6, 0.9]
    b = Builder("fragment")
    b.output("color0", b.sample(0, b.varying("texcoord1"), kind="1d", proj=True))
    program = PassProgram(b.build(), render_state=NO_CULL,
                          textures=(TextureBinding(0, "r", kind="1d"),))
    # u/w = 1.25/2 = 0.625 -> texel 2
    streams, idx, prim = quad(texcoord1=np.tile([1.25, 0, 0, 2], (4, 1)))
    image = render(backend, [(program, (streams, idx, prim))], size=(2, 2), format=FLOAT,
                   textures={"r": Texture("1d", "A32B32G32R32F", [ramp])})
    assert image[0, 0, 0] == pytest.approx(0.6)


def test_several_new_textures_in_one_draw_each_reach_their_sampler(backend):
    """Three textures first seen in the same draw (each upload binds a texture, which must
    not displace the ones already bound to other units)."""
    b = Builder("fragment")
    coord = b.varying("texcoord0")
    red, green, blue = (b.sample(i, coord) for i in (0, 2, 5))
    b.output("color0", b.merge(b.merge(red, green, "y"), blue, "zw"))
    names = {0: "red", 2: "green", 5: "blue"}
    program = PassProgram(b.build(), render_state=NO_CULL,
                          textures=tuple(TextureBinding(i, n) for i, n in names.items()))
    textures = {n: Texture("2d", "A32B32G32R32F", [np.full((2, 2, 4), v, np.float32)])
                for n, v in (("red", 0.25), ("green", 0.5), ("blue", 0.75))}
    image = render(backend, [(program, quad())], size=(2, 2), format=FLOAT, textures=textures)
    np.testing.assert_allclose(image[0, 0], [0.25, 0.5, 0.75, 0.75])


@pytest.mark.parametrize("unit", [0, 3])
def test_unbound_sampler_reads_0001(backend, unit):
    b = Builder("fragment")
    b.output("color0", b.sample(unit, b.varying("texcoord0")))
    image = render(backend, [(PassProgram(b.build(), render_state=NO_CULL), quad())], size=(2, 2),
                   clear=(0.5, 0.5, 0.5, 0.5))
    np.testing.assert_array_equal(image, np.broadcast_to([0, 0, 0, 255], (2, 2, 4)))


def test_srgb_texture_is_linearised(backend):
    texel = np.full((1, 1, 4), 0.5, np.float32)
    binding = TextureBinding(0, "t", srgb_texture=True)
    image = _sampled(backend, binding, Texture("2d", "A8R8G8B8", [texel]), size=(2, 2))
    linear = ((0.5 + 0.055) / 1.055) ** 2.4          # IEC 61966-2-1
    assert image[0, 0, 0] == pytest.approx(linear, abs=1e-4)
    assert image[0, 0, 3] == pytest.approx(0.5)       # alpha is not converted


# --------------------------------------------------------------------------------------------
# Programs, uniforms, kill, fixed-function extras


def test_kill_discards_where_a_component_is_negative(backend):
    b = Builder("fragment")
    coord = b.varying("texcoord0")
    b.kill(b.sub(coord, b.const(0.5)), "x")   # u < 0.5: the left half
    b.output("color0", b.const(1.0))
    image = render(backend, [(PassProgram(b.build(), render_state=NO_CULL), quad())], size=(4, 2))
    expected = np.zeros((2, 4, 4), int)
    expected[:, 2:] = 255                     # the clear (0, 0, 0, 0) on the left, white right
    np.testing.assert_array_equal(image, expected)


def test_uniforms_reach_the_pass_and_unsupplied_ones_read_zero(backend):
    b = Builder("fragment")
    b.output("color0", b.uniform("Tint"))
    fragment = b.build()
    for value in ((1.0, 0.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0)):
        program = PassProgram(fragment, render_state=NO_CULL,
                              uniforms=PassProgram.pack_uniforms({"Tint": value}))
        image = render(backend, [(program, quad())], size=(2, 2))
        np.testing.assert_array_equal(image[0, 0], u8(value))
    image = render(backend, [(PassProgram(fragment, render_state=NO_CULL), quad())], size=(2, 2))
    np.testing.assert_array_equal(image[0, 0], [0, 0, 0, 0])


def test_vertex_program_transforms_positions(backend):
    """Clip = (0.5 x, 0.5 y, z, 1) by four dp4 rows: the quad covers the middle half."""
    b = Builder("vertex")
    p = b.varying("position", "POSITION", 3)
    rows = [b.dp4(p, b.uniform(f"m{i}")) for i in range(4)]
    clip = b.merge(b.merge(b.merge(rows[0], rows[1], "y"), rows[2], "z"), rows[3], "w")
    b.output("position", clip)
    b.output("color0", b.varying("color0"))   # no stream: the D3D default (1, 1, 1, 1)
    uniforms = PassProgram.pack_uniforms({"m0": (0.5, 0, 0, 0), "m1": (0, 0.5, 0, 0),
                                          "m2": (0, 0, 1, 0), "m3": (0, 0, 0, 1)})
    program = PassProgram(show("color0").fragment, vertex=b.build(), render_state=NO_CULL,
                          uniforms=uniforms)
    streams, idx, prim = quad()
    image = render(backend, [(program, ({"position": streams["position"]}, idx, prim))])
    expected = np.zeros((8, 8), int)
    expected[2:6, 2:6] = 255
    np.testing.assert_array_equal(image[..., 0], expected)


# Fog and the specular add are lowered into the programs (effects.lower.passes): a back end
# only runs the IR. These render a lowered pass on every back end; the formulas themselves are
# tested at the IR level in tests/lower/test_lower_stages.py.
FOG_PASS = """technique t {{ pass p {{ Lighting = FALSE; CullMode = None; {states}
    ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse; AlphaOp[0] = SelectArg1; AlphaArg1[0] = Diffuse;
}} }}"""


def lowered(states: str) -> PassProgram:
    effect = effects.load_effect(FOG_PASS.format(states=states))
    return lower_pass(effect, effect.techniques[0], 0, load_profile("modern"))


def test_lowered_specular_add_renders_alike(backend):
    program = lowered("SpecularEnable = TRUE;")
    streams, idx, prim = quad(color0=np.tile([0.5, 0.25, 0, 1], (4, 1)),
                              color1=np.tile([0.25, 0.25, 0.5, 0.9], (4, 1)))
    image = render(backend, [(program, (streams, idx, prim))], size=(2, 2))
    assert_close_u8(image[0, 0], u8([0.75, 0.5, 0.5, 1.0]))


@pytest.mark.parametrize("states, factor", [
    ("FogTableMode = Linear; FogStart = 0.0; FogEnd = 1.0;", 0.5),   # distance z = 0.5
    ("FogTableMode = Exp; FogDensity = 2.0;", math.exp(-1.0)),
    ("FogTableMode = Exp2; FogDensity = 2.0;", math.exp(-1.0)),
    ("FogVertexMode = Linear; FogStart = 0.0; FogEnd = 2.0;", 0.75),  # per vertex
])
def test_lowered_fog_renders_alike(backend, states, factor):
    program = lowered("FogEnable = TRUE; FogColor = 0x000000ff; " + states)
    streams, idx, prim = quad(z=0.5, color0=np.tile([1, 0, 0, 1], (4, 1)))
    image = render(backend, [(program, (streams, idx, prim))], size=(2, 2))
    assert_close_u8(image[0, 0], u8([factor, 0, 1 - factor, 1]))


def test_lowered_specular_is_added_before_fog(backend):
    """Colour 0.5 grey + specular 0.25 red = (0.75, 0.5, 0.5); table fog at z = 0.5 keeps
    half of that and adds half of the blue fog colour: (0.375, 0.25, 0.75)."""
    program = lowered("SpecularEnable = TRUE; FogEnable = TRUE; FogTableMode = Linear;"
                      "FogStart = 0.0; FogEnd = 1.0; FogColor = 0x000000ff;")
    streams, idx, prim = quad(color0=np.tile([0.5, 0.5, 0.5, 1], (4, 1)),
                              color1=np.tile([0.25, 0, 0, 0], (4, 1)))
    image = render(backend, [(program, (streams, idx, prim))], size=(8, 8))
    # 95.6, 63.75, 191.25 and 255: no value near a half step, so exact
    np.testing.assert_array_equal(image, np.broadcast_to([96, 64, 191, 255], (8, 8, 4)))


# --------------------------------------------------------------------------------------------
# Targets


def test_float_target_formats_read_missing_channels_as_one(backend):
    program = constant((2.5, -1.0, 0.125, 3.0))
    r32f = render(backend, [(program, quad())], size=(2, 2), format="R32F")
    np.testing.assert_array_equal(r32f[0, 0], [2.5, 1, 1, 1])
    g32r32f = render(backend, [(program, quad())], size=(2, 2), format="G32R32F")
    np.testing.assert_array_equal(g32r32f[0, 0], [2.5, -1.0, 1, 1])
    x8 = render(backend, [(constant((0.2, 0.4, 0.6, 0.0)), quad())], size=(2, 2), format="X8R8G8B8")
    np.testing.assert_array_equal(x8[0, 0], [51, 102, 153, 255])
    half = render(backend, [(constant((1 / 3, 0, 0, 1)), quad())], size=(2, 2),
                  format="A16B16G16R16F")
    assert half[0, 0, 0] == np.float32(np.float16(1 / 3))


def test_cube_faces_render_into_six_frames(backend):
    def draw_face(face):
        backend.draw(constant((10.0 * face + 0.5, 0, 0, 0)), *quad(), {})
    faces = render_cube_faces(backend, 4, draw_face, format="R32F")
    assert faces.shape == (6, 4, 4, 4) and faces.dtype == np.float32
    expected = np.ones((6, 4, 4, 4), np.float32)      # R32F reads G, B and A as 1
    expected[..., 0] = (10.0 * np.arange(6) + 0.5)[:, None, None]
    np.testing.assert_array_equal(faces, expected)




# --------------------------------------------------------------------------------------------
# First written for the reference back end


CLIP_QUAD = np.array([[-1, -1, 0.5, 1], [-1, 1, 0.5, 1], [1, 1, 0.5, 1], [1, -1, 0.5, 1]],
                     np.float32)
CLIP_QUAD_INDICES = np.array([0, 1, 2, 0, 2, 3])
CLIP_UV = np.array([[0, 1], [0, 0], [1, 0], [1, 1]], np.float32)


def test_pixel_centres_on_a_list_quad_and_unorm_rounding(backend):
    """u = px / W and v = py / H at D3D9 pixel centres, written to an 8-bit target."""
    streams = {"position": CLIP_QUAD, "texcoord0": CLIP_UV}
    image = render(backend, [(show("texcoord0"), (streams, CLIP_QUAD_INDICES, "list"))],
                   size=(10, 4))
    assert_unorm(image[0, :, 0], np.arange(10) / 10)
    assert_unorm(image[:, 0, 1], np.arange(4) / 4)
    assert (image[..., 2] == 0).all() and (image[..., 3] == 255).all()


def assert_unorm(stored, values):
    """8-bit writes of `values`: round(x * 255), except that a value exactly on a half step
    (0.1 * 255 = 25.5) may go either way (docs/reference/semantics.md section 0)."""
    scaled = np.asarray(values, np.float64) * 255
    stored = np.asarray(stored, np.int64)
    on_half = np.isclose(scaled % 1, 0.5)
    np.testing.assert_array_equal(stored[~on_half], np.rint(scaled[~on_half]))
    assert (np.abs(stored[on_half] - scaled[on_half]) == 0.5).all(), stored[on_half]


def test_shared_edges_are_blended_exactly_once(backend):
    """A jittered grid over the screen, additive blending of 0.25: every pixel gets exactly
    one fragment -> 64, never 0 (gap) or 128 (double blend)."""
    rng = np.random.default_rng(7)
    cells = 11
    g = np.linspace(-1, 1, cells + 1)
    x, y = np.meshgrid(g, g)
    inner = np.zeros_like(x, bool)
    inner[1:-1, 1:-1] = True
    x = x + inner * rng.uniform(-0.06, 0.06, x.shape)
    y = y + inner * rng.uniform(-0.06, 0.06, y.shape)
    pos = np.column_stack([x.ravel(), y.ravel(), np.full(x.size, 0.5), np.ones(x.size)])
    i = (np.arange(cells)[:, None] * (cells + 1) + np.arange(cells)).ravel()
    tris = np.concatenate([np.stack([i, i + cells + 1, i + 1], 1),
                           np.stack([i + 1, i + cells + 1, i + cells + 2], 1)])
    program = constant((0.25, 0.25, 0.25, 0.25), RenderState(
        cull_mode="NONE", alpha_blend_enable=True, src_blend="ONE", dest_blend="ONE",
        z_enable=False))
    image = render(backend, [(program, ({"position": pos.astype(np.float32)}, tris, "list"))],
                   size=(45, 37))
    assert (image == 64).all()


def test_depth_order_of_overlapping_rectangles_in_both_draw_orders(backend):
    def rect(x0, y0, x1, y1, z):
        return quad(x0, y0, x1, y1, z=z)
    near = (constant(RED), rect(-1, -1, 0.5, 0.5, 0.3))
    far = (constant(GREEN), rect(-0.5, -0.5, 1, 1, 0.6))
    a = render(backend, [near, far])
    b = render(backend, [far, near])
    np.testing.assert_array_equal(a, b)
    assert a[4, 4].tolist() == [255, 0, 0, 255]        # NDC (0, 0): inside both, near wins
    assert a[1, 7].tolist() == [0, 255, 0, 255]        # only the far rectangle
    # ZEnable off: the last drawn wins
    z_off = RenderState(cull_mode="NONE", z_enable=False)
    near_off, far_off = (constant(RED, z_off), near[1]), (constant(GREEN, z_off), far[1])
    assert render(backend, [near_off, far_off])[4, 4].tolist() == [0, 255, 0, 255]
    assert render(backend, [far_off, near_off])[4, 4].tolist() == [255, 0, 0, 255]


def test_multipass_accumulates_into_one_frame(backend):
    add = RenderState(cull_mode="NONE", alpha_blend_enable=True, src_blend="ONE",
                      dest_blend="ONE")
    first = (constant((0.2, 0, 0, 0)), quad())
    second = (constant((0.2, 0.4, 0, 0), add), quad())
    image = render(backend, [first, second, second])
    # 0.2 -> 51, + 51 + 51 = 153; green 0.4 -> 102 twice = 204
    assert image[3, 3].tolist() == [153, 204, 0, 0]


def test_strips_keep_the_first_triangles_winding(backend):
    strip = np.array([[-1, -1, 0.5, 1], [-1, 1, 0.5, 1], [1, -1, 0.5, 1], [1, 1, 0.5, 1]],
                     np.float32)
    white = constant((1, 1, 1, 1), RenderState())
    image = render(backend, [(white, ({"position": strip}, np.arange(4), "strip"))])
    assert (image == 255).all()
    cw = constant((1, 1, 1, 1), RenderState(cull_mode="CW"))
    assert (render(backend, [(cw, ({"position": strip}, np.arange(4), "strip"))]) == 0).all()


def test_missing_colour_streams_read_the_d3d_defaults(backend):
    b = Builder("fragment")
    b.output("color0", b.add(b.varying("color0"), b.varying("color1")))
    program = PassProgram(b.build(), render_state=NO_CULL)
    image = render(backend, [(program, quad())])
    assert (image == 255).all()      # diffuse (1, 1, 1, 1) + specular (0, 0, 0, 0)


def test_mip_level_from_helper_pixel_derivatives_on_a_lone_triangle(backend):
    """uv spans 16 texels over 8 pixels -> LOD 1 everywhere, even on a lone triangle whose
    edge quads are partly helpers. Level 0 reads 0, level 1 reads 1, level 2 0.5."""
    levels = [np.zeros((n, n, 4), np.float32) for n in (16, 8, 4)]
    for level, value in zip(levels, (0.0, 1.0, 0.5)):
        level[..., 0] = value
    tex = {"tex": Texture("2d", "A32B32G32R32F", levels)}
    b = Builder("fragment")
    b.output("color0", b.sample(0, b.varying("texcoord0")))
    trilinear = dict(min_filter="LINEAR", mag_filter="LINEAR", mip_filter="LINEAR")
    program = PassProgram(b.build(), textures=(TextureBinding(0, "tex", **trilinear),))
    streams = {"position": CLIP_QUAD, "texcoord0": CLIP_UV}
    image = render(backend, [(program, (streams, np.array([0, 1, 2]), "list"))],
                   clear=(0, 0, 1, 1), textures=tex)
    covered = image[..., 2] == 0
    assert covered.sum() > 20
    assert (image[covered][:, 0] == 255).all()
    biased = PassProgram(b.build(), textures=(TextureBinding(0, "tex", mip_lod_bias=-1.0,
                                                             **trilinear),))
    image = render(backend, [(biased, (streams, CLIP_QUAD_INDICES, "list"))], textures=tex)
    assert (image[..., 0] == 0).all()


def test_back_faces_read_vface_minus_one(backend):
    b = Builder("fragment")
    b.output("color0", b.merge(b.const(0.0), b.saturate(b.builtin("vface")), "z"))
    program = PassProgram(b.build(), render_state=NO_CULL)
    streams = {"position": CLIP_QUAD}
    front = render(backend, [(program, (streams, CLIP_QUAD_INDICES, "list"))])
    back = render(backend, [(program, (streams, CLIP_QUAD_INDICES[::-1], "list"))])
    assert (front[..., 2] == 255).all() and (back[..., 2] == 0).all()


def test_lit_surface_matches_the_lighting_formula(backend):
    """A 12 x 12 grid whose normal (x, y, -1) is linear in NDC, transformed by a matrix that
    scales clip space by w = 2 (same picture). Per pixel the expected colour comes from the
    pixel centre (x = 2 px / W - 1, y = 1 - 2 py / H)."""
    cells, size = 12, (48, 40)
    g = np.linspace(-1, 1, cells + 1)
    x, y = np.meshgrid(g, g)
    position = np.column_stack([x.ravel(), y.ravel(), np.full(x.size, 0.25)]).astype(np.float32)
    normal = np.column_stack([x.ravel(), y.ravel(), -np.ones(x.size)]).astype(np.float32)
    i = (np.arange(cells)[:, None] * (cells + 1) + np.arange(cells)).ravel()
    tris = np.concatenate([np.stack([i, i + cells + 1, i + 1], 1),
                           np.stack([i + 1, i + cells + 1, i + cells + 2], 1)])
    light = np.array([0.3, 0.5, -0.8]) / np.linalg.norm([0.3, 0.5, -0.8])
    half = light + np.array([0, 0, -1.0])
    half /= np.linalg.norm(half)
    kd = np.array([0.9, 0.6, 0.3, 1.0])
    vb = Builder("vertex")
    pos = vb.varying("position", components=3)
    clip = vb.const(0.0)
    for r in range(4):
        clip = vb.merge(clip, vb.dp4(pos, vb.uniform(f"m{r}")), "xyzw"[r])
    vb.output("position", clip)
    vb.output("texcoord0", vb.varying("normal", components=3))
    fb = Builder("fragment")
    n = fb.nrm(fb.varying("texcoord0"))
    diffuse = fb.mul(fb.uniform("kd"), fb.saturate(fb.dp3(n, fb.uniform("light"))))
    spec = fb.pow(fb.saturate(fb.dp3(n, fb.uniform("half"))), fb.const(16.0))
    fb.output("color0", fb.merge(fb.saturate(fb.add(diffuse, spec)), fb.const(1.0), "w"))
    m = np.diag([2.0, 2.0, 2.0, 2.0])
    uniforms = {f"m{r}": m[r] for r in range(4)}
    uniforms.update(light=(*light, 0), half=(*half, 0), kd=kd)
    program = PassProgram(fb.build(), vb.build(), render_state=NO_CULL,
                          uniforms=PassProgram.pack_uniforms(uniforms))
    image = render(backend, [(program, ({"position": position, "normal": normal}, tris,
                                        "list"))], size=size)
    px, py = np.meshgrid(np.arange(size[0]), np.arange(size[1]))
    nn = np.stack([2 * px / size[0] - 1, 1 - 2 * py / size[1], -np.ones(px.shape)], -1)
    nn /= np.linalg.norm(nn, axis=-1, keepdims=True)
    expected = np.clip(kd[:3] * np.clip(nn @ light, 0, 1)[..., None]
                       + (np.clip(nn @ half, 0, 1) ** 16)[..., None], 0, 1)
    diff = np.abs(image[..., :3].astype(int) - np.rint(expected * 255))
    assert diff.max() <= 1
    assert (image[..., 3] == 255).all()
    assert len(np.unique(image[..., 0])) > 50


def test_bad_draw_calls_are_draw_errors(backend):
    program = constant((1, 1, 1, 1))
    with pytest.raises(DrawError):                      # no frame begun
        backend.draw(program, {"position": CLIP_QUAD}, CLIP_QUAD_INDICES, "list", {})
    backend.begin_frame((4, 4))
    try:
        with pytest.raises(DrawError):
            backend.draw(program, {"position": CLIP_QUAD}, np.array([0, 1, 7]), "list", {})
        with pytest.raises(DrawError):
            backend.draw(program, {"normal": CLIP_QUAD}, CLIP_QUAD_INDICES, "list", {})
        with pytest.raises(DrawError):
            backend.draw(program, {"position": CLIP_QUAD}, CLIP_QUAD_INDICES, "quads", {})
    finally:
        backend.end_frame()
    with pytest.raises(DrawError):
        backend.begin_frame((4, 4), format="P8")


def test_clear_colour_and_the_frame_read_back(backend):
    """An 8-bit frame reads back as (height, width, 4) uint8 with the clear colour rounded."""
    image = render(backend, [], size=(3, 2), clear=(1, 0.5, 0, 0.25))
    assert image.shape == (2, 3, 4) and image.dtype == np.uint8
    np.testing.assert_array_equal(image[..., [0, 2]], np.broadcast_to([255, 0], (2, 3, 2)))
    assert_unorm(image[..., 1].ravel(), np.full(6, 0.5))       # 127.5: 127 or 128
    assert_unorm(image[..., 3].ravel(), np.full(6, 0.25))      # 63.75: 64


# --------------------------------------------------------------------------------------------
# The registry


BACKEND_CLASSES = {"numpy": ReferenceBackend, "gl": GLBackend}


def test_backend_is_registered_and_follows_the_protocol(backend):
    assert isinstance(backend, Backend) and isinstance(backend, BACKEND_CLASSES[backend.name])
    assert backend.name in available_backends()
    made = create_backend(backend.name)
    try:
        assert type(made) is type(backend)
    finally:
        made.close()


def test_unknown_backend_is_an_effect_error_naming_it():
    assert set(BACKEND_CLASSES) <= set(available_backends())
    with pytest.raises(UnknownBackend) as err:
        create_backend("vulkan")
    assert isinstance(err.value, EffectError) and "vulkan" in str(err.value)


# Fog after a pixel shader (Direct3D 9: the fixed-function blend follows a ps_1_x/2_x shader,
# not a ps_3_0 one; with a vertex shader its factor is oFog). The shader writes red, the fog
# colour is blue.
RED_PS2 = "PixelShader = asm { ps_2_0 def c0, 1, 0, 0, 1 mov oC0, c0 };"
FOG_VS2 = ("VertexShader = asm { vs_2_0 dcl_position v0 def c0, 0.25, 0, 0, 0 mov oPos, v0 "
           "mov oFog, c0.x };")
SM3 = ("VertexShader = asm { vs_3_0 dcl_position v0 dcl_position o0 mov o0, v0 };"
       "PixelShader = asm { ps_3_0 def c0, 1, 0, 0, 1 mov oC0, c0 };")


@pytest.mark.parametrize("states, factor", [
    (RED_PS2 + "FogTableMode = Linear; FogStart = 0.0; FogEnd = 1.0;", 0.5),   # z = 0.5
    (RED_PS2 + "FogVertexMode = Linear; FogStart = 0.0; FogEnd = 2.0;", 0.75),  # per vertex
    (RED_PS2 + FOG_VS2, 0.25),             # oFog = 0.25, FogVertexMode NONE: oFog all the same
    (SM3 + "FogTableMode = Linear; FogStart = 0.0; FogEnd = 1.0;", 1.0),   # ps_3_0: no fog
])
def test_fog_after_a_pixel_shader_renders_alike(backend, states, factor):
    program = lowered("FogEnable = TRUE; FogColor = 0x000000ff; " + states)
    streams, idx, prim = quad(z=0.5, color0=np.tile([0, 1, 0, 1], (4, 1)))
    image = render(backend, [(program, (streams, idx, prim))], size=(2, 2))
    assert_close_u8(image[0, 0], u8([factor, 0, 1 - factor, 1]))


def test_pixel_fog_after_both_shaders_is_a_located_error():
    with pytest.raises(effects.EffectError, match="FogTableMode .pixel fog. after a vertex "
                       "shader and a pixel shader is not lowered yet") as err:
        lowered("FogEnable = TRUE; FogTableMode = Linear;" + RED_PS2 + FOG_VS2)
    assert err.value.line == 1
