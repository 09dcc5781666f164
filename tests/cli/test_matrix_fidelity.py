"""The fidelity figures on the command line: `effects matrix --fidelity` (table, --json, the
contact sheet), kept with the matrix rows and found again only while every file the renders
named is the same; `effects validate --why`; `effects render --policy fidelity`."""
from __future__ import annotations

import json
import os

import numpy as np
import pytest
from PIL import Image

from effects.base import disk_store
from effects.cli import matrix_store
from effects.cli.main import main
from effects.cli.matrix_store import MatrixJob
from effects.cli.report import matrix_job
from effects.cli.sheet import compose
from effects.host.batch import Cell
from tests.cli.test_matrix_store import _settle
from tests.paths import ROOT

PHONG = os.path.join(str(ROOT), "fxfiles", "phong.fx")

TEXTURED = """
texture T < string ResourceName = "t.png"; >;
sampler S = sampler_state { Texture = <T>; };
technique Textured { pass P0 { Sampler[0] = <S>; ColorOp[0] = SelectArg1; ColorArg1[0] = Texture; } }
technique Flat { pass P0 { Lighting = false; ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse; } }
"""
# Flat unlit: the mesh's white, not black on the black clear colour (a best picture that shows
# nothing measures nothing: tests/host/test_fidelity.py)


def _json(capsys, *args) -> dict:
    assert main(["matrix", *args, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_the_json_has_fidelity_only_when_asked(capsys):
    plain = _json(capsys, PHONG, "-p", "geforce2", "-p", "radeon9700")
    assert all("fidelity" not in cell for cell in plain[PHONG].values())
    measured = _json(capsys, PHONG, "-p", "geforce2", "-p", "radeon9700", "--fidelity")
    gf2, r300 = measured[PHONG]["geforce2"], measured[PHONG]["radeon9700"]
    assert gf2["technique"] == "Dot3_dx7"           # file order, as without --fidelity
    assert gf2["fidelity"]["best"] == "PerPixelPhong_ps20"
    assert 0.6 < gf2["fidelity"]["ssim"] < 0.8 and 15 < gf2["fidelity"]["psnr"] < 25
    assert r300["fidelity"] == {"ssim": 1.0, "psnr": None, "best": "PerPixelPhong_ps20"}
    # under the fidelity policy the GeForce2 draws the closer SingleTexture
    chosen = _json(capsys, PHONG, "-p", "geforce2", "--policy", "fidelity")
    assert chosen[PHONG]["geforce2"]["technique"] == "SingleTexture"
    assert chosen[PHONG]["geforce2"]["fidelity"]["ssim"] > gf2["fidelity"]["ssim"]


def test_the_table_shows_the_figure_in_each_cell(capsys):
    assert main(["matrix", PHONG, "-p", "geforce2", "-p", "radeon9700", "--fidelity"]) == 0
    out = capsys.readouterr().out
    assert "Dot3_dx7 (1) SSIM 0.7" in out
    assert "PerPixelPhong_ps20 (1) = best" in out


def test_a_row_with_figures_is_kept_with_the_files_its_renders_named(tmp_path):
    folder = tmp_path / "store"
    assert disk_store.enable(str(folder))
    try:
        path = str(tmp_path / "textured.fx")
        with open(path, "w") as f:
            f.write(TEXTURED)
        picture = str(tmp_path / "t.png")
        Image.fromarray(np.full((8, 8, 3), 200, np.uint8)).save(picture)
        _settle(path, picture)
        cards = ("geforce2",)
        job = MatrixJob(path, cards, "first", None, False,
                        matrix_store.shared_key(cards, "first", False, None,
                                                matrix_store.fidelity_options(True, "Flat")),
                        True, None, "Flat")
        row = matrix_job(job)
        assert row["geforce2"]["technique"] == "Textured"
        assert 0 < row["geforce2"]["fidelity"]["ssim"] < 1
        assert row["geforce2"]["fidelity"]["best"] == "Flat"
        assert matrix_store.stored_row(job) == row
        entry = disk_store.read(matrix_store.inputs(job).name)
        assert [os.path.abspath(picture)] == [p for p, _ in entry["files"]]
        # the texture changes: the row is made again
        Image.fromarray(np.full((8, 8, 3), 10, np.uint8)).save(picture)
        _settle(picture)
        assert matrix_store.stored_row(job) is None
        # a row without figures is another entry, and lists no files
        plain = MatrixJob(path, cards, "first", None, False,
                          matrix_store.shared_key(cards, "first", False, None))
        made = matrix_job(plain)
        assert "fidelity" not in made["geforce2"]
        assert disk_store.read(matrix_store.inputs(plain).name)["files"] == []
    finally:
        disk_store.disable()


def test_a_stored_figure_of_the_wrong_shape_is_a_miss():
    good = {"c": {"technique": "T", "passes": 1, "rejected": {},
                  "fidelity": {"ssim": 0.5, "psnr": None, "best": "B"}}}
    assert matrix_store._checked_row(good) is good
    bad = {"c": {**good["c"], "fidelity": {"ssim": "0.5", "psnr": None, "best": "B"}}}
    with pytest.raises(ValueError):
        matrix_store._checked_row(bad)


def test_validate_why_prints_each_valid_techniques_figure(capsys):
    assert main(["validate", PHONG, "-p", "geforce2", "--why"]) == 0
    out = capsys.readouterr().out
    assert "against PerPixelPhong_ps20 on refrast (128x128" in out
    lines = [line for line in out.splitlines() if "Dot3_dx7: 1 pass" in line]
    assert lines and "SSIM 0.7" in lines[0] and "dB" in lines[0]
    assert main(["validate", PHONG, "-p", "geforce2"]) == 0
    assert "SSIM" not in capsys.readouterr().out          # only with --why


def test_render_under_the_fidelity_policy(tmp_path, capsys):
    out = str(tmp_path / "o.png")
    assert main(["render", PHONG, "-p", "geforce2", "--policy", "fidelity", "--size", "32x32",
                 "-o", out]) == 0
    assert "rendered SingleTexture on" in capsys.readouterr().out


def test_the_sheet_draws_the_figure_under_each_picture():
    picture = np.zeros((20, 20, 4), np.uint8)
    cells = [Cell("a.fx", "geforce2", "T", image=picture)]
    plain = compose(cells, ["a.fx"], ["geforce2"], (20, 20))
    figured = compose(cells, ["a.fx"], ["geforce2"], (20, 20),
                      {("a.fx", "geforce2"): {"ssim": 0.5, "psnr": 12.0, "best": "B"}})
    assert figured.height == plain.height + 14          # one more label line
    line = np.asarray(figured)[14 + 20 + 14:, 120:140]  # the figure's line, under the name
    assert line.max() > 100                              # drawn in ink


def test_rows_with_figures_read_back_load_nothing_heavy(tmp_path):
    """The second `matrix --fidelity` reads its rows and the named files' digests only: no
    effect, card, NumPy or PyYAML is loaded, and it prints what the first printed."""
    from tests.cli.test_matrix_store import _command
    args = ("matrix", "fxfiles/phong.fx", "fxfiles/wood.fx", "--fidelity", "-p", "geforce2",
            "-p", "radeon9700")
    made = _command(tmp_path, *args)
    read = _command(tmp_path, *args)
    assert made.returncode == read.returncode == 0, made.stderr
    assert made.stdout == read.stdout and "SSIM" in made.stdout
    assert read.stderr.splitlines()[-1] == "LOADED"
