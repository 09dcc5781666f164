"""Constructs fxc compiled in Wine's d3dx9 test shaders and effects (issues 30/35) that our
front end refused: each rendered on both back ends with values worked out by hand, and the
neighbouring form fxc refused refused here too, at its place."""
from __future__ import annotations

import numpy as np
import pytest

import effects
from tests.shaders.hlsl.test_hlsl_render import backend, effect_for, render  # noqa: F401

TOL = 1.5 / 255


# -- an unnamed struct type: `struct { ... } s = ...;` ---------------------------------------------

def test_an_unnamed_struct_declares_its_variables_at_the_effects_scope(backend):
    fx = effect_for("""
float4 PS() : COLOR
{
    return float4(s.f, s.i / 8.0, s_2[1].f, s_2[0].i / 8.0);
}""", params="struct {float f; int i;} s = {0.25f, 4}, s_2[2] = {{0.1, 1}, {0.75, 2}};")
    assert [p.name for p in fx.parameters] == ["s", "s_2"]
    img = render(fx, backend)
    assert np.allclose(img[3, 3], (0.25, 0.5, 0.75, 0.125), atol=TOL), img[3, 3]


def test_an_unnamed_struct_as_a_struct_member(backend):
    fx = effect_for("""
float4 PS() : COLOR
{
    return float4(ss.f, ss.s.f, ss.s.v.y, ss.f1);
}""", params="struct {float f; struct {float f; float3 v;} s; float f1;} "
              "ss = {0.125, 0.25, 0.3, 0.5, 0.7, 1.0};")
    img = render(fx, backend)
    assert np.allclose(img[3, 3], (0.125, 0.25, 0.5, 1.0), atol=TOL), img[3, 3]


def test_an_unnamed_struct_member_named_twice_is_fxcs_x3003_at_the_second():
    fx = effect_for("""
float4 PS() : COLOR { return s.f; }""", params="struct {\n  float f;\n  float f;\n} s;")
    with pytest.raises(effects.EffectError) as err:
        effects.render(fx, "radeon9700", technique="T", size=(4, 4))
    assert "X3003: redefinition of 'f'" in str(err.value)
    assert (err.value.line, err.value.column) == (3, 9), str(err.value)
