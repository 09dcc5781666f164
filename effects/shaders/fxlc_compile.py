"""A source expression state compiled to a preshader (FXLC), as fxc wrote one into fx_2_0, so
`effects compile X.fx -o X.fxo` keeps `FogDensity = a * 3` and `PixelShader = (PS[i])`.

The HLSL evaluator builds the expression's DAG with the parameters as uniform registers (not
their current values), and each output component is emitted as scalar FXLC instructions
(effects.shaders.fxlc's op table): one temporary component per DAG value and lane, literals in
the CLIT table, the parameters in the constant table in the compiler's register packing.
Operations FXLC lacks are built from those it has (mad: mul and add; lrp; abs: max(x, -x);
saturate: min and max; pow: exp of mul of log; dp3/dp4: mul and add; cnd: cmp). What has no such
form (a texture read, cross, normalize ...) is a located error: the writer refuses the state.
"""
from __future__ import annotations

import struct
from typing import Any

from effects.base.errors import EffectError, Location
from effects.model import Effect, Expression, Preshader
from effects.shaders import fxlc
from effects.shaders.hlsl.ops import OPS, REDUCE

_BY_NAME = {op.name: op for op in fxlc.OPS}


class _Emitter:
    def __init__(self, location: Location) -> None:
        self.location = location
        self.words: list[int] = []
        self.count = 0
        self.literals: list[float] = []
        self.temps = 0
        self.done: dict[tuple[int, int], tuple[int, int]] = {}   # (node, lane) -> (table, offset)

    def literal(self, x: float) -> tuple[int, int]:
        if x not in self.literals:
            self.literals.append(x)
        return fxlc.IMMEDIATE, self.literals.index(x)

    def emit(self, op: str, args: list[tuple[int, int]], out: tuple[int, int] | None = None
             ) -> tuple[int, int]:
        row = _BY_NAME[op]
        if out is None:
            out = (fxlc.TEMP, self.temps)
            self.temps += 1
        self.words += [row.code << 20 | 1, len(args)]
        for table, offset in [*args, out]:
            self.words += [0, table, offset]
        self.count += 1
        return out

    def fail(self, message: str) -> EffectError:
        return EffectError(f"{message}: not written as an FXLC preshader", self.location)


def compile_expression(effect: Effect, value: Expression) -> tuple[bytes, int]:
    """A source expression as preshader bytes (version token, CTAB, CLIT, FXLC, end) and its
    component count. Raises a located EffectError for what FXLC cannot say."""
    from effects.shaders.d3dbc.ctab import ConstantInfo, ConstantTable, write_ctab
    from effects.shaders.d3dbc.writer import _type_info
    from effects.shaders.hlsl.context import Context, Target, type_names
    from effects.shaders.asm.versions import VERSIONS
    from effects.shaders.hlsl.evaluate import Evaluator
    from effects.shaders.hlsl.parse import Origin, parse
    from effects.shaders.hlsl.preshader import _REFERENCE
    from effects.shaders.hlsl.types import register_count
    text = _REFERENCE.sub(lambda m: " " + m.group(1) + " ", value.text)
    origin = Origin(value.location, text)
    tree = parse(text, "initializer", origin, type_names(effect))
    ctx = Context(effect, Target("vs_3_0", VERSIONS["vs_3_0"]), host_values=False)
    try:
        comps = Evaluator(ctx, origin).flatten_list(tree)
    except RecursionError:
        from effects.shaders.hlsl.budget import out_of_stack
        raise out_of_stack(value.location, origin.line_text(1)) from None
    registers, constants, at = {}, [], 0
    for name, t in ctx.uniforms_used.items():
        if t.base not in ("float", "half", "double", "int", "uint", "bool"):
            raise EffectError(f"'{name}' ({t.base}): not written as an FXLC preshader input",
                              value.location)
        registers[name] = at
        count = register_count(t)
        constants.append(ConstantInfo(name, "float4", at, count, _type_info(t, "float")))
        at += count
    e = _Emitter(value.location)
    for k, comp in enumerate(comps):
        source = _value(e, comp.node, comp.swizzle[0], registers)
        if comp.negate:
            source = e.emit("neg", [source])
        e.emit("mov", [source], (fxlc.OUTPUT, k))
    table = ConstantTable(tuple(constants), "tx", 0x46580200)
    literals = e.literals + [0.0] * (-len(e.literals) % 4)
    out = [0x46580200]
    out += _comment(b"CTAB" + write_ctab(table), value.location)
    out += _comment(b"CLIT" + struct.pack(f"<I{len(literals)}d", len(literals), *literals),
                    value.location)
    out += _comment(b"FXLC" + struct.pack(f"<{1 + len(e.words)}I", e.count, *e.words),
                    value.location)
    out.append(0x0000FFFF)
    return struct.pack(f"<{len(out)}I", *out), len(comps)


def _comment(body: bytes, location: Location) -> list[int]:
    body += b"\0" * (-len(body) % 4)
    n = len(body) // 4
    if n > 0x7FFF:
        raise EffectError(f"the expression's preshader needs a comment of {n} words (at most "
                          "32767): not written as an FXLC preshader", location)
    return [0xFFFE | n << 16, *struct.unpack(f"<{n}I", body)]


def _value(e: _Emitter, node: Any, lane: int, registers: dict[str, int]) -> tuple[int, int]:
    """The register holding lane `lane` of `node`, its instructions emitted once."""
    key = (node.id, lane)
    if key in e.done:
        return e.done[key]
    if node.op == "const":
        got = e.literal(float(node.value[lane if lane < len(node.value) else 0]))
    elif node.op == "uniform":
        name, row = node.key
        got = (fxlc.INPUT, 4 * (registers[name] + row) + lane)
    elif node.op in OPS and OPS[node.op].fxlc:
        scalar = OPS[node.op].shape == "scalar"
        args = []
        for a in node.args:
            src = _value(e, a.node, a.swizzle[0 if scalar else min(lane, len(a.swizzle) - 1)],
                         registers)
            args.append(e.emit("neg", [src]) if a.negate else src)
        got = _steps(e, OPS[node.op].fxlc, args)
    elif node.op in REDUCE:
        n = REDUCE[node.op]
        lanes = []
        for a in node.args[:2]:
            regs = [_value(e, a.node, a.swizzle[min(j, len(a.swizzle) - 1)], registers)
                    for j in range(n)]
            lanes.append([e.emit("neg", [r]) if a.negate else r for r in regs])
        got = e.emit("mul", [lanes[0][0], lanes[1][0]])
        for j in range(1, n):
            got = e.emit("add", [got, e.emit("mul", [lanes[0][j], lanes[1][j]])])
        if node.op == "dp2add":
            c = node.args[2]
            src = _value(e, c.node, c.swizzle[0], registers)
            got = e.emit("add", [got, e.emit("neg", [src]) if c.negate else src])
    else:
        raise e.fail(f"'{node.op}'")
    e.done[key] = got
    return got


def _steps(e: _Emitter, steps: tuple, args: list[tuple[int, int]]
           ) -> tuple[int, int]:
    prev: tuple[int, int] | None = None
    for op, operands in steps:
        regs = [prev if x == "prev" else e.literal(x) if isinstance(x, float) else args[x]
                for x in operands]
        prev = e.emit(op, regs)  # type: ignore[arg-type]
    assert prev is not None
    return prev


def preshader_of(effect: Effect, name: str, value: Expression) -> Preshader:
    """The Preshader a binary holds for source expression `value` of state `name`: a shader
    array picked by an expression (`(PS[i])`) as its selector, any other as its value."""
    from effects.shaders.hlsl.preshader import _SHADER_ELEMENT, _SHADER_TYPES
    if name in ("VertexShader", "PixelShader"):
        m = _SHADER_ELEMENT.match(value.text)
        param = effect.parameter(m.group(1)) if m else None
        if m is None or param is None or not param.array or param.type.base not in _SHADER_TYPES:
            raise EffectError(f"{name} = {value.text.strip()[:40]}: not a shader array element",
                              value.location)
        data, n = compile_expression(effect, Expression(m.group(2), value.location))
        return Preshader(value.text, value.location, data, 0, n, param.name)
    data, n = compile_expression(effect, value)
    return Preshader(value.text, value.location, data, 0, n)
