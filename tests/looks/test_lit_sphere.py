"""A lit sphere through the fixed-function pipeline equals the Direct3D lighting formula.

One technique (Lighting on, one directional light, a material, stage 0 SelectArg1 Diffuse) on
the `modern` card (float pipeline), drawn on a finely tessellated unit sphere. For every pixel
inside the disc the expected colour is the D3D9 vertex lighting formula ("Mathematics of
Lighting"), evaluated here by hand at the sphere's analytic normal where the pixel's ray meets
the sphere:

    colour = Ce + Ca * (Ga + La) + Cd * Ld * max(0, N . Ldir),   alpha = Cd.a

with Ldir the unit vector towards the light (-Direction), Ga the Ambient render state, La the
light's ambient, and Cd, Ca, Ce the material's (the sphere's vertices carry no colour, so D3D
takes every colour from the material whatever ColorVertex says).

The comparison is honest about what is drawn: the pipeline lights the vertices and
interpolates (Gouraud). On a sphere of 128 rings x 256 segments a triangle spans h = pi / 128
of arc, and linear interpolation of a smooth function departs from it by at most
max|f''| h^2 / 8 = 7.5e-5 (f = N . Ldir, |f''| <= 1 per radian^2): far below 1/255. Two bands
are left out, each a few pixels wide, and counted: where max(0, .) has its kink (|N . Ldir| <
h, the interpolated clamp departs by up to h / 4 ~ 1.5/255 there) and the outermost 1.5 pixels
of the disc (the mesh's polygonal outline is not the circle). Pixel (px, py) is sampled at
exactly (px, py): NDC x = 2 px / W - 1, y = 1 - 2 py / H (Direct3D 9 pixel centres).
"""
from __future__ import annotations

from tests.paths import ROOT

import math
import os

import numpy as np
import pytest

import effects
from effects.host.resources import geometry
from effects.assets.meshes import sphere
from effects.host.runtime import Runtime
from effects.host.scene import load_scene
from effects.assets.textures import make_texture

SIZE = 128
RINGS, SEGMENTS = 128, 256
EYE = np.array([0.0, 0.0, 3.0])     # the default camera: eye (0, 0, 3), target 0, up +y
FOV = math.radians(45.0)

DIRECTION = np.array([0.5, -0.6, -0.62])            # the way the light travels
MATERIAL_DIFFUSE = (0.8, 0.6, 0.4, 0.75)
MATERIAL_AMBIENT = (0.2, 0.3, 0.5, 1.0)
MATERIAL_EMISSIVE = (0.05, 0.0, 0.1, 0.0)
LIGHT_DIFFUSE = (1.0, 0.9, 0.7, 1.0)
LIGHT_AMBIENT = (0.25, 0.2, 0.15, 1.0)
AMBIENT_STATE = 0x00201008                           # Ga = (32, 16, 8) / 255

EFFECT = f"""
float4x4 World : WORLD;
float4x4 View : VIEW;
float4x4 Projection : PROJECTION;

technique LitSphere
{{
    pass P0
    {{
        WorldTransform[0] = <World>;
        ViewTransform = <View>;
        ProjectionTransform = <Projection>;
        Lighting = True;
        Ambient = 0x{AMBIENT_STATE:08x};
        LightEnable[0] = True;
        LightType[0] = Directional;
        LightDirection[0] = {{ {DIRECTION[0]}, {DIRECTION[1]}, {DIRECTION[2]} }};
        LightDiffuse[0] = {{ {", ".join(map(str, LIGHT_DIFFUSE))} }};
        LightAmbient[0] = {{ {", ".join(map(str, LIGHT_AMBIENT))} }};
        MaterialDiffuse = {{ {", ".join(map(str, MATERIAL_DIFFUSE))} }};
        MaterialAmbient = {{ {", ".join(map(str, MATERIAL_AMBIENT))} }};
        MaterialEmissive = {{ {", ".join(map(str, MATERIAL_EMISSIVE))} }};
        ColorOp[0] = SelectArg1;
        ColorArg1[0] = Diffuse;
        AlphaOp[0] = SelectArg1;
        AlphaArg1[0] = Diffuse;
    }}
}}
"""


def pixel_hits(size: int = SIZE) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(hit, normal, margin): rays from the eye through each pixel (D3D9 centres), where they
    meet the unit sphere, the normal there, and the ray's distance inside the silhouette in
    pixels (negative outside)."""
    p = np.arange(size, dtype=np.float64)
    t = math.tan(FOV / 2)
    ndc_x, ndc_y = 2 * p[None, :] / size - 1, 1 - 2 * p[:, None] / size
    # The LH view from +z towards -z has world -x on screen right.
    d = np.stack(np.broadcast_arrays(-ndc_x * t, ndc_y * t, -np.ones((1, 1))), axis=-1)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    b = d @ EYE
    disc = b * b - (EYE @ EYE - 1.0)
    hit_t = -b - np.sqrt(np.maximum(disc, 0.0))
    normal = EYE + hit_t[..., None] * d
    # Screen distance (pixels) of the ray from the silhouette circle: the ray's angle from the
    # view axis and the silhouette cone's, both as screen radii (size / 2 * tan(angle) / t).
    edge_angle = math.asin(1.0 / np.linalg.norm(EYE))
    ray_angle = np.arccos(np.clip(-d[..., 2], -1, 1))
    margin = (math.tan(edge_angle) - np.tan(ray_angle)) * size / 2 / t
    return disc > 0, normal, margin


def lighting_formula(normal: np.ndarray, diffuse=MATERIAL_DIFFUSE) -> np.ndarray:
    """D3D9 vertex lighting of one directional light, RGBA in 0..1."""
    to_light = -DIRECTION / np.linalg.norm(DIRECTION)
    n_dot_l = np.maximum(normal @ to_light, 0.0)[..., None]
    ga = np.array([(AMBIENT_STATE >> s) & 0xFF for s in (16, 8, 0)]) / 255.0
    cd = np.asarray(diffuse[:3])
    rgb = (np.asarray(MATERIAL_EMISSIVE[:3]) + np.asarray(MATERIAL_AMBIENT[:3])
           * (ga + np.asarray(LIGHT_AMBIENT[:3])) + cd * np.asarray(LIGHT_DIFFUSE[:3]) * n_dot_l)
    alpha = np.full(normal.shape[:-1] + (1,), diffuse[3])
    return np.clip(np.concatenate([rgb, alpha], axis=-1), 0.0, 1.0)


def render_fine_sphere(scene: dict | None = None) -> np.ndarray:
    """The effect on `modern`, drawn on the fine sphere through the Runtime (D3DX-style
    begin / pass / draw / end), as float RGBA 0..255."""
    effect = effects.load_effect(EFFECT)
    runtime = Runtime(effect, "modern", scene=scene, size=(SIZE, SIZE))
    geo = geometry(load_scene(scene), runtime.effect, sphere(RINGS, SEGMENTS))
    runtime.begin()
    runtime.begin_pass(0)
    runtime.draw(geo)
    runtime.end_pass()
    return runtime.end().astype(np.float64)


def compared_pixels(normal: np.ndarray, hit: np.ndarray, margin: np.ndarray) -> np.ndarray:
    to_light = -DIRECTION / np.linalg.norm(DIRECTION)
    kink = np.abs(normal @ to_light) < math.pi / RINGS
    return hit & (margin > 1.5) & ~kink


def test_every_pixel_of_the_disc_equals_the_d3d_lighting_formula_within_1_255():
    image = render_fine_sphere()
    hit, normal, margin = pixel_hits()
    compared = compared_pixels(normal, hit, margin)
    # The bands left out are thin: nearly the whole disc is compared.
    assert compared.sum() > 0.9 * hit.sum()
    expected = 255.0 * lighting_formula(normal)
    error = np.abs(image - expected)[compared]
    assert error.max() <= 1.0, f"max error {error.max():.2f}/255"
    # Both sides of the terminator are in the picture: the formula is not trivially flat.
    assert expected[compared][:, 0].max() - expected[compared][:, 0].min() > 100
    # Outside the disc (and off the mesh's outline) the clear colour (0, 0, 0, 0) stays.
    outside = ~hit & (margin < -1.5)
    assert (image[outside] == 0).all()


def test_vertex_colours_are_used_only_when_the_vertices_carry_them():
    # The same effect on a sphere whose vertices carry a diffuse colour (the scene's `vertex`
    # key): ColorVertex (on by default) with DiffuseMaterialSource = COLOR1 (the default) takes
    # Cd from the vertex, while ambient and emissive stay with the material (their sources
    # default to MATERIAL).
    vertex = (0.2, 0.9, 0.6, 0.5)
    image = render_fine_sphere({"vertex": {"diffuse": list(vertex)}})
    hit, normal, margin = pixel_hits()
    compared = compared_pixels(normal, hit, margin)
    expected = 255.0 * lighting_formula(normal, diffuse=vertex)
    assert np.abs(image - expected)[compared].max() <= 1.0
    # ... and it is not the material's picture.
    material = 255.0 * lighting_formula(normal)
    assert np.abs(image - material)[compared].max() > 50


@pytest.mark.parametrize("card", ["modern", "geforce2"])
def test_a_vertex_without_colour_takes_the_material_specular(card):
    # Direct3D's default SpecularMaterialSource is COLOR2, but a vertex without a specular
    # colour uses the material's: phong.fx's SingleTexture (MaterialSpecular 0.5, power 24,
    # SpecularEnable) shows its highlight on the default sphere, whose vertices carry no colour.
    black = make_texture(np.zeros((4, 4, 4), np.float32), "X8R8G8B8")
    phong = os.path.join(str(ROOT), "fxfiles", "phong.fx")
    image = effects.render(phong, card, technique="SingleTexture", size=(64, 64),
                           params={"BaseTexture": black})
    # Base black: all that is left is the specular, added after the texture stage.
    assert image[..., :3].max() > 60
