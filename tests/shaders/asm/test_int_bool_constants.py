"""Integer and boolean shader constants the effect sets (VertexShaderConstantI/B,
PixelShaderConstantI/B, from literals and from int / bool parameters): loop counts from an i#,
static branches on a b#, drawn by both back ends against values worked out by hand, and
drawn again when the parameters change."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.d3d9.caps import load_profile

FX = """
int Steps = 2;
bool Flag = true;
int4 Lights = {3, 1, 1, 0};
technique T {
    pass P0 {
        VertexShaderConstantI[0] = <Steps>;
        VertexShaderConstantB[0] = <Flag>;
        VertexShaderConstantF[4] = float4(0.5, 0, 0, 0);
        PixelShaderConstantI[0] = <Lights>;
        PixelShaderConstantB[1] = true;
        PixelShaderConstantF[1] = float4(0.125, 0, 0, 0);
        PixelShaderConstantF[2] = float4(0.25, 0, 0, 0);
        PixelShaderConstantF[3] = float4(0.5, 0, 0, 0);
        VertexShader = asm {
            vs_3_0
            dcl_position v0
            dcl_position o0
            dcl_color o1
            def c0, 0, 0, 0, 1
            def c1, 0.125, 0, 0, 0
            mov o0, v0
            mov r0, c0
            rep i0
                add r0, r0, c1
            endrep
            if b0
                add r0.y, r0.y, c4.x
            endif
            mov o1, r0
        };
        PixelShader = asm {
            ps_3_0
            dcl_color0 v0
            def c5, 0.25, 0, 0, 0
            mov r0, v0
            loop aL, i0
                add r0.z, r0.z, c[aL].x
            endloop
            if b1
                add r0.x, r0.x, c5.x
            endif
            mov oC0, r0
        };
    }
}
"""
SIZE = (8, 8)


def expected(steps: int, flag: bool, lights: tuple[int, int, int, int]) -> np.ndarray:
    """rep i0 adds 1/8 to red `steps` times; if b0 adds 0.5 to green; the pixel loop adds
    c[aL].x for aL = y, y + z, ... (x times; c1..c3 = 1/8, 1/4, 1/2, others 0); b1 = true
    adds 0.25 to red."""
    c = {1: 0.125, 2: 0.25, 3: 0.5}
    count, start, step = lights[:3]
    blue = sum(c.get(start + k * step, 0.0) for k in range(count))
    return np.rint(np.array([0.125 * steps + 0.25, 0.5 if flag else 0.0, blue]) * 255)


@pytest.fixture(scope="module")
def effect():
    return effects.load_effect(FX)


@pytest.mark.parametrize("params, values", [
    ({}, (2, True, (3, 1, 1, 0))),
    ({"Steps": 6, "Flag": False, "Lights": [2, 2, 1, 0]}, (6, False, (2, 2, 1, 0))),
    ({"Steps": 0, "Lights": [3, 0, 1, 0]}, (0, True, (3, 0, 1, 0))),   # aL = 0 reads c0 = 0
])
@pytest.mark.parametrize("backend", ["numpy", "gl"])
def test_loop_counts_and_static_branches_come_from_the_pass(effect, backend, params, values):
    image = effects.render(effect, load_profile("geforce6800"), backend=backend,
                           scene={"mesh": "quad"}, size=SIZE, params=params)
    want = expected(*values)
    assert np.abs(image[..., :3].astype(int) - want).max() <= 1, (image[0, 0], want)


def test_the_values_are_those_of_the_hand_computation():
    # the defaults: red 2/8 + 1/4 = 0.5, green 0.5, blue c1 + c2 + c3 = 7/8
    np.testing.assert_array_equal(expected(2, True, (3, 1, 1, 0)), [128, 128, 223])
    np.testing.assert_array_equal(expected(6, False, (2, 2, 1, 0)), [255, 0, 191])


def test_a_shaders_own_defi_wins_over_the_pass(effect):
    text = FX.replace("dcl_color0 v0", "dcl_color0 v0\n            defi i0, 1, 3, 0, 0")
    image = effects.render(effects.load_effect(text), load_profile("geforce6800"),
                           scene={"mesh": "quad"}, size=SIZE)
    assert abs(int(image[0, 0, 2]) - 128) <= 1      # one iteration, aL = 3: c3 = 0.5


def test_an_app_set_count_past_the_iteration_limit_is_a_located_reason():
    text = FX.replace("rep i0\n", "rep i0\nrep i0\nrep i0\n").replace(
        "endrep\n", "endrep\nendrep\nendrep\n", 1)
    effect = effects.load_effect(text)
    effect.parameter("Steps").value = 255
    validation = effect.validate("T", load_profile("geforce6800"))
    assert not validation.ok
    line = 1 + next(k for k, t in enumerate(text.split("\n")) if "rep i0" in t) + 2
    assert [str(r) for r in validation.reasons] == [
        f"pass P0 (line {line}): rep (nested 3 deep) has 16,581,375 iterations; the limit is "
        "65,536 (limit shader_loop_iterations: raise it with "
        "EFFECTS_LIMIT_SHADER_LOOP_ITERATIONS=N or "
        "effects.base.limits.set_limit('shader_loop_iterations', N))"]
    effect.parameter("Steps").value = 2                       # 8 iterations: valid again
    assert effect.validate("T", load_profile("geforce6800")).ok
