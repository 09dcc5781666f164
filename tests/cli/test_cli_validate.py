"""`effects validate`, `effects matrix`, `effects profiles`: output and exit codes
(docs/design.md: 0 ok, 1 invalid or not renderable, 2 bad input or usage)."""
from __future__ import annotations

from tests.paths import ROOT

import json
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import effects
from effects.d3d9 import caps
from effects.cli import main as cli
from effects.d3d9.caps import list_profiles, load_profile
from effects.cli.report import matrix

PHONG = str(ROOT / "fxfiles" / "phong.fx")
SPECULAR_BUMP = str(ROOT / "fxfiles" / "specular_bump.fx")
WOOD = str(ROOT / "fxfiles" / "wood.fx")


@pytest.fixture(autouse=True)
def wide_console(monkeypatch):
    # rich sizes tables to COLUMNS when output is not a terminal: wide enough for one-line cells
    monkeypatch.setenv("COLUMNS", "1000")


def version_line(path: str, pass_name: str, version: str = "ps.1.1") -> int:
    """The line (1-based) where the pixel shader of `pass_name` writes its version."""
    lines = Path(path).read_text().splitlines()
    start = next(i for i, line in enumerate(lines) if f"pass {pass_name}" in line)
    return next(i + 1 for i in range(start, len(lines))
                if version in lines[i] or version.replace(".", "_") in lines[i])


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def write(tmp_path: Path, name: str, text: str) -> str:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return str(path)


# --- validate ------------------------------------------------------------------------------------

def test_validate_prints_techniques_by_cards_with_pass_counts_and_first_reasons(capsys):
    code, out, err = run(capsys, "validate", PHONG, "--profile", "tnt2", "--profile", "geforce3")
    assert code == 0 and err == ""
    lines = out.splitlines()
    header = next(line for line in lines if "technique" in line)
    assert header.index("tnt2") < header.index("geforce3")
    ps11 = next(line for line in lines if "PerPixelPhong_ps11" in line)
    diffuse = version_line(PHONG, "Diffuse")
    assert f"✗ pass Diffuse (line {diffuse}): PixelShader is ps_1_1; the RIVA TNT2 has no pixel shader hardware" in ps11
    assert "✓ 2 passes" in ps11
    single = next(line for line in lines if "SingleTexture" in line and "selected" not in line)
    assert single.count("✓ 1 pass") == 2
    selected = next(line for line in lines if "selected" in line)
    assert [cell.strip() for cell in selected.split("│")[1:-1]] == [
        "selected", "SingleTexture", "PerPixelPhong_ps11"]
    # only the first reason of each cell without --why
    assert f"(line {version_line(PHONG, 'Specular')})" not in out


def test_validate_why_lists_every_reason_warning_and_note(capsys):
    code, out, _ = run(capsys, "validate", PHONG, "--profile", "tnt2", "--why")
    assert code == 0
    assert "tnt2 (RIVA TNT2, dx6)" in out
    for name in ("Diffuse", "Specular"):
        line = version_line(PHONG, name)
        assert (f"      pass {name} (line {line}): PixelShader is ps_1_1; the RIVA TNT2 has no "
                "pixel shader hardware") in out
    assert "  ✓ SingleTexture: 1 pass" in out
    code, out, _ = run(capsys, "validate", str(ROOT / "fxfiles" / "wood.fx"), "-p", "geforce3", "--why")
    assert code == 1
    assert "PixelShader is ps_2_0; the GeForce3 runs pixel shaders up to ps_1_1" in out


def test_a_pass_from_an_include_is_located_in_the_included_file(capsys, tmp_path):
    # the technique's lines are the include's: a reason that gave only "line 5" would send
    # the reader to the wrong file (main.fx has four lines)
    include = write(tmp_path, "bump.fxh", """\
        // a technique kept in a header
        technique Bump
        {
            pass P0
            {
                ColorOp[0] = BumpEnvMap;
            }
            pass P1
            {
                PixelShader = asm { ps.1.1 tex t0 mov r0, t0 };
            }
        }
        """)
    path = write(tmp_path, "main.fx", """\
        #include "bump.fxh"
        technique Plain
        {
            pass P0 { ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse; }
        }
        """)
    code, out, _ = run(capsys, "validate", path, "-p", "tnt2", "--why")
    assert code == 0
    assert (f"pass P0 ({include}, line 6): ColorOp[0] = BumpEnvMap needs "
            "D3DTEXOPCAPS_BUMPENVMAP") in out
    code, out, _ = run(capsys, "matrix", path, "-p", "tnt2", "--json")
    assert json.loads(out)[path]["tnt2"]["rejected"]["Bump"][0].startswith(
        f"pass P0 ({include}, line 6): ")
    # the summary (no cards named) locates the header's shader in the header
    code, out, _ = run(capsys, "validate", path)
    assert f"asm ps_1_1 ({include}, line 10)" in out
    # a pass in the file itself keeps the short form
    code, out, _ = run(capsys, "validate", PHONG, "-p", "tnt2", "--why")
    assert f"pass Diffuse (line {version_line(PHONG, 'Diffuse')}): " in out
    code, out, _ = run(capsys, "validate", PHONG)
    assert "asm ps_2_0 (line " in out


@pytest.mark.parametrize("shader, label", [
    ("compile ps_2_a PS()", "ps_2_a"), ("compile ps_2_b PS()", "ps_2_b"),
    ("compile ps_3_0 PS()", "ps_3_0"), ("compile ps_2_0 PS()", "ps_2_0")])
def test_a_reason_names_the_shader_profile_as_written(capsys, tmp_path, shader, label):
    # ps_2_a and ps_2_b are version 2.0 with extended caps: the reason said "ps_2_0"
    path = write(tmp_path, "p.fx", f"""\
        sampler2D S;
        float4 PS(float2 uv : TEXCOORD0) : COLOR {{ return tex2D(S, uv); }}
        technique T {{ pass P {{ PixelShader = {shader}; }} }}
        """)
    code, out, _ = run(capsys, "validate", path, "-p", "geforce3", "--why")
    assert f"PixelShader is {label}; the GeForce3 runs pixel shaders up to ps_1_1" in out


def test_validate_exits_1_when_a_named_card_can_run_no_technique(capsys):
    code, out, _ = run(capsys, "validate", SPECULAR_BUMP, "--profile", "tnt2", "--profile", "radeon9700")
    assert code == 0
    code, out, _ = run(capsys, "validate", WOOD, "--profile", "tnt2", "--profile", "geforce3")
    assert code == 1
    selected = next(line for line in out.splitlines() if "selected" in line)
    assert "none" in selected


def test_validate_a_file_without_techniques(capsys, tmp_path):
    path = write(tmp_path, "empty.fx", "float4 Colour = {1, 0, 0, 1};\n")
    code, out, err = run(capsys, "validate", path, "--profile", "tnt2")
    assert code == 1
    assert out.strip() == f"{path}: the effect has no techniques, so no card can render it"


def test_validate_an_unknown_card_is_bad_input(capsys):
    code, out, err = run(capsys, "validate", PHONG, "--profile", "tnt3")
    assert code == 2 and out == ""
    assert err.startswith("tnt3:1:1: error: unknown profile 'tnt3'; did you mean 'tnt2'?")
    assert "Traceback" not in err


def test_validate_a_broken_profile_file_is_a_located_error(capsys, tmp_path):
    bad_bit = write(tmp_path, "bad_bit.yaml", """\
        name: broken
        generation: dx7
        TextureOpCaps: [MODULATE, DOT3]
        """)
    code, out, err = run(capsys, "validate", PHONG, "--profile", bad_bit)
    assert code == 2
    assert err.startswith(f"{bad_bit}:3:27: error: unknown TextureOpCaps bit 'DOT3' (no D3DTEXOPCAPS_DOT3)")
    syntax = write(tmp_path, "syntax.yaml", "name: broken\ngeneration: dx6\nMaxTextureBlendStages: [1\n")
    code, out, err = run(capsys, "validate", PHONG, "--profile", syntax)
    assert code == 2
    assert err.startswith(f"{syntax}:4:1: error: YAML syntax error")
    assert "Traceback" not in err


def test_validate_an_effect_with_a_syntax_error_is_bad_input(capsys, tmp_path):
    path = write(tmp_path, "bad.fx", "technique T\n{\n    pass p0 { ColorOp[0] = ; }\n}\n")
    code, out, err = run(capsys, "validate", path, "--profile", "tnt2")
    assert code == 2
    assert err.startswith(f"{path}:3:")


def test_validate_a_missing_file_is_bad_input(capsys, tmp_path):
    code, _, err = run(capsys, "validate", str(tmp_path / "nope.fx"), "--profile", "tnt2")
    assert code == 2 and "cannot read effect file" in err


# --- matrix --------------------------------------------------------------------------------------

def test_matrix_json_is_the_report_matrix_over_every_card(capsys):
    fx = sorted(str(p) for p in (ROOT / "fxfiles").glob("*.fx"))
    code, out, err = run(capsys, "matrix", *fx, "--json")
    assert code == 0 and err == ""
    got = json.loads(out)
    loaded = {path: effects.load_effect(path) for path in fx}
    assert got == matrix(loaded, [load_profile(n) for n in list_profiles()])
    assert list(got[fx[0]]) == list_profiles()


def test_matrix_named_cards_and_policy(capsys):
    code, out, _ = run(capsys, "matrix", PHONG, "-p", "geforce3", "-p", "tnt2", "--json",
                       "--policy", "max-passes=1")
    assert code == 0
    got = json.loads(out)[PHONG]
    assert list(got) == ["geforce3", "tnt2"]
    assert (got["geforce3"]["technique"], got["geforce3"]["passes"]) == ("Dot3_dx7", 1)
    assert (got["tnt2"]["technique"], got["tnt2"]["passes"]) == ("SingleTexture", 1)


def test_matrix_table_names_cards_and_effects(capsys):
    code, out, _ = run(capsys, "matrix", PHONG, WOOD, "-p", "tnt2", "-p", "radeon9700")
    assert code == 0
    tnt2 = next(line for line in out.splitlines() if "tnt2" in line)
    assert "SingleTexture (1)" in tnt2 and "none" in tnt2
    header = next(line for line in out.splitlines() if "card" in line)
    assert "phong" in header and "wood" in header


def test_matrix_into_a_pipe_is_one_line_per_card_with_whole_names(capsys, monkeypatch):
    # capsys is not a terminal: eleven effects do not fit 80 columns (rich's width there, or
    # the width of a terminal on stdin), and folded to them each card took nine lines of name
    # fragments; here each card's row reads like the JSON
    monkeypatch.setenv("COLUMNS", "80")
    fx = sorted(str(p) for p in (ROOT / "fxfiles").glob("*.fx"))
    code, out, _ = run(capsys, "matrix", *fx)
    assert code == 0
    _, text = run(capsys, "matrix", *fx, "--json")[:2]
    got = json.loads(text)
    lines = out.splitlines()
    assert len(lines) == 4 + len(list_profiles())   # top, header, rule, cards, bottom
    header = [cell.strip() for cell in lines[1].split("┃")[1:-1]]
    assert header == ["card", *(Path(f).stem for f in fx)]
    for card, line in zip(list_profiles(), lines[3:-1]):
        cells = [cell.strip() for cell in line.split("│")[1:-1]]
        assert cells[0] == card
        assert cells[1:] == [f"{got[f][card]['technique']} ({got[f][card]['passes']})"
                             if got[f][card]["technique"] else "none" for f in fx]


def test_matrix_bad_policy_is_bad_input(capsys):
    code, out, err = run(capsys, "matrix", PHONG, "--policy", "fastest")
    assert code == 2 and out == ""
    assert err.startswith("<policy>:1:1: error: unknown selection policy 'fastest'")


# --- profiles ------------------------------------------------------------------------------------

def test_profiles_lists_the_cards_by_generation_with_key_caps(capsys):
    # capsys is not a terminal: one card a line, its fields separated by tabs, the generation
    # a field (a terminal's table has a heading row a generation instead)
    code, out, err = run(capsys, "profiles")
    assert code == 0 and err == ""
    records = [line.split("\t") for line in out.splitlines()]
    assert [r[0] for r in records] == list_profiles()   # by generation, then name
    gens = list(dict.fromkeys(r[1] for r in records))
    assert gens == list(caps.GENERATIONS)
    g400 = next(r for r in records if r[0] == "g400")
    assert g400 == ["g400", "dx6", "Matrox G400", "3/3", "EMBM", "-", "2048", "-", "sw"]
    r8500 = next(r for r in records if r[0] == "radeon8500")
    assert r8500 == ["radeon8500", "dx8.1", "Radeon 8500", "8/6", "EMBM dot3", "cube 3D",
                     "2048", "1.4", "1.1"]


def test_profiles_with_a_broken_bundled_profile_reports_it_located(capsys, tmp_path, monkeypatch):
    (tmp_path / "good.yaml").write_text((ROOT / "caps_profiles" / "tnt2.yaml").read_text())
    (tmp_path / "bad.yaml").write_text("name: bad\ngeneration: dx5\n")
    monkeypatch.setattr(caps, "PROFILE_DIR", tmp_path)
    caps.clear_cache()
    try:
        code, out, err = run(capsys, "profiles")
    finally:
        caps.clear_cache()
    assert code == 2
    assert err.startswith(f"{tmp_path / 'bad.yaml'}:2:13: error: generation 'dx5' is not one of")
    assert "Traceback" not in out + err


def test_the_module_entry_point_runs_as_a_subprocess():
    proc = subprocess.run([sys.executable, "-m", "effects", "matrix", PHONG, "-p", "tnt2", "--json"],
                          capture_output=True, text=True, cwd=ROOT, timeout=60)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)[PHONG]["tnt2"]["technique"] == "SingleTexture"
