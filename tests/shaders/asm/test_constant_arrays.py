"""Arrays of shaders picked by a parameter: `PixelShader PSArray[2] = { compile ..., ... };`
and `PixelShader = (PSArray[ShaderIndex]);` in the pass, as XNA-era effects select a shader
variant per draw (D3DX evaluates the index as a preshader when the pass begins). Lowering
draws the element the current values pick; validation judges that same element."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.host.runtime import Runtime

QUAD = {"mesh": "quad"}

ARRAYS = """
int ShaderIndex = 0;
float Pick = 0.75;
float4 VS(float4 p : POSITION) : POSITION { return p; }
float4 Red() : COLOR { return float4(1, 0, 0, 1); }
float4 Green() : COLOR { return float4(0, 1, 0, 1); }
float4 Blue() : COLOR { return float4(0, 0, 1, 1); }
VertexShader VSArray[2] = { compile vs_2_0 VS(), compile vs_3_0 VS() };
PixelShader PSArray[3] = { compile ps_2_0 Red(), compile ps_2_0 Green(), compile ps_3_0 Blue() };
technique ByIndex
{
    pass
    {
        VertexShader = (VSArray[ShaderIndex / 2]);
        PixelShader  = (PSArray[ShaderIndex]);
    }
}
technique ByExpression { pass { PixelShader = (PSArray[Pick * 2]); } }
"""


@pytest.mark.parametrize("backend", ["numpy", "gl"])
@pytest.mark.parametrize("index, colour", [(0, (255, 0, 0, 255)), (1, (0, 255, 0, 255))])
def test_the_index_picks_the_shader_drawn(backend, index, colour):
    image = effects.render(effects.load_effect(ARRAYS), "radeon9700", scene=QUAD, size=(8, 8),
                           backend=backend, technique="ByIndex",
                           params={"ShaderIndex": index})
    np.testing.assert_array_equal(image[4, 4], colour)


def test_an_expression_index_truncates_as_hlsl_converts():
    # Pick * 2 = 1.5 -> element 1 (green); 0.4 * 2 = 0.8 -> element 0 (red)
    effect = effects.load_effect(ARRAYS)
    image = effects.render(effect, "radeon9700", scene=QUAD, size=(8, 8),
                           technique="ByExpression")
    np.testing.assert_array_equal(image[4, 4], (0, 255, 0, 255))
    image = effects.render(effect, "radeon9700", scene=QUAD, size=(8, 8),
                           technique="ByExpression", params={"Pick": 0.4})
    np.testing.assert_array_equal(image[4, 4], (255, 0, 0, 255))


def test_setting_the_index_redraws_with_the_other_shader():
    runtime = Runtime(effects.load_effect(ARRAYS), "radeon9700", scene=QUAD, size=(8, 8))
    first = runtime.render("ByIndex").image
    runtime.set_value("ShaderIndex", 1)
    second = runtime.render("ByIndex").image
    np.testing.assert_array_equal(first[4, 4], (255, 0, 0, 255))
    np.testing.assert_array_equal(second[4, 4], (0, 255, 0, 255))


def test_validation_judges_the_element_the_values_pick():
    effect = effects.load_effect(ARRAYS)
    radeon = effects.load_profile("radeon9700")
    report = effect.validate("ByIndex", radeon)
    assert report.ok
    assert any("PSArray[0] at the parameters' current values is checked" in n
               for n in report.notes)
    # a card without pixel shaders refuses element 0 for what it is, not "unknown"
    tnt2 = effect.validate("ByIndex", effects.load_profile("tnt2"))
    assert not tnt2.ok
    assert "PixelShader is ps_2_0; the RIVA TNT2 has no pixel shader hardware" in \
        tnt2.reasons[0].message
    # index 2 picks the ps_3_0 element (and VSArray[1], vs_3_0): beyond the Radeon 9700
    effect.parameter("ShaderIndex").value = np.asarray(2)
    report = effect.validate("ByIndex", radeon)
    assert not report.ok
    assert any("ps_3_0" in r.message for r in report.reasons)


def test_an_index_past_the_array_is_a_located_error():
    effect = effects.load_effect(ARRAYS)
    line = ARRAYS[:ARRAYS.index("PixelShader  = (PSArray")].count("\n") + 1
    with pytest.raises(effects.EffectError) as err:
        effects.render(effect, "radeon9700", scene=QUAD, size=(8, 8), technique="ByIndex",
                       params={"ShaderIndex": 3})
    assert err.value.location.line == line
    assert "picks PSArray[3] at the parameters' current values; PSArray holds 3 shaders" in \
        err.value.message
    effect.parameter("ShaderIndex").value = np.asarray(3)
    report = effect.validate("ByIndex", effects.load_profile("radeon9700"))
    assert not report.ok and "PSArray holds 3 shaders" in report.reasons[0].message
