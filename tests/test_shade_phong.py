"""ShadeMode = Phong (fxfiles/fast_phong.fx): the fixed-function lighting evaluated per pixel with
the interpolated normal normalised at each pixel (Bishop and Weimer's "Phong" row), on the one
card that reports D3DPSHADECAPS_COLORPHONGRGB (refrast), against the lighting computed here by
hand; the Gouraud fallback everywhere else."""
from __future__ import annotations

import os

import numpy as np
import pytest

import effects
from effects.errors import EffectError

import test_effect_pictures as pictures

FX = os.path.join(os.path.dirname(__file__), "..", "fxfiles", "fast_phong.fx")


def load() -> effects.Effect:
    return effects.load_effect(FX)


def test_only_refrast_shades_phong():
    fx = load()
    for card in effects.list_profiles():
        profile = effects.load_profile(card)
        chosen = fx.find_valid_technique(profile).name
        assert chosen == ("Phong" if card == "refrast" else "Gouraud"), card
    reasons = fx.validate(fx.technique("Phong"), effects.load_profile("geforce3")).reasons
    assert [r.message for r in reasons] == [
        "ShadeMode = Phong (lights per pixel) needs D3DPSHADECAPS_COLORPHONGRGB; the GeForce3 "
        "does not have it"]


def by_hand() -> np.ndarray:
    """fast_phong.fx's lighting at each pixel of the default sphere, 0..255: ambient 0.1 +
    0.75 max(N.L, 0) + 0.6 (N.H)^40 (where N.L > 0), H the half angle of L and the eye."""
    n, p = pictures.NORMAL, pictures.POINT
    to_light = pictures.unit(np.array([0.577, 0.577, 0.577]))
    h = pictures.unit(to_light + pictures.unit(pictures.EYE - p))
    n_dot_l = np.sum(n * to_light, axis=-1)
    n_dot_h = np.clip(np.sum(n * h, axis=-1), 0.0, 1.0)
    value = 0.1 + 0.75 * np.maximum(n_dot_l, 0.0) + 0.6 * n_dot_h ** 40 * (n_dot_l > 0)
    return np.clip(value, 0.0, 1.0) * 255


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_phong_is_the_lighting_at_every_pixel(backend):
    # Per pixel the only difference from the formula is the mesh: the interpolated normal of
    # the 24 x 48 sphere against the true one. Measured: mean 0.36/255, max 2.5/255 (numpy);
    # Gouraud, the same lighting per vertex, is off by up to 15/255 at the highlight.
    fx = load()
    expected = by_hand()
    disc = pictures.DISC
    scene = pictures.SCENE
    phong = effects.render(fx, "refrast", technique="Phong", scene=scene, size=(128, 128),
                           backend=backend)[..., 0].astype(np.float64)
    gouraud = effects.render(fx, "refrast", technique="Gouraud", scene=scene, size=(128, 128),
                             backend=backend)[..., 0].astype(np.float64)
    error = np.abs(phong - expected)[disc]
    assert error.mean() < 1.0 and error.max() <= 6.0
    assert np.abs(gouraud - expected)[disc].max() > 4 * error.max()


def test_both_back_ends_draw_the_same_phong():
    fx = load()
    a = effects.render(fx, "refrast", technique="Phong", size=(96, 96), backend="numpy")
    b = effects.render(fx, "refrast", technique="Phong", size=(96, 96), backend="gl")
    assert np.abs(a.astype(int) - b.astype(int)).max() <= 2


def test_a_phong_pass_keeps_two_interpolators_free():
    text = open(FX).read().replace("        ColorOp[1]   = Disable;\n        AlphaOp[1]   = Disable;",
                                   "".join(f"        ColorOp[{i}] = SelectArg1;\n        ColorArg1[{i}] = Current;\n"
                                           for i in range(1, 7)) + "        ColorOp[7] = Disable;", 1)
    fx = effects.load_effect(text)
    with pytest.raises(EffectError, match="texture coordinates 6 and 7"):
        effects.render(fx, "refrast", technique="Phong", size=(16, 16))
