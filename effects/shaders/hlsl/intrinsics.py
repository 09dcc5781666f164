"""The intrinsic functions: one row per name (argument count, how it is built).

Each builder returns a Value from the argument Values, using the instructions the target has
(`pow` or exp/log, `nrm` or rsq, `crs` or mul/mad, `lrp` or mad, `dp2add` or mad ...). Where
the target cannot compute an intrinsic at all the error names it and the target.
"""
from __future__ import annotations

import math
from typing import Any, Callable

from effects.base.errors import Location
from effects.shaders.hlsl.dag import Operand, host_computable, reachable
from effects.shaders.hlsl.types import BOOL, FLOAT, HType, builtin, shape_of, vector
from effects.shaders.hlsl.lvalues import store
from effects.shaders.hlsl.values import Value, component, split


def _float(v: Value) -> HType:
    t = v.type
    return t.with_base("float") if t.base not in ("float", "half", "double") else t


def _comps(ev: Any, v: Value, loc: Location) -> list[Operand]:
    if not v.type.numeric:
        raise ev.error(f"X3013: a numeric argument is needed, not '{v.type}'", loc)
    return v.comps


def _unary(build: Callable[[Any, list[Operand], Location], list[Operand]]):
    def f(ev: Any, args: list[Value], loc: Location) -> Value:
        return Value(_float(args[0]), build(ev, _comps(ev, args[0], loc), loc))
    return f


def _binary(build: Callable[[Any, list[Operand], list[Operand], Location], list[Operand]]):
    def f(ev: Any, args: list[Value], loc: Location) -> Value:
        ca, cb, t = ev.a.broadcast(args[0], args[1], loc, "intrinsic")
        return Value(t.with_base("float") if t.base not in ("float", "half") else t, build(ev, ca, cb, loc))
    return f


def _abs(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    if ev.ctx.target.has("abs"):
        return ev.a.lanes("abs", [c], loc)
    return ev.a.lanes("max", [c, [x.neg() for x in c]], loc)


def _rsq(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    return ev.a.scalar_lanes("rsq", [c], loc)


def _sqrt(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    return ev.a.scalar_lanes("rcp", [_rsq(ev, c, loc)], loc)


def _exp2(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    return ev.a.scalar_lanes("exp", [c], loc)


def _log2(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    return ev.a.scalar_lanes("log", [c], loc)


def _scale(ev: Any, c: list[Operand], k: float, loc: Location) -> list[Operand]:
    return ev.a.lanes("mul", [c, [ev.a.const(k)] * len(c)], loc)


def _pow(ev: Any, a: list[Operand], b: list[Operand], loc: Location) -> list[Operand]:
    if ev.ctx.target.has("pow"):
        # fxc's code (issue 31, from its listings): a whole exponent as multiplications
        # (pow(x, 4): two muls) where they take no more slots than the alternative; a vector
        # as log per lane, one mul, exp per lane (2n + 1 slots against 3n for n pow macros,
        # pow being 3 slots: instructions.py); a scalar by the pow macro
        alternative = 3 if len(a) == 1 else 2 * len(a) + 1
        n = {c.const_values() for c in b}
        k = next(iter(n))[0] if len(n) == 1 and None not in n else None  # type: ignore[index]
        if k is not None and 1 <= k <= 16 and k == int(k) and _multiplies(int(k)) <= alternative:
            return _power_lanes(ev, a, int(k), loc)
        if len(a) > 1:
            return _exp2(ev, ev.a.lanes("mul", [b, _log2(ev, a, loc)], loc), loc)
        return ev.a.scalar_lanes("pow", [a, b], loc)
    if ev.ctx.target.rules.is_ps1:
        # fxc expanded a small whole exponent into multiplications (x^8 = three muls); ps_1_x
        # has no exp/log for the rest
        n = [c.const_values() for c in b]
        if all(v is not None and 1 <= v[0] <= 16 and v[0] == int(v[0]) for v in n):
            return [_power_lanes(ev, [x], int(v[0]), loc)[0] for x, v in zip(a, n)]  # type: ignore[index]
        raise ev.error(f"{ev.ctx.target.name} cannot compute pow of a non-constant exponent", loc)
    return _exp2(ev, ev.a.lanes("mul", [b, _log2(ev, a, loc)], loc), loc)


def _multiplies(n: int) -> int:
    """How many muls x^n takes by squaring."""
    return n.bit_length() - 1 + bin(n).count("1") - 1


def _power_lanes(ev: Any, xs: list[Operand], n: int, loc: Location) -> list[Operand]:
    """x^n by squaring, every lane at once (one mul a step for a vector)."""
    result: list[Operand] | None = None
    square = xs
    while n:
        if n & 1:
            result = square if result is None else ev.a.lanes("mul", [result, square], loc)
        n >>= 1
        if n:
            square = ev.a.lanes("mul", [square, square], loc)
    return result  # type: ignore[return-value]


def _floor(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    return ev.a.floor(c, loc)


def _ceil(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    return [x.neg() for x in ev.a.floor([x.neg() for x in c], loc)]


def _round(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    return ev.a.floor(ev.a.lanes("add", [c, [ev.a.const(0.5)] * len(c)], loc), loc)


def _sign(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    zero = [ev.a.const(0.0)] * len(c)
    pos = ev.a.compare(">", c, zero, loc)
    neg = ev.a.compare("<", c, zero, loc)
    return ev.a.lanes("add", [pos, [x.neg() for x in neg]], loc)


def _lerp(ev: Any, args: list[Value], loc: Location) -> Value:
    a, b, s = args
    ca, cb, t = ev.a.broadcast(a, b, loc, "lerp")
    cs = s.comps * len(ca) if len(s.comps) == 1 else s.comps[:len(ca)]
    if ev.ctx.target.has("lrp"):
        return Value(t, ev.a.lanes("lrp", [cs, cb, ca], loc))
    diff = ev.a.lanes("add", [cb, [x.neg() for x in ca]], loc)
    return Value(t, ev.a.lanes("mad", [cs, diff, ca], loc))


def _clamp(ev: Any, args: list[Value], loc: Location) -> Value:
    x, lo, hi = args
    v = Value(x.type, ev.a.lanes("max", list(ev.a.broadcast(x, lo, loc, "clamp")[:2]), loc))
    ca, cb, t = ev.a.broadcast(v, hi, loc, "clamp")
    return Value(t, ev.a.lanes("min", [ca, cb], loc))


def _step(ev: Any, args: list[Value], loc: Location) -> Value:
    ca, cx, t = ev.a.broadcast(args[0], args[1], loc, "step")
    return Value(t.with_base("float"), ev.a.compare(">=", cx, ca, loc))


def _smoothstep(ev: Any, args: list[Value], loc: Location) -> Value:
    a, b, x = args
    n = max(a.type.size, b.type.size, x.type.size)
    ext = lambda v: v.comps * n if len(v.comps) == 1 else v.comps[:n]
    ca, cb, cx = ext(a), ext(b), ext(x)
    num = ev.a.lanes("add", [cx, [c.neg() for c in ca]], loc)
    den = ev.a.lanes("add", [cb, [c.neg() for c in ca]], loc)
    t = ev.a.saturate(ev.a.divide(num, den, loc), loc)
    k = ev.a.lanes("mad", [t, [ev.a.const(-2.0)] * n, [ev.a.const(3.0)] * n], loc)
    return Value(vector("float", n), ev.a.lanes("mul", [ev.a.lanes("mul", [t, t], loc), k], loc))


def dot(ev: Any, a: list[Operand], b: list[Operand], loc: Location) -> Operand:
    n = len(a)
    if n == 1:
        return ev.a.op("mul", [a[0], b[0]], loc)
    if n in (3, 4):
        return ev.a.op(f"dp{n}", [ev.g.pack(a), ev.g.pack(b)], loc)
    if n == 2 and ev.ctx.target.has("dp2add"):
        return ev.a.op("dp2add", [ev.g.pack(a), ev.g.pack(b), ev.a.const(0.0)], loc)
    acc = ev.a.op("mul", [a[0], b[0]], loc)
    for x, y in zip(a[1:], b[1:]):
        acc = ev.a.op("mad", [x, y, acc], loc)
    return acc


def _dot(ev: Any, args: list[Value], loc: Location) -> Value:
    ca, cb, _ = ev.a.broadcast(args[0], args[1], loc, "dot")
    return Value(FLOAT, [dot(ev, ca, cb, loc)])


def _length(ev: Any, args: list[Value], loc: Location) -> Value:
    c = args[0].comps
    return Value(FLOAT, _sqrt(ev, [dot(ev, c, c, loc)], loc))


def _distance(ev: Any, args: list[Value], loc: Location) -> Value:
    ca, cb, _ = ev.a.broadcast(args[0], args[1], loc, "distance")
    d = ev.a.lanes("add", [ca, [x.neg() for x in cb]], loc)
    return Value(FLOAT, _sqrt(ev, [dot(ev, d, d, loc)], loc))


def _normalize(ev: Any, args: list[Value], loc: Location) -> Value:
    c = args[0].comps
    if len(c) == 3 and ev.ctx.target.has("nrm"):
        return Value(args[0].type, split(ev.a.op("nrm", [ev.g.pack(c)], loc)))
    inv = _rsq(ev, [dot(ev, c, c, loc)], loc)[0]
    return Value(_float(args[0]), ev.a.lanes("mul", [c, [inv] * len(c)], loc))


def _cross(ev: Any, args: list[Value], loc: Location) -> Value:
    a, b = args[0].comps[:3], args[1].comps[:3]
    if ev.ctx.target.has("crs"):
        return Value(vector("float", 3), split(ev.a.op("crs", [ev.g.pack(a), ev.g.pack(b)], loc)))
    p = lambda v, s: [v[i] for i in s]
    first = ev.a.lanes("mul", [p(a, (1, 2, 0)), p(b, (2, 0, 1))], loc)
    return Value(vector("float", 3),
                 ev.a.lanes("mad", [[x.neg() for x in p(a, (2, 0, 1))], p(b, (1, 2, 0)), first], loc))


def _reflect(ev: Any, args: list[Value], loc: Location) -> Value:
    i, n = args[0].comps, args[1].comps
    d = dot(ev, n, i, loc)
    d2 = ev.a.op("add", [d, d], loc)
    return Value(args[0].type, ev.a.lanes("mad", [[d2.neg()] * len(n), n, i], loc))


def _mul(ev: Any, args: list[Value], loc: Location) -> Value:
    a, b = args
    ta, tb = a.type, b.type
    if ta.size == 1 or tb.size == 1:
        ca, cb, t = ev.a.broadcast(a, b, loc, "mul")
        return Value(t, ev.a.lanes("mul", [ca, cb], loc))
    if ta.kind != "matrix" and tb.kind != "matrix":
        ca, cb, _ = ev.a.broadcast(a, b, loc, "mul")
        return Value(FLOAT, [dot(ev, ca, cb, loc)])
    rows_a = [a.comps] if ta.kind != "matrix" else \
        [a.comps[i * ta.cols:(i + 1) * ta.cols] for i in range(ta.rows)]
    k_a = len(rows_a[0])
    if tb.kind == "matrix":
        k_b, cols = tb.rows, tb.cols
        col = lambda j: [b.comps[k * cols + j] for k in range(k_b)]
        brows = [b.comps[k * cols:(k + 1) * cols] for k in range(k_b)]
    else:  # matrix * column vector
        k_b, cols = tb.size, 1
        col = lambda j: list(b.comps)
        brows = [[c] for c in b.comps]
    k = min(k_a, k_b)
    if k_a != k_b:
        ev.warn("X3206: implicit truncation of vector type", loc)
    if ta.kind == "matrix" and tb.kind != "matrix":
        by_columns = _columns_product(ev, rows_a, b.comps, k, loc)
        if by_columns is not None:
            return Value(vector("float", len(rows_a)), by_columns)
    out_rows = []
    for row in rows_a:
        row = row[:k]
        columns = [col(j)[:k] for j in range(cols)]
        single = all(len({id(c.node) for c in cc}) == 1 for cc in columns)
        if (single and k in (3, 4)) or cols == 1:
            out_rows.append([dot(ev, row, cc, loc) for cc in columns])
        else:   # a sum of scaled rows: mul then mad
            acc = ev.a.lanes("mul", [[row[0]] * cols, brows[0]], loc)
            for x, br in zip(row[1:], brows[1:k]):
                acc = ev.a.lanes("mad", [[x] * cols, br, acc], loc)
            out_rows.append(acc)
    if ta.kind != "matrix":
        return Value(vector("float", cols), out_rows[0])
    if tb.kind != "matrix":
        return Value(vector("float", len(out_rows)), [r[0] for r in out_rows])
    return Value(shape_of(len(out_rows), cols, "float"), [c for r in out_rows for c in r])


def _columns_product(ev: Any, rows: list[list[Any]], v: list[Any], k: int,
                     loc: Location) -> list[Any] | None:
    """mul(M, v) for a matrix whose rows are spread over registers but whose columns each sit
    in one (a column_major uniform, HLSL's default packing: Wild Magic's mul(PVWMatrix, p)):
    v.x * column 0 + v.y * column 1 ..., a mul and k-1 mads, as fxc emits, instead of gathering
    every row into a temporary for a dp4. None when the rows are whole registers already."""
    one_node = lambda comps: len({id(c.node) for c in comps}) == 1
    if all(one_node(r[:k]) for r in rows):
        return None
    columns = [[r[j] for r in rows] for j in range(k)]
    if not all(one_node(c) for c in columns):
        return None
    acc = ev.a.lanes("mul", [columns[0], [v[0]] * len(rows)], loc)
    for j in range(1, k):
        acc = ev.a.lanes("mad", [columns[j], [v[j]] * len(rows), acc], loc)
    return acc


def _transpose(ev: Any, args: list[Value], loc: Location) -> Value:
    t = args[0].type
    if t.kind != "matrix":
        return args[0]
    comps = [args[0].comps[i * t.cols + j] for j in range(t.cols) for i in range(t.rows)]
    return Value(shape_of(t.cols, t.rows, t.base), comps)


def _determinant(ev: Any, args: list[Value], loc: Location) -> Value:
    t = args[0].type
    n = t.rows
    if t.kind != "matrix" or t.rows != t.cols:
        raise ev.error("X3013: determinant needs a square matrix", loc)
    m = [[args[0].comps[i * n + j] for j in range(n)] for i in range(n)]

    def det(rows: list[list[Operand]]) -> Operand:
        if len(rows) == 1:
            return rows[0][0]
        acc = None
        for j in range(len(rows)):
            minor = [r[:j] + r[j + 1:] for r in rows[1:]]
            term = ev.a.op("mul", [rows[0][j], det(minor)], loc)
            term = term if j % 2 == 0 else term.neg()
            acc = term if acc is None else ev.a.op("add", [acc, term], loc)
        return acc  # type: ignore[return-value]
    return Value(FLOAT, [det(m)])


# vs_1_1 has no sincos: fxc expanded a polynomial there. Ours: Taylor series about 0 on the
# argument reduced to [-pi, pi], to x^13 for sin and x^14 for cos (the first term left out
# bounds the error: pi^15/15! = 2.2e-5, pi^16/16! = 4.3e-6), evaluated by Horner in x^2.
_SIN_TERMS = [(-1) ** k / math.factorial(2 * k + 1) for k in range(7)]
_COS_TERMS = [(-1) ** k / math.factorial(2 * k) for k in range(8)]


def _sincos_parts(ev: Any, c: list[Operand], loc: Location) -> tuple[list[Operand], list[Operand]]:
    t = ev.ctx.target
    if not t.has("sincos") and t.kind != "vs":
        # ps_1_x: only of uniforms, which its preshader computes on the host (preshader.py)
        host = host_computable(reachable(x.node for x in c))
        if not t.rules.is_ps1 or not all(host[x.node.id] for x in c):
            raise ev.error(f"{t.name} cannot compute sin/cos (no sincos instruction)", loc)
        return _sincos_nodes(ev, _reduced(ev, c, loc), loc)
    if t.rules.major < 3:
        c = _reduced(ev, c, loc)
    if not t.has("sincos"):
        return _series(ev, c, _SIN_TERMS, loc, odd=True), _series(ev, c, _COS_TERMS, loc, odd=False)
    return _sincos_nodes(ev, c, loc)


def _reduced(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    """The argument moved into [-pi, pi], as sincos of shader model 2 (and our vs_1_1
    series) wants it."""
    x = ev.a.lanes("mad", [c, [ev.a.const(1 / (2 * math.pi))] * len(c),
                           [ev.a.const(0.5)] * len(c)], loc)
    x = ev.a.frc(x, loc)
    return ev.a.lanes("mad", [x, [ev.a.const(2 * math.pi)] * len(c),
                              [ev.a.const(-math.pi)] * len(c)], loc)


def _sincos_nodes(ev: Any, c: list[Operand], loc: Location
                  ) -> tuple[list[Operand], list[Operand]]:
    sins, coss = [], []
    for x in c:
        r = ev.a.op("sincos", [x], loc, 2)
        coss.append(component(r, 0))
        sins.append(component(r, 1))
    return sins, coss


def _series(ev: Any, x: list[Operand], terms: list[float], loc: Location, odd: bool,
            power: int = 2) -> list[Operand]:
    """sum terms[k] * x^(power*k) (times x when `odd`), one vector mad per term."""
    n = len(x)
    step = ev.a.lanes("mul", [x, x], loc) if power == 2 else x
    acc = [ev.a.const(terms[-1])] * n
    for coefficient in reversed(terms[:-1]):
        acc = ev.a.lanes("mad", [acc, step, [ev.a.const(coefficient)] * n], loc)
    return ev.a.lanes("mul", [acc, x], loc) if odd else acc


def _sin(ev: Any, args: list[Value], loc: Location) -> Value:
    return Value(_float(args[0]), _sincos_parts(ev, args[0].comps, loc)[0])


def _cos(ev: Any, args: list[Value], loc: Location) -> Value:
    return Value(_float(args[0]), _sincos_parts(ev, args[0].comps, loc)[1])


def _tan(ev: Any, args: list[Value], loc: Location) -> Value:
    s, c = _sincos_parts(ev, args[0].comps, loc)
    return Value(_float(args[0]), ev.a.divide(s, c, loc))


# Inverse trigonometry and hyperbolic functions, which no shader model has an instruction for,
# expanded as fxc expanded them, into arithmetic: polynomials of Abramowitz and Stegun,
# "Handbook of Mathematical Functions" (1964), 4.4.49 (arctan on [0, 1], |error| <= 1e-5)
# and 4.4.45 (arccos on [0, 1] as sqrt(1 - x) times a cubic, |error| <= 6.7e-5), extended to
# the whole range by the usual identities.
_ATAN_TERMS = [0.9998660, -0.3302995, 0.1801410, -0.0851330, 0.0208351]
_ACOS_TERMS = [1.5707288, -0.2121144, 0.0742610, -0.0187293]


def _consts(ev: Any, k: float, n: int) -> list[Operand]:
    return [ev.a.const(k)] * n


def _less(ev: Any, k: float, c: list[Operand], loc: Location) -> list[Operand]:
    """k - c per lane."""
    return ev.a.lanes("add", [_consts(ev, k, len(c)), [x.neg() for x in c]], loc)


def _negative(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    """1 where c < 0, else 0."""
    return ev.a.compare("<", c, _consts(ev, 0.0, len(c)), loc)


def _atan_01(ev: Any, t: list[Operand], loc: Location) -> list[Operand]:
    """atan(t) for t in [0, 1] (4.4.49)."""
    return _series(ev, t, _ATAN_TERMS, loc, odd=True)


def _atan(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    n = len(c)
    a = _abs(ev, c, loc)
    one = _consts(ev, 1.0, n)
    p = _atan_01(ev, ev.a.divide(ev.a.lanes("min", [a, one], loc),
                                 ev.a.lanes("max", [a, one], loc), loc), loc)
    r = ev.a.select(ev.a.compare(">", a, one, loc), _less(ev, math.pi / 2, p, loc), p, loc)
    return ev.a.select(_negative(ev, c, loc), [x.neg() for x in r], r, loc)


def _atan2(ev: Any, y: list[Operand], x: list[Operand], loc: Location) -> list[Operand]:
    ay, ax = _abs(ev, y, loc), _abs(ev, x, loc)
    p = _atan_01(ev, ev.a.divide(ev.a.lanes("min", [ax, ay], loc),
                                 ev.a.lanes("max", [ax, ay], loc), loc), loc)
    p = ev.a.select(ev.a.compare(">", ay, ax, loc), _less(ev, math.pi / 2, p, loc), p, loc)
    p = ev.a.select(_negative(ev, x, loc), _less(ev, math.pi, p, loc), p, loc)
    return ev.a.select(_negative(ev, y, loc), [v.neg() for v in p], p, loc)


def _acos(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    a = _abs(ev, c, loc)
    root = _sqrt(ev, _less(ev, 1.0, a, loc), loc)
    p = ev.a.lanes("mul", [_series(ev, a, _ACOS_TERMS, loc, odd=False, power=1), root], loc)
    return ev.a.select(_negative(ev, c, loc), _less(ev, math.pi, p, loc), p, loc)


def _asin(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    return _less(ev, math.pi / 2, _acos(ev, c, loc), loc)


def _exps(ev: Any, c: list[Operand], loc: Location) -> tuple[list[Operand], list[Operand]]:
    """e^x and e^-x."""
    return (_exp2(ev, _scale(ev, c, LOG2E, loc), loc),
            _exp2(ev, _scale(ev, c, -LOG2E, loc), loc))


def _sinh(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    up, down = _exps(ev, c, loc)
    return _scale(ev, ev.a.lanes("add", [up, [x.neg() for x in down]], loc), 0.5, loc)


def _cosh(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    up, down = _exps(ev, c, loc)
    return _scale(ev, ev.a.lanes("add", [up, down], loc), 0.5, loc)


def _tanh(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    up, down = _exps(ev, c, loc)
    return ev.a.divide(ev.a.lanes("add", [up, [x.neg() for x in down]], loc),
                       ev.a.lanes("add", [up, down], loc), loc)


def _faceforward(ev: Any, args: list[Value], loc: Location) -> Value:
    """n where dot(i, ng) < 0, else -n."""
    n, i, ng = (v.comps for v in args)
    behind = _negative(ev, [dot(ev, i, ng, loc)], loc)
    return Value(_float(args[0]), ev.a.select(behind, n, [x.neg() for x in n], loc))


def _refract(ev: Any, args: list[Value], loc: Location) -> Value:
    """eta*i - (eta*dot(n, i) + sqrt(k))*n with k = 1 - eta^2 (1 - dot(n, i)^2); 0 where k < 0
    (total internal reflection)."""
    i, n, eta = args[0].comps, args[1].comps, args[2].comps[0]
    m = len(i)
    d = dot(ev, n, i, loc)
    eta2 = ev.a.op("mul", [eta, eta], loc)
    k = ev.a.op("mad", [ev.a.op("mad", [d.neg(), d, ev.a.const(1.0)], loc).neg(), eta2,
                        ev.a.const(1.0)], loc)
    scale = ev.a.op("mad", [eta, d, _sqrt(ev, [ev.a.op("max", [k, ev.a.const(0.0)], loc)],
                                          loc)[0]], loc)
    bent = ev.a.lanes("mul", [[scale] * m, n], loc)
    r = ev.a.lanes("mad", [[eta] * m, i, [x.neg() for x in bent]], loc)
    reflected = _negative(ev, [k], loc)
    return Value(_float(args[0]), ev.a.select(reflected, _consts(ev, 0.0, m), r, loc))


def _out(ev: Any, trees: list[Any], k: int, value: Value) -> None:
    store(ev, trees[k], lambda current: ev.a.convert(value, current.type, ev.at(trees[k])))


def _lit(ev: Any, args: list[Value], loc: Location) -> Value:
    ndl, ndh, m = (a.comps[0] for a in args)
    if ev.ctx.target.has("lit"):
        # vertex shaders have the instruction (1 slot in vs_1_1, 3 after; fxc's vertex code
        # uses it: `lit r2, r1.xxww` in Unity's compiled vs_2_0 standard shader), where the
        # spelled-out form takes a log and an exp of 10 slots each in vs_1_1. It differs only
        # in clamping the power to +-127.9961
        # in the power clamp to +-127.9961. The diffuse term stays max(n.l, 0): where the
        # specular term is not read the lit goes unused (one max, not a lit and its operand's
        # movs); where it is, codegen reads the lit's .y for it (fusion.share_lit_diffuse)
        lit = split(ev.a.op("lit", [ev.g.pack([ndl, ndh, m, m])], loc))
        one = ev.a.const(1.0)
        return Value(vector("float", 4), [one, ev.a.op("max", [ndl, ev.a.const(0.0)], loc),
                                          lit[2], one])
    zero = ev.a.const(0.0)
    diffuse = ev.a.op("max", [ndl, zero], loc)
    both = ev.a.lanes("mul", [ev.a.compare(">", [ndl], [zero], loc), ev.a.compare(">", [ndh], [zero], loc)], loc)
    spec = _pow(ev, [ev.a.op("max", [ndh, zero], loc)], [m], loc)
    spec = ev.a.select(both, spec, [zero], loc)
    one = ev.a.const(1.0)
    return Value(vector("float", 4), [one, diffuse, spec[0], one])


def _any_all(kind: str):
    def f(ev: Any, args: list[Value], loc: Location) -> Value:
        b = ev.a.to_bool(args[0], loc).comps
        acc = b[0]
        for x in b[1:]:
            acc = ev.a.op("max" if kind == "any" else "mul", [acc, x], loc)
        return Value(BOOL, [acc])
    return f


def _derivative(op: str):
    def f(ev: Any, args: list[Value], loc: Location) -> Value:
        if not ev.ctx.target.has(op):
            raise ev.error(f"{ev.ctx.target.name} has no gradient instructions ({op}); "
                           "ddx/ddy need ps_2_a or ps_3_0", loc)
        return Value(_float(args[0]), ev.a.lanes(op, [args[0].comps], loc))
    return f


def _fwidth(ev: Any, args: list[Value], loc: Location) -> Value:
    dx = _derivative("dsx")(ev, args, loc).comps
    dy = _derivative("dsy")(ev, args, loc).comps
    return Value(_float(args[0]), ev.a.lanes("add", [_abs(ev, dx, loc), _abs(ev, dy, loc)], loc))


_TEX_KINDS = {"1D": ("1d", 1), "2D": ("2d", 2), "3D": ("3d", 3), "CUBE": ("cube", 3)}


def _texture(dim: str, variant: str):
    kind, n = _TEX_KINDS[dim]

    def f(ev: Any, args: list[Value], loc: Location) -> Value:
        # tex2D(s, t, ddx, ddy): the DirectX 9 reference's second overload, a texldd
        variant_ = "grad" if variant == "" and len(args) == 4 else variant
        return read(ev, args, loc, variant_)

    def read(ev: Any, args: list[Value], loc: Location, variant: str) -> Value:
        s = args[0]
        if s.type.kind != "sampler" or s.sampler is None:
            raise ev.error(f"X3013: tex{dim}{variant}: the first argument must be a sampler", loc)
        t = ev.ctx.target
        if t.kind == "vs" and not ev.ctx.host_values:   # a state expression is no shader:
            _vertex_read(ev, f"tex{dim}", variant, loc)  # its read is not a constant (X3013)
        width = 4 if variant in ("proj", "bias", "lod") else n
        coord = list(args[1].comps)
        if len(coord) < width:
            raise ev.error(f"X3013: tex{dim}{variant} needs a float{width} coordinate", loc)
        if len(coord) > width:
            ev.warn("X3206: implicit truncation of vector type", loc)
        coord = coord[:width]
        op = {"": "tex", "proj": "texldp", "bias": "texldb", "lod": "texldl", "grad": "texldd"}[variant]
        if op != "tex" and not t.has(op):
            raise ev.error(f"{t.name} has no {op} (tex{dim}{variant})", loc)
        extra: tuple[Operand, ...] = ()
        if variant == "grad":
            extra = (ev.g.pack((args[2].comps + [ev.a.const(0.0)] * 4)[:4]),
                     ev.g.pack((args[3].comps + [ev.a.const(0.0)] * 4)[:4]))
        ev.ctx.samplers_used.setdefault(s.sampler, kind)
        r = ev.g.leaf(op, (s.sampler, kind), 4, loc, (ev.g.pack(coord),) + extra)
        return Value(vector("float", 4), split(r))
    return f


# fxc's vertex shader code generator has only texldl (vs_3_0) for a texture read: any other
# read is "cannot map expression to vertex shader instruction set" (X4532, fxc 9.29 for
# tex1D in a vs_3_0 function: the DirectX SDK's Skinning10 sample compiled for vs_3_0). A read
# whose level comes from the pixel's derivatives (tex2D, tex2Dbias, tex2Dproj; texld, texldb,
# texldp) or from gradients (tex2Dgrad: texldd) is refused by every vertex target: a language
# error; tex2Dlod only by the vertex targets before vs_3_0.
_VERTEX_READS = {"lod": "texldl"}


def _vertex_read(ev: Any, family: str, variant: str, loc: Location) -> None:
    """Refuse a texture read (`family` tex2D ..., `variant` '', 'lod' ...) that the vertex
    target `ev.ctx.target` cannot make."""
    t = ev.ctx.target
    call = family + variant
    prefix = "X4532: cannot map expression to vertex shader instruction set"
    if variant not in _VERTEX_READS:
        raise ev.error(f"{prefix}: {call} needs a pixel shader (the level of its read comes "
                       f"from {'gradients' if variant == 'grad' else 'derivatives'} between "
                       f"pixels); a vertex shader reads a level it names with {family}lod "
                       f"(texldl, vs_3_0)", loc, language=True)
    if not t.has(_VERTEX_READS[variant]):
        raise ev.error(f"{prefix}: {t.name} cannot sample textures ({call}: vertex texture "
                       f"fetch needs vs_3_0)", loc)


# The later fxc's texture methods on shader models 2-3 (d3dcompiler_43/47 for ps_2_0-ps_3_0,
# vs_3_0): each the DX9 read it stands for, by name -> (the tex* variant, arguments besides
# the sampler and the coordinate). The texture and the sampler become one sampler register,
# named `Sampler+Texture` as vkd3d-shader names the combined sampler it makes for shader model
# 1-3 (`lower_separate_samples`, vkd3d's combined-samplers shader test records
# native d3dcompiler's placement); compiler._sampler_registers places it.
_METHODS = {"Sample": ("", 0), "SampleBias": ("bias", 1), "SampleLevel": ("lod", 1),
            "SampleGrad": ("grad", 2)}
# The methods only shader model 4 has (the "Texture2D" object's method list): no read of a
# shader model 1-3 register does what they do
_SM4_METHODS = frozenset({"Load", "Gather", "GatherRed", "GatherGreen", "GatherBlue",
                          "GatherAlpha", "SampleCmp", "SampleCmpLevelZero", "GetDimensions",
                          "CalculateLevelOfDetail", "CalculateLevelOfDetailUnclamped"})
_KIND_DIMS = {"1d": "1D", "2d": "2D", "3d": "3D", "cube": "CUBE"}


def texture_method(ev: Any, obj: Value, method: str, args: list[Value], where: Any) -> Value:
    """`Tex.Sample(S, uv)`, `SampleBias(S, uv, b)`, `SampleLevel(S, uv, lod)`,
    `SampleGrad(S, uv, dx, dy)` as the DX9 reads they are: `texld`, `texldb` and `texldl` with
    the bias or level in .w, `texldd`, through the sampler register of the pair (S, Tex)."""
    loc = ev.at(where)
    if obj.type.kind != "texture":
        raise ev.error(f"X3018: invalid subscript '{method}': only a texture object "
                       f"(Texture2D ...) has methods, not '{obj.type}'", where)
    if obj.sampler is None:
        # an element of a texture array has no register of its own to pair with a sampler
        # on shader models 1-3 (vkd3d leaves it unimplemented for them too)
        raise ev.error(f"'{method}' of an element of a texture array: shader models 1-3 pair "
                       f"a sampler with a texture declared on its own (Texture2D T;)", where)
    target = ev.ctx.target.name
    if method in ("Sample", "SampleBias", "SampleGrad") and ev.ctx.target.kind == "vs" \
            and not ev.ctx.host_values:
        # implicit derivatives exist only between pixels (shader model 4 allows Sample in
        # pixel shaders only); a vertex shader names its level: every vertex target refuses
        raise ev.error(f"X4532: cannot map expression to vertex shader instruction set: "
                       f"'{obj.sampler}.{method}' needs a pixel shader's derivatives; a "
                       f"{target} reads a level with SampleLevel (texldl)", where, language=True)
    if method in _SM4_METHODS:
        raise ev.error(f"'{obj.sampler}.{method}' needs shader model 4 (vs_4_0/ps_4_0): "
                       f"{target} has no instruction for it (the texture methods shader "
                       f"models 2-3 have are {', '.join(_METHODS)})", where)
    row = _METHODS.get(method)
    if row is None:
        raise ev.error(f"X3018: invalid subscript '{method}' (a texture's methods are "
                       f"{', '.join(_METHODS)})", where)
    variant, extra = row
    if len(args) == 3 + extra and variant != "grad" or len(args) > 3 + extra:
        raise ev.error(f"'{obj.sampler}.{method}' with a texel offset needs shader model 4 "
                       f"(vs_4_0/ps_4_0): {target} samples without offsets", where)
    if len(args) != 2 + extra:
        raise ev.error(f"X3013: '{method}': no matching {len(args)} parameter method", where)
    s = args[0]
    if s.type.kind != "sampler" or s.sampler is None:
        raise ev.error(f"X3013: '{method}': the first argument must be a sampler "
                       f"(SamplerState or sampler)", where)
    kind = obj.type.base or s.type.base or "2d"
    dim = _KIND_DIMS[kind]
    pair = Value(HType("sampler", kind), sampler=f"{s.sampler}+{obj.sampler}")
    coord = args[1]
    if variant in ("bias", "lod"):
        # the bias or level rides in the coordinate's .w (texldb, texldl)
        n = _TEX_KINDS[dim][1]
        lanes = list(coord.comps[:n])
        if len(lanes) < n:
            raise ev.error(f"X3013: '{method}' needs a float{n} coordinate", where)
        amount = args[2].comps[:1]
        lanes += [ev.a.const(0.0)] * (3 - n) + amount
        coord = Value(vector("float", 4), lanes)
        return _element(ev, obj, _texture(dim, variant)(ev, [pair, coord], loc))
    return _element(ev, obj, _texture(dim, variant)(ev, [pair, coord, *args[2:]], loc))


def _element(ev: Any, texture: Value, read: Value) -> Value:
    """A read of a `Texture2D<float2>` is its element type: the sample's first components
    (as the later fxc typed it); a texture declared without one returns the float4."""
    from effects.frontend.types import texture_element
    p = ev.ctx.effect.parameter(texture.sampler)
    element = texture_element(p.type) if p is not None else None
    t = builtin(element.spelling) if element is not None else None
    if t is None:
        return read
    return Value(t, read.comps[:element.rows * element.cols])


def _clip(ev: Any, args: list[Value], loc: Location) -> Value:
    ev.kill(list(args[0].comps), loc)
    return Value(HType("void"))


def _ubyte4(ev: Any, args: list[Value], loc: Location) -> Value:
    """x.zyxw * 255.001953, as fxc compiled it for shader models 1-3: one `mul r, x.zyxw, c.x`,
    no truncation (its reference page: it "swizzles and scales"; DXC's tests of the intrinsic:
    "no rounding is applied"). The int4 holds whole numbers for what a D3DCOLOR stream gives
    (k / 255 scales to k + k / 130560, under 0.002 above k: a0's floor (vs_1_1 mov) and
    round (mova) both give k), and the scale's fraction otherwise, as fxc's code did."""
    c = args[0].comps
    swz = [c[2], c[1], c[0], c[3]]
    return Value(vector("int", 4), _scale(ev, swz, 255.001953, loc))


def _frexp(ev: Any, args: list[Value], loc: Location, trees: list[Any]) -> Value:
    """frexp(x, out e): x = m * 2^e with |m| in [0.5, 1), e = floor(log2|x|) + 1 (log and
    exp as the target has them); 0 gives m = e = 0 (the DirectX 9 reference's frexp)."""
    c = args[0].comps
    e = ev.a.lanes("add", [ev.a.floor(_log2(ev, _abs(ev, c, loc), loc), loc),
                           [ev.a.const(1.0)] * len(c)], loc)
    m = ev.a.lanes("mul", [c, _exp2(ev, [x.neg() for x in e], loc)], loc)
    zero = ev.a.compare("==", c, [ev.a.const(0.0)] * len(c), loc)
    nothing = [ev.a.const(0.0)] * len(c)
    t = _float(args[0])
    _out(ev, trees, 1, Value(t, ev.a.select(zero, nothing, e, loc)))
    return Value(t, ev.a.select(zero, nothing, m, loc))


def _modf(ev: Any, args: list[Value], loc: Location, trees: list[Any]) -> Value:
    c = args[0].comps
    ip = ev.a.trunc(c, loc)
    _out(ev, trees, 1, Value(args[0].type, ip))
    return Value(args[0].type, ev.a.lanes("add", [c, [x.neg() for x in ip]], loc))


def _sincos(ev: Any, args: list[Value], loc: Location, trees: list[Any]) -> Value:
    s, c = _sincos_parts(ev, args[0].comps, loc)
    _out(ev, trees, 1, Value(_float(args[0]), s))
    _out(ev, trees, 2, Value(_float(args[0]), c))
    return Value(HType("void"))


def _mad(ev: Any, args: list[Value], loc: Location) -> Value:
    """mad(m, a, b) = m * a + b per component, at the shape _shaped_args gave the three."""
    m, a, b = args
    t = m.type if m.type.size >= a.type.size else a.type
    n = t.size
    ext = lambda v: v.comps * n if len(v.comps) == 1 else v.comps[:n]
    return Value(t, ev.a.lanes("mad", [ext(m), ext(a), ext(b)], loc))


def _dst(ev: Any, args: list[Value], loc: Location) -> Value:
    """dst(a, b) = (1, a.y * b.y, a.z, b.w): the distance vector of the DirectX 9 `dst`
    instruction (vs has it; elsewhere its three moves and one multiply)."""
    a, b = args[0].comps, args[1].comps
    if ev.ctx.target.has("dst"):
        return Value(vector("float", 4),
                     split(ev.a.op("dst", [ev.g.pack(a), ev.g.pack(b)], loc)))
    yy = ev.a.op("mul", [a[1], b[1]], loc, 1)
    return Value(vector("float", 4), [ev.a.const(1.0), yy, a[2], b[3]])


# The largest float32: a number past it is an infinity. isnan/isinf/isfinite compare with it
# and with 0 by cmp (or sge), whose test fails for a NaN (`NaN >= 0` is false), so a NaN
# takes each comparison's "false" side; x - x or x * 0 would fold to 0 in the DAG.
_FLT_MAX = 3.4028234663852886e38


def _finite_test(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    """1 where |x| <= FLT_MAX (a NaN fails the test: 0)."""
    room = ev.a.lanes("add", [[ev.a.const(_FLT_MAX)] * len(c), [x.neg() for x in _abs(ev, c, loc)]], loc)
    return _ge_zero(ev, room, loc)


def _ge_zero(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    """1 where x >= 0, 0 where not (a NaN included)."""
    one, zero = [ev.a.const(1.0)] * len(c), [ev.a.const(0.0)] * len(c)
    if ev.ctx.target.has("cmp"):
        return ev.a.lanes("cmp", [c, one, zero], loc)
    return ev.a.lanes("sge", [c, zero], loc)


def _is_nan(ev: Any, c: list[Operand], loc: Location) -> list[Operand]:
    """1 - max(x >= 0, -x >= 0): every number passes one of the two tests, a NaN neither."""
    some = ev.a.lanes("max", [_ge_zero(ev, c, loc), _ge_zero(ev, [x.neg() for x in c], loc)], loc)
    return ev.a.logical_not(some, loc)


def _classify(kind: str):
    def f(ev: Any, args: list[Value], loc: Location) -> Value:
        c = args[0].comps
        if kind == "isnan":
            out = _is_nan(ev, c, loc)
        elif kind == "isfinite":
            out = _finite_test(ev, c, loc)
        else:   # isinf: neither finite nor a NaN
            out = ev.a.lanes("add", [ev.a.logical_not(_finite_test(ev, c, loc), loc),
                                     [x.neg() for x in _is_nan(ev, c, loc)]], loc)
        return Value(args[0].type.with_base("bool"), out)
    return f


def _saturate(ev: Any, args: list[Value], loc: Location) -> Value:
    return Value(_float(args[0]), ev.a.saturate(args[0].comps, loc))


LN2, LOG2E, LOG10_2 = math.log(2.0), math.log2(math.e), math.log10(2.0)

# name -> (argument counts, builder(ev, args, loc) or (ev, args, loc, trees) when it writes
# an out argument)
INTRINSICS: dict[str, tuple[tuple[int, ...], Callable[..., Value], bool]] = {
    "abs": ((1,), _unary(_abs), False),
    "sqrt": ((1,), _unary(_sqrt), False),
    "rsqrt": ((1,), _unary(_rsq), False),
    # rcp and mad: the DirectX HLSL reference lists them from shader model 5 (their own
    # instructions there); issue 30's fxc-checked set compiles them for SM2/3 as rcp and mad
    "rcp": ((1,), _unary(lambda ev, c, loc: ev.a.scalar_lanes("rcp", [c], loc)), False),
    "mad": ((3,), _mad, False),
    "dst": ((2,), _dst, False),
    "isnan": ((1,), _classify("isnan"), False),
    "isinf": ((1,), _classify("isinf"), False),
    "isfinite": ((1,), _classify("isfinite"), False),
    "exp2": ((1,), _unary(_exp2), False),
    "exp": ((1,), _unary(lambda ev, c, loc: _exp2(ev, _scale(ev, c, LOG2E, loc), loc)), False),
    "log2": ((1,), _unary(_log2), False),
    "log": ((1,), _unary(lambda ev, c, loc: _scale(ev, _log2(ev, c, loc), LN2, loc)), False),
    "log10": ((1,), _unary(lambda ev, c, loc: _scale(ev, _log2(ev, c, loc), LOG10_2, loc)), False),
    "frac": ((1,), _unary(lambda ev, c, loc: ev.a.frc(c, loc)), False),
    "floor": ((1,), _unary(_floor), False),
    "ceil": ((1,), _unary(_ceil), False),
    "round": ((1,), _unary(_round), False),
    "trunc": ((1,), _unary(lambda ev, c, loc: ev.a.trunc(c, loc)), False),
    "sign": ((1,), _unary(_sign), False),
    "saturate": ((1,), _saturate, False),
    "degrees": ((1,), _unary(lambda ev, c, loc: _scale(ev, c, 180 / math.pi, loc)), False),
    "radians": ((1,), _unary(lambda ev, c, loc: _scale(ev, c, math.pi / 180, loc)), False),
    "pow": ((2,), _binary(_pow), False),
    "min": ((2,), _binary(lambda ev, a, b, loc: ev.a.lanes("min", [a, b], loc)), False),
    "max": ((2,), _binary(lambda ev, a, b, loc: ev.a.lanes("max", [a, b], loc)), False),
    "fmod": ((2,), _binary(lambda ev, a, b, loc: ev.a.fmod(a, b, loc)), False),
    "ldexp": ((2,), _binary(lambda ev, a, b, loc: ev.a.lanes("mul", [a, _exp2(ev, b, loc)], loc)), False),
    "clamp": ((3,), _clamp, False),
    "lerp": ((3,), _lerp, False),
    "step": ((2,), _step, False),
    "smoothstep": ((3,), _smoothstep, False),
    "dot": ((2,), _dot, False),
    "length": ((1,), _length, False),
    "distance": ((2,), _distance, False),
    "normalize": ((1,), _normalize, False),
    "cross": ((2,), _cross, False),
    "reflect": ((2,), _reflect, False),
    "mul": ((2,), _mul, False),
    "transpose": ((1,), _transpose, False),
    "determinant": ((1,), _determinant, False),
    "sin": ((1,), _sin, False),
    "cos": ((1,), _cos, False),
    "tan": ((1,), _tan, False),
    "asin": ((1,), _unary(_asin), False),
    "acos": ((1,), _unary(_acos), False),
    "atan": ((1,), _unary(_atan), False),
    "atan2": ((2,), _binary(_atan2), False),
    "sinh": ((1,), _unary(_sinh), False),
    "cosh": ((1,), _unary(_cosh), False),
    "tanh": ((1,), _unary(_tanh), False),
    "faceforward": ((3,), _faceforward, False),
    "refract": ((3,), _refract, False),
    "sincos": ((3,), _sincos, True),
    "modf": ((2,), _modf, True),
    "frexp": ((2,), _frexp, True),
    "lit": ((3,), _lit, False),
    "any": ((1,), _any_all("any"), False),
    "all": ((1,), _any_all("all"), False),
    "ddx": ((1,), _derivative("dsx"), False),
    "ddy": ((1,), _derivative("dsy"), False),
    "fwidth": ((1,), _fwidth, False),
    "clip": ((1,), _clip, False),
    "D3DCOLORtoUBYTE4": ((1,), _ubyte4, False),
    **{f"tex{dim}{variant}": ((4,) if variant == "grad" else (2, 4) if variant == "" else (2,),
                              _texture(dim, variant), False)
       for dim in _TEX_KINDS for variant in ("", "proj", "bias", "lod", "grad")},
}


# Arguments brought to one shape before the builder sees them (fxc's rule for intrinsics
# taking "the same type": a scalar spreads, a longer vector truncates with X3206): how many
# of the leading arguments share it. And the vector size an intrinsic takes.
_SAME_SHAPE = {"mad": 3, "lerp": 3, "clamp": 3, "smoothstep": 3, "faceforward": 3, "reflect": 2,
               "refract": 2, "distance": 2, "dot": 2, "step": 2}
_SIZE = {"cross": 3, "D3DCOLORtoUBYTE4": 4, "dst": 4}


def _shaped_args(ev: Any, name: str, args: list[Value], loc: Location) -> list[Value]:
    """`args` checked and shaped as the builder of `name` reads them (X3013 otherwise)."""
    first = 1 if name.startswith("tex") else 0
    for a in args[first:]:
        if not a.type.numeric:
            raise ev.error(f"X3013: '{name}': no matching intrinsic function for an argument "
                           f"of type '{a.type}' (numbers are needed)", loc)
    k = _SAME_SHAPE.get(name, 0)
    if k:
        head = args[:k]
        kinds = {a.type.kind for a in head if a.type.size > 1}
        if "matrix" in kinds and len({a.type for a in head if a.type.size > 1}) > 1:
            raise ev.error(f"X3013: '{name}': its arguments need one shape, not "
                           f"{', '.join(str(a.type) for a in head)}", loc)
        if "matrix" not in kinds:
            sizes = [a.type.size for a in head if a.type.size > 1]
            n = min(sizes) if sizes else 1
            if any(size != n for size in sizes):
                ev.warn("X3206: implicit truncation of vector type", loc)
            head = [Value(vector(a.type.base, n), a.comps * n if a.type.size == 1 else a.comps[:n])
                    for a in head]
            args = head + args[k:]
    size = _SIZE.get(name)
    if size is not None:
        out = []
        for a in args:
            if a.type.size != 1 and a.type.size < size:
                raise ev.error(f"X3013: '{name}' takes float{size} arguments, not '{a.type}'", loc)
            if a.type.size > size:
                ev.warn("X3206: implicit truncation of vector type", loc)
            comps = a.comps * size if a.type.size == 1 else a.comps[:size]
            out.append(Value(vector(a.type.base, size), comps))
        args = out
    return args


def _sampler_kind(ev: Any, name: str, args: list[Value], where: Any) -> None:
    """tex2D of a samplerCUBE (or any texture read of a sampler declared for another kind) is
    no overload fxc has (X3013); an untyped `sampler` reads as any kind."""
    kind = _TEX_KINDS.get(name[3:].replace("proj", "").replace("bias", "").replace("lod", "")
                          .replace("grad", ""))
    s = args[0] if args else None
    if kind is None or s is None or s.sampler is None:
        return
    param = ev.ctx.effect.parameter(s.sampler.split("[", 1)[0])
    dim = param.type.dim if param is not None and param.type.base == "sampler" else ""
    if dim and _TEX_KINDS.get(dim, kind) != kind:
        raise ev.error(f"X3013: '{name}': no matching intrinsic function for '{s.sampler}', "
                       f"a sampler{dim}", where)


def call_intrinsic(ev: Any, name: str, args: list[Value], trees: list[Any], where: Any) -> Value:
    counts, build, writes = INTRINSICS[name]
    loc = ev.at(where)
    _sampler_kind(ev, name, args, where)
    if len(args) not in counts:
        raise ev.error(f"X3013: '{name}': no matching {len(args)} parameter intrinsic function", where)
    args = _shaped_args(ev, name, args, loc)
    return build(ev, args, loc, trees) if writes else build(ev, args, loc)
