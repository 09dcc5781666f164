"""A pass lowered again because a parameter that feeds only a shader constant changed (a
viewer's slider, TIME each frame) reuses its shaders' IR (`lower.shader_ir`): the new pass has
the same vertex and fragment programs and new uniforms, and draws the new value."""
from __future__ import annotations

from tests.paths import ROOT

import numpy as np

import effects
from effects.host.runtime import Runtime
from effects.lower.passes import clear_cache


def test_a_constant_only_change_keeps_the_shader_ir_and_changes_the_uniforms():
    clear_cache()
    effect = effects.load_effect(str(ROOT / "fxfiles" / "phong.fx"))
    technique = effect.technique("PerPixelPhong_ps20")
    runtime = Runtime(effect, "radeon9700", size=(48, 48))
    first = runtime.lower(technique, 0)
    before = runtime.render(technique).image
    runtime.set_value("SpecularPower", 4.0)
    second = runtime.lower(technique, 0)
    assert second is not first                             # lowered again: a value it read changed
    assert second.fragment is first.fragment and second.vertex is first.vertex
    assert second.uniforms != first.uniforms
    after = runtime.render(technique).image
    # a broader highlight (exponent 4 instead of 24): more of the sphere is brighter
    assert after[..., :3].astype(int).sum() > before[..., :3].astype(int).sum()
    # and the same picture a runtime made with that value draws (nothing stale reused)
    fresh = Runtime(effect, "radeon9700", size=(48, 48), params={"SpecularPower": 4.0})
    assert np.array_equal(fresh.render(technique).image, after)
