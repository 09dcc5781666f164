"""Validation judges expression-valued states (preshaders) as it judges literal values: at the
parameters' current values, each reason saying where its value came from; what waits on the
application is a note, and an expression that does not evaluate rejects the technique.

The hand values: D3DCOLORWRITEENABLE RED 1, GREEN 2, BLUE 4, ALPHA 8 (Mask | Blue with Mask 3
is 7, red green blue; with Mask 11 it is 15, every channel, which needs no caps bit);
D3DTTFF_COUNT2 2, D3DTTFF_PROJECTED 256; the modern profile's MaxPointSize is 256.
"""
from __future__ import annotations

import pytest

import effects


def validated(source: str, card: str, **values):
    fx = effects.load_effect(source)
    for name, value in values.items():
        fx.parameter(name).value = value
    return fx.validate("T", effects.load_profile(card))


COLOR_WRITE = "int Mask = 3;\ntechnique T { pass P { ColorWriteEnable = Mask | Blue; } }"


def test_a_write_mask_from_an_expression_needs_the_caps_bit_a_literal_needs():
    # the GeForce2 has no D3DPMISCCAPS_COLORWRITEENABLE: 7 is refused as the literal is
    literal = validated("technique T { pass P { ColorWriteEnable = Red | Green | Blue; } }", "geforce2")
    [plain] = literal.reasons
    [reason] = validated(COLOR_WRITE, "geforce2").reasons
    assert reason.message == (
        f"{plain.message}; ColorWriteEnable = Mask | Blue is Red | Green | Blue at the parameters' "
        "current values (Mask = 3)")
    assert (reason.location.line, reason.location.column) == (2, 24)     # at the state
    # Mask = 11: 11 | 4 = 15 writes every channel, which every card does
    assert validated(COLOR_WRITE, "geforce2", Mask=11).ok


def test_an_independent_write_mask_from_an_expression():
    # ColorWriteEnable1 = 7 differs from ColorWriteEnable (15): the GeForce3 has no
    # independent write masks; with Mask 11 the two agree
    src = "int Mask = 3;\ntechnique T { pass P { ColorWriteEnable1 = Mask | Blue; } }"
    [reason] = validated(src, "geforce3").reasons
    assert "D3DPMISCCAPS_INDEPENDENTWRITEMASKS" in reason.message
    assert reason.message.endswith("; ColorWriteEnable1 = Mask | Blue is Red | Green | Blue at the "
                                   "parameters' current values (Mask = 3)")
    assert validated(src, "geforce3", Mask=11).ok
    assert validated(src, "radeon9700").ok        # which has them


def test_a_projected_transform_flag_from_an_expression():
    # Count | Projected with Count 2 is 258: Count2 | Projected; the G400 has no
    # D3DPTEXTURECAPS_PROJECTED
    src = """int Count = 2; texture Tex;
technique T { pass P { Texture[0] = <Tex>; ColorOp[0] = SelectArg1; ColorArg1[0] = Texture;
                       TextureTransformFlags[0] = Count | Projected; } }"""
    [reason] = validated(src, "g400").reasons
    assert reason.message == (
        "TextureTransformFlags[0] = Projected needs D3DPTEXTURECAPS_PROJECTED; the Matrox G400 "
        "does not have it; TextureTransformFlags[0] = Count | Projected is Count2 | Projected at the "
        "parameters' current values (Count = 2)")
    assert reason.location.line == 3


POINTS = "float Size = 200;\ntechnique T { pass P { PointSize = Size * 2; } }"


def test_a_point_size_from_an_expression_above_max_point_size_is_a_warning():
    # 200 * 2 = 400 > 256: drawn at 256 (the driver clamps; nothing is rejected)
    validation = validated(POINTS, "modern")
    assert validation.ok
    [warning] = validation.warnings
    assert warning.message == (
        "PointSize = 400 is above the Modern GPU (DXVK/Wine)'s MaxPointSize 256; points are "
        "drawn at most 256 pixels wide; PointSize = Size * 2 is 400 at the parameters' current "
        "values (Size = 200)")
    assert validated(POINTS, "modern", Size=100.0).warnings == []        # 200 fits
    # the literal the same, without the clause
    [literal] = validated("technique T { pass P { PointSize = 400; } }", "modern").warnings
    assert literal.message == warning.message.split("; PointSize = Size")[0]
    # a profile that does not state MaxPointSize says nothing
    assert validated(POINTS, "radeon9700").warnings == []


def test_point_size_max_above_max_point_size():
    [warning] = validated("technique T { pass P { PointSize_Max = 512; } }", "modern").warnings
    assert warning.message == ("PointSize_Max = 512 is above the Modern GPU (DXVK/Wine)'s "
                               "MaxPointSize 256, which PointSize_Max must not exceed; sizes are "
                               "clamped to it")


def test_a_parameter_with_a_semantic_is_named_as_judged_at_its_current_value():
    src = "float Time : TIME = 200;\ntechnique T { pass P { PointSize = Time * 2; } }"
    [warning] = validated(src, "modern").warnings
    assert warning.message.endswith("(Time = 200 (semantic TIME: the application may set "
                                    "another value at render time))")


def test_a_parameter_without_a_value_leaves_the_state_to_render_time():
    validation = validated("float Size;\ntechnique T { pass P { PointSize = Size * 2; } }", "modern")
    assert validation.ok and validation.warnings == []
    assert validation.notes == ["pass P: PointSize = Size * 2 reads Size, which has no value: "
                                "not checked until the application sets it"]


def test_an_expression_that_does_not_evaluate_rejects_the_technique_at_it():
    validation = validated("float4 V = 1;\ntechnique T { pass P { PointSize = V * 2; } }", "radeon9700")
    [reason] = validation.reasons
    assert reason.message == "X3017: PointSize takes 1 value(s); 'V * 2' has 4"
    assert (reason.location.line, reason.location.column) == (2, 36)
    assert validation.notes == []


def test_the_pass_report_keeps_the_expression_for_lowering():
    # lowering evaluates again at render time: the report's state is the state as written
    validation = validated(COLOR_WRITE, "radeon9700")
    assert type(validation.pass_reports[0].state.get("ColorWriteEnable")).__name__ == "Expression"


@pytest.mark.parametrize("mask, ok", [(3, False), (11, True)])
def test_selection_follows_the_parameter(mask, ok):
    # find_valid_technique on the GeForce2: the write-mask technique, or the fallback
    src = f"""int Mask = {mask};
technique Masked {{ pass P {{ ColorWriteEnable = Mask | Blue; }} }}
technique Plain {{ pass P {{ }} }}"""
    fx = effects.load_effect(src)
    assert fx.find_valid_technique(effects.load_profile("geforce2")).name == ("Masked" if ok else "Plain")
