"""Value-level arithmetic for the target: conversions, operators, comparisons and selects.

Each helper builds the DAG nodes the target has instructions for: a comparison is `cmp` on a
difference in pixel shaders and `slt`/`sge` in vertex shaders, an ordering of one channel on
ps_1_1-1_3 (every ordering on ps_1_1) is `cnd` (a > b: a - (b - 0.5) > 0.5); a select (the flattened `if`,
`?:`) is `cmp` where the target has it, `lrp` where it has that, else `mad`; saturate is a
`_sat` move, or min/max where the version has no `_sat` (vs_1_1, vs_2_0).
"""
from __future__ import annotations

from typing import Any, Callable

from effects.base.errors import Location
from effects.shaders.hlsl.context import Context
from effects.shaders.hlsl.dag import Operand, can_fold, complement_of, fold
from effects.shaders.hlsl.folding import bitwise, truncate
from effects.shaders.hlsl.values import Value, component, split
from effects.shaders.hlsl.types import HType, common_base, shape_of, vector


_COMPARISONS = frozenset(("<", ">", "<=", ">=", "==", "!="))
_BITWISE = frozenset(("&", "|", "^", "<<", ">>"))
# the bases a bitwise operator takes (fxc's X3082, "int or unsigned int type required"; a bool
# is 0 or 1 there)
INTEGRAL = frozenset(("int", "uint", "bool"))


class Arith:
    def __init__(self, ctx: Context, error: Callable[[str, Any], Exception],
                 warn: Callable[[str, Location], None]) -> None:
        self.ctx = ctx
        self.g = ctx.graph
        self.error = error
        self.warn = warn

    # -- building blocks -------------------------------------------------------------------
    def const(self, *values: float) -> Operand:
        return self.g.const(tuple(values))

    def op(self, name: str, args: list[Operand], loc: Location, width: int | None = None) -> Operand:
        return self.g.op(name, args, width, loc)

    def lanes(self, name: str, comps_list: list[list[Operand]], loc: Location) -> list[Operand]:
        """A component-wise op over equally long component lists, as one vector node a group
        of four (a register's width: a float3x3's nine are three nodes), folded at once when
        every component is a constant (the node Graph.op would fold to)."""
        n = max(len(c) for c in comps_list)
        if n > 4:
            out: list[Operand] = []
            for k in range(0, n, 4):
                out += self.lanes(name, [c[k:k + 4] if len(c) > 1 else c for c in comps_list],
                                  loc)
            return out
        values = []
        for comps in comps_list:
            lanes = []
            for c in comps:
                v = c.node.value
                if v is None or len(c.swizzle) != 1:
                    break
                x = v[c.swizzle[0]]
                lanes.append(-x if c.negate else x)
            else:
                values.append(tuple(lanes))
                continue
            break
        else:
            if can_fold(name):
                width = max(len(v) for v in values)
                return split(self.g.const(tuple(fold(name, values, width)), loc))
        ops = [self.g.pack(comps) for comps in comps_list]
        return split(self.op(name, ops, loc))

    def scalar_lanes(self, name: str, comps_list: list[list[Operand]], loc: Location) -> list[Operand]:
        """A scalar-only instruction (rcp, rsq, exp, log, pow): one node per component."""
        n = len(comps_list[0])
        return [self.op(name, [c[i] for c in comps_list], loc, 1) for i in range(n)]

    # -- conversions ------------------------------------------------------------------------
    def convert(self, v: Value, t: HType, loc: Location, explicit: bool = False) -> Value:
        if v.type == t and v.type.row_major == t.row_major:
            return v
        if not t.numeric or not v.type.numeric:
            if t.kind == v.type.kind and t.name == v.type.name and t.kind in ("struct", "sampler", "texture", "array"):
                return v
            raise self.error(f"X3017: cannot {'convert' if explicit else 'implicitly convert'} "
                             f"from '{v.type}' to '{t}'", loc)
        comps = v.comps
        if len(comps) == 1 and t.size > 1:
            comps = comps * t.size
        elif len(comps) != t.size:
            if v.type.kind == "matrix" and t.kind == "matrix" and v.type.rows >= t.rows \
                    and v.type.cols >= t.cols:
                comps = [comps[i * v.type.cols + j] for i in range(t.rows) for j in range(t.cols)]
            elif len(comps) > t.size and t.kind != "matrix" and v.type.kind != "matrix":
                comps = comps[:t.size]
            elif len(comps) > t.size and t.size == 1:
                comps = comps[:1]
            elif len(comps) > t.size and 1 in (v.type.rows, v.type.cols) and \
                    (t.kind != "matrix" or 1 in (t.rows, t.cols)):
                # a 1xN or Nx1 matrix is a vector here: its first numbers (vkd3d's
                # implicit_compatible_data_types, checked against native d3dcompiler)
                comps = comps[:t.size]
            else:
                raise self.error(f"X3017: cannot {'convert' if explicit else 'implicitly convert'}"
                                 f" from '{v.type}' to '{t}'", loc)
            if not explicit:
                self.warn("X3206: implicit truncation of vector type", loc)
        comps = self.convert_base(comps, v.type.base, t.base, loc)
        return Value(t, comps)

    def convert_base(self, comps: list[Operand], src: str, dst: str, loc: Location) -> list[Operand]:
        if dst == "bool" and src != "bool":
            return self.compare("!=", comps, [self.const(0.0)] * len(comps), loc)
        if dst in ("int", "uint") and src not in ("int", "uint", "bool"):
            return self.trunc(comps, loc)
        return comps

    def trunc(self, comps: list[Operand], loc: Location) -> list[Operand]:
        # toward zero: x - frc(x) is floor; negative non-integers add one back
        fl = self.floor(comps, loc)
        if all(c.const_values() is not None for c in fl):
            return [self.const(truncate(c.const_values()[0])) for c in comps]  # type: ignore[index]
        neg = self.compare("<", comps, [self.const(0.0)] * len(comps), loc)
        frac = self.frc(comps, loc)
        nonint = self.compare("!=", frac, [self.const(0.0)] * len(comps), loc)
        fix = self.lanes("mul", [neg, nonint], loc)
        return self.lanes("add", [fl, fix], loc)

    def floor(self, comps: list[Operand], loc: Location) -> list[Operand]:
        return self.lanes("add", [comps, [c.neg() for c in self.frc(comps, loc)]], loc)

    def frc(self, comps: list[Operand], loc: Location) -> list[Operand]:
        if self.ctx.target.name == "vs_1_1":
            # vs_1_1's frc macro writes .y or .xy only: one component at a time in .y
            out = []
            for c in comps:
                r = self.op("frc", [Operand(c.node, (c.swizzle[0],) * 2, c.negate)], loc, 2)
                out.append(component(r, 1))
            return out
        return self.lanes("frc", [comps], loc)

    # -- operators --------------------------------------------------------------------------
    def broadcast(self, a: Value, b: Value, loc: Location, what: str) -> tuple[list[Operand], list[Operand], HType]:
        """Both operands at a common shape (a scalar spreads; longer vectors truncate, X3206)."""
        ta, tb = a.type, b.type
        if not ta.numeric or not tb.numeric:
            raise self.error(f"X3020: type mismatch: '{what}' needs numeric operands, not "
                             f"'{ta}' and '{tb}'", loc)
        base = common_base(ta.base, tb.base)
        if ta.size == 1 and tb.size > 1:
            return a.comps * tb.size, b.comps, tb.with_base(base)
        if tb.size == 1 and ta.size > 1:
            return a.comps, b.comps * ta.size, ta.with_base(base)
        if ta.kind == tb.kind == "matrix":
            rows, cols = min(ta.rows, tb.rows), min(ta.cols, tb.cols)
            if (rows, cols) != (ta.rows, ta.cols) or (rows, cols) != (tb.rows, tb.cols):
                self.warn("X3206: implicit truncation of vector type", loc)
            t = shape_of(rows, cols, base)
            pick = lambda v, tt: [v.comps[i * tt.cols + j] for i in range(rows) for j in range(cols)]
            return pick(a, ta), pick(b, tb), t
        if ta.kind == "matrix" or tb.kind == "matrix":
            if ta.size != tb.size:
                raise self.error(f"X3020: type mismatch between '{ta}' and '{tb}'", loc)
            return a.comps, b.comps, (ta if ta.kind == "matrix" else tb).with_base(base)
        n = min(ta.size, tb.size)
        if ta.size != tb.size:
            self.warn("X3206: implicit truncation of vector type", loc)
        return a.comps[:n], b.comps[:n], vector(base, n)

    def binary(self, opname: str, a: Value, b: Value, loc: Location) -> Value:
        if opname not in _COMPARISONS and not (a.type.numeric and b.type.numeric):
            # fxc: arithmetic on a struct or an object is X3022 (a comparison X3020, as
            # broadcast says); DXC's tests record the text
            shown = a.type if not a.type.numeric else b.type
            raise self.error(f"X3022: scalar, vector, or matrix expected ('{opname}' on "
                             f"'{shown}')", loc)
        if opname in _BITWISE and not {a.type.base, b.type.base} <= INTEGRAL:
            shown = a.type if a.type.base not in INTEGRAL else b.type
            raise self.error(f"X3082: int or unsigned int type required ('{opname}' on "
                             f"'{shown}')", loc)
        if opname in ("&&", "||"):
            ca, cb, t = self.broadcast(self.to_bool(a, loc), self.to_bool(b, loc), loc, opname)
            if opname == "&&" and self.ctx.target.has("cmp"):
                # `a && b` as `b ? a : 0`: a compare made b selects on its difference, one cmp
                # where the flag and a mul were two (dxwrapper's ColorKeyPixelShader: fxc
                # `cmp r1.xyz, r2, r1, c2.y` for `tex >= low && tex <= high`)
                comps = self.select(cb, ca, [self.const(0.0)] * len(ca), loc)
            else:
                comps = self.lanes("mul" if opname == "&&" else "max", [ca, cb], loc)
            return Value(t.with_base("bool"), comps)
        ca, cb, t = self.broadcast(a, b, loc, opname)
        if opname in ("<", ">", "<=", ">=", "==", "!="):
            return Value(t.with_base("bool"), self.compare(opname, ca, cb, loc))
        if t.base == "bool":
            t = t.with_base("int")
        if opname == "+":
            comps = self.lanes("add", [ca, cb], loc)
        elif opname == "-":
            comps = self.lanes("add", [ca, [c.neg() for c in cb]], loc)
        elif opname == "*":
            comps = self.lanes("mul", [ca, cb], loc)
        elif opname == "/":
            self._int_divisor(opname, t, cb, loc)
            comps = self.divide(ca, cb, loc)
            if t.base in ("int", "uint"):
                comps = self.trunc(comps, loc)
        elif opname == "%":
            self._int_divisor(opname, t, cb, loc)
            comps = self.fmod(ca, cb, loc)
        elif opname in ("&", "|", "^", "<<", ">>"):
            comps = self.bitwise(opname, ca, cb, loc, t.base)
        else:
            raise self.error(f"X3000: operator '{opname}' is not supported", loc)
        return Value(t, comps)

    def _int_divisor(self, opname: str, t: HType, cb: list[Operand], loc: Location) -> None:
        """An integer divided by a constant 0 has no value: fxc refuses it (vkd3d-shader's
        tests of fxc, arithmetic-int.shader_test; the X code was not found)."""
        if t.base in ("int", "uint") and any(c.const_values() == (0.0,) for c in cb):
            raise self.error(f"integer division by zero ('{opname}' with a constant 0 divisor)",
                             loc)

    def divide(self, ca: list[Operand], cb: list[Operand], loc: Location) -> list[Operand]:
        if all(c.const_values() is not None for c in cb):
            inv = [self.const(1.0 / c.const_values()[0]) if c.const_values()[0] else
                   self.const(float("inf")) for c in cb]
        else:
            inv = self.scalar_lanes("rcp", [cb], loc)
        return self.lanes("mul", [ca, inv], loc)

    def fmod(self, ca: list[Operand], cb: list[Operand], loc: Location) -> list[Operand]:
        q = self.divide(ca, cb, loc)
        # fxc's fmod: the remainder has the sign of a: b * frc(|a/b|) with a's sign
        aq = self.lanes("abs", [q], loc) if self.ctx.target.has("abs") else \
            self.lanes("max", [q, [c.neg() for c in q]], loc)
        fr = self.frc(aq, loc)
        sgn = self.select(self.compare("<", q, [self.const(0.0)] * len(q), loc),
                          [c.neg() for c in fr], fr, loc)
        return self.lanes("mul", [sgn, cb], loc)

    def bitwise(self, opname: str, ca: list[Operand], cb: list[Operand], loc: Location,
                base: str = "int") -> list[Operand]:
        """Constant operands only (DX9 has no integer hardware), folded by fxc's 32-bit rules
        (folding.bitwise: a shift takes its count's low five bits, results wrap)."""
        out = []
        for x, y in zip(ca, cb):
            vx, vy = x.const_values(), y.const_values()
            if vx is None or vy is None:
                raise self.error(f"X3535: bitwise operation '{opname}' needs integer hardware; "
                                 f"{self.ctx.target.name} has none (only constant operands fold)", loc)
            out.append(self.const(bitwise(opname, vx[0], vy[0], base)))
        return out

    # -- comparisons and selects ------------------------------------------------------------
    def compare(self, opname: str, ca: list[Operand], cb: list[Operand], loc: Location) -> list[Operand]:
        """0/1 per component."""
        if self._by_cnd(opname, ca):
            return self.cnd_compare(opname, ca, cb, loc)
        if self.ctx.target.has("cmp"):
            # cmp d, a, b = d >= 0 ? a : b
            one, zero = [self.const(1.0)] * len(ca), [self.const(0.0)] * len(ca)
            if opname in (">=", "<"):
                d = self.lanes("add", [ca, [c.neg() for c in cb]], loc)
            elif opname in ("<=", ">"):
                d = self.lanes("add", [cb, [c.neg() for c in ca]], loc)
            else:
                diff = self.lanes("add", [ca, [c.neg() for c in cb]], loc)
                d = [c.neg() for c in self.lanes("abs", [diff], loc)] if self.ctx.target.has("abs") \
                    else [c.neg() for c in self.lanes("mul", [diff, diff], loc)]
            t, f = (one, zero) if opname in (">=", "<=", "==") else (zero, one)
            return self.lanes("cmp", [d, t, f], loc)
        if opname == "<":
            return self.lanes("slt", [ca, cb], loc)
        if opname == ">=":
            return self.lanes("sge", [ca, cb], loc)
        if opname == ">":
            return self.lanes("slt", [cb, ca], loc)
        if opname == "<=":
            return self.lanes("sge", [cb, ca], loc)
        ge = self.lanes("sge", [ca, cb], loc)
        le = self.lanes("sge", [cb, ca], loc)
        eq = self.lanes("mul", [ge, le], loc)
        if opname == "==":
            return eq
        return self.lanes("add", [[self.const(1.0)] * len(eq), [c.neg() for c in eq]], loc)

    def _by_cnd(self, opname: str, ca: list[Operand]) -> bool:
        """ps_1_1-1_3 order a comparison by cnd (r0.a > 0.5): ps_1_1 has nothing else, and on
        ps_1_2/1_3 a one-channel comparison is cheaper so than by cmp (two slots there)."""
        rules = self.ctx.target.rules
        return rules.is_ps11_13 and opname in ("<", ">", "<=", ">=") and (
            not self.ctx.target.has("cmp") or len(ca) == 1)

    def cnd_compare(self, opname: str, ca: list[Operand], cb: list[Operand], loc: Location) -> list[Operand]:
        """a > b is (a - (b - 0.5)) > 0.5, cnd's own test (the DX9 docs' `sub r0, v0, v1_bias`
        example); b - 0.5 folds to b_bias, and a comparison with 0.5 itself to cnd on a.
        a <= b is the same cnd with 0 and 1 swapped; < and >= swap the operands."""
        if opname in ("<", ">="):
            ca, cb = cb, ca
        half = [self.const(-0.5)] * len(cb)
        d = self.lanes("add", [ca, [c.neg() for c in self.lanes("add", [cb, half], loc)]], loc)
        one, zero = [self.const(1.0)] * len(ca), [self.const(0.0)] * len(ca)
        t, f = (one, zero) if opname in (">", "<") else (zero, one)
        return self.lanes("cnd", [d, t, f], loc)

    def select(self, cond: list[Operand], a: list[Operand], b: list[Operand], loc: Location,
               unfold: bool = False) -> list[Operand]:
        """cond ? a : b per component, for 0/1 conditions; `unfold`: a flattened `if`'s
        predicate (_unfold_predicate)."""
        out_a, out_b = list(a), list(b)
        if len(cond) == 1 and len(a) > 1:
            cond = cond * len(a)
        consts = [c.const_values() for c in cond]
        if all(v is not None for v in consts):
            return [x if v[0] else y for v, x, y in zip(consts, out_a, out_b)]  # type: ignore[index]
        same = [x.sig() == y.sig() for x, y in zip(out_a, out_b)]
        if all(same):
            return out_a
        if any(same) and len(cond) == len(out_a):
            # select only the components the sides disagree on (`c.rgb = ...` under a
            # condition leaves c.a as it was): fxc's `cmp r1.xyz, ...` writes those lanes
            idx = [i for i, s in enumerate(same) if not s]
            picked = self.select([cond[i] for i in idx], [out_a[i] for i in idx],
                                 [out_b[i] for i in idx], loc, unfold)
            out = list(out_a)
            for i, v in zip(idx, picked):
                out[i] = v
            return out
        node = cond[0].node
        if node.op == "cnd" and all(c.node is node and not c.negate for c in cond):
            # a condition made by cnd_compare is cnd(d, 1, 0) or cnd(d, 0, 1): select on d
            t, f = node.args[1].const_values(), node.args[2].const_values()
            lanes = [c.swizzle[0] for c in cond]
            d = node.args[0].pick(tuple(lanes))
            if t is not None and f is not None and all(t[i] == 1 and f[i] == 0 for i in lanes):
                return split(self.op("cnd", [d, self.g.pack(out_a), self.g.pack(out_b)], loc))
            if t is not None and f is not None and all(t[i] == 0 and f[i] == 1 for i in lanes):
                return split(self.op("cnd", [d, self.g.pack(out_b), self.g.pack(out_a)], loc))
        if self.ctx.target.has("cmp"):
            unfolded = self._unfold_predicate(cond, out_a, out_b, loc) if unfold else None
            if unfolded is not None:
                return unfolded
            # a condition made by compare() is cmp(d, 1, 0) or cmp(d, 0, 1): select on d
            node = cond[0].node
            if all(c.node is node for c in cond) and node.op == "cmp" and not cond[0].negate:
                t, f = node.args[1].const_values(), node.args[2].const_values()
                lanes = [c.swizzle[0] for c in cond]
                d = node.args[0].pick(tuple(lanes))
                if t is not None and f is not None and all(t[i] == 1 and f[i] == 0 for i in lanes):
                    return split(self.op("cmp", [d, self.g.pack(out_a), self.g.pack(out_b)], loc))
                if t is not None and f is not None and all(t[i] == 0 and f[i] == 1 for i in lanes):
                    return split(self.op("cmp", [d, self.g.pack(out_b), self.g.pack(out_a)], loc))
            return self.lanes("cmp", [[c.neg() for c in cond], out_b, out_a], loc)
        if self.ctx.target.has("lrp") and self.ctx.target.kind == "vs":
            return self.lanes("lrp", [cond, out_a, out_b], loc)
        diff = self.lanes("add", [out_a, [c.neg() for c in out_b]], loc)
        return self.lanes("mad", [cond, diff, out_b], loc)

    def _unfold_predicate(self, cond: list[Operand], a: list[Operand], b: list[Operand],
                          loc: Location) -> list[Operand] | None:
        """A flattened `if`'s predicate made of compares, as fxc selects on it: `not c` swaps
        the sides, `p and q` (an else-if's mask) selects twice, the inner select on `q`, so
        each compare feeds its cmp directly and no 0/1 flag or product is computed (Effekseer's
        ApplyTextureBlending chain: fxc `cmp r1.xyz, -r7_abs.z, r2.yzww, r1` per level). Not
        in a loop: there the unroller folds a counter by the break flags (livefold.py), which
        an unfolded select no longer reads."""
        p = cond[0]
        if p.negate or any(c.sig() != p.sig() for c in cond):
            return None
        node = p.node
        if node.width == 1:
            x = complement_of(p)
            if x is not None and self._is_flag(x):
                return self.select([x] * len(cond), b, a, loc, unfold=True)
        if node.op == "mul" and node.width == 1:
            x, y = node.args
            if self._is_flag(x) or self._is_flag(y):
                # each distinct factor once: nested `if`s on one condition multiply its flag
                # by itself, and selecting twice on a compare is selecting once
                factors: dict[Any, Operand] = {}
                for f in self._factors(p):
                    factors.setdefault(f.sig(), f)
                out = a
                for f in reversed(list(factors.values())):
                    out = self.select([f] * len(cond), out, b, loc, unfold=True)
                return out
        if node.op == "max" and node.width == 1 and self._is_flag(p):
            # `p or q` (a function's 'returned' after two returns): the outer select on p,
            # the inner on q, as fxc writes `if (p) return a; if (q) return b; return c;`
            x, y = node.args
            inner = self.select([y] * len(cond), a, b, loc, unfold=True)
            return self.select([x] * len(cond), a, inner, loc, unfold=True)
        return None

    def _factors(self, p: Operand) -> list[Operand]:
        """The factors a predicate's product unfolds into: a one-lane product with a flag
        among its two factors splits into theirs (as selecting on each in turn would), any
        other operand is one factor."""
        node = p.node
        if p.negate or node.op != "mul" or node.width != 1 or \
                not any(self._is_flag(x) for x in node.args):
            return [p]
        return [f for x in node.args for f in self._factors(x)]

    def _is_flag(self, p: Operand) -> bool:
        """A 0/1 scalar that compare() made (cmp(d, 1, 0) or cmp(d, 0, 1)), or `not` of one,
        or a product of them: selects on it unfold into cmps on the compared differences."""
        if p.negate:
            return False
        node = p.node
        if node.op == "cmp":
            t, f = node.args[1].const_values(), node.args[2].const_values()
            return t is not None and f is not None and {t[p.swizzle[0]], f[p.swizzle[0]]} == {0.0, 1.0}
        if node.op == "add" and node.width == 1:
            x = complement_of(p)
            return x is not None and self._is_flag(x)
        if node.op in ("mul", "max") and node.width == 1:
            return all(self._is_flag(x) for x in node.args)
        return False

    def to_bool(self, v: Value, loc: Location) -> Value:
        if not v.type.numeric:
            raise self.error(f"X3020: a condition or logical operand needs a numeric value, not "
                             f"'{v.type}'", loc)
        if v.type.base == "bool":
            return v
        return Value(v.type.with_base("bool"),
                     self.compare("!=", v.comps, [self.const(0.0)] * len(v.comps), loc))

    def logical_not(self, comps: list[Operand], loc: Location) -> list[Operand]:
        return self.lanes("add", [[self.const(1.0)] * len(comps), [c.neg() for c in comps]], loc)

    def saturate(self, comps: list[Operand], loc: Location) -> list[Operand]:
        if self.ctx.target.rules.saturate and self.ctx.target.kind == "ps" or \
                self.ctx.target.name == "vs_3_0":
            return self.lanes("sat", [comps], loc)
        lo = self.lanes("max", [comps, [self.const(0.0)] * len(comps)], loc)
        return self.lanes("min", [lo, [self.const(1.0)] * len(comps)], loc)
