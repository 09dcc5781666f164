"""Texture-addressing instructions whose lowering is a small handler rather than a rewrite
tree: sampling, the ps_1_1-1_3 texm3x* dot-product chains, depth replacement, texkill.

Each function is the `Handler` of its instruction's row (instructions.py) and lowers one
instruction through the lowering's operand readers and register writes (lower.py). Sources:
docs/reference/semantics.md §2.5-2.6 and §3, the table's `formula` column.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

from effects.base.errors import AsmError
from effects.shaders.asm.rewrites import BEM

if TYPE_CHECKING:  # pragma: no cover
    from effects.shaders.asm.lower import _Lowering as Lowering
    from effects.shaders.asm.program import Instruction

ZERO = (0.0, 0.0, 0.0, 0.0)
ONE = (1.0, 1.0, 1.0, 1.0)


def _dot_row(lo: Lowering, instr: Instruction, reads: dict) -> int:
    """tc(m) . t(n).rgb for the texm3x* / texdp3 rows (m = destination register)."""
    return lo.b.dp3(lo.texcoord(instr.dst.index), lo.source(instr.srcs[0], reads))


def _xyz(lo: Lowering, u: int, v: int, w: int | None = None, fill: int | None = None) -> int:
    coord = lo.b.merge(u, v, "y")
    if w is not None:
        coord = lo.b.merge(coord, w, "z")
    return lo.b.merge(coord, fill, "w") if fill is not None else coord


def tex(lo: Lowering, instr: Instruction, reads: dict) -> None:
    m = instr.dst.index
    proj = bool(lo.ctx.projected.get(m))
    lo.write(instr, lo.sample(m, lo.texcoord(m), proj=proj), computed=False)


def texcoord(lo: Lowering, instr: Instruction, reads: dict) -> None:
    tc = lo.b.saturate(lo.texcoord(instr.dst.index))
    lo.write(instr, lo.b.merge(lo.e.const(ONE), tc, "xyz"))


def texkill(lo: Lowering, instr: Instruction, reads: dict) -> None:
    if lo.rules.is_ps11_13:
        lo.kill(lo.texcoord(instr.dst.index), "xyz")
    elif lo.rules.is_ps14:
        lo.kill(lo.source(instr.dst, reads), "xyz")
    else:
        lo.kill(lo.source(instr.srcs[0], reads), "xyzw")


def _bumped(lo: Lowering, instr: Instruction, reads: dict) -> tuple[int, int]:
    """texbem: sample stage m at tc(m).uv + M(m) (t(n).r, t(n).g); also returns t(n)."""
    m = instr.dst.index
    src = lo.source(instr.srcs[0], reads)
    bumpenv = lo.b.uniform(f"bumpenv{m}")
    offset = lo.e.emit(BEM, {"a": lo.e.const(ZERO), "b": src,
                                             "bumpenv": bumpenv})
    tc = lo.projected_coord(m)
    coord = lo.b.merge(tc, lo.b.add(tc, offset), "xy")
    return lo.sample(m, coord), src


def texbem(lo: Lowering, instr: Instruction, reads: dict) -> None:
    texel, _ = _bumped(lo, instr, reads)
    lo.write(instr, texel, computed=False)


def texbeml(lo: Lowering, instr: Instruction, reads: dict) -> None:
    # L = sat(t(n).b * LSCALE(m) + LOFFSET(m)); clamped as the FF path and DXVK do (2.5)
    texel, src = _bumped(lo, instr, reads)
    scale_offset = lo.b.uniform(f"bumpenvl{instr.dst.index}")
    lum = lo.b.saturate(lo.b.mad(lo.e.swizzle(src, "zzzz"), lo.e.swizzle(scale_offset, "xxxx"),
                                 lo.e.swizzle(scale_offset, "yyyy")))
    lo.write(instr, lo.b.mul(texel, lum))


def texreg2(lo: Lowering, instr: Instruction, reads: dict, *, pattern: str,
            default: str = "2d") -> None:
    """texreg2ar / gb / rgb: sample stage m at t(n) rearranged by `pattern` (the row's)."""
    coord = lo.e.swizzle(lo.source(instr.srcs[0], reads), pattern)
    lo.write(instr, lo.sample(instr.dst.index, coord, default), computed=False)


def pad(lo: Lowering, instr: Instruction, reads: dict) -> None:
    if instr.info.op == "texm3x2pad" or not lo.pending_rows or len(lo.pending_rows) >= 2:
        lo.pending_rows = []
    lo.pending_rows.append(_dot_row(lo, instr, reads))


def _rows(lo: Lowering, instr: Instruction, count: int) -> list[int]:
    rows, lo.pending_rows = lo.pending_rows, []
    if len(rows) != count:
        raise AsmError(f"{instr.opcode} needs {count} pad instruction(s) before it",
                       instr.location)
    return rows


def texm3x2tex(lo: Lowering, instr: Instruction, reads: dict) -> None:
    (u,) = _rows(lo, instr, 1)
    coord = _xyz(lo, u, _dot_row(lo, instr, reads))
    lo.write(instr, lo.sample(instr.dst.index, coord), computed=False)


def texm3x2depth(lo: Lowering, instr: Instruction, reads: dict) -> None:
    (u,) = _rows(lo, instr, 1)
    w = _dot_row(lo, instr, reads)
    ratio = lo.b.saturate(lo.b.mul(u, lo.b.rcp(w)))
    lo.depth = lo.b.cmp(lo.b.neg(lo.b.abs(w)), lo.e.const(ONE), ratio)   # w == 0 gives 1


def texm3x3(lo: Lowering, instr: Instruction, reads: dict) -> None:
    u, v = _rows(lo, instr, 2)
    n = _xyz(lo, u, v, _dot_row(lo, instr, reads))
    m = instr.dst.index
    op = instr.info.op
    if op == "texm3x3":
        lo.write(instr, lo.b.merge(n, lo.e.const(ONE), "w"))
        return
    if op == "texm3x3tex":
        lo.write(instr, lo.sample(m, n, "cube"), computed=False)
        return
    if op == "texm3x3spec":
        eye = lo.source(instr.srcs[1], reads)
    else:   # the eye vector rides in the w of the three rows' texture coordinates
        eye = _xyz(lo, *(lo.e.swizzle(lo.texcoord(m - 2 + k), "wwww") for k in range(3)))
    # R = 2 N (N.E) / (N.N) - E
    b = lo.b
    factor = b.mul(lo.e.const(2.0), b.mul(b.dp3(n, eye), b.rcp(b.dp3(n, n))))
    lo.write(instr, lo.sample(m, b.sub(b.mul(n, factor), eye), "cube"), computed=False)


def texdp3(lo: Lowering, instr: Instruction, reads: dict) -> None:
    lo.write(instr, _dot_row(lo, instr, reads))


def texdp3tex(lo: Lowering, instr: Instruction, reads: dict) -> None:
    coord = lo.b.merge(lo.e.const(ZERO), _dot_row(lo, instr, reads), "x")
    lo.write(instr, lo.sample(instr.dst.index, coord), computed=False)


def texdepth(lo: Lowering, instr: Instruction, reads: dict) -> None:
    # depth = sat(r5.r / min(r5.g, 1)); g == 0 gives 1 (docs/reference/semantics.md 2.6,
    # Wine's formula)
    b, r5 = lo.b, lo.source(instr.dst, reads)
    g = lo.e.swizzle(r5, "yyyy")
    ratio = b.saturate(b.mul(lo.e.swizzle(r5, "xxxx"), b.rcp(b.min(g, lo.e.const(ONE)))))
    lo.depth = b.cmp(b.neg(b.abs(g)), lo.e.const(ONE), ratio)


def texcrd(lo: Lowering, instr: Instruction, reads: dict) -> None:
    lo.write(instr, lo.source(instr.srcs[0], reads))


def texldd(lo: Lowering, instr: Instruction, reads: dict) -> None:
    """texldd d, coord, s#, ddx, ddy: sample with the LOD of the given screen gradients."""
    coord, ddx, ddy = (lo.source(instr.srcs[k], reads) for k in (0, 2, 3))
    stage = instr.srcs[1].index
    lo.write(instr, lo.b.sample_grad(stage, coord, ddx, ddy, lo.sampler_kind(stage)),
             computed=False)


def texld(lo: Lowering, instr: Instruction, reads: dict, **flags: bool) -> None:
    """texld and its forms; `flags` (proj, bias, lod) come from the row."""
    coord = lo.source(instr.srcs[0], reads)
    if lo.rules.is_ps14:                           # stage = destination register number
        lo.write(instr, lo.sample(instr.dst.index, coord), computed=False)
        return
    lo.write(instr, lo.sample(instr.srcs[1].index, coord, **flags), computed=False)
