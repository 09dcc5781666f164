"""The real-effect corpus (tests/data/realfx/MANIFEST.md): each file loads,
validates and renders a sensible, non-blank picture on the reference device."""
from __future__ import annotations

from tests.paths import TESTS

import math

import numpy as np
import pytest

import effects
from effects.host.runtime import render_frame

DATA = TESTS / "data" / "realfx"
SIZE = (64, 64)


def load(name: str):
    return effects.load_effect(DATA / name)


def coverage(image: np.ndarray) -> np.ndarray:
    """Pixels drawn: the clear's alpha is 0, every corpus technique writes alpha > 0."""
    return image[..., 3] > 0


def test_every_corpus_file_is_in_the_manifest():
    manifest = (DATA / "MANIFEST.md").read_text()
    for path in DATA.glob("*.fx"):
        assert f"`{path.name}`" in manifest, path.name


def test_sdk_envmap_draws_the_sphere_with_a_sky_stand_in():
    frame = render_frame(load("sdk_envmap.fx"), "geforce2", size=SIZE)
    assert frame.technique.name == "TEnvMapFF"
    # its `string XFile = "sphere.x"` (EffectEdit's model) is not shipped either: the sphere
    assert [w.message.split(";")[0] for w in frame.warnings] == [
        f"mesh file not found: {DATA / 'sphere.x'}",
        f"texture parameter tEnvMap: texture file not found: {DATA / 'lobbycube.dds'}"]
    covered = coverage(frame.image)
    # the camera's transforms: the unit sphere 3 units away fills pi r^2 / 4 of the frame
    r = math.tan(math.asin(1 / 3)) / math.tan(math.radians(22.5))
    assert covered.mean() == pytest.approx(math.pi * r * r / 4, abs=0.04)
    top, bottom = frame.image[16:24, 24:40, :3].mean((0, 1)), frame.image[44:50, 24:40, :3].mean((0, 1))
    assert top[2] > top[0] + 40          # the sky reflected in the upper half
    assert abs(bottom[0] - bottom[2]) < top[2] - top[0]   # the grey checker ground below


def test_engine_fixed_lights_the_sphere_from_its_light_arrays():
    effect = load("engine_fixed.fx")
    assert any("D3DX's assembler rejects it" in str(w) for w in effect.warnings)
    frame = render_frame(effect, "geforce3", size=SIZE)
    assert frame.technique.name == "tLit"
    image = frame.image[..., :3].astype(int)
    # the camera at +z looks down -z in a left-handed frame, so +x is on the image's left
    left, right = image[20:44, 14:24].mean((0, 1)), image[20:44, 40:50].mean((0, 1))
    assert left[0] > left[2] + 20        # the warm light at +x
    assert right[2] > right[0] + 20      # the blue light at -x
    assert coverage(frame.image).mean() > 0.4


@pytest.mark.parametrize("card, technique", [("radeon9700", "Water14"), ("radeon8500", "Water14"),
                                             ("geforce2", "WaterFF")])
def test_mod_water_skips_its_arb_program(card, technique):
    effect = load("mod_water.fx")
    arb = effect.validate("WaterARB", effects.load_profile(card))
    assert not arb.ok and "OpenGL ARB program" in str(arb.reasons[0])
    frame = render_frame(effect, card, size=SIZE)
    assert frame.technique.name == technique and not frame.warnings
    assert coverage(frame.image).mean() > 0.4
    assert frame.image[..., 2].mean() > frame.image[..., 0].mean()   # water is bluish


def test_xna_sprite_compiles_its_hlsl_and_renders_with_the_games_matrices():
    effect = load("xna_sprite.fx")
    assert effect.validate("Sprite", effects.load_profile("radeon9700")).ok
    # no semantics: the game set World/View/Projection by name, here --set / params do
    identity = ",".join(str(float(i % 5 == 0)) for i in range(16))
    frame = render_frame(effect, "radeon9700", size=SIZE, scene={"mesh": "quad"},
                         params={"World": identity, "View": identity, "Projection": identity})
    assert [w.message.split(";")[0] for w in frame.warnings] == [
        "texture parameter SpriteTexture: nothing supplies it (no ResourceName, scene params "
        "or --set value)"]
    assert coverage(frame.image).mean() > 0.9
    assert len(np.unique(frame.image[..., 0])) >= 2      # the checker stand-in, tinted white


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_post_blur_on_the_default_scene(backend):
    frame = render_frame(load("own_postblur.fx"), "geforce3", backend=backend, size=SIZE)
    image = frame.image[..., 0].astype(int)
    values = set(np.unique(image[16:48, 16:48]).tolist())
    assert {0, 255} <= values and len(values) > 3     # a checker, blurred at its edges
