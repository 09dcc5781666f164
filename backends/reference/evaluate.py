"""Run an IR program over N vertices or fragments at once with NumPy.

Each instruction's kernel (the `OPS` row in `effects.ir`) runs once over (N, 4) float32 arrays;
there is no per-row Python loop. Texture sampling is delegated to callbacks the caller supplies
(the rasteriser, which knows the 2x2 quads needed for derivatives; tests pass fakes).

A sampler callback is called as `sampler(coord, kind=..., bias=..., lod=...)` with coord an
(N, 4) float32 array, already divided by w for projected reads, and bias / lod an (N,) array or
None; it returns (N, 4) texels. A sampler index with no callback reads (0, 0, 0, 1), as an
unbound ps_2_0 sampler does.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Mapping

import numpy as np

from effects.ir import OPS, IRError, Program

SamplerFn = Callable[..., np.ndarray]
_MISSING_DEFAULT = np.array([0, 0, 0, 1], dtype=np.float32)
_UNBOUND_TEXEL = np.array([0, 0, 0, 1], dtype=np.float32)


@dataclass
class EvalResult:
    """`outputs`: name -> (N, 4) float32. `killed`: (N,) bool for fragment programs that kill,
    else None."""

    outputs: dict[str, np.ndarray]
    killed: np.ndarray | None


class _Context:
    """The KernelContext of effects.ir: inputs padded to vec4, samplers, the kill mask."""

    def __init__(self, program: Program, inputs: Mapping[str, np.ndarray],
                 samplers: Mapping[int, SamplerFn], count: int) -> None:
        self.program = program
        self.inputs = inputs
        self.samplers = samplers
        self.count = count
        self.killed: np.ndarray | None = None

    def input(self, name: str) -> np.ndarray:
        return _as_vec4(name, self.inputs[name], self.count)

    def sample(self, index: int, coord: np.ndarray, kind: str, bias: np.ndarray | None,
               lod: np.ndarray | None) -> np.ndarray:
        fn = self.samplers.get(index)
        if fn is None:
            return np.broadcast_to(_UNBOUND_TEXEL, (self.count, 4))
        texels = np.asarray(fn(coord, kind=kind, bias=bias, lod=lod), dtype=np.float32)
        if texels.shape != (self.count, 4):
            raise IRError(f"sampler {index} returned shape {texels.shape}, "
                          f"expected {(self.count, 4)}")
        return texels

    def kill(self, mask: np.ndarray) -> None:
        self.killed = mask if self.killed is None else self.killed | mask


def _as_vec4(name: str, value: np.ndarray, count: int) -> np.ndarray:
    """(N, k) or (k,) with k <= 4 as (N, 4); missing components read (0, 0, 0, 1)."""
    array = np.asarray(value, dtype=np.float32)
    if array.ndim == 1:
        array = array[None, :]
    if array.ndim != 2 or not 1 <= array.shape[1] <= 4 or array.shape[0] not in (1, count):
        raise IRError(f"input {name}: shape {np.shape(value)} is not (N, k) or (k,) with "
                      f"k <= 4 and N = {count}")
    if array.shape[1] < 4:
        padded = np.repeat(_MISSING_DEFAULT[None, :], array.shape[0], axis=0)
        padded[:, :array.shape[1]] = array
        array = padded
    return _dense(np.broadcast_to(array, (count, 4)))


def _dense(value: np.ndarray) -> np.ndarray:
    """`value` as a C-contiguous float32 array. Broadcast views (uniforms, constants, a
    replicated column) are expanded once, with a cheap repeat: NumPy runs (N, 4) arithmetic
    with a stride-0 operand about five times slower than on dense arrays."""
    array = np.asarray(value, dtype=np.float32)
    if array.flags.c_contiguous or array.ndim != 2:
        return array
    if array.strides[0] == 0:                      # every row the same
        return np.repeat(np.ascontiguousarray(array[:1]), array.shape[0], axis=0)
    if array.strides[1] == 0:                      # one column, replicated
        return np.repeat(np.ascontiguousarray(array[:, :1]), array.shape[1], axis=1)
    return np.ascontiguousarray(array)


# Per-component ops whose result is replicated when every argument is; the costly ones are
# then run on one column (D3D's scalar rsq, rcp, pow, exp, log reach the IR replicated).
_PER_COMPONENT = frozenset({"add", "sub", "mul", "mad", "neg", "min", "max", "rcp", "rsq",
                            "exp2", "log2", "pow", "frc", "abs", "sin", "cos", "cmp", "cnd",
                            "lrp", "slt", "sge", "saturate", "clamp", "quantize"})
_WORTH_ONE_COLUMN = frozenset({"rcp", "rsq", "exp2", "log2", "pow", "sin", "cos"})
_SCALAR_CACHE: dict[int, tuple[Program, frozenset]] = {}


def _scalar_instructions(program: Program) -> frozenset:
    """Indices of the costly per-component instructions whose arguments are all replicated
    (dp3/dp4 results, one-component swizzles, constants with four equal values, and
    per-component results of those)."""
    found = _SCALAR_CACHE.get(id(program))
    if found is not None and found[0] is program:
        return found[1]
    replicated: set[int] = set()
    scalar = set()
    for index, instr in enumerate(program.instrs):
        attrs = instr.attr_map
        if instr.op in ("dp3", "dp4"):
            same = True
        elif instr.op == "swizzle":
            same = len(set(attrs["pattern"])) == 1 or instr.args[0] in replicated
        elif instr.op == "const":
            same = len(set(attrs["value"])) == 1
        elif instr.op in _PER_COMPONENT:
            same = all(a in replicated for a in instr.args)
            if same and instr.op in _WORTH_ONE_COLUMN:
                scalar.add(index)
        else:
            same = False
        if same and instr.dest is not None:
            replicated.add(instr.dest)
    if len(_SCALAR_CACHE) > 1024:
        _SCALAR_CACHE.clear()
    result = frozenset(scalar)
    _SCALAR_CACHE[id(program)] = (program, result)
    return result


def _row_count(program: Program, inputs: Mapping[str, np.ndarray], count: int | None) -> int:
    counts = {np.shape(inputs[i.name])[0] for i in program.inputs
              if i.kind != "uniform" and np.ndim(inputs[i.name]) == 2}
    if count is not None:
        counts.add(count)
    if len(counts) > 1:
        raise IRError(f"inputs disagree on the row count: {sorted(counts)}")
    if not counts:
        raise IRError("no per-row input fixes N: pass count=")
    return counts.pop()


def evaluate(program: Program, inputs: Mapping[str, np.ndarray],
             samplers: Mapping[int, SamplerFn] | None = None, *,
             count: int | None = None) -> EvalResult:
    """Evaluate `program` over N rows. `inputs` maps every declared input name to an (N, k)
    array (varyings, builtins) or a (k,) vector (uniforms, broadcast); `count` gives N when no
    input is per row."""
    missing = [i.name for i in program.inputs if i.name not in inputs]
    if missing:
        raise IRError(f"missing inputs: {', '.join(missing)}")
    ctx = _Context(program, inputs, samplers or {}, _row_count(program, inputs, count))
    values: dict[int, np.ndarray] = {}
    scalar = _scalar_instructions(program)
    with np.errstate(all="ignore"):  # inf and NaN are legitimate D3D results (rcp 0, log 0)
        for index, instr in enumerate(program.instrs):
            args = [values[a] for a in instr.args]
            if index in scalar:      # one column does: every component is the same
                args = [a[:, :1] for a in args]
                result = np.repeat(OPS[instr.op].kernel(ctx, args, instr.attr_map), 4, axis=1)
            else:
                result = OPS[instr.op].kernel(ctx, args, instr.attr_map)
            if instr.dest is not None:
                values[instr.dest] = _dense(result)
    outputs = {name: np.array(values[value], dtype=np.float32)
               for name, value in program.outputs}
    killed = ctx.killed
    if killed is None and any(i.op == "kill" for i in program.instrs):
        killed = np.zeros(ctx.count, dtype=bool)
    return EvalResult(outputs, killed)
