"""XNA 4.0's stock effects (tests/data/realfx/xna_stock/: BasicEffect, DualTextureEffect and
AlphaTestEffect from Microsoft's Stock Effects sample, Ms-PL, as FNA ships them beside the
fx_2_0 binaries fxc made of them): an all-HLSL origin. Every shader of their VSArray /
PSArray compiles for its target within the target's limits (fxc compiled every one), the
technique validates and draws for each ShaderIndex the game set, and the pixels are the
sample's formulas worked out by hand on a quad whose WorldViewProj is the identity."""
from __future__ import annotations

from tests.paths import TESTS

import re

import numpy as np
import pytest

import effects
from effects.assets.textures import make_texture
from effects.shaders.hlsl import compile_shader

STOCK = TESTS / "data" / "realfx" / "xna_stock"
FILES = ("BasicEffect.fx", "DualTextureEffect.fx", "AlphaTestEffect.fx")
QUAD = {"mesh": "quad", "size": [8, 8]}
IDENTITY = np.eye(4).tolist()
TOL = 1.5 / 255


def compiles(name: str) -> list[tuple[str, str]]:
    """(entry, target) of every `compile` in the file, in its arrays' order."""
    return re.findall(r"compile (\w+) (\w+)\(\)", (STOCK / name).read_text())


@pytest.mark.parametrize("name", FILES)
def test_every_shader_of_the_arrays_compiles_without_a_warning(name):
    effect = effects.load_effect(STOCK / name)
    shaders = compiles(name)
    assert len(shaders) == {"BasicEffect.fx": 30, "DualTextureEffect.fx": 6,
                            "AlphaTestEffect.fx": 8}[name]
    for target, entry in shaders:
        shader = compile_shader(effect, entry, target)     # the limits: validation, below
        assert shader.warnings == [], (entry, shader.warnings)


@pytest.mark.parametrize("name, count", [("BasicEffect.fx", 32), ("DualTextureEffect.fx", 4),
                                         ("AlphaTestEffect.fx", 8)])
def test_every_shader_index_validates_on_a_dx9_card(name, count):
    effect = effects.load_effect(STOCK / name)
    technique = effect.techniques[0].name
    card = effects.load_profile("radeon9700")
    for k in range(count):
        effect.parameter("ShaderIndex").value = k
        report = effect.validate(technique, card)
        assert report.ok, (k, [r.message for r in report.reasons])


def flat(colour, size=(2, 2)) -> object:
    return make_texture(np.full(size + (4,), colour, np.float32), mips=False)


def draw(name: str, backend: str, **params) -> np.ndarray:
    effect = effects.load_effect(STOCK / name)
    values = {"WorldViewProj": IDENTITY, "DiffuseColor": [1, 1, 1, 1]}
    if effect.parameter("World") is not None:
        values["World"] = IDENTITY
    values.update(params)
    image = effects.render(effect, "radeon9700", backend=backend, scene=QUAD, params=values)
    return image.astype(np.float64) / 255


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_dual_texture_doubles_the_first_and_fogs_by_the_fog_vector(backend):
    t1, t2 = flat((0.25, 0.5, 0.75, 1)), flat((0.5, 0.5, 1, 0.5))
    # no fog (ShaderIndex 1): rgb * 2 * overlay * diffuse; 0.75 * 2 = 1.5 held past 1 in the
    # register until the output clamps it
    plain = draw("DualTextureEffect.fx", backend, Texture=t1, Texture2=t2, ShaderIndex=1,
                 DiffuseColor=[1, 0.5, 1, 1])
    assert np.allclose(plain[4, 4], (0.25, 0.25, 1, 0.5), atol=TOL), plain[4, 4]
    # fog (ShaderIndex 0): factor = saturate(dot(position, FogVector)) = 0.5 at w = 1; the
    # colour goes halfway to FogColor * alpha = (0.5, 0, 0): 1.5 becomes 0.75
    fogged = draw("DualTextureEffect.fx", backend, Texture=t1, Texture2=t2, ShaderIndex=0,
                  DiffuseColor=[1, 0.5, 1, 1], FogVector=[0, 0, 0, 0.5], FogColor=[1, 0, 0])
    assert np.allclose(fogged[4, 4], (0.375, 0.125, 0.75, 0.5), atol=TOL), fogged[4, 4]


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_alpha_test_discards_by_its_compare_function(backend):
    # left half alpha 0.25, right half 0.75
    texels = np.array([[[0.5, 0.5, 0.5, 0.25], [0.5, 0.5, 0.5, 0.75]]], np.float32)
    texture = make_texture(texels, mips=False)
    # less/greater (ShaderIndex 1): clip((a < 0.5) ? -1 : 1) keeps alpha >= 0.5
    lt = draw("AlphaTestEffect.fx", backend, Texture=texture, ShaderIndex=1,
              AlphaTest=[0.5, 0, -1, 1])
    assert np.allclose(lt[4, 1], 0) and np.allclose(lt[4, 6], (0.5, 0.5, 0.5, 0.75), atol=TOL)
    # equal/notequal (ShaderIndex 5): clip((|a - 0.25| < 0.1) ? 1 : -1) keeps alpha 0.25
    eq = draw("AlphaTestEffect.fx", backend, Texture=texture, ShaderIndex=5,
              AlphaTest=[0.25, 0.1, 1, -1])
    assert np.allclose(eq[4, 1], (0.5, 0.5, 0.5, 0.25), atol=TOL) and np.allclose(eq[4, 6], 0)


@pytest.mark.parametrize("backend", ["numpy", "gl"])
@pytest.mark.parametrize("index", [8, 16, 24])       # vertex, one-light and pixel lighting
def test_basic_effect_lights_by_the_sample_formula(backend, index):
    # the quad's normal (0, 0, -1) faces light 0 (direction (0, 0, 1)): N.L = 1, diffuse =
    # light colour * DiffuseColor + EmissiveColor; light 1 shines from behind (N.L < 0: 0);
    # no specular colour, no fog
    lights = dict(DirLight0Direction=[0, 0, 1], DirLight0DiffuseColor=[1, 0.5, 0.25],
                  DirLight1Direction=[0, 0, -1], DirLight1DiffuseColor=[1, 1, 1],
                  WorldInverseTranspose=np.eye(3).tolist(), EyePosition=[0, 0, -5],
                  SpecularPower=16, EmissiveColor=[0, 0.125, 0])
    image = draw("BasicEffect.fx", backend, ShaderIndex=index, DiffuseColor=[0.5, 0.5, 1, 1],
                 **lights)
    assert np.allclose(image[3, 5], (0.5, 0.375, 0.25, 1), atol=TOL), image[3, 5]
