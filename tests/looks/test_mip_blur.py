"""Persson's advice to blur the lower mip levels of normal and gloss maps ("the artifacts tend to
occur on lower mipmap levels, so it may help to not only just down-sample the previous mipmap
level ... but also apply a soft blur filter"), measured against the picture it should come
closer to: the same render supersampled 8 x 8 and averaged (each pixel the mean of 64 samples
of the shading over its area, drawn from mip level 0).

fxfiles/phong.fx's ps_2_0 technique on the default sphere, its stone normal map with plain box
mips and with each level after the first also blurred [1 2 1] / 4, pixels the sphere covers
wholly: the blurred chain is further from the supersampled average at every size (RMS 13.6
against 11.4 levels at 48 x 48, 11.2 against 10.1 at 64, 8.3 against 7.7 at 96). The blur
removes the aliasing it was meant to remove less than it removes the relief the average
keeps. So the bundled generators (sobel_normals, sobel_normals_ao, gloss) make plain box mips,
as the PNG gloss map already had; `mip_chain(blur=True)` stays for a caller who wants it.
"""
from __future__ import annotations

from tests.paths import ROOT

import numpy as np
import pytest

import effects
from effects.assets.textures import _height_from_image, make_texture, procedural, sobel_normal_map
from effects.base.errors import Location

FX = ROOT / "fxfiles"
SUPER = 8


@pytest.fixture(scope="module")
def normal_maps() -> dict[str, "effects.program.texture.Texture"]:
    heights = _height_from_image(str(FX / "textures" / "stones_height.png"), Location("h", 1, 1))
    normals = sobel_normal_map(heights, 1.0)
    return {"plain": make_texture(normals, "X8R8G8B8"),
            "blurred": make_texture(normals, "X8R8G8B8", blur=True)}


def errors(size: int, maps) -> dict[str, float]:
    """RMS difference (levels) from the supersampled average, over the pixels the sphere
    covers wholly, for each normal map's mip chain."""
    fx = effects.load_effect(FX / "phong.fx")

    def draw(n: int, texture) -> np.ndarray:
        return effects.render(fx, "radeon9700", technique="PerPixelPhong_ps20", size=(n, n),
                              params={"NormalMap": texture})[..., :3].astype(np.float64)

    fine = draw(size * SUPER, maps["plain"])          # level 0 at 8 x 8 samples a pixel
    blocks = fine.reshape(size, SUPER, size, SUPER, 3)
    covered = (blocks.max(axis=-1) > 0).all(axis=(1, 3))
    average = blocks.mean(axis=(1, 3))
    return {name: float(np.sqrt(((draw(size, texture) - average)[covered] ** 2).mean()))
            for name, texture in maps.items()}


@pytest.mark.parametrize("size, plain, blurred", [(48, 11.4, 13.6), (64, 10.1, 11.2), (96, 7.7, 8.3)])
def test_blurred_mips_move_away_from_the_supersampled_average(normal_maps, size, plain, blurred):
    got = errors(size, normal_maps)
    assert got["plain"] == pytest.approx(plain, abs=0.3)
    assert got["blurred"] == pytest.approx(blurred, abs=0.3)
    assert got["blurred"] > got["plain"]


def test_the_bundled_normal_and_gloss_maps_have_plain_mips(normal_maps):
    made = procedural("sobel_normals:textures/stones_height.png", base_dir=str(FX))
    assert len(made.levels) == len(normal_maps["plain"].levels)
    for mine, plain in zip(made.levels, normal_maps["plain"].levels):
        assert np.array_equal(mine, plain)
    gloss = procedural("gloss")
    level0 = np.asarray(gloss.levels[0], np.float64)
    box = level0.reshape(64, 2, 64, 2, -1).mean(axis=(1, 3))
    assert np.abs(np.asarray(gloss.levels[1]) - box).max() <= 1 / 255 + 1e-6
