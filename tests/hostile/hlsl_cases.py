"""Hostile HLSL (issue 33, the compiler's side): one function per case, run by
tests/hostile/test_hostile_hlsl.py in child processes holding at most 1 GiB, their work metered, as
hostile_cases.py's are (this module reuses its runner: run as a script, it adds its cases to
hostile_cases.CASES and runs them the same way).

Each case compiles a function (`compiled`: the assembly, or the located error), evaluates an
effect-level expression, or validates; most build their input as text first and return a
function, so only what the framework does with it is metered.
"""
from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import Callable

CASES: dict[str, Callable[[Path], object]] = {}


def case(fn: Callable[[Path], object]) -> Callable[[Path], object]:
    CASES[fn.__name__] = fn
    return fn


def compiled(body: str, target: str = "ps_2_0", pre: str = "") -> Callable[[], str]:
    """A function `f(float2 uv : TEXCOORD0)` with `body`, compiled when called: its assembly
    without the version line."""
    semantic = "COLOR" if target.startswith("ps") else "POSITION"
    text = f"{pre}\nfloat4 f(float2 uv : TEXCOORD0) : {semantic}\n{{\n{body}\n}}\n"

    def run() -> str:
        import effects
        from effects.shaders.hlsl.compiler import compile_shader
        shader = compile_shader(effects.load_effect(text), "f", target)
        return " | ".join(shader.text.strip().splitlines()[1:])[:1500]
    return run


def state(pre: str, name: str, expression: str) -> Callable[[], object]:
    """The value of state `name = expression` at the parameters' current values."""
    text = f"{pre}\ntechnique t {{ pass p {{ {name} = {expression}; }} }}\n"

    def run() -> object:
        import effects
        from effects.shaders.hlsl.preshader import state_value
        effect = effects.load_effect(text)
        [assignment] = effect.techniques[0].passes[0].states
        return state_value(name, None, assignment.value.text, assignment.value.location, effect)
    return run


def reasons(text: str, card: str = "radeon9700") -> Callable[[], object]:
    def run() -> object:
        import effects
        effect = effects.load_effect(text)
        v = effect.validate(effect.techniques[0], effects.load_profile(card))
        return [v.ok] + [str(r) for r in v.reasons] + [str(w) for w in v.warnings]
    return run


# ---------------------------------------------------------------------------------------------
# 1. nesting: deep but legal programs compile; past the limits, a located error

@case
def flat_sum_of_5000_literals(d):
    # 1 + 2 + ... + 5000 = 12,502,500: one constant
    return compiled("return " + " + ".join(str(k) for k in range(1, 5001)) + ";")


@case
def flat_sum_of_5000_terms_that_fold(d):
    # uv.x * 0 is 0 (x * 0 folds): 5,000 of them and 0.5 is 0.5
    return compiled("return " + " + ".join(["uv.x * 0"] * 5000) + " + 0.5;")


@case
def nested_expression_1000_deep(d):
    # ((((0 + 1) * 1) + 1) * 1) ...: 1,000 levels of parentheses, 500 additions of 1
    text = "0"
    for k in range(1000):
        text = f"({text} + 1)" if k % 2 == 0 else f"({text} * 1)"
    return compiled(f"return {text};")


@case
def negation_1000_deep(d):
    # - ( - ( ... uv.x ) ): an even count is uv.x itself
    return compiled("return " + "-(" * 1000 + "uv.x" + ")" * 1000 + ";")


@case
def calls_nested_1000_deep_as_arguments(d):
    # g(g(...g(1)...)) with g(x) = x * 0.5 + 0.5: each call is inlined after its argument,
    # not inside it; the fixed point of x -> x/2 + 1/2 is 1
    return compiled("return " + "g(" * 1000 + "1" + ")" * 1000 + ";",
                    pre="float g(float x) { return x * 0.5 + 0.5; }")


@case
def casts_and_swizzles_1000_deep(d):
    # (float2)((float2)(uv.yx).yx ...): 500 casts, 500 swaps: uv as it was
    return compiled("return float4(" + "(float2)(" * 500 + "uv" + ".yx)" * 500 + ", 0, 1);")


@case
def initializer_braces_1000_deep(d):
    return compiled("float4 v = " + "{" * 1000 + "1, 2, 3, 4" + "}" * 1000 + "; return v;")


@case
def blocks_65_deep(d):
    return compiled("float s = uv.x; " + "{" * 65 + "s += 1;" + "}" * 65 + " return s;")


@case
def ifs_30_deep(d):
    # 30 ifs, each with its block: 60 levels of 64; one addition under the same predicate
    # (uv.x > 0) thirty times over is one select: cmp between uv.x and uv.x + 1
    return compiled("float s = uv.x; " + "if (s > 0) {" * 30 + "s += 1;" + "}" * 30 +
                    " return s;")


@case
def call_chain_30_deep(d):
    # g29 -> g28 -> ... -> g0: not recursion; 30 nested calls take 60 levels of 64
    pre = "float g0(float x) { return x; }\n" + "".join(
        f"float g{k}(float x) {{ return g{k - 1}(x); }}\n" for k in range(1, 30))
    return compiled("return g29(uv.x);", pre=pre)


@case
def call_chain_40_deep(d):
    pre = "float g0(float x) { return x; }\n" + "".join(
        f"float g{k}(float x) {{ return g{k - 1}(x); }}\n" for k in range(1, 40))
    return compiled("return g39(uv.x);", pre=pre)


@case
def recursion(d):
    return compiled("return r(uv.x);",
                    pre="float r(float x) { if (x > 0) return r(x - 1); return 0; }")


@case
def struct_nested_100_deep(d):
    pre = "struct S0 { float a; };\n" + "".join(
        f"struct S{k} {{ S{k - 1} a; }};\n" for k in range(1, 100))
    return compiled("S99 s = (S99)0; return 1;", pre=pre)


@case
def array_of_100_dimensions(d):
    return compiled("float a" + "[1]" * 100 + "; return 1;")


@case
def l_value_1000_swizzles_deep(d):
    # s.x.x.x...x = 3: 1,000 swizzles of a scalar, written
    return compiled("float s = uv.x; s" + ".x" * 1000 + " = 3; return s;")


@case
def index_inside_index_70_deep(d):
    # a[a[...a[0] = 0 ...] = 0] = 1: each index re-enters the evaluator through the l-value
    # it is written to (one level each)
    lvalue = "a[0]"
    for _ in range(70):
        lvalue = f"a[{lvalue} = 0]"
    return compiled(f"float a[2] = {{0, 0}}; {lvalue} = 1; return a[0];")


@case
def chained_initializers_500(d):
    # P0 = 0.25, Pk = P(k-1) + 1: P499 = 499.25
    pre = "float P0 = 0.25;\n" + "".join(f"float P{k} = P{k - 1} + 1;\n" for k in range(1, 500))
    return state(pre, "FogDensity", "P499 * 0.001")


@case
def chained_static_initializers_500_in_a_shader(d):
    pre = "static float P0 = 0.25;\n" + "".join(
        f"static float P{k} = P{k - 1} + 1;\n" for k in range(1, 500))
    return compiled("return P499;", pre=pre)


@case
def initializer_cycle(d):
    return state("float A = B + 1; float B = C * 2; float C = A;", "FogDensity", "A * 1")


@case
def state_expression_sum_of_5000_terms(d):
    return state("float A = 0.001;", "FogDensity", " + ".join(["A"] * 5000))


# ---------------------------------------------------------------------------------------------
# 2. folding inf, NaN and huge values

@case
def frac_of_nan(d):
    return compiled("float z = 0; return frac(z / z);")


@case
def frac_of_infinity(d):
    return compiled("return frac(1e300 * 1e300);")       # inf even in float64: NaN


@case
def float_literal_past_float32(d):
    return compiled("return uv.x * 1e39;")


@case
def nan_constant_read_by_code(d):
    return compiled("float z = 0; return uv.x * (z / z);")


@case
def shift_by_negative_count(d):
    # 1 << -1 is 1 << 31 (the count's low five bits): int -2147483648
    return compiled("int a = 1 << -1; return a;")


@case
def shift_by_2_to_the_31(d):
    # 2147483648 as an int saturates to 2147483647: low five bits 31
    return compiled("int a = 1 << 2147483648; return a;")


@case
def shift_by_34(d):
    return compiled("int a = 1 << 34; return a;")


@case
def bitwise_not_of_infinity(d):
    # (int)inf saturates to 2147483647; ~2147483647 = -2147483648
    return compiled("return ~(int)(1e300 * 1e300);")


@case
def integer_division_by_zero(d):
    return compiled("int a = 7; int b = 0; return a / b;")


@case
def integer_modulo_by_zero(d):
    return compiled("int a = 7; int b = 0; return a % b;")


@case
def float_modulo_by_zero(d):
    return compiled("return 7.0 % 0.0;")


@case
def nan_index(d):
    return compiled("float z = 0; float a[2] = {1, 2}; return a[z / z];")


@case
def infinite_index(d):
    return compiled("float a[2] = {1, 2}; return a[1e300 * 1e300];")


@case
def int_literal_5000_digits(d):
    return compiled("return " + "7" * 5000 + ";")


@case
def hex_literal_300_digits(d):
    return compiled("return 0x" + "f" * 300 + ";")


@case
def register_number_5000_digits(d):
    return compiled("return C;", pre="float4 C : register(c" + "9" * 5000 + ");")


@case
def log_sqrt_pow_of_negatives(d):
    # D3D log and rsq take |x|; pow is |a|^b: log2(4) = 2, 1/rsq(|-4|) = 2, |-2|^0.5
    return compiled("return float4(log2(-4), sqrt(-4), pow(-2, 2), exp2(-1));")


@case
def asin_outside_its_domain(d):
    return compiled("return asin(2) + acos(-3);")


@case
def exp_overflow(d):
    return compiled("return exp(1e30);")


@case
def state_expression_folding_nan(d):
    return state("float A = 0;", "FogDensity", "A / A")


@case
def normalize_of_zero(d):
    # nrm of a zero vector scales by FLT_MAX: 0 (the IR's kernel), not NaN
    return compiled("float3 z = 0; return float4(normalize(z), 1);", "ps_2_0")


@case
def asm_def_past_float32(d):
    # the same value written by hand: a def register is a float32 (an IRError at render before)
    def run() -> object:
        import effects
        effect = effects.load_effect("technique t { pass p { PixelShader = asm { ps_2_0\n"
                                     " def c0, 1e39, 0, 0, 0\n mov oC0, c0\n }; } }")
        return effects.render(effect, "radeon9700", technique="t", size=(4, 4))
    return run


# ---------------------------------------------------------------------------------------------
# 3. the work budget and local storage

@case
def local_array_of_a_billion(d):
    return compiled("float a[1000000000]; return a[0];")


@case
def local_array_of_65536_float4(d):
    return compiled("float4 a[65536]; return a[0];")


@case
def vector_of_2147483647(d):
    return compiled("vector<float, 2147483647> v; return v.x;")


@case
def struct_doubling_30_levels(d):
    pre = "struct S0 { float4 a; float4 b; };\n" + "".join(
        f"struct S{k} {{ S{k - 1} a; S{k - 1} b; }};\n" for k in range(1, 30))
    return compiled("S29 s = (S29)0; return s.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a.a;",
                    pre=pre)


@case
def nested_loops_1000_by_1000(d):
    return compiled("float s = 0; for (int i = 0; i < 1000; i++) for (int j = 0; j < 1000; j++) "
                    "s += 1; return s;")


@case
def call_fan_out_2_to_the_20(d):
    pre = "float f0(float x) { return x * 2; }\n" + "".join(
        f"float f{k}(float x) {{ return f{k - 1}(x) + f{k - 1}(x * 0.5); }}\n" for k in range(1, 21))
    return compiled("return f20(uv.x);", pre=pre)


@case
def big_local_in_a_long_loop(d):
    return compiled("float s = 0; for (int i = 0; i < 1000; i++) { float a[60000]; a[i] = i; "
                    "s += a[i]; } return s;")


@case
def loop_that_never_ends_with_a_heavy_body(d):
    return compiled("float4 s = uv.xyxy; for (int i = 0; i < 10; i += 0) "
                    "{ s = s * s + sin(s) * cos(s) + normalize(s) + tex2D(S, s.xy); } return s;",
                    pre="sampler S;")


@case
def while_true(d):
    return compiled("float4 s = uv.xyxy; while (true) { s = s * s + sin(s); } return s;")


@case
def loop_counted_by_a_uniform_on_ps_2_0(d):
    return compiled("float4 s = uv.xyxy; for (int i = 0; i < N; i++) { s = s * s + sin(s); } "
                    "return s;", pre="int N = 4;")


@case
def loop_on_a_run_time_condition(d):
    return compiled("float4 s = uv.xyxy; for (int i = 0; i < uv.x * 100; i++) "
                    "{ s = s * s + sin(s); } return s;")


@case
def loop_1025_iterations(d):
    return compiled("float s = 0; for (int i = 0; i < 1025; i++) s += 1; return s;")


# ---------------------------------------------------------------------------------------------
# 5, 7, 8: derived parameters, legal inputs once refused, wrongly accepted types

@case
def derived_parameter_in_a_state(d):
    # Size0 = 100, Size = 200, PointSize = 400 > the Modern profile's MaxPointSize 256: a
    # warning that names both reads (this crashed validation: float() of an Expression)
    return reasons("float Size0 = 100; float Size = Size0 * 2;\n"
                   "technique t { pass p { PointSize = Size * 2; } }", "modern")


@case
def loop_of_exactly_1024_iterations(d):
    return compiled("float s = 0; for (int i = 0; i < 1024; i++) s += 1; return s;")


@case
def unroll_1024_attribute(d):
    return compiled("float s = 0; [unroll(1024)] for (int i = 0; i < 1024; i++) s += 2; "
                    "return s;")


@case
def sampler_array_with_a_constant_index(d):
    return compiled("return tex2D(SA[1], uv) + tex2D(SA[0], uv) * 0.5;", pre="sampler SA[2];")


@case
def sampler_array_index_past_its_end(d):
    return compiled("return tex2D(SA[2], uv);", pre="sampler SA[2];")


@case
def matrix_swizzle_of_5_components(d):
    return compiled("float4x4 m = 0; return m._m00_m01_m02_m03_m10;")


@case
def matrix_9_by_9(d):
    return compiled("matrix<float, 9, 9> m; return 1;")


@case
def vector_of_0(d):
    return compiled("vector<float, 0> v; return 1;")


@case
def vector_constructor_of_5(d):
    return compiled("return vector<float, 5>(1, 2, 3, 4, 5).x;")


# ---------------------------------------------------------------------------------------------
# the child process: hostile_cases' runner over these cases

if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import hostile_cases as base
    base.CASES.clear()
    base.CASES.update(CASES)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    base._limit_memory()
    base.install_alarms()
    import effects  # noqa: F401 - imported before the clock starts
    from effects.shaders.hlsl.parse import parser
    parser()                    # the compiler and its grammar too
    for name in sys.argv[1:]:
        print(json.dumps({"case": name, "started": True}), flush=True)
        print(json.dumps(base.run_case(name)), flush=True)
