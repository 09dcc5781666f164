"""fxc's code size against ours (issue 31's ours/fxc ratio) on the shaders fxc compiled whose
HLSL is beside them (tests/data/d3dbc/MANIFEST.md): for each pair, the instruction slots
(texture + arithmetic), slots counted the same way for both (`compute_stats`, what the card
checks), the slot count fxc's own listing prints, and the temporaries.

    .venv/bin/python benchmarks/bench_fxc_slots.py

A pair whose HLSL this framework refuses (SDL 2's Direct3D 10 syntax) is not listed; the
bytecode-only shaders (SDL's YUV) have no pair.
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import effects  # noqa: E402
from effects.shaders.asm.stats import compute_stats  # noqa: E402
from effects.shaders.d3dbc import read_header, read_shader  # noqa: E402
from effects.shaders.hlsl import compile_state  # noqa: E402

DATA = ROOT / "tests" / "data" / "d3dbc"
# (fxc's header, the HLSL file, the defines fxc was given, entry, target)
PAIRS = [
    ("sdl/D3D9_PixelShader_Palette.h", "sdl/D3D9_PixelShader_Palette.hlsl", {}, "main", "ps_2_0"),
    ("mpv/d3d_shader_420p.h", "mpv/d3d_shader_yuv.hlsl", {"USE_420P": "1"}, "main", "ps_2_0"),
    ("mpv/d3d_shader_nv12.h", "mpv/d3d_shader_yuv.hlsl", {"USE_NV12": "1"}, "main", "ps_2_0"),
]


def ours(source: Path, defines: dict[str, str], entry: str, target: str):
    """Our compile of `entry` in `source` (an effect that includes it, with the defines)."""
    lines = [f"#define {k} {v}" for k, v in defines.items()]
    lines += [f'#include "{source.name}"',
              f"technique T {{ pass P {{ PixelShader = compile {target} {entry}(); }} }}"]
    effect = effects.load_effect("\n".join(lines), include_dirs=[str(source.parent)])
    value = effect.techniques[0].passes[0].state("PixelShader").value
    return compile_state(effect, value).program


def measure() -> list[tuple[str, int, int, int, int, int]]:
    rows = []
    for header, source, defines, entry, target in PAIRS:
        text = (DATA / header).read_text()
        fxc = read_shader(read_header(text)[0][1], header).program
        listed = re.search(r"approximately (\d+) instruction slots? used", text)
        mine = ours(DATA / source, defines, entry, target)
        a, b = compute_stats(fxc), compute_stats(mine)
        rows.append((header, a.total_slots, int(listed.group(1)) if listed else -1,
                     b.total_slots, a.temps_used, b.temps_used))
    return rows


def main() -> None:
    rows = measure()
    print(f"{'fxc header':38} {'fxc':>4} {'listed':>6} {'ours':>4} {'ours/fxc':>8} "
          f"{'temps fxc':>9} {'ours':>4}")
    for name, fxc, listed, mine, t_fxc, t_mine in rows:
        print(f"{name:38} {fxc:4d} {listed:6d} {mine:4d} {mine / fxc:8.2f} {t_fxc:9d} "
              f"{t_mine:4d}")


if __name__ == "__main__":
    main()
