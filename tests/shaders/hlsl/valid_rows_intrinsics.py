"""Valid-corpus rows (valid_corpus.py): every intrinsic of the DirectX 9 HLSL intrinsic table
with its overload shapes (scalar, vector, matrix where the table allows one), at its minimum
shader model. `noise` is in the table for texture fill functions only (tx_1_0), not shaders.
Expected values from the reference page's definition of each intrinsic."""
from __future__ import annotations

import math

from tests.shaders.hlsl.valid_corpus import CUBE, MIP_LEVELS, Row, line, ps, t2, vol

PI = math.pi


def ss(a: float, b: float, x: float) -> float:
    t = min(max((x - a) / (b - a), 0.0), 1.0)
    return t * t * (3 - 2 * t)


def k4(u: float) -> int:
    """floor(4u + 0.25) at a probe: x // 2."""
    return int(u * 4 + 0.25)


ROWS: list[Row] = [
    # -- abs, sign, saturate, clamp, min, max ----------------------------------------------
    Row("abs of a scalar and a vector", ps(
        "    return float4(abs(uv.x - 0.5), abs(float2(-0.25, uv.y - 1)), 1);"),
        lambda u, v: (abs(u - 0.5), 0.25, 1 - v, 1)),
    Row("abs of an int and a matrix", ps(
        "    int2 i = int2(-3, 2);\n    float2x2 m = float2x2(-uv.x, 0.5, uv.y - 1, -0.25);\n"
        "    float2x2 a = abs(m);\n    return float4(abs(i).x * 0.25, a._m00, a._m10, a[1][1]);"),
        lambda u, v: (0.75, u, 1 - v, 0.25)),
    Row("sign returns an int of each shape", ps(
        "    int s = sign(uv.x - 0.5);\n    float2 t = sign(float2(-2, uv.y));\n"
        "    return float4(s * 0.5 + 0.5, t * 0.5 + 0.5, sign(0) + 0.5);"),
        lambda u, v: (1.0 if u > 0.5 else 0.0, 0, 1, 0.5)),
    Row("saturate of a scalar and a matrix", ps(
        "    float2x2 m = saturate(float2x2(uv * 2, -uv));\n"
        "    return float4(saturate(uv.x * 4 - 1), m._m01, m._m10 + 0.5, saturate(1.5));"),
        lambda u, v: (min(max(4 * u - 1, 0), 1), min(2 * v, 1), 0.5, 1)),
    Row("clamp with scalar bounds spread to the vector", ps(
        "    return float4(clamp(uv, 0.25, 0.5), clamp(uv.x * 2, float2(0, 0.3), float2(0.2, 1)));"),
        lambda u, v: (min(max(u, 0.25), 0.5), min(max(v, 0.25), 0.5), min(2 * u, 0.2),
                      min(max(2 * u, 0.3), 1))),
    Row("clamp of ints", ps(
        "    int3 i = clamp(int3(uv.x * 8 + 0.5, -4, 9), 0, 4);\n    return float4(i * 0.25, 1);"),
        lambda u, v: (min(round(u * 8), 4) / 4, 0, 1, 1)),
    Row("max and min of scalars and vectors", ps(
        "    return float4(max(uv.x, 0.5), min(uv, float2(0.25, 0.5)), max(-1, min(2, 0.75)));"),
        lambda u, v: (max(u, 0.5), min(u, 0.25), min(v, 0.5), 0.75)),
    Row("max and min of ints and matrices", ps(
        "    int a = max(int(uv.x * 8 + 0.5), 3);\n    float2x2 m = min(float2x2(uv, uv), 0.5);\n"
        "    return float4(a * 0.125, m._m00, m._m11, m[1].x);"),
        lambda u, v: (max(round(u * 8), 3) / 8, min(u, 0.5), min(v, 0.5), min(u, 0.5))),
    # -- rounding ------------------------------------------------------------------------------
    Row("ceil floor round trunc at run time", ps(
        "    float4 x = float4(uv.x * 4 - 2.1, uv.y * 3 - 1, uv.x * 3 + 0.1, -uv.y * 3);\n"
        "    return float4(ceil(x.x) * 0.25 + 0.5, floor(x.y) * 0.25 + 0.5, round(x.z) * 0.25,\n"
        "                  trunc(x.w) * -0.25);"),
        lambda u, v: (math.ceil(4 * u - 2.1) * 0.25 + 0.5, math.floor(3 * v - 1) * 0.25 + 0.5,
                      math.floor(3 * u + 0.6) * 0.25, math.trunc(-3 * v) * -0.25)),
    Row("floor ceil frac of constants", ps(
        "    return float4(floor(float2(1.5, -0.5)) * 0.25 + 0.5, ceil(-0.5) + 0.25, frac(-0.25));"),
        lambda u, v: (0.75, 0.25, 0.25, 0.75)),
    Row("frac of a matrix", ps(
        "    float2x2 m = frac(float2x2(uv * 3, -uv));\n    return float4(m._m00, m._m01, m._m10, m._m11);"),
        lambda u, v: ((3 * u) % 1, (3 * v) % 1, 1 - u, 1 - v)),
    Row("round and trunc of vectors", ps(
        "    float2 r = round(float2(uv.x * 2 + 0.3, -1.7));\n    float2 t = trunc(float2(-uv.y * 2, 2.9));\n"
        "    return float4(r.x * 0.25, r.y * -0.25, t.x * -0.5, t.y * 0.25);"),
        lambda u, v: (math.floor(2 * u + 0.8) * 0.25, 0.5, math.trunc(-2 * v) * -0.5, 0.5)),
    Row("fmod keeps the sign of the dividend", ps(
        "    return float4(fmod(uv.x * 3, 1), fmod(-uv.y * 3, 1) + 1, fmod(float2(5.5, -5.5), 2) * 0.25 + 0.5);"),
        lambda u, v: ((3 * u) % 1, 1 - (3 * v) % 1, 0.875, 0.125)),
    Row("modf splits a scalar and a vector", ps(
        "    float ip;\n    float f = modf(uv.x * 3 + 1, ip);\n    float2 ip2;\n"
        "    float2 f2 = modf(float2(-1.25, 2.5), ip2);\n    return float4(f, ip * 0.25, -f2.x, ip2.y * 0.25);"),
        lambda u, v: ((3 * u + 1) % 1, math.floor(3 * u + 1) * 0.25, 0.25, 0.5)),
    Row("ldexp multiplies by a power of two", ps(
        "    return float4(ldexp(uv.x, -1), ldexp(float2(0.75, uv.y), float2(-2, -1)), 1);"),
        lambda u, v: (u / 2, 0.1875, v / 2, 1)),
    # -- exponentials -----------------------------------------------------------------------------
    Row("exp and exp2", ps("    return float4(exp(-uv.x), exp2(uv.y) - 1, exp(float2(-1, 0)) * 0.5);"),
        lambda u, v: (math.exp(-u), 2 ** v - 1, math.exp(-1) / 2, 0.5)),
    Row("log log2 log10", ps(
        "    return float4(log(uv.x + 1), log2(uv.y + 1), log10(uv.x * 9 + 1), log2(float2(4, 8)).x * 0.125);"),
        lambda u, v: (math.log(u + 1), math.log2(v + 1), math.log10(9 * u + 1), 0.25)),
    Row("pow of each shape", ps(
        "    return float4(pow(uv.x, 2), pow(uv, float2(0.5, 3)).y, pow(2, uv.y) - 1,\n"
        "                  pow(float2(0.25, 4), 0.5).x);"),
        lambda u, v: (u * u, v ** 3, 2 ** v - 1, 0.5)),
    Row("sqrt and rsqrt", ps("    return float4(rsqrt(uv.x + 1), sqrt(uv.y), sqrt(float2(0.25, 0.0625)));"),
        lambda u, v: (1 / math.sqrt(u + 1), math.sqrt(v), 0.5, 0.25)),
    Row("sqrt of a matrix", ps(
        "    float2x2 m = sqrt(float2x2(uv, 0.25, 0.0625));\n    return float4(m[0], m[1]);"),
        lambda u, v: (math.sqrt(u), math.sqrt(v), 0.5, 0.25)),
    # -- trigonometry --------------------------------------------------------------------------
    Row("sin cos tan of scalars", ps(
        "    return float4(sin(uv.x * 3) * 0.5 + 0.5, cos(uv.y * 2 - 1), tan(uv.x * 0.5) * 0.5 + 0.2, 1);"),
        lambda u, v: (math.sin(3 * u) / 2 + 0.5, math.cos(2 * v - 1), math.tan(u / 2) / 2 + 0.2, 1)),
    Row("sin of a matrix", ps(
        "    float2x2 s = sin(float2x2(uv, uv.yx * 2));\n"
        "    return float4(s._m00, s._m11 * 0.5 + 0.5, s._m01, s._m10 * 0.5 + 0.5);"),
        lambda u, v: (math.sin(u), math.sin(2 * u) / 2 + 0.5, math.sin(v), math.sin(2 * v) / 2 + 0.5)),
    Row("cos and tan of vectors", ps(
        "    float2 c = cos(uv * 2);\n    float2 t = tan(uv * 0.5);\n    return float4(c, t);"),
        lambda u, v: (math.cos(2 * u), math.cos(2 * v), math.tan(u / 2), math.tan(v / 2))),
    Row("sincos of a scalar and a vector", ps(
        "    float s, c;\n    sincos(uv.x * 2, s, c);\n    float2 s2, c2;\n"
        "    sincos(float2(0, 1.5707963), s2, c2);\n    return float4(s, c * 0.5 + 0.5, s2.y, c2.x);"),
        lambda u, v: (math.sin(2 * u), math.cos(2 * u) / 2 + 0.5, 1, 1)),
    Row("acos asin atan of scalars", ps(
        "    return float4(acos(uv.x) / 3.14159265, asin(uv.y) / 3.14159265 + 0.5, atan(uv.x) + 0.1, 1);"),
        lambda u, v: (math.acos(u) / PI, math.asin(v) / PI + 0.5, math.atan(u) + 0.1, 1)),
    Row("acos and asin of vectors", ps(
        "    float2 a = acos(uv - 0.5);\n    float2 b = asin(0.5 - uv);\n"
        "    return float4(a / 3.14159265, b / 3.14159265 + 0.5);"),
        lambda u, v: (math.acos(u - 0.5) / PI, math.acos(v - 0.5) / PI,
                      math.asin(0.5 - u) / PI + 0.5, math.asin(0.5 - v) / PI + 0.5)),
    Row("atan of a vector", ps("    float2 a = atan(uv * 4 - 2);\n    return float4(a / 3.14159265 + 0.5, 0, 1);"),
        lambda u, v: (math.atan(4 * u - 2) / PI + 0.5, math.atan(4 * v - 2) / PI + 0.5, 0, 1)),
    Row("atan2 of scalars and vectors in every quadrant", ps(
        "    float2 a = atan2(float2(uv.y, -uv.y), uv.x - 0.5);\n"
        "    return float4((a + 3.14159265) / 6.2831853, atan2(uv.x, 1), 1);"),
        lambda u, v: ((math.atan2(v, u - 0.5) + PI) / (2 * PI), (math.atan2(-v, u - 0.5) + PI) / (2 * PI),
                      math.atan2(u, 1), 1)),
    Row("sinh cosh tanh", ps(
        "    return float4(cosh(uv.x) - 1, sinh(uv.y) * 0.5, tanh(uv.x * 2 - 1) * 0.5 + 0.5, 1);"),
        lambda u, v: (math.cosh(u) - 1, math.sinh(v) / 2, math.tanh(2 * u - 1) / 2 + 0.5, 1)),
    Row("sinh cosh tanh of vectors", ps(
        "    float2 s = sinh(uv);\n    float2 t = tanh(-uv);\n    return float4(s * 0.5, t + 1);"),
        lambda u, v: (math.sinh(u) / 2, math.sinh(v) / 2, 1 - math.tanh(u), 1 - math.tanh(v))),
    Row("degrees and radians", ps(
        "    return float4(degrees(uv.x) / 180, radians(uv.y * 36), degrees(float2(0.5, 1)) / 360);"),
        lambda u, v: (u / PI, v * 36 * PI / 180, math.degrees(0.5) / 360, math.degrees(1) / 360)),
    # -- interpolation -----------------------------------------------------------------------
    Row("lerp with a scalar weight and vectors", ps(
        "    return float4(lerp(0.25, 0.75, uv.x), lerp(float2(0, 1), float2(1, 0), uv.y),\n"
        "                  lerp(uv.x, uv.y, 0.5));"),
        lambda u, v: (0.25 + 0.5 * u, v, 1 - v, (u + v) / 2)),
    Row("lerp of matrices", ps(
        "    float2x2 m = lerp(float2x2(0, 0, 1, 1), float2x2(uv, 0, 0), 0.5);\n    return float4(m[0], m[1]);"),
        lambda u, v: (u / 2, v / 2, 0.5, 0.5)),
    Row("smoothstep of scalars and vectors", ps(
        "    return float4(smoothstep(0.25, 0.75, uv.x), smoothstep(float2(0, 0.5), float2(1, 1), uv.y), 1);"),
        lambda u, v: (ss(0.25, 0.75, u), ss(0, 1, v), ss(0.5, 1, v), 1)),
    Row("step of scalars and vectors", ps(
        "    return float4(step(0.5, uv.x), step(uv, float2(0.25, 0.5)), step(1, 1));"),
        lambda u, v: (float(u >= 0.5), float(0.25 >= u), float(0.5 >= v), 1)),
    # -- vectors ---------------------------------------------------------------------------------
    Row("dot of each shape", ps(
        "    return float4(dot(uv, float2(0.5, 0.25)), dot(float3(uv, 1), 0.25),\n"
        "                  dot(int2(1, 2), int2(0, 1)) * 0.25, dot(float4(uv, uv), float4(1, 0, 0, 0)));"),
        lambda u, v: (u / 2 + v / 4, (u + v + 1) / 4, 0.5, u)),
    Row("cross", ps("    float3 c = cross(float3(uv, 0), float3(0, 0, 1));\n    return float4(c * 0.5 + 0.5, 1);"),
        lambda u, v: (v / 2 + 0.5, 0.5 - u / 2, 0.5, 1)),
    Row("distance and length", ps(
        "    return float4(distance(uv, float2(0, 0)) * 0.5, length(float3(uv.x, 0, uv.y)) * 0.5,\n"
        "                  length(-0.25), distance(uv.x, 0.5));"),
        lambda u, v: (math.hypot(u, v) / 2, math.hypot(u, v) / 2, 0.25, abs(u - 0.5))),
    Row("normalize", ps(
        "    float3 n = normalize(float3(uv.x, 0, 0.5));\n    float2 m = normalize(float2(3, 4));\n"
        "    return float4(n.x, n.z, m);"),
        lambda u, v: (u / math.hypot(u, 0.5), 0.5 / math.hypot(u, 0.5), 0.6, 0.8)),
    Row("reflect", ps(
        "    float3 r = reflect(float3(uv.x, -0.5, 0), float3(0, 1, 0));\n    return float4(r * 0.5 + 0.5, 1);"),
        lambda u, v: (u / 2 + 0.5, 0.75, 0.5, 1)),
    Row("refract at an angle with a run-time index", ps(
        "    float3 r = refract(float3(0.70710678, 0, -0.70710678), float3(0, 0, 1), uv.x);\n"
        "    return float4(r * 0.5 + 0.5, 1);"),
        lambda u, v: (u * 0.70710678 / 2 + 0.5, 0.5, 0.5 - math.sqrt(1 - u * u / 2) / 2, 1)),
    Row("faceforward", ps(
        "    float3 f = faceforward(float3(0, 0, 1), float3(0, 0, uv.x - 0.5), float3(0, 0, 1));\n"
        "    return float4(f * 0.5 + 0.5, 1);"),
        lambda u, v: (0.5, 0.5, 1.0 if u < 0.5 else 0.0, 1)),
    Row("lit", ps("    float4 l = lit(uv.x - 0.5, uv.y, 2);\n    return l * float4(0.5, 1, 1, 0.25);"),
        lambda u, v: (0.5, max(u - 0.5, 0), 0 if u < 0.5 else v * v, 0.25)),
    Row("rcp and mad of scalars and vectors", ps(
        "    float2 r = rcp(uv + 1);\n    return float4(r, mad(uv.x, 0.5, 0.25), mad(uv, float2(0.5, 2), 0.125).x);"),
        lambda u, v: (1 / (u + 1), 1 / (v + 1), u / 2 + 0.25, u / 2 + 0.125)),
    Row("isnan isinf isfinite of a vector", ps(
        "    float2 x = float2(uv.x, 1 / Zero);\n"
        "    return float4(isinf(x), isfinite(x).x * 0.5 + isnan(x * Zero).y * 0.25, isnan(uv.y));",
        "float Zero = 0;\n"),
        lambda u, v: (0, 1, 0.75, 0)),
    Row("frexp of a vector", ps(
        "    float2 e;\n    float2 m = frexp(float2(uv.x + 1, 6), e);\n    return float4(m, e * 0.25);"),
        lambda u, v: ((u + 1) / 2, 0.75, 0.25, 0.75)),
    Row("dst", ps("    float4 d = dst(float4(0, uv.x, uv.x, 0), float4(0, 1, 0, uv.y));\n    return d;"),
        lambda u, v: (1, u, u, v)),
    Row("all and any of scalars, vectors and a matrix", ps(
        "    float3 a = float3(uv.x > 0.5, 1, uv.y);\n"
        "    return float4(all(a), any(float2(uv.x - 0.7, 0)), all(uv.y), any(float2x2(0, 0, 0, uv.x)));"),
        lambda u, v: (float(u > 0.5), float(u != 0.7), 1, 1)),
    # -- matrices ------------------------------------------------------------------------------
    Row("mul of a scalar and a vector, and two vectors", ps(
        "    float2 a = mul(2, uv) * 0.25;\n    float b = mul(uv, float2(0.5, 0.5));\n"
        "    float c = mul(uv.x, 0.5);\n    return float4(a, b, c);"),
        lambda u, v: (u / 2, v / 2, (u + v) / 2, u / 2)),
    Row("mul of a vector and a non-square matrix both ways", ps(
        "    float3x2 m = float3x2(1, 0, 0, 1, 0.5, 0.5);\n    float2 a = mul(float3(uv, 1), m);\n"
        "    float3 b = mul(m, float2(0.5, uv.y));\n    return float4(a * 0.5, b.z, b.x);"),
        lambda u, v: ((u + 0.5) / 2, (v + 0.5) / 2, 0.25 + 0.5 * v, 0.5)),
    Row("mul of two non-square matrices", ps(
        "    float2x3 a = float2x3(uv.x, 0, 0, 0, uv.y, 0);\n    float3x2 b = float3x2(1, 0.5, 0.25, 1, 0, 0);\n"
        "    float2x2 c = mul(a, b);\n    return float4(c._m00, c._m01, c._m10, c._m11);"),
        lambda u, v: (u, u / 2, v / 4, v)),
    Row("mul of a scalar and a matrix", ps(
        "    float2x2 m = mul(0.5, float2x2(uv, 1, uv.x));\n    return float4(m[0], m[1]);"),
        lambda u, v: (u / 2, v / 2, 0.5, u / 2)),
    Row("mul of a float4 and a float4x4", ps(
        "    float4x4 m = { 0.5, 0, 0, 0,  0, 0.5, 0, 0,  0, 0, 1, 0,  0.25, 0.25, 0, 1 };\n"
        "    return mul(float4(uv, 0.5, 1), m);"),
        lambda u, v: (u / 2 + 0.25, v / 2 + 0.25, 0.5, 1)),
    Row("mul of a float3 and a float4x3", ps(
        "    float4x3 m = { 1, 0, 0,  0, 1, 0,  0, 0, 1,  0, 0, 0 };\n"
        "    return float4(mul(float4(uv, 0.5, 1), m), 1);"),
        lambda u, v: (u, v, 0.5, 1)),
    Row("transpose", ps(
        "    float2x3 m = float2x3(uv.x, 0.25, 0.5, uv.y, 0.75, 1);\n    float3x2 t = transpose(m);\n"
        "    return float4(t._m10, t._m01, t[2].x, t._m21 * 0.5);"),
        lambda u, v: (0.25, v, 0.5, 0.5)),
    Row("determinant of 2x2, 3x3 and 4x4", ps(
        "    float2x2 a = float2x2(uv.x, 0.25, 0.5, uv.y);\n"
        "    float3x3 b = float3x3(1, 0, 0, 0, uv.x, 0, 0, 0.5, 2);\n"
        "    float4x4 c = float4x4(2, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0.5);\n"
        "    return float4(determinant(a) + 0.5, determinant(b) * 0.25, determinant(c), 1);"),
        lambda u, v: (u * v + 0.375, u / 2, 0.5, 1)),
    # -- derivatives (ps_2_a and up: ps_3_0 here) --------------------------------------------------
    Row("ddx and ddy", ps(
        "    float2 d = float2(ddx(uv.x), ddy(uv.y)) * 4;\n"
        "    return float4(d, ddx(uv.y) + 0.5, abs(ddy(uv.x * 2)) + 0.25);"),
        lambda u, v: (0.5, 0.5, 0.5, 0.25), target="ps_3_0"),
    Row("ddx of a vector", ps("    float4 d = ddx(float4(uv, uv * 2)) * 4;\n    return d + float4(0, 0.5, 0, 0.5);"),
        lambda u, v: (0.5, 0.5, 1, 0.5), target="ps_3_0"),
    Row("fwidth", ps("    return float4(fwidth(uv) * 4, fwidth(uv.x * 2) * 2, 1);"),
        lambda u, v: (0.5, 0.5, 0.5, 1), target="ps_3_0"),
    # -- clip -------------------------------------------------------------------------------------
    Row("clip of a vector keeps the pixels it does not discard", ps(
        "    clip(float2(1, uv.y + 1));\n    clip(uv.x);\n    return float4(uv, 0, 1);"),
        lambda u, v: (u, v, 0, 1)),
    # -- D3DCOLORtoUBYTE4 ------------------------------------------------------------------------
    Row("D3DCOLORtoUBYTE4 swizzles and scales", ps(
        "    int4 b = D3DCOLORtoUBYTE4(float4(0.2, 0.4, 0.6, 1));\n    return b / 255.0;"),
        lambda u, v: (0.6, 0.4, 0.2, 1)),
    Row("D3DCOLORtoUBYTE4 indexes a vertex constant array",
        "float4 Pal[4] = { 0.1, 0.1, 0.1, 1,  0.2, 0.4, 0.6, 1,  0.9, 0.5, 0.25, 1,  1, 1, 1, 1 };\n"
        "float4 Colour = { 0, 0, 0.00784314, 0 };\n"
        "struct VO { float4 p : POSITION; float4 c : COLOR0; };\n"
        "VO VS(float4 p : POSITION) { VO o; o.p = p; o.c = Pal[D3DCOLORtoUBYTE4(Colour).x]; return o; }\n"
        "float4 PS(float4 c : COLOR0) : COLOR { return c; }\n",
        lambda u, v: (0.9, 0.5, 0.25, 1), vs="vs_1_1"),
    # -- textures ----------------------------------------------------------------------------
    Row("tex1D", ps("    return tex1D(sLine, uv.x + 0.0625);"), lambda u, v: line(u + 0.0625)),
    Row("tex1Dproj divides by w", ps("    return tex1Dproj(sLine, float4(uv.x * 0.5 + 0.03125, 0, 0, 0.5));"),
        lambda u, v: line(u + 0.0625)),
    Row("tex1Dbias", ps("    return tex1Dbias(sLine, float4(uv.x + 0.0625, 0, 0, 1));"), lambda u, v: line(u + 0.0625)),
    Row("tex1Dlod", ps("    return tex1Dlod(sLine, float4(uv.x + 0.0625, 0, 0, 0));"), lambda u, v: line(u + 0.0625),
        target="ps_3_0"),
    Row("tex1Dgrad", ps("    return tex1Dgrad(sLine, uv.x + 0.0625, 0.01, 0.01);"), lambda u, v: line(u + 0.0625),
        target="ps_3_0"),
    Row("tex2D", ps("    return tex2D(sT2, uv);"), lambda u, v: t2(u, v)),
    Row("tex2Dproj divides by w", ps("    return tex2Dproj(sT2, float4(uv * 0.5, 0.25, 0.5));"),
        lambda u, v: t2(u, v)),
    Row("tex2Dbias raises the mip level", ps("    return tex2Dbias(sMip, float4(uv, 0, 2.2));"),
        lambda u, v: MIP_LEVELS[1]),
    Row("tex2Dlod picks the mip level", ps("    return tex2Dlod(sMip, float4(uv, 0, 2));"),
        lambda u, v: MIP_LEVELS[2], target="ps_3_0"),
    Row("tex2Dgrad picks the level of its gradients", ps(
        "    return tex2Dgrad(sMip, uv, float2(0.5, 0), float2(0, 0.5)) * 0.5\n"
        "         + tex2D(sMip, uv, float2(1, 0), float2(0, 1)) * 0.5;"),
        lambda u, v: (0, 0.5, 0.5, 1), target="ps_3_0"),
    Row("tex2D at level 0 on a mip-mapped texture", ps("    return tex2D(sMip, uv);"),
        lambda u, v: MIP_LEVELS[0]),
    Row("tex2D of a float3 coordinate truncates with X3206", ps("    return tex2D(sT2, float3(uv, 0.5));"),
        lambda u, v: t2(u, v), warns=("X3206",)),
    Row("texCUBE picks the face of the largest component", ps(
        "    return texCUBE(sCube, float3(uv.x - 0.5, 1, 0.1)) * 0.5 + texCUBE(sCube, float3(0.1, uv.y, -2)) * 0.5;"),
        lambda u, v: tuple((a + b) / 2 for a, b in zip(CUBE[2], CUBE[5]))),
    Row("texCUBEproj", ps("    return texCUBEproj(sCube, float4(-1, uv * 0.5, 0.5));"), lambda u, v: CUBE[1]),
    Row("texCUBEbias", ps("    return texCUBEbias(sCube, float4(0.2, -1, uv.x - 0.5, 1));"), lambda u, v: CUBE[3]),
    Row("texCUBElod", ps("    return texCUBElod(sCube, float4(1, uv * 0.5, 0));"), lambda u, v: CUBE[0],
        target="ps_3_0"),
    Row("texCUBEgrad", ps("    return texCUBEgrad(sCube, float3(0, uv.x - 0.5, 1), 0.01, 0.01);"),
        lambda u, v: CUBE[4], target="ps_3_0"),
    Row("tex3D", ps("    return tex3D(sVol, float3(uv, 0.75));"), lambda u, v: vol(u, v, 0.75)),
    Row("tex3Dproj", ps("    return tex3Dproj(sVol, float4(uv * 2, 0.5, 2));"), lambda u, v: vol(u, v, 0.25)),
    Row("tex3Dbias", ps("    return tex3Dbias(sVol, float4(uv.yx, 0.25, 1));"), lambda u, v: vol(v, u, 0.25)),
    Row("tex3Dlod", ps("    return tex3Dlod(sVol, float4(uv, 0.75, 0));"), lambda u, v: vol(u, v, 0.75),
        target="ps_3_0"),
    Row("tex3Dgrad", ps("    return tex3Dgrad(sVol, float3(uv, 0.25), 0.01, 0.01);"), lambda u, v: vol(u, v, 0.25),
        target="ps_3_0"),
    Row("tex2D through an untyped sampler", "sampler S = sampler_state { Texture = <T2tex>;"
        " MinFilter = Point; MagFilter = Point; MipFilter = None; };\n" + ps("    return tex2D(S, uv);")
        + "// sT2\n", lambda u, v: t2(u, v)),
    Row("a sampler passed to a function", ps(
        "    return Read(sT2, uv.yx);", "float4 Read(sampler2D s, float2 t) { return tex2D(s, t); }\n"),
        lambda u, v: t2(v, u)),
    Row("a texture read at a computed coordinate", ps(
        "    float2 t = frac(uv * 2 + 0.3);\n    return tex2D(sT2, t) * 0.5 + tex1D(sLine, t.y) * 0.5;"),
        lambda u, v: (t2((2 * u + 0.3) % 1, (2 * v + 0.3) % 1) + line((2 * v + 0.3) % 1)) / 2),
]
