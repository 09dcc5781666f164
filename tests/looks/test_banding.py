"""The hardware-precision story of Boyd and Taylor's chapter, measured in the picture.

The chapter (section on ps.1.1 specular): "Notice the banding in the highlight. This is due to
loss of precision in the calculations, since each result channel is only 8-bits ... don't try
to use the technique for powers greater than 16. On graphic chips with higher precision, this
may not be an issue." And of the table lookup: "There is higher precision in the texture read
unit, and the table-lookup texture ends up nicely filtered, so that the banding is reduced to
a tolerable level."

fxfiles/specular_bump.fx draws both: SpecularMultiply_ps11 (N.H by dp3_sat, then four mul
squarings: N.H^16) and SpecularTable_ps11 (texm3x2pad/texm3x2tex read N.H^16 from a 256 x 256
table). The GeForce3 profile holds ps_1_1 results at 8 fraction bits in [-1, 1]
(effects.d3d9.precision: quantize to steps of 1/255 after every instruction), `modern` computes
in float. To see the specular term alone, the Earth is black, the normal map flat and the
ps_2_0 specular colour white; the picture is then N.H^16 (x 255) and nothing else.

The arithmetic of the bands. dp3_sat leaves x = k / 255 for a whole k. Each `mul r0, r0, r0`
squares and rounds to the nearest 1/255 again, so the output is a function of k alone: the
"ladder" L(k) = q(q(q(q(x^2)^2)^2)^2), q(y) = round(255 y) / 255. Above half brightness,
x^16 >= 1/2 needs x >= 2^(-1/16) = 0.95760, i.e. k >= 244.2: only k = 245..255, eleven values,
so the whole upper half of the highlight is drawn with at most 11 grey levels (255, 239, 224,
211, 197, 185, 175, 163, 152, 142, 134: steps of up to 16/255, each wide enough to see as a
ring). The slope of x^16 near x = 1 is 16: one input step of 1/255 is an output step of
~16/255. The table instead looks up (u, v) computed at texture-address precision and filters
between texels 1/256 apart, so its output takes nearly every level in the same region.
"""
from __future__ import annotations

from tests.paths import ROOT

import os

import numpy as np
import pytest

import effects
from effects.assets.textures import make_texture

FX = os.path.join(str(ROOT), "fxfiles", "specular_bump.fx")
SIZE = 128
HALF = 128            # the highlight region: where the float picture is at least half bright


def solid(rgb) -> "effects.program.texture.Texture":
    return make_texture(np.broadcast_to(np.array([*rgb, 1.0], np.float32), (4, 4, 4)).copy(),
                        "X8R8G8B8")


SPECULAR_ONLY = {"NormalMap": solid((0.5, 0.5, 1.0)), "EarthTexture": solid((0.0, 0.0, 0.0)),
                 "SpecularColor": [1.0, 1.0, 1.0, 1.0]}


@pytest.fixture(scope="module")
def pictures() -> dict[tuple[str, str], np.ndarray]:
    fx = effects.load_effect(FX)
    out = {}
    for technique, card in [("SpecularMultiply_ps11", "geforce3"),
                            ("SpecularTable_ps11", "geforce3"),
                            ("SpecularMultiply_ps11", "modern"),
                            ("Specular_ps20", "radeon9700"),
                            ("Specular_ps20", "modern")]:
        image = effects.render(fx, card, technique=technique, size=(SIZE, SIZE),
                               params=SPECULAR_ONLY)
        assert (image[..., 0] == image[..., 1]).all() and (image[..., 1] == image[..., 2]).all()
        out[(technique, card)] = image[..., 1].astype(int)
    return out


def ladder() -> set[int]:
    """Every output level the 8-bit multiply chain can produce (module docstring)."""
    levels = set()
    for k in range(256):
        x = k / 255
        for _ in range(4):
            x = np.floor(x * x * 255 + 0.5) / 255      # round half up, as the card's grid
        levels.add(int(round(x * 255)))
    return levels


def highlight(pictures) -> np.ndarray:
    """The region where the float version of the same technique is at least half bright."""
    region = pictures[("SpecularMultiply_ps11", "modern")] >= HALF
    assert 300 < region.sum() < 3000       # a highlight, not the whole disc or a dot
    return region


def levels(picture: np.ndarray, region: np.ndarray) -> int:
    return len(np.unique(picture[region]))


def test_the_ladder_has_eleven_levels_above_half():
    # The arithmetic of the docstring, checked: 11 levels >= 128, from 134 to 255.
    upper = sorted(v for v in ladder() if v >= HALF)
    assert upper == [134, 142, 152, 163, 175, 185, 197, 211, 224, 239, 255]


def test_the_geforce3_multiply_draws_only_ladder_levels(pictures):
    # Every pixel of the 8-bit multiply picture is one of the ladder's values: the bands are
    # exactly the precision the profile gives ps_1_1.
    picture = pictures[("SpecularMultiply_ps11", "geforce3")]
    assert set(np.unique(picture)) <= ladder()
    assert picture.max() == 255           # the peak is reached (k = 255)


def test_multiply_bands_more_than_the_table_on_the_geforce3(pictures):
    region = highlight(pictures)
    multiply = pictures[("SpecularMultiply_ps11", "geforce3")]
    table = pictures[("SpecularTable_ps11", "geforce3")]
    # Distinct grey levels over the upper half of the highlight: at most the ladder's 11
    # (plus one for pixels the float picture puts just above 128 and the ladder just below)
    # against a level for nearly every value from 128 up for the table.
    assert levels(multiply, region) <= 12
    assert levels(table, region) >= 80
    # Distance from the float curve (the same technique on `modern`): the multiply's bands
    # leave it by up to half a ring step (~8/255), the table follows it to within its
    # filtering (the table's last texel centre is v = 255.5/256, so its peak is
    # (255.5/256)^16 = 0.969 = 247/255 where the float reaches 250).
    exact = pictures[("SpecularMultiply_ps11", "modern")]
    multiply_error = np.abs(multiply - exact)[region].mean()
    table_error = np.abs(table - exact)[region].mean()
    assert multiply_error > 2.0
    assert table_error < 1.0
    assert multiply_error > 5 * table_error


def test_the_same_multiply_does_not_band_in_float(pictures):
    # On `modern` (float) the same four squarings keep every level, like ps_2_0's pow.
    region = highlight(pictures)
    multiply_float = pictures[("SpecularMultiply_ps11", "modern")]
    assert levels(multiply_float, region) >= 80
    assert not set(np.unique(multiply_float[region])) <= ladder()
    for card in ("radeon9700", "modern"):
        pow_picture = pictures[("Specular_ps20", card)]
        assert levels(pow_picture, pow_picture >= HALF) >= 80
    # Along the row through the peak, where the float picture is above 225/255: the float
    # curve climbs in steps of at most ~7/255 a pixel (x^16 is flat near its top), the 8-bit
    # one jumps a whole ladder rung (239 -> 255 is 16/255) between flat runs.
    row = np.unravel_index(np.argmax(multiply_float), multiply_float.shape)[0]
    top = (multiply_float[row][1:] >= 225) & (multiply_float[row][:-1] >= 225)
    assert top.sum() >= 6
    steps_float = np.abs(np.diff(multiply_float[row]))[top]
    steps_band = np.abs(np.diff(pictures[("SpecularMultiply_ps11", "geforce3")][row]))[top]
    assert steps_float.max() <= 8
    assert steps_band.max() >= 13
    assert (steps_band == 0).sum() >= top.sum() // 2    # mostly flat runs between the jumps
