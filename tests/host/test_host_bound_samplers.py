"""A sampler whose sampler_state names no texture (`sampler2D S;`, or a state block of filters
only): D3DX leaves the stage's texture to the host (IDirect3DDevice9::SetTexture on the s# the
compiled shader gave the sampler), as Irrlicht's and Wild Magic's shaders expect. The host here
binds a picture to it by the sampler's name (`--set S=image`, scene params, `params=`); with
nothing given it is drawn with a stand-in and a warning at the sampler, as a texture parameter
nothing supplies is."""
from __future__ import annotations

import numpy as np
import pytest
from PIL import Image

import effects
from effects.base.errors import EffectError, SceneError
from effects.host.runtime import Runtime

QUAD = {"mesh": "quad"}

SAMPLER_ONLY = """
sampler2D S{STATE};
float4 PS(float2 uv : TEXCOORD0) : COLOR {{ return tex2D(S, uv) * 0.5 + float4(0, 0, 0, 0.5); }}
technique T {{ pass P {{ PixelShader = compile ps_2_0 PS(); }} }}
"""


def _effect(state: str = "") -> effects.Effect:
    return effects.load_effect(SAMPLER_ONLY.format(STATE=state))


@pytest.fixture
def orange(tmp_path):
    path = tmp_path / "orange.png"
    Image.new("RGB", (2, 2), (200, 100, 50)).save(path)
    return str(path)


@pytest.mark.parametrize("backend", ["numpy", "gl"])
@pytest.mark.parametrize("state", ["", " = sampler_state { MinFilter = Linear; MagFilter = Linear; }"],
                         ids=["no sampler_state", "filters only"])
def test_the_host_binds_a_picture_to_the_samplers_stage_by_its_name(orange, backend, state):
    image = effects.render(_effect(state), "radeon9700", scene=QUAD, size=(8, 8),
                           backend=backend, params={"S": orange})
    # tex2D reads the image (200, 100, 50, 255)/255 everywhere; times 0.5, alpha + 0.5
    np.testing.assert_allclose(image[4, 4], (100, 50, 25, 255), atol=1)


def test_with_nothing_given_a_stand_in_is_drawn_with_a_warning_at_the_sampler():
    runtime = Runtime(_effect(), effects.load_profile("radeon9700"), scene=QUAD, size=(8, 8))
    image = runtime.render().image
    (warning,) = runtime.warnings
    assert str(warning).startswith(
        "<string>:2:11: warning: sampler S (no texture in its sampler_state: the host sets one "
        "on its stage): nothing supplies it")
    assert image[..., :3].max() > 0            # the stand-in, not the empty stage's black


def test_strict_refuses_a_sampler_nothing_binds():
    runtime = Runtime(_effect(), effects.load_profile("radeon9700"), scene=QUAD, size=(8, 8),
                      strict=True)
    with pytest.raises(SceneError, match=r"^<string>:2:11: .*sampler S .*nothing supplies it"):
        runtime.render()


def test_a_sampler_naming_its_texture_refuses_a_picture_and_says_which_to_set(orange):
    text = "texture Tex;\n" + SAMPLER_ONLY.format(STATE=" = sampler_state { Texture = <Tex>; }")
    effect = effects.load_effect(text)
    with pytest.raises(EffectError) as err:
        effects.render(effect, "radeon9700", scene=QUAD, size=(8, 8), params={"S": orange})
    assert str(err.value).startswith(
        "<string>:3:31: error: --set S: this sampler samples the texture its sampler_state "
        "names (Tex): set that one instead")
    image = effects.render(effect, "radeon9700", scene=QUAD, size=(8, 8), params={"Tex": orange})
    np.testing.assert_allclose(image[4, 4], (100, 50, 25, 255), atol=1)


def test_a_picture_of_the_wrong_kind_is_refused_at_the_sampler(orange):
    effect = effects.load_effect(SAMPLER_ONLY.format(STATE="").replace("sampler2D", "samplerCUBE")
                                 .replace("tex2D(S, uv)", "texCUBE(S, float3(uv, 1))"))
    with pytest.raises(EffectError, match=r"^<string>:2:13: error: .*a cube texture is needed"):
        effects.render(effect, "radeon9700", scene=QUAD, size=(8, 8), params={"S": orange})
