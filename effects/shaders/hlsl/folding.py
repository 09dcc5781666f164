"""Compile-time arithmetic: constant folding with IEEE semantics, and fxc's integer rules.

Folding runs the kernel of the IR op each DAG op lowers to (`effects.program.ir.OPS`), so a
folded constant is what the renderer would have computed from the same operands: rcp(0) and
rsq(0) are +inf, log(0) -inf, frc(inf) NaN, nrm of a zero vector scales by FLT_MAX, NaN
propagates and compares false. Values stay float64 between ops, as the compiler always kept
them (float32 where the IR kernel itself rounds: rcp, nrm); `finite32` says whether a value
survives as a Direct3D 9 constant register.

Integers (DX9 hardware has none; fxc folds them at compile time, with the D3D10 rules its
integer front end follows): a float becomes an int32 by truncation, saturating at the int32
range with NaN as 0 (D3D10's ftoi); `& | ^ ~` work on the 32-bit two's-complement pattern; a
shift uses the low five bits of its count (1 << -1 is 1 << 31, 1 << 34 is 4: vkd3d-shader's
tests of fxc, tests/hlsl/bitwise.shader_test); the result wraps to int32 (uint: 0..2^32-1).
"""
from __future__ import annotations

import math
from typing import Any, Callable

import numpy as np

from effects.program.ir import OPS

FLT_MAX = float(np.finfo(np.float32).max)
_F64 = np.float64

# DAG op -> the IR op whose kernel folds it (one row each; the DAG keeps D3D's names)
IR_OP = {
    "add": "add", "mul": "mul", "mad": "mad", "min": "min", "max": "max", "frc": "frc",
    "abs": "abs", "rcp": "rcp", "rsq": "rsq", "exp": "exp2", "log": "log2", "pow": "pow",
    "cmp": "cmp", "cnd": "cnd", "lrp": "lrp", "sat": "saturate", "slt": "slt", "sge": "sge",
    "dp3": "dp3", "dp4": "dp4", "crs": "crs", "nrm": "nrm",
}


def _kernel(ir_op: str) -> Callable[..., np.ndarray]:
    kernel = OPS[ir_op].kernel
    return lambda *args: kernel(None, list(args), {})


def _row(values: Any, width: int = 4) -> np.ndarray:
    """Lanes as one (1, 4) float64 row (an IR value), zero-padded."""
    row = np.zeros((1, 4), np.float64)
    row[0, :min(width, len(values))] = values[:width]
    return row


def _lanes(ir_op: str) -> Callable[[list[Any], int], list[float]]:
    """A per-component op: lane i from lane i of each argument (a scalar argument spreads)."""
    kernel = _kernel(ir_op)

    def fold(consts: list[Any], width: int) -> list[float]:
        # lane by lane on float64 scalars: the kernel's arithmetic, without building arrays
        return [float(kernel(*[_F64(c[i] if len(c) > 1 else c[0]) for c in consts]))
                for i in range(width)]
    return fold


def _shaped(ir_op: str, widths: tuple[int, ...], out: int) -> Callable[[list[Any], int], list[float]]:
    """An op on whole rows (dot products, cross, normalise): its arguments padded to four."""
    kernel = _kernel(ir_op)

    def fold(consts: list[Any], width: int) -> list[float]:
        rows = [_row(c, n) for c, n in zip(consts, widths)]
        return [float(x) for x in np.ravel(kernel(*rows))[:out]]
    return fold


def _dp2add(consts: list[Any], width: int) -> list[float]:
    a, b, c = consts       # no IR op of its own: lowering writes mul + mad
    return [float(np.float64(a[0]) * b[0] + np.float64(a[1]) * b[1] + c[0])]


def _sincos(consts: list[Any], width: int) -> list[float]:
    a = np.array([consts[0][0]], np.float64)      # D3D sincos: .x = cos, .y = sin
    return [float(_kernel("cos")(a)[0]), float(_kernel("sin")(a)[0])]


def _lit(consts: list[Any], width: int) -> list[float]:
    """The vertex shader's lit (its reference page): (1, x > 0 ? x : 0, x > 0 and y > 0 ?
    y^w : 0, 1), the power clamped to +-127.9961 (8.8 fixed point)."""
    x, y, _, w = (float(v) for v in consts[0])
    power = min(max(w, -127.9961), 127.9961)
    spec = float(np.power(_F64(y), _F64(power))) if x > 0 and y > 0 else 0.0
    return [1.0, x if x > 0 else 0.0, spec, 1.0]


def _dst(consts: list[Any], width: int) -> list[float]:
    """The vertex shader's dst (its reference page): (1, a.y * b.y, a.z, b.w)."""
    a, b = consts
    return [1.0, float(np.float32(a[1]) * np.float32(b[1])), float(a[2]), float(b[3])]


# op -> (argument widths or None for per-component, result width or None, fold function)
FOLDS: dict[str, tuple[tuple[int, ...] | None, int | None, Callable[[list[Any], int], list[float]]]] = {
    **{op: (None, None, _lanes(ir)) for op, ir in IR_OP.items()
       if op not in ("dp3", "dp4", "crs", "nrm")},
    "mov": (None, None, lambda consts, width: [float(consts[0][i] if len(consts[0]) > 1
                                                      else consts[0][0]) for i in range(width)]),
    "dp3": ((3, 3), 1, _shaped("dp3", (3, 3), 1)),
    "dp4": ((4, 4), 1, _shaped("dp4", (4, 4), 1)),
    "crs": ((3, 3), 3, _shaped("crs", (3, 3), 3)),
    "nrm": ((3,), 3, _shaped("nrm", (3,), 3)),
    "dp2add": ((2, 2, 1), 1, _dp2add),
    "sincos": ((1,), 2, _sincos),
    "lit": ((4,), 4, _lit),
    "dst": ((4, 4), 4, _dst),
}


def fold(op: str, consts: list[Any], width: int) -> list[float]:
    """`op` on constant arguments (each its lanes after swizzle and negation): IEEE results,
    never an exception (inf and NaN are values; `finite32` judges them where they land)."""
    with np.errstate(all="ignore"):
        return FOLDS[op][2](consts, width)


def finite32(value: float) -> bool:
    """Whether `value` is a finite float32 (what a Direct3D 9 constant register holds)."""
    return math.isfinite(value) and abs(value) <= FLT_MAX * (1 + 2.0 ** -25)


# -- integers -------------------------------------------------------------------------------

def to_int32(x: float) -> int:
    """A float as int32: truncated toward zero, saturated at the int32 range, NaN as 0."""
    if x != x:
        return 0
    if x >= 2147483647.0:
        return 2147483647
    if x <= -2147483648.0:
        return -2147483648
    return int(x)


def _wrap(n: int, base: str) -> int:
    n &= 0xFFFFFFFF
    if base == "uint":
        return n
    return n - (1 << 32) if n >= 1 << 31 else n


def _pattern(x: float, base: str) -> int:
    """The 32-bit pattern of a folded int or uint (a uint past int32 converts as unsigned)."""
    if base == "uint" and x == x and x >= 0:
        return int(min(x, 4294967295.0))
    return to_int32(x) & 0xFFFFFFFF


def bitwise(opname: str, a: float, b: float, base: str) -> float:
    """`a op b` on ints (`& | ^ << >>`), fxc's rules above; `base` 'int' or 'uint'."""
    x, y = _pattern(a, base), _pattern(b, base)
    if opname == "&":
        r = x & y
    elif opname == "|":
        r = x | y
    elif opname == "^":
        r = x ^ y
    elif opname == "<<":
        r = x << (y & 31)
    else:                       # >>: arithmetic for int, logical for uint
        r = (_wrap(x, base) >> (y & 31))
    return float(_wrap(r, base))


def bitwise_not(a: float, base: str) -> float:
    """`~a` on an int (uint: of its 32 bits)."""
    return float(_wrap(~_pattern(a, base), base))


def truncate(x: float) -> float:
    """Toward zero, IEEE: inf and NaN stay what they are."""
    return x if not math.isfinite(x) else float(math.trunc(x))
