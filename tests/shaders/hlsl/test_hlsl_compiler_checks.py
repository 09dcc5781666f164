"""Every check of compile_shader (effects/shaders/hlsl/compiler.py) fed an input that fails it,
with the code, the wording and the place the user reads; and for the output rules, the inputs
just beside that pass (issue 31: a vertex shader without POSITION compiled for vs_1_1)."""
from __future__ import annotations

import pytest

import effects
from effects.base.errors import EffectError
from effects.shaders.hlsl import compile_shader


def compile_text(functions: str, entry: str, target: str, args: tuple[str, ...] = ()):
    fx = effects.load_effect(functions + "\ntechnique T { pass P { } }\n")
    return compile_shader(fx, entry, target, args)


def refusal(functions: str, entry: str, target: str, args: tuple[str, ...] = ()) -> EffectError:
    with pytest.raises(EffectError) as info:
        compile_text(functions, entry, target, args)
    return info.value


NO_POSITION = "float4 VS(float4 p : POSITION) : COLOR0 { return p; }"


@pytest.mark.parametrize("target", ["vs_1_1", "vs_2_0", "vs_3_0"])
def test_a_vertex_shader_without_position_is_refused_x4541(target):
    err = refusal(NO_POSITION, "VS", target)
    assert err.message == ("X4541: 'VS': vertex shader must minimally write all four "
                           "components of POSITION")
    assert (err.line, err.column) == (1, 1)


def test_position1_is_not_position0_x4541():
    # fxc's check counts the components of usage POSITION with index 0 only
    err = refusal("float4 VS(float4 p : POSITION) : POSITION1 { return p; }", "VS", "vs_2_0")
    assert err.message.startswith("X4541:")


@pytest.mark.parametrize("semantic", ["POSITION", "POSITION0", "SV_Position"])
def test_position_or_sv_position_satisfies_the_vertex_check(semantic):
    shader = compile_text(f"float4 VS(float4 p : POSITION) : {semantic} {{ return p; }}",
                          "VS", "vs_1_1")
    assert shader.text == "vs_1_1\ndcl_position v0\nmov oPos, v0\n"


def test_position_in_an_output_struct_satisfies_the_vertex_check():
    shader = compile_text("struct O { float4 c : COLOR0; float4 p : POSITION; };\n"
                          "O VS(float4 p : POSITION) { O o; o.c = p; o.p = p; return o; }",
                          "VS", "vs_3_0")
    assert "dcl_position o1" in shader.text


@pytest.mark.parametrize("target", ["ps_2_0", "ps_3_0"])
def test_a_pixel_shader_without_color0_is_refused_x4530(target):
    err = refusal("float4 PS() : COLOR1 { return 1; }", "PS", target)
    assert err.message == ("X4530: 'PS': pixel shader must minimally write all four "
                           "components of COLOR0")


@pytest.mark.parametrize("target", ["ps_1_1", "ps_1_4"])
def test_color1_is_no_ps_1_x_output_x4503(target):
    # ps_1_x writes its colour in r0 alone: COLOR1 is refused as it is bound, before the
    # COLOR0 check could run
    err = refusal("float4 PS() : COLOR1 { return 1; }", "PS", target)
    assert err.message == "X4503: invalid pixel shader output semantic 'COLOR1'"


def test_depth_alone_is_not_a_pixel_shader_x4530():
    err = refusal("float PS() : DEPTH { return 0.5; }", "PS", "ps_2_0")
    assert err.message.startswith("X4530:")


def test_entry_point_not_found_x3501():
    err = refusal("float4 PS() : COLOR { return 1; }", "Nope", "ps_2_0")
    assert err.message == "X3501: 'Nope': entrypoint not found"


def test_ps_1_0_is_not_an_hlsl_target_x3507():
    err = refusal("float4 PS() : COLOR { return 1; }", "PS", "ps_1_0")
    assert err.message == "X3507: fxc compiles HLSL for ps_1_1 and later, not ps_1_0"


def test_too_many_compile_arguments_x3013():
    err = refusal("float4 PS() : COLOR { return 1; }", "PS", "ps_2_0", ("1",))
    assert err.message == "X3013: 'PS': too many compile arguments (1)"


def test_a_function_that_never_returns_x3080():
    err = refusal("float4 PS() : COLOR { if (1) { } }", "PS", "ps_2_0")
    assert err.message == "X3080: 'PS': function must return a value"


def test_an_input_without_semantic_x4502():
    err = refusal("float4 PS(float4 c) : COLOR { return c; }", "PS", "ps_2_0")
    assert err.message == "X4502: input 'c' of the entry point has no semantic"


def test_a_non_numeric_input_x4502():
    err = refusal("float4 PS(sampler s : TEXCOORD0) : COLOR { return 1; }", "PS", "ps_2_0")
    assert err.message == "X4502: input 's' must be numeric, not 'sampler'"
    assert (err.line, err.column) == (1, 21)


def test_a_pixel_input_the_target_cannot_map_is_refused_when_read_x4502():
    err = refusal("float4 PS(float4 p : POSITION) : COLOR { return p; }", "PS", "ps_2_0")
    assert err.message == "X4502: invalid ps_2_0 input semantic 'POSITION'"
    # not read: fxc accepts it (XNA's shared vertex-output structs)
    shader = compile_text("float4 PS(float4 p : POSITION, float4 c : COLOR0) : COLOR "
                          "{ return c; }", "PS", "ps_2_0")
    assert "mov oC0, v0" in shader.text


def test_an_output_without_semantic_x4503():
    err = refusal("struct O { float4 c; }; O PS() { O o; o.c = 1; return o; }", "PS", "ps_2_0")
    assert err.message == "X4503: output of the entry point has no semantic"


def test_a_pixel_output_semantic_the_target_has_not_x4503():
    err = refusal("float4 PS() : TEXCOORD0 { return 1; }", "PS", "ps_2_0")
    assert err.message == "X4503: invalid pixel shader output semantic 'TEXCOORD0'"


def test_a_vertex_output_semantic_vs_1_1_has_not_x4503():
    err = refusal("struct O { float4 p : POSITION; float3 n : NORMAL; };\n"
                  "O VS(float4 p : POSITION) { O o; o.p = p; o.n = 1; return o; }", "VS", "vs_1_1")
    assert err.message == "X4503: invalid vertex shader output semantic 'NORMAL'"


def test_a_constant_no_register_can_hold():
    err = refusal("float4 PS() : COLOR { return float4(1e30 * 1e30, 0, 0, 1); }", "PS", "ps_2_0")
    assert err.message.startswith("a constant here folds to 1.0000000000000001e+60, which a "
                                  "ps_2_0 constant register cannot hold")
    assert (err.line, err.column) == (1, 42)
