"""A corpus of small HLSL programs that fxc refused (issue 30), each with the code fxc gave.

One row per program: (name, fxc's code, the functions, the entry, its target). The effect is
the text plus one technique compiling the entry. Where the code is sourced, the row's comment
says from where: DXC's verify tests (tools/clang/test/HLSL*, whose `fxc-error {{...}}`
annotations record what fxc said), the DirectX 9 d3dx HLSL compiler's own message table (the
`'%s': void functions cannot return a value` family, with their numbers), ReShade's FX parser
(which gives fxc's codes and texts for the same checks); "from memory" where none was found.

`refusal(row)` compiles a row as a user would (load, compile the entry for its target) and
returns the code of the error it is refused with, or "accepted": the measure of the issue
(`tests/shaders/hlsl/test_hlsl_invalid_corpus.py` asserts every row; the report counts).
`UNIT` holds the errors written where a compile of the entry never evaluates them (fxc
type-checked the whole file: effects/shaders/hlsl/check.py), asserted by
test_hlsl_unit_check.py. `python -m tests.shaders.hlsl.invalid_corpus` prints both counts
(run it with another checkout first on PYTHONPATH for a before figure).
"""
from __future__ import annotations

from typing import NamedTuple


class Row(NamedTuple):
    name: str
    code: str
    text: str
    entry: str = "PS"
    target: str = "ps_2_0"
    strict: bool = False      # refused under a strict load (D3DXCreateEffect without /Gec)


PS = "float4 PS(float2 uv : TEXCOORD0) : COLOR\n{\n%s\n}\n"


def ps(body: str, before: str = "") -> str:
    return before + PS % body


CORPUS: list[Row] = [
    # -- redefinitions: X3003 "redefinition of '%s'" (d3dx message table; ReShade) ----------
    Row("local twice", "X3003", ps("    float a = 1;\n    float a = 2;\n    return a;")),
    Row("local twice, one declaration", "X3003", ps("    float a = 1, a = 2;\n    return a;")),
    Row("local twice in an inner block", "X3003",
        ps("    float r = 0;\n    {\n        float t = 1;\n        int t = 2;\n        r = t;\n    }\n"
           "    return r;")),
    Row("parameter twice", "X3003",
        "float4 PS(float2 uv : TEXCOORD0, float uv : TEXCOORD1) : COLOR\n{\n    return uv;\n}\n"),
    Row("parameter twice in a called function", "X3003",
        ps("    return f(uv.x, uv.y);", "float f(float a, float a) { return a; }\n")),
    Row("a local named as a parameter", "X3036",
        ps("    float uv = 1;\n    return uv;")),
    Row("a local named as a parameter of a called function", "X3036",
        ps("    return f(uv.x);", "float f(float x) { float x = 2; return x; }\n")),
    Row("function defined twice", "X3003",
        ps("    return f(uv.x);", "float f(float x) { return x; }\nfloat f(float y) { return y; }\n")),
    Row("struct member twice", "X3003",
        ps("    S s = (S)uv.x;\n    return s.a;", "struct S { float a; float a; };\n")),
    Row("struct defined twice", "X3003",
        ps("    S s = (S)uv.x;\n    return s.b;", "struct S { float a; };\nstruct S { float b; };\n")),
    Row("global twice", "X3003", ps("    return k;", "float k;\nfloat k;\n")),
    # -- scope: X3004 "undeclared identifier '%s'" ---------------------------------------------
    Row("a local after its block", "X3004", ps("    {\n        float t = uv.x;\n    }\n    return t;")),
    Row("a local of an if after it", "X3004",
        ps("    if (uv.x > 0.5)\n    {\n        float t = 1;\n    }\n    return t;")),
    Row("a local of an else after it", "X3004",
        ps("    if (uv.x > 0.5) { } else { float e = 2; }\n    return e;")),
    Row("a local of a called function", "X3004",
        ps("    f(uv.x);\n    return inner;", "float f(float x) { float inner = x; return inner; }\n")),
    Row("a local of a loop body after it", "X3004",
        ps("    for (int i = 0; i < 2; i++) { float acc = i; }\n    return acc;")),
    Row("undeclared function", "X3004", ps("    return shade(uv);")),
    Row("undeclared in a called function", "X3004",
        ps("    return f(uv.x);", "float f(float x) { return x * gain; }\n")),
    # -- calls: X3013 no matching overload, X3014 constructor arity ----------------------------
    Row("lerp with two arguments", "X3013", ps("    return lerp(uv.x, uv.y);")),
    Row("mul with one argument", "X3013", ps("    return mul(uv);")),
    Row("dot with three arguments", "X3013", ps("    return dot(uv, uv, uv);")),
    Row("user function, too many arguments", "X3013",
        ps("    return f(uv.x, uv.y);", "float f(float x) { return x; }\n")),
    Row("user function, too few arguments", "X3013",
        ps("    return f(uv.x);", "float f(float x, float y) { return x + y; }\n")),
    Row("user function, a struct for a float", "X3013",
        ps("    S s = (S)0;\n    return f(s);", "struct S { float a; float b; };\n"
           "float f(float2 x) { return x.x; }\n")),
    Row("normalize of a struct", "X3013",
        ps("    S s = (S)0;\n    return normalize(s);", "struct S { float3 n; };\n")),
    Row("tex2D without a sampler", "X3013", ps("    return tex2D(uv, uv);")),
    Row("tex2D with its arguments swapped", "X3013",
        ps("    return tex2D(uv, Sam);", "sampler Sam;\n")),
    Row("tex2D of a samplerCUBE", "X3013",
        ps("    return tex2D(Env, uv);", "samplerCUBE Env;\n")),
    Row("texCUBE of a sampler2D", "X3013",
        ps("    return texCUBE(Map, uv.xyx);", "sampler2D Map;\n")),
    Row("float4 of three", "X3014", ps("    return float4(uv, 1);")),
    Row("float2 of three", "X3014", ps("    float2 v = float2(1, 2, 3);\n    return v.x;")),
    Row("float3x3 of two", "X3014", ps("    float3x3 m = float3x3(1, 2);\n    return m[0].x;")),
    Row("float4 of nothing", "X3014", ps("    return float4();")),
    # -- void and string: X3038 (ReShade's texts), X3017 ----------------------------------------
    Row("void local", "X3038", ps("    void v;\n    return 1;")),
    Row("void parameter", "X3038", ps("    return f(uv.x);", "float f(void x) { return 1; }\n")),
    Row("void struct member", "X3038",
        ps("    S s = (S)0;\n    return s.a;", "struct S { float a; void b; };\n")),
    Row("string global as a colour", "X3017", ps("    return Name;", "string Name = \"a\";\n")),
    Row("string global in arithmetic", "X3022", ps("    return Name + 1;", "string Name = \"a\";\n")),
    Row("texture as a value", "X3017", ps("    float4 c = Tex;\n    return c;", "texture Tex;\n")),
    # -- conversions and casts: X3017 ------------------------------------------------------------
    Row("cast to a larger vector", "X3017", ps("    return (float4)uv;")),
    Row("implicit float2 to float3", "X3017", ps("    float3 v = uv;\n    return v.x;")),
    Row("implicit int to struct", "X3017", ps("    S s = 0;\n    return s.a;", "struct S { float a; };\n")),
    Row("struct to unrelated struct", "X3017",
        ps("    A a = (A)0;\n    B b = a;\n    return b.y;",
           "struct A { float x; };\nstruct B { float y; float z; };\n")),
    Row("cast to a struct of more numbers", "X3017",
        ps("    A a = (A)uv.x;\n    B b = (B)a;\n    return b.z;",
           "struct A { float x; };\nstruct B { float y; float z; };\n")),
    Row("cast of a sampler", "X3017", ps("    return (float)Sam;", "sampler Sam;\n")),
    Row("matrix to vector", "X3017", ps("    float4x4 m = 0;\n    float3 v = m;\n    return v.x;")),
    Row("return a struct for a float4", "X3017",
        ps("    S s = (S)0;\n    return s;", "struct S { float4 c; float d; };\n")),
    Row("return a float2 for a float4", "X3017", ps("    return uv;")),
    # -- return: X3079, X3080 (d3dx message table) ------------------------------------------------
    Row("void function returns a value", "X3079",
        ps("    f();\n    return 1;", "void f() { return 1; }\n")),
    Row("return with no value", "X3080", ps("    return;")),
    Row("function without return", "X3080", ps("    return f();", "float f() { }\n")),
    Row("not every path returns", "X3507",     # from memory: fxc's code and text not found
        ps("    return g(uv.x);", "float g(float x)\n{\n    if (x > 0)\n        return 1;\n}\n")),
    Row("a function never called returns nothing", "X3080",
        ps("    return uv.x;", "float unused(float x) { x = 1; }\n")),
    Row("void function with a semantic", "X3076",
        ps("    f();\n    return 1;", "void f() : COLOR { }\n")),
    # -- const, uniform, l-values: X3025, X3012 --------------------------------------------------
    Row("const local written", "X3025", ps("    const float k = 1;\n    k = 2;\n    return k;")),
    Row("const local incremented", "X3025", ps("    const float k = 1;\n    k++;\n    return k;")),
    Row("const parameter written", "X3025",
        ps("    return f(uv.x);", "float f(const float x) { x = 1; return x; }\n")),
    Row("uniform parameter written", "X3025",
        "float4 PS(float2 uv : TEXCOORD0, uniform float4 k) : COLOR\n{\n    k = 1;\n    return k;\n}\n"),
    Row("static const global written", "X3025",
        ps("    K = 2;\n    return K;", "static const float K = 1;\n")),
    Row("literal as an out argument", "X3025",
        ps("    float s;\n    sincos(uv.x, s, 1);\n    return s;")),
    Row("out argument an expression", "X3025",
        ps("    f(uv.x + 1);\n    return 1;", "void f(out float o) { o = 1; }\n")),
    Row("write mask naming a component twice", "X3025",
        ps("    float4 v = 0;\n    v.xx = uv;\n    return v;")),
    Row("const local without a value", "X3012", ps("    const float k;\n    return k;")),
    Row("non-static global written (strict)", "X3025",
        ps("    Gain = 2;\n    return Gain;", "float Gain = 1;\n"), strict=True),
    # -- ternaries and conditions: X3020, X3019 ---------------------------------------------------
    Row("ternary struct and float", "X3020",
        ps("    S s = (S)0;\n    return uv.x > 0 ? s : 1;", "struct S { float a; };\n")),
    Row("ternary condition of another size", "X3020",
        ps("    float4 v = uv.xyxy;\n    return (uv > 0) ? v : (v + 1);")),
    Row("if on a float3", "X3019",
        ps("    float3 v = uv.xyx;\n    if (v)\n        return 1;\n    return 0;")),
    Row("if on a struct", "X3019",
        ps("    S s = (S)0;\n    if (s)\n        return 1;\n    return 0;", "struct S { float a; };\n")),
    Row("while on a float2", "X3019",
        ps("    float r = 0;\n    while (uv)\n    {\n        r = 1;\n        break;\n    }\n    return r;")),
    Row("for condition a float2", "X3019",
        ps("    float r = 0;\n    for (int i = 0; uv; i++)\n    {\n        r = 1;\n        break;\n    }\n"
           "    return r;")),
    Row("do-while on a float2", "X3019",
        ps("    float r = 0;\n    do { r += 1; } while (uv);\n    return r;")),
    # -- operators: X3022, X3020 -----------------------------------------------------------------
    Row("struct plus struct", "X3022",
        ps("    S s = (S)0;\n    S t = s + s;\n    return t.a;", "struct S { float a; };\n")),
    Row("struct plus a number", "X3022",
        ps("    S s = (S)0;\n    return s + 1;", "struct S { float a; };\n")),
    Row("negated struct", "X3022",
        ps("    S s = (S)0;\n    S t = -s;\n    return t.a;", "struct S { float a; };\n")),
    Row("struct compared", "X3020",
        ps("    S s = (S)0;\n    return s == 1;", "struct S { float a; };\n")),
    Row("bool decremented", "X3020", ps("    bool b = true;\n    b--;\n    return b;")),
    # -- subscripts and indices ------------------------------------------------------------------
    Row("member that is not there", "X3018", ps("    S s = (S)0;\n    return s.b;", "struct S { float a; };\n")),
    Row("swizzle past the vector", "X3018", ps("    return uv.xyzw;")),
    Row("swizzle of mixed sets", "X3018", ps("    return uv.xg;")),
    Row("index on a scalar", "X3121", ps("    float f = 1;\n    return f[0];")),
    Row("literal index out of bounds", "X3504", ps("    float a[2] = { 1, 2 };\n    return a[2];")),
    # -- types and declarations ------------------------------------------------------------------
    Row("unknown type", "X3000", ps("    flaot4 c = 1;\n    return c;")),
    Row("vector of five", "X3052", ps("    vector<float, 5> v = 0;\n    return v.x;")),
    Row("matrix of five rows", "X3053", ps("    matrix<float, 5, 4> m = 0;\n    return m[0];")),
    Row("array of zero", "X3059", ps("    float a[0];\n    return 1;")),
    Row("row_major and column_major", "X3048",
        ps("    row_major column_major float4x4 m = 0;\n    return m[0];")),
    Row("row_major vector", "X3077", ps("    row_major float4 v = 1;\n    return v;")),
    Row("column_major scalar parameter", "X3077",
        ps("    return f(uv.x);", "float f(column_major float x) { return x; }\n")),
    Row("uniform local", "X3047", ps("    uniform float k = 1;\n    return k;")),
    Row("extern local", "X3006", ps("    extern float k = 1;\n    return k;")),
    Row("const out parameter", "X3046",
        ps("    float r;\n    f(r);\n    return r;", "void f(const out float o) { o = 1; }\n")),
    Row("array size not a constant", "X3058",
        ps("    int n = (int)(uv.x * 4);\n    float a[n];\n    return 1;")),
    Row("value of a void function", "X3017",
        ps("    float x = f();\n    return x;", "void f() { }\n")),
    Row("a variable before its declaration", "X3004", ps("    x = 1;\n    float x;\n    return x;")),
    Row("constructor of a struct value", "X3017",
        ps("    S s = (S)0;\n    return float4(s);", "struct S { float4 c; };\n")),
    Row("cast to a sampler", "X3017", ps("    return tex2D((sampler)1, uv);")),
    Row("texture as a sampler", "X3013", ps("    return tex2D(Tex, uv);", "texture Tex;\n")),
    Row("input without a semantic", "X4502",
        "float4 PS(float2 uv) : COLOR\n{\n    return uv.x;\n}\n"),
    Row("output of an unknown semantic", "X4503",
        "float4 PS(float2 uv : TEXCOORD0) : BOGUS\n{\n    return uv.x;\n}\n"),
    Row("void parameter of a function never called", "X3038",
        ps("    return uv.x;", "float unused(void x) { return 1; }\n")),
    Row("parameter twice in a function never called", "X3003",
        ps("    return uv.x;", "float unused(float a, float2 a) { return 1; }\n")),
    Row("vertex input of no usage", "X4502",
        "float4 VS(float4 p : FOO) : POSITION\n{\n    return p;\n}\n", entry="VS", target="vs_2_0"),
    Row("vertex output COLOR2", "X4503",
        "void VS(float4 p : POSITION, out float4 o : POSITION, out float4 c : COLOR2)\n"
        "{\n    o = p;\n    c = p;\n}\n", entry="VS", target="vs_2_0"),
    Row("vertex output TEXCOORD8", "X4503",
        "void VS(float4 p : POSITION, out float4 o : POSITION, out float4 t : TEXCOORD8)\n"
        "{\n    o = p;\n    t = p;\n}\n", entry="VS", target="vs_2_0"),
    Row("vs_3_0 output of no usage", "X4503",
        "void VS(float4 p : POSITION, out float4 o : POSITION, out float4 t : BOGUS)\n"
        "{\n    o = p;\n    t = p;\n}\n", entry="VS", target="vs_3_0"),
    Row("pixel input TEXCOORD8", "X4502",
        "float4 PS(float4 t : TEXCOORD8) : COLOR\n{\n    return t;\n}\n"),
    Row("pixel input COLOR2", "X4502",
        "float4 PS(float4 c : COLOR2) : COLOR\n{\n    return c;\n}\n"),
    Row("pixel output COLOR4", "X4503",
        "float4 PS(float4 c : COLOR0) : COLOR4\n{\n    return c;\n}\n"),
    Row("COLOR0 written twice", "X4504",
        "struct O { float4 a : COLOR0; float4 b : COLOR0; };\nO PS(float2 uv : TEXCOORD0)\n{\n"
        "    O o;\n    o.a = uv.x;\n    o.b = uv.y;\n    return o;\n}\n"),
    Row("TEXCOORD0 written twice", "X4504",
        "void VS(float4 p : POSITION, out float4 o : POSITION, out float4 t : TEXCOORD0,\n"
        "        out float4 u : TEXCOORD0)\n{\n    o = p;\n    t = p;\n    u = p;\n}\n",
        entry="VS", target="vs_2_0"),
    Row("default before a parameter without one", "X3044",
        ps("    return f(uv.x, 1);", "float f(float a = 1, float b) { return a + b; }\n")),
    Row("out parameter with a default", "X3045",
        ps("    float r;\n    f(r);\n    return r;", "void f(out float o = 1) { o = 2; }\n")),
    Row("bitwise and of floats", "X3082", ps("    return 1.5 & 2;")),
    Row("bitwise not of a float", "X3082", ps("    return ~uv.x;")),
    Row("shift of a float", "X3082", ps("    int i = 1;\n    return uv.x << i;")),
    Row("recursion", "X3500", ps("    return f(uv.x);", "float f(float x) { return f(x); }\n")),
    Row("entry point not there", "X3501", ps("    return 1;"), entry="Main"),
    Row("break outside a loop", "X3518", ps("    break;\n    return 1;")),
    Row("continue outside a loop", "X3519", ps("    continue;\n    return 1;")),
    # -- registers past the target: X4507 (d3dx message table: "maximum constant register index
    # exceeded"), X4509 (DXC's packreg test: "maximum sampler register index exceeded") ----------
    Row("register c300 on vs_2_0", "X4507",
        "float4 Far : register(c300);\nfloat4 VS(float4 p : POSITION) : POSITION\n{\n    return p * Far;\n}\n",
        entry="VS", target="vs_2_0"),
    Row("register c40 on ps_2_0", "X4507", ps("    return Far;", "float4 Far : register(c40);\n")),
    Row("register s16", "X4509", ps("    return tex2D(Sam, uv);", "sampler Sam : register(s16);\n")),
]


def unused(body: str, before: str = "") -> str:
    """A valid entry and, before it, a function `Unused(float2 uv, float4 c)` that nothing
    calls, whose body is `body`."""
    return ps("    return uv.x;", before + "float4 Unused(float2 uv, float4 c)\n{\n" + body + "\n}\n")


def dead(body: str, before: str = "") -> str:
    """The entry with `body` inside `if (false) { ... }`, a branch a constant drops."""
    return ps("    if (false)\n    {\n" + body + "\n    }\n    return uv.x;", before)


# Where fxc reported an error (issue 30): fxc type-checked every function body, statement and
# global initialiser as it parsed the file, before it optimised anything, so the rows below
# are errors of the rows above (their codes sourced there) written where a compile of the
# entry never evaluates them: in a function nothing calls, in a second entry point no
# technique compiles, in a branch a constant drops, in a loop body that runs no times, after
# a return, in a global initialiser nothing reads. The evidence for the split: DXC's verify
# tests annotate `fxc-error` in functions their entry never calls (tools/clang/test/HLSL/
# string.hlsl's get_message: X3038), and vkd3d's tests/hlsl/function.shader_test (native
# d3dcompiler's verdicts) accepts, in unused code, only what is legal there: a call to a
# function that is declared and never defined. "vkd3d <file>" names a `[pixel shader fail]`
# case of vkd3d's tests/hlsl that the row is written after.
UNIT: list[Row] = [
    # -- in a function nothing calls (each code as sourced above for a called one) ------------
    Row("unused: undeclared identifier", "X3004", unused("    return c * gain;")),
    Row("unused: undeclared function", "X3004", unused("    return shade(uv);")),
    Row("unused: a local after its block", "X3004",
        unused("    {\n        float t = 1;\n    }\n    return t;")),
    Row("unused: lerp with two arguments", "X3013", unused("    return lerp(c, c);")),
    Row("unused: user function, too many arguments", "X3013",
        unused("    return f(uv.x, uv.y);", "float f(float x) { return x; }\n")),
    Row("unused: tex2D without a sampler", "X3013", unused("    return tex2D(uv, uv);")),
    Row("unused: float4 of three", "X3014", unused("    return float4(uv, 1);")),
    Row("unused: float2 to float3", "X3017", unused("    float3 v = uv;\n    return v.x;")),
    Row("unused: return a float2 for a float4", "X3017", unused("    return uv;")),
    Row("unused: cast to a larger vector", "X3017", unused("    return (float4)uv;")),
    Row("unused: value of a void function", "X3017",
        unused("    float x = f();\n    return x;", "void f() { }\n")),
    Row("unused: member that is not there", "X3018",
        unused("    S s = (S)0;\n    return s.b;", "struct S { float a; };\n")),
    Row("unused: swizzle past the vector", "X3018", unused("    return uv.xyzw;")),
    Row("unused: if on a float3", "X3019",
        unused("    if (c.xyz)\n        return 1;\n    return 0;")),
    Row("unused: while on a float2", "X3019",
        unused("    while (uv)\n        break;\n    return 0;")),
    Row("unused: ternary struct and float", "X3020",
        unused("    S s = (S)0;\n    return uv.x > 0 ? s : 1;", "struct S { float a; };\n")),
    Row("unused: bool decremented", "X3020", unused("    bool b = true;\n    b--;\n    return b;")),
    Row("unused: struct plus a number", "X3022",
        unused("    S s = (S)0;\n    return s + 1;", "struct S { float a; };\n")),
    Row("unused: const local written", "X3025",
        unused("    const float k = 1;\n    k = 2;\n    return k;")),
    Row("unused: literal as an out argument", "X3025",
        unused("    float s;\n    sincos(uv.x, s, 1);\n    return s;")),
    Row("unused: out argument an expression", "X3025",
        unused("    f(uv.x + 1);\n    return c;", "void f(out float o) { o = 1; }\n")),
    Row("unused: static const global written", "X3025",
        unused("    K = 2;\n    return K;", "static const float K = 1;\n")),
    Row("unused: local twice", "X3003", unused("    float a = 1;\n    float a = 2;\n    return a;")),
    Row("unused: a local named as a parameter", "X3036", unused("    float c = 1;\n    return c;")),
    Row("unused: void local", "X3038", unused("    void v;\n    return c;")),
    Row("unused: const local without a value", "X3012", unused("    const float k;\n    return k;")),
    Row("unused: uniform local", "X3047", unused("    uniform float k = 1;\n    return k;")),
    Row("unused: constructor of a struct", "X3037",
        unused("    S s = S(1);\n    return s.a;", "struct S { float a; };\n")),
    Row("unused: index on a scalar", "X3121", unused("    float f = 1;\n    return f[0];")),
    Row("unused: literal index out of bounds", "X3504",
        unused("    float a[2] = { 1, 2 };\n    return a[2];")),
    Row("unused: bitwise not of a float", "X3082", unused("    return ~uv.x;")),
    Row("unused: array size not a constant", "X3058",
        unused("    int n = (int)(uv.x * 4);\n    float a[n];\n    return c;")),
    Row("unused: break outside a loop", "X3518", unused("    break;\n    return c;")),
    Row("unused: continue outside a loop", "X3519", unused("    continue;\n    return c;")),
    Row("unused: void function returns a value", "X3079",
        ps("    return uv.x;", "void Unused() { return 1; }\n")),
    Row("unused: return with no value", "X3080", unused("    return;")),
    Row("unused: a case without break", "X3533",
        unused("    int k = (int)uv.x;\n    switch (k)\n    {\n    case 0:\n        c = 1;\n"
               "    case 1:\n        break;\n    }\n    return c;")),
    Row("unused: switch on a float", "X3020",
        unused("    switch (uv.x)\n    {\n    case 0:\n        break;\n    }\n    return c;")),
    Row("unused: a parameter's default of a texture", "X3017",
        ps("    return uv.x;", "texture Tex;\nfloat Unused(float x = Tex) { return x; }\n")),
    Row("unused: an overload of its own called with a struct", "X3013",
        unused("    S s = (S)0;\n    return f(s);",
               "struct S { float a; float b; };\nfloat f(float2 x) { return x.x; }\n")),
    # -- a second entry point no technique compiles ----------------------------------------------
    Row("second entry: undeclared identifier", "X3004",
        ps("    return uv.x;", "float4 PS2(float2 uv : TEXCOORD0) : COLOR { return uv.x * nope; }\n")),
    Row("second entry: tex2D of a texture", "X3013",
        ps("    return uv.x;", "texture Tex;\n"
           "float4 PS2(float2 uv : TEXCOORD0) : COLOR { return tex2D(Tex, uv); }\n")),
    Row("second vertex entry: matrix to vector", "X3017",
        ps("    return uv.x;", "float4x4 World;\n"
           "float4 VS2(float4 p : POSITION) : POSITION { float3 v = World; return p; }\n")),
    # -- in a branch a constant drops, a loop that runs no times, after a return ------------------
    Row("if (false): undeclared identifier", "X3004", dead("        return nope;")),
    Row("if (false): float4 of three", "X3014", dead("        return float4(uv, 1);")),
    Row("if (false): implicit float2 to float3", "X3017", dead("        float3 v = uv;\n        return v.x;")),
    Row("if (false): lerp with one argument", "X3013", dead("        return lerp(uv.x);")),
    Row("if (false): swizzle of mixed sets", "X3018", dead("        return uv.xg;")),
    Row("if (false): const local written", "X3025",
        dead("        const float k = 1;\n        k = 2;")),
    Row("else of if (true): undeclared identifier", "X3004",
        ps("    if (true)\n        return uv.x;\n    else\n        return missing;")),
    Row("if (0) in a called function", "X3004",
        ps("    return f(uv.x);", "float f(float x)\n{\n    if (0)\n        x = y;\n    return x;\n}\n")),
    Row("a loop that runs no times", "X3004",
        ps("    float r = 0;\n    for (int i = 0; i < 0; i++)\n        r += nope;\n    return r;")),
    Row("while (false)", "X3013",
        ps("    float r = 0;\n    while (false)\n        r = dot(uv);\n    return r;")),
    Row("after a return", "X3004", ps("    return uv.x;\n    nope = 1;")),
    Row("after a return in a block", "X3017",
        ps("    {\n        return uv.x;\n        float3 v = uv;\n    }")),
    Row("a case a constant selector skips", "X3004",
        ps("    switch (1)\n    {\n    case 0:\n        return nope;\n    default:\n"
           "        return uv.x;\n    }")),
    Row("static const bool false branch", "X3022",
        ps("    if (Off)\n    {\n        S s = (S)0;\n        return -s;\n    }\n    return uv.x;",
           "struct S { float a; };\nstatic const bool Off = false;\n")),
    # -- global initialisers nothing reads ---------------------------------------------------------
    Row("static initialiser: undeclared identifier", "X3004",
        ps("    return uv.x;", "static float K = nope;\n")),
    Row("static initialiser: sin of two", "X3013",
        ps("    return uv.x;", "static float K = sin(1, 2);\n")),
    Row("uniform initialiser: undeclared identifier", "X3004",
        ps("    return uv.x;", "float K = nope * 2;\n")),
    Row("static initialiser: lerp of two", "X3013",
        ps("    return uv.x;", "static float4 K = lerp(1, 2);\n")),
    # -- strings (DXC tools/clang/test/HLSL/string.hlsl, its fxc-error notes) ---------------------
    Row("string: a function returning one", "X3038",
        ps("    return uv.x;", "string Name = \"a\";\nstring f() { return Name; }\n")),
    Row("string: a bool initialised from one", "X3017",
        ps("    return uv.x;", "string Name = \"a\";\nstatic const bool B = Name;\n")),
    Row("string: an int initialised from one", "X3017",
        ps("    return uv.x;", "string Name = \"a\";\nstatic const int I = Name;\n")),
    Row("string: a float initialised from one", "X3017",
        ps("    return uv.x;", "string Name = \"a\";\nstatic const float F = Name;\n")),
    Row("string: a vector of strings", "X3122", ps("    vector<string, 4> v;\n    return uv.x;")),
    Row("string: a matrix of strings", "X3123", ps("    matrix<string, 4, 4> m;\n    return uv.x;")),
    Row("string: a local assigned a number", "X3017",
        unused("    string s;\n    s = 1;\n    return c;")),
    Row("string: a local in arithmetic", "X3022",
        unused("    string s = Name;\n    return c * s;", "string Name = \"a\";\n")),
    Row("texture: a function returning one", "X3038",
        ps("    return uv.x;", "texture Tex;\ntexture f() { return Tex; }\n")),
    # -- void (ReShade's and d3dx's texts as above) ------------------------------------------------
    Row("void: an array of void", "X3038", unused("    void a[2];\n    return c;")),
    Row("void: a global of void", "X3038", ps("    return uv.x;", "void G;\n")),
    Row("void: a void value in arithmetic", "X3022",
        unused("    return f() + 1;", "void f() { }\n")),
    Row("void: a void value as an intrinsic's argument", "X3013",
        unused("    return sin(f());", "void f() { }\n")),
    # -- vkd3d's fail cases, in the entry ---------------------------------------------------------
    Row("vkd3d initializer-invalid-arg-count: an array list one short", "X3017",
        ps("    float4 a[2] = { 1, 2, 3, 4, 5, 6, 7 };\n    return a[1];")),
    Row("vkd3d initializer-invalid-arg-count: an array list one long", "X3017",
        ps("    float4 a[2] = { 1, 2, 3, 4, 5, 6, 7, 8, 9 };\n    return a[1];")),
    Row("vkd3d initializer-invalid-arg-count: a struct list one short", "X3017",
        ps("    S s = { 1, 2, 3, 4 };\n    return s.b;", "struct S { int a; float4 b; };\n")),
    Row("vkd3d cf-cond-types: if on an array", "X3019",
        ps("    if (F)\n        return 1;\n    return 0;", "static const float F[1] = { 1 };\n")),
    Row("vkd3d cf-cond-types: while on a texture", "X3019",
        ps("    while (Tex)\n        break;\n    return 0;", "texture Tex;\n")),
    Row("vkd3d function: an inout argument of a repeated swizzle", "X3025",
        ps("    float2 x = 0;\n    f(x.yy);\n    return x.x;", "void f(inout float2 o) { o += 0.1; }\n")),
    Row("vkd3d function: a const local as an out argument", "X3025",
        ps("    const float x = 0;\n    f(x);\n    return x;", "void f(out float o) { o = 0.1; }\n")),
    Row("vkd3d invalid: a member of a const uniform struct written", "X3025",
        ps("    A.a = 1;\n    return A.a;", "struct S { float a; };\nuniform const S A;\n")),
]


def refusal(row: Row) -> str:
    """The fxc code `row` is refused with here, or 'accepted'."""
    import effects
    from effects.base.errors import EffectError
    from effects.shaders.hlsl import compile_shader
    stage = "VertexShader" if row.target.startswith("vs") else "PixelShader"
    text = row.text + f"\ntechnique T {{ pass P {{ {stage} = compile {row.target} {row.entry}(); }} }}\n"
    try:
        fx = effects.load_effect(text, strict=row.strict)
        compile_shader(fx, row.entry, row.target)
    except EffectError as err:
        message = err.message
        return message[:5] if message[:1] == "X" and message[5:6] == ":" else "uncoded: " + message
    return "accepted"


def report(rows: list[Row]) -> tuple[int, list[str]]:
    """How many of `rows` are refused with their code, and a line for each that is not."""
    right, wrong = 0, []
    for row in rows:
        got = refusal(row)
        if got == row.code:
            right += 1
        else:
            wrong.append(f"{row.name}: {got}, fxc {row.code}")
    return right, wrong


if __name__ == "__main__":    # the measure: python -m tests.shaders.hlsl.invalid_corpus
    for label, rows in (("corpus", CORPUS), ("unit (where fxc reported)", UNIT)):
        right, wrong = report(rows)
        print(f"{label}: {right} of {len(rows)} refused with fxc's code")
        for line in wrong:
            print("   ", line)
