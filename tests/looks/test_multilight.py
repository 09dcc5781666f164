"""fxfiles/multilight.fx: the bundled Shader Model 3 technique (a ps_3_0 loop over four lights
with aL-relative constants) and its ps_2_0 and fixed-function fallbacks, drawn by both back
ends on the cards that select them, against the lighting sum worked out by hand."""
from __future__ import annotations

from tests.paths import ROOT


import numpy as np
import pytest

import effects
from effects.d3d9.caps import load_profile

FX = ROOT / "fxfiles" / "multilight.fx"
SIZE = (64, 64)


@pytest.fixture(scope="module")
def effect():
    return effects.load_effect(str(FX))


@pytest.mark.parametrize("card, technique", [
    ("geforce6800", "MultiLight_ps30"), ("refrast", "MultiLight_ps30"),
    ("radeon9700", "MultiLight_ps20"), ("geforce3", "MultiLight_ff")])
def test_the_card_selects(effect, card, technique):
    assert effect.find_valid_technique(load_profile(card)).name == technique


@pytest.fixture(scope="module")
def pictures(effect):
    return {(card, backend): effects.render(effect, load_profile(card), backend=backend,
                                            size=SIZE)
            for card in ("geforce6800", "radeon9700", "geforce3")
            for backend in ("numpy", "gl")}


def test_the_sphere_centre_is_the_hand_computed_sum(pictures):
    # At the centre N = (0, 0, 1) (towards the camera at (0, 0, 3)): N.L = 0, 0, 0.8, 1 for the
    # four lights, so colour = 0.05 + 0.8 (0.2, 0.3, 0.9) + (0.25, 0.25, 0.25)
    # = (0.46, 0.54, 1.02 -> 1.0).
    expected = np.rint(np.array([0.46, 0.54, 1.0]) * 255)
    for (card, backend), image in pictures.items():
        tolerance = 3 if card == "geforce3" else 1      # per vertex: interpolated across
        got = image[SIZE[1] // 2, SIZE[0] // 2, :3].astype(int)
        assert np.abs(got - expected).max() <= tolerance, (card, backend, got)


def test_sm3_loop_draws_what_the_unrolled_ps20_draws_and_back_ends_agree(pictures):
    sm3, sm2 = pictures["geforce6800", "numpy"], pictures["radeon9700", "numpy"]
    assert np.abs(sm3.astype(int) - sm2).max() <= 1
    for card in ("geforce6800", "radeon9700", "geforce3"):
        diff = np.abs(pictures[card, "numpy"].astype(int) - pictures[card, "gl"])
        assert diff.max() <= 2, card
    # the lights show where they shine: +x (red) appears on screen left (D3D's left-handed
    # view from +z), -x (green) on the right, the blue light from below
    image = sm3[..., :3].astype(int)
    left, right = image[32, 12], image[32, 52]
    assert left[0] > left[1] + 60 and right[1] > right[0] + 60
    assert image[56, 32, 2] > image[8, 32, 2]
