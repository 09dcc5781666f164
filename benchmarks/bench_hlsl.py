"""HLSL compile speed (issue 11) and the compile cache (issue 15's `effects matrix` row), side by
side in one run.

    .venv/bin/python benchmarks/bench_hlsl.py [--runs 9] [--before DIR]

Rows:
- the goal row: a realistic 150-line ps_2_0 function (benchmarks/data/lighting_ps20.fx,
  `LightingPS`: SDK-style per-pixel lighting, 27 comment/blank lines, 61 of ps_2_0's 64
  arithmetic slots) compiled cold: parse, evaluate + code generation, writing the records and
  the listing (writer.py; before issue 31's writer this column was the assembler parsing the
  generated text back), the whole.
  Goal: <= 20 ms.
- dense N-line functions (38 / 75 / 150 / 300 lines), generated: every line a statement that
  costs instructions (the 150-line one is 618 slots, ~10x what ps_2_0 holds, which fxc would
  refuse; compiled here for ps_2_0 anyway to time the compiler at size). Same columns; the
  exponent is the least-squares slope of log(time) over log(lines) (bench_scale's fit).
- the bundled HLSL shaders compiled cold, and a `compile` state answered by the cache.
- every technique of fxfiles/*.fx validated on the 19 cards in one process: how many compiles
  ran, and the time.
- `effects --help` and `effects matrix fxfiles/*.fx` as commands (interpreter start included):
  wall time, and the CPU time of the child (steadier on a loaded machine). `--before DIR` runs
  the commands in another checkout too (e.g. `git worktree add /tmp/before COMMIT`), side by side.
In-process figures are CPU time (time.process_time), median of --runs.
"""
from __future__ import annotations

import argparse
import contextlib
import io
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

import effects  # noqa: E402
from bench_scale import exponent  # noqa: E402
from effects.base.errors import Location  # noqa: E402
from effects.model import CompileShader  # noqa: E402
from effects.shaders.hlsl import cache, compile_shader, compile_state  # noqa: E402
from effects.shaders.hlsl import parse as parse_module  # noqa: E402
from effects.shaders.hlsl.compiler import (Compilation, allocate_registers, list_program,  # noqa: E402
                                           run_passes, write_program)
from effects.shaders.hlsl.context import load_context  # noqa: E402

GOAL_150_MS = 20.0
SIZES = (38, 75, 150, 300)
REALISTIC = ROOT / "benchmarks" / "data" / "lighting_ps20.fx"


def long_function(lines: int = 150) -> str:
    """A ps_2_0 function of `lines` lines: locals, swizzles, intrinsics, a flattened if and an
    unrolled loop, each line a statement (as long HLSL functions are written)."""
    head = ["float4 Long(float2 uv : TEXCOORD0, float4 col : COLOR0) : COLOR",
            "{", "    float4 acc = col;", "    float3 n = normalize(float3(uv, 1));"]
    statements: list[str] = []
    k = 0
    while len(statements) < lines - 6:
        k += 1
        statements += [f"    float t{k} = dot(n, float3({k % 5} * 0.1, 0.2, 0.3)) * Scale;",
                       f"    acc.rgb = lerp(acc.rgb, acc.gbr * t{k}, 0.05);",
                       f"    if (t{k} > 0.5) acc.a = acc.a * 0.99; else acc.a = acc.a + 0.001;",
                       f"    n = n * 0.999 + float3(0.0001 * {k}, 0, 0);"]
    return "\n".join(head + statements[:lines - 6] + ["    return saturate(acc);", "}"])


def long_effect(lines: int) -> effects.Effect:
    return effects.load_effect("float Scale = 0.5;\n" + long_function(lines) +
                               "\ntechnique T { pass P { PixelShader = compile ps_2_0 Long(); } }\n")


def cpu_ms(fn, runs: int) -> float:
    times = []
    for _ in range(runs):
        start = time.process_time()
        fn()
        times.append((time.process_time() - start) * 1000)
    return statistics.median(times)


def cold(fn):
    """`fn` as the first compile after an edit: no parse tree kept for the text."""
    def run():
        parse_module._TREES.clear()
        fn()
    return run


def _row(label: str, fx: effects.Effect, entry: str, args: tuple[str, ...], runs: int) -> float:
    """Print parse / eval+gen / write / total of one cold compile; return the total."""
    shader = compile_shader(fx, entry, "ps_2_0", args)
    c = run_passes(Compilation(fx, entry, "ps_2_0", args, Location(fx.path, 1, 1)),
                   allocate_registers)
    parse = cpu_ms(cold(lambda: load_context(fx, "ps_2_0")), runs)
    total = cpu_ms(cold(lambda: compile_shader(fx, entry, "ps_2_0", args)), runs)
    asm = cpu_ms(lambda: (write_program(c), list_program(c)), runs)
    stats = shader.program.stats
    print(f"{label:34} {parse:6.1f}ms {total - parse - asm:7.1f}ms {asm:7.1f}ms "
          f"{total:6.1f}ms {stats.total_slots:6d} {stats.arithmetic_slots:5d}")
    return total


def bench_sizes(runs: int) -> None:
    print(f"{'ps_2_0 function, cold':34} {'parse':>8} {'eval+gen':>9} {'write':>9} "
          f"{'total':>8} {'slots':>6} {'arith':>5}")
    fx = effects.load_effect(str(REALISTIC))
    value = next(s.value for t in fx.techniques for p in t.passes for s in p.states
                 if isinstance(s.value, CompileShader))
    real = _row("realistic 150 lines (lighting_ps20)", fx, value.function, value.args, runs)
    totals = [_row(f"dense {lines:3d} lines", long_effect(lines), "Long", (), runs)
              for lines in SIZES]
    print(f"goal (the realistic 150-line ps_2_0 function) <= {GOAL_150_MS:.0f} ms: {real:.1f} ms, "
          f"{'met' if real <= GOAL_150_MS else 'NOT met'}; dense 150 lines (618 slots, not a "
          f"ps_2_0 program): {totals[SIZES.index(150)]:.1f} ms; exponent (dense total over "
          f"lines): {exponent(SIZES, totals):.2f}\n")


def bench_bundled(runs: int) -> None:
    wood = effects.load_effect(str(ROOT / "fxfiles" / "wood.fx"))
    marble = effects.load_effect(str(ROOT / "fxfiles" / "sdk9_style.fx"))
    scene = effects.load_effect(str(ROOT / "fxfiles" / "sdk9_hlsl.fx"))
    rows = [("wood.fx Wood, ps_2_0", wood, "Wood", "ps_2_0", ()),
            ("wood.fx WoodVS, vs_1_1", wood, "WoodVS", "vs_1_1", ()),
            ("sdk9_style.fx MarbleVS(1), vs_1_1", marble, "MarbleVS", "vs_1_1", ("1",)),
            ("sdk9_hlsl.fx ScenePS(true), ps_2_0", scene, "ScenePS", "ps_2_0", ("true",))]
    print(f"{'bundled shader':38} {'cold':>8} {'cached':>10} {'slots':>6}")
    for label, fx, entry, target, args in rows:
        value = CompileShader(target, entry, args, fx.functions[0].location)
        total = cpu_ms(cold(lambda: compile_shader(fx, entry, target, args, value.location)), runs)
        compile_state(fx, value)
        hit = cpu_ms(lambda: compile_state(fx, value), runs * 20)
        slots = compile_state(fx, value).program.stats.total_slots
        print(f"{label:38} {total:6.1f}ms {hit * 1000:7.0f} us {slots:6d}")
    print()


def bench_validation(runs: int) -> None:
    files = sorted((ROOT / "fxfiles").glob("*.fx"))
    loaded = [effects.load_effect(str(p)) for p in files]
    cards = [effects.load_profile(name) for name in effects.list_profiles()]
    compiles = []
    real = compile_shader.__globals__["compile_shader"]

    def counting(*a, **k):
        compiles.append(1)
        return real(*a, **k)

    def validate_all():
        cache.clear()
        parse_module._TREES.clear()
        compiles.clear()
        for fx in loaded:
            for card in cards:
                for technique in fx.techniques:
                    fx.validate(technique, card)
    from effects.shaders.hlsl import compiler
    compiler.compile_shader = counting          # counted: compile_state calls it on a miss
    try:
        spent = cpu_ms(validate_all, max(3, runs // 3))
    finally:
        compiler.compile_shader = real
    states = sum(isinstance(s.value, CompileShader) for fx in loaded for t in fx.techniques
                 for p in t.passes for s in p.states)
    print(f"validate every technique of {len(files)} fxfiles on {len(cards)} cards: "
          f"{spent:.0f} ms CPU, {len(compiles)} compiles for {states} compile states "
          f"x {len(cards)} cards\n")


def _command(argv: list[str], cwd: Path, runs: int) -> tuple[float, float]:
    """(median wall ms, median child CPU ms) of `python -m effects ARGV` run in `cwd`
    (`FXFILES` in ARGV: that checkout's fxfiles/*.fx)."""
    if "FXFILES" in argv:
        k = argv.index("FXFILES")
        argv = argv[:k] + [str(p.relative_to(cwd)) for p in sorted((cwd / "fxfiles").glob("*.fx"))]
    walls, cpus = [], []
    for _ in range(runs):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "effects", *argv], cwd=cwd,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
        walls.append((time.perf_counter() - start) * 1000)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append((after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime) * 1000)
    return statistics.median(walls), statistics.median(cpus)


def bench_commands(runs: int, before: Path | None) -> None:
    rows = [("effects --help", ["--help"], 60.0),
            ("effects matrix fxfiles/*.fx", ["matrix", "FXFILES"], 300.0)]
    head = f"{'command':30} {'wall':>9} {'CPU':>9}"
    print(head + (f" {'before wall':>12} {'before CPU':>11} {'CPU ratio':>10}" if before else "")
          + "  goal")
    for label, argv, goal in rows:
        # interleaved, so both checkouts see the same load
        wall, cpu = _command(argv, ROOT, runs)
        line = f"{label:30} {wall:7.0f}ms {cpu:7.0f}ms"
        if before is not None:
            bwall, bcpu = _command(argv, before, runs)
            line += f" {bwall:10.0f}ms {bcpu:9.0f}ms {bcpu / cpu:9.2f}x"
        print(f"{line}  <= {goal:.0f} ms wall")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=9)
    ap.add_argument("--before", type=Path, help="another checkout to run the commands in")
    ap.add_argument("--only", default="sizes,bundled,validation,commands")
    args = ap.parse_args(argv)
    compile_shader(long_effect(38), "Long", "ps_2_0")      # the grammar, once per process
    only = set(args.only.split(","))
    with contextlib.redirect_stderr(io.StringIO()):
        if "sizes" in only:
            bench_sizes(args.runs)
        if "bundled" in only:
            bench_bundled(args.runs)
        if "validation" in only:
            bench_validation(args.runs)
    if "commands" in only:
        bench_commands(args.runs, args.before)
    return 0


if __name__ == "__main__":
    sys.exit(main())
