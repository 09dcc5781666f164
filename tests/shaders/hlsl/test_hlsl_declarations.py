"""Function overloads and prototypes, typedefs, struct and array initializers (issue 30's list
of constructs valid programs failed on): each rendered on both back ends, values worked out by
hand. Read at pixel (2, 4) of the 8 x 8 quad: u = 2 / 8 = 0.25, v = 4 / 8 = 0.5.

fxc's initializers are flattened: the numbers of the list, braces ignored, structs and arrays
in it taken member by member, fill the numbers of the declared type; an implicit size `[]` is
as many elements as the list fills ("HLSL ignores braces in initializer lists and flattens
all the argument structures down to an ordering of individual scalar elements", Chris Bieneman,
abolishcrlf.org 2025-03-28, whose `int2 Arr[] = {int2(0,1), int2(2,3), int4(4,5,6,7)}` has 4
elements).
"""
from __future__ import annotations

import numpy as np
import pytest

import effects
from effects.base.errors import EffectError
from effects.program.backend import create_backend
from effects.shaders.hlsl import compile_shader

U, V = 0.25, 0.5
TOL = 1.5 / 255


@pytest.fixture(scope="module", params=("numpy", "gl"))
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


def effect_for(functions: str, **load) -> effects.Effect:
    return effects.load_effect(
        functions + "\ntechnique T { pass P { PixelShader = compile ps_2_0 PS(); } }\n", **load)


def pixel(fx: effects.Effect, backend) -> np.ndarray:
    img = effects.render(fx, "radeon9700", technique="T", backend=backend,
                         scene={"mesh": "quad", "size": [8, 8]})
    return img[4, 2].astype(np.float64) / 255.0


# --- overloads and prototypes ---------------------------------------------------------------------

def test_overloads_by_shape_by_literal_type_and_by_struct(backend):
    fx = effect_for("""
struct A { float x; };
struct B { float2 y; };
float f(float x) { return x * 2; }
float2 f(float2 x) { return x * 0.5; }
float g(int i) { return 0.25; }
float g(float x) { return 0.75; }
float h(A a) { return a.x; }
float h(B b) { return b.y.y; }
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    A a = { 0.125 };
    B b = { 0, 0.375 };
    float2 half_uv = f(uv);
    return float4(f(uv.x), half_uv.y, g(1) + g(1.0) * 0 + h(a) * 0 + h(b), 1);
}""")
    # f(u) = 0.5; f(uv).y = v / 2 = 0.25; g(1) picks int: 0.25, + h(b) = 0.375
    assert np.allclose(pixel(fx, backend), (2 * U, V / 2, 0.25 + 0.375, 1), atol=TOL)


def test_a_prototype_before_use_and_the_definition_after_with_other_names(backend):
    fx = effect_for("""
float3 Light(float3 n, float3 l);
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    return float4(Light(float3(uv, 1) * 0.5, float3(0, 0, 1)), 1);
}
float3 Light(float3 normal, float3 direction)
{
    return saturate(dot(normal, direction)) * normal;
}""")
    # n = (u, v, 1) / 2, dot(n, z) = 0.5: 0.5 * n
    assert np.allclose(pixel(fx, backend), (U / 4, V / 4, 0.25, 1), atol=TOL)


# --- typedefs ----------------------------------------------------------------------------------------

def test_typedefs_global_local_from_an_include_and_as_constructors(backend, tmp_path):
    (tmp_path / "types.fxh").write_text("typedef vector<half, 4> vec4;\n"
                                        "typedef matrix<float, 2, 2> mat2;\n")
    path = tmp_path / "typedefs.fx"
    path.write_text("""#include "types.fxh"
struct Light { float3 colour; };
typedef Light Lamp;
typedef float2 Pair[2];
vec4 PS(float2 uv : TEXCOORD0) : COLOR
{
    typedef float1 one;
    mat2 m = mat2(uv, 0.75, 1);          // rows (u, v), (0.75, 1)
    Lamp lamp = { m[1], 0.5 };           // (0.75, 1, 0.5)
    Pair p = { lamp.colour.z, m[0], 0 }; // p[0] = (0.5, u), p[1] = (v, 0)
    one k = 0.125;
    return vec4(p[0].y, p[1].x, lamp.colour.x, k);
}
technique T { pass P { PixelShader = compile ps_2_0 PS(); } }
""")
    fx = effects.load_effect(str(path))
    assert np.allclose(pixel(fx, backend), (U, V, 0.75, 0.125), atol=TOL)


def test_a_parameter_of_an_array_typedef_is_a_located_error():
    with pytest.raises(EffectError) as info:
        effects.load_effect("typedef float2 Pair[2];\nPair Offsets;\n")
    assert str(info.value) == ("<string>:2:1: error: typedef 'Pair' is an array type: a "
                               "parameter of an array typedef is not supported (declare the array)")


# --- initializers -------------------------------------------------------------------------------------

def test_struct_initializers_flat_nested_and_from_values(backend):
    fx = effect_for("""
struct S { float a; float2 b; };
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    S s = { 0.125, uv };
    S t = { s };                                  // a struct in a list: its members
    S pair[2] = { {0.1, {0.2, 0.3}}, {0.4, 0.5, 0.6} };
    float4 v = { t.b, pair[1].b.y, pair[0].a };
    return v;
}""")
    assert np.allclose(pixel(fx, backend), (U, V, 0.6, 0.1), atol=TOL)


def test_implicit_array_sizes_count_the_flattened_numbers(backend):
    fx = effect_for("""
float4 PS(float2 uv : TEXCOORD0) : COLOR
{
    float2 arr[] = { float2(0, 0.125), float2(0.25, 0.375), float4(0.5, 0.625, 0.75, 0.875) };
    float w[] = { uv, arr[3] };                   // 4 numbers: 4 elements
    return float4(arr[3].y, arr[2].x, w[1], w[3]);
}""")
    assert np.allclose(pixel(fx, backend), (0.875, 0.5, V, 0.875), atol=TOL)


@pytest.mark.parametrize("body, message", [
    ("float a[];\n    return a[0];",
     "an array of implicit size ('[]') needs an initializer list (no X code: fxc's wording "
     "for this was not found)"),
    ("float2 a[] = { 1, 2, 3 };\n    return a[0].x;",
     "X3017: initializer has 3 values, an array of 'float2' needs a multiple of 2"),
])
def test_implicit_sizes_fxc_refuses(body, message):
    fx = effect_for("float4 PS() : COLOR\n{\n    " + body + "\n}")
    with pytest.raises(EffectError) as info:
        compile_shader(fx, "PS", "ps_2_0")
    assert info.value.message == message and info.value.language
    assert info.value.line == 3


def test_a_void_parameter_list_is_no_parameters(backend):
    # C's `f(void)`, as fxc accepted it (DirectX SDK samples write `float4 PS(void)`); a void
    # *named* parameter stays X3038 (test_hlsl_invalid_corpus)
    fx = effect_for("float Half(void) { return 0.5; }\n"
                    "float4 PS(void) : COLOR { return float4(Half(), 0.25, 0, 1); }")
    assert pixel(fx, backend)[:2] == pytest.approx([0.5, 0.25], abs=TOL)
