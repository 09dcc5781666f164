"""Time `load_effect` on a generated 1,000-line effect (goal: 30 ms or less).

    python benchmarks/bench_load.py [--lines 1000] [--runs 20] [--profile]

The effect mixes what real files hold: parameters with annotations and initialisers,
samplers, named asm shaders, and several techniques whose passes set texture-stage and
render states and carry asm blocks. It prints the median of `--runs` timed loads after one
warm-up load (which also builds the parser tables), in milliseconds.
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time

import effects

_STAGE_OPS = ("Modulate", "SelectArg1", "Add", "Modulate2x", "DotProduct3", "BlendTextureAlpha")


def make_effect(lines: int = 1000) -> str:
    """Effect source of about `lines` lines."""
    out: list[str] = []
    i = 0
    # parameters: about a fifth of the file
    while len(out) < lines // 5:
        out += [
            f"float4 Color{i} : COLOR{i % 4} < string UIName = \"Colour {i}\"; float UIMin = 0.0; > "
            f"= {{0.5, 0.25, 1.0, 1.0}};",
            f"float4x4 World{i} : WORLD;",
            f"texture Tex{i} < string ResourceName = \"tex{i}.png\"; >;",
            f"sampler S{i} = sampler_state {{ Texture = <Tex{i}>; MinFilter = Linear; "
            f"MagFilter = Linear; AddressU = Wrap; }};",
            f"DWORD Flags{i} = 0xff2020{i % 100:02d};",
        ]
        i += 1
    out += ["PixelShader SharedPS = asm", "{", "    ps.1.1", "    tex t0", "    tex t1",
            "    mul r0, t0, t1", "};", ""]
    t = 0
    while len(out) < lines - 2:
        out += [f"technique T{t}", "<", f"    int Quality = {t % 5};", ">", "{"]
        for p in range(3):
            out += [f"    pass P{p}", "    {"]
            for stage in range(2):
                op = _STAGE_OPS[(t + p + stage) % len(_STAGE_OPS)]
                out += [
                    f"        ColorOp[{stage}] = {op};",
                    f"        ColorArg1[{stage}] = Texture;",
                    f"        ColorArg2[{stage}] = Diffuse | Complement;",
                    f"        AlphaOp[{stage}] = SelectArg1;",
                    f"        Texture[{stage}] = <Tex{(t + stage) % i}>;",
                    f"        MinFilter[{stage}] = Linear;",
                ]
            out += [
                "        AlphaBlendEnable = TRUE;",
                "        SrcBlend = SrcAlpha;",
                "        DestBlend = InvSrcAlpha;",
                "        ZWriteEnable = FALSE;",
                f"        VertexShaderConstant[0] = <World{t % i}>;",
                "        VertexShader = asm",
                "        {",
                "            vs.1.1",
                "            dcl_position v0",
                "            m4x4 oPos, v0, c0",
                "            mov oD0, c4",
                "        };",
                "        PixelShader = <SharedPS>;" if p else "        PixelShader = asm { ps.1.1 mov r0, v0 };",
                "    }",
            ]
        out += ["}", ""]
        t += 1
    return "\n".join(out) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lines", type=int, default=1000)
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--profile", action="store_true", help="print a cProfile of one load")
    args = ap.parse_args(argv)

    source = make_effect(args.lines)
    effect = effects.load_effect(source)  # warm-up: builds the parser tables
    states = sum(len(p.states) for t in effect.techniques for p in t.passes)
    times = []
    for _ in range(args.runs):
        start = time.perf_counter()
        effects.load_effect(source)
        times.append((time.perf_counter() - start) * 1000.0)
    print(f"load_effect: {source.count(chr(10))} lines, {len(effect.parameters)} parameters, "
          f"{len(effect.techniques)} techniques, {states} state assignments")
    print(f"median {statistics.median(times):.1f} ms (min {min(times):.1f}, max {max(times):.1f}, "
          f"{args.runs} runs; goal <= 30 ms)")
    if args.profile:
        import cProfile
        import pstats
        prof = cProfile.Profile()
        prof.enable()
        effects.load_effect(source)
        prof.disable()
        pstats.Stats(prof, stream=sys.stdout).sort_stats("tottime").print_stats(15)
    return 0


if __name__ == "__main__":
    sys.exit(main())
