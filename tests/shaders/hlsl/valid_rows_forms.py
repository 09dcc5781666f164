"""Valid-corpus rows (valid_corpus.py): the forms real effects write that the plainer rows do
not reach: scoping as fxc had it, arrays of arrays and array parameters, local and anonymous
structs, run-time indices written, loops of every shape, discard, constant globals built from
intrinsics, casts of uniform matrices, centroid semantics, comments and line splices. A
discarded pixel keeps the clear colour (0, 0, 0, 0)."""
from __future__ import annotations

import math

from tests.shaders.hlsl.valid_corpus import Row, line, ps, t2


def k4(u: float) -> int:
    return int(u * 4 + 0.25)


ROWS: list[Row] = [
    # -- scoping ---------------------------------------------------------------------------------
    Row("a for counter used by a later loop without a declaration", ps(
        "    for (int i = 0; i < 2; i++) { }\n    for (i = 0; i < 3; i++) { }\n    return float4(i * 0.25, 0, 0, 1);"),
        lambda u, v: (0.75, 0, 0, 1)),
    Row("two loops declaring the same counter", ps(
        "    float s = 0;\n    for (int i = 0; i < 2; i++) s += 0.125;\n    for (int i = 0; i < 3; i++) s += 0.125;\n"
        "    return float4(s, 0, 0, 1);"),
        lambda u, v: (0.625, 0, 0, 1), warns=("X3078",)),
    Row("an inner block's local hides an outer one", ps(
        "    float a = 0.25;\n    {\n        float a = 0.75;\n        a += 0.125;\n    }\n    return float4(a, 0, 0, 1);"),
        lambda u, v: (0.25, 0, 0, 1)),
    Row("a local hides a global of the same name", ps(
        "    float K = uv.x;\n    return float4(K, 0, 0, 1);", "float K = 0.5;\n"),
        lambda u, v: (u, 0, 0, 1)),
    Row("an input parameter is a copy the function may write", ps(
        "    uv *= 0.5;\n    uv.y += 0.25;\n    return float4(uv, 0, 1);"),
        lambda u, v: (u / 2, v / 2 + 0.25, 0, 1)),
    Row("a struct defined inside a function", ps(
        "    struct L { float a; float2 b; };\n    L l = { 0.25, uv };\n    return float4(l.b, l.a, 1);"),
        lambda u, v: (u, v, 0.25, 1)),
    Row("an anonymous struct variable", ps(
        "    struct { float a; float b; } s;\n    s.a = uv.x;\n    s.b = 0.5;\n    return float4(s.a, s.b, 0, 1);"),
        lambda u, v: (u, 0.5, 0, 1)),
    Row("a struct declared with its variable", ps(
        "    struct P { float2 q; } p = { uv.yx };\n    return float4(p.q, 0, 1);"),
        lambda u, v: (v, u, 0, 1)),
    Row("empty statements and blocks", ps(
        "    ;\n    { }\n    float a = uv.x;;\n    if (a > 2) { } else ;\n    return float4(a, 0, 0, 1);"),
        lambda u, v: (u, 0, 0, 1)),
    Row("a dangling else binds to the nearest if", ps(
        "    float c = 0.1;\n    if (uv.x > 0.5)\n        if (uv.y > 0.5) c = 0.9;\n        else c = 0.5;\n"
        "    return float4(c, 0, 0, 1);"),
        lambda u, v: ((0.9 if v > 0.5 else 0.5) if u > 0.5 else 0.1, 0, 0, 1)),
    Row("an assignment inside a condition", ps(
        "    float a;\n    float c = 0;\n    if ((a = uv.x * 2) > 1) c = 0.5;\n    return float4(a * 0.5, c, 0, 1);"),
        lambda u, v: (u, 0.5 if u > 0.5 else 0, 0, 1)),
    # -- arrays --------------------------------------------------------------------------------------
    Row("an array of arrays", ps(
        "    float a[2][3] = { { 0.1, 0.2, 0.3 }, { 0.4, 0.5, 0.6 } };\n    return float4(a[1][2], a[0][1], a[1][0], 1);"),
        lambda u, v: (0.6, 0.2, 0.4, 1)),
    Row("an array parameter", ps(
        "    float w[3] = { 0.25, 0.5, 0.125 };\n    return float4(sum(w), w[1], 0, 1);",
        "float sum(float a[3]) { return a[0] + a[1] + a[2]; }\n"),
        lambda u, v: (0.875, 0.5, 0, 1)),
    Row("an out array parameter", ps(
        "    float w[2];\n    fill(w, uv.x);\n    return float4(w[0], w[1], 0, 1);",
        "void fill(out float a[2], float x) { a[0] = x; a[1] = x * 0.5; }\n"),
        lambda u, v: (u, u / 2, 0, 1)),
    Row("a static const int sizes an array and bounds a loop", ps(
        "    float a[N];\n    for (int i = 0; i < N; i++) a[i] = (i + 1) * 0.25;\n    return float4(a[0], a[1], a[2], 1);",
        "static const int N = 3;\n"),
        lambda u, v: (0.25, 0.5, 0.75, 1)),
    Row("a global static const array with an implicit size", ps(
        "    return float4(D[2], D[0].x);", "static const float3 D[] = { { 0.1, 0.2, 0.3 }, { 0, 0, 0 }, { 0.5, 0.25, 0.75 } };\n"),
        lambda u, v: (0.5, 0.25, 0.75, 0.1)),
    Row("a vector lane written at a run-time index", ps(
        "    float4 c = 0;\n    int k = (int)(uv.x * 4 + 0.25);\n    c[k] = 0.5;\n    return c;"),
        lambda u, v: tuple(0.5 if i == k4(u) else 0 for i in range(4))),
    Row("a struct member array read at a run-time index", ps(
        "    S s = { 0.1, 0.2, 0.3, 0.4, 0.5 };\n    int k = (int)(uv.x * 4 + 0.25);\n    return float4(s.w[k], s.b, 0, 1);",
        "struct S { float w[4]; float b; };\n"),
        lambda u, v: ((k4(u) + 1) * 0.1, 0.5, 0, 1)),
    Row("a uniform array read at a uniform index in ps_2_0", ps(
        "    return C[Idx];", "float4 C[3] = { 0.1, 0.2, 0.3, 1,  0.4, 0.5, 0.6, 1,  0.7, 0.8, 0.9, 1 };\nint Idx = 2;\n"),
        lambda u, v: (0.7, 0.8, 0.9, 1)),
    Row("a static array written then read at a run-time index", ps(
        "    int k = (int)(uv.y * 4 + 0.25);\n    G[1] = 0.5;\n    return float4(G[k], 0, 0, 1);",
        "static float G[4] = { 0.1, 0.2, 0.3, 0.4 };\n"),
        lambda u, v: ((0.1, 0.5, 0.3, 0.4)[k4(v)], 0, 0, 1)),
    Row("partial writes through array elements", ps(
        "    float4 a[2] = { (float4)0, (float4)1 };\n    a[0].xy = uv;\n    a[1].zw *= 0.5;\n    return float4(a[0].xy, a[1].zw);"),
        lambda u, v: (u, v, 0.5, 0.5)),
    Row("a local array of matrices", ps(
        "    float2x2 m[2];\n    m[0] = float2x2(uv, 0, 0);\n    m[1] = 0.5;\n    return float4(m[0][0], m[1]._m01, m[0]._m11);"),
        lambda u, v: (u, v, 0.5, 0)),
    Row("a matrix column at a run-time index", ps(
        "    float2x4 m = { 0.1, 0.2, 0.3, 0.4,  0.5, 0.6, 0.7, 0.8 };\n    int k = (int)(uv.x * 4 + 0.25);\n"
        "    return float4(m[1][k], m[0][k], 0, 1);"),
        lambda u, v: (0.5 + 0.1 * k4(u), 0.1 + 0.1 * k4(u), 0, 1)),
    # -- matrices ----------------------------------------------------------------------------------
    Row("matrix arithmetic per component", ps(
        "    float2x2 a = float2x2(uv, 0.5, 0.25);\n    float2x2 b = a * a + 0.125 - a * 0.5;\n"
        "    return float4(b[0], b[1]);"),
        lambda u, v: (u * u + 0.125 - u / 2, v * v + 0.125 - v / 2, 0.125, 0.0625 + 0.125 - 0.125)),
    Row("matrix comparisons", ps(
        "    float2x2 a = float2x2(uv, 0.5, 0.25);\n    bool2x2 c = a > 0.3;\n"
        "    return float4(c[0], any(a != a), all(a == a));"),
        lambda u, v: (float(u > 0.3), float(v > 0.3), 0, 1)),
    Row("a uniform float4x4 cast to float3x3 in a mul", ps(
        "    float3 n = mul(float3(uv, 0.5), (float3x3)W);\n    return float4(n, 1);",
        "float4x4 W = { 0, 1, 0, 0,  1, 0, 0, 0,  0, 0, 1, 0,  9, 9, 9, 1 };\n"),
        lambda u, v: (v, u, 0.5, 1)),
    Row("int and bool matrices", ps(
        "    int2x2 i = { 1, 2, 3, 4 };\n    bool2x2 b = { true, false, false, true };\n"
        "    return float4(i[1] * 0.125, b[0].x, b[1].x);"),
        lambda u, v: (0.375, 0.5, 1, 0)),
    Row("half matrices and mixed half and float", ps(
        "    half3x3 m = { 0.5, 0, 0,  0, 0.5, 0,  0, 0, 1 };\n    float3 r = mul(half3(uv, 0.25), m);\n    return float4(r, 1);"),
        lambda u, v: (u / 2, v / 2, 0.25, 1)),
    Row("repeated matrix swizzle components", ps(
        "    float2x2 m = float2x2(uv, 0.25, 0.5);\n    return float4(m._m00_m00, m._22_11);"),
        lambda u, v: (u, u, 0.5, u)),
    Row("a matrix member of a struct swizzled", ps(
        "    S s;\n    s.m = float2x2(uv, 0.25, 0.5);\n    return float4(s.m._m01_m10, s.m[1].y, 1);",
        "struct S { float2x2 m; };\n"),
        lambda u, v: (v, 0.25, 0.5, 1)),
    Row("pack_matrix(row_major) for a uniform in mul", "#pragma pack_matrix(row_major)\n" + ps(
        "    return float4(mul(float2(uv.x, 1), M), 0, 1);", "float2x2 M = { 0.5, 0, 0.25, 1 };\n"),
        lambda u, v: (u / 2 + 0.25, 1, 0, 1)),
    # -- loops -------------------------------------------------------------------------------------
    Row("a float loop counter", ps(
        "    float s = 0;\n    for (float f = 0; f < 1; f += 0.25) s += 0.125;\n    return float4(s, 0, 0, 1);"),
        lambda u, v: (0.5, 0, 0, 1)),
    Row("a counting-down loop with a step of two", ps(
        "    float s = 0;\n    for (int i = 6; i >= 0; i -= 2) s += i * 0.03125;\n    return float4(s, 0, 0, 1);"),
        lambda u, v: (12 * 0.03125, 0, 0, 1)),
    Row("a side effect in a while condition", ps(
        "    int i = 0;\n    float s = 0;\n    while (i++ < 3) s += 0.25;\n    return float4(s, i * 0.125, 0, 1);"),
        lambda u, v: (0.75, 0.5, 0, 1)),
    Row("do while (false)", ps(
        "    float s = 0;\n    do { s += uv.x; } while (false);\n    return float4(s, 0, 0, 1);"),
        lambda u, v: (u, 0, 0, 1)),
    Row("a break inside a switch inside a loop leaves the switch", ps(
        "    float s = 0;\n    for (int i = 0; i < 3; i++)\n    {\n        switch (i)\n        {\n"
        "        case 1: s += 0.5; break;\n        default: s += 0.125; break;\n        }\n    }\n    return float4(s, 0, 0, 1);"),
        lambda u, v: (0.75, 0, 0, 1)),
    Row("returns inside switch cases", ps(
        "    int k = (int)(uv.x * 4 + 0.25);\n    switch (k)\n    {\n    case 0: return float4(0.25, 0, 0, 1);\n"
        "    case 3: return float4(0, 0.75, 0, 1);\n    }\n    return float4(0, 0, 0.5, 1);"),
        lambda u, v: {0: (0.25, 0, 0, 1), 3: (0, 0.75, 0, 1)}.get(k4(u), (0, 0, 0.5, 1))),
    Row("a switch on a uniform int", ps(
        "    float c = 0;\n    switch (Mode)\n    {\n    case 1: c = 0.25; break;\n    case 2: c = 0.5; break;\n"
        "    default: c = 1; break;\n    }\n    return float4(c, 0, 0, 1);", "int Mode = 2;\n"),
        lambda u, v: (0.5, 0, 0, 1)),
    Row("nested switches", ps(
        "    int a = (int)(uv.x * 4 + 0.25);\n    int b = (int)(uv.y * 4 + 0.25);\n    float c = 0;\n"
        "    switch (a)\n    {\n    case 0:\n        switch (b) { case 1: c = 0.25; break; default: c = 0.5; break; }\n"
        "        break;\n    default: c = 0.75; break;\n    }\n    return float4(c, 0, 0, 1);"),
        lambda u, v: ((0.25 if k4(v) == 1 else 0.5) if k4(u) == 0 else 0.75, 0, 0, 1)),
    Row("a function called in a loop writes an out argument", ps(
        "    float acc = 0, last = 0;\n    for (int i = 1; i <= 3; i++) step3(i * 0.125, acc, last);\n"
        "    return float4(acc, last, 0, 1);",
        "void step3(float x, inout float a, out float l) { a += x; l = x; }\n"),
        lambda u, v: (0.75, 0.375, 0, 1)),
    Row("an early return from a void function", ps(
        "    float4 c = 0.5;\n    paint(c, uv.x);\n    return c;",
        "void paint(inout float4 c, float x) { if (x < 0.5) return; c.r = x; }\n"),
        lambda u, v: (u if u >= 0.5 else 0.5, 0.5, 0.5, 0.5)),
    # -- discard -------------------------------------------------------------------------------
    Row("discard", ps("    if (uv.x < 0.5) discard;\n    return float4(uv, 0, 1);"),
        lambda u, v: (0, 0, 0, 0) if u < 0.5 else (u, v, 0, 1)),
    Row("clip of a texture's alpha", ps(
        "    float4 c = tex2D(sT2, uv);\n    clip(c.r - 0.5);\n    return c;"),
        lambda u, v: tuple(t2(u, v)) if t2(u, v)[0] > 0.5 else (0, 0, 0, 0)),
    # -- constant globals ---------------------------------------------------------------------------
    Row("a static const from other constants", ps(
        "    return float4(A, B, 0, 1);", "static const float A = 0.25;\nstatic const float B = A * 2 + 0.25;\n"),
        lambda u, v: (0.25, 0.75, 0, 1)),
    Row("a static const from an intrinsic", ps(
        "    return float4(D, 1);", "static const float3 D = normalize(float3(3, 0, 4));\n"),
        lambda u, v: (0.6, 0, 0.8, 1)),
    Row("a uniform default from a constant expression", ps(
        "    return float4(K, L, 1);", "float K = 0.5 * 0.5;\nfloat2 L = float2(1, 2) / 4;\n"),
        lambda u, v: (0.25, 0.25, 0.5, 1)),
    Row("a sampler with a register and Texture in parentheses",
        "texture Tx;\nsampler2D S : register(s1) = sampler_state { Texture = (T2tex); MinFilter = Point;"
        " MagFilter = Point; MipFilter = None; };\n" + ps("    return tex2D(S, uv); // sT2"),
        lambda u, v: t2(u, v)),
    Row("a string global and annotations left unused", ps(
        "    return float4(uv, 0, 1);", "string Description = \"a test\";\nfloat Unused < string UIWidget = \"slider\"; float UIMin = 0; > = 1;\n"),
        lambda u, v: (u, v, 0, 1)),
    # -- semantics ----------------------------------------------------------------------------------
    Row("TEXCOORD without an index is TEXCOORD0",
        "float4 PS(float2 uv : TEXCOORD) : COLOR0 { return float4(uv, 0.5, 1); }\n",
        lambda u, v: (u, v, 0.5, 1)),
    Row("in and out modifiers on the entry point",
        "void PS(in float2 uv : TEXCOORD0, out float4 c : COLOR) { c = float4(uv.yx, 0.25, 1); }\n",
        lambda u, v: (v, u, 0.25, 1)),
    Row("a _centroid semantic on ps_3_0",
        "float4 PS(float2 uv : TEXCOORD0_centroid) : COLOR { return float4(uv, 0, 1); }\n",
        lambda u, v: (u, v, 0, 1), target="ps_3_0", asm="dcl_texcoord_centroid v0"),
    Row("a _centroid semantic on ps_2_0",
        "float4 PS(float2 uv : TEXCOORD0_centroid) : COLOR { return float4(uv.yx, 0, 1); }\n",
        lambda u, v: (v, u, 0, 1), asm="dcl_centroid t0"),
    Row("a semantic on a parameter of a helper is ignored", ps(
        "    return float4(f(uv), 0, 1);", "float2 f(float2 t : TEXCOORD5) { return t.yx; }\n"),
        lambda u, v: (v, u, 0, 1)),
    # -- expressions -----------------------------------------------------------------------------
    Row("a swizzle of a texture read and a premultiply", ps(
        "    float4 c = tex2D(sT2, uv);\n    c.rgb *= c.a * 0.5;\n    return float4(c.rgb, tex2D(sT2, uv).g);"),
        lambda u, v: (t2(u, v)[0] / 2, t2(u, v)[1] / 2, 0.25, t2(u, v)[1])),
    Row("a swizzle of a dot product", ps("    return float4(dot(uv, 0.5).xxx, 1);"),
        lambda u, v: ((u + v) / 2, (u + v) / 2, (u + v) / 2, 1)),
    Row("a negated swizzle and an increment of a component", ps(
        "    float4 c = float4(-uv.yx + 1, 0, 0);\n    ++c.z;\n    c.w++;\n    return c * float4(1, 1, 0.5, 0.25);"),
        lambda u, v: (1 - v, 1 - u, 0.5, 0.25)),
    Row("bool arguments of a vector constructor", ps("    return float4(true, false, uv.x > 0.5, 1);"),
        lambda u, v: (1, 0, float(u > 0.5), 1)),
    Row("int literals where floats are taken", ps(
        "    return float4(clamp(uv.x * 2, 0, 1), pow(uv.y, 2), max(uv.x, 0), lerp(0, 1, uv.y));"),
        lambda u, v: (min(2 * u, 1), v * v, u, v)),
    Row("a ternary with int and float branches", ps(
        "    float a = uv.x > 0.5 ? 1 : 0.25;\n    int b = uv.y > 0.5 ? 2 : 1;\n    return float4(a, b * 0.25, 0, 1);"),
        lambda u, v: (1 if u > 0.5 else 0.25, 0.5 if v > 0.5 else 0.25, 0, 1)),
    Row("a long float literal", ps(
        "    return float4(3.14159265358979323846 / 4, 0.333333333333333333 * 3 - 0.5, 0, 1);"),
        lambda u, v: (math.pi / 4, 0.5, 0, 1)),
    Row("literal suffixes on integers", ps("    return float4(1L * 0.25, 2l * 0.25, 3U * 0.25, 1);"),
        lambda u, v: (0.25, 0.5, 0.75, 1)),
    Row("an exponent with a sign", ps("    return float4(2.5e-1, 5E+0 * 0.1, 1e+0 * 0.75, 1);"),
        lambda u, v: (0.25, 0.5, 0.75, 1)),
    # -- preprocessor and lexing ---------------------------------------------------------------------
    Row("#if 0 hides text that does not parse", "#if 0\nthis is not HLSL {\n#error never\n#endif\n"
        + ps("    return float4(uv, 0, 1);"),
        lambda u, v: (u, v, 0, 1)),
    Row("a nested function-like macro", "#define SQ(x) ((x) * (x))\n#define QUAD(x) SQ(SQ(x))\n"
        + ps("    return float4(QUAD(uv.x), SQ(uv.y), 0, 1);"),
        lambda u, v: (u ** 4, v * v, 0, 1)),
    Row("block comments inside an expression and across lines", ps(
        "    return float4(uv.x /* the u */ * 0.5, /* a\n       comment */ uv.y, 0, 1);"),
        lambda u, v: (u / 2, v, 0, 1)),
    Row("a line splice outside a macro", ps("    return float4(uv.x * \\\n0.5, uv.y, 0, 1);"),
        lambda u, v: (u / 2, v, 0, 1)),
    Row("a macro whose body uses another defined later", "#define A (B * 2)\n#define B 0.25\n"
        + ps("    return float4(A, B, 0, 1);"),
        lambda u, v: (0.5, 0.25, 0, 1)),
    Row("#pragma once and an unknown pragma", "#pragma once\n#pragma message(\"hello\")\n"
        + ps("    return float4(uv, 0, 1);"),
        lambda u, v: (u, v, 0, 1)),
]

ROWS += [
    # -- more forms: typedefs, uniforms of the entry, truncations real shaders warn on --------
    Row("a typedef of a vector template", ps(
        "    vec4 c = vec4(uv, 0.25, 1);\n    return c;", "typedef vector<half, 4> vec4;\n"),
        lambda u, v: (u, v, 0.25, 1)),
    Row("a C-style typedef of an anonymous struct", ps(
        "    Pair p;\n    p.a = uv.x;\n    p.b = 0.5;\n    return float4(p.a, p.b, 0, 1);",
        "typedef struct { float a; float b; } Pair;\n"),
        lambda u, v: (u, 0.5, 0, 1)),
    Row("a global struct declared with its variable", ps(
        "    return float4(G.a, G.b, 0, 1);", "struct GS { float a; float b; } G = { 0.25, 0.5 };\n"),
        lambda u, v: (0.25, 0.5, 0, 1)),
    Row("a uniform parameter of the entry with no compile argument",
        "float4 PS(float2 uv : TEXCOORD0, uniform float4 tint) : COLOR\n{\n    return float4(uv, 0, 1) + tint;\n}\n",
        lambda u, v: (u, v, 0, 1)),
    Row("a texture read into a float3 warns X3206", ps(
        "    float3 c = tex2D(sT2, uv);\n    return float4(c, 1);"),
        lambda u, v: (t2(u, v)[0], t2(u, v)[1], 0.5, 1), warns=("X3206",)),
    Row("a compound assignment from a longer vector warns X3206", ps(
        "    float3 a = 0.25;\n    a += float4(uv, 0.5, 1);\n    return float4(a, 1);"),
        lambda u, v: (u + 0.25, v + 0.25, 0.75, 1), warns=("X3206",)),
    Row("a ternary with a vector condition and scalar results", ps(
        "    float2 r = (uv > 0.5) ? 1 : 0.25;\n    return float4(r, 0, 1);"),
        lambda u, v: (1 if u > 0.5 else 0.25, 1 if v > 0.5 else 0.25, 0, 1)),
    Row("if on all() and any() of a comparison", ps(
        "    float c = 0.1;\n    if (all(uv > 0.3)) c = 0.5;\n    if (any(uv > 0.8)) c += 0.25;\n    return float4(c, 0, 0, 1);"),
        lambda u, v: ((0.5 if u > 0.3 and v > 0.3 else 0.1) + (0.25 if u > 0.8 or v > 0.8 else 0), 0, 0, 1)),
    Row("a while with a compound condition", ps(
        "    int i = 0;\n    float s = 0;\n    while (i < 8 && s < 0.5) { s += 0.125; i++; }\n    return float4(s, i * 0.125, 0, 1);"),
        lambda u, v: (0.5, 0.5, 0, 1)),
    Row("not of a bool vector", ps(
        "    bool2 b = uv > 0.5;\n    return float4(!b, 0, 1);"),
        lambda u, v: (float(u <= 0.5), float(v <= 0.5), 0, 1)),
    Row("lerp by a bool", ps(
        "    return float4(lerp(0.25, 0.75, uv.x > 0.5), 0, 0, 1);"),
        lambda u, v: (0.75 if u > 0.5 else 0.25, 0, 0, 1)),
    Row("sincos into the lanes of a vector", ps(
        "    float2 sc;\n    sincos(uv.x, sc.x, sc.y);\n    return float4(sc, 0, 1);"),
        lambda u, v: (math.sin(u), math.cos(u), 0, 1)),
    Row("a matrix row written through a swizzle", ps(
        "    float3x3 m = 0;\n    m[1].yz = uv;\n    m[2].x = 0.5;\n    return float4(m[1], m[2].x);"),
        lambda u, v: (0, u, v, 0.5)),
    Row("vector<int, 2> and matrix<half, 2, 2>", ps(
        "    vector<int, 2> i = int2(1, 3);\n    matrix<half, 2, 2> m = { 0.5, 0, 0, 0.25 };\n"
        "    return float4(i * 0.25, m._m00, m._m11);"),
        lambda u, v: (0.25, 0.75, 0.5, 0.25)),
    Row("a redundant constructor around a vector", ps(
        "    return float4(float4(float2(uv), float2(0.25, 0.5)));"),
        lambda u, v: (u, v, 0.25, 0.5)),
    Row("a macro argument with a comma inside parentheses", "#define FIRST(v) (v).x\n"
        + ps("    return float4(FIRST(float2(uv.y, 0.5)), 0, 0, 1);"),
        lambda u, v: (v, 0, 0, 1)),
    Row("a struct with an array of structs from a flat list", ps(
        "    Outer o = { 0.1, 0.2, 0.3, 0.4, 0.5 };\n    return float4(o.items[1].a, o.items[0].b, o.k, 1);",
        "struct Item { float a; float b; };\nstruct Outer { Item items[2]; float k; };\n"),
        lambda u, v: (0.3, 0.2, 0.5, 1)),
    Row("return (T)0 of a struct", ps(
        "    return Zero().c + float4(uv, 0, 1);", "struct Z { float4 c; };\nZ Zero() { return (Z)0; }\n"),
        lambda u, v: (u, v, 0, 1)),
    Row("a void entry with an out struct", "struct PO { float4 c : COLOR0; };\n"
        "void PS(float2 uv : TEXCOORD0, out PO o) { o.c = float4(uv, 0.5, 1); }\n",
        lambda u, v: (u, v, 0.5, 1)),
    Row("a uniform array summed in a [loop] on ps_3_0", ps(
        "    float s = 0;\n    [loop] for (int i = 0; i < 4; i++) s += W[i].x * uv.x;\n    return float4(s, 0, 0, 1);",
        "float4 W[4] = { 0.1, 0, 0, 0,  0.2, 0, 0, 0,  0.3, 0, 0, 0,  0.4, 0, 0, 0 };\n"),
        lambda u, v: (u, 0, 0, 1), target="ps_3_0"),
    Row("a [loop] with a run-time break on ps_3_0", ps(
        "    float s = 0;\n    [loop] for (int i = 0; i < 8; i++) { if (s > uv.x + 0.0625) break; s += 0.125; }\n"
        "    return float4(s, 0, 0, 1);"),
        lambda u, v: (math.floor((u + 0.0625) / 0.125) * 0.125 + 0.125, 0, 0, 1), target="ps_3_0"),
    Row("a [branch] with a texture read by tex2Dlod inside on ps_3_0", ps(
        "    float4 c = 0;\n    [branch] if (uv.x > 0.5) c = tex2Dlod(sT2, float4(uv, 0, 0));\n    return c;"),
        lambda u, v: tuple(t2(u, v)) if u > 0.5 else (0, 0, 0, 0), target="ps_3_0"),
    Row("a const global array read at a run-time index", ps(
        "    return float4(K[(int)(uv.y * 4 + 0.25)], 0, 0, 1);", "const float K[4] = { 0.2, 0.4, 0.6, 0.8 };\n"),
        lambda u, v: ((k4(v) + 1) * 0.2, 0, 0, 1)),
    Row("sign of an int vector", ps(
        "    int4 s = sign(int4(-3, 0, 2, (int)(uv.x * 8 + 0.5) - 4));\n    return s * 0.25 + 0.5;"),
        lambda u, v: (0.25, 0.5, 0.75, 0.5 + 0.25 * (1 if round(u * 8) > 4 else -1 if round(u * 8) < 4 else 0))),
    Row("pow with a zero base and a constant exponent", ps(
        "    return float4(pow(uv.x, 0.5), pow(0, 2) + 0.25, pow(uv.y, 1), pow(2, 0) * 0.5);"),
        lambda u, v: (math.sqrt(u), 0.25, v, 0.5)),
    Row("a struct parameter passed and returned", ps(
        "    S s = { uv, 0.5 };\n    S t = twice(s);\n    return float4(t.a, t.b, 1);",
        "struct S { float2 a; float b; };\nS twice(S s) { s.a *= 0.5; s.b *= 0.5; return s; }\n"),
        lambda u, v: (u / 2, v / 2, 0.25, 1)),
    Row("nested calls with out arguments in a loop", ps(
        "    float a = 0;\n    for (int i = 0; i < 3; i++) { float b; half_of(0.5, b); a += b; }\n"
        "    return float4(a, 0, 0, 1);",
        "void half_of(float x, out float y) { y = x * 0.5; }\n"),
        lambda u, v: (0.75, 0, 0, 1)),
    Row("a sampler array read at constant indices",
        "texture TA;\nsampler2D SA[2] = { sampler_state { Texture = <T2tex>; MinFilter = Point; MagFilter = Point;"
        " MipFilter = None; }, sampler_state { Texture = <Linetex>; MinFilter = Point; MagFilter = Point;"
        " MipFilter = None; } };\n" + ps("    return tex2D(SA[0], uv) * 0.5 + tex2D(SA[1], uv + 0.0625) * 0.5; // sT2"),
        lambda u, v: (t2(u, v) + line(u + 0.0625)) / 2),
]

ROWS += [
    # -- from vkd3d-shader's tests (tests/hlsl/*.shader_test, their fxc probes): our programs --
    Row("a user function named like an intrinsic is called in its place", ps(
        "    return float4(max(0.1, 0.2), max(float2(0.1, 0.2), float2(0.3, 0.4)));",
        "float2 max(float2 a, float2 b) { return a + b; }\n"),
        lambda u, v: (0.3, 0.3, 0.4, 0.6)),
    Row("indexing an expression, a swizzle and a call's result", ps(
        "    float4 a = float4(uv, 0.25, 0.5);\n    float4 b = 0.25;\n    int k = (int)(uv.x * 4 + 0.25);\n"
        "    return float4((a + b)[1], a.wyxz[3], f(a)[0], a.wyxz[k]);",
        "float4 f(float4 x) { return x; }\n"),
        lambda u, v: (v + 0.25, 0.25, u, (0.5, v, u, 0.25)[k4(u)])),
    Row("an out argument converted to an int vector", ps(
        "    int4 x;\n    fill(x);\n    return x * 0.25;", "float4 F = { 0.25, 1.5, 2.75, 1 };\n"
        "void fill(out float4 o) { o = F; }\n"),
        lambda u, v: (0, 0.25, 0.5, 0.25)),
    Row("an out argument through a cast", ps(
        "    int4 x;\n    fill((float4)x);\n    float4 y;\n    fill((int4)y);\n    return x * 0.125 + y * 0.125;",
        "float4 F = { 0.25, 1.5, 2.75, 1 };\nvoid fill(out float4 o) { o = F; }\n"),
        lambda u, v: (0, 0.25, 0.5, 0.25)),
]

ROWS += [
    # -- ps_2_a (GeForce FX: gradients, 512 slots) and vertex-shader addressing -----------------
    Row("ddx and ddy on ps_2_a", ps(
        "    return float4(ddx(uv.x) * 4, ddy(uv.y) * 4, abs(ddx(uv.y)), 1);"),
        lambda u, v: (0.5, 0.5, 0, 1), target="ps_2_a"),
    Row("a shader past ps_2_0's 64 slots on ps_2_a", ps(
        "    float s = 0;\n    float x = uv.x;\n    [unroll] for (int i = 0; i < 40; i++) { s += x * 0.0125; x = x * 0.99 + 0.01; }\n"
        "    return float4(s, 0, 0, 1);"),
        lambda u, v: (sum((u * 0.99 ** i + (1 - 0.99 ** i)) * 0.0125 for i in range(40)), 0, 0, 1),
        target="ps_2_a"),
    Row("vs_2_0: a constant array indexed per vertex (a0)",
        "float4 Pal[4] = { 0.1, 0.2, 0.3, 1,  0.2, 0.4, 0.6, 1,  0.3, 0.6, 0.9, 1,  0.9, 0.5, 0.25, 1 };\n"
        "struct VO { float4 p : POSITION; float4 c : COLOR0; };\n"
        "VO VS(float4 p : POSITION, float2 t : TEXCOORD0) { VO o; o.p = p; o.c = Pal[(int)(t.x * 3 + 0.5)]; return o; }\n"
        "float4 PS(float4 c : COLOR0) : COLOR { return c; }\n",
        lambda u, v: tuple(a + (b - a) * u for a, b in zip((0.1, 0.2, 0.3, 1), (0.9, 0.5, 0.25, 1))),
        vs="vs_2_0"),
    Row("vs_2_0: a loop over a uniform count reading a constant array",
        "int N = 3;\nfloat4 L[4] = { 0.125, 0, 0, 0,  0, 0.25, 0, 0,  0, 0, 0.5, 0,  1, 1, 1, 1 };\n"
        "struct VO { float4 p : POSITION; float4 c : COLOR0; };\n"
        "VO VS(float4 p : POSITION) { VO o; o.p = p; float4 c = float4(0, 0, 0, 1);\n"
        "  for (int i = 0; i < N; i++) c += L[i];\n  o.c = c; return o; }\n"
        "float4 PS(float4 c : COLOR0) : COLOR { return c; }\n",
        lambda u, v: (0.125, 0.25, 0.5, 1), vs="vs_2_0"),
    Row("vs_1_1: an array of matrices indexed per vertex",
        "float4x4 Bones[2] = { 1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1,\n"
        "                      0.5, 0, 0, 0,  0, 0.5, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1 };\n"
        "struct VO { float4 p : POSITION; float4 c : COLOR0; };\n"
        "VO VS(float4 p : POSITION, float2 t : TEXCOORD0) { VO o; o.p = p;\n"
        "  float4x4 m = Bones[(int)(t.y + 0.5)]; o.c = float4(m._m00, m._m11, 0, 1); return o; }\n"
        "float4 PS(float4 c : COLOR0) : COLOR { return c; }\n",
        lambda u, v: (1 - v / 2, 1 - v / 2, 0, 1), vs="vs_1_1"),
]

ROWS += [
    # -- integer and rounding semantics on run-time values (uniforms, not folded) ----------------
    Row("int division and modulo of negative run-time ints", ps(
        "    return float4(X / Y, -X / Y, X % Y, -X % Y) / 16 + 0.5;", "int X = 42;\nint Y = 5;\n"),
        lambda u, v: (1.0, 0.0, 0.625, 0.375)),
    Row("int division by a negative run-time int", ps(
        "    return float4(X / -Y, -X / -Y, X % -Y, -X % -Y) / 16 + 0.5;", "int X = 42;\nint Y = 5;\n"),
        lambda u, v: (0.0, 1.0, 0.625, 0.375)),
    Row("int vectors divided and reduced", ps(
        "    return float4(A / B, C % B) / 8;", "int2 A = { 5, 15 };\nint2 B = { 2, 5 };\nint2 C = { 3, 8 };\n"),
        lambda u, v: (0.25, 0.375, 0.125, 0.375)),
    Row("round of negative run-time values", ps(
        "    return round(U) / 16 + 0.5;", "float4 U = { -0.4, -6.6, 7.6, 3.4 };\n"),
        lambda u, v: (0.5, 0.0625, 1.0, 0.6875)),
    Row("float to int of negative run-time values", ps(
        "    int4 i = U;\n    return i / 16.0 + 0.5;", "float4 U = { -0.4, -6.6, 7.6, 3.4 };\n"),
        lambda u, v: (0.5, 0.125, 0.9375, 0.6875)),
    Row("floor ceil frac of negative run-time values", ps(
        "    return float4(floor(U.y) / 16 + 0.5, ceil(U.y) / 16 + 0.5, frac(U.y), frac(U.x));",
        "float4 U = { -0.4, -6.6, 7.6, 3.4 };\n"),
        lambda u, v: (0.0625, 0.125, 0.4, 0.6)),
    Row("a bool from a negative float and from a uniform int", ps(
        "    bool a = U.x;\n    bool b = Z;\n    return float4(a, b, (bool)U.y * 0.5, !Z);", "float4 U = { -0.4, 0, 0, 0 };\nint Z = 0;\n"),
        lambda u, v: (1, 0, 0, 1)),
]

ROWS += [
    # -- "HLSL expressions never short-circuit ... all sides of the expression are always
    # evaluated" (the reference's Operators page) ------------------------------------------
    Row("&& and || evaluate both sides", ps(
        "    int a = 0, b = 0, c = 0;\n    bool t = (a++ > 0) && (b++ > 0);\n    bool f = (c++ == 0) || (a++ > 5);\n"
        "    return float4(a * 0.25, b * 0.25, c * 0.25, t * 0.5 + f * 0.25);"),
        lambda u, v: (0.5, 0.25, 0.25, 0.25)),
    Row("a ternary evaluates both results", ps(
        "    float a = 0, b = 0;\n    float c = (uv.x > 2) ? (a += 0.25) : (b += 0.5);\n    return float4(a, b, c, 1);"),
        lambda u, v: (0.25, 0.5, 0.5, 1)),
    Row("an assignment's value in an expression", ps(
        "    float a;\n    float b = (a = uv.x) * 0.5 + 0.25;\n    return float4(a, b, 0, 1);"),
        lambda u, v: (u, u / 2 + 0.25, 0, 1)),
    Row("__LINE__ in the text", "\n" + ps("    return float4(__LINE__ / 8.0, 0, 0, 1);"),
        lambda u, v: (5 / 8, 0, 0, 1)),
    Row("bool vectors cast to int and float vectors", ps(
        "    bool3 b = bool3(true, uv.x > 0.5, false);\n    int3 i = (int3)b;\n    float3 f = b;\n"
        "    return float4(i.x * 0.5, f.y, f.z + 0.25, 1);"),
        lambda u, v: (0.5, float(u > 0.5), 0.25, 1)),
    Row("transpose of a uniform row_major matrix", ps(
        "    float2x2 t = transpose(M);\n    return float4(t[0], t[1]);", "row_major float2x2 M = { 0.25, 0.5, 0.75, 1 };\n"),
        lambda u, v: (0.25, 0.75, 0.5, 1)),
    Row("an int compared with a float", ps(
        "    int i = 2;\n    return float4(i > 1.5, i < 2.5, i == 2.0, (float)(i != 2));"),
        lambda u, v: (1, 1, 1, 0)),
    Row("#undef and a macro defined again", "#define K 0.25\n#undef K\n#define K 0.75\n"
        + ps("    return float4(K, 0, 0, 1);"),
        lambda u, v: (0.75, 0, 0, 1)),
]

ROWS += [
    # -- compile arguments and sizes ----------------------------------------------------------
    Row("compile arguments that are expressions and globals",
        "float4 Tint = { 0.25, 0.5, 0.75, 1 };\n"
        "float4 PS(float2 uv : TEXCOORD0, uniform float4 t, uniform float k) : COLOR\n"
        "{\n    return float4(t.xy, uv.x * k, t.w);\n}\n",
        lambda u, v: (0.25, 0.5, u / 2, 1), args="Tint, 2 * 0.25"),
    Row("local array sizes from constant expressions", ps(
        "    float a[N * 2];\n    float b[2u];\n    a[3] = 0.5;\n    b[1] = 0.25;\n    return float4(a[3], b[1], N * 0.25, 1);",
        "static const int N = 2;\n"),
        lambda u, v: (0.5, 0.25, 0.5, 1)),
    Row("a static const struct global", ps(
        "    return float4(M.colour, M.k);", "struct Mat { float3 colour; float k; };\n"
        "static const Mat M = { 0.25, 0.5, 0.75, 1 };\n"),
        lambda u, v: (0.25, 0.5, 0.75, 1)),
    Row("an untyped sampler parameter", ps(
        "    return Read(sT2, uv);", "float4 Read(sampler s, float2 t) { return tex2D(s, t); }\n"),
        lambda u, v: t2(u, v)),
]

ROWS += [
    # -- accuracy away from the unit range -------------------------------------------------------
    Row("sin and cos of large arguments", ps(
        "    return float4(sin(uv.x * 50) * 0.5 + 0.5, cos(uv.y * 80 + 3) * 0.5 + 0.5, sin(-uv.x * 30) * 0.5 + 0.5, 1);"),
        lambda u, v: (math.sin(50 * u) / 2 + 0.5, math.cos(80 * v + 3) / 2 + 0.5, math.sin(-30 * u) / 2 + 0.5, 1)),
    Row("sin and cos on vs_1_1 of a large uniform", 
        "float A = 37.5;\nstruct VO { float4 p : POSITION; float4 c : COLOR0; };\n"
        "VO VS(float4 p : POSITION) { VO o; o.p = p; o.c = float4(sin(A) * 0.5 + 0.5, cos(A) * 0.5 + 0.5, 0, 1); return o; }\n"
        "float4 PS(float4 c : COLOR0) : COLOR { return c; }\n",
        lambda u, v: (math.sin(37.5) / 2 + 0.5, math.cos(37.5) / 2 + 0.5, 0, 1), vs="vs_1_1"),
    Row("pow exp log over a wide range", ps(
        "    return float4(pow(uv.x, 7.5), exp(-uv.y * 6), log(uv.x * 100 + 1) / 5, pow(uv.y + 1, 2.7) / 6);"),
        lambda u, v: (u ** 7.5, math.exp(-6 * v), math.log(100 * u + 1) / 5, (v + 1) ** 2.7 / 6)),
    Row("tan near its poles and atan of large values", ps(
        "    return float4(tan(uv.x * 1.4) / 8, atan(uv.y * 50) / 1.6, atan2(-uv.x, -0.001) / 6.3 + 0.5, 1);"),
        lambda u, v: (math.tan(1.4 * u) / 8, math.atan(50 * v) / 1.6, math.atan2(-u, -0.001) / 6.3 + 0.5, 1)),
]

ROWS += [
    # -- indices that are uniform floats; copies of a value a branch changed ---------------------
    Row("an array indexed by a sum of uniform floats", ps(
        "    return F[J.x + J.y];", "float4 F[3] = { 0.1, 0.2, 0.3, 0.4,  0.5, 0.6, 0.7, 0.8,  0.9, 1, 0.25, 0.5 };\n"
        "float2 J = { 1, 1 };\n"),
        lambda u, v: (0.9, 1, 0.25, 0.5)),
    Row("int and bool vectors indexed by a uniform float", ps(
        "    int4 ai = int4(21, 22, 23, 24);\n    bool4 ab = bool4(true, false, true, false);\n"
        "    return float4(ai[I] / 32.0, ab[I], ai[3 - I] / 32.0, ab[3 - I]);", "float I = 2;\n"),
        lambda u, v: (23 / 32, 1, 22 / 32, 0)),
    Row("a copy taken after a branch changed the value", ps(
        "    float4 a = { 0.1, 0.2, 0.3, 0.4 };\n    float4 b;\n    if (C) a = float4(0.5, 0.6, 0.7, 0.8);\n"
        "    b = a;\n    a.y = 0.9;\n    float2 r = { 0.3, 0.4 };\n    if (uv.x > 0.5) r = float2(0.25, 0.75);\n"
        "    r = r;\n    r = float2(1, r.y);\n    return float4(b.y, a.y, r);", "float C = 1;\n"),
        lambda u, v: (0.6, 0.9, 1, 0.75 if u > 0.5 else 0.4)),
]

ROWS += [
    # a for's counter read after the loop, where lanes broke out at different counts
    Row("a for counter read after a run-time break", ps(
        "    for (int i = 0; i < 4; i++) { if (i * 0.25 + 0.0625 > uv.x) break; }\n"
        "    int j;\n    for (j = 0; j < 3; j++) { if (uv.y < j * 0.25 - 0.0625) break; }\n"
        "    return float4(i * 0.25, j * 0.25, 0, 1);"),
        lambda u, v: (0.25 * min(int((u - 0.0625) / 0.25) + 1, 4),
                      0.25 * next((j for j in range(3) if v < j * 0.25 - 0.0625), 3), 0, 1)),
    Row("a for counter read after a run-time break on ps_3_0", ps(
        "    for (int i = 0; i < 4; i++) { if (i * 0.25 + 0.0625 > uv.x) break; }\n"
        "    return float4(i * 0.25, 0, 0, 1);"),
        lambda u, v: (0.25 * min(int((u - 0.0625) / 0.25) + 1, 4), 0, 0, 1), target="ps_3_0"),
]
