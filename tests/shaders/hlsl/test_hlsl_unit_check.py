"""The whole file type-checked as fxc did (effects/shaders/hlsl/check.py, issue 30): a language
error is reported wherever it is written (a function nothing calls, a second entry point, a
branch a constant drops, a loop that runs no times, after a return, a global initialiser),
and only there where fxc reported it: what is legal in unused code, and what only a target
refuses, stays accepted."""
from __future__ import annotations

import subprocess
import sys

import pytest

import effects
from effects.base.errors import EffectError
from effects.shaders.hlsl import check, compile_shader
from tests.shaders.hlsl.invalid_corpus import UNIT, Row, ps, refusal, report, unused


@pytest.mark.parametrize("row", UNIT, ids=[r.name for r in UNIT])
def test_an_error_where_a_compile_never_looks_is_refused_with_fxc_code(row):
    assert refusal(row) == row.code


def test_the_unit_rows_are_of_size_and_all_refused():
    right, wrong = report(UNIT)
    assert len(UNIT) >= 60 and right == len(UNIT), wrong


# what fxc accepted in code a compile does not reach (each with its source)
VALID = [
    # DXC tools/clang/test/HLSL/string.hlsl: fxc-pass for string locals, parameters, members
    Row("a string local and parameter", "accepted",
        ps("    return uv.x;", "string Name = \"a\";\nstruct T { string field; float a; };\n"
           "float Use(string message, float f) { string s; s = Name; return f; }\n")),
    # refusals for a target only: fxc gave them for code it compiled for that target
    Row("a run-time index into a sampler array, unused", "accepted",
        unused("    int k = (int)uv.x;\n    return tex2D(Maps[k], uv);", "sampler Maps[2];\n")),
    Row("a loop of 5,000 iterations, unused", "accepted",
        unused("    float4 r = 0;\n    for (int i = 0; i < 5000; i++)\n        r += c * i;\n"
               "    return r;")),
    Row("tex2Dlod and ddx in a function a ps_2_0 entry does not call", "accepted",
        unused("    return tex2Dlod(Sam, float4(uv, 0, 0)) + ddx(uv.x);", "sampler Sam;\n")),
    Row("discard in a helper of a file with one vertex entry", "accepted",
        "float4 Unused(float4 c) { discard; return c; }\n"
        "float4 VS(float4 p : POSITION) : POSITION\n{\n    return p;\n}\n",
        entry="VS", target="vs_2_0"),
    # valid code in a dropped branch and after a loop that runs no times: still valid
    Row("valid code in dropped branches", "accepted",
        ps("    float r = uv.x;\n    if (false)\n        r = dot(uv, uv);\n"
           "    for (int i = 0; i < 0; i++)\n        r += sin(uv.y);\n    return r;")),
]


@pytest.mark.parametrize("row", VALID, ids=[r.name for r in VALID])
def test_what_fxc_accepted_where_a_compile_never_looks_is_accepted(row):
    assert refusal(row) == "accepted"


def test_the_error_is_located_in_the_unused_function_and_fails_every_compile():
    text = ("float4 Tint;\n"
            "float4 Helper(float2 uv)\n"
            "{\n"
            "    return Tint * brightnes;\n"
            "}\n" + ps("    return Tint * uv.x;") +
            "technique T { pass P { PixelShader = compile ps_2_0 PS(); } }\n")
    fx = effects.load_effect(text)
    for target in ("ps_2_0", "ps_3_0"):
        with pytest.raises(EffectError) as info:
            compile_shader(fx, "PS", target)
        err = info.value
        assert err.language
        assert (err.location.line, err.location.column) == (4, 19)
        assert err.message == "X3004: undeclared identifier 'brightnes'"


def test_the_file_is_checked_once_for_many_compiles(monkeypatch):
    calls = []
    real = check._first_error
    monkeypatch.setattr(check, "_first_error", lambda ctx: calls.append(1) or real(ctx))
    text = ps("    return uv.x * 0.123456;") + \
        "technique T { pass P { PixelShader = compile ps_2_0 PS(); } }\n"
    fx = effects.load_effect(text)
    for target in ("ps_2_0", "ps_2_a", "ps_3_0"):
        compile_shader(fx, "PS", target)
    assert calls == [1]


def test_the_first_error_in_the_file_is_the_one_reported():
    text = ps("    return uv.x;",
              "float A() { return first; }\nfloat B() { return float4(1, 2, 3); }\n")
    fx = effects.load_effect(text)
    assert check.check_unit(fx).message == "X3004: undeclared identifier 'first'"


def test_render_of_an_effect_with_a_typo_in_an_unused_function_prints_it_and_exits_1(tmp_path):
    path = tmp_path / "typo.fx"
    path.write_text("float4 Tint = { 1, 0.5, 0.25, 1 };\n"
                    "float4 Helper(float2 uv)\n{\n    return Tint * brightnes;\n}\n" +
                    ps("    return Tint * uv.x;") +
                    "technique Main { pass P { PixelShader = compile ps_2_0 PS(); } }\n"
                    "technique Fallback { pass P { ColorOp[0] = SelectArg1; "
                    "ColorArg1[0] = TFactor; } }\n")
    out = subprocess.run([sys.executable, "-m", "effects", "render", str(path), "-p",
                          "radeon9700", "-o", str(tmp_path / "out.png"), "--backend",
                          "reference"], capture_output=True, text=True)
    assert out.returncode == 1
    assert f"{path}:4:19: error: X3004: undeclared identifier 'brightnes'" in out.stderr
    assert not (tmp_path / "out.png").exists()


def test_a_strict_load_fails_on_an_unused_function_though_no_technique_compiles_hlsl():
    # D3DXCreateEffect compiled the file's HLSL whatever its techniques used
    text = ("float4 Helper(float2 uv) { return uv.x * nope; }\n"
            "technique T { pass P { ColorOp[0] = SelectArg1; ColorArg1[0] = TFactor; } }\n")
    assert effects.load_effect(text).techniques[0].name == "T"
    with pytest.raises(EffectError) as info:
        effects.load_effect(text, strict=True)
    assert info.value.message == "X3004: undeclared identifier 'nope'"
    assert (info.value.location.line, info.value.location.column) == (1, 42)
