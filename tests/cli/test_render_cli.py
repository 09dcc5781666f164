"""`effects render`: writes the PNG, prints one line, exits 0 / 1 / 2."""
from __future__ import annotations

from tests.paths import ROOT

import os
import re
import subprocess
import sys

import numpy as np
import pytest
from PIL import Image

from effects.cli.main import main

# Draws the TFACTOR colour (a DWORD parameter) on whatever the scene gives.
EFFECT = """
DWORD Col = 0xff0000ff;
float Scale = 1;
technique Flat { pass P {
    Lighting = False; TextureFactor = <Col>;
    ColorOp[0] = SelectArg1; ColorArg1[0] = TFactor;
    AlphaOp[0] = SelectArg1; AlphaArg1[0] = TFactor;
} }
"""
SHADER_ONLY = """
technique Shader { pass P { PixelShader = asm { ps.2.0
    mov oC0, c0
}; } }
technique Dot3 { pass P { ColorOp[0] = DotProduct3; } }
"""


@pytest.fixture()
def fx(tmp_path):
    path = tmp_path / "flat.fx"
    path.write_text(EFFECT)
    return path


def run(*argv: str) -> int:
    return main([str(a) for a in argv])


def test_render_writes_the_png_and_prints_one_line(fx, tmp_path, capsys):
    out = tmp_path / "out.png"
    scene = tmp_path / "quad.yaml"
    scene.write_text("mesh: {primitive: list, vertices: [{position: [-1, 1, 0.5]}, "
                     "{position: [1, 1, 0.5]}, {position: [-1, -1, 0.5]}]}\n")
    code = run("render", fx, "--profile", "tnt2", "--scene", scene, "--size", "6x4", "-o", out)
    printed = capsys.readouterr().out.strip().splitlines()
    assert code == 0
    assert len(printed) == 1
    assert re.fullmatch(rf"rendered Flat on RIVA TNT2 \(1 pass\) with numpy in \d+\.\d ms -> {re.escape(str(out))}",
                        printed[0]), printed
    image = np.asarray(Image.open(out))
    assert image.shape == (4, 6, 4)
    # the triangle covers the upper-left half in blue; the black clear elsewhere, opaque in
    # the PNG although the target's alpha there is 0
    assert tuple(image[0, 0]) == (0, 0, 255, 255) and tuple(image[3, 5]) == (0, 0, 0, 255)
    assert run("render", fx, "--profile", "tnt2", "--scene", scene, "--size", "6x4", "--alpha",
               "-o", out) == 0
    kept = np.asarray(Image.open(out))
    assert tuple(kept[0, 0]) == (0, 0, 255, 255) and tuple(kept[3, 5]) == (0, 0, 0, 0)


def test_scene_size_technique_and_set_values(fx, tmp_path, capsys):
    scene = tmp_path / "s.yaml"
    scene.write_text("mesh: quad\nsize: [9, 9]\nclear: {color: '0xff000000'}\n")
    out = tmp_path / "out.png"
    code = run("render", fx, "-p", "geforce2", "--technique", "Flat", "--scene", scene,
               "--size", "3x2", "--set", "Col=0xff00ff00", "--set", "Scale=[2]", "-o", out)
    assert code == 0, capsys.readouterr().err
    image = np.asarray(Image.open(out))
    assert image.shape == (2, 3, 4) and (image == (0, 255, 0, 255)).all()


def test_no_valid_technique_exits_1_with_every_reason(tmp_path, capsys):
    path = tmp_path / "shader.fx"
    path.write_text(SHADER_ONLY)
    out = tmp_path / "out.png"
    code = run("render", path, "--profile", "tnt2", "-o", out)
    err = capsys.readouterr().err
    assert code == 1
    assert "no technique is valid on RIVA TNT2" in err
    assert "Shader:" in err and "ps_2_0" in err
    assert "Dot3:" in err and "DOTPRODUCT3" in err
    assert not out.exists()


@pytest.mark.parametrize("extra, words", [
    (["--set", "Col=green"], "--set Col='green'"),
    (["--set", "Colour=1"], "no parameter of that name"),
    (["--set", "Col"], "expected NAME=VALUE"),
    (["--size", "big"], "expected WxH"),
    (["--size", "0x10"], "size"),
    (["--technique", "Nope"], "no technique named 'Nope'"),
    (["--backend", "vulkan"], "unknown back end 'vulkan'"),
    (["--scene", "missing.yaml"], "cannot read scene file"),
])
def test_bad_input_exits_2_and_says_why(fx, tmp_path, capsys, extra, words):
    code = run("render", fx, "--profile", "tnt2", "-o", tmp_path / "out.png", *extra)
    err = capsys.readouterr().err
    assert code == 2
    assert words in " ".join(err.split()), err


def test_a_bad_set_value_is_located_at_the_parameter(fx, tmp_path, capsys):
    code = run("render", fx, "--profile", "tnt2", "-o", tmp_path / "o.png", "--set", "Scale=1,2")
    err = " ".join(capsys.readouterr().err.split())
    assert code == 2
    assert f"{fx}:3:7: error: --set Scale='1,2': float Scale: takes a number, got 2" in err


def test_missing_required_options_are_usage_errors(fx, capsys):
    assert run("render", fx, "-o", "x.png") == 2          # no --profile
    assert run("render", fx, "--profile", "tnt2") == 2    # no -o
    capsys.readouterr()


def test_python_dash_m_effects_render(fx, tmp_path):
    out = tmp_path / "m.png"
    result = subprocess.run([sys.executable, "-m", "effects", "render", str(fx), "--profile", "tnt2",
                             "--size", "4x4", "-o", str(out)], capture_output=True, text=True,
                            cwd=str(tmp_path))
    assert result.returncode == 0, result.stderr
    assert out.exists() and result.stdout.startswith("rendered Flat on RIVA TNT2")


FXFILES = os.path.join(str(ROOT), "fxfiles")


@pytest.mark.parametrize("name, card", [("phong.fx", "geforce3"), ("specular_bump.fx", "radeon9700")])
def test_bundled_effects_render_from_the_command_line(tmp_path, capsys, name, card):
    out = tmp_path / "bundled.png"
    code = run("render", os.path.join(FXFILES, name), "--profile", card, "--size", "48x48", "-o", out)
    assert code == 0, capsys.readouterr().err
    image = np.asarray(Image.open(out)).astype(int)
    assert image[..., :3].std() > 5          # neither black nor uniform


def test_the_scene_beside_the_effect_is_its_scene(tmp_path, capsys):
    """wood.fx's colours and light come from wood.yaml beside it: `render` and `doctor` read
    it as `matrix --render` does (it drew black, exit 0, without); --no-scene skips it."""
    wood = ROOT / "fxfiles" / "wood.fx"
    beside, named, none = (tmp_path / f"{n}.png" for n in ("beside", "named", "none"))
    common = ("--profile", "radeon9700", "--size", "32x32")
    assert run("render", wood, *common, "-o", beside) == 0
    assert run("render", wood, *common, "--scene", ROOT / "fxfiles" / "wood.yaml", "-o", named) == 0
    assert run("render", wood, *common, "--no-scene", "-o", none) == 0
    pictures = [np.asarray(Image.open(p).convert("RGB"), np.int32) for p in (beside, named, none)]
    assert np.array_equal(pictures[0], pictures[1])
    # ambient white x the wood's own colour: the lit sphere is brown, not black
    assert pictures[0].max() > 60 and pictures[2].max() == 0
    capsys.readouterr()
    assert run("doctor", wood) == 0
    beside_report = capsys.readouterr().out
    assert run("doctor", wood, "--no-scene") == 0
    alone_report = capsys.readouterr().out
    assert "diffuse_color <- --set / scene params" in beside_report
    assert "nothing missing" in beside_report
    assert "set by nothing (they read 0):\n    ambient_color" in alone_report


def test_render_mesh_draws_a_mesh_file_or_a_built_in_one(tmp_path, capsys):
    """`render --mesh` (issue 32): a mesh file through the mesh loader, or a built-in name,
    wins over the scene's mesh; a missing file is a located input error."""
    phong = str(ROOT / "fxfiles" / "phong.fx")
    pictures = {}
    for mesh in ("sphere", "cube", str(ROOT / "fxfiles" / "coarse_sphere.obj")):
        out = tmp_path / f"{os.path.basename(mesh)}.png"
        assert main(["render", phong, "-p", "refrast", "--size", "32x32", "--mesh", mesh,
                     "-o", str(out)]) == 0
        pictures[mesh] = np.asarray(Image.open(out))[..., :3].astype(int)
    sphere, cube, coarse = pictures.values()
    assert np.abs(sphere - cube).max() > 100            # another silhouette
    assert 0 < np.abs(sphere - coarse).mean() < np.abs(sphere - cube).mean()   # a coarser sphere
    capsys.readouterr()
    assert main(["render", phong, "-p", "refrast", "--mesh", str(tmp_path / "none.obj"),
                 "-o", str(tmp_path / "x.png")]) == 2
    assert "--mesh:1:1: error: mesh file not found" in capsys.readouterr().err
