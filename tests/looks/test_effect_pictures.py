"""The bundled effects' pictures, technique by technique, on the NumPy reference back end.

Every technique of fxfiles/phong.fx (Persson's fragment-level Phong and its fallbacks) and
fxfiles/specular_bump.fx (Boyd and Taylor's specular bump-mapped Earth: ps.2.0 -> ps.1.1 table
and multiply -> dot3 -> BumpEnvMap -> emboss -> single texture) is drawn on a card that selects
it, on the default scene (the unit sphere seen from (0, 0, 3), fov 45 degrees), and checked
for what a user would notice, against values computed here from the scene by hand:
- the sphere covers the disc a ray-sphere intersection predicts; the background is the clear;
- the side facing the light is brighter than the side facing away;
- the highlight (brightest pixel) lies where the reflection formula puts it;
- the texture shows, where the sphere's mapping puts it: recovered from three renders (real,
  white and black texture) it equals the texture at each pixel's (u, v), not its mirror image,
  and varies as much;
- the relief is raised, not sunk: the change the normal map makes to the picture correlates
  positively with the change a raised surface makes to N.L (a sunken one, negatively);
- techniques that draw the same look agree in mean colour over the disc.

Two techniques no card selects under the default policy (D3DX's first valid technique) are
drawn on a card where they are valid: SpecularMultiply_ps11 comes after SpecularTable_ps11,
which every ps_1_1 card also runs, so it is named on a GeForce3; the Earth's SingleTexture
comes after Emboss_dx6, which every card runs, so it is chosen on a TNT2 by the "cost"
policy (its Cost annotation, 1, is the lowest).
"""
from __future__ import annotations

from tests.paths import ROOT

import math
import os

import numpy as np
import pytest

import effects
import effects.assets.textures
from effects.assets.texture_files import load_texture
from effects.assets.textures import make_texture, procedural
from effects.program.texture import Texture

FXFILES = os.path.join(str(ROOT), "fxfiles")
SIZE = 128
CLEAR = (255, 0, 255)        # magenta: no bundled texture or lighting result can be exactly this
SCENE = {"clear": {"color": "0xffff00ff"}}

# Default scene (effects.host.scene): eye (0, 0, 3) looking at the origin, up +y, fov 45, LH.
EYE = np.array([0.0, 0.0, 3.0])
FOV = math.radians(45.0)
# The effects' own light defaults (the default scene has no `light` key, so they stand).
PHONG_LIGHT = np.array([2.0, 2.0, 2.0])                       # phong.fx LightPosition
EARTH_TO_LIGHT = -np.array([0.577, -0.577, -0.577]) / np.linalg.norm([0.577, 0.577, 0.577])

# (effect, technique, card, policy): the card (and policy) that selects each technique.
CASES = [
    ("phong", "PerPixelPhong_ps20", "radeon9700", "first"),
    ("phong", "PerPixelPhong_ps11", "geforce3", "first"),
    ("phong", "Dot3_dx7", "geforce2", "first"),
    ("phong", "SingleTexture", "tnt2", "first"),
    ("specular_bump", "Specular_ps20", "radeon9700", "first"),
    ("specular_bump", "SpecularTable_ps11", "geforce3", "first"),
    ("specular_bump", "SpecularMultiply_ps11", "geforce3", None),   # named: valid, never first
    ("specular_bump", "Dot3_dx7", "geforce2", "first"),
    ("specular_bump", "BumpEnvMap_dx6", "g400", "first"),
    ("specular_bump", "Emboss_dx6", "tnt2", "first"),
    ("specular_bump", "SingleTexture", "tnt2", "cost"),
]
IDS = [f"{e}-{t}-{c}" for e, t, c, _ in CASES]


# ---------------------------------------------------------------------------------------------
# The scene, by hand


def pixel_rays(size: int = SIZE) -> np.ndarray:
    """(size, size, 3) unit world-space ray directions from the eye through each pixel, D3D9
    style: pixel (px, py) is sampled at exactly (px, py), NDC x = 2 px / W - 1, y = 1 - 2 py / H.
    The LH view from +z looking at -z has world -x on screen right."""
    p = np.arange(size, dtype=np.float64)
    ndc_x = 2 * p[None, :] / size - 1
    ndc_y = 1 - 2 * p[:, None] / size
    t = math.tan(FOV / 2)
    d = np.stack(np.broadcast_arrays(-ndc_x * t, ndc_y * t, -np.ones((1, 1))), axis=-1)
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


def sphere_hits(size: int = SIZE) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(hit, P, edge): which pixels' rays meet the unit sphere, the point met, and how far the
    ray passes inside the silhouette (1 - closest approach distance; near 0 at the edge)."""
    d = pixel_rays(size)
    b = d @ EYE                               # |E + t d|^2 = 1: t^2 + 2 b t + |E|^2 - 1 = 0
    closest = np.sqrt(np.maximum(EYE @ EYE - b * b, 0.0))
    disc = b * b - (EYE @ EYE - 1.0)
    t = -b - np.sqrt(np.maximum(disc, 0.0))
    return disc > 0, EYE + t[..., None] * d, 1.0 - closest


def sphere_uv(p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(u, v) of effects.assets.meshes.sphere's mapping, whose point at (u, v) is
    (sin(pi v) cos(2 pi u), cos(pi v), sin(pi v) sin(2 pi u))."""
    u = np.mod(np.arctan2(p[..., 2], p[..., 0]) / (2 * np.pi), 1.0)
    v = np.arccos(np.clip(p[..., 1], -1, 1)) / np.pi
    return u, v


def tangent_frame(p: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """T = dP/du (normalised), B = N x T (= dP/dv direction on this sphere), N = P."""
    n = p / np.linalg.norm(p, axis=-1, keepdims=True)
    t = np.stack([-p[..., 2], np.zeros_like(p[..., 0]), p[..., 0]], axis=-1)
    t /= np.maximum(np.linalg.norm(t, axis=-1, keepdims=True), 1e-12)
    return t, np.cross(n, t), n


def sample_bilinear(texture: Texture, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Level 0 of a 2D texture at (u, v), bilinear, wrapping (texel centres at (j + .5) / W)."""
    img = texture.levels[0]
    h, w = img.shape[:2]
    x, y = u * w - 0.5, v * h - 0.5
    x0, y0 = np.floor(x).astype(int), np.floor(y).astype(int)
    fx, fy = (x - x0)[..., None], (y - y0)[..., None]
    at = lambda yy, xx: img[np.mod(yy, h), np.mod(xx, w)]   # noqa: E731
    return ((1 - fy) * ((1 - fx) * at(y0, x0) + fx * at(y0, x0 + 1))
            + fy * ((1 - fx) * at(y0 + 1, x0) + fx * at(y0 + 1, x0 + 1)))


def bumped_normals(p: np.ndarray, normal_map: Texture, *, raised: bool = True) -> np.ndarray:
    """World normals of the sphere carrying the normal map (0.5 n + 0.5 in T, B, N); with
    raised=False the relief is turned inside out (x and y of n negated: dents)."""
    u, v = sphere_uv(p)
    n = 2 * sample_bilinear(normal_map, u, v)[..., :3] - 1
    if not raised:
        n = n * np.array([-1.0, -1.0, 1.0])
    t, b, nn = tangent_frame(p)
    out = n[..., :1] * t + n[..., 1:2] * b + n[..., 2:3] * nn
    return out / np.linalg.norm(out, axis=-1, keepdims=True)


def unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def to_light(effect: str, p: np.ndarray) -> np.ndarray:
    return unit(PHONG_LIGHT - p) if effect == "phong" else np.broadcast_to(EARTH_TO_LIGHT, p.shape)


def blinn_point(effect: str) -> np.ndarray:
    """The point of the unit sphere whose normal is the half angle of the light and view
    directions there (where N.H = 1): a fixed-point iteration, converging in a few steps."""
    n = unit(EYE)
    for _ in range(50):
        n = unit(unit(to_light(effect, n)) + unit(EYE - n))
    return n


def project(p: np.ndarray, size: int = SIZE) -> tuple[float, float]:
    """Pixel (x, y) of a world point, inverse of pixel_rays."""
    d = p - EYE
    t = math.tan(FOV / 2)
    ndc_x, ndc_y = -d[0] / (-d[2] * t), d[1] / (-d[2] * t)
    return (ndc_x + 1) * size / 2, (1 - ndc_y) * size / 2


# ---------------------------------------------------------------------------------------------
# Rendering


_EFFECTS: dict[str, effects.Effect] = {}


def load(name: str) -> "effects.Effect":
    if name not in _EFFECTS:
        _EFFECTS[name] = effects.load_effect(os.path.join(FXFILES, f"{name}.fx"))
    return _EFFECTS[name]


def render(effect: str, technique: str, card: str, policy: str | None, params=None,
           size: int = SIZE) -> np.ndarray:
    """The technique on its card: chosen by the card (and policy) when one selects it, else
    named. Returns H x W x 3 float RGB in 0..255."""
    fx = load(effect)
    if policy is not None:
        chosen = fx.find_valid_technique(effects.load_profile(card), policy)
        assert chosen is not None and chosen.name == technique, \
            f"{card} ({policy}) selects {chosen and chosen.name}, not {technique}"
        image = effects.render(fx, card, scene=SCENE, size=(size, size), params=params,
                               policy=policy)
    else:
        assert fx.validate(fx.technique(technique), effects.load_profile(card)).ok
        image = effects.render(fx, card, technique=technique, scene=SCENE, size=(size, size),
                               params=params)
    assert image.shape == (size, size, 4) and image.dtype == np.uint8
    return image[..., :3].astype(np.float64)


def solid(rgb, fmt: str = "X8R8G8B8") -> Texture:
    return make_texture(np.broadcast_to(np.array([*rgb, 1.0], np.float32), (4, 4, 4)).copy(), fmt)


WHITE, BLACK = solid((1, 1, 1)), solid((0, 0, 0))
FLAT_NORMALS = solid((0.5, 0.5, 1.0))
NO_BUMPS = make_texture(np.zeros((4, 4, 4), np.float32), "V8U8")


def luminance(rgb: np.ndarray) -> np.ndarray:
    return rgb @ np.array([0.299, 0.587, 0.114])


def normal_map(effect: str) -> Texture:
    height = "stones_height.png" if effect == "phong" else "earth_height.png"
    return procedural(f"sobel_normals:textures/{height}", base_dir=FXFILES)


def base_texture(effect: str) -> Texture:
    name = "stones_base.png" if effect == "phong" else "earth_base.png"
    return load_texture(os.path.join(FXFILES, "textures", name))


def base_key(effect: str) -> str:
    return "BaseTexture" if effect == "phong" else "EarthTexture"


def correlation(a: np.ndarray, b: np.ndarray, mask: np.ndarray) -> float:
    a, b = a[mask] - a[mask].mean(), b[mask] - b[mask].mean()
    return float((a * b).sum() / np.sqrt((a * a).sum() * (b * b).sum()))


HIT, POINT, EDGE = sphere_hits()
DISC = HIT & (EDGE > 0.02)           # clear of the mesh's polygonal outline (~1.5 pixels)
NORMAL = unit(POINT)


# ---------------------------------------------------------------------------------------------
# Tests


@pytest.mark.parametrize("effect, technique, card, policy", CASES, ids=IDS)
def test_the_sphere_covers_its_disc_on_the_clear(effect, technique, card, policy):
    image = render(effect, technique, card, policy)
    background = np.all(image == CLEAR, axis=-1)
    assert background[~HIT].all()                 # nothing drawn off the sphere
    assert not background[DISC].any()             # every pixel of the disc drawn
    assert DISC.sum() > 0.25 * SIZE * SIZE * math.pi / 4 * 0.5   # a real disc, not a dot


@pytest.mark.parametrize("effect, technique, card, policy", CASES, ids=IDS)
def test_the_side_facing_the_light_is_brighter(effect, technique, card, policy):
    lum = luminance(render(effect, technique, card, policy))
    n_dot_l = np.sum(NORMAL * to_light(effect, POINT), axis=-1)
    lit, shadow = lum[DISC & (n_dot_l > 0.5)], lum[DISC & (n_dot_l < -0.1)]
    assert lit.size > 500 and shadow.size > 400
    assert lit.mean() > 2 * shadow.mean() + 20


# What each technique highlights, and the parameters that isolate it: the base texture black
# (or white for the diffuse-only techniques) and the relief flat, so the brightest pixels are
# the peak of the lighting term alone.
EARTH_SPECULAR = {"Specular_ps20", "SpecularTable_ps11", "SpecularMultiply_ps11"}


def peak_case(effect: str, technique: str) -> tuple[dict, np.ndarray, str]:
    flat = {"NormalMap": FLAT_NORMALS}
    if effect == "phong":     # every phong technique has a specular term
        return ({**flat, "BaseTexture": BLACK, "GlossMap": WHITE}, blinn_point(effect),
                "specular")
    if technique in EARTH_SPECULAR:
        return {**flat, "EarthTexture": BLACK}, blinn_point(effect), "specular"
    return ({**flat, "EarthTexture": WHITE, "BumpMap": NO_BUMPS, "EnvMapTexture": BLACK,
             "HeightMap": solid((0.5, 0.5, 0.5))}, EARTH_TO_LIGHT, "diffuse")


@pytest.mark.parametrize("effect, technique, card, policy", CASES, ids=IDS)
def test_the_highlight_is_where_the_formula_puts_it(effect, technique, card, policy):
    # Specular: the point where N bisects the light and view directions (N.H = 1, and R = V
    # for Phong: the same point). Diffuse only: the point facing the light (N = L). The
    # brightest pixels (within 2/255 of the maximum: a plateau of equal values is common)
    # have their centroid within 4 pixels of it: per-pixel techniques land within 1.5, the
    # per-vertex ones within about half a triangle of the 24 x 48 sphere (6 pixels wide here).
    params, target, kind = peak_case(effect, technique)
    image = render(effect, technique, card, policy, params=params)
    lum = luminance(image)
    lum[np.all(image == CLEAR, axis=-1)] = 0
    assert lum.max() > 60, f"no {kind} highlight"
    ys, xs = np.nonzero(lum >= lum.max() - 2)
    tx, ty = project(target)
    assert math.hypot(xs.mean() - tx, ys.mean() - ty) < 4.0
    # and it stands out: the far side of the disc is much darker
    assert np.median(lum[DISC]) < 0.6 * lum.max()


@pytest.mark.parametrize("effect, technique, card, policy", CASES, ids=IDS)
def test_the_texture_is_mapped_as_the_sphere_says(effect, technique, card, policy):
    # Every technique multiplies its lighting by the base texture and may add a term that
    # does not depend on it (specular, the environment map). So three renders -- the real
    # texture, white, black -- give the texture back: (real - black) / (white - black), which
    # must equal the texture's luminance at the sphere's (u, v) for the pixel (computed here
    # by the mesh's mapping), and not the mirror image's.
    key = base_key(effect)
    real = render(effect, technique, card, policy)
    white = render(effect, technique, card, policy, params={key: WHITE})
    black = render(effect, technique, card, policy, params={key: BLACK})
    lit = luminance(white - black)
    mask = DISC & (lit > 30) & (white.max(axis=-1) < 250)
    assert mask.sum() > 2000
    albedo = luminance(real - black) / np.maximum(lit, 1.0)
    u, v = sphere_uv(POINT)
    texture = base_texture(effect)
    expected = luminance(sample_bilinear(texture, u, v)[..., :3])
    mirrored = luminance(sample_bilinear(texture, 0.5 - u, v)[..., :3])
    error = np.abs(albedo - expected)[mask].mean()
    assert error < 0.02
    assert np.abs(albedo - mirrored)[mask].mean() > 3 * error
    # The detail shows: the recovered texture varies as much as the texture does.
    assert albedo[mask].std() > 0.8 * expected[mask].std() > 0.02


# The relief: the picture with the effect's relief map minus the picture with a flat one,
# base white and specular removed, against the change a raised relief makes to N.L.
FLAT = {"NormalMap": FLAT_NORMALS}
RELIEF = {"PerPixelPhong_ps20": FLAT, "PerPixelPhong_ps11": FLAT, "Dot3_dx7": FLAT,
          "Specular_ps20": FLAT, "SpecularTable_ps11": FLAT, "SpecularMultiply_ps11": FLAT,
          "Emboss_dx6": {"HeightMap": solid((0.5, 0.5, 0.5))}}
RELIEF_CASES = [c for c in CASES if c[1] in RELIEF]


def no_specular(effect: str) -> dict:
    if effect == "phong":
        return {"BaseTexture": WHITE, "GlossMap": BLACK}
    # rgb of the power table 0 (no specular), alpha u = N.L as before
    table = np.zeros((256, 256, 4), np.float32)
    table[..., 3] = (np.arange(256) + 0.5) / 256
    return {"EarthTexture": WHITE, "SpecularColor": [0.0, 0.0, 0.0, 0.0],
            "PowerTable": make_texture(table, "A8R8G8B8", mips=False)}


@pytest.mark.parametrize("effect, technique, card, policy", RELIEF_CASES,
                         ids=[f"{e}-{t}-{c}" for e, t, c, _ in RELIEF_CASES])
def test_the_relief_is_raised_not_sunk(effect, technique, card, policy):
    # Raised relief (the normal map's n = (-dh/du, -dh/dv, 1) in the frame T = dP/du,
    # B = N x T = dP/dv, N) brightens the slopes facing the light; sunk relief (n.x, n.y
    # negated) darkens them. The picture's change must follow the raised one. (The multiply
    # technique cannot switch its specular off; it is kept, and is small off the highlight.)
    base = no_specular(effect)
    bumped = luminance(render(effect, technique, card, policy, params=base))
    flat = luminance(render(effect, technique, card, policy,
                            params={**base, **RELIEF[technique]}))
    change = bumped - flat
    light = to_light(effect, POINT)
    n_dot_l = np.maximum(np.sum(NORMAL * light, axis=-1), 0.0)
    mask = DISC & (np.sum(NORMAL * light, axis=-1) > 0.1)
    assert np.abs(change[mask]).mean() > 3.0          # the relief is visible
    def relief(raised: bool) -> np.ndarray:
        n = bumped_normals(POINT, normal_map(effect), raised=raised)
        return np.maximum(np.sum(n * light, axis=-1), 0.0) - n_dot_l

    raised, sunk = relief(True), relief(False)
    assert correlation(change, raised, mask) > 0.8
    assert correlation(change, sunk, mask) < 0.0


def test_bump_env_map_perturbs_the_environment_lookup():
    # G400's BUMPENVMAP: the V8U8 map offsets the environment map's coordinates by
    # BUMPENVMAT (0.5, 0, 0, 0.5) x (du, dv). With the bump map zeroed the light map lands
    # unperturbed; with it, the spot breaks up: the pictures differ, and only by what the
    # environment map adds (with the environment map black, the bump map changes nothing).
    case = ("specular_bump", "BumpEnvMap_dx6", "g400", "first")
    bumped = render(*case)
    smooth = render(*case, params={"BumpMap": NO_BUMPS})
    assert np.abs(bumped - smooth)[DISC].mean() > 2.0
    dark = {"EnvMapTexture": BLACK}
    assert np.array_equal(render(*case, params=dark),
                          render(*case, params={**dark, "BumpMap": NO_BUMPS}))


def disc_mean(effect: str, technique: str, params=None) -> np.ndarray:
    case = next(c for c in CASES if c[:2] == (effect, technique))
    return render(*case, params=params)[DISC].mean(axis=0)


def test_the_earths_techniques_draw_the_same_look():
    # Mean RGB over the disc, 0..255. The two ps.1.1 techniques compute the same N.H^16 (one
    # by table, one by multiplies): within 0.5. The ps_2_0 one scales its specular by
    # SpecularColor (0.6) where the chapter's ps.1.1 shaders add N.H^16 unscaled, and
    # normalises per pixel: within 10. Without specular, ps_2_0's per-pixel N.L and the
    # DOTPRODUCT3 stage agree within 3, and the per-vertex fallbacks (emboss, single texture)
    # lie within 3 of the DOTPRODUCT3 picture.
    table, multiply = disc_mean("specular_bump", "SpecularTable_ps11"), disc_mean(
        "specular_bump", "SpecularMultiply_ps11")
    ps20 = disc_mean("specular_bump", "Specular_ps20")
    assert np.abs(table - multiply).max() < 0.5
    assert np.abs(ps20 - table).max() < 10
    diffuse_ps20 = disc_mean("specular_bump", "Specular_ps20", {"SpecularColor": [0, 0, 0, 0]})
    dot3 = disc_mean("specular_bump", "Dot3_dx7")
    assert np.abs(diffuse_ps20 - dot3).max() < 3
    for technique in ("Emboss_dx6", "SingleTexture"):
        assert np.abs(disc_mean("specular_bump", technique) - dot3).max() < 3
    assert dot3.max() > 20                      # not black


def test_the_phong_techniques_draw_the_same_look():
    # Persson's ps_2_0 Phong, its ps.1.1 two-pass version (Blinn half angle, per-vertex
    # attenuation) and the DOTPRODUCT3 stage with per-vertex specular: mean RGB over the disc
    # within 3. SingleTexture lights per vertex without the relief (whose slopes catch light on
    # the dark side), so it is darker; it stays within 10.
    ps20 = disc_mean("phong", "PerPixelPhong_ps20")
    for technique in ("PerPixelPhong_ps11", "Dot3_dx7"):
        assert np.abs(disc_mean("phong", technique) - ps20).max() < 3
    single = disc_mean("phong", "SingleTexture")
    assert np.abs(single - ps20).max() < 10
    assert ps20.max() > 30
