"""Language errors are errors, card limits are reasons (issue 30): a technique whose HLSL fxc
refuses for every target keeps its reason, marked (`Reason.error`), and a selection that fell
past it answers with that located error; `strict` loads fail on one in any technique."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.base.errors import EffectError
from effects.d3d9.caps import load_profile
from effects.validate.technique import validate_technique
from effects.validate.select import language_error, select
from effects.validate.verdicts import language_errors


R300 = load_profile("radeon9700")     # ps_2_0
GF2 = load_profile("geforce2")        # no pixel shaders: a ps_2_0 technique is never compiled

def selection(fx, card, policy="first"):
    """The choice and the language error it fell past (Selection.passed_over)."""
    made = select(fx, card, policy)
    return made.chosen, made.passed_over


# A language error of one technique only: its `compile` state's argument (an error in a
# function body fails every compile of the file, as fxc type-checked the whole file:
# tests/shaders/hlsl/test_hlsl_unit_check.py)
FUNCTIONS = """float4 Tint = {1, 0.5, 0.25, 1};
float4 Tinted(float2 uv : TEXCOORD0, uniform float4 k) : COLOR { return Tint * k; }
float4 Fine(float2 uv : TEXCOORD0) : COLOR { return Tint; }
"""
SHADER = "technique Shader < int Quality = 9; float Cost = 4.0; > " \
         "{ pass P0 { PixelShader = compile ps_2_0 Tinted(fooo); } }\n"
GOOD = "technique Good < int Quality = 5; float Cost = 2.0; > " \
       "{ pass P0 { PixelShader = compile ps_2_0 Fine(); } }\n"
FALLBACK = "technique Fallback < int Quality = 1; float Cost = 1.0; > " \
           "{ pass P0 { Lighting = false; ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse; } }\n"
COLUMN = SHADER.index("compile") + 1        # an argument's error is located at its state
MESSAGE = "X3004: undeclared identifier 'fooo'"


def where(text: str) -> tuple[int, int]:
    """(line, column) of the error in the effect `text`: SHADER's `compile`."""
    return text.splitlines().index(SHADER.rstrip("\n")) + 1, COLUMN


def same(error: EffectError, text: str) -> bool:
    """Whether `error` is the argument's X3004, located in `text`."""
    return error.message == MESSAGE and error.language and \
        (error.location.line, error.location.column) == where(text)


def load(*techniques: str, **options) -> effects.Effect:
    return effects.load_effect(FUNCTIONS + "".join(techniques), **options)


def text_of(*techniques: str) -> str:
    return FUNCTIONS + "".join(techniques)


def test_the_reason_keeps_the_language_error_and_reads_as_before():
    fx = load(SHADER, FALLBACK)
    v = validate_technique(fx, fx.techniques[0], R300)
    [reason] = v.reasons
    line = where(text_of(SHADER, FALLBACK))[0]
    assert str(reason) == f"pass P0 (line {line}): X3004: undeclared identifier 'fooo'"
    assert reason.language and same(reason.error, text_of(SHADER, FALLBACK))
    assert language_error(v) is reason.error
    # a card that refuses the version first never compiles it: its reason is the card's
    on_gf2 = validate_technique(fx, fx.techniques[0], GF2)
    assert [r.language for r in on_gf2.reasons] == [False]
    assert language_error(on_gf2) is None


def test_a_target_refusal_is_a_plain_reason():
    # (a run-time index into numbers is a select chain now; a sampler array's is still X3512)
    fx = effects.load_effect("""sampler S[2];
float4 PS(float2 uv : TEXCOORD0) : COLOR { return tex2D(S[uv.x * 2], uv); }
technique T { pass P0 { PixelShader = compile ps_2_0 PS(); } }
""")
    v = validate_technique(fx, fx.techniques[0], R300)
    assert [r.message.split(":")[0] for r in v.reasons] == ["X3512"]
    assert language_error(v) is None
    assert language_errors(fx) == []


def test_the_selection_that_fell_past_a_language_error_answers_with_it():
    fx = load(SHADER, GOOD, FALLBACK)
    chosen, error = selection(fx, R300)
    assert chosen.technique.name == "Good"
    assert same(error, text_of(SHADER, GOOD, FALLBACK))
    # the same on the GeForce2: it chooses the fallback, but it never compiled the ps_2_0
    chosen, error = selection(fx, GF2)
    assert chosen.technique.name == "Fallback" and error is None


def test_a_language_error_after_the_choice_changes_nothing():
    fx = load(GOOD, SHADER, FALLBACK)
    chosen, error = selection(fx, R300)
    assert chosen.technique.name == "Good" and error is None


def test_no_valid_technique_after_a_language_error_is_that_error():
    fx = load(SHADER)
    chosen, error = selection(fx, R300)
    assert chosen is None and same(error, text_of(SHADER))


@pytest.mark.parametrize("policy, choice, fell_past", [
    ("first", "Good", False),       # Good comes first in the file
    ("quality", "Good", True),      # Shader's Quality 9 would have beaten Good's 5
    ("cost", "Fallback", False),    # Shader's Cost 4 comes after Fallback's 1
    ("quality,max-cost=3", "Good", False),   # the policy refuses Shader's cost in any case
])
def test_the_policy_says_what_would_have_been_chosen(policy, choice, fell_past):
    fx = load(GOOD, SHADER, FALLBACK)
    results = [validate_technique(fx, t, R300) for t in fx.techniques]
    chosen, error = selection(fx, R300, policy)
    assert chosen.technique.name == choice
    assert (error is not None) is fell_past
    made = select(fx, R300, policy, validations=results)
    assert made.chosen is chosen or made.chosen.technique is chosen.technique
    assert (made.passed_over is not None) is fell_past


def test_language_errors_lists_every_shader_of_the_effect_in_file_order():
    kept = "PixelShader Kept = compile ps_2_0 Tinted(barr);\n"
    text = FUNCTIONS + kept + GOOD + SHADER + FALLBACK
    fx = effects.load_effect(text)
    line, column = where(text)
    assert [str(e) for e in language_errors(fx)] == [
        f"<string>:4:{kept.index('compile') + 1}: error: X3004: undeclared identifier 'barr'",
        f"<string>:{line}:{column}: error: X3004: undeclared identifier 'fooo'"]


def test_a_strict_load_fails_on_a_language_error_in_any_technique():
    text = FUNCTIONS + GOOD + FALLBACK + SHADER       # the broken technique is the last
    assert effects.load_effect(text).techniques[2].name == "Shader"
    with pytest.raises(EffectError) as info:
        effects.load_effect(text, strict=True)
    assert same(info.value, text)
    assert len(effects.load_effect(FUNCTIONS + GOOD, strict=True).techniques) == 1


def test_render_raises_the_error_the_selection_fell_past_and_draws_a_card_that_never_compiled_it():
    fx = load(SHADER, FALLBACK)
    scene = {"mesh": "quad", "size": [4, 4], "vertex": {"diffuse": [0, 1, 0, 1]}}
    for _ in range(2):   # the second answer comes from the runtime's memory of the selection
        with pytest.raises(EffectError) as info:
            effects.render(fx, R300, scene=scene)
        assert same(info.value, text_of(SHADER, FALLBACK))
    image = effects.render(fx, GF2, scene=scene)      # Fallback: the diffuse colour
    assert np.array_equal(image[2, 2], [0, 255, 0, 255])
    named = effects.render(fx, R300, technique="Fallback", scene=scene)
    assert np.array_equal(named[2, 2], [0, 255, 0, 255])
