"""Shader-assembly semantics as data: source modifiers, instruction modifiers and macros.

Every rule is a small expression tree over named values (after Mesa's `nir_opt_algebraic.py`);
`Emitter.emit` turns a tree into IR through the Builder. The lowering (lower.py) picks a row and
binds the names; it holds no per-modifier or per-macro if-chains.

Tree grammar
    "a" / "b" / "c" / "x" ...      a bound name: a value id, or a float for parameters
    1.5                            a float literal (all four components)
    ("vec", x, y, z, w)            a vec4 literal
    ("swz", "wwww", tree)          swizzle (4 of xyzw)
    ("merge", "yz", old, new)      new in the named components, old elsewhere
    ("clamp", lo, hi, tree)        lo / hi are floats or names bound to floats
    ("quantize", tree)             the fixed-point grid bound as "grid" (bits, signed, scale)
    (op, tree, ...)                any Builder op: add sub mul mad neg dp3 dp4 min max rcp rsq
                                   exp2 log2 pow frc abs sin cos cmp cnd lrp nrm crs slt sge
                                   saturate

Sources: docs/reference/semantics.md §2.2-2.4 (ps_1_x modifiers and instructions), §3
(ps_2_0), §4 (vs_1_1 macros: expp, logp, lit, dst, frc, m4x4 family), the instruction table's
`formula` column (instructions.py).
"""
from __future__ import annotations

from typing import Any, Callable, Mapping, Union

from effects.program.ir import COMPONENTS, Builder

Tree = Union[str, float, tuple]

# -- source modifiers (applied to "x": the register after its swizzle; negate last) ------------
# _dz/_dw divide xy by z/w before the swizzle (DXVK order); a zero divisor gives 1
# (docs/reference/semantics.md 2.2: "division by 0 gives 1").
def _divide_xy_by(component: str) -> Tree:
    d = ("swz", component * 4, "x")
    return ("merge", "xy", "x", ("cmp", ("neg", ("abs", d)), 1.0, ("mul", "x", ("rcp", d))))


SOURCE_MODIFIERS: dict[str | None, Tree] = {
    None: "x",
    "bias": ("sub", "x", 0.5),                    # x - 0.5
    "bx2": ("mul", ("sub", "x", 0.5), 2.0),       # 2 (x - 0.5)
    "x2": ("mul", "x", 2.0),                      # 2 x (ps_1_4)
    "invert": ("sub", 1.0, "x"),                  # 1 - x
    "abs": ("abs", "x"),                          # |x| (sm3)
    "dz": _divide_xy_by("z"),
    "dw": _divide_xy_by("w"),
}
# Modifiers applied to the register before its swizzle.
PRE_SWIZZLE_MODIFIERS = frozenset({"dz", "dw"})
NEGATE: Tree = ("neg", "x")

# -- instruction modifiers: applied to the result "x" in this order ----------------------------
# shift, then _sat (Wine and DXVK order, docs/reference/semantics.md 2.3), then the card's
# register range and fixed-point grid (the profile's precision, effects.d3d9.precision). Each
# row: (name, tree); the
# lowering binds "scale", "range", "neg_range" and "grid" and skips rows whose switch is off.
# Each row carries its condition (as nir_opt_algebraic rows do), over the write's facts `w`:
# w.shift, w.saturate (the instruction's), w.computed (an arithmetic result, not a texel),
# w.range and w.grid (the register precision, None when float).
RESULT_MODIFIERS: tuple[tuple[str, Callable[[Any], bool], Tree], ...] = (
    ("shift", lambda w: w.shift != 0, ("mul", "x", "scale")),
    ("saturate", lambda w: w.saturate, ("saturate", "x")),
    ("range", lambda w: w.computed and w.range is not None,
     ("clamp", "neg_range", "range", "x")),
    ("quantize", lambda w: w.computed and w.grid is not None, ("quantize", "x")),
)

# -- instructions: the result over the sources a, b, c ----------------------------------------
# Scalar sources (role 'x' in the table) arrive already replicated from their selected
# component. Names other than a/b/c are bound by the lowering ("bumpenv" for bem).
_X, _Y, _Z, _W = (("swz", c * 4, "a") for c in COMPONENTS)


def _floor(t: Tree) -> Tree:
    return ("sub", t, ("frc", t))


def _sign(t: Tree) -> Tree:
    return ("sub", ("slt", 0.0, t), ("slt", t, 0.0))


# Comparisons of if_cmp / break_cmp / setp_cmp, per component, as 1 (true) or 0.
def _eq(a: Tree, b: Tree) -> Tree:
    return ("mul", ("sge", a, b), ("sge", b, a))


COMPARE: dict[str, Tree] = {
    "gt": ("slt", "b", "a"), "lt": ("slt", "a", "b"), "ge": ("sge", "a", "b"),
    "le": ("sge", "b", "a"), "eq": _eq("a", "b"), "ne": ("sub", 1.0, _eq("a", "b")),
}

# Rows of the instruction table (instructions.py) name these trees; the plain ones (add, mul
# ...) are written in the row itself.
# ps_1_1-1_3: the condition is r0.a for all four components
CND_ALPHA: Tree = ("cnd", ("swz", "wwww", "a"), "b", "c")
# ps_1_1-1_3 co-issued cnd writing colour: always the first choice (Wine; the d3d9 cnd test
# expects src1, docs/reference/semantics.md 2.4)
CND_COISSUE: Tree = "b"
# a.x * b.x + a.y * b.y + c (c scalar)
DP2ADD: Tree = ("add", ("add", ("swz", "xxxx", ("mul", "a", "b")),
                        ("swz", "yyyy", ("mul", "a", "b"))), "c")
# x = cos a, y = sin a (sincos's extra constant sources of sm2 are not needed)
SINCOS: Tree = ("merge", "y", ("cos", "a"), ("sin", "a"))
# (1, a.y * b.y, a.z, b.w)
DST: Tree = ("merge", "w", ("merge", "z", ("merge", "y", 1.0, ("mul", "a", "b")), "a"), "b")
# (1, max(a.x, 0), a.x > 0 ? max(a.y, 0)^clamp(a.w, -128, 128) : 0, 1)
LIT: Tree = ("merge", "z", ("merge", "y", 1.0, ("max", _X, 0.0)),
             ("cmp", ("neg", _X), 0.0, ("pow", ("max", _Y, 0.0), ("clamp", -128.0, 128.0, _W))))
# vs_1_1: (2^floor a, a - floor a, 2^a, 1); vs_2_0+: 2^a (partial precision)
EXPP_VS1: Tree = ("merge", "xyz", 1.0,
                  ("merge", "y", ("merge", "z", ("exp2", _floor("a")), ("exp2", "a")),
                   ("frc", "a")))
# vs_1_1: v = |a|: (floor log2 v, v / 2^floor(log2 v), log2 v, 1); vs_2_0+: log2 |a|
LOGP_VS1: Tree = ("merge", "xyz", 1.0,
                  ("merge", "y", ("merge", "z", _floor(("log2", "a")), ("log2", "a")),
                   ("mul", ("abs", "a"), ("exp2", ("neg", _floor(("log2", "a")))))))
# address register loads: vs_1_1 `mov a0` floors; vs_2_0 `mova` rounds halves away from 0
MOV_A0: Tree = _floor("a")
MOVA: Tree = ("mul", _sign("a"), _floor(("add", ("abs", "a"), 0.5)))
# bem r(n): xy = a.xy + M(n) (b.r, b.g); bumpenv = (M00, M01, M10, M11)
BEM: Tree = ("mad", ("swz", "xxxx", "b"), ("swz", "xyxy", "bumpenv"),
             ("mad", ("swz", "yyyy", "b"), ("swz", "zwzw", "bumpenv"), "a"))


class Emitter:
    """Emits rewrite trees into a Builder. Swizzles of swizzles compose into one, so a
    replicate selector followed by a scalar pick stays a single swizzle; a swizzle of a
    literal is a literal (`def c0` then `c0.x`)."""

    def __init__(self, builder: Builder) -> None:
        self.b = builder
        self._swizzled: dict[int, tuple[int, str]] = {}
        self._literals: dict[int, tuple[float, ...]] = {}

    def const(self, value: float | tuple[float, ...]) -> int:
        values = (float(value),) * 4 if isinstance(value, (int, float)) else tuple(value)
        result = self.b.const(values)
        self._literals[result] = values
        return result

    def swizzle(self, value: int, pattern: str) -> int:
        if value in self._literals:
            values = self._literals[value]
            return self.const(tuple(values[COMPONENTS.index(c)] for c in pattern))
        if value in self._swizzled:
            source, inner = self._swizzled[value]
            value, pattern = source, "".join(inner[COMPONENTS.index(c)] for c in pattern)
        result = self.b.swizzle(value, pattern)
        if result != value:
            self._swizzled[result] = (value, pattern)
        return result

    def emit(self, tree: Tree, env: Mapping[str, Any]) -> int:
        if isinstance(tree, str):
            value = env[tree]
            return self.const(value) if isinstance(value, float) else value
        if isinstance(tree, (int, float)):
            return self.const(float(tree))
        head, *rest = tree
        if head == "vec":
            return self.const(tuple(float(v) for v in rest))
        if head == "swz":
            return self.swizzle(self.emit(rest[1], env), rest[0])
        if head == "merge":
            return self.b.merge(self.emit(rest[1], env), self.emit(rest[2], env), rest[0])
        if head == "clamp":
            lo, hi = (env[v] if isinstance(v, str) else v for v in rest[:2])
            return self.b.clamp(self.emit(rest[2], env), float(lo), float(hi))
        if head == "quantize":
            bits, signed, scale = env["grid"]
            return self.b.quantize(self.emit(rest[0], env), bits, signed, scale)
        # any other head is an IR op by name: its row in effects.program.ir.OPS is all it needs
        return self.b.emit(head, *(self.emit(t, env) for t in rest))
