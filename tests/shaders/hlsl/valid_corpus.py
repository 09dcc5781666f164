"""A corpus of small HLSL programs that fxc compiled (issue 30), each with the colour it draws.

One row per program: its functions (the pixel shader is `PS`, a vertex shader where there is
one `VS`), the colour at a pixel as a function of the quad's texture coordinate (u, v) worked
out by hand from the HLSL reference's definition of each construct, its target and the fxc
warning codes it gives. The effect is the text plus one technique `T` compiling the entry.
`outcome(row, backend)` compiles, validates and renders a row as a user would and says "ok"
or what went wrong; `python -m tests.shaders.hlsl.valid_corpus` prints the pass figure per
back end (`tests/shaders/hlsl/test_hlsl_valid_corpus.py` asserts every row on both).

The rows (valid_rows_*.py) are grouped by what they cover: every intrinsic of the DirectX 9
HLSL intrinsic table ("Intrinsic Functions (DirectX HLSL)": abs ... trunc, each with its
minimum shader model) with its overload shapes; conversions, initializers, swizzles,
operators, flow and its attributes, functions and their parameters, preprocessor forms,
types and literal suffixes ("Scalar Types", "Per-Component Math Operations", "Variable
Syntax" of the same reference). vkd3d-shader's tests/hlsl/*.shader_test, which record fxc's
verdict for each program, were read for which forms fxc accepted; the programs are our own.

The quad's texture coordinate at pixel (x, y) is (x / 8, y / 8) (test_hlsl_render.pixel_uv);
the probes sit where no rounding of it crosses a threshold the programs test.
"""
from __future__ import annotations

from typing import Callable, NamedTuple, Sequence

import numpy as np

PROBES = ((1, 2), (6, 5), (3, 7))
TOL = 2.0 / 255


class Row(NamedTuple):
    name: str
    text: str                                         # globals and functions
    want: Callable[[float, float], Sequence[float]]   # RGBA at texture coordinate (u, v)
    target: str = "ps_2_0"
    vs: str = ""                                      # a vertex shader target: entry VS
    args: str = ""                                    # the compile arguments of PS
    warns: tuple[str, ...] = ()                       # fxc warning codes the compile gives
    asm: str = ""                                     # an instruction the listing must hold
    known: str = ""       # why it still fails here: the test expects the failure (strict xfail)


PS = "float4 PS(float2 uv : TEXCOORD0) : COLOR\n{\n%s\n}\n"


def ps(body: str, before: str = "") -> str:
    return before + PS % body


# -- textures the sampling rows read ----------------------------------------------------------

SAMPLERS = """
texture T2tex;
sampler2D sT2 = sampler_state { Texture = <T2tex>; MinFilter = Point; MagFilter = Point;
                                MipFilter = None; AddressU = Clamp; AddressV = Clamp; };
texture Miptex;
sampler2D sMip = sampler_state { Texture = <Miptex>; MinFilter = Point; MagFilter = Point;
                                 MipFilter = Point; AddressU = Clamp; AddressV = Clamp; };
texture Cubetex;
samplerCUBE sCube = sampler_state { Texture = <Cubetex>; MinFilter = Point; MagFilter = Point;
                                    MipFilter = None; };
texture Voltex;
sampler3D sVol = sampler_state { Texture = <Voltex>; MinFilter = Point; MagFilter = Point;
                                 MipFilter = None; AddressU = Clamp; AddressV = Clamp;
                                 AddressW = Clamp; };
texture Linetex;
sampler1D sLine = sampler_state { Texture = <Linetex>; MinFilter = Point; MagFilter = Point;
                                  MipFilter = None; AddressU = Clamp; };
"""
SAMPLER_NAMES = ("sT2", "sMip", "sCube", "sVol", "sLine")

# T2: 2 x 2, texel (row r, column c) = (0.25 + 0.5c, 0.25 + 0.5r, 0.5, 1)
T2 = np.array([[[0.25 + 0.5 * c, 0.25 + 0.5 * r, 0.5, 1.0] for c in range(2)] for r in range(2)])
# Mip: 4 x 4 red, its 2 x 2 level green, its 1 x 1 level blue
MIP_LEVELS = [(1.0, 0.0, 0.0, 1.0), (0.0, 1.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0)]
# Cube: one colour per face, in Direct3D's face order +X -X +Y -Y +Z -Z
CUBE = [(1, 0, 0, 1), (0, 1, 0, 1), (0, 0, 1, 1), (1, 1, 0, 1), (0, 1, 1, 1), (1, 0, 1, 1)]
# Vol: 2 x 2 x 2, texel (slice s, row r, column c) = (0.25 + 0.5c, 0.25 + 0.5r, 0.25 + 0.5s, 1)
VOL = np.array([[[[0.25 + 0.5 * c, 0.25 + 0.5 * r, 0.25 + 0.5 * s, 1.0] for c in range(2)]
                 for r in range(2)] for s in range(2)])
# Line: 4 texels wide, texel i = (0.125 + 0.25i, 1 - 0.25i, 0.5, 1)
LINE = np.array([[[0.125 + 0.25 * i, 1 - 0.25 * i, 0.5, 1.0] for i in range(4)]])


def t2(u: float, v: float) -> np.ndarray:
    return T2[min(int(v * 2), 1), min(int(u * 2), 1)]


def vol(u: float, v: float, w: float) -> np.ndarray:
    return VOL[min(int(w * 2), 1), min(int(v * 2), 1), min(int(u * 2), 1)]


def line(u: float) -> np.ndarray:
    return LINE[0, min(int(u * 4), 3)]


def textures() -> dict:
    from effects.assets.textures import encode, make_texture
    from effects.program.texture import Texture
    levels = [np.full((4 >> k, 4 >> k, 4), colour, np.float32) for k, colour in enumerate(MIP_LEVELS)]
    cube = np.array([np.full((2, 2, 4), face, np.float32) for face in CUBE])
    return {
        "T2tex": make_texture(T2, mips=False),
        "Miptex": Texture("2d", "A8R8G8B8", [encode(level, "A8R8G8B8") for level in levels], "mip"),
        "Cubetex": make_texture(cube, kind="cube", mips=False),
        "Voltex": make_texture(VOL, kind="3d", mips=False),
        "Linetex": make_texture(LINE, kind="1d", mips=False),
    }


# -- running a row -------------------------------------------------------------------------------

def card_for(row: Row) -> str:
    three = row.target.endswith("_3_0") or row.vs.endswith("_3_0")
    if three:
        return "geforce6800"
    return "geforcefx5900" if row.target == "ps_2_a" else "radeon9700"


PASS_VS = """
struct PassOut { float4 p : POSITION; float2 t : TEXCOORD0; };
PassOut PassVS(float4 p : POSITION, float2 t : TEXCOORD0) { PassOut o; o.p = p; o.t = t; return o; }
"""


def effect_text(row: Row) -> str:
    states = f"PixelShader = compile {row.target} PS({row.args});"
    text = row.text
    if row.vs:
        states += f" VertexShader = compile {row.vs} VS();"
    elif row.target.endswith("_3_0"):
        # a ps_3_0 runs only beside a vs_3_0 (D3D9): the quad's position and coordinate through
        states += " VertexShader = compile vs_3_0 PassVS();"
        text += PASS_VS
    samplers = SAMPLERS if any(s in row.text for s in SAMPLER_NAMES) else ""
    return f"{samplers}\n{text}\ntechnique T {{ pass P {{ {states} }} }}\n"


def expected(row: Row, x: int, y: int) -> np.ndarray:
    u, v = x / 8, y / 8
    return np.clip(np.asarray(row.want(u, v), np.float64), 0.0, 1.0)


def outcome(row: Row, backend) -> str:
    """'ok', or why `row` did not compile, validate or draw its values on `backend`."""
    import effects
    from effects.base.errors import EffectError
    from effects.shaders.hlsl.cache import compile_state
    try:
        fx = effects.load_effect(effect_text(row))
        shaders = {s.name: compile_state(fx, s.value) for s in fx.techniques[0].passes[0].states}
        compiled = shaders["PixelShader"]
        codes = {w.message[:5] for shader in shaders.values() for w in shader.warnings}
        missing = set(row.warns) - codes
        if missing:
            return f"warning {sorted(missing)} not given (gave {sorted(codes)})"
        if row.asm and row.asm not in compiled.text:
            return f"no {row.asm!r} in the listing"
        report = fx.validate("T", effects.load_profile(card_for(row)))
        if not report.ok:
            return "rejected: " + "; ".join(r.message for r in report.reasons)
        img = effects.render(fx, card_for(row), technique="T", backend=backend,
                             scene={"mesh": "quad", "size": [8, 8]},
                             params=textures() if "sampler" in effect_text(row) else None)
    except EffectError as err:
        return f"refused: {err.message} (line {err.line})"
    img = img.astype(np.float64) / 255
    wrong = []
    for x, y in PROBES:
        want = expected(row, x, y)
        if not np.allclose(img[y, x], want, atol=TOL):
            wrong.append(f"({x},{y}) drew {np.round(img[y, x], 3).tolist()} want {np.round(want, 3).tolist()}")
    return "ok" if not wrong else "wrong: " + "; ".join(wrong)


def all_rows() -> list[Row]:
    from tests.shaders.hlsl import valid_rows_forms, valid_rows_intrinsics, valid_rows_language
    return valid_rows_intrinsics.ROWS + valid_rows_language.ROWS + valid_rows_forms.ROWS


def main(names: Sequence[str] = ()) -> int:
    """Print the pass figure per back end and each failure; `names`: only the rows whose
    name holds one of them."""
    from effects.program.backend import create_backend
    rows = [r for r in all_rows() if not names or any(n in r.name for n in names)]
    failed = 0
    for name in ("numpy", "gl"):
        backend = create_backend(name)
        results = [(row, outcome(row, backend)) for row in rows]
        backend.close()
        good = sum(r == "ok" for _, r in results)
        failed += len(rows) - good
        print(f"{name}: {good}/{len(rows)} valid programs draw their values ({100 * good / len(rows):.1f} %)")
        for row, r in results:
            if r != "ok":
                print(f"  {row.name}: {r}")
    return 1 if failed else 0


if __name__ == "__main__":
    import sys
    raise SystemExit(main(sys.argv[1:]))
