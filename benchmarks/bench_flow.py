"""The cost of Shader Model 3 flow control: fxfiles/multilight.fx's ps_3_0 technique (a loop
over four lights, c[aL] by relative addressing) against its ps_2_0 technique (the same sum
unrolled), side by side on both back ends, with the loop's share of the reference's time.

    .venv/bin/python benchmarks/bench_flow.py [--size 512] [--repeat 3]

The reference evaluator runs structured IR with per-fragment masks (every instruction of the
body once per iteration on all fragments) and without its demand analysis; c[aL + n] is a
select over the registers the loop's aL can reach. GL runs real for loops.
"""
from __future__ import annotations

import argparse
from pathlib import Path

import effects
from effects.d3d9.caps import load_profile
from bench_scale import best  # one timing helper for the benchmarks

FX = Path(__file__).resolve().parent.parent / "fxfiles" / "multilight.fx"


def best_of(fn, repeat: int) -> float:
    fn()                                   # warm: programs, caches, GL context
    return best(fn, repeat)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    effect = effects.load_effect(str(FX))
    size = (args.size, args.size)
    rows = {}
    for label, card in (("ps_3_0 loop", "geforce6800"), ("ps_2_0 unrolled", "radeon9700")):
        profile = load_profile(card)
        rows[label] = [best_of(lambda b=b: effects.render(effect, profile, backend=b, size=size),
                               args.repeat) for b in ("numpy", "gl")]
    print(f"multilight.fx at {args.size} x {args.size}, best of {args.repeat}")
    print(f"{'technique':<18}{'numpy ms':>10}{'gl ms':>10}")
    for label, (ref, gl) in rows.items():
        print(f"{label:<18}{ref * 1000:>10.1f}{gl * 1000:>10.1f}")
    loop, flat = rows["ps_3_0 loop"], rows["ps_2_0 unrolled"]
    print(f"loop / unrolled: numpy {loop[0] / flat[0]:.2f}x, gl {loop[1] / flat[1]:.2f}x")


if __name__ == "__main__":
    main()
