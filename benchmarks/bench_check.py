"""What the whole-file check (effects/shaders/hlsl/check.py, issue 30) costs.

    .venv/bin/python benchmarks/bench_check.py [--runs 9]

Rows:
- the first compile after an edit (no parse tree, no check kept) of bench_hlsl's goal row
  (benchmarks/data/lighting_ps20.fx) and of a dense 150-line function, with the check and
  with it taken out (check_unit answering None): the difference is the check's price on a
  reload. Later compiles of the same file (other targets, cards) find the check kept.
- the check alone, cold, over every effect with HLSL functions in fxfiles/ and
  tests/data/realfx/: files, functions walked, total and per function.
- `load_effect` of bench_load's 1,000-line effect: the check does not run at load (it runs
  with the first compile), so this row is the same with and without it.
In-process figures are CPU time (time.process_time), median of --runs.
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

import effects  # noqa: E402
from bench_hlsl import REALISTIC, long_effect  # noqa: E402
from bench_load import make_effect  # noqa: E402
from effects.model import CompileShader  # noqa: E402
from effects.shaders.hlsl import check, compile_shader  # noqa: E402
from effects.shaders.hlsl import parse as parse_module  # noqa: E402


def cpu_ms(fn, runs: int) -> float:
    times = []
    for _ in range(runs):
        start = time.process_time()
        fn()
        times.append((time.process_time() - start) * 1000)
    return statistics.median(times)


def first_compile(fx: effects.Effect, entry: str, args: tuple[str, ...]):
    def run():
        parse_module._TREES.clear()
        check._CHECKED.clear()
        compile_shader(fx, entry, "ps_2_0", args)
    return run


def without_check(fn):
    def run():
        real = check.check_unit
        import effects.shaders.hlsl.compiler as compiler
        compiler.check_unit = lambda effect, unit=None: None
        try:
            fn()
        finally:
            compiler.check_unit = real
    return run


def bench_compiles(runs: int) -> None:
    print(f"{'first compile after an edit, ps_2_0':40} {'with':>8} {'without':>8} {'check':>8}")
    fx = effects.load_effect(str(REALISTIC))
    value = next(s.value for t in fx.techniques for p in t.passes for s in p.states
                 if isinstance(s.value, CompileShader))
    rows = [("realistic 150 lines (lighting_ps20)", fx, value.function, value.args),
            ("dense 150 lines", long_effect(150), "Long", ())]
    for label, effect, entry, args in rows:
        run = first_compile(effect, entry, args)
        with_ms = cpu_ms(run, runs)
        without_ms = cpu_ms(without_check(run), runs)
        print(f"{label:40} {with_ms:6.1f}ms {without_ms:6.1f}ms {with_ms - without_ms:6.1f}ms")


def bench_files(runs: int) -> None:
    paths = sorted((ROOT / "fxfiles").glob("*.fx")) + \
        sorted((ROOT / "tests" / "data" / "realfx").rglob("*.fx"))
    loaded = []
    for path in paths:
        try:
            fx = effects.load_effect(str(path))
        except effects.EffectError:
            continue
        if fx.functions:
            loaded.append(fx)
    functions = sum(len(fx.functions) for fx in loaded)

    def run():
        parse_module._TREES.clear()
        check._CHECKED.clear()
        for fx in loaded:
            check.check_unit(fx)
    ms = cpu_ms(run, runs)
    print(f"check alone, cold: {len(loaded)} files, {functions} functions: {ms:.1f}ms "
          f"({ms / max(functions, 1):.2f}ms a function, parse included)")


def bench_load(runs: int) -> None:
    text = make_effect(1000)
    effects.load_effect(text)
    print(f"load_effect, bench_load's 1,000 lines: {cpu_ms(lambda: effects.load_effect(text), runs):.1f}ms")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=9)
    args = ap.parse_args()
    bench_compiles(args.runs)
    bench_files(args.runs)
    bench_load(args.runs)


if __name__ == "__main__":
    main()
