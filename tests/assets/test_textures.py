"""Textures: mip chains, Sobel normal maps, cube map orientation, power tables, loaders and the
procedural registry, each checked against values computed by hand from the formulas."""
import numpy as np
import pytest
from PIL import Image

from effects.assets import textures as T
from effects.assets.texture_files import load_texture
from effects.base.errors import SceneError


# ---- mip chains ------------------------------------------------------------------------------

def grey(a) -> np.ndarray:
    a = np.asarray(a, np.float32)
    return np.repeat(a[..., None], 4, axis=-1)


def test_mip_chain_two_by_two_box():
    levels = T.mip_chain(grey([[0, 1, 4, 4], [2, 3, 4, 4], [8, 8, 0, 0], [8, 8, 0, 2]]))
    assert [lv.shape[:2] for lv in levels] == [(4, 4), (2, 2), (1, 1)]
    assert levels[1][..., 0].tolist() == [[1.5, 4.0], [8.0, 0.5]]
    assert levels[2][0, 0, 0] == pytest.approx((1.5 + 4 + 8 + 0.5) / 4)


def test_mip_chain_odd_and_non_square_sizes():
    # 3 x 3 -> 1 x 1: the area average of all nine texels
    levels = T.mip_chain(grey(np.arange(9).reshape(3, 3)))
    assert [lv.shape[:2] for lv in levels] == [(3, 3), (1, 1)]
    assert levels[1][0, 0, 0] == pytest.approx(4.0)
    # 2 rows x 5 columns -> 1 x 2: column weights (1, 1, 0.5) / 2.5 and (0.5, 1, 1) / 2.5
    row = np.array([10, 20, 30, 40, 50], float)
    levels = T.mip_chain(grey([row, row]))
    assert [lv.shape[:2] for lv in levels] == [(2, 5), (1, 2), (1, 1)]
    assert levels[1][0, :, 0].tolist() == pytest.approx([(10 + 20 + 15) / 2.5, (15 + 40 + 50) / 2.5])
    assert levels[2][0, 0, 0] == pytest.approx(30.0)


def test_mip_chain_soft_blur_on_lower_levels_only():
    # a checker of 2x2 squares becomes a 1-texel checker at level 1; the [1 2 1]/4 blur
    # (wrapping) turns that into flat 0.5, and leaves level 0 alone
    base = grey(np.kron((np.indices((4, 4)).sum(0) % 2), np.ones((2, 2))))
    plain, soft = T.mip_chain(base), T.mip_chain(base, blur=True)
    assert sorted(set(plain[1][..., 0].ravel().tolist())) == [0.0, 1.0]
    assert np.allclose(soft[1][..., 0], 0.5)
    np.testing.assert_array_equal(soft[0], base)


def test_cube_and_volume_chains_keep_faces_and_halve_depth():
    cube = T.mip_chain(np.zeros((6, 8, 8, 4)), kind="cube")
    assert [lv.shape for lv in cube][-1] == (6, 1, 1, 4) and len(cube) == 4
    vol = T.mip_chain(np.zeros((8, 4, 2, 4)), kind="3d")
    assert [lv.shape[:3] for lv in vol] == [(8, 4, 2), (4, 2, 1), (2, 1, 1), (1, 1, 1)]


def test_make_texture_quantises_every_level():
    tex = T.make_texture(grey([[0.1, 0.2], [0.3, 0.4]]), "L8")
    assert tex.levels[0][0, 0].tolist() == pytest.approx([26 / 255] * 3 + [1.0])
    assert tex.levels[1][0, 0, 0] == pytest.approx(64 / 255)   # mean 0.25 -> rint(63.75)


# ---- normal and bump maps ----------------------------------------------------------------------

def test_sobel_normal_map_of_a_ramp():
    a, scale = 0.01, 2.0
    ramp_u = a * np.tile(np.arange(16.0), (16, 1))                  # rises along +u (columns)
    n = T.sobel_normal_map(ramp_u, scale)[8, 8]
    # Sobel dX of a*x is (1 + 2 + 1) * 2a = 8a; n = normalize(-scale * 8a, 0, 1)
    expect = np.array([-scale * 8 * a, 0.0, 1.0])
    expect /= np.linalg.norm(expect)
    assert n.tolist() == pytest.approx((0.5 + 0.5 * expect).tolist() + [1.0], abs=1e-6)
    ramp_v = ramp_u.T                                               # rises down the image (+v)
    n = T.sobel_normal_map(ramp_v, scale)[8, 8]
    assert n[:3].tolist() == pytest.approx((0.5 + 0.5 * expect[[1, 0, 2]]).tolist(), abs=1e-6)


def test_flat_height_gives_straight_up_normals():
    n = T.sobel_normal_map(np.full((4, 4), 0.3))
    assert np.allclose(n, [0.5, 0.5, 1.0, 1.0])


def test_dudv_map_of_a_ramp_is_quantised_v8u8():
    ramp = 0.01 * np.tile(np.arange(64.0), (64, 1))
    dudv = T.bump_map_du_dv(ramp, scale=0.05)
    # dh/du per texture = 0.01 * 64; du = -0.05 * 0.64 = -0.032 -> rint(-4.064) / 127
    assert dudv[10, 10].tolist() == pytest.approx([-4 / 127, 0.0, 1.0, 1.0])
    assert np.allclose(dudv[..., :2] * 127, np.rint(dudv[..., :2] * 127))


# ---- cube maps ---------------------------------------------------------------------------------

def test_normalization_cube_centre_of_each_face():
    cube = T.normalization_cube(5)                       # odd size: texel (2, 2) is the face centre
    axes = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    for face, axis in enumerate(axes):
        assert (2 * cube[face, 2, 2, :3] - 1).tolist() == pytest.approx(list(axis), abs=1e-6)
    stored = T.procedural("normalization_cube", size=5).levels[0]
    # stored as X8R8G8B8: within one 8-bit step, which is 2/255 once expanded to [-1, 1]
    assert (2 * stored[0, 2, 2, :3] - 1).tolist() == pytest.approx([1, 0, 0], abs=2 / 255)


@pytest.mark.parametrize("direction, face, u, v", [
    ((1, 0.5, -0.5), 0, 0.75, 0.25),    # +X: u grows towards -z, v towards -y
    ((-1, 0.5, -0.5), 1, 0.25, 0.25),   # -X: u grows towards +z
    ((0.5, 1, 0.5), 2, 0.75, 0.75),     # +Y: u towards +x, v towards +z (top row borders -Z)
    ((0.5, -1, 0.5), 3, 0.75, 0.25),    # -Y: v towards -z
    ((0.5, 0.5, 1), 4, 0.75, 0.25),     # +Z: u towards +x
    ((0.5, 0.5, -1), 5, 0.25, 0.25),    # -Z: u towards -x
])
def test_cube_face_orientation(direction, face, u, v):
    f, uu, vv = T.cube_face_uv(np.array(direction, float))
    assert (int(f), float(uu), float(vv)) == (face, pytest.approx(u), pytest.approx(v))


def test_cube_directions_invert_cube_face_uv():
    d = T.cube_directions(4)
    f, u, v = T.cube_face_uv(d)
    cu, cv = T.texel_centres(4, 4)
    assert np.all(f == np.arange(6)[:, None, None])
    assert np.allclose(u, cu) and np.allclose(v, cv)


def test_environment_cube_sky_above_ground_below():
    env = T.environment_cube(8)
    sky, ground = env[2, 4, 4], env[3, 4, 4]
    assert sky[2] > sky[0] and ground[0] >= ground[2]


# ---- lookup tables -----------------------------------------------------------------------------

def test_power_table_is_filled_at_texel_centres():
    level0, level1 = T.power_table(256, 16.0, levels=2)
    assert level0[200, 10].tolist() == pytest.approx([(200.5 / 256) ** 16] * 3 + [10.5 / 256])
    assert level0[255, 0, 0] == pytest.approx((255.5 / 256) ** 16)
    # D3DXFillTexture evaluates each mip level afresh at that level's texel centres
    assert level1[5, 100].tolist() == pytest.approx([(5.5 / 128) ** 16] * 3 + [100.5 / 128])


def test_power_table_1d_and_range_table():
    one = T.power_table_1d(64, 8.0)
    assert one.shape == (1, 64, 4)
    assert one[0, 40, 0] == pytest.approx((40.5 / 64) ** 8)
    rng = T.power_range_table(32, 64.0)
    assert rng[3, 20, 0] == pytest.approx((20.5 / 32) ** (3.5 / 32 * 64))


def test_procedural_power_is_stored_as_a8r8g8b8():
    tex = T.procedural("power:24", size=64)
    assert (tex.kind, tex.format, tex.width) == ("2d", "A8R8G8B8", 64)
    assert tex.levels[0][50, 0, 0] == pytest.approx(round((50.5 / 64) ** 24 * 255) / 255)


# ---- procedural registry -----------------------------------------------------------------------

def test_procedural_names_and_sizes():
    tex = T.procedural("sobel_normals:stones", size=64)
    assert (tex.kind, tex.format, tex.width, tex.height, len(tex.levels)) == ("2d", "X8R8G8B8", 64, 64, 7)
    n = 2 * tex.levels[0][..., :3] - 1
    assert np.allclose(np.linalg.norm(n, axis=-1), 1, atol=0.02)
    assert T.procedural("environment").kind == "cube"
    vol = T.procedural("noise_volume", size=8)
    assert vol.kind == "3d" and vol.levels[0].shape == (8, 8, 8, 4)
    dudv = T.procedural("dudv:craters", size=32)
    assert dudv.format == "V8U8" and dudv.signed
    assert T.procedural("earth", size=16).levels[0].shape == (16, 32, 4)


def test_procedural_textures_are_deterministic_and_read_only():
    a = T.height_field(32, "stones")
    assert np.array_equal(a, T.height_field(32, "stones"))
    assert 0.0 <= a.min() and a.max() <= 1.0
    tex = T.procedural("height:craters", size=32)
    with pytest.raises(ValueError):
        tex.levels[0][0, 0, 0] = 1.0


@pytest.mark.parametrize("name, message", [
    ("marble", "unknown procedural texture 'marble'"),
    ("height:lumpy", "bad argument 'lumpy'"),
    ("power:steep", "bad argument 'steep'"),
])
def test_procedural_errors(name, message):
    with pytest.raises(SceneError) as info:
        T.procedural(name, size=8)
    assert message in str(info.value)


# ---- files ------------------------------------------------------------------------------------

def test_png_through_pillow(tmp_path):
    pixels = np.array([[[255, 0, 0, 255], [0, 255, 0, 128]],
                       [[0, 0, 255, 255], [10, 20, 30, 1]]], np.uint8)
    path = tmp_path / "known.png"
    Image.fromarray(pixels, "RGBA").save(path)
    tex = load_texture(path)
    assert (tex.kind, tex.format, len(tex.levels)) == ("2d", "A8R8G8B8", 2)
    np.testing.assert_allclose(tex.levels[0], pixels / 255.0, atol=1e-7)
    assert tex.levels[1][0, 0, 3] == pytest.approx(160 / 255)   # rint(639 / 4)


def test_npy_cube_volume_and_luminance(tmp_path):
    cube = np.random.default_rng(0).uniform(-2, 2, (6, 4, 4, 3)).astype(np.float32)
    np.save(tmp_path / "c.npy", cube)
    tex = load_texture(tmp_path / "c.npy")
    assert (tex.kind, tex.format) == ("cube", "A32B32G32R32F")
    np.testing.assert_array_equal(tex.levels[0][..., :3], cube)
    assert np.all(tex.levels[0][..., 3] == 1)
    np.save(tmp_path / "v.npy", np.zeros((6, 4, 4, 4), np.float32))
    assert load_texture(tmp_path / "v.npy", kind="3d").kind == "3d"
    np.save(tmp_path / "l.npy", np.full((2, 2, 1), 51, np.uint8))
    lum = load_texture(tmp_path / "l.npy")
    assert lum.levels[0][0, 0].tolist() == pytest.approx([0.2, 0.2, 0.2, 1.0])


def test_dds_through_load_texture(tmp_path):
    from effects.assets.dds import write_dds
    tex = T.make_texture(np.zeros((6, 4, 4, 4)), "X8R8G8B8", kind="cube")
    write_dds(tmp_path / "c.dds", tex)
    back = load_texture(tmp_path / "c.dds", kind="cube")
    assert back.kind == "cube" and len(back.levels) == 3


@pytest.mark.parametrize("name, content, kind, message", [
    ("missing.png", None, None, "texture file not found"),
    ("broken.png", b"not an image", None, "cannot read image"),
    ("shape.npy", "bad-shape", None, "is not (H, W, C)"),
    ("flat.png", "png", "cube", "is a 2d texture, but a cube texture is needed"),
    ("notes.txt", b"hello", None, "unknown texture file type '.txt'"),
])
def test_bad_texture_files(tmp_path, name, content, kind, message):
    path = tmp_path / name
    if content == "bad-shape":
        np.save(path, np.zeros((4, 4), np.float32))
    elif content == "png":
        Image.new("RGB", (2, 2)).save(path)
    elif content is not None:
        path.write_bytes(content)
    with pytest.raises(SceneError) as info:
        load_texture(path, kind=kind)
    assert message in str(info.value)
    assert str(info.value).startswith(f"{path}:1:1: error:")


def test_effect_file_generator_names(tmp_path):
    # the names fxfiles/README.md documents: the argument is an image path or an edge length
    ramp = np.tile(np.arange(16, dtype=np.uint8) * 8, (16, 1))          # height rises along +u
    (tmp_path / "tex").mkdir()
    Image.fromarray(ramp, "L").save(tmp_path / "tex" / "h.png")
    normals = T.procedural("sobel_normals:tex/h.png", base_dir=str(tmp_path))
    assert (normals.format, normals.width) == ("X8R8G8B8", 16)
    # interior texel: dX = 8 * (8 / 255), scale 1 for images; n leans towards -u
    expect = np.array([-64 / 255, 0, 1.0]) / np.hypot(64 / 255, 1.0)
    assert normals.levels[0][5, 5, :3].tolist() == pytest.approx((0.5 + 0.5 * expect).tolist(), abs=1 / 255)
    dudv = T.procedural("sobel_dudv:tex/h.png", base_dir=str(tmp_path))
    assert dudv.format == "V8U8"
    assert dudv.levels[0][5, 5, :2].tolist() == pytest.approx([round(expect[0] * 127) / 127, 0.0])
    assert T.procedural("normalization_cube:8").levels[0].shape == (6, 8, 8, 4)
    sky = T.procedural("sky_cube:16")
    assert sky.kind == "cube" and sky.width == 16
    noise = T.procedural("noise3d:8")
    assert (noise.kind, noise.format, noise.levels[0].shape) == ("3d", "L8", (8, 8, 8, 4))
    table = T.procedural("power_table:16", size=32)
    assert table.levels[0][31, 0, 0] == pytest.approx(round((31.5 / 32) ** 16 * 255) / 255)


def test_missing_height_image_is_reported_at_the_annotation(tmp_path):
    from effects.base.errors import Location
    where = Location("fx/phong.fx", 94, 5)
    with pytest.raises(SceneError) as info:
        T.procedural("sobel_normals:textures/none.png", base_dir=str(tmp_path), location=where)
    assert str(info.value).startswith("fx/phong.fx:94:5: error: height image not found")
    with pytest.raises(SceneError, match="expected an edge length"):
        T.procedural("normalization_cube:big")


def test_the_texture_caches_are_bounded_by_bytes_least_recently_used_first():
    from effects.base.lru import ByteLRU
    levels = lambda n: T.Texture("2d", "A8R8G8B8", [np.zeros((n, n, 4), np.float32)])  # noqa: E731
    cache = ByteLRU(max_bytes=3 * 16 * 16 * 4 * 4)       # three 16x16 float textures
    for key in "abc":
        cache.put(key, levels(16))
    assert cache.get("a") is not None                    # a is now the most recent
    cache.put("d", levels(16))                           # evicts b, the least recent
    assert "b" not in cache and all(k in cache for k in "acd")
    for n in range(100):                                 # many small ones fit together
        cache.put(("small", n), levels(1))
    assert sum(1 for n in range(100) if ("small", n) in cache) == 100
    cache.put("huge", levels(64))                        # bigger than the bound: not kept
    assert "huge" not in cache and cache.bytes <= cache.max_bytes
