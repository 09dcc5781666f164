"""The command line with fx_2_0 binaries: `effects compile FILE.fx -o out.fxo` writes the whole
effect, `--disassemble X.fxo` lists it, and every command takes a binary, recognised by its
tag whatever its name (validate, matrix, render, doctor)."""
from __future__ import annotations

import shutil

import numpy as np
from PIL import Image

import effects
from effects.cli import main as cli
from effects.shaders.fxo import write_effect_binary
from tests.paths import ROOT


def _copy(tmp_path, name="sdk9_hlsl.fx"):
    folder = tmp_path / "fx"
    shutil.copytree(ROOT / "fxfiles", folder)
    return folder / name


def test_compile_writes_the_effect_and_disassemble_lists_it(tmp_path, capsys):
    source = _copy(tmp_path)
    out = source.with_suffix(".fxo")
    assert cli.main(["compile", str(source), "-o", str(out)]) == 0
    assert out.read_bytes() == write_effect_binary(effects.load_effect(str(source)))
    assert cli.main(["compile", "--disassemble", str(out)]) == 0
    text = capsys.readouterr().out
    # parameters with semantics and defaults, annotations, techniques, states, shaders
    assert "float4x4 WorldViewProjection : WORLDVIEWPROJECTION" in text
    assert "float SpecularPower = 24;" in text
    assert '<string ResourceName = "textures/stones_base.png">' in text
    assert "technique Scene_ps20" in text and "technique Scene_ff" in text
    assert "LightType[0] = DIRECTIONAL;" in text and "WorldTransform[0] = <World>;" in text
    assert "\nps_2_0\n" in text and "\nvs_1_1\n" in text and "//   MaterialDiffuse" in text


def test_every_command_takes_a_binary_by_its_tag(tmp_path, capsys):
    source = _copy(tmp_path)
    out = source.with_name("sdk9_hlsl.bin")          # not named .fxo: the tag tells
    out.write_bytes(write_effect_binary(effects.load_effect(str(source))))
    assert cli.main(["validate", str(out), "--profile", "radeon8500"]) == 0
    assert "Scene_ps14" in capsys.readouterr().out
    assert cli.main(["matrix", str(out), "--profile", "geforce3", "--profile", "modern"]) == 0
    text = capsys.readouterr().out
    assert "Scene_ps11" in text and "Scene_ps20" in text
    assert cli.main(["doctor", str(out), "--profile", "modern"]) in (0, 1)
    capsys.readouterr()


def test_render_draws_the_binary_as_the_source(tmp_path):
    source = _copy(tmp_path, "wood.fx")
    binary = source.with_suffix(".fxo")
    assert cli.main(["compile", str(source), "-o", str(binary)]) == 0
    pictures = []
    for path in (source, binary):
        png = tmp_path / (path.name + ".png")
        assert cli.main(["render", str(path), "--profile", "modern", "--size", "64x64",
                         "-o", str(png)]) == 0
        pictures.append(np.asarray(Image.open(png)))
    assert np.array_equal(pictures[0], pictures[1])
    assert pictures[0].std() > 5       # a picture, not one colour


def test_a_bad_binary_is_a_located_error(tmp_path, capsys):
    bad = tmp_path / "bad.fxo"
    bad.write_bytes(bytes([0x01, 0x09, 0xFF, 0xFE]) + b"\xff\xff\x00\x00")
    assert cli.main(["validate", str(bad)]) == 2
    err = capsys.readouterr().err
    assert f"{bad}:1:5:" in err and "outside the 8-byte effect binary" in err
