"""Selection: D3DX's first-valid order, FindNextValidTechnique, and the named policies."""
from __future__ import annotations

import pytest

import effects
from effects import EffectError
from effects.d3d9.caps import load_profile
from effects.validate.select import (Policy, find_next_valid_technique, find_valid_technique, select,
                            technique_cost, technique_quality)

# Five techniques; on a TNT2 (no dot3, no pixel shaders) the ones marked * are valid.
#   Shader     ps_1_1                       Quality 9  Cost 4   1 pass
#   Dot3       DotProduct3                  Quality 5  Cost 2   1 pass
#   * TwoPass  two passes of Modulate       Quality 4  Cost 2   2 passes
#   * Cheap    one stage                    Quality 1  Cost 1   1 pass
#   * Plain    no annotations               -          -        1 pass
SOURCE = """
technique Shader < int Quality = 9; float Cost = 4.0; >
{ pass p0 { PixelShader = asm { ps_1_1
    mov r0, v0 }; } }
technique Dot3 < int Quality = 5; float Cost = 2.0; >
{ pass p0 { ColorOp[0] = DotProduct3; } }
technique TwoPass < int Quality = 4; float Cost = 2.0; >
{ pass a { ColorOp[0] = Modulate; } pass b { ColorOp[0] = Modulate; } }
technique Cheap < int Quality = 1; float Cost = 1.0; >
{ pass p0 { ColorOp[0] = SelectArg1; } }
technique Plain
{ pass p0 { ColorOp[0] = Modulate; } }
"""


@pytest.fixture(scope="module")
def effect():
    return effects.load_effect(SOURCE)


TNT2 = load_profile("tnt2")
GF2 = load_profile("geforce2")
GF3 = load_profile("geforce3")


def name(tech):
    return tech.name if tech is not None else None


def test_default_is_the_first_valid_technique_in_file_order(effect):
    assert name(find_valid_technique(effect, TNT2)) == "TwoPass"
    assert name(find_valid_technique(effect, GF2)) == "Dot3"
    assert name(find_valid_technique(effect, GF3)) == "Shader"
    assert name(effect.find_valid_technique(TNT2)) == "TwoPass"   # the Effect method


def test_find_next_valid_technique_walks_the_valid_ones_in_file_order(effect):
    seen, tech = [], None
    while True:
        tech = find_next_valid_technique(effect, TNT2, tech)
        if tech is None:
            break
        seen.append(tech.name)
    assert seen == ["TwoPass", "Cheap", "Plain"]
    assert name(effect.find_next_valid_technique(TNT2, "Cheap")) == "Plain"
    assert name(find_next_valid_technique(effect, GF2, "Shader")) == "Dot3"


def test_find_next_after_an_unknown_technique_is_a_located_error(effect):
    with pytest.raises(EffectError, match="no technique named 'Nope'"):
        find_next_valid_technique(effect, TNT2, "Nope")
    other = effects.load_effect("technique X { pass p { } }").techniques[0]
    with pytest.raises(EffectError, match="technique 'X' is not one of this effect's techniques"):
        find_next_valid_technique(effect, TNT2, other)


def test_quality_picks_the_highest_quality_valid_technique(effect):
    assert name(find_valid_technique(effect, TNT2, "quality")) == "TwoPass"   # 4 > 1 > 0
    assert name(find_valid_technique(effect, GF3, "quality")) == "Shader"


def test_cost_picks_the_cheapest_valid_technique_and_unannotated_ones_come_last(effect):
    assert name(find_valid_technique(effect, TNT2, "cost")) == "Cheap"       # 1 < 2 < unknown
    assert name(find_valid_technique(effect, GF2, "cost")) == "Cheap"        # Dot3 costs 2


def test_max_passes_refuses_longer_techniques(effect):
    assert name(find_valid_technique(effect, TNT2, "max-passes=1")) == "Cheap"
    assert name(find_valid_technique(effect, TNT2, "first,max-passes=2")) == "TwoPass"


def test_policies_combine(effect):
    assert name(find_valid_technique(effect, TNT2, "quality,max-passes=1")) == "Cheap"
    assert name(find_valid_technique(effect, GF3, "quality,max-cost=3")) == "Dot3"
    assert name(find_valid_technique(effect, GF3, "cost,max-cost=0.5")) is None
    assert name(find_valid_technique(effect, TNT2, Policy("quality", max_passes=1))) == "Cheap"


def test_no_valid_technique_is_an_answer_with_every_reason():
    e = effects.load_effect("technique A { pass p { ColorOp[0] = DotProduct3; } }\n"
                            "technique B { pass p { ColorOp[0] = BumpEnvMap; } }")
    assert find_valid_technique(e, TNT2) is None
    assert find_valid_technique(e, TNT2, "quality") is None
    ranked = select(e, TNT2, "quality").ranked
    assert [v.technique.name for v in ranked] == ["A", "B"]   # file order when none is usable
    assert [r.requirement for v in ranked for r in v.reasons] == [
        "D3DTEXOPCAPS_DOTPRODUCT3", "D3DTEXOPCAPS_BUMPENVMAP"]


def test_rank_puts_the_usable_ones_first_in_policy_order(effect):
    ranked = select(effect, TNT2, "quality").ranked
    assert [v.technique.name for v in ranked] == ["TwoPass", "Cheap", "Plain", "Shader", "Dot3"]
    assert [v.ok for v in ranked] == [True, True, True, False, False]


def test_annotation_readers():
    e = effects.load_effect('technique A < int Quality = 3; float Cost = 2.5; > { }\n'
                            'technique B < string Quality = "high"; > { }')
    a, b = e.techniques
    assert (technique_quality(a), technique_cost(a)) == (3.0, 2.5)
    assert (technique_quality(b), technique_cost(b)) == (0.0, None)


@pytest.mark.parametrize("text,policy", [
    ("first", Policy()), ("quality", Policy("quality")), ("COST", Policy("cost")),
    ("max-passes=2", Policy("first", 2)), (" quality , max-passes=1 ", Policy("quality", 1)),
    ("cost,max-cost=2.5", Policy("cost", None, 2.5)),
])
def test_policy_parse(text, policy):
    assert Policy.parse(text) == policy


@pytest.mark.parametrize("text,message", [
    ("best", "unknown selection policy 'best'"),
    ("max-passes=two", "bad policy 'max-passes=two': max-passes needs an integer, not 'two'"),
    ("max-cost=cheap", "bad policy 'max-cost=cheap': max-cost needs a number, not 'cheap'"),
    ("quality,cost", "'quality' and 'cost' are both orders"),
    ("", "empty selection policy"),
    ("max-passes=-1", "max-passes must be a finite number >= 0"),
])
def test_bad_policies_are_located_errors(text, message):
    with pytest.raises(EffectError) as info:
        Policy.parse(text)
    assert message in str(info.value)
    assert str(info.value).startswith("<policy>:1:1: error: ")


def test_policy_prints_back_to_its_text():
    assert str(Policy.parse("quality,max-passes=1,max-cost=3")) == "quality,max-passes=1,max-cost=3"


def test_select_answers_with_the_choice_every_validation_and_the_policys_reasons(effect):
    chosen = select(effect, TNT2, "quality,max-passes=1", lazy=False)
    assert name(chosen.technique) == "Cheap" and chosen.chosen.ok
    assert [v.technique.name for v in chosen.validations] == [
        "Shader", "Dot3", "TwoPass", "Cheap", "Plain"]                  # file order, all of them
    rejected = chosen.rejected()
    assert list(rejected) == ["Shader", "Dot3", "TwoPass"]
    assert rejected["TwoPass"] == ["policy quality,max-passes=1: the technique takes 2 passes; "
                                   "the policy allows at most 1"]
    assert rejected["Dot3"] == [str(r) for r in effect.validate("Dot3", TNT2).reasons]


def test_a_lazy_selection_stops_at_the_first_valid_technique_under_the_default_policy(effect):
    lazy = select(effect, TNT2)
    assert [v.technique.name for v in lazy.validations] == ["Shader", "Dot3", "TwoPass"]
    assert [t.name for t in lazy.pending] == ["Cheap", "Plain"]
    assert name(lazy.technique) == "TwoPass"
    assert select(effect, TNT2, lazy=False).pending == []
    assert select(effect, TNT2, "cost").pending == []     # a ranking policy validates all


def test_a_forced_technique_is_chosen_when_valid_whatever_the_policy(effect):
    plain = effect.technique("Plain")
    forced = select(effect, TNT2, "max-passes=0", forced=plain)
    assert name(forced.technique) == "Plain" and forced.forced_rejected is None
    # rejected: the policy chooses, and says why the forced one is not drawn
    shader = effect.technique("Shader")
    fallback = select(effect, TNT2, forced=shader)
    assert name(fallback.technique) == "TwoPass"
    assert fallback.forced_rejected.technique is shader and not fallback.forced_rejected.ok
    other = effects.load_effect("technique X { pass p { } }").techniques[0]
    with pytest.raises(EffectError, match="technique 'X' is not one of this effect's techniques"):
        select(effect, TNT2, forced=other)


def test_select_chooses_among_validations_already_made(effect):
    made = [effect.validate(t, GF2) for t in effect.techniques]
    chosen = select(effect, GF2, "cost", validations=made)
    assert chosen.validations == made and chosen.chosen is made[3]   # Cheap, by the given answers
