"""Texture sampling: point/bilinear at known positions, address modes, mip selection from quad
derivatives (trilinear between known levels), LOD bias, 1D/3D/cube lookups and projected
reads through the IR, against texel mixes worked out by hand."""
import numpy as np
import pytest

from backends.reference.evaluate import evaluate
from backends.reference.renderer import sampler_callbacks
from backends.reference.sampler import (SamplerSettings, cube_face_coords, sample_1d,
                                        sample_2d, sample_3d, sample_cube)
from effects.program.ir import Builder
from effects.program.passprogram import PassProgram, TextureBinding
from effects.assets.textures import cube_face_uv, make_texture
from effects.program.texture import Texture

LINEAR = SamplerSettings(min_filter="LINEAR", mag_filter="LINEAR")


def ramp(h=4, w=4):
    """(H, W, 4) level whose red channel is 4*row + col (so bilinear results are linear)."""
    level = np.zeros((h, w, 4), np.float32)
    level[..., 0] = np.arange(h)[:, None] * w + np.arange(w)[None, :]
    level[..., 3] = 1
    return level


def quad(u, v, du=1e-4, dv=1e-4, extra=()):
    """4 rows of one 2x2 quad whose coordinates step du per pixel in x and dv in y."""
    rows = [(u, v), (u + du, v), (u, v + dv), (u + du, v + dv)]
    return np.array([r + tuple(extra) for r in rows], np.float32)


def red(texels):
    return texels[:, 0]


def test_point_sampling_reads_the_texel_containing_the_coordinate():
    level = ramp()
    uv = np.array([[0.125, 0.125], [0.99, 0.01], [0.26, 0.74], [0.5, 0.5]], np.float32)
    # texel (row, col): (0, 0), (0, 3), (2, 1), (2, 2)
    np.testing.assert_array_equal(red(sample_2d([level], uv, SamplerSettings())), [0, 3, 9, 10])


def test_bilinear_at_known_positions_of_a_4x4_texture():
    level = ramp()
    uv = np.concatenate([quad(0.125, 0.125), quad(0.25, 0.25), quad(0.3, 0.6)])
    out = red(sample_2d([level], uv, LINEAR))
    # centre of texel (0,0) -> 0; corner shared by texels 0,1,4,5 -> 2.5;
    # (0.3, 0.6): x = 1.2 - 0.5 = 0.7, y = 2.4 - 0.5 = 1.9 -> 0.1*(0.3*4 + 0.7*5)
    #   + 0.9*(0.3*8 + 0.7*9) = 0.47 + 7.83 = 8.3
    np.testing.assert_allclose(out[[0, 4, 8]], [0.0, 2.5, 8.3], atol=1e-5)


@pytest.mark.parametrize("mode, expected", [
    # u = 0.05 on row 0: x = -0.3 mixes texel -1 (weight 0.3) and texel 0 (weight 0.7)
    ("WRAP", 0.3 * 3 + 0.7 * 0),      # texel -1 wraps to 3
    ("CLAMP", 0.0),                   # texel -1 clamps to 0
    ("MIRROR", 0.0),                  # texel -1 mirrors to 0
    ("BORDER", 0.3 * 10 + 0.7 * 0),   # texel -1 reads the border colour (10)
])
def test_bilinear_address_modes_at_the_left_edge(mode, expected):
    s = SamplerSettings(address_u=mode, address_v=mode, border=(10, 10, 10, 10),
                        min_filter="LINEAR", mag_filter="LINEAR")
    out = red(sample_2d([ramp()], quad(0.05, 0.125), s))
    assert out[0] == pytest.approx(expected, abs=1e-5)


@pytest.mark.parametrize("mode, expected", [
    # u -> texel index floor(4u): -0.1 -> -1, 1.1 -> 4, 1.6 -> 6, -1.3 -> -6
    ("WRAP", [3, 0, 2, 2]),
    ("MIRROR", [0, 3, 1, 2]),
    ("CLAMP", [0, 3, 3, 0]),
    ("BORDER", [-7, -7, -7, -7]),
    ("MIRRORONCE", [0, 3, 3, 3]),
])
def test_point_address_modes(mode, expected):
    s = SamplerSettings(address_u=mode, border=(-7, -7, -7, -7))
    uv = np.array([[-0.1, 0.125], [1.1, 0.125], [1.6, 0.125], [-1.3, 0.125]], np.float32)
    np.testing.assert_array_equal(red(sample_2d([ramp()], uv, s)), expected)


def constant_chain(values, size=8):
    """Mip levels of sizes size, size/2, ... each filled with one value."""
    levels = []
    for value in values:
        levels.append(np.full((size, size, 4), value, np.float32))
        size = max(size // 2, 1)
    return levels


CHAIN = constant_chain([0.0, 1.0, 0.5, 0.25])          # 8x8, 4x4, 2x2, 1x1


def lod_quad(lod, size=8):
    """A quad whose uv steps 2^lod texels of an N-texel level per pixel in x and y."""
    step = 2.0 ** lod / size
    return quad(0.3, 0.3, step, step)


@pytest.mark.parametrize("lod, mip, expected", [
    (1.0, "LINEAR", 1.0),            # exactly level 1
    (1.5, "LINEAR", 0.75),           # halfway between level 1 (1.0) and level 2 (0.5)
    (2.5, "LINEAR", 0.375),          # between 0.5 and 0.25
    (1.5, "POINT", 1.0),             # nearest level: 1.5 is still level 1's
    (1.6, "POINT", 0.5),
    (1.5, "NONE", 0.0),              # no mipmapping: the base level
    (-1.0, "LINEAR", 0.0),           # magnified: level 0
    (7.0, "LINEAR", 0.25),           # beyond the chain: the last level
])
def test_mip_level_from_quad_derivatives(lod, mip, expected):
    s = SamplerSettings(min_filter="LINEAR", mag_filter="LINEAR", mip_filter=mip)
    out = red(sample_2d(CHAIN, lod_quad(lod), s))
    np.testing.assert_allclose(out, expected, atol=1e-5)


def test_lod_is_the_longer_derivative_and_one_per_quad():
    s = SamplerSettings(min_filter="LINEAR", mag_filter="LINEAR", mip_filter="LINEAR")
    # ddx spans 2 texels, ddy 4 -> LOD 2 -> level 2 (0.5) on all four rows
    out = red(sample_2d(CHAIN, quad(0.3, 0.3, 2 / 8, 4 / 8), s))
    np.testing.assert_allclose(out, 0.5, atol=1e-6)
    # diagonal ddx (3, 4) texels -> length 5 -> LOD log2(5) = 2.3219 -> 0.5 + 0.3219*(0.25-0.5)
    out = red(sample_2d(CHAIN, np.array([[0.3, 0.3], [0.3 + 3 / 8, 0.3 + 4 / 8], [0.3, 0.3],
                                          [0.3 + 3 / 8, 0.3 + 4 / 8]], np.float32), s))
    np.testing.assert_allclose(out, 0.5 - (np.log2(5) - 2) * 0.25, atol=1e-5)


def test_lod_bias_and_max_mip_level():
    base = dict(min_filter="LINEAR", mag_filter="LINEAR", mip_filter="LINEAR")
    # sampler bias +1: LOD 1 -> 2 -> 0.5
    out = sample_2d(CHAIN, lod_quad(1.0), SamplerSettings(lod_bias=1.0, **base))
    np.testing.assert_allclose(red(out), 0.5, atol=1e-6)
    # per-row bias (texldb) -0.5: LOD 1 -> 0.5 -> halfway between 0.0 and 1.0
    out = sample_2d(CHAIN, lod_quad(1.0), SamplerSettings(**base), bias=np.full(4, -0.5))
    np.testing.assert_allclose(red(out), 0.5, atol=1e-6)
    # MaxMipLevel 2: nothing more detailed than level 2 is used
    out = sample_2d(CHAIN, lod_quad(0.5), SamplerSettings(max_mip_level=2, **base))
    np.testing.assert_allclose(red(out), 0.5, atol=1e-6)
    # explicit LOD (texldl) replaces the derivative one
    out = sample_2d(CHAIN, lod_quad(0.0), SamplerSettings(**base), lod=np.full(4, 2.5))
    np.testing.assert_allclose(red(out), 0.375, atol=1e-6)


def test_min_and_mag_filters_are_chosen_by_the_lod():
    s = SamplerSettings(min_filter="LINEAR", mag_filter="POINT")
    # magnified at (0.3, 0.125): point -> texel (0, 1) = 1
    assert red(sample_2d([ramp()], quad(0.3, 0.125), s))[0] == 1
    # minified (2 texels per pixel), no mips: bilinear on level 0: x = 0.7 -> 0.7
    assert red(sample_2d([ramp()], quad(0.3, 0.125, 0.5, 0.5), s))[0] == pytest.approx(0.7)


@pytest.mark.parametrize("format", ["V8U8", "L6V5U5", "X8L8V8U8"])
def test_signed_bump_texels_filter_to_signed_values(format):
    values = np.zeros((2, 2, 4), np.float32)
    values[..., 0] = [[-1, 1], [-1, 1]]
    values[..., 2] = 1                          # the luminance channel of the L formats
    tex = make_texture(values, format, mips=False)
    s = SamplerSettings(address_u="CLAMP", address_v="CLAMP", min_filter="LINEAR",
                        mag_filter="LINEAR")
    # u = 0.375: x = 0.25 -> 0.75 * (-1) + 0.25 * 1 = -0.5
    out = sample_2d(tex.levels, quad(0.375, 0.5), s)
    assert out[0, 0] == pytest.approx(-0.5, abs=1e-6)
    assert out[0, 2] == 1 and out[0, 3] == 1   # (U, V, 1, 1) and (U, V, L = 1, 1)


def test_1d_lookup():
    level = ramp(1, 4)                       # values 0, 1, 2, 3 along u
    u = np.array([[0.375], [0.5], [0.9], [0.0]], np.float32)
    clamp = SamplerSettings(address_u="CLAMP", min_filter="LINEAR", mag_filter="LINEAR")
    # x = 4u - 0.5: 1.0 -> 1; 1.5 -> 1.5; 3.1 -> clamp to 3; -0.5 -> 0
    np.testing.assert_allclose(red(sample_1d([level], u, clamp)), [1, 1.5, 3, 0], atol=1e-6)


def volume():
    level = np.zeros((2, 2, 2, 4), np.float32)   # (D, H, W): value 4z + 2y + x
    z, y, x = np.meshgrid(range(2), range(2), range(2), indexing="ij")
    level[..., 0] = 4 * z + 2 * y + x
    return level


def test_3d_lookup_point_and_trilinear():
    s = SamplerSettings(address_u="CLAMP", address_v="CLAMP", address_w="CLAMP")
    uvw = np.array([[0.75, 0.25, 0.75]] * 4, np.float32)
    assert red(sample_3d([volume()], uvw, s))[0] == 5          # texel x=1, y=0, z=1
    lin = SamplerSettings("CLAMP", "CLAMP", "CLAMP", min_filter="LINEAR", mag_filter="LINEAR")
    uvw = np.array([[0.5, 0.5, 0.5]] * 4 + [[0.5, 0.25, 0.75]] * 4, np.float32)
    # the centre mixes all eight equally -> 3.5; (0.5, 0.25, 0.75) -> x 0.5, y 0, z 1 -> 4.5
    np.testing.assert_allclose(red(sample_3d([volume()], uvw, lin))[[0, 4]], [3.5, 4.5])


def cube_level(size=4):
    level = np.zeros((6, size, size, 4), np.float32)   # value 16*face + 4*row + col
    f, r, c = np.meshgrid(range(6), range(size), range(size), indexing="ij")
    level[..., 0] = 16 * f + 4 * r + c
    return level


@pytest.mark.parametrize("direction, face", [
    ((1, 0, 0), 0), ((-1, 0, 0), 1), ((0, 1, 0), 2), ((0, -1, 0), 3), ((0, 0, 1), 4),
    ((0, 0, -1), 5),
    ((1, 1, 0), 0), ((-1, 0, -1), 1), ((0, -1, 1), 3), ((1, 1, 1), 0),   # ties: x, then y
    ((0.2, -0.9, 0.5), 3), ((0.1, 0.2, -0.3), 5),
])
def test_cube_face_selection(direction, face):
    d = np.array([direction] * 4, np.float32)
    assert cube_face_coords(d)[0][0] == face
    out = red(sample_cube([cube_level()], d, SamplerSettings()))
    assert out[0] // 16 == face


@pytest.mark.parametrize("direction, value", [
    # +X: u = (-z/|x| + 1)/2 = 0.75 -> col 3, v = (-y/|x| + 1)/2 = 0.25 -> row 1
    ((1, 0.5, -0.5), 0 + 4 + 3),
    # +Y: u = (x + 1)/2 = 0.75 -> col 3, v = (z/|y| + 1)/2 = 0.375 -> row 1
    ((0.5, 1, -0.25), 32 + 4 + 3),
    # -Z: u = (-x/|z| + 1)/2 = 0.75 -> col 3, v = (-y/|z| + 1)/2 = 0.4 -> row 1
    ((-0.5, 0.2, -1), 80 + 4 + 3),
    # -X (scaled by 2): u = (z/|x| + 1)/2 = 0.25 -> col 1, v = (-y/|x| + 1)/2 = 0.875 -> row 3
    ((-2, -1.5, -1), 16 + 12 + 1),
])
def test_cube_texel_placement_on_faces(direction, value):
    d = np.array([direction] * 4, np.float32)
    assert red(sample_cube([cube_level()], d, SamplerSettings()))[0] == value


def test_cube_face_coords_agree_with_the_texture_generators():
    d = np.random.default_rng(3).normal(size=(200, 3)).astype(np.float32)
    face, u, v = cube_face_coords(d)
    face2, u2, v2 = cube_face_uv(d)
    np.testing.assert_array_equal(face, face2)
    np.testing.assert_allclose(u, u2, atol=1e-6)
    np.testing.assert_allclose(v, v2, atol=1e-6)


def test_cube_lod_across_a_face_edge_uses_one_face():
    # A quad straddling the +X / +Z edge with tiny direction steps must not minify: with
    # mips of value 0 (level 0) and 1 (level 1) it reads level 0.
    levels = [np.zeros((6, 4, 4, 4), np.float32), np.ones((6, 2, 2, 4), np.float32)]
    d = np.array([[1, 0, 0.999], [1, 0, 1.001], [1, 0.001, 0.999], [1, 0.001, 1.001]],
                 np.float32)
    s = SamplerSettings(min_filter="LINEAR", mag_filter="LINEAR", mip_filter="LINEAR")
    np.testing.assert_array_equal(red(sample_cube(levels, d, s)), 0)


def test_projected_lookup_through_the_ir_and_sampler_callbacks():
    b = Builder("fragment")
    b.output("color0", b.sample(0, b.varying("tc"), proj=True))
    program = PassProgram(b.build(), textures=(TextureBinding(0, "ramp"),))
    callbacks = sampler_callbacks(program, {"ramp": Texture("2d", "A8R8G8B8", [ramp()])})
    # (0.5, 1.25, 0, 2) / 2 -> (0.25, 0.625): texel row 2, col 1 -> 9
    tc = np.array([[0.5, 1.25, 0, 2]] * 4, np.float32)
    out = evaluate(program.fragment, {"tc": tc}, callbacks).outputs["color0"]
    np.testing.assert_array_equal(out[:, 0], 9)


def test_unbound_and_missing_textures_have_no_callback():
    b = Builder("fragment")
    b.output("color0", b.sample(1, b.varying("tc")))
    unbound = PassProgram(b.build(), textures=(TextureBinding(1, None),))
    assert sampler_callbacks(unbound, {}) == {}
    out = evaluate(unbound.fragment, {"tc": np.zeros((4, 4), np.float32)}, {})
    np.testing.assert_array_equal(out.outputs["color0"], np.tile([0, 0, 0, 1], (4, 1)))
