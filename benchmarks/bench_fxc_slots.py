"""fxc's code size against ours (issue 31's ours/fxc ratio) on the shaders fxc compiled whose
HLSL is beside them (tests/data/d3dbc/MANIFEST.md): for each pair, the instruction slots
(texture + arithmetic), counted the same way for both (`compute_stats`, what the card checks),
the slot count fxc's own listing prints (-1: the file has no listing), and the temporaries.

    .venv/bin/python benchmarks/bench_fxc_slots.py

Wine's D3DX9 test shaders (`wine/d3dx9_36_shader_excerpt.c`, read as its test reads them) are
listed too; one our compiler refuses shows `refused` (the front end's gaps, named in
tests/shaders/d3dbc/test_wine_d3dx9_shaders.py). SDL 2's YUV shaders are not listed: their HLSL
is Direct3D 10 syntax, which this framework's HLSL front end does not accept yet.
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import effects  # noqa: E402
from effects.base.errors import EffectError  # noqa: E402
from effects.shaders.asm.stats import compute_stats  # noqa: E402
from effects.shaders.d3dbc import read_header, read_shader  # noqa: E402
from effects.shaders.hlsl import compile_shader, compile_state  # noqa: E402

DATA = ROOT / "tests" / "data" / "d3dbc"
WINE = "wine/d3d10core_test_create_shader.c"
# (fxc's file, its array, the HLSL file, the defines fxc was given, entry, target)
PAIRS = [
    (WINE, 0, WINE, {}, "main", "vs_2_0"),
    (WINE, 1, WINE, {}, "main", "vs_3_0"),
]


def _hlsl(source: Path) -> str:
    """The HLSL of `source`: the file, or the `#if 0` block of a C file that carries it."""
    text = source.read_text()
    if source.suffix == ".c":
        return text[text.index("#if 0") + len("#if 0"):text.index("#endif")]
    return text


def ours(source: Path, defines: dict[str, str], entry: str, target: str):
    """Our compile of `entry` in `source` (in an effect, after the defines)."""
    state = "PixelShader" if target.startswith("ps") else "VertexShader"
    lines = [f"#define {k} {v}" for k, v in defines.items()]
    lines += [_hlsl(source), f"technique T {{ pass P {{ {state} = compile {target} {entry}(); }} }}"]
    effect = effects.load_effect("\n".join(lines), include_dirs=[str(source.parent)])
    value = effect.techniques[0].passes[0].state(state).value
    return compile_state(effect, value).program


def _program(hlsl: str, entry: str, target: str):
    effect = effects.load_effect(hlsl + "\ntechnique T { pass P { } }\n")
    return compile_shader(effect, entry, target).program


def measure() -> list[tuple[str, int, int, int | None, int, int | None]]:
    rows: list[tuple[str, int, int, int | None, int, int | None]] = []
    for header, array, source, defines, entry, target in PAIRS:
        text = (DATA / header).read_text()
        name, data = read_header(text)[array]
        fxc = read_shader(data, header).program
        listed = re.search(r"approximately (\d+) instruction slots? used", text)
        header = header if header != WINE else f"{header}:{name}"
        mine = ours(DATA / source, defines, entry, target)
        a, b = compute_stats(fxc), compute_stats(mine)
        rows.append((header, a.total_slots, int(listed.group(1)) if listed else -1,
                     b.total_slots, a.temps_used, b.temps_used))
    from tests.shaders.d3dbc.test_wine_d3dx9_shaders import _pairs
    for name, target, hlsl, data in _pairs():
        a = compute_stats(read_shader(data, name).program)
        try:
            b = compute_stats(_program(hlsl, "main", target))
        except EffectError:
            rows.append((f"wine/d3dx9:{name}", a.total_slots, -1, None, a.temps_used, None))
            continue
        rows.append((f"wine/d3dx9:{name}", a.total_slots, -1, b.total_slots, a.temps_used,
                     b.temps_used))
    return rows


def main() -> None:
    rows = measure()
    print(f"{'fxc header':52} {'fxc':>4} {'listed':>6} {'ours':>4} {'ours/fxc':>8} "
          f"{'temps fxc':>9} {'ours':>4}")
    for name, fxc, listed, mine, t_fxc, t_mine in rows:
        if mine is None:
            print(f"{name:52} {fxc:4d} {listed:6d} refused")
            continue
        print(f"{name:52} {fxc:4d} {listed:6d} {mine:4d} {mine / fxc:8.2f} {t_fxc:9d} "
              f"{t_mine:4d}")


if __name__ == "__main__":
    main()
