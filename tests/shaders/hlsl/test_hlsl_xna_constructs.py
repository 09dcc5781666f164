"""Constructs found opening Kodu Game Lab's XNA effects (Microsoft, MIT licence): each one
reproduced by a small effect of our own. An array sized by a parenthesised macro
(`#define NUM_LUZ (10)`, `float4 LightPosition[NUM_LUZ]`), a function prototype before the
function it declares, a pass that picks its shaders from arrays by an int parameter
(`VertexShader = (ColorVS_FA[VSIndex])`) as `effects compile` lists it, and the game's
`WorldViewProjMatrix` / `EyeLocation` / `LightDirection0` names bound as XNA games set them."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.base.errors import ParseError
from effects.host.semantics import name_semantic
from effects.shaders.listing import pass_listing

# -- array sizes that are constant expressions ------------------------------------------------

SIZES = """#define N (2)
static const int K = 2;
float4 Lights[N * K - 1] = {{0.25, 0, 0, 0}, {0, 0.5, 0, 0}, {0, 0, 0.75, 0}};
float Weights[(N + 1) * 2 % 4];
float Ten[(10)];
float Seven[7 / 2 * 2 + 1];
"""


def test_array_sizes_are_constant_integer_expressions():
    effect = effects.load_effect(SIZES)
    sizes = {p.name: p.array for p in effect.parameters}
    # N * K - 1 = 3; (2 + 1) * 2 % 4 = 2; (10); 7 / 2 is 3 in integer division, * 2 + 1 = 7
    assert sizes == {"K": (), "Lights": (3,), "Weights": (2,), "Ten": (10,), "Seven": (7,)}


@pytest.mark.parametrize("source, where, message", [
    ("float a[(2 - 3)];", "1:9", "array size -1 is negative"),
    ("float a[4 / (1 - 1)];", "1:9", "array size divides by zero"),
    ("float a[(70000)];", "1:9", "array size 70000 is too large"),
    ("float a[max(1, 2)];", "1:9", "array size 'max(1, 2)' is not a constant integer expression"),
    ("float a[2 | 1];", "1:9", "array size '2 | 1' is not a constant integer expression"),
    ("float a[(M)];", "1:10", "array size 'M' is not a constant integer declared before"),
    ("float a[(2 - 2)];", "1:9", "array size must be at least 1"),
])
def test_a_size_that_is_not_a_constant_is_a_located_error(source, where, message):
    with pytest.raises(ParseError) as err:
        effects.load_effect(source)
    assert str(err.value).startswith(f"<string>:{where}: error: {message}")


# -- a function prototype ---------------------------------------------------------------------

PROTOTYPE = SIZES + """float4 Sum(int n);
float4 PS() : COLOR
{
    float4 local[N];
    local[0] = Lights[0];
    local[1] = Lights[2];
    return Sum(0) + local[0] + local[1];
}
float4 Sum(int n) { return Lights[1] + n; }
technique T { pass P { PixelShader = compile ps_2_0 PS(); } }
"""


@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_a_prototype_lets_a_function_call_one_defined_below(backend):
    effect = effects.load_effect(PROTOTYPE)
    assert [f.name for f in effect.functions] == ["PS", "Sum"]   # the prototype adds nothing
    image = effects.render(effect, "radeon9700", scene={"mesh": "quad"}, size=(4, 4),
                           backend=backend)
    # Lights[1] + Lights[0] + Lights[2] = (0.25, 0.5, 0.75, 0)
    np.testing.assert_allclose(image[2, 2], (64, 128, 191, 0), atol=1)


def test_a_prototype_keeps_its_semantic_and_a_missing_semicolon_is_located():
    effects.load_effect("float4 PS(float2 t : TEXCOORD0) : COLOR0;")
    with pytest.raises(ParseError) as err:
        effects.load_effect("float4 PS(float2 t : TEXCOORD0) : COLOR0\nfloat x;")
    assert str(err.value).startswith("<string>:2:1: error: expected a function body or ';' "
                                     "(a prototype) after the parameter list of 'PS', found "
                                     "'float'")


# -- shaders picked from arrays, as `effects compile` lists them -------------------------------

ARRAYS = """int VSIndex = 1;
int PSIndex;
float4 VS0(float4 p : POSITION) : POSITION { return p; }
float4 VS1(float4 p : POSITION) : POSITION { return p * 0.5; }
float4 PSA() : COLOR { return float4(1, 0, 0, 1); }
float4 PSB() : COLOR { return float4(0, 1, 0, 1); }
VertexShader VSArray[] = { compile vs_2_0 VS0(), compile vs_2_0 VS1(), };
PixelShader PSArray[] = { compile ps_2_0 PSA(), compile ps_2_0 PSB(), };
technique Picked { pass P0 { VertexShader = (VSArray[VSIndex]); PixelShader = (PSArray[PSIndex + 1]); } }
technique Literal { pass P0 { VertexShader = (VSArray[0]); PixelShader = <PSArray[1]>; } }
"""


def test_the_listing_of_a_shader_picked_by_an_expression_is_that_element():
    effect = effects.load_effect(ARRAYS)
    text = "\n".join(pass_listing(effect, effect.technique("Picked"), 0))
    assert "// VertexShader = (VSArray[VSIndex]): VSArray[1] at the parameters' current values\n" \
           "// VS1 compiled for vs_2_0" in text
    assert "// PixelShader = (PSArray[PSIndex + 1]): PSArray[1] at the parameters' current " \
           "values\n// PSB compiled for ps_2_0" in text
    assert "no shader" not in text
    literal = "\n".join(pass_listing(effect, effect.technique("Literal"), 0))
    assert "// VS0 compiled for vs_2_0" in literal and "// PSB compiled for ps_2_0" in literal


def test_an_index_past_the_array_in_the_listing_is_the_located_error():
    effect = effects.load_effect(ARRAYS.replace("int VSIndex = 1;", "int VSIndex = 2;"))
    with pytest.raises(effects.EffectError) as err:
        pass_listing(effect, effect.technique("Picked"), 0)
    assert str(err.value).startswith("<string>:9:45: error: '(VSArray[VSIndex])' picks "
                                     "VSArray[2] at the parameters' current values; VSArray "
                                     "holds 2 shaders")


def test_effects_compile_lists_the_picked_shaders(tmp_path, capsys):
    from effects.cli.main import main
    path = tmp_path / "arrays.fx"
    path.write_text(ARRAYS)
    assert main(["compile", str(path), "--technique", "Picked"]) == 0
    out = capsys.readouterr().out
    assert "// VS1 compiled for vs_2_0" in out and "// PSB compiled for ps_2_0" in out
    assert "    def c0, 0.5, 0, 0, 0\n    dcl_position v0\n" in out
    assert "    mul oPos, v0, c0.x\n" in out     # VS1's p * 0.5, not VS0's mov


# -- the game's names ------------------------------------------------------------------------

@pytest.mark.parametrize("name, semantic", [
    ("WorldViewProjMatrix", "WORLDVIEWPROJECTION"), ("WorldMatrix", "WORLD"),
    ("viewMatrix", "VIEW"), ("ProjectionMatrix", "PROJECTION"), ("InvWorldMatrix", "WORLDINVERSE"),
    ("g_WorldMtx", "WORLD"), ("EyeLocation", "CAMERAPOSITION"),
    ("LightDirection0", "LIGHT0DIRECTION"), ("LightColor0", "LIGHT0COLOR"),
    ("LightPosition0", "LIGHT0POSITION"),
    ("Matrix", None), ("LightPositionMatrix", None), ("ColorMatrix", None), ("LightColor1", None)])
def test_matrix_and_light_zero_names(name, semantic):
    assert name_semantic(name) == semantic


KODU_NAMES = """float4x4 WorldViewProjMatrix;
float4 EyeLocation;
float4 VS(float4 p : POSITION, out float4 eye : TEXCOORD0) : POSITION
{
    eye = EyeLocation;
    return mul(p, WorldViewProjMatrix);
}
float4 PS(float4 eye : TEXCOORD0) : COLOR { return float4(0, 0, eye.z / 4, 1); }
technique T { pass P { VertexShader = compile vs_2_0 VS(); PixelShader = compile ps_2_0 PS(); } }
"""


def test_the_game_names_draw_the_sphere_where_the_camera_sees_it():
    effect = effects.load_effect(KODU_NAMES)
    image = effects.render(effect, "radeon9700", size=(32, 32))
    # the unit sphere from the default camera at (0, 0, 3): covered in the middle, clear at the
    # corner; the blue is the eye's z, 3 / 4
    assert tuple(image[16, 16]) == (0, 0, 191, 255)
    assert tuple(image[0, 0]) == (0, 0, 0, 0)   # the clear colour, 0x00000000


# -- an #include under another letter case ---------------------------------------------------

def test_an_include_in_another_letter_case_opens_with_a_located_warning(tmp_path):
    (tmp_path / "Shaders").mkdir()
    (tmp_path / "Shaders" / "skin.fx").write_text("float4 Tint = {0.25, 0.5, 0.75, 1};\n")
    main = tmp_path / "main.fx"
    main.write_text('// Kodu: #include "Skin.fx" of skin.fx, fxc on Windows\n'
                    '#include "shaders/Skin.fx"\n'
                    "float4 PS() : COLOR { return Tint; }\n"
                    "technique T { pass P { PixelShader = compile ps_2_0 PS(); } }\n")
    effect = effects.load_effect(str(main))
    assert effect.parameter("Tint").value.tolist() == [0.25, 0.5, 0.75, 1]
    warnings = [str(w).splitlines()[0] for w in effect.warnings]
    shown = "Shaders/skin.fx".replace("/", __import__("os").sep)
    assert warnings == [f"{main}:2:10: warning: #include \"shaders/Skin.fx\" opens '{shown}': "
                        "the names differ in letter case (Windows file names do not)"]
    image = effects.render(effect, "radeon9700", scene={"mesh": "quad"}, size=(4, 4))
    np.testing.assert_allclose(image[2, 2], (64, 128, 191, 255), atol=1)


def test_an_include_matching_two_names_in_other_cases_is_not_guessed(tmp_path):
    (tmp_path / "skin.fx").write_text("float a;\n")
    (tmp_path / "SKIN.fx").write_text("float b;\n")
    main = tmp_path / "main.fx"
    main.write_text('#include "Skin.fx"\n')
    with pytest.raises(effects.EffectError) as err:
        effects.load_effect(str(main))
    assert str(err.value).startswith(f"{main}:1:10: error: cannot open include file 'Skin.fx'")


def test_an_include_in_another_case_stays_inside_the_include_root(tmp_path):
    (tmp_path / "Outside.fx").write_text("float a;\n")
    (tmp_path / "root").mkdir()
    main = tmp_path / "root" / "main.fx"
    main.write_text('#include "../outside.fx"\n')
    with pytest.raises(effects.EffectError) as err:
        effects.load_effect(str(main), include_root=str(tmp_path / "root"))
    assert "escapes the include root" in str(err.value)


# -- effects doctor: what the technique reads ---------------------------------------------------

DOCTOR = """float Weights[4];
float2 PixelSize;
float4 UIColour;             // a game's other parameters, read by other techniques
int PSIndex;
texture Source;
sampler S = sampler_state { Texture = <Source>; };
float4 Blur(float2 uv : TEXCOORD0) : COLOR
{
    float4 c = 0;
    for (int i = 0; i < 4; i++)
        c += Weights[i] * tex2D(S, uv + float2(i, 0) * PixelSize);
    return c;
}
float4 Flat() : COLOR { return UIColour; }
PixelShader PS[] = { compile ps_2_0 Blur(), compile ps_2_0 Flat() };
technique Filter { pass P { PixelShader = (PS[PSIndex]); } }
"""


def test_doctor_lists_what_the_technique_reads_arrays_included(tmp_path, capsys):
    from effects.cli.main import main
    path = tmp_path / "doctor.fx"
    path.write_text(DOCTOR)
    assert main(["doctor", str(path), "-p", "radeon9700"]) == 0
    out = capsys.readouterr().out
    # PSIndex (read by the pass's index) picks Blur: Weights and PixelSize read 0; UIColour
    # is read only by Flat, which PSIndex = 0 does not pick
    assert ("  set by nothing (they read 0):\n"
            f"    Weights (declared at {path}:1:7)\n"
            f"    PixelSize (declared at {path}:2:8)\n"
            f"    PSIndex (declared at {path}:4:5)\n"
            "  set by nothing, but Filter does not read them: UIColour\n") in out
    assert main(["doctor", str(path), "-p", "radeon9700", "--set", "PSIndex=1"]) == 0
    out = capsys.readouterr().out
    assert ("  set by nothing (they read 0):\n"
            f"    UIColour (declared at {path}:3:8)\n"
            "  set by nothing, but Filter does not read them: Weights, PixelSize\n") in out


# -- a vs_2_0 on a DX8 card: valid in software vertex processing, and said ----------------------

VS20 = """float4 VS(float4 p : POSITION) : POSITION { return p; }
technique VertexOnly { pass P { VertexShader = compile vs_2_0 VS(); } }
"""


@pytest.mark.parametrize("card, why", [
    ("geforce3", "above the GeForce3's vs_1_1"),
    ("gma900", "and the Intel GMA 900 has no vertex shader hardware")])
def test_a_vertex_shader_above_the_hardware_notes_software_processing(card, why):
    v = effects.load_effect(VS20).validate("VertexOnly", effects.load_profile(card))
    assert v.ok and v.pass_reports[0].software_vertex_processing
    assert v.notes == [f"pass P: VertexShader is vs_2_0, {why}: it runs in software vertex "
                       "processing (a device created with D3DCREATE_SOFTWARE_VERTEXPROCESSING or "
                       "D3DCREATE_MIXED_VERTEXPROCESSING)"]
    # on the Radeon 9700 it runs in hardware: no note
    assert effects.load_effect(VS20).validate("VertexOnly", effects.load_profile("radeon9700")).notes == []
