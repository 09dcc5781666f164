"""The instruction table: one row per Direct3D shader instruction (per version family).

Each row says which versions have the instruction, its operands (roles, and which register
kinds they may name where the instruction narrows the version's rules), its slot cost, whether
it is a texture or an arithmetic instruction, and what it computes: `op` is the key a lowering
dispatches on and `formula` a short statement of the result (a, b, c = the sources after
swizzle and modifiers; d = the destination). `lowers` says how it becomes IR: a `Rewrite`
(an expression tree over the sources, rewrites.py, with variants whose conditions the row
carries), a `Handler` (a function, texture_ops.py), `NO_CODE` (declarations), or `NotLowered`
with the reason, which validation reports, so a valid shader is one that renders.
`matrix_rows` is how many consecutive registers a matrix macro reads from its second source.
The checker, the stats, validation and the lowering all read these rows, so what validates and
what runs come from one place.

`code` is the instruction's D3DSIO_* number in the bytecode (D3DSHADER_INSTRUCTION_OPCODE_TYPE
of d3d9types.h, as the Windows driver documentation's "Instruction Token" pages list it).

Sources: DirectX 9 assembly reference instruction tables (ps_1_x, ps_2_0, ps_2_x, vs_1_1,
vs_2_0: slot counts; footnote "cmp/dp4: 2 slots in ps_1_2 and ps_1_3"; texbeml "1 + 1"),
the instruction pages (texld ps_1_4 / ps_2_0, texbem, texm3x2pad ...), and
docs/reference/semantics.md §2–4 for the formulas.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, partial
from typing import Any, Callable

from effects.shaders.asm import flow as fl
from effects.shaders.asm import rewrites as rw
from effects.shaders.asm import texture_ops as tx
from effects.shaders.asm.rewrites import Tree
from effects.shaders.asm.versions import (PS1, PS10_13, PS12_13, PS13, PS14, PS2, PS2X, PS3, VS, VS1, VS2,
                       VS3, Group, group)

# Operand roles, in order (dst first when the instruction has one):
#   d  destination register          s  vector source         x  scalar source (one component)
#   S  sampler s#                    f  float literal         n  integer literal
#   B  boolean literal               l  label l#              b  boolean register b# or p0
#   I  integer register i#           L  loop counter aL       p  predicate register p0
SOURCE_ROLES = frozenset("sx")
REGISTER_ROLES = frozenset("dsxSlbILp")


@dataclass(frozen=True)
class Rewrite:
    """Lowers by emitting `tree` over the sources a, b, c. `variants` are (condition, tree)
    pairs tried first, the condition over (instruction, write mask); `dst_uniform` binds
    (name, prefix): the uniform `prefix<n>` for destination register n (bem's BUMPENVMAT)."""

    tree: Tree
    variants: tuple[tuple[Callable[[Any, str], bool], Tree], ...] = ()
    dst_uniform: tuple[str, str] | None = None


@dataclass(frozen=True)
class Handler:
    """Lowers by calling `fn(lowering, instruction, register reads)`."""

    fn: Callable[..., None]


@dataclass(frozen=True)
class NotLowered:
    """Not lowered (yet): validation rejects the shader with `reason`."""

    reason: str


@dataclass(frozen=True)
class NoCode:
    """Emits no IR (declarations, def, nop): nothing runs."""


NO_CODE = NoCode()
Lowers = Rewrite | Handler | NotLowered | NoCode


@dataclass(frozen=True)
class InstrInfo:
    name: str
    versions: Group
    operands: str                  # roles, e.g. "dss" for add d, a, b
    category: str                  # 'arith' | 'tex' | 'flow' | 'setup'
    op: str                        # lowering key
    formula: str
    slots: int = 1
    slot_overrides: tuple[tuple[str, int], ...] = ()   # (version, slots) where it differs
    # (version, slots) where fxc's count differs from the reference's: what its listings'
    # "approximately N instruction slots used" and its X5608 limit check count, so a compiled
    # shader fits where fxc fitted it. The reference's number stays in `documented_cost`.
    fxc_slots: tuple[tuple[str, int], ...] = ()
    extra_arith: int = 0           # texbeml: 1 texture slot plus 1 arithmetic slot
    dst_kinds: tuple[str, ...] | None = None           # narrows the version's writable kinds
    src_kinds: tuple[tuple[str, ...] | None, ...] = ()  # per source; None = version default
    writes: str = ""               # components written when fixed ('xyz' for m3x3); '' = mask
    # per source, the components it reads ('xyz' for dp3's); '' (or none given): the lanes the
    # instruction writes, through the swizzle; 'coord': a texture coordinate's, by its
    # sampler's dcl (2d: xy; cube, volume: xyz), 'coord+w' with .w (projection, bias, level).
    # A scalar source (role x) reads the swizzle's last lane. The checker's per-component
    # reads-before-writes (check.py) ask it.
    reads: tuple[str, ...] = ()
    modifiers: bool = True         # takes instruction modifiers (_sat, _x2 ...)
    lowers: Lowers = NotLowered("not lowered yet")
    matrix_rows: int = 0           # m4x4 r0, v0, c4 reads c4..c7: 4
    ends_body: bool = False        # ret, label: the main program or a subroutine ends here
    gradient: bool = False         # takes screen-space gradients (dsx, dsy, texld's LOD)
    # the bytecode (effects/shaders/d3dbc): D3DSIO_* opcode (bits 0-15 of the instruction
    # token), the opcode of the comparing form (if_gt is D3DSIO_IFC, break_ne D3DSIO_BREAKC),
    # and the fixed opcode-specific control bits 16-23 (texldp 1, texldb 2)
    code: int = -1
    compare_code: int | None = None
    control: int = 0

    # read for every operand the assembler and the checker see: worked out once per row
    @cached_property
    def has_dst(self) -> bool:
        return self.operands.startswith("d")

    @cached_property
    def source_roles(self) -> str:
        return self.operands[1:] if self.has_dst else self.operands

    @property
    def is_texture(self) -> bool:
        return self.category == "tex"

    def slot_cost(self, version: str) -> int:
        """The slots the limit decision counts: fxc's count where its row gives one, else
        the instruction reference's."""
        for name, n in self.fxc_slots:
            if name == version:
                return n
        return self.documented_cost(version)

    def documented_cost(self, version: str) -> int:
        """The slots the DirectX 9 instruction reference gives for `version`."""
        for name, n in self.slot_overrides:
            if name == version:
                return n
        return self.slots

    def src_kind(self, i: int) -> tuple[str, ...] | None:
        return self.src_kinds[i] if i < len(self.src_kinds) else None


def _row(name, code, versions, operands, category, formula, *, op=None, **kw) -> InstrInfo:
    return InstrInfo(name, versions, operands, category, op or name, formula, code=code, **kw)


def _ir(op: str, *args: str) -> Rewrite:
    """The rewrite `op(a, b, ...)`: the IR op of that name over the sources."""
    return Rewrite((op, *(args or ("a", "b"))))


def _coissued_colour(instr: Any, mask: str) -> bool:
    return instr.coissue and mask != "w"


def _to_address(instr: Any, mask: str) -> bool:
    return instr.dst is not None and instr.dst.kind == "a"


PS_ALL = PS1 | PS2 | PS3
PS2UP = PS2 | PS3
VS2UP = VS2 | VS3
FLOW_VERSIONS = VS2UP | PS2X | PS3
# The predicate register p0 (setp, breakp, predicated instructions): not in vs_2_0 or ps_2_b;
# the loop counter aL (loop / endloop): vertex shaders 2_0+ and ps_3_0 only (versions.py).
PREDICATE_VERSIONS = group("ps_2_x", "ps_2_a", "vs_2_x", "vs_2_a") | PS3 | VS3
LOOP_VERSIONS = VS2UP | PS3
T = ("t",)
R = ("r",)
TR = ("t", "r")
C = ("c",)
S = ("s",)

_ARITH = [
    _row("add", 2, PS_ALL | VS, "dss", "arith", "d = a + b",
         lowers=_ir("add")),
    _row("sub", 3, PS_ALL | VS, "dss", "arith", "d = a - b",
         lowers=_ir("sub")),
    _row("mul", 5, PS_ALL | VS, "dss", "arith", "d = a * b",
         lowers=_ir("mul")),
    _row("mad", 4, PS_ALL | VS, "dsss", "arith", "d = a * b + c",
         lowers=_ir("mad", "a", "b", "c")),
    _row("mov", 1, PS_ALL | VS, "ds", "arith", "d = a",
         lowers=Rewrite("a", variants=((_to_address, rw.MOV_A0),))),
    _row("nop", 0, PS_ALL | VS, "", "arith", "nothing", slot_overrides=tuple(
        (v, 0) for v in sorted(PS1.names)), lowers=NO_CODE),
    _row("dp3", 8, PS_ALL | VS, "dss", "arith", "d = a.x*b.x + a.y*b.y + a.z*b.z (replicated)",
         reads=("xyz", "xyz"), lowers=_ir("dp3")),
    _row("dp4", 9, PS12_13 | PS14 | PS2UP | VS, "dss", "arith",
         "d = a.x*b.x + a.y*b.y + a.z*b.z + a.w*b.w (replicated)",
         slot_overrides=(("ps_1_2", 2), ("ps_1_3", 2)), reads=("xyzw", "xyzw"),
         lowers=_ir("dp4")),
    # 2 slots in ps_2_0 and up by the reference; fxc counted 1 there: an HLSL Shader Compiler
    # 9.26.952.2844 ps_3_0 listing of 64 arithmetic instructions (2 pow, 1 nrm, 2 lrp) says
    # "70 arithmetic" = 64 + 2*2 (pow) + 2 (nrm) + 0 (lrp); issue 31 read the same from
    # ps_2_0 listings. vs_2_0 and up keep the reference's 2 (no listing read).
    _row("lrp", 18, PS1 | PS2UP | VS2UP, "dsss", "arith", "d = a*b + (1-a)*c",
         slots=2, slot_overrides=tuple((v, 1) for v in sorted(PS1.names)),
         fxc_slots=tuple((v, 1) for v in sorted(PS2UP.names)),
         lowers=_ir("lrp", "a", "b", "c")),
    _row("cnd", 80, PS10_13, "dsss", "arith", "d = (r0.a > 0.5) ? b : c for all components",
         lowers=Rewrite(rw.CND_ALPHA, variants=((_coissued_colour, rw.CND_COISSUE),))),
    _row("cnd", 80, PS14, "dsss", "arith", "d = (a > 0.5) ? b : c per component",
         lowers=_ir("cnd", "a", "b", "c")),
    _row("cmp", 88, PS12_13 | PS14 | PS2UP, "dsss", "arith", "d = (a >= 0) ? b : c per component",
         slot_overrides=(("ps_1_2", 2), ("ps_1_3", 2)), lowers=_ir("cmp", "a", "b", "c")),
    _row("bem", 89, PS14, "dss", "arith",
         "d.r = a.r + M00(n)*b.r + M10(n)*b.g; d.g = a.g + M01(n)*b.r + M11(n)*b.g "
         "(n = destination register number, M = D3DTSS_BUMPENVMAT of stage n)",
         slots=2, dst_kinds=R, writes="xy",
         reads=("xy", "xy"), lowers=Rewrite(rw.BEM, dst_uniform=("bumpenv", "bumpenv"))),
    _row("min", 10, PS2UP | VS, "dss", "arith", "d = min(a, b) per component",
         lowers=_ir("min")),
    _row("max", 11, PS2UP | VS, "dss", "arith", "d = max(a, b) per component",
         lowers=_ir("max")),
    _row("sge", 13, VS, "dss", "arith", "d = (a >= b) ? 1 : 0 per component",
         lowers=_ir("sge")),
    _row("slt", 12, VS, "dss", "arith", "d = (a < b) ? 1 : 0 per component",
         lowers=_ir("slt")),
    _row("rcp", 6, PS2UP | VS, "dx", "arith", "d = 1/a (replicated; 1/0 = +inf)",
         lowers=_ir("rcp", "a")),
    _row("rsq", 7, PS2UP | VS, "dx", "arith", "d = 1/sqrt(|a|) (replicated)",
         lowers=_ir("rsq", "a")),
    _row("exp", 14, PS2UP | VS, "dx", "arith", "d = 2^a (full precision, replicated)",
         slot_overrides=(("vs_1_1", 10),), lowers=_ir("exp2", "a")),
    _row("log", 15, PS2UP | VS, "dx", "arith", "d = log2(|a|) (full precision, replicated)",
         slot_overrides=(("vs_1_1", 10),), lowers=_ir("log2", "a")),
    _row("expp", 78, VS1, "dx", "arith", "d = (2^floor(a), a - floor(a), 2^a approx, 1)",
         lowers=Rewrite(rw.EXPP_VS1)),
    _row("expp", 78, VS2 | VS3, "dx", "arith", "d = 2^a partial precision",
         lowers=_ir("exp2", "a")),
    _row("logp", 79, VS1, "dx", "arith",
         "v = |a|; d = (floor(log2 v), v / 2^floor(log2 v), log2 v approx, 1)",
         lowers=Rewrite(rw.LOGP_VS1)),
    _row("logp", 79, VS2 | VS3, "dx", "arith", "d = log2(|a|) partial precision",
         lowers=_ir("log2", "a")),
    _row("frc", 19, PS2UP | VS, "ds", "arith", "d = a - floor(a)",
         slot_overrides=(("vs_1_1", 3),), lowers=_ir("frc", "a")),
    _row("lit", 16, VS, "ds", "arith",
         "d = (1, max(a.x, 0), a.x > 0 ? max(a.y, 0)^clamp(a.w, -128, 128) : 0, 1)",
         slot_overrides=(("vs_2_0", 3), ("vs_2_x", 3), ("vs_2_a", 3), ("vs_3_0", 3)),
         reads=("xyw",), lowers=Rewrite(rw.LIT)),
    _row("dst", 17, VS, "dss", "arith", "d = (1, a.y*b.y, a.z, b.w)", reads=("yz", "yw"),
         lowers=Rewrite(rw.DST)),
    _row("m3x2", 24, PS2UP | VS, "dss", "arith", "d.x = dp3(a, b[0]); d.y = dp3(a, b[1])",
         slots=2, writes="xy", reads=("xyz", "xyz"), lowers=_ir("dp3"), matrix_rows=2),
    _row("m3x3", 23, PS2UP | VS, "dss", "arith", "d.i = dp3(a, b[i]) for i = 0..2 (b[i] = b + i)",
         slots=3, writes="xyz", reads=("xyz", "xyz"), lowers=_ir("dp3"), matrix_rows=3),
    _row("m3x4", 22, PS2UP | VS, "dss", "arith", "d.i = dp3(a, b[i]) for i = 0..3", slots=4,
         writes="xyzw", reads=("xyz", "xyz"), lowers=_ir("dp3"), matrix_rows=4),
    _row("m4x3", 21, PS2UP | VS, "dss", "arith", "d.i = dp4(a, b[i]) for i = 0..2", slots=3,
         writes="xyz", reads=("xyzw", "xyzw"), lowers=_ir("dp4"), matrix_rows=3),
    _row("m4x4", 20, PS2UP | VS, "dss", "arith", "d.i = dp4(a, b[i]) for i = 0..3", slots=4,
         writes="xyzw", reads=("xyzw", "xyzw"), lowers=_ir("dp4"), matrix_rows=4),
    _row("abs", 35, PS2UP | VS2UP, "ds", "arith", "d = |a|", lowers=_ir("abs", "a")),
    _row("crs", 33, PS2UP | VS2UP, "dss", "arith", "d.xyz = cross(a.xyz, b.xyz)", slots=2,
         reads=("xyz", "xyz"), lowers=_ir("crs")),
    # nrm and pow: the reference's 3 slots, which fxc's listings count too (the lrp row's)
    _row("nrm", 36, PS2UP | VS2UP, "ds", "arith", "d = a / length(a.xyz)", slots=3,
         reads=("xyz",), lowers=_ir("nrm", "a")),
    _row("pow", 32, PS2UP | VS2UP, "dxx", "arith", "d = |a|^b (replicated)", slots=3,
         lowers=_ir("pow")),
    _row("sgn", 34, VS2UP, "dsss", "arith", "d = sign(a) per component (b, c: scratch temps)",
         slots=3, lowers=_ir("sign", "a")),
    _row("sincos", 37, PS2 | VS2, "dxss", "arith",
         "d.x = cos(a), d.y = sin(a) (b, c = D3DSINCOSCONST1/2)", slots=8,
         lowers=Rewrite(rw.SINCOS)),
    _row("sincos", 37, PS3 | VS3, "dx", "arith", "d.x = cos(a), d.y = sin(a)", slots=8,
         lowers=Rewrite(rw.SINCOS)),
    _row("dp2add", 90, PS2UP, "dssx", "arith", "d = a.x*b.x + a.y*b.y + c (replicated)", slots=2,
         reads=("xy", "xy"), lowers=Rewrite(rw.DP2ADD)),
    _row("mova", 46, VS2UP, "ds", "arith", "a0 = round_half_away_from_zero(a)",
         dst_kinds=("a",), lowers=Rewrite(rw.MOVA)),
    _row("dsx", 91, PS2X | PS3, "ds", "arith", "d = d(a)/dx (screen-space gradient)", slots=2,
         lowers=_ir("ddx", "a"), gradient=True),
    _row("dsy", 92, PS2X | PS3, "ds", "arith", "d = d(a)/dy (screen-space gradient)", slots=2,
         lowers=_ir("ddy", "a"), gradient=True),
    _row("setp", 94, PREDICATE_VERSIONS, "dss", "flow", "p0 = a <cmp> b per component",
         dst_kinds=("p",), lowers=Handler(fl.setp)),
]

# ps_1_1-1_3 texture-address instructions: dst t(m), source t(n) with n < m
# (docs/reference/semantics.md §2.5).
_PS1_TEX = dict(dst_kinds=T, src_kinds=(T,), modifiers=False)
_PAD = Handler(tx.pad)
_M3X3 = Handler(tx.texm3x3)
_TEXTURE = [
    _row("tex", 66, PS10_13, "d", "tex", "t(m) = sample(stage m, texcoord m)", dst_kinds=T,
         modifiers=False, lowers=Handler(tx.tex)),
    _row("texcoord", 64, PS10_13, "d", "tex", "t(m) = (sat(tc.x), sat(tc.y), sat(tc.z), 1)",
         dst_kinds=T, modifiers=False, lowers=Handler(tx.texcoord)),
    _row("texbem", 67, PS10_13, "ds", "tex",
         "t(m) = sample(m, tc(m).uv + M(m) * t(n).rg)", lowers=Handler(tx.texbem), **_PS1_TEX),
    _row("texbeml", 68, PS10_13, "ds", "tex",
         "texbem, then t(m) *= sat(t(n).b * LSCALE(m) + LOFFSET(m))", extra_arith=1,
         lowers=Handler(tx.texbeml), **_PS1_TEX),
    _row("texreg2ar", 69, PS10_13, "ds", "tex", "t(m) = sample(m, (t(n).a, t(n).r))",
         lowers=Handler(partial(tx.texreg2, pattern="wxxx")), **_PS1_TEX),
    _row("texreg2gb", 70, PS10_13, "ds", "tex", "t(m) = sample(m, (t(n).g, t(n).b))",
         lowers=Handler(partial(tx.texreg2, pattern="yzzz")), **_PS1_TEX),
    _row("texreg2rgb", 82, PS12_13, "ds", "tex", "t(m) = sample(m, t(n).rgb)",
         lowers=Handler(partial(tx.texreg2, pattern="xyzz", default="3d")), **_PS1_TEX),
    _row("texm3x2pad", 71, PS10_13, "ds", "tex", "u = tc(m).xyz . t(n).rgb (no write)",
         lowers=_PAD, **_PS1_TEX),
    _row("texm3x2tex", 72, PS10_13, "ds", "tex",
         "v = tc(m+1).xyz . t(n).rgb; t(m+1) = sample(m+1, (u, v))",
         lowers=Handler(tx.texm3x2tex), **_PS1_TEX),
    _row("texm3x2depth", 84, PS13, "ds", "tex",
         "w = tc(m+1).xyz . t(n).rgb; depth = (w == 0) ? 1 : sat(u / w)",
         lowers=Handler(tx.texm3x2depth), **_PS1_TEX),
    _row("texm3x3pad", 73, PS10_13, "ds", "tex", "row k of a 3x3: tc(m).xyz . t(n).rgb (no write)",
         lowers=_PAD, **_PS1_TEX),
    _row("texm3x3tex", 74, PS10_13, "ds", "tex",
         "w = tc(m+2).xyz . t(n).rgb; t(m+2) = sample(m+2, (u, v, w))",
         lowers=_M3X3, **_PS1_TEX),
    _row("texm3x3", 86, PS12_13, "ds", "tex", "t(m+2) = (u, v, w, 1)", lowers=_M3X3,
         **_PS1_TEX),
    _row("texm3x3spec", 76, PS10_13, "dss", "tex",
         "N = (u, v, w), E = c.xyz; t(m+2) = sample(m+2, 2 N (N.E)/(N.N) - E)",
         dst_kinds=T, src_kinds=(T, C), modifiers=False, lowers=_M3X3),
    _row("texm3x3vspec", 77, PS10_13, "ds", "tex",
         "as texm3x3spec with E = (tc(m).w, tc(m+1).w, tc(m+2).w)", lowers=_M3X3,
         **_PS1_TEX),
    _row("texdp3", 85, PS12_13, "ds", "tex", "t(m) = tc(m).xyz . t(n).rgb (replicated)",
         lowers=Handler(tx.texdp3), **_PS1_TEX),
    _row("texdp3tex", 83, PS12_13, "ds", "tex",
         "t(m) = sample(m, (tc(m).xyz . t(n).rgb, 0))",
         lowers=Handler(tx.texdp3tex), **_PS1_TEX),
    _row("texkill", 65, PS10_13, "d", "tex", "discard if any of tc(m).xyz < 0", op="texkill",
         dst_kinds=T, modifiers=False, lowers=Handler(tx.texkill)),
    _row("texkill", 65, PS14, "d", "tex", "discard if any of a.xyz < 0", dst_kinds=TR,
         modifiers=False, lowers=Handler(tx.texkill)),
    _row("texkill", 65, PS2, "s", "tex", "discard if any of a.xyzw < 0", src_kinds=(TR,),
         modifiers=False, reads=("xyzw",), lowers=Handler(tx.texkill)),
    _row("texkill", 65, PS3, "s", "tex", "discard if any of a.xyzw < 0", modifiers=False,
         reads=("xyzw",), lowers=Handler(tx.texkill)),
    _row("texld", 66, PS14, "ds", "tex",
         "r(n) = sample(stage n, a.xyz) (a = t# coordinates or, in phase 2, r# dependent)",
         dst_kinds=R, src_kinds=(TR,), modifiers=False, reads=("xyz",),
         lowers=Handler(tx.texld)),
    _row("texcrd", 64, PS14, "ds", "tex", "r(n) = texcoord a (unclamped; .w undefined)",
         dst_kinds=R, src_kinds=(T,), lowers=Handler(tx.texcrd)),
    _row("texdepth", 87, PS14, "d", "tex", "depth = (r5.g == 0) ? 1 : sat(r5.r / r5.g)",
         dst_kinds=R, modifiers=False, lowers=Handler(tx.texdepth)),
    *[_row(name, 66, versions, "dsS", "tex", formula, control=control, dst_kinds=R,
           src_kinds=(coords, S), lowers=Handler(partial(tx.texld, **flags)), gradient=True,
           reads=("coord" if name == "texld" else "coord+w",))
      # ps_2_x reads coordinates from t# or r#; ps_3_0 from any readable register (v#, r# ...)
      for versions, coords in ((PS2, TR), (PS3, None))
      # one opcode, D3DSIO_TEX; bits 16-17 of the token say projected (1) or biased (2)
      for name, formula, flags, control in (
          ("texld", "d = sample(sampler b, a)", {}, 0),
          ("texldp", "d = sample(sampler b, a.xyz / a.w)", {"proj": True}, 1),
          ("texldb", "d = sample(sampler b, a.xyz, lod bias a.w)", {"bias": True}, 2))],
    _row("texldd", 93, PS2X | PS3, "dsSss", "tex", "d = sample(sampler b, a, ddx = c, ddy = e)",
         slots=3, dst_kinds=R, src_kinds=(None, S), reads=("coord", "", "coord", "coord"),
         lowers=Handler(tx.texldd)),
    _row("texldl", 95, PS3 | VS3, "dsS", "tex", "d = sample(sampler b, a.xyz, lod a.w)", slots=2,
         src_kinds=(None, S), reads=("coord+w",), lowers=Handler(partial(tx.texld, lod=True))),
]

_FLOW = [
    _row("call", 25, FLOW_VERSIONS, "l", "flow", "call subroutine l", slots=2,
         lowers=Handler(fl.call)),
    _row("callnz", 26, FLOW_VERSIONS, "lb", "flow", "call subroutine l if b", slots=3,
         lowers=Handler(fl.callnz)),
    _row("ret", 28, FLOW_VERSIONS, "", "flow", "return", slots=1, lowers=Handler(fl.ret),
         ends_body=True),
    _row("label", 30, FLOW_VERSIONS, "l", "flow", "subroutine entry", slots=0, lowers=NO_CODE,
         ends_body=True),
    _row("loop", 27, LOOP_VERSIONS, "LI", "flow", "loop i.x times, aL from i.y step i.z", slots=3,
         lowers=Handler(fl.loop)),
    _row("endloop", 29, LOOP_VERSIONS, "", "flow", "end of loop", slots=2,
         lowers=Handler(fl.endloop)),
    _row("rep", 38, FLOW_VERSIONS, "I", "flow", "repeat i.x times", slots=3,
         lowers=Handler(fl.rep)),
    _row("endrep", 39, FLOW_VERSIONS, "", "flow", "end of rep", slots=2,
         lowers=Handler(fl.endrep)),
    _row("if", 40, FLOW_VERSIONS, "b", "flow", "if b (or if_cmp a, b)", slots=3, compare_code=41,
         lowers=Handler(fl.if_)),
    _row("else", 42, FLOW_VERSIONS, "", "flow", "else", slots=1, lowers=Handler(fl.else_)),
    _row("endif", 43, FLOW_VERSIONS, "", "flow", "end of if", slots=1, lowers=Handler(fl.endif)),
    _row("break", 44, FLOW_VERSIONS, "", "flow", "leave the loop (break_cmp a, b: if a <cmp> b)",
         compare_code=45,
         slots=1, lowers=Handler(fl.break_)),
    _row("breakp", 96, PREDICATE_VERSIONS, "p", "flow", "leave the loop if p0", slots=3,
         lowers=Handler(fl.break_)),
]

# Instructions that are no instruction: the version token, constants, declarations, phase.
_SETUP = [
    _row("def", 81, PS_ALL | VS, "dffff", "setup", "c# = (x, y, z, w)", slots=0, lowers=NO_CODE, dst_kinds=C),
    _row("defi", 48, PS2X | PS3 | VS2UP, "dnnnn", "setup", "i# = (x, y, z, w)", slots=0, lowers=NO_CODE,
         dst_kinds=("i",)),
    _row("defb", 47, PS2X | PS3 | VS2UP, "dB", "setup", "b# = value", slots=0, lowers=NO_CODE, dst_kinds=("b",)),
    _row("dcl", 31, PS2UP | VS, "d", "setup", "declare an input, output or sampler", slots=0, lowers=NO_CODE),
    _row("phase", 0xFFFD, PS14, "", "setup", "ends phase 1 of a ps_1_4 shader", slots=0, lowers=NO_CODE),
]

TABLE: tuple[InstrInfo, ...] = tuple(_ARITH + _TEXTURE + _FLOW + _SETUP)


# Comparison suffixes of if_cmp / break_cmp / setp_cmp.
COMPARISONS = ("gt", "lt", "ge", "le", "eq", "ne")
# Opcodes that take a comparison suffix; if_cmp/break_cmp take two sources instead of b/none.
COMPARING = {"if": "ss", "break": "ss", "setp": None}

_BY_NAME: dict[str, list[InstrInfo]] = {}
for _info in TABLE:
    _BY_NAME.setdefault(_info.name, []).append(_info)
# (opcode, version) -> the row `lookup` answers: the first row of that name the version has
# (the assembler asks once per instruction; scanning the rows' version sets cost a tenth of it)
_BY_VERSION: dict[tuple[str, str], InstrInfo] = {}
for _info in TABLE:
    for _version in _info.versions.names:
        _BY_VERSION.setdefault((_info.name, _version), _info)


# (opcode number, control bits, version) -> the row: what a bytecode reader asks per instruction
_BY_CODE: dict[tuple[int, int, str], InstrInfo] = {}
for _info in TABLE:
    for _code in (_info.code, _info.compare_code):
        if _code is None:
            continue
        for _version in _info.versions.names:
            _BY_CODE.setdefault((_code, _info.control, _version), _info)


def by_code(code: int, control: int, version: str) -> InstrInfo | None:
    """The row of D3DSIO opcode `code` with opcode-specific `control` bits (texldp's 1; 0 for
    most) in `version`; None when the version has no such instruction."""
    return _BY_CODE.get((code, control, version))


def rows_named(name: str) -> list[InstrInfo]:
    """Every row for an opcode (texld has one for ps_1_4 and one for ps_2_0+)."""
    return list(_BY_NAME.get(name, ()))


def lookup(name: str, version: str) -> InstrInfo | None:
    """The row for `name` in `version`, or None when the version lacks the instruction."""
    return _BY_VERSION.get((name, version))


def is_known(name: str) -> bool:
    return name in _BY_NAME


def versions_having(name: str) -> list[str]:
    from effects.shaders.asm.versions import VERSION_ORDER
    names: set[str] = set()
    for info in _BY_NAME.get(name, ()):
        names |= info.versions.names
    return [v for v in VERSION_ORDER if v in names]
