"""Persson's omni-directional shadows (fxfiles/shadows.fx): the cube render target a DXSAS
script draws face by face, and the shadow of a known occluder against the geometry, on both
back ends.

The test scene (fxfiles/shadow_scene.obj): a floor at y = 0 and a cube of side 1 from
y = 1.5 to 2.5 over the origin; the point light at (0, 4, 0) straight above it; the camera at
(0, 8, 0) looking straight down (up +z, 60° field of view), so the floor maps linearly onto the
frame: pixel centre px (D3D: at integer positions) sees floor x = (2 px / W - 1) · 8 tan 30°.
The cube's shadow is the light's projection of its top face, a square of half-side
0.5 · 4 / (4 - 2.5) = 4/3; the camera sees the lit top face over the middle of it, a square of
half-side 0.5 · 8 / (8 - 2.5) in floor units. The dark pixels are the ring between the two.
"""
from __future__ import annotations

from tests.paths import ROOT

import math

import numpy as np
import pytest

import effects
from effects.d3d9.caps import load_profile
from effects.host.runtime import Runtime, render_frame
from effects.host.scene import scene_from_mapping
from effects.host.scripts import cube_face_matrices, is_cube_target
from effects.assets.textures import cube_directions, cube_face_uv

BACKENDS = ["numpy", "gl"]
FXFILES = ROOT / "fxfiles"
SIZE = 256
LIGHT_Y, TOP, BOTTOM, HALF, EYE_Y = 4.0, 2.5, 1.5, 0.5, 8.0
EXTENT = EYE_Y * math.tan(math.radians(30))          # floor half-width the frame sees
DARK = 60                                            # red below this: in shadow (ambient 26)


@pytest.fixture(scope="module")
def effect():
    return effects.load_effect(FXFILES / "shadows.fx")


def scene(**params) -> object:
    return scene_from_mapping({
        "mesh": "shadow_scene.obj", "size": [SIZE, SIZE],
        "camera": {"eye": [0, EYE_Y, 0], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 60},
        "light": {"position": [0, LIGHT_Y, 0]}, "params": params}, base_dir=str(FXFILES))


def floor_coordinates() -> tuple[np.ndarray, np.ndarray]:
    """(x, z) on the floor seen at each pixel centre (row 0 at the top is +z)."""
    p = np.arange(SIZE)
    x = (2 * p / SIZE - 1) * EXTENT
    z = (1 - 2 * p / SIZE) * EXTENT
    return np.meshgrid(x, z)


def expected_dark() -> np.ndarray:
    x, z = floor_coordinates()
    shadow = LIGHT_Y / (LIGHT_Y - TOP) * HALF
    top_image = EYE_Y / (EYE_Y - TOP) * HALF
    inside = lambda h: (np.abs(x) < h) & (np.abs(z) < h)  # noqa: E731
    return inside(shadow) & ~inside(top_image)


def pixel_centre_directions(n: int) -> np.ndarray:
    """(6, n, n, 3) directions through the pixel centres each face is rasterised at: the
    face-local (s, t) of `cube_directions` less half a texel (2 / n / 2)."""
    face, u, v = cube_face_uv(cube_directions(n))
    s, t = 2 * (u - 0.5 / n) - 1, 2 * (v - 0.5 / n) - 1
    one = np.ones_like(s[0])
    faces = [(one, -t[0], -s[0]), (-one, -t[1], s[1]), (s[2], one, t[2]), (s[3], -one, -t[3]),
             (s[4], -t[4], one), (-s[5], -t[5], -one)]
    assert (face == np.arange(6)[:, None, None]).all()
    return np.stack([np.stack(f, axis=-1) for f in faces])


def draw(effect, backend, technique, **params):
    frame = render_frame(effect, "refrast", technique=technique, backend=backend,
                         scene=scene(**params))
    assert not frame.warnings, frame.warnings
    return frame.image[..., 0].astype(int)


def test_cube_target_holds_the_squared_light_distance_on_every_face(effect):
    """The shadow pass alone: each face's texels hold |P - light|² of the floor point their
    direction hits (faces in D3D order, as a cube texture is sampled), the sky FarAway."""
    rt = Runtime(effect, "refrast", scene=scene(), backend="numpy")
    shadow = effect.parameter("ShadowCube32")
    assert is_cube_target(shadow)
    from effects.host.scripts import ScriptRunner
    runner = ScriptRunner(rt, effect.technique("Shadow1_R32F"))
    runner.run()
    texels = rt.texture("ShadowCube32").levels[0][..., 0]
    assert texels.shape == (6, 256, 256)
    # Direct3D 9 puts pixel centres at integer positions, texel centres at j + 0.5: what
    # texel j of a face holds was drawn for the direction through j, half a texel off the
    # centre a look-up reads it at (absorbed by the bias, as on the real runtime)
    d = pixel_centre_directions(256)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    t = np.where(d[..., 1] < 0, LIGHT_Y / np.maximum(-d[..., 1], 1e-9), 1e9)
    hit = d * t[..., None]                                   # the floor point, from the light
    on_floor = (d[..., 1] < -0.05) & (np.abs(hit[..., 0]) < 4.9) & (np.abs(hit[..., 2]) < 4.9)
    # not towards the cube (its shadow cone, with a texel's margin)
    cone = (np.abs(hit[..., 0]) < 4 / 3 + 0.1) & (np.abs(hit[..., 2]) < 4 / 3 + 0.1)
    check = on_floor & ~cone
    for face in (1, 0, 3, 4, 5):                             # every face but +Y sees the floor
        assert check[face].sum() > 2000, face
    expected = t ** 2
    rel = np.abs(texels[check] - expected[check]) / expected[check]
    assert np.percentile(rel, 99) < 0.01 and rel.mean() < 0.003
    assert (texels[2] == 1.0e6).all()                        # +Y: only sky
    # under the light (-Y face, the middle): the cube's top face at distance 1.5
    assert abs(texels[3, 128, 128] - (LIGHT_Y - TOP) ** 2) < 1e-3


def test_cube_faces_look_out_from_the_named_origin(effect):
    m = cube_face_matrices(effect.parameter("ShadowCube32"), effect, np.identity(4))
    assert len(m) == 6
    light = np.array([0, 4, 0, 1.0])
    looks = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    for face, look in enumerate(looks):      # one unit along each face's axis: straight ahead
        ahead = np.array([*(np.array(light[:3]) + look), 1.0]) @ m[face]["view"]
        np.testing.assert_allclose(ahead[:3], [0, 0, 1], atol=1e-12)


@pytest.mark.parametrize("backend", BACKENDS)
def test_shadow_covers_the_area_the_geometry_gives(effect, backend):
    red = draw(effect, backend, "Shadow1_R32F")
    dark = red < DARK
    want = expected_dark()
    # the ring's area in floor units, against the dark pixels' (each pixel (2 EXTENT / SIZE)²)
    shadow, top_image = LIGHT_Y / (LIGHT_Y - TOP) * HALF, EYE_Y / (EYE_Y - TOP) * HALF
    area = (2 * shadow) ** 2 - (2 * top_image) ** 2          # 4.995
    measured = dark.sum() * (2 * EXTENT / SIZE) ** 2
    assert abs(measured - area) <= 0.03 * area, (measured, area)
    # in the right place: every pixel centre inside is dark, and no dark pixel is more than a
    # pixel outside (the outer edge lies 0.05 px inside pixel 165's centre here)
    assert (dark & want).sum() == want.sum()
    near = np.zeros_like(want)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            near |= np.roll(np.roll(want, dy, 0), dx, 1)
    assert not (dark & ~near).any()
    # the ambient in the shadow, the lit floor and top face by hand: 0.1 + 0.9 N.L
    assert abs(np.median(red[want]) - 0.1 * 255) <= 1
    assert abs(red[128, 128] - round(255 * (0.1 + 0.9))) <= 2   # top face, N.L = 1


def transition_width(red: np.ndarray) -> float:
    """Mean pixels per shadow edge strictly between the shadow's level and the lit floor's
    beside it (10 %..90 %), over the rows through the shadow's middle: its left edge (near
    px 91) in columns 76..100, its right edge (near px 165) in 156..180."""
    widths = []
    for lo_col, hi_col, lit_col in ((76, 101, 76), (156, 181, 180)):
        rows = red[110:146, lo_col:hi_col].astype(float)
        lit = red[110:146, lit_col:lit_col + 1].astype(float)
        frac = (rows - 0.1 * 255) / (lit - 0.1 * 255)
        widths.append(((frac > 0.1) & (frac < 0.9)).sum(axis=1).mean())
    return float(np.mean(widths))


@pytest.mark.parametrize("backend", BACKENDS)
def test_four_samples_soften_the_edge(effect, backend):
    one = draw(effect, backend, "Shadow1_R32F")
    four = draw(effect, backend, "Shadow4_R32F")                    # ShadowSpread 0.03
    wide = draw(effect, backend, "Shadow4_R32F", ShadowSpread=0.05)
    hard, soft, softer = (transition_width(im) for im in (one, four, wide))
    # his offsets span 3 · ShadowSpread in x: 0.09 floor units (2.5 px), 0.15 (4.2 px)
    assert hard <= 0.5 and 2.0 <= soft <= 3.5 and 3.5 <= softer <= 5.5, (hard, soft, softer)
    # fixed offsets against a percentage bias alone darkened the floor at 0.05 where an offset
    # look-up landed on the floor nearer the light; the slope term (the offset's angle) keeps
    # both spreads clean
    x, z = floor_coordinates()
    lit = np.maximum(np.abs(x), np.abs(z)) > 4 / 3 + 0.25
    assert ((four < one - 10) & lit).sum() == 0
    assert ((wide < one - 10) & lit).sum() == 0


@pytest.mark.parametrize("backend", BACKENDS)
def test_the_bias_removes_acne_on_the_lit_floor(effect, backend):
    x, z = floor_coordinates()
    lit = (np.maximum(np.abs(x), np.abs(z)) > 4 / 3 + 0.15)   # clear of the shadow's edge
    unbiased = draw(effect, backend, "Shadow1_R32F", ShadowFactors1=[1.0, 1.0, 0.0, 0.0],
                    ShadowTexelAngle=0.0)
    biased = draw(effect, backend, "Shadow1_R32F")
    acne = (unbiased < DARK) & lit
    assert acne.sum() > 0.05 * lit.sum(), acne.sum()         # self-shadowing speckles
    assert ((biased < DARK) & lit).sum() == 0


def test_back_ends_agree(effect):
    for technique in ("Shadow1_R32F", "Shadow4_R32F", "Shadow4_R16F", "Shadow4_Linear8"):
        a = draw(effect, "numpy", technique)
        b = draw(effect, "gl", technique)
        off = np.abs(a - b) > 2
        assert off.mean() < 0.005, (technique, off.sum())


@pytest.mark.parametrize("backend", BACKENDS)
def test_linear_fallback_casts_the_same_shadow(effect, backend):
    """The A8R8G8B8 fallback of the cards without float cube targets: the same area."""
    red = draw(effect, backend, "Shadow4_Linear8", ShadowSpread=0.0)
    one = draw(effect, backend, "Shadow1_R32F")
    assert abs(int((red < DARK).sum()) - int((one < DARK).sum())) <= 0.01 * (one < DARK).sum()


@pytest.mark.parametrize("card, technique", [
    ("refrast", "Shadow4_R32F"), ("modern", "Shadow4_R32F"),
    ("radeon9700", "Shadow4_R32F"), ("radeonx1800", "Shadow4_R32F"),
    ("geforcefx5900", "Shadow4_Linear8"), ("gma900", "Shadow4_Linear8"),
    ("geforce6800", "Shadow4_R16F"), ("geforce3", "Lit_ff"), ("tnt2", "Lit_ff")])
def test_cards_without_float_cube_targets_fall_back(effect, card, technique):
    from effects.validate.select import find_valid_technique
    chosen = find_valid_technique(effect, load_profile(card))
    assert chosen.name == technique
    if card in ("geforcefx5900", "geforce6800"):
        reasons = effect.validate(effect.technique("Shadow4_R32F"), load_profile(card)).reasons
        assert any("R32F" in r.message and "cube" in r.message for r in reasons)
    if card == "geforcefx5900":                   # R16F without the cube usage
        reasons = effect.validate(effect.technique("Shadow4_R16F"), load_profile(card)).reasons
        assert any("R16F" in r.message and "cube" in r.message for r in reasons)


def test_the_radeon_9700_draws_persson_s_technique(effect, bundled_scene):
    """The card Persson wrote for (caps_profiles/radeon9700.yaml: R300's float cube maps,
    sourced) selects the R32F technique and draws the occluder's top as Lambert gives it,
    where the 8-bit fallback it used to get dotted 30 % of the top (fp24 arithmetic: the
    stored squared distance keeps 16 mantissa bits, far inside the margin)."""
    frame = render_frame(effect, "radeon9700", backend="numpy", scene=bundled_scene)
    assert frame.technique.name == "Shadow4_R32F"
    mask, want = top_face_lambert(bundled_scene)
    red = frame.image[..., 0].astype(float)[mask]
    assert np.abs(red - want[mask]).max() <= 2
    floor = frame.image[..., 0].astype(int)
    refrast = render_frame(effect, "refrast", backend="numpy", scene=bundled_scene).image
    assert (np.abs(floor - refrast[..., 0].astype(int)) > 2).mean() < 0.002


@pytest.mark.parametrize("backend", BACKENDS)
def test_half_float_fallback_casts_the_shadow_of_the_single_float_map(effect, backend):
    """Shadow4_R16F (GeForce 6800): the squared distance in halves, 1 part in 2048, is the
    R32F technique's shadow within a few edge pixels, and the floor clear of acne."""
    half = draw(effect, backend, "Shadow4_R16F")
    single = draw(effect, backend, "Shadow4_R32F")
    assert (np.abs(half - single) > 2).sum() <= 0.01 * (single < DARK).sum()
    x, z = floor_coordinates()
    lit = np.maximum(np.abs(x), np.abs(z)) > 4 / 3 + 0.25
    assert ((half < DARK) & lit).sum() == 0


def test_half_float_map_holds_the_squared_distance_rounded_to_halves(effect):
    from effects.host.scripts import ScriptRunner
    rt = Runtime(effect, "geforce6800", scene=scene(), backend="numpy")
    ScriptRunner(rt, effect.technique("Shadow4_R16F")).run()
    texels = rt.texture("ShadowCube16").levels[0][..., 0]
    assert texels.shape == (6, 256, 256)
    assert (texels[2] == 60000.0).all()                      # +Y: only sky, the half clear
    assert texels[3, 128, 128] == np.float16((LIGHT_Y - TOP) ** 2)   # 2.25 is a half exactly
    floor = texels[3][(texels[3] > 2.5) & (texels[3] < 1e4)]
    assert len(floor) > 1000
    assert (floor.astype(np.float16).astype(np.float32) == floor).all()   # stored as halves


# ---------------------------------------------------------------------------------------------
# The occluder's lit top face on the bundled scene (fxfiles/shadows.yaml: light at (1, 4, 0.5),
# camera at (0, 7, -5) looking at (0, 0.5, 0)) and the default sphere: no acne in any technique.

SHADOW_TECHNIQUES = ["Shadow4_R32F", "Shadow1_R32F", "Shadow4_R16F", "Shadow4_Linear8"]


def top_face_lambert(scene) -> tuple[np.ndarray, np.ndarray]:
    """(mask, red) for the cube's top face (y = 2.5, |x|, |z| < 0.5, less a 0.02 margin at the
    edges) as the scene's camera sees it: each pixel centre's ray (D3D: at integer positions,
    y up the frame) met with the plane by hand, and 255 (0.1 + 0.9 N.L) there, N = +y."""
    cam = scene.camera
    w, h = scene.size
    eye, target = np.array(cam.eye, float), np.array(cam.target, float)
    forward = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(cam.up, forward)                      # left-handed: x right, y up, z in
    right /= np.linalg.norm(right)
    up = np.cross(forward, right)
    px, py = np.meshgrid(np.arange(w), np.arange(h))
    half = math.tan(math.radians(cam.fov) / 2)
    ray = (forward + ((2 * px / w - 1) * half * w / h)[..., None] * right
           + ((1 - 2 * py / h) * half)[..., None] * up)
    t = (TOP - eye[1]) / ray[..., 1]
    p = eye + ray * t[..., None]
    mask = (np.abs(p[..., 0]) < HALF - 0.02) & (np.abs(p[..., 2]) < HALF - 0.02)
    to_light = np.array(scene.light.position) - p
    n_dot_l = to_light[..., 1] / np.linalg.norm(to_light, axis=-1)
    return mask, 255 * (0.1 + 0.9 * n_dot_l)


@pytest.fixture(scope="module")
def bundled_scene():
    from effects.host.scene import load_scene
    return load_scene(str(FXFILES / "shadows.yaml"))


@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("technique", SHADOW_TECHNIQUES)
def test_the_occluders_lit_top_is_lambert_in_every_technique(effect, bundled_scene, technique,
                                                             backend):
    """Before the slope term the four-sample techniques drew the top at a mean red of 164
    (Lambert: 207), the 8-bit one dotted 30 % of it: their offset look-ups landed on the top
    itself nearer the light, under Persson's 3 % margin."""
    frame = render_frame(effect, "refrast", technique=technique, backend=backend,
                         scene=bundled_scene)
    assert not frame.warnings, frame.warnings
    mask, want = top_face_lambert(bundled_scene)
    assert mask.sum() > 600                                   # 708 pixels at 256 x 256
    red = frame.image[..., 0].astype(float)[mask]
    assert abs(want[mask].mean() - 207.2) < 0.1               # the hand value
    assert np.abs(red - want[mask]).max() <= 2, np.abs(red - want[mask]).max()
    assert abs(red.mean() - want[mask].mean()) <= 0.5


def test_the_occluders_top_stays_lit_with_the_wider_spread(effect, bundled_scene):
    scene = bundled_scene
    from dataclasses import replace
    wide = replace(scene, params={**scene.params, "ShadowSpread": 0.05})
    mask, want = top_face_lambert(scene)
    for technique in ("Shadow4_R32F", "Shadow4_Linear8"):
        red = render_frame(effect, "refrast", technique=technique, backend="numpy",
                           scene=wide).image[..., 0].astype(float)[mask]
        assert np.abs(red - want[mask]).max() <= 2, technique


def sphere_scene(**params):
    """The default scene (`--no-scene`): the sphere of radius 1, the effect's light (0, 4, 0)."""
    return scene_from_mapping({"params": params}, base_dir=str(FXFILES))


@pytest.mark.parametrize("technique", SHADOW_TECHNIQUES)
def test_the_default_sphere_is_free_of_acne(effect, technique):
    """A convex sphere cannot shadow its lit side: every pixel matches the same technique with
    the comparison switched off (bias factor 0: the stored value always wins). Before the
    slope term the four-sample techniques darkened 1,185 of its 10,400 lit pixels in rings
    (up to 28/255), the one-look-up technique 182 near the terminator (up to 77/255)."""
    factors = "ShadowFactors1" if technique == "Shadow1_R32F" else "ShadowFactors4"
    weight = 1.0 if technique == "Shadow1_R32F" else 0.25
    shadowed = render_frame(effect, "refrast", technique=technique, backend="numpy",
                            scene=sphere_scene()).image[..., 0].astype(int)
    unshadowed = render_frame(effect, "refrast", technique=technique, backend="numpy",
                              scene=sphere_scene(**{factors: [0.0, weight, 0.0, 0.0]}))
    unshadowed = unshadowed.image[..., 0].astype(int)
    assert (unshadowed > 40).sum() > 5000                    # the lit part is there
    assert (shadowed < unshadowed - 2).sum() == 0


def test_the_texel_term_is_what_clears_the_spheres_terminator(effect):
    """Without ShadowTexelAngle the single look-up reads a texel drawn for a direction up to a
    texel off, nearer the light on the steep part of the sphere: acne comes back."""
    plain = render_frame(effect, "refrast", technique="Shadow1_R32F", backend="numpy",
                         scene=sphere_scene(ShadowTexelAngle=0.0)).image[..., 0].astype(int)
    off = render_frame(effect, "refrast", technique="Shadow1_R32F", backend="numpy",
                       scene=sphere_scene(ShadowFactors1=[0.0, 1.0, 0.0, 0.0]))
    assert (plain < off.image[..., 0].astype(int) - 10).sum() > 50
