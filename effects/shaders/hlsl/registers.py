"""The constant registers a compiled shader reads, filled from the effect's parameter values.

fxc's packing (the same as `types.register_count`): a scalar or vector takes one register
(padded with zeros), a matrix one register per column (per row when row_major), each array
element and struct member starts a new register. A uniform parameter of the entry point that
no compile argument fixed (`$name`) and a parameter without a value read zero, as in D3DX.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from effects.model import Effect
from effects.shaders.hlsl.types import HType

Row = tuple[float, float, float, float]


def _rows(t: HType, flat: list[float]) -> tuple[list[Row], int]:
    """Registers of a value of type `t` from its numbers in declaration order; also how many
    numbers it consumed."""
    if t.kind in ("scalar", "vector"):
        vals = (flat[:t.size] + [0.0] * 4)[:4]
        return [tuple(vals)], t.size  # type: ignore[list-item]
    if t.kind == "matrix":
        m = np.zeros((t.rows, t.cols))
        got = np.array((flat[:t.size] + [0.0] * t.size)[:t.size]).reshape(t.rows, t.cols)
        m[:, :] = got
        regs = m if t.row_major else m.T
        return [tuple((list(r) + [0.0] * 4)[:4]) for r in regs], t.size  # type: ignore[misc]
    if t.kind == "array" and t.element is not None:
        out: list[Row] = []
        used = 0
        for _ in range(t.length):
            rows, n = _rows(t.element, flat[used:])
            out += rows
            used += n
        return out, used
    if t.kind == "struct":
        out, used = [], 0
        for _, ft, _ in t.fields:
            rows, n = _rows(ft, flat[used:])
            out += rows
            used += n
        return out, used
    return [], 0


def _register_rows(effect: Effect, shader: Any, name: str) -> list[Row]:
    """The registers of uniform `name` of `shader` at the parameters' current values, or
    what its preshader computes from them (none for a parameter without a value, or an entry
    uniform no compile argument fixed)."""
    t = shader.types.get(name)
    if name in shader.preshaders:
        flat = preshader_numbers(effect, shader, shader.preshaders[name])
    else:
        from effects.shaders.hlsl.preshader import parameter_numbers
        flat = parameter_numbers(effect, name) if not name.startswith("$") else None
    return _rows(t, flat)[0] if (t is not None and flat is not None) else []


def preshader_numbers(effect: Effect, shader: Any, preshader: Any) -> list[float]:
    """The value of one of `shader`'s preshaders (preshader.ShaderPreshader) at the
    parameters' current values: its steps folded as the compiler folds constants."""
    from effects.shaders.hlsl.dag import fold
    values: list[tuple[float, ...]] = []
    for step in preshader.steps:
        if step[0] == "const":
            values.append(tuple(step[1]))
        elif step[0] == "uniform":
            _, name, row, width = step
            rows = _register_rows(effect, shader, name)
            values.append(tuple(rows[row][:width]) if row < len(rows) else (0.0,) * width)
        else:
            op, width, args = step
            consts = [tuple(-values[k][i] if negate else values[k][i] for i in swizzle)
                      for k, swizzle, negate in args]
            values.append(tuple(float(v) for v in fold(op, consts, width)))
    return list(values[-1])


def constant_values(effect: Effect, shader: Any) -> dict[int, Row]:
    """c# -> four floats for every uniform register the shader reads, its preshaders' too."""
    out: dict[int, Row] = {}
    for name, (start, count) in shader.constants.items():
        t = shader.types.get(name)
        rows = _register_rows(effect, shader, name)
        if rows and t is not None and t.kind == "scalar" and shader.target.startswith("ps_1"):
            # ps_1_1-1_3 cannot select .x of a register: a scalar is loaded replicated (what
            # D3DX's preshader did for DX8 targets), and codegen_ps1 reads it so
            rows = [(rows[0][0],) * 4]
        for k in range(count):
            out[start + k] = rows[k] if k < len(rows) else (0.0, 0.0, 0.0, 0.0)
    program = getattr(shader, "fxlc", None)
    if program is not None:
        # a bytecode shader's constant preshader: the registers it writes, as D3DX set them
        from effects.shaders.fxlc import run, written_registers
        from effects.shaders.hlsl.preshader import parameter_numbers
        oc = run(program, effect, lambda name: parameter_numbers(effect, name))
        for k in written_registers(program):
            out[k] = tuple(float(x) for x in oc[4 * k:4 * k + 4])  # type: ignore[assignment]
    return out
