"""Every bundled effect draws its intended look alone (issue 32): `effects render
fxfiles/X.fx -p CARD -o out.png`, nothing else given (its beside-scene X.yaml, where there is
one, is read by the command), says nothing about what it shows nothing of, and the picture has
the feature its look is about, measured. The camera at +z looks down -z in a left-handed
frame, so the scene light at (2, 2, 2) lights the upper left of the sphere (+x is the left)."""
from __future__ import annotations

from tests.paths import ROOT

import numpy as np
import pytest
from PIL import Image

from effects.cli.main import main

FXFILES = ROOT / "fxfiles"


def luma(rgb: np.ndarray) -> float:
    return float(rgb[..., :3].astype(float).mean())


def quarter(image: np.ndarray, which: str) -> np.ndarray:
    """The inner 16x16 of a quadrant of a 64x64 picture (on the sphere for every effect)."""
    rows = slice(12, 28) if which[0] == "T" else slice(36, 52)
    cols = slice(12, 28) if which[1] == "L" else slice(36, 52)
    return image[rows, cols, :3].astype(int)


def lit_side_brighter(image, times):
    return luma(quarter(image, "TL")) > times * luma(quarter(image, "BR"))


def mean(image, which):
    return quarter(image, which).reshape(-1, 3).mean(0)


def rings(image) -> int:
    """How often the red along the middle row rises again by 4 or more: a smooth lit sphere
    rises once and falls; wood's rings rise again and again."""
    row = image[32, 8:56, 0].astype(int)
    return int((np.diff(row) >= 4).sum())


LOOKS = {
    # the factored BRDF (McCool et al.) lights an earth-like texture from the upper left
    "brdf": ("radeon9700", lambda im: lit_side_brighter(im, 3.0) and mean(im, "TL")[1] > mean(im, "TL")[0]),
    # a grey sphere, its specular highlight in the lit quadrant and saturating
    "fast_phong": ("radeon9700", lambda im: (quarter(im, "TL").max() == 255
                                              and lit_side_brighter(im, 3.0)
                                              and (im[..., 0] == im[..., 2]).all())),
    # the stone texture, bluish sky occlusion: many colours, blue above red
    "hemisphere": ("radeon9700", lambda im: (len(np.unique(im[..., :3].reshape(-1, 3), axis=0)) > 500
                                              and mean(im, "TR")[2] > mean(im, "TR")[0] + 10)),
    # three coloured lights: red-purple upper left, blue below
    "multilight": ("radeon9700", lambda im: (mean(im, "TL")[0] > mean(im, "TL")[1] + 50
                                              and mean(im, "BR")[2] > mean(im, "BR")[0] + 100)),
    "phong": ("radeon9700", lambda im: lit_side_brighter(im, 3.0) and quarter(im, "TL").max() > 200),
    # the reflected orange checker ground in the lower half
    "sdk8_style": ("radeon9700", lambda im: mean(im, "BL")[0] > mean(im, "BL")[2] + 100),
    "sdk9_hlsl": ("radeon9700", lambda im: luma(quarter(im, "TR")) > 3 * luma(quarter(im, "BL"))),
    # white-grey marble: bright and nearly colourless where lit
    "sdk9_style": ("radeon9700", lambda im: (luma(quarter(im, "TR")) > 180
                                              and abs(mean(im, "TR")[0] - mean(im, "TR")[2]) < 10)),
    # the box's shadow on the lit floor (lower left) against the lit floor (lower right)
    "shadows": ("radeon9700", lambda im: luma(quarter(im, "BR")) > 2.5 * luma(quarter(im, "BL"))),
    # a bumped, specular earth: the lit upper right far brighter than the lower left, greenish
    "specular_bump": ("radeon9700", lambda im: (luma(quarter(im, "TR")) > 4 * luma(quarter(im, "BL"))
                                                 and mean(im, "TR")[1] > mean(im, "TR")[0])),
    # brown wood (red over green over blue) with rings
    "wood": ("radeon9700", lambda im: (mean(im, "TL")[0] > mean(im, "TL")[1] > mean(im, "TL")[2]
                                        and rings(im) > 3)),
}


def test_every_bundled_effect_has_a_look_checked():
    assert sorted(LOOKS) == sorted(p.stem for p in FXFILES.glob("*.fx"))


@pytest.mark.parametrize("name", sorted(LOOKS))
def test_the_bundled_effect_draws_its_look_alone(name, tmp_path, capsys):
    card, look = LOOKS[name]
    out = tmp_path / f"{name}.png"
    assert main(["render", str(FXFILES / f"{name}.fx"), "-p", card, "--size", "64x64",
                 "-o", str(out)]) == 0
    assert capsys.readouterr().err == ""       # no stand-in, nothing unset, nothing culled
    image = np.asarray(Image.open(out))
    assert len(np.unique(image[..., :3].reshape(-1, 3), axis=0)) > 50   # not blank
    assert look(image), name


def test_without_its_scene_wood_says_why_it_looks_wrong(tmp_path, capsys):
    """wood.yaml gives its colours and light; without it (--no-scene) the render is not
    silent about what nothing sets."""
    out = tmp_path / "wood.png"
    assert main(["render", str(FXFILES / "wood.fx"), "-p", "radeon9700", "--size", "32x32",
                 "--no-scene", "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert "set by nothing" in err and "the frame is one colour (0, 0, 0)" in err
