"""Writes to a uniform global, as fxc's compatibility mode compiled them (issue 30).

fxc refused `Gain = ...` in a shader (X3025, "global variables are implicitly constant, enable
compatibility mode to allow modification"); with /Gec (D3DXSHADER_ENABLE_BACKWARDS_COMPATIBILITY)
it compiled the write to a private copy of the global, first the uniform's value, and hosts
such as MikuMikuDance compiled so. Here such a write compiles with a located warning, which the
commands print; a strict load (`strict=True`, `--strict`) refuses it, as fxc without the flag.
A static global is the shader's own (no warning); a const one is no l-value (an error always).
"""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.base.errors import EffectError
from effects.cli import main as cli
from effects.program.backend import create_backend
from effects.shaders.hlsl import compile_shader

SIZE = (8, 8)
QUAD = {"mesh": "quad", "size": list(SIZE)}
GEC = """float Gain = 0.25;
void Boost(float k)
{
    Gain = Gain * k;
}
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float before = Gain;
    if (uv.x > 0.45)
        Boost(2);
    return float4(before, Gain, 0, 1);
}
technique T { pass P { PixelShader = compile ps_2_0 PS(); } }
"""
WARNING = ("X3025: global variables are implicitly constant, enable compatibility mode to allow "
           "modification: 'Gain' is written as fxc's /Gec compiled it, a private copy "
           "initialised from the uniform")


@pytest.fixture(scope="module", params=("numpy", "gl"))
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


@pytest.mark.parametrize("gain", [0.25, 0.4])
def test_the_write_goes_to_a_copy_of_the_uniform(backend, gain):
    fx = effects.load_effect(GEC)
    image = effects.render(fx, "radeon9700", technique="T", backend=backend, scene=QUAD,
                           params={"Gain": gain}).astype(np.float64) / 255.0
    for x in range(SIZE[0]):
        u = x / SIZE[0]        # the pixel's texture coordinate (test_hlsl_render.pixel_uv)
        boosted = gain * 2 if u > 0.45 else gain
        assert image[3, x, 0] == pytest.approx(gain, abs=1.5 / 255), x
        assert image[3, x, 1] == pytest.approx(boosted, abs=1.5 / 255), x


def test_the_write_is_a_located_warning_that_the_effect_carries():
    fx = effects.load_effect(GEC)
    shader = compile_shader(fx, "PS", "ps_2_0")
    assert [w.report() for w in shader.warnings] == [
        f"<string>:4:5: warning: {WARNING}\n    Gain = Gain * k;\n    ^"]
    assert fx.warnings == []
    effects.render(fx, "radeon9700", technique="T", backend="numpy", scene=QUAD)
    assert [w.message for w in fx.warnings] == [WARNING]      # told where load warnings are


def test_a_strict_load_refuses_it_as_fxc_without_the_flag():
    with pytest.raises(EffectError) as info:
        effects.load_effect(GEC, strict=True)
    err = info.value
    assert err.language is True
    assert err.report() == (
        "<string>:4:5: error: X3025: global variables are implicitly constant, enable "
        "compatibility mode to allow modification: 'Gain' cannot be written: a strict load "
        "compiles as fxc did without /Gec\n    Gain = Gain * k;\n    ^")


def test_the_commands_print_it_and_strict_fails(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("COLUMNS", "1000")
    path = tmp_path / "gec.fx"
    path.write_text(GEC)
    out = tmp_path / "out.png"
    assert cli.main(["render", str(path), "--profile", "radeon9700", "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert f"{path}:4:5: warning: {WARNING}" in err
    assert cli.main(["validate", str(path), "--profile", "radeon9700"]) == 0
    assert f"{path}:4:5: warning: {WARNING}" in capsys.readouterr().out
    assert cli.main(["render", str(path), "--profile", "radeon9700", "-o", str(out),
                     "--strict"]) == 2
    assert f"{path}:4:5: error: X3025: global variables are implicitly constant" in \
        capsys.readouterr().err


def test_a_static_global_is_the_shaders_own_and_a_const_one_no_lvalue():
    static = ("static float S = 0.25;\nfloat4 PS() : COLOR\n{\n    S = S * 2;\n    return S;\n}\n"
              "technique T { pass P { PixelShader = compile ps_2_0 PS(); } }\n")
    fx = effects.load_effect(static, strict=True)
    shader = compile_shader(fx, "PS", "ps_2_0")
    assert shader.warnings == [] and "0.5" in shader.text
    for kind in ("const float", "static const float"):
        fx = effects.load_effect(static.replace("static float", kind))
        with pytest.raises(EffectError) as info:
            compile_shader(fx, "PS", "ps_2_0")
        assert str(info.value) == "<string>:4:5: error: X3025: l-value specifies const object 'S'"
