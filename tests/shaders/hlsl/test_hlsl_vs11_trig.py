"""sin, cos and sincos in vs_1_1, which has no sincos instruction: the argument is reduced to
[-pi, pi] (mad, frc, mad) and a Taylor polynomial evaluated (intrinsics._series). Values
are checked against Python's math on both back ends, angles chosen across several turns."""
from __future__ import annotations

import math

import numpy as np
import pytest

from effects.base.errors import EffectError
from tests.shaders.hlsl.test_hlsl_render import backend, effect_for, fx_asm, pixel_uv, render  # noqa: F401

TOL = 2.5 / 255
PS = "float4 PS(float4 c : COLOR0) : COLOR { return c; }"


def trig_effect(body: str) -> object:
    return effect_for(f"""
float4 VS(float4 p : POSITION, float2 uv : TEXCOORD0, out float4 c : COLOR0) : POSITION
{{
{body}
    return p;
}}
{PS}""", vs="compile vs_1_1 VS()", params="float4 K;")


@pytest.mark.parametrize("angles", [(0.3, -1.2, 2.9, 0.0), (10.0, -7.5, 25.0, math.pi),
                                    (-31.0, 100.0, 4.0, -math.pi / 2)])
def test_sin_and_cos_of_uniforms_in_vs_1_1(backend, angles):
    fx = trig_effect("    c = float4(sin(K.xy), cos(K.zw)) * 0.5 + 0.5;")
    text = fx_asm(fx, "VS", "vs_1_1")
    assert "sincos" not in text and "frc" in text
    img = render(fx, backend, params={"K": ",".join(map(str, angles))})
    a, b, c, d = angles
    want = np.array([math.sin(a), math.sin(b), math.cos(c), math.cos(d)]) * 0.5 + 0.5
    for x, y in ((1, 1), (6, 5)):
        assert np.allclose(img[y, x], want, atol=TOL), (x, y, img[y, x], want)


def test_sincos_with_out_parameters_in_vs_1_1(backend):
    fx = trig_effect("    float s, co;\n    sincos(K.x * 2, s, co);\n"
                     "    c = float4(s * 0.5 + 0.5, co * 0.5 + 0.5, s * s + co * co - 0.5, 1);")
    img = render(fx, backend, params={"K": "1.7,0,0,0"})
    s, co = math.sin(3.4), math.cos(3.4)
    assert np.allclose(img[3, 3], (s / 2 + .5, co / 2 + .5, 0.5, 1), atol=TOL), img[3, 3]


def test_per_vertex_sin_is_interpolated_across_the_quad(backend):
    # the quad's left vertices have u = 0, the right ones u = 1: the colour a pixel gets is
    # the linear interpolation of the two vertex values (w = 1, no perspective)
    fx = trig_effect("    c = float4(sin(uv.x * 3 + 1) * 0.5 + 0.5, cos(uv.y * 5 - 2) * 0.5 + 0.5, 0, 1);")
    img = render(fx, backend)
    for x, y in ((0, 0), (3, 6), (7, 2)):
        u, v = pixel_uv(x, y)
        r = (1 - u) * math.sin(1) + u * math.sin(4)
        g = (1 - v) * math.cos(-2) + v * math.cos(3)
        assert np.allclose(img[y, x, :2], (r * .5 + .5, g * .5 + .5), atol=TOL), (x, y)


def test_the_series_is_accurate_over_a_turn():
    """The polynomial's coefficients on the reduced range [-pi, pi], in double precision:
    within the bound the first left-out term gives (no 8-bit colour in the way)."""
    from effects.shaders.hlsl.intrinsics import _COS_TERMS, _SIN_TERMS
    for y in np.linspace(-math.pi, math.pi, 721):
        y2 = y * y
        s = sum(t * y2 ** k for k, t in enumerate(_SIN_TERMS)) * y
        c = sum(t * y2 ** k for k, t in enumerate(_COS_TERMS))
        assert abs(s - math.sin(y)) < 3e-5 and abs(c - math.cos(y)) < 1e-5, y


def test_sincos_outputs_must_be_variables_located():
    fx = effect_for("float4 VS(float4 p : POSITION) : POSITION\n{\n    float c;\n"
                    "    sincos(p.x, 1.0, c);\n    return p * c;\n}\n" + PS,
                    vs="compile vs_1_1 VS()")
    with pytest.raises(EffectError) as info:
        fx_asm(fx, "VS", "vs_1_1")
    assert info.value.message.startswith("X3025: l-value expected")
    assert (info.value.line, info.value.column) == (5, 17)
