"""The HLSL typo case end to end (issue 30): a ps_2_0 technique with an undeclared identifier,
then a fixed-function fallback. Where the card would have drawn the broken technique, `render`,
`validate` and `matrix` print the located X3004 error (line, caret) and exit 1, instead of a
grey reason and a silent fallback; a card that never compiles it (no pixel shaders) draws the
fallback; `--strict` fails the load on it whatever the card, exit 2 as any load error."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import pytest

from tests.paths import ROOT
from effects.cli import main as cli

TYPO = """float4 Tint = {1, 0.5, 0.25, 1};

float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    return Tint * fooo;
}

technique Shader
{
    pass P0 { PixelShader = compile ps_2_0 PS(); }
}

technique Fallback
{
    pass P0 { Lighting = false; ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse; }
}
"""


@pytest.fixture(autouse=True)
def wide_console(monkeypatch):
    monkeypatch.setenv("COLUMNS", "1000")


@pytest.fixture
def typo(tmp_path) -> str:
    path = tmp_path / "typo.fx"
    path.write_text(TYPO)
    return str(path)


def report(path: str) -> str:
    """The error as the user reads it: written out here from the file's text."""
    line = TYPO.splitlines()[4]
    column = line.index("fooo") + 1
    return (f"{path}:5:{column}: error: X3004: undeclared identifier 'fooo'\n"
            f"{line}\n{' ' * (column - 1)}^\n")


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_render_prints_the_located_error_and_exits_1(capsys, typo, tmp_path):
    png = str(tmp_path / "out.png")
    code, out, err = run(capsys, "render", typo, "-p", "radeon9700", "-o", png)
    assert (code, out, err) == (1, "", report(typo))
    assert not os.path.exists(png)
    # the technique asked for by name: the same error
    code, out, err = run(capsys, "render", typo, "-p", "radeon9700", "-t", "Shader", "-o", png)
    assert (code, out, err) == (1, "", report(typo))


def test_a_card_that_never_compiles_it_draws_the_fallback(capsys, typo, tmp_path):
    png = str(tmp_path / "out.png")
    code, out, err = run(capsys, "render", typo, "-p", "geforce2", "-o", png)
    assert code == 0 and err == "" and out.startswith("rendered Fallback on GeForce2")


@pytest.mark.parametrize("command", [
    ("render", "-p", "geforce2", "-o", "OUT"),
    ("validate", "-p", "geforce2"),
    ("matrix", "-p", "geforce2"),
])
def test_strict_fails_the_load_whatever_the_card(capsys, typo, tmp_path, command):
    argv = [a if a != "OUT" else str(tmp_path / "out.png") for a in command]
    code, out, err = run(capsys, argv[0], typo, *argv[1:], "--strict")
    assert (code, out, err) == (2, "", report(typo))


def test_validate_marks_the_error_and_prints_it_located(capsys, typo):
    code, out, err = run(capsys, "validate", typo, "-p", "radeon9700", "-p", "geforce2")
    assert code == 1 and err == ""
    shader = next(line for line in out.splitlines() if line.startswith("│ Shader"))
    r300, gf2 = [cell.strip() for cell in shader.split("│")[2:4]]
    assert r300 == "✗ error pass P0 (line 5): X3004: undeclared identifier 'fooo' (below)"
    assert gf2.startswith("✗ pass P0 (line 10): PixelShader is ps_2_0")
    assert out.endswith("┘\n" + report(typo))
    # a card that never compiled it: no error to tell, and it runs the fallback
    code, out, err = run(capsys, "validate", typo, "-p", "geforce2")
    assert code == 0 and "fooo" not in out


def test_matrix_prints_the_error_once_and_exits_1(capsys, typo):
    code, out, err = run(capsys, "matrix", typo, "-p", "radeon9700", "-p", "refrast",
                         "-p", "geforce2")
    assert code == 1 and err == report(typo)
    assert [line.split()[1:3] for line in out.splitlines() if "Fallback" in line] == [
        ["radeon9700", "│"], ["refrast", "│"], ["geforce2", "│"]]


def test_matrix_json_says_it_in_the_cards_it_concerns(capsys, typo):
    code, out, err = run(capsys, "matrix", typo, "-p", "radeon9700", "-p", "geforce2", "--json")
    assert code == 1 and err == report(typo)
    row = json.loads(out)[typo]
    assert row["radeon9700"] == {
        "technique": "Fallback", "passes": 1,
        "rejected": {"Shader": ["pass P0 (line 5): X3004: undeclared identifier 'fooo'"]},
        "error": report(typo).rstrip("\n")}
    assert "error" not in row["geforce2"] and row["geforce2"]["technique"] == "Fallback"


def test_a_stored_matrix_row_keeps_the_error(tmp_path, typo):
    """Run twice in fresh processes: the second reads the row the first kept (matrix_store)."""
    then = time.time() - 10          # a file written in the last 2 s is not kept
    os.utime(typo, (then, then))
    runs = [subprocess.run([sys.executable, "-m", "effects", "matrix", typo, "-p", "radeon9700"],
                           cwd=str(ROOT), capture_output=True, text=True,
                           env={**os.environ, "EFFECTS_CACHE_DIR": str(tmp_path / "store")})
            for _ in range(2)]
    assert [r.returncode for r in runs] == [1, 1]
    assert runs[0].stderr == runs[1].stderr == report(typo)
    assert runs[0].stdout == runs[1].stdout
    assert any(f.endswith(".json") for f in os.listdir(tmp_path / "store"))
