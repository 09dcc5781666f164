"""The lowering options a caps profile implies (effects.d3d9.precision): one precision grid, read by
the fixed-function and the assembly lowerings, derived from the profile's data only."""
from __future__ import annotations

import dataclasses

import pytest

from effects.d3d9.caps import list_profiles, load_profile
from effects.d3d9.precision import FLOAT_OPTIONS, LoweringOptions, lowering_options
from effects.shaders.asm import assemble
from effects.shaders.asm.lower import ShaderContext, lower_pixel_shader
from effects.base.errors import Location
from effects.model import ShaderBlock


def test_geforce3_holds_ps_1_x_at_nine_signed_bits_in_plus_minus_one():
    options = lowering_options(load_profile("geforce3"))
    assert (options.stage_bits, options.ps1x_bits, options.ps1x_range) == (8, 8, 1.0)
    # sign + 8 fraction bits, no integer bits over [-1, 1]
    assert options.register_grid("ps_1_x") == (1.0, (9, True, 1.0))


def test_radeon8500_ps_1_4_grid_includes_the_integer_bits():
    options = lowering_options(load_profile("radeon8500"))
    # 12 fraction bits over [-8, 8]: 12 + 3 + 1 = 16 bits, scale 8
    assert options.register_grid("ps_1_4") == (8.0, (16, True, 8.0))


def test_float_models_have_no_grid():
    assert FLOAT_OPTIONS.register_grid("ps_1_x") == (None, None)
    assert lowering_options(load_profile("radeon9700")).register_grid("ps_1_4") == (None, None)


@pytest.mark.parametrize("name", ["refrast", "modern"])
def test_exact_float_pipelines_come_from_their_precision_entries(name):
    assert lowering_options(load_profile(name)) == FLOAT_OPTIONS


@pytest.mark.parametrize("name", sorted(list_profiles()))
def test_nothing_depends_on_a_profile_name(name):
    """The same caps under another name lower the same way."""
    profile = load_profile(name)
    renamed = dataclasses.replace(profile, name="some-other-card", display_name="Other")
    assert lowering_options(renamed) == lowering_options(profile)


def test_a_dx7_card_without_an_entry_holds_stages_at_8_bits_by_its_generation():
    card = load_profile("geforce2")
    profile = dataclasses.replace(card, caps={k: v for k, v in card.caps.items()
                                              if k != "Precision"})
    assert profile.precision("fixed_function") is None and profile.generation == "dx7"
    assert lowering_options(profile).stage_bits == 8
    assert lowering_options(dataclasses.replace(profile, generation="dx9")).stage_bits is None


def test_asm_lowering_quantises_on_the_options_grid():
    """The assembly lowering reads the grid from LoweringOptions, signedness included."""
    block = ShaderBlock("pixel", None, "ps.1.4\nadd r0, c0, c0", location=Location("t.fx", 1, 1))
    program = assemble(block)
    for signed in (True, False):
        options = LoweringOptions(ps14_bits=12, ps14_range=8.0, ps14_signed=signed)
        lowered = lower_pixel_shader(program, ShaderContext(options))
        q = [i for i in lowered.instrs if i.op == "quantize"]
        expected = options.register_grid("ps_1_4")[1]
        assert [(i.attr("bits"), i.attr("signed"), i.attr("scale")) for i in q] == [expected]
        assert expected[1] is signed

