"""Run an IR program over N vertices or fragments at once with NumPy.

Every value is held as four component columns, each an (N,) float32 array, or a (1,) array
when it is the same on every row (uniforms, constants and what is computed from them only).
Swizzles and write-mask merges then only rearrange columns, a dp3 result is one column shared
by all four components, and a per-component op runs its `OPS` kernel (`effects.program.ir`) once per
distinct column of its arguments, so replicated scalars (rsq, pow of a dp3) cost one column.
Only the components some later instruction or output reads are computed. There is no per-row
Python loop; ops without a column form (sample, crs, kill, ...) run their kernel on (N, 4).
The values are those of the kernels on (N, 4) rows: the same float32 formula per element.

Texture sampling is delegated to callbacks the caller supplies (the rasteriser, which knows the
2x2 quads needed for derivatives; tests pass fakes). A sampler callback is called as
`sampler(coord, kind=..., bias=..., lod=...)` with coord an (N, 4) float32 array, already
divided by w for projected reads, and bias / lod an (N,) array or None; it returns (N, 4)
texels (any memory order). A sampler index with no callback reads (0, 0, 0, 1), as an unbound
ps_2_0 sampler does.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Mapping, Sequence

import numpy as np

from effects.base import caches
from effects.program.ir import OPS, IRError, Instr, Program, has_flow

SamplerFn = Callable[..., np.ndarray]
Columns = list  # four entries: (N,) or (1,) float32 arrays, None where nothing reads them
_MISSING_DEFAULT = np.array([0, 0, 0, 1], dtype=np.float32)
_UNBOUND_TEXEL = np.array([0, 0, 0, 1], dtype=np.float32)
_ALL = frozenset(range(4))
_MISSING_COLUMNS = [_MISSING_DEFAULT[i:i + 1] for i in range(4)]


@dataclass
class EvalResult:
    """`outputs`: name -> (N, 4) float32. `killed`: (N,) bool for fragment programs that kill,
    else None."""

    outputs: dict[str, np.ndarray]
    killed: np.ndarray | None


class _Context:
    """The KernelContext of effects.program.ir: inputs padded to vec4, samplers, the kill mask."""

    def __init__(self, program: Program, inputs: Mapping[str, np.ndarray],
                 samplers: Mapping[int, SamplerFn], count: int) -> None:
        self.program = program
        self.inputs = inputs
        self.samplers = samplers
        self.count = count
        self.killed: np.ndarray | None = None
        self.active: np.ndarray | None = None    # (N,) bool inside control flow, else None
        self.quads = False
        self.keep: np.ndarray | None = None    # sampling for the kept rows only (see `_Split`)
        self.sampling: _Context | None = None  # a kept-rows context's: over every row
        self.every: dict | None = None         # a kept-rows context's: the every-row values
        self.rows: dict[tuple, tuple] = {}

    def as_rows(self, columns: Columns) -> np.ndarray:
        """`_as_rows`, built once per distinct set of columns (several texture reads at one
        coordinate share it; kernels never write to their arguments)."""
        key = tuple(map(id, columns))
        found = self.rows.get(key)
        if found is None:   # the entry keeps the columns alive, so their ids stay theirs
            found = self.rows[key] = (list(columns), _as_rows(columns, self.count))
        return found[1]

    def input(self, name: str) -> np.ndarray:
        return _as_vec4(name, self.inputs[name], self.count)

    def input_columns(self, name: str) -> Columns:
        return _input_columns(name, self.inputs[name], self.count)

    def sample(self, index: int, coord: np.ndarray, kind: str, bias: np.ndarray | None,
               lod: np.ndarray | None, grad: tuple | None = None) -> np.ndarray:
        fn = self.samplers.get(index)
        count = self.count if self.keep is None else len(self.keep)
        if fn is None:
            return np.broadcast_to(_UNBOUND_TEXEL, (count, 4))
        extra = {} if grad is None else {"grad": grad}    # (d coord/dx, d coord/dy) rows
        if self.keep is not None:       # the LOD from every row's quad, texels of the kept
            extra["rows"] = self.keep
        texels = np.asarray(fn(coord, kind=kind, bias=bias, lod=lod, **extra), dtype=np.float32)
        if texels.shape != (count, 4):
            raise IRError(f"sampler {index} returned shape {texels.shape}, "
                          f"expected {(count, 4)}")
        return texels

    def derivative(self, x: np.ndarray, axis: int) -> np.ndarray:
        """d x / d(screen x or y) from the 2x2 quad each row belongs to (rows quad*4 + pixel,
        pixels (0,0) (1,0) (0,1) (1,1)): each pixel takes the difference along its own row
        (axis 0) or column (axis 1) of the quad, as GL's fine derivatives do."""
        if not self.quads or self.count % 4:
            raise IRError("screen-space gradients need the rows as whole 2x2 quads (quads=True)")
        q = np.asarray(x, np.float32).reshape(-1, 2, 2, x.shape[1])   # quad, y, x, component
        d = (q[:, :, 1] - q[:, :, 0])[:, :, None] if axis == 0 else (q[:, 1] - q[:, 0])[:, None]
        return np.broadcast_to(d, q.shape).reshape(-1, x.shape[1])

    def kill(self, mask: np.ndarray) -> None:
        if self.active is not None:        # inside control flow: only the running fragments
            mask = mask & self.active
        self.killed = mask if self.killed is None else self.killed | mask


def _checked_input(name: str, value: np.ndarray, count: int) -> np.ndarray:
    """(N, k) or (1, k) float32 with k <= 4, or IRError."""
    array = np.asarray(value, dtype=np.float32)
    if array.ndim == 1:
        array = array[None, :]
    if array.ndim != 2 or not 1 <= array.shape[1] <= 4 or array.shape[0] not in (1, count):
        raise IRError(f"input {name}: shape {np.shape(value)} is not (N, k) or (k,) with "
                      f"k <= 4 and N = {count}")
    return array


def _as_vec4(name: str, value: np.ndarray, count: int) -> np.ndarray:
    """(N, k) or (k,) with k <= 4 as (N, 4); missing components read (0, 0, 0, 1)."""
    array = _checked_input(name, value, count)
    if array.shape[1] < 4:
        padded = np.repeat(_MISSING_DEFAULT[None, :], array.shape[0], axis=0)
        padded[:, :array.shape[1]] = array
        array = padded
    return _dense(np.broadcast_to(array, (count, 4)))


def _input_columns(name: str, value: np.ndarray, count: int) -> Columns:
    """An input's four columns: contiguous (N,) per-row columns, (1,) where one row serves
    all (uniforms), missing components (0, 0, 0, 1)."""
    array = _checked_input(name, value, count)
    columns = list(np.ascontiguousarray(array.T))      # one copy: the k contiguous columns
    columns += _MISSING_COLUMNS[array.shape[1]:]
    return columns


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


# Worked out once per program object (kept with it in the entry and compared on a hit, so a
# recycled id cannot match): 1,024 entries each before, then all cleared. A program's steps
# and demand hold 24-31 KB together (tracemalloc: phong.fx's and wood.fx's 66-instruction
# fragment programs)
_DEMAND_CACHE = caches.declare("reference.demand", keys="program object, the sampler-read "
                               "rule, the given values", entry_bytes=8 << 10,
                               max_bytes=1024 * (8 << 10))


def _arg_demand(instr: Instr, wanted: frozenset, sample_reads=None) -> tuple[frozenset, ...]:
    """The components of each argument that `instr` reads to produce `wanted` of its result:
    the op row's demand rule, or for a sampling op the caller's `sample_reads` when given
    (what the sampler callback reads of its coordinate)."""
    info = OPS[instr.op]
    demand = info.arg_demand(wanted, instr.attr_map)
    if info.names_sampler and sample_reads is not None:   # its first argument: the coordinate
        return (sample_reads(instr), *demand[1:])
    return demand


def _demand(program: Program, sample_reads: Callable[[Instr], frozenset] | None = None,
            given: frozenset = frozenset()) -> list[frozenset]:
    """Per instruction, the components of its result that some instruction or output reads
    (kill and other effects count as reading what they read; a sample reads its whole
    coordinate unless `sample_reads` says otherwise). The values in `given` are supplied by
    the caller: they read nothing."""
    found = _DEMAND_CACHE.get((id(program), sample_reads, given))
    if found is not None and found[0] is program:
        return found[1]
    if has_flow(program):      # variables and loops: every component of every value counts
        return [_ALL] * len(program.instrs)
    need: dict[int, frozenset] = {}
    for _, value in program.outputs:
        need[value] = _ALL
    per_instr = [frozenset()] * len(program.instrs)
    for index in range(len(program.instrs) - 1, -1, -1):
        instr = program.instrs[index]
        wanted = _ALL if instr.dest is None else need.get(instr.dest, frozenset())
        per_instr[index] = wanted
        if not wanted or instr.dest in given:
            continue
        for arg, arg_need in zip(instr.args, _arg_demand(instr, wanted, sample_reads)):
            need[arg] = need.get(arg, frozenset()) | arg_need
    _DEMAND_CACHE.put((id(program), sample_reads, given), (program, per_instr))
    return per_instr


def input_components(program: Program,
                     sample_reads: Callable[[Instr], frozenset] | None = None,
                     given: frozenset = frozenset()) -> dict[str, frozenset]:
    """Input name -> the components (0 = x) the program's outputs and effects depend on.
    `sample_reads(instr)` gives the coordinate components a sample instruction's callback
    reads (default: all four, since a callback sees the whole vec4); the values in `given`
    are supplied (`evaluate(..., given=)`), so what only they read is not needed."""
    reads: dict[str, frozenset] = {}
    for instr, wanted in zip(program.instrs, _demand(program, sample_reads, given)):
        if OPS[instr.op].names_input:
            name = instr.attr("name")
            reads[name] = reads.get(name, frozenset()) | wanted
    return reads


# ------------------------------------------------------------------------------------------------
# Running instructions on columns

def _per_component(instr: Instr, args: Sequence[Columns], wanted: frozenset) -> Columns:
    """The op's kernel on each wanted column; columns whose arguments are the same arrays as
    another's (replicated values) share its result instead of recomputing it."""
    kernel, attrs = OPS[instr.op].kernel, instr.attr_map
    out: Columns = [None] * 4
    done: dict[tuple, np.ndarray] = {}
    for i in sorted(wanted):
        column_args = [a[i] for a in args]
        key = tuple(id(c) for c in column_args)
        if key not in done:
            done[key] = np.asarray(kernel(None, column_args, attrs), np.float32)
        out[i] = done[key]
    return out


def _as_rows(columns: Columns, count: int) -> np.ndarray:
    """Columns as an (N, 4) C-ordered array; unread (None) columns hold 0."""
    rows = np.empty((count, 4), np.float32)
    for i, column in enumerate(columns):
        rows[:, i] = 0 if column is None else column
    return rows


def _from_rows(rows: np.ndarray) -> Columns:
    """An (N, 4) kernel result as contiguous columns (free for a column-major result)."""
    planar = np.ascontiguousarray(np.asarray(rows, np.float32).T)
    return list(planar)


def _run(ctx: _Context, instr: Instr, args: Sequence[Columns], wanted: frozenset) -> Columns:
    """One instruction, as its op row says: its column form, its kernel per column, or (no
    column form) its kernel on whole (N, 4) rows."""
    info = OPS[instr.op]
    if info.columns is not None:
        return info.columns(ctx, args, instr.attr_map, wanted)
    if info.per_component:
        return _per_component(instr, args, wanted)
    result = info.kernel(ctx, [ctx.as_rows(a) for a in args], instr.attr_map)
    return None if result is None else _from_rows(result)


# ------------------------------------------------------------------------------------------------
# Structured control flow: every fragment runs every instruction; a mask says which fragments a
# block runs for. Assignments and kills only touch running fragments, so a fragment's result is
# that of running its own path (D3D's semantics, and GLSL's). A loop repeats while some fragment
# still runs it and its count is not reached; `break` stops fragments until the loop ends.

@dataclass
class _Block:
    info: object
    parent: np.ndarray                 # the mask when the block was entered
    cond: np.ndarray | None = None     # if: where the condition holds
    start: int = 0                     # loop: index of the loop instruction
    left: int = 0                      # loop: iterations still to run after this one
    broken: np.ndarray | None = None   # loop: fragments that took a break


def _truth(columns: Columns, count: int) -> np.ndarray:
    return np.broadcast_to(columns[0] != 0, (count,))


def _masked(old: Columns, new: Columns, active: np.ndarray) -> Columns:
    if active.all():
        return list(new)
    return [np.where(active, n, o).astype(np.float32) for o, n in zip(old, new)]


def _run_structured(ctx: _Context, program: Program, values: dict[int, Columns]) -> None:
    instrs, count = program.instrs, ctx.count
    active = np.ones(count, dtype=bool)
    blocks: list[_Block] = []
    everything = _ALL
    pc = 0
    while pc < len(instrs):
        instr = instrs[pc]
        info = OPS[instr.op]
        args = [values[a] for a in instr.args]
        flow = info.flow
        ctx.active = active
        if info.assigns:
            values[instr.args[0]] = _masked(args[0], args[1], active)
        elif flow is None:
            result = _run(ctx, instr, args, everything)
            if instr.dest is not None:
                values[instr.dest] = result
        elif flow == "open" and info.loop:
            n = instr.attr("count")
            blocks.append(_Block(info, active, start=pc, left=n - 1,
                                 broken=np.zeros(count, dtype=bool)))
            if n == 0:
                active = np.zeros(count, dtype=bool)
        elif flow == "open":
            cond = _truth(args[0], count)
            blocks.append(_Block(info, active, cond=cond))
            active = active & cond
        elif flow == "middle":
            block = blocks[-1]
            active = block.parent & ~block.cond & ~_broken(blocks)
        elif flow == "exit":
            loop = next(b for b in reversed(blocks) if b.broken is not None)
            leaving = active & _truth(args[0], count)
            loop.broken |= leaving
            active = active & ~leaving
        elif info.loop:                                   # endloop
            loop = blocks[-1]
            running = loop.parent & ~loop.broken
            if loop.left > 0 and running.any():
                loop.left -= 1
                active = running
                pc = loop.start + 1
                continue
            blocks.pop()
            active = loop.parent & ~_broken(blocks)
        else:                                             # endif
            block = blocks.pop()
            active = block.parent & ~_broken(blocks)
        pc += 1
    ctx.active = None


def _broken(blocks: list[_Block]) -> np.ndarray | np.bool_:
    """Fragments that broke out of the innermost loop enclosing the current point (NumPy's
    False outside loops: Python's ~False is -1, which would turn a mask into integers)."""
    for block in reversed(blocks):
        if block.broken is not None:
            return block.broken
    return np.False_


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


# ------------------------------------------------------------------------------------------------
# A straight-line program's steps, worked out once per program (and set of given values): what
# `_run` decides per instruction on every call (the op row, its attributes as a dict, the
# components wanted in order) is looked up once, so a call's Python work per instruction is
# gathering the arguments and calling the kernel. Keyed by the program object (checked on a
# hit, like `_demand`), so a new or changed program gets its own steps.

_SKIP, _GIVEN, _COLUMNS, _PER_COMPONENT, _ROWS, _BATCH = range(6)


@dataclass
class _Steps:
    steps: list            # (mode, dest, args, fn, attrs, wanted, order) per instruction
    discards: bool         # some instruction may discard (a kill mask is always returned)


_STEPS_CACHE = caches.declare("reference.steps", keys="program object, the given values",
                              entry_bytes=16 << 10, max_bytes=1024 * (16 << 10))


def _steps(program: Program, given: frozenset) -> _Steps:
    key = (id(program), given)
    found = _STEPS_CACHE.get(key)
    if found is not None and found[0] is program:
        return found[1]
    steps = []
    for instr, wanted in zip(program.instrs, _demand(program, None, given)):
        info = OPS[instr.op]
        if not wanted:
            mode, fn = _SKIP, None
        elif instr.dest in given:
            mode, fn = _GIVEN, None
        elif info.columns is not None:
            mode, fn = _COLUMNS, info.columns
        elif info.per_component:
            mode, fn = _PER_COMPONENT, info.kernel
        else:
            mode, fn = _ROWS, info.kernel
        steps.append((mode, instr.dest, instr.args, fn, instr.attr_map, wanted,
                      tuple(sorted(wanted))))
    result = _Steps(_batched(program, steps), any(OPS[i.op].discards for i in program.instrs))
    _STEPS_CACHE.put(key, (program, result))
    return result


def _batched(program: Program, steps: list) -> list:
    """The steps with instructions of one op that has a `batch` form, sharing their first
    argument and each taking a uniform as the second (m4x4, m3x3 rows), run as one step at
    the first of them. Argument-less pure steps (inputs, constants) go first, so every such
    uniform is there by then; nothing else moves, and each value is the one its own step
    would make."""
    uniforms = {i.name for i in program.inputs if i.kind == "uniform"}
    one_row = {instr.dest for instr in program.instrs
               if OPS[instr.op].names_input and instr.attr("name") in uniforms}
    groups: dict[tuple, list[int]] = {}
    for k, (instr, step) in enumerate(zip(program.instrs, steps)):
        if (step[0] == _COLUMNS and OPS[instr.op].batch is not None and len(instr.args) == 2
                and instr.args[1] in one_row):
            groups.setdefault((instr.op, instr.args[0]), []).append(k)
    groups = {key: members for key, members in groups.items() if len(members) > 1}
    if not groups:
        return steps
    first = {members[0]: members for members in groups.values()}
    later = {k for members in groups.values() for k in members[1:]}

    def free(instr) -> bool:
        info = OPS[instr.op]
        return (info.arity == 0 and info.pure and info.flow is None and not info.discards
                and instr.dest is not None)

    out = [step for instr, step in zip(program.instrs, steps) if free(instr)]
    for k, (instr, step) in enumerate(zip(program.instrs, steps)):
        if free(instr) or k in later:
            continue
        if k in first:
            members = first[k]
            out.append((_BATCH, tuple(steps[m][1] for m in members),
                        (instr.args[0], *(program.instrs[m].args[1] for m in members)),
                        OPS[instr.op].batch, tuple(steps[m] for m in members), None, None))
            continue
        out.append(step)
    return out


_FLOW_CACHE = caches.declare("reference.flow", keys="program object", entry_bytes=256,
                             max_bytes=1024 * 256)


def _has_flow(program: Program) -> bool:
    """`has_flow`, kept per program object (it scans every instruction)."""
    found = _FLOW_CACHE.get(id(program))
    if found is not None and found[0] is program:
        return found[1]
    flow = has_flow(program)
    _FLOW_CACHE.put(id(program), (program, flow))
    return flow


def _run_steps(ctx: _Context, steps: list, values: dict[int, Columns],
               given: Mapping[int, np.ndarray]) -> None:
    """Run a straight-line program's steps; the values are those `_run` gives."""
    for mode, dest, args, fn, attrs, wanted, order in steps:
        if mode == _SKIP:                 # nothing reads it
            values[dest] = [None] * 4
            continue
        if mode == _GIVEN:
            values[dest] = _from_rows(given[dest])
            continue
        if mode == _SPLIT:                # the coordinate over every row (`_run_split`)
            sampling = ctx.sampling
            values[dest] = _from_rows(
                fn(sampling, [sampling.as_rows(ctx.every[a]) for a in args], attrs))
            continue
        argv = [values[a] for a in args]
        if mode == _COLUMNS:
            result = fn(ctx, argv, attrs, wanted)
        elif mode == _PER_COMPONENT:
            # the kernel once per distinct set of argument columns (as `_per_component`)
            result = [None] * 4
            done: dict[tuple, np.ndarray] = {}
            for i in order:
                column_args = [a[i] for a in argv]
                key = tuple(map(id, column_args))
                column = done.get(key)
                if column is None:
                    column = done[key] = np.asarray(fn(None, column_args, attrs), np.float32)
                result[i] = column
        elif mode == _BATCH:              # dest: the members' results, attrs: their steps
            results = fn(argv[0], argv[1:])
            if results is None:
                results = [member[3](ctx, [argv[0], b], member[4], member[5])
                           for member, b in zip(attrs, argv[1:])]
            for member_dest, member_result in zip(dest, results):
                values[member_dest] = member_result
            continue
        else:
            rows = fn(ctx, [ctx.as_rows(a) for a in argv], attrs)
            result = None if rows is None else _from_rows(rows)
        if dest is not None:
            values[dest] = result


# ------------------------------------------------------------------------------------------------
# Helper pixels only where derivatives read them. A quad's helper (uncovered) pixels exist for
# the differences across the quad: the LOD of an implicit-LOD texture read and ddx / ddy. What
# the kept rows end with never reads a helper's value otherwise, and every other op works row
# by row, so the program splits in two: the steps those differences read (back from each
# sample's coordinate and each ddx / ddy argument) run over every row, the rest over the kept
# rows only, and a sample whose texel only the rest reads takes its LOD from every row's quad
# and reads texels for the kept rows (`sampler(..., rows=)`). Each kept row's values are those
# of running everything over every row.

_SPLIT = 6                  # a sample step: coordinate over every row, texels of the kept ones


@dataclass
class _Split:
    every: list             # steps run over every row, in program order
    kept: list              # the rest, over the kept rows, in program order
    carried: tuple          # values made over every row that a kept-rows step reads


_SPLIT_CACHE = caches.declare("reference.split", keys="program object, the given values",
                              entry_bytes=16 << 10, max_bytes=1024 * (16 << 10))


def _step_dests(step) -> tuple:
    return step[1] if step[0] == _BATCH else (step[1],)


def _split(program: Program, steps: _Steps, given: frozenset) -> _Split | None:
    """The program's steps split as above, or None when every step would run over every row
    (nothing to gain). Cached per program object and set of given values, as `_steps`."""
    key = (id(program), given)
    found = _SPLIT_CACHE.get(key)
    if found is not None and found[0] is program:
        return found[1]
    op_of = {instr.dest: instr.op for instr in program.instrs if instr.dest is not None}
    producer = {d: k for k, step in enumerate(steps.steps) for d in _step_dests(step)}
    every: set[int] = set()
    samples: set[int] = set()
    pending: list[int] = []
    for k, step in enumerate(steps.steps):
        mode, dest = step[0], step[1]
        if mode in (_SKIP, _BATCH) or dest is None or not OPS[op_of[dest]].needs_quads:
            continue
        if mode == _ROWS and OPS[op_of[dest]].names_sampler:
            samples.add(k)
            pending.extend(step[2])             # its coordinate, over every row
        else:                                   # ddx, ddy: run over every row
            every.add(k)
            pending.extend(step[2])
    while pending:
        k = producer.get(pending.pop())
        if k is not None and k not in every:
            every.add(k)
            pending.extend(steps.steps[k][2])
    if len(every) + len(samples - every) >= len(steps.steps):
        result = None
    else:
        made_every = {d for k in every for d in _step_dests(steps.steps[k])}
        kept, carried = [], set()
        for k, step in enumerate(steps.steps):
            if k in every:
                continue
            if k in samples:
                kept.append((_SPLIT, *step[1:]))
            else:
                kept.append(step)
                carried.update(a for a in step[2] if a in made_every)
        outputs_made = {value for _, value in program.outputs} & made_every
        result = _Split([steps.steps[k] for k in sorted(every)], kept,
                        tuple(sorted(carried | outputs_made)))
    _SPLIT_CACHE.put(key, (program, result))
    return result


class _KeptInputs(Mapping):
    """The inputs at the kept rows, each taken once, when a kept-rows step first reads it."""

    def __init__(self, inputs: Mapping[str, np.ndarray], keep: np.ndarray, count: int) -> None:
        self._inputs, self._keep, self._count = inputs, keep, count
        self._taken: dict[str, np.ndarray] = {}

    def __getitem__(self, name: str) -> np.ndarray:
        found = self._taken.get(name)
        if found is None:
            value = self._inputs[name]      # per row, or one row for all (a uniform)
            per_row = np.ndim(value) == 2 and np.shape(value)[0] == self._count
            found = self._taken[name] = (np.asarray(value)[self._keep] if per_row else value)
        return found

    def __iter__(self):
        return iter(self._inputs)

    def __len__(self) -> int:
        return len(self._inputs)


def _kept_columns(columns: Columns, keep: np.ndarray) -> Columns:
    return [c if c is None or len(c) == 1 else c[keep] for c in columns]


def _run_split(ctx: _Context, split: _Split, keep: np.ndarray, values: dict[int, Columns],
               given: Mapping[int, np.ndarray]) -> tuple[_Context, dict[int, Columns]]:
    """Run `split`: its first part over ctx's rows (into `values`), the rest over the rows
    `keep`. Returns the kept rows' context (its kill mask) and values."""
    _run_steps(ctx, split.every, values, given)
    kept = _Context(ctx.program, _KeptInputs(ctx.inputs, keep, ctx.count), ctx.samplers,
                    len(keep))
    sampling = kept.sampling = _Context(ctx.program, ctx.inputs, ctx.samplers, ctx.count)
    sampling.quads, sampling.keep, sampling.rows = ctx.quads, keep, ctx.rows
    kept.every = values
    kept_values = {v: _kept_columns(values[v], keep) for v in split.carried}
    _run_steps(kept, split.kept, kept_values, {d: g[keep] for d, g in given.items()})
    return kept, kept_values


def evaluate(program: Program, inputs: Mapping[str, np.ndarray],
             samplers: Mapping[int, SamplerFn] | None = None, *,
             count: int | None = None, quads: bool = False,
             given: Mapping[int, np.ndarray] | None = None,
             keep: np.ndarray | None = None) -> EvalResult:
    """Evaluate `program` over N rows. `inputs` maps every declared input name to an (N, k)
    array (varyings, builtins) or a (k,) vector (uniforms, broadcast); `count` gives N when no
    input is per row. `quads`: the rows are whole 2x2 quads (rasteriser order), which
    gradient ops (ddx, ddy) need. `given` maps value numbers to (N, 4) rows used in place of
    computing them (what only they read is not run): how the reference shades a Phong pass's
    lighting its own way (`PassProgram.lighting`); not with control flow. `keep`: the indices
    (increasing) of the rows whose results are wanted, with `quads`: the outputs and kill
    mask then hold those rows only, and the others (helper pixels) run only what derivatives
    read (samplers are then called with `rows=keep`: see `_Split`)."""
    given = given or {}
    flow = _has_flow(program)
    if given and flow:
        raise IRError("given values need a program without control flow")
    missing = [i.name for i in program.inputs if i.name not in inputs]
    if missing:
        raise IRError(f"missing inputs: {', '.join(missing)}")
    ctx = _Context(program, inputs, samplers or {}, _row_count(program, inputs, count))
    ctx.quads = quads
    values: dict[int, Columns] = {}
    steps = None
    split = None
    with np.errstate(all="ignore"):  # inf and NaN are legitimate D3D results (rcp 0, log 0)
        if flow:
            _run_structured(ctx, program, values)
        else:
            steps = _steps(program, frozenset(given))
            if keep is not None and quads and len(keep) < ctx.count:
                split = _split(program, steps, frozenset(given))
            if split is not None:
                ctx, values = _run_split(ctx, split, keep, values, given)
            else:
                _run_steps(ctx, steps.steps, values, given)
    if keep is not None and split is None:      # every row ran: the kept ones
        values = {v: _kept_columns(values[v], keep) for _, v in program.outputs}
        ctx.killed = None if ctx.killed is None else ctx.killed[keep]
        ctx.count = len(keep)
    outputs = {name: _as_rows(values[value], ctx.count) for name, value in program.outputs}
    killed = ctx.killed
    discards = (steps.discards if steps is not None
                else any(OPS[i.op].discards for i in program.instrs))
    if killed is None and discards:
        killed = np.zeros(ctx.count, dtype=bool)
    return EvalResult(outputs, killed)
