"""The NumPy reference back end end to end: registry and protocol, D3D9 pixel centres, shared
edges blended once, depth order, multipass accumulation, vertex programs, textures with
derivative LOD, kill, builtins, fog, cube-face render targets, and a lit sphere-like surface
whose pixels must equal the lighting formula within 1/255."""
import numpy as np
import pytest

from backends.base import (Backend, DrawError, UnknownBackend, available_backends,
                           create_backend, render_cube_faces)
from backends.reference.renderer import ReferenceBackend
from effects.errors import EffectError
from effects.ir import Builder
from effects.passprogram import PassProgram, RenderState, TextureBinding
from effects.textures import Texture

QUAD = np.array([[-1, -1, 0.5, 1], [-1, 1, 0.5, 1], [1, 1, 0.5, 1], [1, -1, 0.5, 1]],
                np.float32)
QUAD_INDICES = np.array([0, 1, 2, 0, 2, 3])
UV = np.array([[0, 1], [0, 0], [1, 0], [1, 1]], np.float32)


def colour_pass(value=None, varying="color0", **state):
    """A fragment program writing a constant (or the varying `varying`)."""
    b = Builder("fragment")
    b.output("color0", b.const(value) if value is not None else b.varying(varying))
    return PassProgram(b.build(), render_state=RenderState(**state))


def frame(draws, size=(8, 8), **clear):
    backend = create_backend("numpy", threads=1)
    backend.begin_frame(size, **clear)
    for program, streams, indices, primitive, textures in draws:
        backend.draw(program, streams, indices, primitive, textures)
    return backend.end_frame()


def rect(x0, y0, x1, y1, z=0.5):
    return np.array([[x0, y0, z, 1], [x0, y1, z, 1], [x1, y1, z, 1], [x1, y0, z, 1]],
                    np.float32)


def test_registry_and_protocol():
    backend = create_backend("numpy")
    assert isinstance(backend, ReferenceBackend) and isinstance(backend, Backend)
    assert backend.name == "numpy"
    assert {"numpy", "gl"} <= set(available_backends())
    with pytest.raises(UnknownBackend) as err:
        create_backend("vulkan")
    assert isinstance(err.value, EffectError) and "vulkan" in str(err.value)


def test_clear_and_end_frame_format():
    image = frame([], size=(3, 2), clear_color=(1, 0.5, 0, 0.25))
    assert image.shape == (2, 3, 4) and image.dtype == np.uint8
    assert image[0, 0].tolist() == [255, 128, 0, 64]
    backend = create_backend("numpy")
    with pytest.raises(DrawError):
        backend.draw(colour_pass((1, 1, 1, 1)), {"position": QUAD}, QUAD_INDICES, "list", {})


def test_pixel_centres_on_a_full_screen_quad():
    # u = px / W and v = py / H at D3D9 pixel centres; written as colour
    program = colour_pass(varying="texcoord0")
    image = frame([(program, {"position": QUAD, "texcoord0": UV}, QUAD_INDICES, "list", {})],
                  size=(10, 4))
    px = np.arange(10)
    np.testing.assert_array_equal(image[0, :, 0], np.rint(px / 10 * 255))
    np.testing.assert_array_equal(image[:, 0, 1], np.rint(np.arange(4) / 4 * 255))
    assert (image[..., 2] == 0).all() and (image[..., 3] == 255).all()


def test_shared_edges_are_blended_exactly_once():
    # A jittered grid over the screen, additive blending of 0.25: every pixel gets exactly
    # one fragment -> 64, never 0 (gap) or 128 (double blend).
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
    program = colour_pass((0.25, 0.25, 0.25, 0.25), alpha_blend_enable=True, src_blend="ONE",
                          dest_blend="ONE", z_enable=False)
    image = frame([(program, {"position": pos}, tris, "list", {})], size=(45, 37))
    assert (image == 64).all()


def test_depth_order_in_both_draw_orders_and_with_z_off():
    near = (colour_pass((1, 0, 0, 1)), {"position": rect(-1, -1, 0.5, 0.5, z=0.3)},
            QUAD_INDICES, "list", {})
    far = (colour_pass((0, 1, 0, 1)), {"position": rect(-0.5, -0.5, 1, 1, z=0.6)},
           QUAD_INDICES, "list", {})
    a = frame([near, far])
    b = frame([far, near])
    np.testing.assert_array_equal(a, b)
    # pixel (4, 4) is NDC (0, 0): inside both -> the near (red) one
    assert a[4, 4].tolist() == [255, 0, 0, 255]
    assert a[1, 7].tolist() == [0, 255, 0, 255]        # only the far quad
    # ZEnable off: the last drawn wins
    near_off = (colour_pass((1, 0, 0, 1), z_enable=False),) + near[1:]
    far_off = (colour_pass((0, 1, 0, 1), z_enable=False),) + far[1:]
    assert frame([near_off, far_off])[4, 4].tolist() == [0, 255, 0, 255]
    assert frame([far_off, near_off])[4, 4].tolist() == [255, 0, 0, 255]


def test_multipass_accumulates_into_one_framebuffer():
    add = dict(alpha_blend_enable=True, src_blend="ONE", dest_blend="ONE")
    first = (colour_pass((0.2, 0, 0, 0)), {"position": QUAD}, QUAD_INDICES, "list", {})
    second = (colour_pass((0.2, 0.4, 0, 0), **add), {"position": QUAD}, QUAD_INDICES, "list",
              {})
    image = frame([first, second, second])
    # 0.2 -> 51; + 51 + 51 = 153; green 0.4 -> 102 twice = 204
    assert image[3, 3].tolist() == [153, 204, 0, 0]


def test_strip_and_cull_mode():
    strip = np.array([[-1, -1, 0.5, 1], [-1, 1, 0.5, 1], [1, -1, 0.5, 1], [1, 1, 0.5, 1]],
                     np.float32)
    white = colour_pass((1, 1, 1, 1))
    image = frame([(white, {"position": strip}, np.arange(4), "strip", {})])
    assert (image == 255).all()
    # culling clockwise faces removes both (D3D strips keep the first triangle's winding)
    cw = colour_pass((1, 1, 1, 1), cull_mode="CW")
    assert (frame([(cw, {"position": strip}, np.arange(4), "strip", {})]) == 0).all()


def test_vertex_colours_are_saturated_before_interpolation():
    colours = np.array([[2, 0, 0, 1], [2, 0, 0, 1], [0, 0, 0, 1], [0, 0, 0, 1]], np.float32)
    image = frame([(colour_pass(), {"position": QUAD, "color0": colours}, QUAD_INDICES, "list",
                    {})])
    # red runs from sat(2) = 1 at the left to 0 at the right: 1 - px/8 (not min(2 - 2t, 1))
    np.testing.assert_array_equal(image[0, :, 0], np.rint((1 - np.arange(8) / 8) * 255))


def test_missing_colour_streams_read_the_d3d_defaults():
    b = Builder("fragment")
    b.output("color0", b.add(b.varying("color0"), b.varying("color1")))
    image = frame([(PassProgram(b.build()), {"position": QUAD}, QUAD_INDICES, "list", {})])
    assert (image == 255).all()      # diffuse (1,1,1,1) + specular (0,0,0,0)


def lighting_vertex_program():
    """clip = M @ (x, y, z, 1) with M's rows as uniforms; normal passes through."""
    vb = Builder("vertex")
    pos = vb.varying("position", components=3)
    clip = vb.const(0.0)
    for i in range(4):
        clip = vb.merge(clip, vb.dp4(pos, vb.uniform(f"m{i}")), "xyzw"[i])
    vb.output("position", clip)
    vb.output("texcoord0", vb.varying("normal", components=3))
    return vb.build()


def lighting_fragment_program():
    fb = Builder("fragment")
    n = fb.nrm(fb.varying("texcoord0"))
    diffuse = fb.mul(fb.uniform("kd"), fb.saturate(fb.dp3(n, fb.uniform("light"))))
    spec = fb.pow(fb.saturate(fb.dp3(n, fb.uniform("half"))), fb.const(16.0))
    fb.output("color0", fb.merge(fb.saturate(fb.add(diffuse, spec)), fb.const(1.0), "w"))
    return fb.build()


def test_lit_sphere_like_surface_matches_the_lighting_formula():
    # A 12 x 12 grid over the screen whose normal (x, y, -1) is linear in NDC, transformed by
    # a matrix that scales clip space by w = 2 (same picture). Per pixel the expected colour
    # is computed here from the pixel centre (x = 2 px / W - 1, y = 1 - 2 py / H).
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
    m = np.diag([2.0, 2.0, 2.0, 2.0])
    uniforms = {f"m{r}": m[r] for r in range(4)}
    uniforms.update(light=(*light, 0), half=(*half, 0), kd=kd)
    program = PassProgram(lighting_fragment_program(), lighting_vertex_program(),
                          uniforms=PassProgram.pack_uniforms(uniforms))
    image = frame([(program, {"position": position, "normal": normal}, tris, "list", {})],
                  size=size)
    px, py = np.meshgrid(np.arange(size[0]), np.arange(size[1]))
    n = np.stack([2 * px / size[0] - 1, 1 - 2 * py / size[1], -np.ones(px.shape)], -1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    ndl = np.clip(n @ light, 0, 1)
    ndh = np.clip(n @ half, 0, 1)
    expected = np.clip(kd[:3] * ndl[..., None] + (ndh ** 16)[..., None], 0, 1)
    diff = np.abs(image[..., :3].astype(int) - np.rint(expected * 255))
    assert diff.max() <= 1
    assert (image[..., 3] == 255).all()
    assert len(np.unique(image[..., 0])) > 50       # a real gradient, not a flat colour


def ramp_texture(size=4):
    level = np.zeros((size, size, 4), np.float32)
    level[..., 0] = (np.arange(size)[:, None] * size + np.arange(size)) / (size * size - 1)
    level[..., 3] = 1
    return Texture("2d", "A32B32G32R32F", [level])


def texture_pass(**binding):
    b = Builder("fragment")
    b.output("color0", b.sample(0, b.varying("texcoord0")))
    return PassProgram(b.build(), textures=(TextureBinding(0, "tex", **binding),))


def test_point_sampled_texture_on_a_full_screen_quad():
    image = frame([(texture_pass(), {"position": QUAD, "texcoord0": UV}, QUAD_INDICES, "list",
                    {"tex": ramp_texture()})])
    # odd pixels sample texel centres: u*4 = px/2 = k + 0.5 -> texel (px - 1)/2
    for py in (1, 3, 5, 7):
        for px in (1, 3, 5, 7):
            expected = ((py - 1) // 2 * 4 + (px - 1) // 2) / 15
            assert image[py, px, 0] == np.rint(expected * 255)


def test_mip_level_from_helper_pixel_derivatives():
    # uv spans 16 texels over 8 pixels -> LOD 1 everywhere, even on a lone triangle whose
    # edge quads are partly helpers. Level 0 reads 0, level 1 reads 1, level 2 0.5.
    levels = [np.zeros((n, n, 4), np.float32) for n in (16, 8, 4)]
    for level, value in zip(levels, (0.0, 1.0, 0.5)):
        level[..., 0] = value                  # red carries the level; blue stays 0
    tex = Texture("2d", "A32B32G32R32F", levels)
    program = texture_pass(min_filter="LINEAR", mag_filter="LINEAR", mip_filter="LINEAR")
    image = frame([(program, {"position": QUAD, "texcoord0": UV}, np.array([0, 1, 2]), "list",
                    {"tex": tex})], clear_color=(0, 0, 1, 1))
    covered = image[..., 2] == 0          # pixels the triangle wrote (the clear is blue)
    assert covered.sum() > 20
    assert (image[covered][:, 0] == 255).all()
    # LOD bias -1 brings it back to level 0
    program = texture_pass(min_filter="LINEAR", mag_filter="LINEAR", mip_filter="LINEAR",
                           mip_lod_bias=-1.0)
    image = frame([(program, {"position": QUAD, "texcoord0": UV}, QUAD_INDICES, "list",
                    {"tex": tex})])
    assert (image[..., 0] == 0).all()


def test_unbound_sampler_reads_0001():
    b = Builder("fragment")
    b.output("color0", b.sample(0, b.varying("texcoord0")))
    program = PassProgram(b.build())
    image = frame([(program, {"position": QUAD, "texcoord0": UV}, QUAD_INDICES, "list", {})],
                  clear_color=(1, 1, 1, 0))
    assert (image == [0, 0, 0, 255]).all()


def test_kill_discards_fragments():
    # kill where u - 0.5 < 0: the left half keeps the clear colour
    b = Builder("fragment")
    uv = b.varying("texcoord0")
    b.kill(b.sub(uv, b.const((0.5, 0.0, 0.0, 0.0))), "x")
    b.output("color0", b.const(1.0))
    image = frame([(PassProgram(b.build()), {"position": QUAD, "texcoord0": UV}, QUAD_INDICES,
                    "list", {})])
    assert (image[:, :4] == 0).all() and (image[:, 4:] == 255).all()


def test_vpos_and_vface_builtins():
    b = Builder("fragment")
    pos = b.builtin("vpos")
    scale = b.const((1 / 255, 1 / 255, 0, 0))
    face = b.builtin("vface")
    b.output("color0", b.merge(b.mul(pos, scale), b.saturate(face), "zw"))
    program = PassProgram(b.build(), render_state=RenderState(cull_mode="NONE"))
    image = frame([(program, {"position": QUAD}, QUAD_INDICES, "list", {})])
    py, px = np.mgrid[0:8, 0:8]
    np.testing.assert_array_equal(image[..., 0], px)
    np.testing.assert_array_equal(image[..., 1], py)
    assert (image[..., 2] == 255).all()         # front-facing: +1
    image = frame([(program, {"position": QUAD}, QUAD_INDICES[::-1], "list", {})])
    assert (image[..., 2] == 0).all()           # back-facing: -1 saturates to 0


def test_table_fog_and_specular_enable():
    colours = {"position": QUAD, "color0": np.tile([0.5, 0.5, 0.5, 1], (4, 1)),
               "color1": np.tile([0.25, 0, 0, 0], (4, 1))}
    program = colour_pass(fog_enable=True, fog_table_mode="LINEAR", fog_start=0.0,
                          fog_end=1.0, fog_color=(0, 0, 1, 0), specular_enable=True)
    image = frame([(program, colours, QUAD_INDICES, "list", {})])
    # colour 0.5 + specular 0.25 red; fog factor (1 - z) = 0.5 towards blue
    assert image[2, 2].tolist() == [np.rint(0.75 * 0.5 * 255), 64, np.rint(0.75 * 255), 255]


def test_cube_faces_as_float_render_targets():
    backend = create_backend("numpy")

    def draw_face(face):
        program = colour_pass((10.0 * face + 0.5, 0, 0, 0))
        backend.draw(program, {"position": QUAD}, QUAD_INDICES, "list", {})

    faces = render_cube_faces(backend, 4, draw_face, format="R32F")
    assert faces.shape == (6, 4, 4, 4) and faces.dtype == np.float32
    for f in range(6):
        assert (faces[f, ..., 0] == 10.0 * f + 0.5).all()
        assert (faces[f, ..., 1:] == 1).all()


def test_bad_draw_calls():
    backend = create_backend("numpy")
    backend.begin_frame((4, 4))
    program = colour_pass((1, 1, 1, 1))
    with pytest.raises(DrawError):
        backend.draw(program, {"position": QUAD}, np.array([0, 1, 7]), "list", {})
    with pytest.raises(DrawError):
        backend.draw(program, {"normal": QUAD}, QUAD_INDICES, "list", {})
    with pytest.raises(DrawError):
        backend.draw(program, {"position": QUAD}, QUAD_INDICES, "quads", {})
    with pytest.raises(DrawError):
        backend.begin_frame((4, 4), format="P8")


def test_threaded_chunks_give_the_same_image():
    # Enough triangles for several parallel rasterise-and-shade chunks, overlapping so the
    # in-order merge matters (blending is order dependent), and a texture with helper pixels.
    rng = np.random.default_rng(11)
    count = 3000
    centre = rng.uniform(-1, 1, (count, 2))
    offsets = rng.uniform(-0.15, 0.15, (count, 3, 2))
    xy = (centre[:, None, :] + offsets).reshape(-1, 2)
    pos = np.column_stack([xy, rng.uniform(0.1, 0.9, len(xy)), np.ones(len(xy))]).astype(
        np.float32)
    uv = rng.uniform(0, 1, (len(xy), 2)).astype(np.float32)
    b = Builder("fragment")
    texel = b.sample(0, b.varying("texcoord0"))
    b.output("color0", b.mul(texel, b.const((0.6, 0.6, 0.6, 0.5))))
    state = RenderState(cull_mode="NONE", alpha_blend_enable=True, src_blend="SRCALPHA",
                        dest_blend="INVSRCALPHA", z_enable=False)
    program = PassProgram(b.build(), render_state=state, textures=(
        TextureBinding(0, "tex", min_filter="LINEAR", mag_filter="LINEAR", mip_filter="LINEAR"),))
    levels = [np.random.default_rng(n).uniform(0, 1, (16 >> n, 16 >> n, 4)).astype(np.float32)
              for n in range(5)]
    textures = {"tex": Texture("2d", "A32B32G32R32F", levels)}
    images = []
    for threads in (1, 2):
        backend = create_backend("numpy", threads=threads)
        backend.begin_frame((64, 64))
        backend.draw(program, {"position": pos, "texcoord0": uv}, np.arange(len(xy)), "list",
                     textures)
        images.append(backend.end_frame())
    np.testing.assert_array_equal(images[0], images[1])
    assert len(np.unique(images[0][..., 0])) > 50
