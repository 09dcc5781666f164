"""Taylor's three-term hemisphere lighting (fxfiles/hemisphere.fx): the occlusion term cast over
the mesh (effects/assets/occlusion.py), the relief's occlusion in the normal map's alpha
(effects/assets/heightfield.py), and the corrected per-pixel technique against the printed one.
"""
from __future__ import annotations

from tests.paths import ROOT

import math
import os

import numpy as np

import effects
from effects.assets import meshes
from effects.assets.heightfield import horizon_occlusion
from effects.assets.occlusion import vertex_occlusion
from effects.assets.textures import make_texture

FXFILES = os.path.join(str(ROOT), "fxfiles")
GROUND = np.array([0.30, 0.22, 0.15]) * 255        # hemisphere.fx GroundColor
SKY = np.array([0.55, 0.65, 0.90]) * 255            # hemisphere.fx SkyColor


def solid(rgba, fmt: str = "A8R8G8B8"):
    return make_texture(np.broadcast_to(np.array(rgba, np.float32), (4, 4, 4)).copy(), fmt)


def load() -> effects.Effect:
    return effects.load_effect(os.path.join(FXFILES, "hemisphere.fx"))


def test_a_convex_mesh_occludes_nothing():
    sphere = meshes.sphere()
    assert vertex_occlusion(sphere.positions, sphere.normals, sphere.indices).max() < 0.01


def open_box_floor_centre() -> float:
    """The occlusion at the centre of the floor of an open-topped unit cube (inner faces)."""
    c = [0.5, 0.0, 0.5]
    floor = [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]]
    top = [[x, 1.0, z] for x, _, z in floor]
    positions = [c] + floor + top
    tris = [[0, 1 + (k + 1) % 4, 1 + k] for k in range(4)]            # floor fan, facing +y
    for k in range(4):                                                # walls, facing in
        a, b = 1 + k, 1 + (k + 1) % 4
        tris += [[a, b, b + 4], [a, b + 4, a + 4]]
    positions = np.array(positions, np.float64)
    normals = np.tile([0.0, 1.0, 0.0], (len(positions), 1))
    return float(vertex_occlusion(positions, normals, np.array(tris))[0])


def test_occlusion_at_the_floor_of_a_box_is_its_form_factor():
    # Seen from the centre of the floor, the cosine-weighted sky is the form factor to the
    # square opening one unit above: 4 corner rectangles of 0.5 x 0.5 at height 1,
    # F = 4 / (2 pi) * 2 * X / sqrt(1 + X^2) * atan(X / sqrt(1 + X^2)), X = 0.5: 0.2394.
    x = 0.5
    visible = 4 / (2 * math.pi) * 2 * x / math.sqrt(1 + x * x) * math.atan(x / math.sqrt(1 + x * x))
    assert abs(open_box_floor_centre() - (1 - visible)) < 0.05


def test_the_teapot_occludes_itself_at_the_spout_and_handle():
    pot = meshes.teapot()
    occ = vertex_occlusion(pot.positions, pot.normals, pot.indices)
    patch = np.arange(pot.vertex_count) // 81          # 9 x 9 vertices a patch (teapot(8))
    p = pot.positions
    body = (patch >= 4) & (patch < 12)
    waist = np.abs(p[:, 2]) < 0.15
    facing_handle = occ[body & waist & (p[:, 0] < -0.3)].mean()
    facing_spout = occ[body & waist & (p[:, 0] > 0.3)].mean()
    front = occ[body & (p[:, 2] > 0.3)].mean()
    # measured 0.20, 0.25 and 0.003
    assert facing_handle > 0.12 and facing_spout > 0.12 and front < 0.02
    handle = occ[(patch >= 12) & (patch < 16)].mean()
    assert handle > 0.15                                 # the handle's inside faces the body


def test_relief_occlusion_darkens_the_grooves():
    # A groove one texel wide and 0.5 deep (4 texels in the Sobel normal map's units) is
    # mostly closed to the sky; the flat top is open.
    h = np.ones((32, 32))
    h[:, 16] = 0.5
    occ = horizon_occlusion(h)
    assert occ[:, 16].min() > 0.5 and occ[:, 4].max() < 1e-9


BELOW = {"camera": {"eye": [0.0, -3.0, 0.0], "target": [0, 0, 0], "up": [0.0, 0.0, 1.0]}}
PLAIN = {"BaseTexture": solid([1, 1, 1, 1], "X8R8G8B8"), "NormalMap": solid([0.5, 0.5, 1.0, 1.0])}


def bottom_pole(technique: str, card: str) -> np.ndarray:
    image = effects.render(load(), card, technique=technique, scene=BELOW, size=(64, 64),
                           params=PLAIN)
    return image[30:34, 30:34, :3].reshape(-1, 3).astype(np.float64).mean(axis=0)


def test_the_corrected_technique_reaches_the_ground_colour_at_the_bottom_pole():
    # a = 0.5 + 0.5 cos(180 degrees) = 0: the ground colour alone (white base, flat relief,
    # the sphere occludes nothing). The printed dp3_d2_sat stops a at 0.5: the 50/50 mix.
    corrected = bottom_pole("HemisphereOcclusion_ps11", "geforce3")
    assert np.abs(corrected - GROUND).max() <= 2.0
    printed = bottom_pole("HemispherePerPixel_ps11", "geforce3")
    assert np.abs(printed - 0.5 * (SKY + GROUND)).max() <= 2.0
    vertex = bottom_pole("HemisphereVertex_vs11", "tnt2")
    assert np.abs(vertex - GROUND).max() <= 2.0


def test_vertex_occlusion_darkens_the_teapot_picture():
    fx = load()
    scene = {"mesh": "teapot"}
    lit = effects.render(fx, "geforce3", technique="HemisphereOcclusion_ps11", scene=scene,
                         size=(128, 128), params=PLAIN)[..., :3].astype(np.float64)
    open_sky = effects.render(fx, "geforce3", technique="HemisphereOcclusion_ps11",
                              scene={**scene, "streams": {"texcoord0": "uv"}}, size=(128, 128),
                              params=PLAIN)[..., :3].astype(np.float64)
    drawn = open_sky.sum(axis=-1) > 30
    ratio = lit.sum(axis=-1)[drawn] / open_sky.sum(axis=-1)[drawn]
    assert ratio.max() <= 1.0 + 1e-9
    assert (ratio < 0.8).sum() > 100                     # darkened where the pot is closed
    assert np.median(ratio) > 0.97                       # most of the surface sees the sky
