"""Language errors against target refusals (issue 30): each fxc code the compiler raises is
located at the HLSL line and column, as the user reads it (message, source line, caret), and
says whether fxc gives it for every target (`language`) or only for the one compiled for.
Locations hold through #include and macros: the file as written, not the expanded text."""
from __future__ import annotations

import textwrap

import pytest

import effects
from effects.base import disk_store
from effects.base.errors import EffectError
from effects.shaders.hlsl import cache, compile_shader, store
from effects.shaders.hlsl.parse import LANGUAGE_CODES, HlslError

TECHNIQUE = "\ntechnique T { pass P { PixelShader = compile ps_2_0 PS(); } }\n"


def compile_error(functions: str, target: str = "ps_2_0") -> EffectError:
    fx = effects.load_effect(functions + TECHNIQUE)
    with pytest.raises(EffectError) as info:
        compile_shader(fx, "PS", target)
    return info.value


# (functions, the report as printed); every one is a language error. Line 1 is the first line
# of `functions`; the caret sits under the column the report names.
LANGUAGE = {
    "X3000": ("float4 PS() : COLOR\n{\n    return float4(1, 0, 0, 1) +;\n}",
              "<string>:3:32: error: X3000: syntax error: unexpected ';'\n"
              "    return float4(1, 0, 0, 1) +;\n"
              "                               ^"),
    "X3003": ("float4 PS() : COLOR\n{\n    float a = 1;\n    float a = 2;\n    return a;\n}",
              "<string>:4:11: error: X3003: redefinition of 'a'\n"
              "    float a = 2;\n"
              "          ^"),
    "X3012": ("float4 PS() : COLOR\n{\n    const float k;\n    return k;\n}",
              "<string>:3:17: error: X3012: 'k': missing initial value\n"
              "    const float k;\n"
              "                ^"),
    "X3019": ("float4 PS(float3 v : TEXCOORD0) : COLOR\n{\n    if (v)\n        return 1;\n    return 0;\n}",
              "<string>:3:9: error: X3019: if statement conditional expressions must evaluate to "
              "a scalar (not 'float3')\n"
              "    if (v)\n"
              "        ^"),
    "X3004": ("float4 PS() : COLOR\n{\n    return foo * 2;\n}",
              "<string>:3:12: error: X3004: undeclared identifier 'foo'\n"
              "    return foo * 2;\n"
              "           ^"),
    "X3013": ("float4 PS() : COLOR\n{\n    return lerp(1, 2);\n}",
              "<string>:3:12: error: X3013: 'lerp': no matching 2 parameter intrinsic function\n"
              "    return lerp(1, 2);\n"
              "           ^"),
    "X3014": ("float4 PS() : COLOR\n{\n    return float4(1, 2);\n}",
              "<string>:3:12: error: X3014: incorrect number of arguments to numeric-type "
              "constructor ('float4' needs 4 values, given 2)\n"
              "    return float4(1, 2);\n"
              "           ^"),
    "X3017": ("float4 PS() : COLOR\n{\n    float4x4 m = 0;\n    float3 v = m;\n    return float4(v, 1);\n}",
              "<string>:4:16: error: X3017: cannot implicitly convert from 'float4x4' to 'float3'\n"
              "    float3 v = m;\n"
              "               ^"),
    "X3018": ("float4 PS() : COLOR\n{\n    float2 v = 1;\n    return float4(v.xyz, 1);\n}",
              "<string>:4:21: error: X3018: invalid subscript 'xyz'\n"
              "    return float4(v.xyz, 1);\n"
              "                    ^"),
    "X3020": ("struct S { float a; };\nfloat4 PS() : COLOR\n{\n    S s = (S)0;\n    return s == 1;\n}",
              "<string>:5:14: error: X3020: type mismatch: '==' needs numeric operands, not 'S' and 'int'\n"
              "    return s == 1;\n"
              "             ^"),
    "X3022": ("struct S { float a; };\nfloat4 PS() : COLOR\n{\n    S s = (S)0;\n    return s + 1;\n}",
              "<string>:5:14: error: X3022: scalar, vector, or matrix expected ('+' on 'S')\n"
              "    return s + 1;\n"
              "             ^"),
    "X3025": ("float4 PS() : COLOR\n{\n    const float k = 1;\n    k = 2;\n    return k;\n}",
              "<string>:4:5: error: X3025: l-value specifies const object 'k'\n"
              "    k = 2;\n"
              "    ^"),
    "X3036": ("float4 PS(float2 uv : TEXCOORD0) : COLOR\n{\n    float uv = 1;\n    return uv;\n}",
              "<string>:3:11: error: X3036: 'uv': formal parameter redefinition\n"
              "    float uv = 1;\n"
              "          ^"),
    "X3037": ("sampler S;\nfloat4 PS() : COLOR\n{\n    return sampler(1);\n}",
              "<string>:4:12: error: X3037: constructors only defined for numeric base types\n"
              "    return sampler(1);\n"
              "           ^"),
    "X3038": ("float4 PS() : COLOR\n{\n    void v;\n    return 1;\n}",
              "<string>:3:10: error: X3038: 'v': variables cannot be void\n"
              "    void v;\n"
              "         ^"),
    "X3048": ("float4 PS() : COLOR\n{\n    row_major column_major float2x2 m = 0;\n    return m[0].x;\n}",
              "<string>:3:5: error: X3048: matrix types cannot be both column_major and row_major\n"
              "    row_major column_major float2x2 m = 0;\n"
              "    ^"),
    "X3076": ("void f() : COLOR { }\nfloat4 PS() : COLOR\n{\n    return 1;\n}",
              "<string>:1:10: error: X3076: 'f': void function cannot have a semantic\n"
              "void f() : COLOR { }\n"
              "         ^"),
    "X3077": ("float4 PS() : COLOR\n{\n    row_major float4 v = 1;\n    return v;\n}",
              "<string>:3:5: error: X3077: non-matrix types cannot be declared 'row_major' or "
              "'column_major'\n"
              "    row_major float4 v = 1;\n"
              "    ^"),
    "X3080": ("float f() { }\nfloat4 PS() : COLOR\n{\n    return f();\n}",
              "<string>:1:1: error: X3080: 'f': function must return a value\n"
              "float f() { }\n"
              "^"),
    "X4504": ("struct O { float4 a : COLOR0; float4 b : COLOR0; };\nO PS()\n{\n    O o = (O)0;\n"
              "    return o;\n}",
              "<string>:2:1: error: X4504: overlapping output semantics ('COLOR0' is written twice)\n"
              "O PS()\n"
              "^"),
    "X3518": ("float4 PS() : COLOR\n{\n    break;\n    return 1;\n}",
              "<string>:3:5: error: X3518: break must be inside a loop\n"
              "    break;\n"
              "    ^"),
}


@pytest.mark.parametrize("code", sorted(LANGUAGE))
def test_a_language_error_is_located_and_marked_for_every_target(code):
    functions, report = LANGUAGE[code]
    for target in ("ps_2_0", "ps_3_0", "ps_1_1"):
        err = compile_error(functions, target)
        assert err.report() == report, target
        assert err.language is True and code in LANGUAGE_CODES


# refusals for the target: another target compiles the same function
TARGET = {
    "X3511": ("int Count = 2;\nfloat4 PS(float2 uv : TEXCOORD0) : COLOR\n{\n    float s = 0;\n"
              "    for (int i = 0; i < Count; i++) s += 0.25;\n    return s;\n}",
              "ps_2_0", "ps_3_0", None),
    # (a run-time index into numbers is a select chain: test_hlsl_valid_constructs.py)
    "X3512": ("sampler S[2];\nfloat4 PS(float2 uv : TEXCOORD0) : COLOR\n{\n"
              "    return tex2D(S[uv.x * 2], uv);\n}", "ps_2_0", None,
              "<string>:4:20: error: X3512: sampler array index must be a literal expression "
              "(ps_2_0 picks samplers by number only)"),
    "X4507": ("float4 Far : register(c40);\nfloat4 PS() : COLOR\n{\n    return Far;\n}",
              "ps_2_0", "ps_3_0",
              "<string>:1:8: error: X4507: maximum constant register index exceeded: 'Far' is "
              "bound to c40, ps_2_0 has c0..c31"),
    "X4532": ("sampler S;\nfloat4 PS(float2 uv : TEXCOORD0) : COLOR\n{\n"
              "    return tex2D(S, uv * uv);\n}", "ps_1_1", "ps_2_0",
              "<string>:4:12: error: X4532: cannot map expression to pixel shader instruction "
              "set: ps_1_1 has no texture read at computed coordinates (a dependent read needs "
              "ps_1_4, or the texbem/texm3x* instructions fxc did not generate)"),
}


@pytest.mark.parametrize("code", sorted(TARGET))
def test_a_refusal_for_the_target_is_not_a_language_error(code):
    functions, refused, compiles, first_line = TARGET[code]
    err = compile_error(functions, refused)
    assert err.message.startswith(f"{code}: ") and err.language is False
    assert code not in LANGUAGE_CODES and (first_line is None or str(err) == first_line)
    if compiles is not None:   # no target indexes samplers at run time (X3512)
        fx = effects.load_effect(functions + TECHNIQUE)
        compile_shader(fx, "PS", compiles)


# register() bindings that overlap in what the code reads (X4500), and their neighbours that do
# not: a variable holds the registers up to the last one read (constant_layout.py)
OVERLAPS = [
    ("float4 A : register(c0); float4 B : register(c0);", "A + B", "c0", None),
    ("sampler A : register(s0); sampler B : register(s0);", "tex2D(A, uv) * tex2D(B, uv)",
     "s0", None),
    ("float4 A[2] : register(c0); float4 B : register(c1);", "A[1] + B", "c1", None),
    ("float4 A[2] : register(c0); float4 B : register(c1);", "A[0] + B", None,
     {"A": (0, 1), "B": (1, 1)}),
    ("float4 A : register(c0); float4 B : register(c0);", "A", None, {"A": (0, 1)}),
    ("sampler A : register(s1); sampler B[2] : register(s0);",
     "tex2D(A, uv) + tex2D(B[1], uv)", "s1", None),
    ("sampler A : register(s1); sampler B[2] : register(s0);",
     "tex2D(A, uv) + tex2D(B[0], uv)", None, {"A": (1, 1), "B": (0, 1)}),
]


@pytest.mark.parametrize("globals_, expression, register, table", OVERLAPS)
def test_bindings_that_overlap_in_what_the_code_reads_are_refused_for_every_target(
        globals_, expression, register, table):
    functions = (f"{globals_}\nfloat4 PS(float2 uv : TEXCOORD0) : COLOR\n{{\n"
                 f"    return {expression};\n}}")
    for target in ("ps_2_0", "ps_3_0"):
        fx = effects.load_effect(functions + TECHNIQUE)
        if register is None:
            shader = compile_shader(fx, "PS", target)
            got = {**shader.constants, **shader.sampler_table()}
            assert {k: got[k] for k in table} == table
            continue
        err = compile_error(functions, target)
        assert err.message == (f"X4500: overlapping register semantics not yet implemented "
                               f"'{register}': 'A' and 'B' are both bound to {register}")
        # located at the later declaration's name
        at = (err.location.line, err.location.column)
        assert err.language is True and at == (1, globals_.index(" B") + 2)


def test_the_flag_is_set_where_the_error_is_made_and_a_raise_may_say():
    assert HlslError("X3004: undeclared identifier 'a'").language is True
    assert HlslError("X3512: array index must be a literal expression").language is False
    assert HlslError("internal: no register holds the value").language is False
    assert HlslError("X3004: said otherwise", language=False).language is False
    assert EffectError("a parse error").language is False


def test_the_disk_store_keeps_the_flag(tmp_path):
    fx = effects.load_effect(LANGUAGE["X3004"][0] + TECHNIQUE)
    value = fx.techniques[0].passes[0].state("PixelShader").value
    assert disk_store.enable(str(tmp_path))
    try:
        name = store.key(cache.key_parts(fx, value, []), cache.declarations(fx), value.location)
        for made in (HlslError("X3004: undeclared identifier 'foo'", value.location, source_line="x"),
                     HlslError("X3004: undeclared identifier 'foo'", value.location, language=False)):
            store.save(name, made)
            back = store.load(name)
            assert type(back) is HlslError and str(back) == str(made)
            assert back.language is made.language and back.source_line == made.source_line
    finally:
        disk_store.disable()


# --- through #include and macros -----------------------------------------------------------------

def write(tmp_path, name: str, text: str) -> str:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text).lstrip("\n"))
    return str(path)


def only_error(path: str, entry: str = "PS") -> EffectError:
    fx = effects.load_effect(path)
    with pytest.raises(EffectError) as info:
        compile_shader(fx, entry, "ps_2_0")
    return info.value


def test_an_error_in_an_included_function_is_located_in_the_include(tmp_path):
    lib = write(tmp_path, "lib.fxh", """
        // shared lighting
        float4 Shade(float2 uv)
        {
            float3 n = normalize(float3(uv, 1));
            return float4(n * scalee, 1);
        }
        """)
    path = write(tmp_path, "main.fx", """
        #include "lib.fxh"
        float4 PS(float2 uv : TEXCOORD0) : COLOR { return Shade(uv); }
        technique T { pass P { PixelShader = compile ps_2_0 PS(); } }
        """)
    err = only_error(path)
    assert err.report() == (f"{lib}:5:23: error: X3004: undeclared identifier 'scalee'\n"
                            "    return float4(n * scalee, 1);\n"
                            "                      ^")


MACROS = """
    #define TINT(c) (c * Missing)
    #define SCALE 2.0 * 0.5
    #define TWICE(x) ((x) + (x))
    float4 Body(float2 uv : TEXCOORD0) : COLOR
    {
        return TINT(float4(uv, 0, 1));
    }
    float4 After(float2 uv : TEXCOORD0) : COLOR
    {
        float4 v = float4(uv, 0, 1);   return v * SCALE + /* c */ fooz;
    }
    float4 Argument(float2 uv : TEXCOORD0) : COLOR
    {
        float4 v = float4(uv, 0, 1);   return TWICE(v + quxx) ;
    }
    technique T { pass P { PixelShader = compile ps_2_0 Body(); } }
    """


@pytest.mark.parametrize("entry, line, column, name", [
    ("Body", 6, 12, "Missing"),       # in a macro's body: at the call, `TINT(`
    ("After", 10, 63, "fooz"),        # after an expansion on the line: where it is written
    ("Argument", 14, 53, "quxx"),     # in a macro's argument: where the argument is written
])
def test_an_error_in_a_macro_expanded_line_is_located_in_the_file_as_written(
        tmp_path, entry, line, column, name):
    # fxc reports the file's first error whichever entry is compiled (check.py): the other
    # functions' lines are blanked (each stays on its line)
    lines = MACROS.split("\n")
    starts = [k for k, text in enumerate(lines) if "(float2 uv : TEXCOORD0)" in text]
    for start, end in zip(starts, starts[1:] + [len(lines) - 2]):
        if f" {entry}(" not in lines[start]:
            lines[start:end] = [""] * (end - start)
    path = write(tmp_path, "macros.fx", "\n".join(lines))
    written = (tmp_path / "macros.fx").read_text().splitlines()[line - 1]
    assert written[column - 1:].startswith("TINT(" if name == "Missing" else name)
    err = only_error(path, entry)
    assert err.report() == (f"{path}:{line}:{column}: error: X3004: undeclared identifier "
                            f"'{name}'\n{written}\n{' ' * (column - 1)}^")


def test_a_path_that_falls_off_a_function_is_a_language_error_though_its_code_is_a_targets():
    # X3507 also names a target fxc does not compile for (a refusal for the target); this
    # raise marks itself: every target refuses the function, called or not
    functions = ("float g(float x)\n{\n    if (x > 0)\n        return 1;\n}\n"
                 "float4 PS() : COLOR\n{\n    return 1;\n}")
    for target in ("ps_2_0", "ps_3_0", "ps_1_1"):
        err = compile_error(functions, target)
        assert err.report() == ("<string>:1:7: error: X3507: 'g': Not all control paths return "
                                "a value\nfloat g(float x)\n      ^")
        assert err.language is True
