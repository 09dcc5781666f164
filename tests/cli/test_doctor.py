"""`effects doctor`: what an effect needs from a host that it does not get."""
from __future__ import annotations

from tests.paths import ROOT

from effects.cli.main import main

NEEDY = """float4x4 Wvp : WorldViewProjection;
float4 Tint;
float Gloss < float UIMin = 0; float UIMax = 2; >;
texture Base;
texture Map : RenderColorTarget;
sampler S = sampler_state { Texture = <Base>; };
technique T < string Script = "RenderPort=x; Pass=P;"; > {
    pass P { Sampler[0] = <S>; TextureFactor = 0xffffffff; }
}
"""


def test_doctor_names_unbound_parameters_stand_ins_and_unsupported_commands(tmp_path, capsys):
    path = tmp_path / "needy.fx"
    path.write_text(NEEDY)
    assert main(["doctor", str(path), "-p", "geforce2"]) == 0
    out = capsys.readouterr().out
    assert f"{path} on GeForce2 GTS:" in out
    assert "technique T (1 pass)" in out
    assert "Wvp <- semantic WORLDVIEWPROJECTION" in out
    assert "Gloss <- the middle of its UIMin..UIMax range" in out
    # the pass reads nothing of Tint: said apart from what the technique reads as 0
    assert "set by nothing (they read 0)" not in out
    assert "  set by nothing, but T does not read them: Tint\n" in out
    assert "Base: stand-in checker:8" in out
    assert f"{path}:4:9: warning: texture parameter Base: nothing supplies it" in out
    assert f"script commands not run:\n    {path}:7:22: RenderPort=x" in out
    assert "Map" not in out.split("textures the passes sample:")[1]   # not sampled


def test_doctor_of_a_complete_effect_says_nothing_is_missing(tmp_path, capsys):
    path = tmp_path / "ok.fx"
    path.write_text('float4x4 Wvp : WORLDVIEWPROJECTION;\ntechnique T { pass P { } }\n')
    assert main(["doctor", str(path), "--set", "Wvp=" + ",".join(["1"] * 16)]) == 0
    out = capsys.readouterr().out
    assert "Wvp <- --set / scene params" in out
    assert "nothing missing" in out


def test_doctor_on_bad_input_exits_2(tmp_path, capsys):
    path = tmp_path / "bad.fx"
    path.write_text("technique {")
    assert main(["doctor", str(path)]) == 2


def test_doctor_lists_the_file_defaults_kept_and_whose_value_is_missing(capsys):
    wood = ROOT / "fxfiles" / "wood.fx"
    assert main(["doctor", str(wood), "-p", "radeon9700"]) == 0
    out = capsys.readouterr().out
    # wood.yaml beside it binds the colours and the light; the file's own values stand for
    # the rest, shown as the file writes them
    assert "    L <- --set / scene params" in out
    assert "keep the file's default (nothing binds them):" in out
    assert "    ringscale = 10\n" in out and "    lightwood = 0.3, 0.12, 0.03\n" in out
    toon = ROOT / "tests" / "data" / "blank" / "toon_unset_light.fx"
    assert main(["doctor", str(toon)]) == 0
    out = capsys.readouterr().out
    assert "vLightDirection (declared at" in out and "a light the application placed" in out
    assert "    cBase = 1, 0.5, 0.2, 1\n" in out
