"""Valid-corpus rows (valid_corpus.py): the language around the intrinsics, as the DirectX 9
HLSL reference describes it (Scalar Types, Vector and Matrix Types, Per-Component Math
Operations, Variable Syntax, Function Syntax, Flow Control, Preprocessor Directives)."""
from __future__ import annotations

import math

from tests.shaders.hlsl.valid_corpus import Row, ps


def k4(u: float) -> int:
    """floor(4u + 0.25) at a probe: x // 2 (a quarter away from the next integer)."""
    return int(u * 4 + 0.25)


def x8(u: float) -> int:
    """(int)(8u + 0.5): the pixel column."""
    return int(u * 8 + 0.5)


ROWS: list[Row] = [
    # -- conversions and promotions ------------------------------------------------------------
    Row("float to int truncates toward zero", ps(
        "    int a = (int)(uv.x * 4 - 1.9);\n"
        "    return float4(a * 0.25 + 0.5, (int)(-1.75) * -0.25, (int)2.9 * 0.25, 1);"),
        lambda u, v: (math.trunc(4 * u - 1.9) * 0.25 + 0.5, 0.25, 0.5, 1)),
    Row("int division truncates and modulo keeps the sign", ps(
        "    int i = (int)(uv.x * 8 + 0.5);\n    int q = i / 2;\n    int r = i % 3;\n"
        "    return float4(q * 0.25, r * 0.5, 7 / 2 * 0.25, -7 % 3 * -0.5);"),
        lambda u, v: (x8(u) // 2 * 0.25, x8(u) % 3 * 0.5, 0.75, 0.5)),
    Row("an int divided by an int and by a float", ps(
        "    int i = 3;\n    float f = i / 2;\n    float g = i / 2.0;\n    return float4(f * 0.5, g * 0.5, 0, 1);"),
        lambda u, v: (0.5, 0.75, 0, 1)),
    Row("bool from a float and from a vector", ps(
        "    bool b = uv.x;\n    bool2 c = floor(uv * 4 + 0.25) - 1;\n"
        "    return float4(b, c, (float)true * 0.5);"),
        lambda u, v: (1, float(k4(u) != 1), float(k4(v) != 1), 0.5)),
    Row("a float assigned to an int", ps(
        "    int i = uv.x * 8 + 0.5;\n    int2 j = uv * 8 + 0.5;\n    return float4(i * 0.125, j * 0.125, 1);"),
        lambda u, v: (x8(u) / 8, x8(u) / 8, x8(v) / 8, 1)),
    Row("a scalar spreads to a vector and a matrix", ps(
        "    float4 a = uv.x;\n    float2x2 m = 0.5;\n    float3 b = 2;\n    return float4(a.w, m._m11, b.z * 0.25, 1);"),
        lambda u, v: (u, 0.5, 0.5, 1)),
    Row("a vector assigned to a scalar takes its x with X3206", ps(
        "    float s = uv;\n    return float4(s, 0, 0, 1);"), lambda u, v: (u, 0, 0, 1), warns=("X3206",)),
    Row("a longer vector assigned to a shorter one with X3206", ps(
        "    float2 t = float4(uv, 0.5, 1);\n    float3 w = float4(0.25, 0.5, 0.75, 1);\n    return float4(t, w.z, 1);"),
        lambda u, v: (u, v, 0.75, 1), warns=("X3206",)),
    Row("an argument truncated to the parameter with X3206", ps(
        "    return float4(f(float4(uv, 0, 1)), 0, 0, 1);", "float f(float2 a) { return a.y; }\n"),
        lambda u, v: (v, 0, 0, 1), warns=("X3206",)),
    Row("a return value truncated to the return type with X3206", ps(
        "    return float4(g(uv), 0, 1);", "float2 g(float2 x) { return float3(x.yx, 1); }\n"),
        lambda u, v: (v, u, 0, 1), warns=("X3206",)),
    Row("a scalar argument spreads to a vector parameter", ps(
        "    return h(uv.x);", "float4 h(float4 a) { return a * float4(1, 0.5, 0.25, 1); }\n"),
        lambda u, v: (u, u / 2, u / 4, u)),
    Row("a matrix cast to a vector of as many components", ps(
        "    float2x2 m = float2x2(uv, 0.25, 0.5);\n    float4 f = (float4)m;\n    return f;"),
        lambda u, v: (u, v, 0.25, 0.5)),
    Row("a vector cast to a matrix", ps(
        "    float2x2 m = (float2x2)float4(uv, 0.25, 0.5);\n    return float4(m._m10, m._m11, m._m00, m._m01);"),
        lambda u, v: (0.25, 0.5, u, v)),
    Row("a matrix cast to a smaller matrix keeps the upper left", ps(
        "    float3x3 a = float3x3(uv, 0, 0.25, 0.5, 0, 0, 0, 1);\n    float2x2 b = (float2x2)a;\n"
        "    return float4(b[0], b[1]);"),
        lambda u, v: (u, v, 0.25, 0.5)),
    Row("a struct cast to a vector", ps(
        "    S s = { uv, 0.25, 0.5 };\n    float4 f = (float4)s;\n    return f;",
        "struct S { float2 a; float b; float c; };\n"),
        lambda u, v: (u, v, 0.25, 0.5)),
    Row("a vector cast to a struct", ps(
        "    S s = (S)float4(uv, 0.25, 0.5);\n    return float4(s.c, s.b, s.a);",
        "struct S { float2 a; float b; float c; };\n"),
        lambda u, v: (0.5, 0.25, u, v)),
    Row("an array cast to a vector", ps(
        "    float a[4] = { uv.x, uv.y, 0.25, 1 };\n    return (float4)a;"),
        lambda u, v: (u, v, 0.25, 1)),
    Row("a struct cast to another struct of as many components", ps(
        "    A a;\n    a.x = float4(uv, 0.25, 0.5);\n    B b = (B)a;\n    return float4(b.q, b.p);",
        "struct A { float4 x; };\nstruct B { float2 p; float2 q; };\n"),
        lambda u, v: (0.25, 0.5, u, v)),
    Row("a scalar cast to a struct fills every member", ps(
        "    S s = (S)0.5;\n    return float4(s.a, s.b, s.c);", "struct S { float2 a; float b; float c; };\n"),
        lambda u, v: (0.5, 0.5, 0.5, 0.5)),
    Row("half with its suffix", ps(
        "    half h = 0.5h;\n    half2 hh = half2(uv);\n    half4 r = half4(hh, h, 1.0h);\n    return r;"),
        lambda u, v: (u, v, 0.5, 1)),
    Row("double with its suffix", ps(
        "    double d = 0.25L;\n    double2 e = uv;\n    return float4(d, e, 1);"),
        lambda u, v: (0.25, u, v, 1)),
    Row("literal forms: suffixes, exponents, hex and octal", ps(
        "    return float4(1.0f * 0.25, .5 * 5e-1 + 0.25, 0x1F / 31.0 - 0.5, 010 / 16.0 + 2. * 1.5E-1);"),
        lambda u, v: (0.25, 0.5, 0.5, 0.8)),
    Row("unsigned suffixes and uint, dword", ps(
        "    uint a = 3u;\n    dword b = 2;\n    return float4(a * 0.25, b * 0.25, 1U * 0.5, 1);"),
        lambda u, v: (0.75, 0.5, 0.5, 1)),
    Row("vector<> and matrix<> and the bare vector", ps(
        "    vector<float, 2> a = uv;\n    matrix<float, 2, 2> m = { a, a.yx };\n"
        "    vector b = float4(0.5, 0.25, 0, 1);\n    return float4(m._m01, m._m10, b.xy);"),
        lambda u, v: (v, v, 0.5, 0.25)),
    Row("float1 and float1x1", ps(
        "    float1 a = uv.x;\n    float1x1 m = uv.y;\n    return float4(a, m._m00, a.x * 0.5, 1);"),
        lambda u, v: (u, v, u / 2, 1)),
    Row("comparisons make bool vectors", ps(
        "    bool2 b = uv > 0.5;\n    float2 f = b;\n    return float4(f, b.x && b.y, b.x || b.y);"),
        lambda u, v: (float(u > 0.5), float(v > 0.5), float(u > 0.5 and v > 0.5), float(u > 0.5 or v > 0.5))),
    Row("int vectors promote to float", ps(
        "    int2 i = int2(1, 3);\n    float2 f = i * 0.25 + uv.x;\n    return float4(f, i.y / 4.0, 1);"),
        lambda u, v: (0.25 + u, 0.75 + u, 0.75, 1)),
    # -- initializers --------------------------------------------------------------------------
    Row("an array with an implicit size", ps(
        "    float a[] = { 0.25, 0.5, 0.75 };\n    return float4(a[0], a[1], a[2], 1);"),
        lambda u, v: (0.25, 0.5, 0.75, 1)),
    Row("an array of vectors with nested braces", ps(
        "    float2 a[2] = { { 0.25, 0.5 }, { uv } };\n    return float4(a[0], a[1]);"),
        lambda u, v: (0.25, 0.5, u, v)),
    Row("an array of vectors from a flat list", ps(
        "    float2 a[2] = { 0.25, 0.5, uv };\n    return float4(a[1], a[0]);"),
        lambda u, v: (u, v, 0.25, 0.5)),
    Row("a struct with a nested struct and an array from a flat list", ps(
        "    Out o = { 0.25, uv, 0.5, 0.75 };\n    return float4(o.i.b, o.c[1], o.i.a);",
        "struct In { float a; float2 b; };\nstruct Out { In i; float c[2]; };\n"),
        lambda u, v: (u, v, 0.75, 0.25)),
    Row("a struct with braces per member", ps(
        "    Out o = { { 0.25, uv }, { 0.5, 0.75 } };\n    return float4(o.c[0], o.i.b.yx, o.i.a);",
        "struct In { float a; float2 b; };\nstruct Out { In i; float c[2]; };\n"),
        lambda u, v: (0.5, v, u, 0.25)),
    Row("a matrix from a list of vectors and scalars", ps(
        "    float2x2 m = { uv, 0.25, 0.5 };\n    return float4(m[1], m[0]);"),
        lambda u, v: (0.25, 0.5, u, v)),
    Row("a scalar and a vector in braces", ps(
        "    float x = { 0.5 };\n    float4 c = { uv, x, 1 };\n    return c;"),
        lambda u, v: (u, v, 0.5, 1)),
    Row("a static const array read at a run-time index", ps(
        "    return float4(W[(int)(uv.x * 4 + 0.25)], W[1], 0, 1);",
        "static const float W[4] = { 0.1, 0.2, 0.3, 0.4 };\n"),
        lambda u, v: ((k4(u) + 1) * 0.1, 0.2, 0, 1)),
    Row("a uniform array with a flat default", ps(
        "    return C[1];", "float4 C[2] = { 0.25, 0.5, 0.75, 1, 0, 0.25, 0.5, 0.75 };\n"),
        lambda u, v: (0, 0.25, 0.5, 0.75)),
    Row("a static const array of structs", ps(
        "    return float4(ls[1].d, ls[0].k);",
        "struct L { float3 d; float k; };\n"
        "static const L ls[2] = { { 1, 0, 0, 0.25 }, { 0, 1, 0, 0.75 } };\n"),
        lambda u, v: (0, 1, 0, 0.25)),
    Row("several declarators of different shapes", ps(
        "    float a = 0.25, b[2] = { 0.5, 0.75 }, c;\n    c = uv.x;\n    return float4(a, b[1], c, 1);"),
        lambda u, v: (0.25, 0.75, u, 1)),
    Row("an array assigned whole", ps(
        "    float2 a[2] = { uv, uv.yx };\n    float2 b[2];\n    b = a;\n    return float4(b[1], b[0]);"),
        lambda u, v: (v, u, u, v)),
    Row("a struct assigned whole and copied", ps(
        "    S s = { uv, 0.5 };\n    S t = s;\n    t.b = 0.25;\n    return float4(s.a, s.b, t.b);",
        "struct S { float2 a; float b; };\n"),
        lambda u, v: (u, v, 0.5, 0.25)),
    Row("constructors with vector and matrix arguments", ps(
        "    float2x2 m = float2x2(0.25, 0.5, 0.75, 1);\n    float4 a = float4(m);\n"
        "    float4 b = float4(uv.x, float2(0.25, 0.5), 1);\n    return float4(a.yz, b.xy);"),
        lambda u, v: (0.5, 0.75, u, 0.25)),
    Row("a matrix constructor from vectors", ps(
        "    float2x3 m = float2x3(float3(0.25, uv), uv.yx, 1);\n    return float4(m[0].yz, m[1].xz);"),
        lambda u, v: (u, v, v, 1)),
    # -- swizzles -----------------------------------------------------------------------------------
    Row("rgba and xyzw swizzles", ps(
        "    float4 c = float4(uv, 0.25, 0.5);\n    return float4(c.b, c.z, c.ar);"),
        lambda u, v: (0.25, 0.25, 0.5, u)),
    Row("repeated and reordered swizzles", ps("    return uv.yxyx * float4(1, 1, 0.5, 0.5);"),
        lambda u, v: (v, u, v / 2, u / 2)),
    Row("a swizzle of a scalar", ps(
        "    float s = uv.x;\n    return s.xxxx * float4(1, 0.5, 0.25, 1) + uv.y.xxxx * 0;"),
        lambda u, v: (u, u / 2, u / 4, u)),
    Row("a swizzle of a swizzle", ps(
        "    float4 c = float4(uv, 0.25, 0.5);\n    return float4(c.wzyx.yx, c.xyz.z, 1);"),
        lambda u, v: (0.25, 0.5, 0.25, 1)),
    Row("a swizzle of a call and of a constructor", ps(
        "    return float4(float3(0.25, 0.5, 0.75).zy, g(uv).x, 1);",
        "float2 g(float2 t) { return t.yx; }\n"),
        lambda u, v: (0.75, 0.5, v, 1)),
    Row("write masks in any order", ps(
        "    float4 c = 0;\n    c.wy = uv;\n    c.zx = float2(0.25, 0.5);\n    return c;"),
        lambda u, v: (0.5, v, 0.25, u)),
    Row("matrix swizzles in the _m00 form", ps(
        "    float2x2 m = float2x2(uv, 0.25, 0.5);\n    float2 d = m._m00_m11;\n"
        "    float4 r = m._m11_m10_m01_m00;\n    return float4(d, r.yz);"),
        lambda u, v: (u, 0.5, 0.25, v)),
    Row("matrix swizzles in the _11 form, read and written", ps(
        "    float2x2 m = float2x2(uv, 0.25, 0.5);\n    float3 r = m._11_22_21;\n"
        "    m._12_21 = float2(0.75, 1);\n    return float4(r.xz, m._m01, m._m10);"),
        lambda u, v: (u, 0.25, 0.75, 1)),
    Row("matrix rows and elements by index", ps(
        "    float3x3 m = 0;\n    m[1] = float3(uv, 0);\n    m[2][1] = 0.5;\n    return float4(m[1], m[2].y);"),
        lambda u, v: (u, v, 0, 0.5)),
    Row("a matrix written through a swizzle", ps(
        "    float2x2 m = 0;\n    m._m01_m10 = uv;\n    return float4(m[0], m[1]);"),
        lambda u, v: (0, u, v, 0)),
    Row("swizzles of a struct member and an array element", ps(
        "    S s;\n    s.v = float4(uv, 0.25, 0.5);\n    float2 a[2] = { uv, float2(0.75, 1) };\n"
        "    return float4(s.v.wz, a[1].yx);", "struct S { float4 v; };\n"),
        lambda u, v: (0.5, 0.25, 1, 0.75)),
    # -- operators -------------------------------------------------------------------------------
    Row("compound assignments on a vector", ps(
        "    float4 c = float4(uv, 0.5, 1);\n    c += 0.25;\n    c -= float4(0.25, 0, 0, 0);\n"
        "    c *= float4(1, 0.5, 1, 0.5);\n    c /= 2;\n    return c;"),
        lambda u, v: (u / 2, (v + 0.25) / 4, 0.375, 0.3125)),
    Row("compound assignments through a swizzle", ps(
        "    float4 c = 0.5;\n    c.xz *= uv;\n    c.yw += uv.yx * 0.5;\n    return c;"),
        lambda u, v: (u / 2, 0.5 + v / 2, v / 2, 0.5 + u / 2)),
    Row("the float modulo operator", ps(
        "    float m = uv.x * 3;\n    m %= 1;\n    float2 n = float2(2.5, -2.5);\n    n %= 2;\n"
        "    return float4(m, n * 0.25 + 0.5, 1);"),
        lambda u, v: ((3 * u) % 1, 0.625, 0.375, 1)),
    Row("compound assignments on an int", ps(
        "    int i = 7;\n    i %= 4;\n    i *= 2;\n    i -= 1;\n    i /= 2;\n    return float4(i * 0.25, 0, 0, 1);"),
        lambda u, v: (0.5, 0, 0, 1)),
    Row("increments and decrements before and after", ps(
        "    float a = uv.x;\n    float b = a++;\n    float c = ++a;\n    float d = a--;\n"
        "    return float4(b, c - 2, (d - 2) * 0.5, a - 1);"),
        lambda u, v: (u, u, u / 2, u)),
    Row("increments of a vector and of array elements", ps(
        "    float2 w = uv;\n    w++;\n    float a[2] = { 0, 0.25 };\n    a[1]++;\n    --a[0];\n"
        "    return float4(w - 1, a[1] - 1, a[0] + 1.5);"),
        lambda u, v: (u, v, 0.25, 0.5)),
    Row("a ternary on vectors selects per component", ps(
        "    float4 a = float4(0.25, 0.5, 0.75, 1);\n    return (float4(uv, uv) > 0.5) ? a : 0;"),
        lambda u, v: (0.25 * (u > 0.5), 0.5 * (v > 0.5), 0.75 * (u > 0.5), 1.0 * (v > 0.5))),
    Row("a ternary with a scalar condition and vector results", ps(
        "    return uv.x > 0.5 ? float4(1, 0, 0, 1) : float4(uv, 0, 1);"),
        lambda u, v: (1, 0, 0, 1) if u > 0.5 else (u, v, 0, 1)),
    Row("nested ternaries", ps(
        "    float t = uv.x < 0.25 ? 0.1 : uv.x < 0.5 ? 0.2 : 0.3;\n    return float4(t, 0, 0, 1);"),
        lambda u, v: (0.1 if u < 0.25 else 0.2 if u < 0.5 else 0.3, 0, 0, 1)),
    Row("logical operators on vectors work per component", ps(
        "    bool2 a = uv > 0.3;\n    bool2 b = uv < 0.7;\n    bool2 c = a && b;\n    bool2 d = !a || b;\n"
        "    return float4(c, d);"),
        lambda u, v: (float(0.3 < u < 0.7), float(0.3 < v < 0.7), float(u < 0.7), float(v < 0.7))),
    Row("comparison operators give 0 or 1", ps(
        "    return float4(uv.x == uv.x, uv.x != uv.y, uv.x <= 0.5, uv.y >= 0.5);"),
        lambda u, v: (1, float(u != v), float(u <= 0.5), float(v >= 0.5))),
    Row("unary operators", ps("    return float4(-(-uv.x), +uv.y, !uv.x, !0);"),
        lambda u, v: (u, v, 0, 1)),
    Row("the comma operator", ps(
        "    float a, b;\n    a = (b = 0.25, b + 0.5);\n    return float4(a, b, 0, 1);"),
        lambda u, v: (0.75, 0.25, 0, 1)),
    Row("the comma operator as a statement", ps(
        "    float a, b;\n    a = uv.x, b = 0.5;\n    return float4(a, b, 0, 1);"),
        lambda u, v: (u, 0.5, 0, 1)),
    Row("chained assignments", ps(
        "    float a, b;\n    a = b = uv.x;\n    float4 c = 0;\n    c.x = c.y = 0.5;\n    return float4(a, b, c.xy);"),
        lambda u, v: (u, u, 0.5, 0.5)),
    Row("operator precedence", ps(
        "    return float4(0.25 + 0.5 * uv.x, (0.25 + 0.5) * uv.x, 1 - 0.5 - 0.25, 2 * 3 % 4 * 0.125);"),
        lambda u, v: (0.25 + 0.5 * u, 0.75 * u, 0.25, 0.25)),
    # -- flow -------------------------------------------------------------------------------------
    Row("for with break and continue", ps(
        "    float s = 0;\n    for (int i = 0; i < 8; i++)\n    {\n        if (i == 2) continue;\n"
        "        if (i == 5) break;\n        s += 0.125;\n    }\n    return float4(s, 0, 0, 1);"),
        lambda u, v: (0.5, 0, 0, 1)),
    Row("for with a run-time break", ps(
        "    float s = 0;\n    for (int i = 0; i < 4; i++)\n    {\n"
        "        if (i * 0.25 + 0.0625 > uv.x) break;\n        s += 0.25;\n    }\n    return float4(s, 0, 0, 1);"),
        lambda u, v: (0.25 * min(int((u - 0.0625) / 0.25) + 1, 4), 0, 0, 1)),
    Row("while (true) with a break", ps(
        "    float t = 0;\n    int n = 0;\n    while (true)\n    {\n        t += 0.125;\n        n++;\n"
        "        if (n >= 3) break;\n    }\n    return float4(t, 0, 0, 1);"),
        lambda u, v: (0.375, 0, 0, 1)),
    Row("do while with continue", ps(
        "    int i = 0;\n    float s = 0;\n    do\n    {\n        i++;\n        if (i == 2) continue;\n"
        "        s += 0.125;\n    } while (i < 4);\n    return float4(s, 0, 0, 1);"),
        lambda u, v: (0.375, 0, 0, 1)),
    Row("nested loops with a break from the inner", ps(
        "    float s = 0;\n    for (int i = 0; i < 3; i++)\n        for (int j = 0; j < 3; j++)\n"
        "        {\n            if (j > i) break;\n            s += 0.0625;\n        }\n    return float4(s, 0, 0, 1);"),
        lambda u, v: (0.375, 0, 0, 1)),
    Row("[unroll(n)]", ps(
        "    float s = 0;\n    [unroll(4)] for (int i = 0; i < 4; i++) s += uv.x * 0.25;\n    return float4(s, 0, 0, 1);"),
        lambda u, v: (u, 0, 0, 1)),
    Row("[loop] on ps_3_0 is a real loop", ps(
        "    float s = 0;\n    [loop] for (int i = 0; i < 4; i++) s += 0.125;\n    return float4(s, uv, 1);"),
        lambda u, v: (0.5, u, v, 1), target="ps_3_0", asm="rep"),
    Row("[loop] over a uniform count on ps_3_0", ps(
        "    float s = 0;\n    [loop] for (int i = 0; i < N; i++) s += 0.25;\n    return float4(s, 0, 0, 1);",
        "int N = 3;\n"),
        lambda u, v: (0.75, 0, 0, 1), target="ps_3_0"),
    Row("[branch] if on ps_3_0", ps(
        "    float4 c;\n    [branch] if (uv.x > 0.5) c = float4(1, 0, 0, 1);\n    else c = float4(0, 0, 1, 1);\n    return c;"),
        lambda u, v: (1, 0, 0, 1) if u > 0.5 else (0, 0, 1, 1), target="ps_3_0", asm="if"),
    Row("[flatten] if", ps(
        "    float4 c = 0;\n    [flatten] if (uv.y > 0.5) c = float4(uv, 0, 1);\n    return c;"),
        lambda u, v: (u, v, 0, 1) if v > 0.5 else (0, 0, 0, 0)),
    Row("[fastopt] on a loop", ps(
        "    float s = 0;\n    [fastopt] for (int i = 0; i < 3; i++) s += 0.25;\n    return float4(s, 0, 0, 1);"),
        lambda u, v: (0.75, 0, 0, 1)),
    Row("an if else-if chain", ps(
        "    float c;\n    if (uv.x < 0.25) c = 0.1;\n    else if (uv.x < 0.5) c = 0.2;\n"
        "    else if (uv.x < 0.7) c = 0.3;\n    else c = 0.4;\n    return float4(c, 0, 0, 1);"),
        lambda u, v: ((0.1 if u < 0.25 else 0.2 if u < 0.5 else 0.3 if u < 0.7 else 0.4), 0, 0, 1)),
    Row("a loop counter declared before the loop", ps(
        "    int i;\n    for (i = 0; i < 3; i++) { }\n    return float4(i * 0.25, 0, 0, 1);"),
        lambda u, v: (0.75, 0, 0, 1)),
    Row("for with empty parts", ps(
        "    int i = 0;\n    for (;;)\n    {\n        if (i >= 3) break;\n        i++;\n    }\n"
        "    return float4(i * 0.25, 0, 0, 1);"),
        lambda u, v: (0.75, 0, 0, 1)),
    Row("for with two counters", ps(
        "    float s = 0;\n    for (int i = 0, j = 4; i < j; i++, j--) s += 0.125;\n"
        "    return float4(s, 0, 0, 1);"),
        lambda u, v: (0.25, 0, 0, 1)),
    Row("switch with a shared case and default", ps(
        "    int k = (int)(uv.x * 4 + 0.25);\n    float c;\n    switch (k)\n    {\n"
        "    case 0: c = 0.1; break;\n    case 1:\n    case 2: c = 0.5; break;\n    default: c = 0.9; break;\n"
        "    }\n    return float4(c, 0, 0, 1);"),
        lambda u, v: ((0.1, 0.5, 0.5, 0.9)[k4(u)], 0, 0, 1)),
    Row("[flatten] switch", ps(
        "    int k = (int)(uv.y * 4 + 0.25);\n    float4 c = 0;\n    [flatten] switch (k)\n    {\n"
        "    case 1: c.r = 0.25; break;\n    case 3: c.g = 0.75; break;\n    default: c.b = 0.5; break;\n"
        "    }\n    return c;"),
        lambda u, v: {1: (0.25, 0, 0, 0), 3: (0, 0.75, 0, 0)}.get(k4(v), (0, 0, 0.5, 0))),
    Row("an unrolled loop writing an array", ps(
        "    float a[4];\n    for (int i = 0; i < 4; i++) a[i] = i * 0.25;\n    return float4(a[1], a[2], a[3], 1);"),
        lambda u, v: (0.25, 0.5, 0.75, 1)),
    Row("a while loop with continue", ps(
        "    int i = 0;\n    float s = 0;\n    while (i < 5)\n    {\n        i++;\n"
        "        if (i % 2 == 0) continue;\n        s += 0.25;\n    }\n    return float4(s, 0, 0, 1);"),
        lambda u, v: (0.75, 0, 0, 1)),
    Row("a loop summing a static const array", ps(
        "    float s = 0;\n    for (int i = 0; i < 4; i++) s += W[i] * uv.x;\n    return float4(s, 0, 0, 1);",
        "static const float W[4] = { 0.1, 0.2, 0.3, 0.4 };\n"),
        lambda u, v: (u, 0, 0, 1)),
    Row("a return inside an if", ps(
        "    if (uv.x < 0.5)\n        return float4(0.25, 0, 0, 1);\n    return float4(uv, 0, 1);"),
        lambda u, v: (0.25, 0, 0, 1) if u < 0.5 else (u, v, 0, 1)),
    # -- functions -----------------------------------------------------------------------------
    Row("out parameters", ps(
        "    float2 a, b;\n    split(float4(uv, 0.25, 0.5), a, b);\n    return float4(b, a);",
        "void split(float4 c, out float2 a, out float2 b) { a = c.xy; b = c.zw; }\n"),
        lambda u, v: (0.25, 0.5, u, v)),
    Row("an inout argument through a swizzle", ps(
        "    float4 c = float4(uv * 0.25, 0, 1);\n    twice(c.yx);\n    return c;",
        "void twice(inout float2 x) { x *= 2; }\n"),
        lambda u, v: (u / 2, v / 2, 0, 1)),
    Row("out arguments to an array element and a struct member", ps(
        "    float a[2] = { 0, 0 };\n    S s;\n    set(a[1], 0.25);\n    set(s.f, 0.5);\n    return float4(a[1], s.f, a[0], 1);",
        "struct S { float f; };\nvoid set(out float x, float k) { x = k; }\n"),
        lambda u, v: (0.25, 0.5, 0, 1)),
    Row("uniform parameters from the compile arguments",
        "float4 PS(float2 uv : TEXCOORD0, uniform float k, uniform float4 tint) : COLOR\n"
        "{\n    return float4(uv * k, tint.zy);\n}\n",
        lambda u, v: (u / 2, v / 2, 0.25, 0.5), args="0.5, float4(1, 0.5, 0.25, 1)"),
    Row("a uniform bool parameter selects a branch",
        "float4 PS(float2 uv : TEXCOORD0, uniform bool flip) : COLOR\n"
        "{\n    if (flip) return float4(uv.yx, 0, 1);\n    return float4(uv, 0, 1);\n}\n",
        lambda u, v: (v, u, 0, 1), args="true"),
    Row("a uniform int parameter counts a loop",
        "float4 PS(float2 uv : TEXCOORD0, uniform int n) : COLOR\n"
        "{\n    float s = 0;\n    for (int i = 0; i < n; i++) s += 0.25;\n    return float4(s, 0, 0, 1);\n}\n",
        lambda u, v: (0.75, 0, 0, 1), args="3"),
    Row("default parameter values", ps(
        "    return float4(f(uv.x * 0.5), f(0.1, 0.2), 0, 1);",
        "float f(float a, float b = 0.25) { return a + b; }\n"),
        lambda u, v: (u / 2 + 0.25, 0.3, 0, 1)),
    Row("overloads by vector size", ps(
        "    return float4(g(uv.x), g(uv), g(float3(uv, 0)), 1);",
        "float g(float x) { return 0.25; }\nfloat g(float2 x) { return 0.5; }\nfloat g(float3 x) { return 0.75; }\n"),
        lambda u, v: (0.25, 0.5, 0.75, 1)),
    Row("overloads by int and float", ps(
        "    return float4(h(2), h(2.0), h(uv.x), 1);",
        "float h(int x) { return 0.25; }\nfloat h(float x) { return 0.75; }\n"),
        lambda u, v: (0.25, 0.75, 0.75, 1)),
    Row("a function returning a struct", ps(
        "    return float4(make(uv).a.yx, make(uv).b, 1);",
        "struct S { float2 a; float b; };\nS make(float2 t) { S s; s.a = t; s.b = 0.5; return s; }\n"),
        lambda u, v: (v, u, 0.5, 1)),
    Row("a prototype before the definition", ps(
        "    return float4(late(uv.x), 0, 0, 1);",
        "float late(float x);\n") + "float late(float x) { return x * 0.5; }\n",
        lambda u, v: (u / 2, 0, 0, 1)),
    Row("inline functions calling each other", ps(
        "    return float4(f(uv.x), 0, 0, 1);",
        "inline float h(float x) { return x * 0.5; }\ninline float g(float x) { return h(x) + 0.25; }\n"
        "float f(float x) { return g(x); }\n"),
        lambda u, v: (u / 2 + 0.25, 0, 0, 1)),
    Row("a static local", ps(
        "    static float k = 0.5;\n    return float4(uv.x * k, 0, 0, 1);"),
        lambda u, v: (u / 2, 0, 0, 1)),
    Row("const locals and const and in parameters", ps(
        "    const float k = 0.5;\n    return float4(f(uv.x, k), 0, 0, 1);",
        "float f(const float x, in float k) { return x * k; }\n"),
        lambda u, v: (u / 2, 0, 0, 1)),
    Row("a struct input with member semantics",
        "struct PSIn { float4 c : COLOR0; float2 uv : TEXCOORD0; };\n"
        "float4 PS(PSIn i) : COLOR { return float4(i.uv, 0, 1); }\n",
        lambda u, v: (u, v, 0, 1)),
    Row("a struct output with COLOR0",
        "struct PSOut { float4 c : COLOR0; };\n"
        "PSOut PS(float2 uv : TEXCOORD0) { PSOut o; o.c = float4(uv.yx, 0, 1); return o; }\n",
        lambda u, v: (v, u, 0, 1)),
    Row("an out parameter as the output",
        "void PS(float2 uv : TEXCOORD0, out float4 c : COLOR0) { c = float4(uv, 0.5, 1); }\n",
        lambda u, v: (u, v, 0.5, 1)),
    Row("semantics in lower case",
        "float4 PS(float2 uv : texcoord0) : color { return float4(uv, 0.25, 1); }\n",
        lambda u, v: (u, v, 0.25, 1)),
    Row("a nested struct input",
        "struct Inner { float2 uv : TEXCOORD0; };\nstruct PSIn { Inner i; };\n"
        "float4 PS(PSIn p) : COLOR { return float4(p.i.uv, 0, 1); }\n",
        lambda u, v: (u, v, 0, 1)),
    Row("VPOS on ps_3_0",
        "float4 PS(float2 pos : VPOS) : COLOR { return float4(pos / 8, 0, 1); }\n",
        lambda u, v: (u, v, 0, 1), target="ps_3_0"),
    Row("VFACE on ps_3_0",
        "float4 PS(float face : VFACE, float2 uv : TEXCOORD0) : COLOR { return float4(face > 0 ? 1 : 0.25, uv, 1); }\n",
        lambda u, v: (1, u, v, 1), target="ps_3_0"),
    # -- vertex shaders -----------------------------------------------------------------------------
    Row("vs_1_1: lit and a colour output",
        "struct VO { float4 p : POSITION; float4 c : COLOR0; };\n"
        "VO VS(float4 p : POSITION) { VO o; o.p = p; o.c = lit(0.5, 0.5, 2) * float4(0.5, 1, 1, 1); return o; }\n"
        "float4 PS(float4 c : COLOR0) : COLOR { return c; }\n",
        lambda u, v: (0.5, 0.5, 0.25, 1), vs="vs_1_1"),
    Row("vs_1_1: sincos of a uniform",
        "float A = 0.5;\nstruct VO { float4 p : POSITION; float4 c : COLOR0; };\n"
        "VO VS(float4 p : POSITION) { VO o; o.p = p; float s, c; sincos(A, s, c); o.c = float4(s, c, 0, 1); return o; }\n"
        "float4 PS(float4 c : COLOR0) : COLOR { return c; }\n",
        lambda u, v: (math.sin(0.5), math.cos(0.5), 0, 1), vs="vs_1_1"),
    Row("vs_2_0: a loop over a uniform count",
        "int N = 3;\nstruct VO { float4 p : POSITION; float4 c : COLOR0; };\n"
        "VO VS(float4 p : POSITION) { VO o; o.p = p; float s = 0; for (int i = 0; i < N; i++) s += 0.25;\n"
        "  o.c = float4(s, 0, 0, 1); return o; }\n"
        "float4 PS(float4 c : COLOR0) : COLOR { return c; }\n",
        lambda u, v: (0.75, 0, 0, 1), vs="vs_2_0"),
    Row("vs_1_1: a uniform index into a constant array",
        "float4 Pal[4] = { 0.1, 0.1, 0.1, 1,  0.2, 0.4, 0.6, 1,  0.9, 0.5, 0.25, 1,  1, 1, 1, 1 };\nint Idx = 1;\n"
        "struct VO { float4 p : POSITION; float4 c : COLOR0; };\n"
        "VO VS(float4 p : POSITION) { VO o; o.p = p; o.c = Pal[Idx]; return o; }\n"
        "float4 PS(float4 c : COLOR0) : COLOR { return c; }\n",
        lambda u, v: (0.2, 0.4, 0.6, 1), vs="vs_1_1"),
    Row("vs_2_0: a texture coordinate computed per vertex",
        "struct VO { float4 p : POSITION; float2 t : TEXCOORD0; };\n"
        "VO VS(float4 p : POSITION, float2 t : TEXCOORD0) { VO o; o.p = p; o.t = t * 0.5 + 0.25; return o; }\n"
        "float4 PS(float2 t : TEXCOORD0) : COLOR { return float4(t, 0, 1); }\n",
        lambda u, v: (u / 2 + 0.25, v / 2 + 0.25, 0, 1), vs="vs_2_0"),
    Row("vs_2_0: mul by an identity uniform matrix",
        "float4x4 M = { 1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1 };\n"
        "struct VO { float4 p : POSITION; float2 t : TEXCOORD0; };\n"
        "VO VS(float4 p : POSITION, float2 t : TEXCOORD0) { VO o; o.p = mul(p, M); o.t = t; return o; }\n"
        "float4 PS(float2 t : TEXCOORD0) : COLOR { return float4(t.yx, 0, 1); }\n",
        lambda u, v: (v, u, 0, 1), vs="vs_2_0"),
    Row("vs_2_0: a uniform bool chooses a branch",
        "bool B = true;\nstruct VO { float4 p : POSITION; float4 c : COLOR0; };\n"
        "VO VS(float4 p : POSITION) { VO o; o.p = p; if (B) o.c = float4(0.25, 0.5, 0, 1); else o.c = 0; return o; }\n"
        "float4 PS(float4 c : COLOR0) : COLOR { return c; }\n",
        lambda u, v: (0.25, 0.5, 0, 1), vs="vs_2_0"),
    Row("vs_3_0 with ps_3_0: an output struct of semantics",
        "struct VO { float4 p : POSITION; float4 a : TEXCOORD3; float2 t : TEXCOORD0; };\n"
        "VO VS(float4 p : POSITION, float2 t : TEXCOORD0) { VO o; o.p = p; o.t = t; o.a = float4(0.25, 0.5, 0.75, 1); return o; }\n"
        "float4 PS(float4 a : TEXCOORD3, float2 t : TEXCOORD0) : COLOR { return float4(a.x, t, a.w); }\n",
        lambda u, v: (0.25, u, v, 1), target="ps_3_0", vs="vs_3_0"),
    # -- preprocessor ----------------------------------------------------------------------------
    Row("object and function macros",
        "#define SCALE 0.5\n#define MIX(a, b) ((a) * 0.5 + (b) * 0.5)\n"
        + ps("    return float4(uv.x * SCALE, MIX(uv.y, 1), MIX(0, 0.5), 1);"),
        lambda u, v: (u / 2, v / 2 + 0.5, 0.25, 1)),
    Row("#if #elif #else",
        "#define LEVEL 2\n#if LEVEL == 1\n#define K 0.1\n#elif LEVEL == 2\n#define K 0.5\n#else\n#define K 0.9\n#endif\n"
        + ps("    return float4(K, 0, 0, 1);"),
        lambda u, v: (0.5, 0, 0, 1)),
    Row("#ifdef #ifndef #undef and defined()",
        "#define A\n#undef A\n#define B 1\n#ifdef A\n#define K 0.1\n#endif\n#ifndef A\n#define K 0.25\n#endif\n"
        "#if defined(B) && !defined(A)\n#define L 0.75\n#endif\n" + ps("    return float4(K, L, 0, 1);"),
        lambda u, v: (0.25, 0.75, 0, 1)),
    Row("token pasting", "#define NAME(n) value##n\nstatic const float value1 = 0.25;\n"
        + ps("    return float4(NAME(1), 0, 0, 1);"),
        lambda u, v: (0.25, 0, 0, 1)),
    Row("a macro continued over lines",
        "#define SHADE(c) \\\n    float4((c).x, \\\n           (c).y, 0, 1)\n" + ps("    return SHADE(uv.yx);"),
        lambda u, v: (v, u, 0, 1)),
    Row("#pragma warning and pack_matrix",
        "#pragma warning(disable : 3206)\n#pragma pack_matrix(row_major)\n#pragma pack_matrix(column_major)\n"
        + ps("    float2x2 m = float2x2(uv, 0.25, 0.5);\n    return float4(m[1], m[0]);"),
        lambda u, v: (0.25, 0.5, u, v)),
    Row("#line", "#line 100 \"other.fx\"\n" + ps("    return float4(uv, 0, 1);"),
        lambda u, v: (u, v, 0, 1)),
    Row("a macro as an array size", "#define N 3\n" + ps(
        "    float a[N] = { 0.25, 0.5, 0.75 };\n    return float4(a[N - 1], 0, 0, 1);"),
        lambda u, v: (0.75, 0, 0, 1)),
    # -- globals -----------------------------------------------------------------------------------
    Row("a static global written in the function", ps(
        "    g.x = uv.x;\n    return g;", "static float4 g = 0.5;\n"),
        lambda u, v: (u, 0.5, 0.5, 0.5)),
    Row("a const global", ps("    return float4(K, K * 2, 0, 1);", "const float K = 0.25;\n"),
        lambda u, v: (0.25, 0.5, 0, 1)),
    Row("a uniform with a semantic and an annotation", ps(
        "    return Tint;", "float4 Tint : TINT < string UIName = \"tint\"; > = { 0.25, 0.5, 0.75, 1 };\n"),
        lambda u, v: (0.25, 0.5, 0.75, 1)),
    Row("uniform, extern and shared globals", ps(
        "    return float4(U, E, Sh, 1);",
        "uniform float U = 0.25;\nextern float E = 0.5;\nshared float Sh = 0.75;\n"),
        lambda u, v: (0.25, 0.5, 0.75, 1)),
    Row("a row_major global matrix", ps(
        "    return float4(RM[0], RM[1]);", "row_major float2x2 RM = { 0.25, 0.5, 0.75, 1 };\n"),
        lambda u, v: (0.25, 0.5, 0.75, 1)),
    Row("a column_major global matrix in a mul", ps(
        "    return float4(mul(float2(uv.x, 1), CM), 0, 1);",
        "column_major float2x2 CM = { 0.5, 0, 0.25, 1 };\n"),
        lambda u, v: (u / 2 + 0.25, 1, 0, 1)),
    Row("a uniform struct", ps(
        "    return float4(L.dir, L.k);", "struct Light { float3 dir; float k; };\n"
        "Light L = { 0, 0.25, 1, 0.5 };\n"),
        lambda u, v: (0, 0.25, 1, 0.5)),
    Row("bool and int uniforms in ps_2_0", ps(
        "    float4 c = float4(Count * 0.25, 0, 0, 1);\n    if (Flag) c.g = 0.5;\n    return c;",
        "bool Flag = true;\nint Count = 3;\n"),
        lambda u, v: (0.75, 0.5, 0, 1)),
    Row("a global array of matrices", ps(
        "    return float4(Ms[1][0], Ms[0]._m11, Ms[1]._m11);",
        "float2x2 Ms[2] = { 1, 0, 0, 0.5,  0.25, 0.75, 0, 1 };\n"),
        lambda u, v: (0.25, 0.75, 0.5, 1)),
]
