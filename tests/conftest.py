"""Fixtures shared by several test modules: the back ends made once per module, and the small
tinted effect that the reload and viewer tests edit on disk."""
from __future__ import annotations

import atexit
import os
import shutil
import tempfile
from pathlib import Path

import pytest

# The command line keeps compiled shaders on disk (effects/shaders/hlsl/store.py): the tests'
# commands, in process and as child processes, keep theirs in a folder of this run, not in the
# user's ~/.cache.
os.environ["EFFECTS_CACHE_DIR"] = tempfile.mkdtemp(prefix="effects-test-shaders-")
atexit.register(shutil.rmtree, os.environ["EFFECTS_CACHE_DIR"], ignore_errors=True)
from PIL import Image

from effects.program.backend import create_backend
from backends.gl import GLBackend


@pytest.fixture(scope="module")
def gl():
    """The GL back end, one per module (a context is costly). Without GL it fails with
    GLUnavailable, never skips."""
    backend = GLBackend()
    yield backend
    backend.close()


@pytest.fixture(scope="module")
def ref():
    """The NumPy reference back end, one per module."""
    backend = create_backend("numpy")
    yield backend
    backend.close()


# Technique Flat draws TextureFactor = TINT (from tint.fxh) on every pixel; Dot3 needs
# D3DTEXOPCAPS_DOTPRODUCT3 (line 15). The texture is named but no stage reads it: its image
# is only a file to watch.
TINTED_EFFECT = """#include "tint.fxh"
texture Base < string ResourceName = "base.png"; >;
technique Flat
{
    pass P0
    {
        Lighting = False;
        TextureFactor = TINT;
        ColorOp[0] = SelectArg1;
        ColorArg1[0] = TFactor;
        AlphaOp[0] = SelectArg1;
        AlphaArg1[0] = TFactor;
    }
}
technique Dot3 { pass P0 { Lighting = False; ColorOp[0] = DotProduct3; ColorArg1[0] = TFactor; ColorArg2[0] = Diffuse; } }
"""


@pytest.fixture
def tinted_effect(tmp_path) -> Path:
    """flat.fx (TINTED_EFFECT), tint.fxh defining TINT as red (0xffff0000) and a red 4 x 4
    base.png, written to a temporary folder. Returns the path of flat.fx."""
    (tmp_path / "tint.fxh").write_text("#define TINT 0xffff0000\n")
    Image.new("RGB", (4, 4), (255, 0, 0)).save(tmp_path / "base.png")
    path = tmp_path / "flat.fx"
    path.write_text(TINTED_EFFECT)
    return path
