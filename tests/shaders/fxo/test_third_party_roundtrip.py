"""An effect written by someone else (Irrlicht 1.8's example HLSL shader, from Debian's
package: tests/data/realfx/MANIFEST.md) compiled to fx_2_0 and loaded back draws what its
source draws. Its light colour and position are declared without values, which fxc writes
as zeros: the host binds them by name in the binary as in the source (an all-zero light is
no light of the file's own), where the binary once drew black."""
from __future__ import annotations

import shutil

import numpy as np

import effects
from effects.shaders.fxo import write_effect_binary
from tests.paths import ROOT

IRRLICHT = ROOT / "tests" / "data" / "realfx" / "irrlicht" / "irr_d3d9_hlsl.fx"


def test_irrlichts_effect_draws_the_same_from_its_binary(tmp_path):
    source = effects.load_effect(str(IRRLICHT))
    shutil.copy(IRRLICHT.parent / "wall.jpg", tmp_path)    # the binary names it relatively
    binary_path = tmp_path / "irr_d3d9_hlsl.fxo"
    binary_path.write_bytes(write_effect_binary(source))
    loaded = effects.load_effect(str(binary_path))
    assert loaded.parameter("mLightColor").value is not None   # zeros, as fxc writes them
    a = effects.render(source, "radeon9700", size=(48, 48))
    b = effects.render(loaded, "radeon9700", size=(48, 48))
    assert np.asarray(a)[..., :3].mean() > 30       # lit by the bound light, not black
    assert np.array_equal(np.asarray(a), np.asarray(b))
