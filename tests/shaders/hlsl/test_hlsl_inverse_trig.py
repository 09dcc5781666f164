"""asin, acos, atan, atan2, sinh, cosh, tanh, faceforward and refract: no shader model has an
instruction for them, so the compiler expands them into arithmetic (Abramowitz and Stegun's
polynomials for the inverse trigonometry). Each is drawn on a quad, every pixel against the
function computed here by the formula at that pixel's texture coordinate."""
from __future__ import annotations

import math

import numpy as np
import pytest

import effects
from effects.program.backend import create_backend

SIZE = (8, 8)
QUAD = {"mesh": "quad", "size": list(SIZE)}
TOL = 1.5 / 255 + 1e-4   # 8-bit output; the polynomials are within 1e-4


@pytest.fixture(scope="module", params=("numpy", "gl"))
def backend(request):
    made = create_backend(request.param)
    yield made
    made.close()


def draw(body: str, backend, target: str = "ps_2_0") -> np.ndarray:
    fx = effects.load_effect(
        f"float4 PS(float2 uv : TEXCOORD0) : COLOR {{ {body} }}\n"
        f"technique T {{ pass P {{ Lighting = False; PixelShader = compile {target} PS(); }} }}\n")
    return effects.render(fx, "radeon9700", technique="T", backend=backend, scene=QUAD) / 255.0


def each_pixel(img: np.ndarray, want) -> None:
    for y in range(SIZE[1]):
        for x in range(SIZE[0]):
            u, v = x / SIZE[0], y / SIZE[1]       # D3D9: texel (0, 0) at the first pixel
            expected = np.clip(np.asarray(want(u, v), np.float64), 0, 1)
            assert np.allclose(img[y, x], expected, atol=TOL), (x, y, img[y, x], expected)


def test_inverse_trigonometry(backend):
    # each result moved into [0, 1]: asin and atan of [-1, 1) over pi, acos over pi,
    # atan2 of the direction from the quad's centre over 2 pi
    img = draw("float s = uv.x * 2 - 1, c = uv.y * 2 - 1;"
               "return float4(asin(s) / 3.14159265 + 0.5, acos(c) / 3.14159265,"
               " atan(s * 4) / 3.14159265 + 0.5, atan2(c, s + 0.0625) / 6.2831853 + 0.5);",
               backend)
    each_pixel(img, lambda u, v: [math.asin(2 * u - 1) / math.pi + 0.5,
                                  math.acos(2 * v - 1) / math.pi,
                                  math.atan((2 * u - 1) * 4) / math.pi + 0.5,
                                  math.atan2(2 * v - 1, 2 * u - 1 + 0.0625) / (2 * math.pi) + 0.5])


def test_hyperbolic_functions(backend):
    img = draw("float x = uv.x * 2 - 1;"
               "return float4(sinh(x) / 2.4 + 0.5, cosh(x) - 0.5, tanh(x * 2) / 2 + 0.5, 1);",
               backend)
    each_pixel(img, lambda u, v: [math.sinh(2 * u - 1) / 2.4 + 0.5, math.cosh(2 * u - 1) - 0.5,
                                  math.tanh((2 * u - 1) * 2) / 2 + 0.5, 1])


def test_faceforward_and_refract(backend):
    # faceforward keeps n where dot(i, ng) < 0; refract with eta 0.9 of a direction tilted
    # by uv, through the plane z = 0 (normal +z); where k < 0 it is 0 (not here: eta < 1)
    img = draw("float3 i = normalize(float3(uv.x - 0.5, uv.y - 0.5, -1));"
               "float3 n = float3(0, 0, 1);"
               "float3 f = faceforward(n, float3(uv.x - 0.5, 0, 1), n);"
               "float3 r = refract(i, n, 0.9);"
               "return float4(r.xy + 0.5, -r.z * 0.5, f.z * 0.5 + 0.5);", backend)

    def want(u, v):
        i = np.array([u - 0.5, v - 0.5, -1.0])
        i /= np.linalg.norm(i)
        n = np.array([0.0, 0.0, 1.0])
        d = float(n @ i)
        k = 1 - 0.81 * (1 - d * d)
        r = 0.9 * i - (0.9 * d + math.sqrt(k)) * n
        face = 1.0 if (u - 0.5) * 0 + 1 < 0 else -1.0     # dot(i, ng) = 1 > 0: -n
        return [r[0] + 0.5, r[1] + 0.5, -r[2] * 0.5, face * 0.5 + 0.5]
    each_pixel(img, want)


@pytest.mark.parametrize("name, fn, lo, hi, bound", [
    ("asin", math.asin, -1, 1, 7e-5), ("acos", math.acos, -1, 1, 7e-5),
    ("atan", math.atan, -20, 20, 1.2e-5), ("sinh", math.sinh, -3, 3, 1e-5),
    ("cosh", math.cosh, -3, 3, 1e-5), ("tanh", math.tanh, -3, 3, 1e-6)])
def test_the_expansions_are_within_their_error_bounds(name, fn, lo, hi, bound):
    """The compiled ps_2_0 code, evaluated in float32 by the reference's evaluator at 1,001
    points: within Abramowitz and Stegun's bounds (6.7e-5 for arccos, 1e-5 for arctan) plus
    float32 rounding, relative for sinh and cosh."""
    from backends.reference.evaluate import evaluate
    from effects.d3d9.precision import LoweringOptions
    from effects.shaders.asm.lower import ShaderContext, lower_pixel_shader
    from effects.shaders.hlsl.compiler import compile_shader
    fx = effects.load_effect(
        f"float4 PS(float2 uv : TEXCOORD0) : COLOR {{ return {name}(uv.x); }}\n"
        "technique T { pass P { PixelShader = compile ps_2_0 PS(); } }\n")
    program = lower_pixel_shader(compile_shader(fx, "PS", "ps_2_0").program,
                                 ShaderContext(LoweringOptions()))
    x = np.linspace(lo, hi, 1001)
    got = evaluate(program, {"texcoord0": np.stack([x, x * 0], 1).astype(np.float32)})
    want = np.array([fn(v) for v in x])
    error = np.abs(got.outputs["color0"][:, 0] - want) / np.maximum(1, np.abs(want))
    assert error.max() <= bound, (name, float(error.max()), x[error.argmax()])


def test_an_unknown_intrinsic_is_still_located():
    fx = effects.load_effect("float4 PS(float2 uv : TEXCOORD0) : COLOR { return isnormal(uv.x); }\n"
                             "technique T { pass P { PixelShader = compile ps_2_0 PS(); } }\n")
    from effects.d3d9.caps import load_profile
    validation = fx.validate(fx.techniques[0], load_profile("radeon9700"))
    assert not validation.ok
    assert "X3004: undeclared identifier 'isnormal'" in str(validation.reasons[0])
