"""HLSL compile speed: a 150-line pixel shader function compiled for ps_2_0 (goal <= 20 ms),
and the two bundled HLSL effects, timed per stage (parse, evaluate + passes, codegen +
assembly) and in all, median of N runs, printed side by side.

    .venv/bin/python benchmarks/bench_hlsl.py
"""
from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import effects  # noqa: E402
from effects.shaders.hlsl import compile_shader  # noqa: E402
from effects.shaders.hlsl.context import load_context  # noqa: E402

RUNS = 15


def long_function(lines: int = 150) -> str:
    """A ps_2_0 function of `lines` lines: locals, swizzles, intrinsics, a flattened if and an
    unrolled loop, each line a statement (as long HLSL functions are written)."""
    body = ["float4 Long(float2 uv : TEXCOORD0, float4 col : COLOR0) : COLOR",
            "{", "    float4 acc = col;", "    float3 n = normalize(float3(uv, 1));"]
    k = 0
    while len(body) < lines - 3:
        k += 1
        body.append(f"    float t{k} = dot(n, float3({k % 5} * 0.1, 0.2, 0.3)) * Scale;")
        body.append(f"    acc.rgb = lerp(acc.rgb, acc.gbr * t{k}, 0.05);")
        body.append(f"    if (t{k} > 0.5) acc.a = acc.a * 0.99; else acc.a = acc.a + 0.001;")
        body.append(f"    n = n * 0.999 + float3(0.0001 * {k}, 0, 0);")
    body += ["    return saturate(acc);", "}"]
    return "\n".join(body[:lines - 1] + ["}"]) if len(body) > lines else "\n".join(body)


def median_ms(fn, runs: int = RUNS) -> float:
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        fn()
        times.append((time.perf_counter() - t) * 1000)
    return statistics.median(times)


def main() -> None:
    src = long_function()
    n_lines = src.count("\n") + 1
    fx = effects.load_effect("float Scale = 0.5;\n" + src +
                             "\ntechnique T { pass P { PixelShader = compile ps_2_0 Long(); } }\n")
    compile_shader(fx, "Long", "ps_2_0")   # warm: the grammar is built once per process
    rows = [(f"{n_lines}-line function, ps_2_0", fx, "Long", "ps_2_0")]
    wood = effects.load_effect(str(ROOT / "fxfiles" / "wood.fx"))
    rows += [("wood.fx Wood, ps_2_0", wood, "Wood", "ps_2_0"),
             ("wood.fx WoodVS, vs_1_1", wood, "WoodVS", "vs_1_1")]
    marble = effects.load_effect(str(ROOT / "fxfiles" / "sdk9_style.fx"))
    rows.append(("sdk9_style.fx MarbleVS(1), vs_1_1", marble, "MarbleVS", "vs_1_1"))
    from effects.shaders.hlsl import parse as parse_module
    print(f"{'shader':38} {'parse ms':>9} {'total ms':>9} {'cached tree':>12} {'slots':>6}")
    for label, effect, entry, target in rows:
        args = ("1",) if entry == "MarbleVS" else ()

        def cold(fn):
            def run():
                parse_module._TREES.clear()   # as the first compile after a load
                fn()
            return run
        parse = median_ms(cold(lambda: load_context(effect, target)))
        total = median_ms(cold(lambda: compile_shader(effect, entry, target, args)))
        warm = median_ms(lambda: compile_shader(effect, entry, target, args))
        slots = compile_shader(effect, entry, target, args).program.stats.total_slots
        print(f"{label:38} {parse:9.1f} {total:9.1f} {warm:12.1f} {slots:6d}")
    parse_module._TREES.clear()
    goal = median_ms(cold(lambda: compile_shader(fx, "Long", "ps_2_0")))
    print(f"goal: {n_lines}-line function for ps_2_0 <= 20 ms: {goal:.1f} ms "
          f"({'met' if goal <= 20 else 'NOT met'})")


if __name__ == "__main__":
    main()
