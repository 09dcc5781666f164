"""The IR every shading path lowers to: straight-line SSA over vec4 float values.

Fixed-function texture stages, ps.1.x / ps.2.0 / vs.1.1 assembly and the fixed-function vertex
pipeline all lower to a `Program`; the NumPy reference (`backends.reference.evaluate`) and the
GLSL 330 printer consume it. Every op is one row of `OPS` (after Mesa's `nir_opcodes.py`): its
arity, its NumPy kernel, its GLSL expression, whether it is per component, which components of
its arguments it reads, its column form for the evaluator. Back ends read that row and nothing
else (no back end knows an op by name); they never look at caps, so precision (clamp,
quantize) is always explicit in the program.

Conventions
- Every value is a vec4 of float32; the evaluator holds it as an (N, 4) array over N vertices or
  fragments. Scalar D3D instructions (rcp, rsq, exp, log, pow) are per component here: lowering
  replicates the selected component with a swizzle first.
- Values are produced only by instructions. `input` reads a declared `Input` (varying, uniform or
  builtin) by name and `const` makes a literal; both are ordinary instructions, so constants are
  deduplicated like any other value and print inline in GLSL. (A 'constant' input kind is not
  needed: a constant is a `const` instruction.)
- Structured control flow (Shader Model 2.x/3.0): `if %c` / `else` / `endif` run a block where
  `c.x != 0`, `loop count=N` / `endloop` repeat a block N times (N static, at most 255 as in
  D3D), `break %c` leaves the innermost loop where `c.x != 0`. Values that change inside a
  block are mutable variables: `%v = var %init` declares one, `assign %v, %x` sets it (under
  the current per-fragment mask in the evaluator); every other value is SSA and a value defined
  inside a block is not used after it. Row columns say which op opens, continues or closes a
  block (`flow`), so checker, evaluator and printer follow the table.
- `kill`, `assign` and the flow ops are the instructions without a result (`dest is None`).
- GLSL templates format with the GLSL expressions of the arguments. Several templates use an
  argument more than once, so the printer binds every value to a variable and passes names.
  Samplers are the uniforms `sampler0`..; inputs keep their names.
- Malformed IR is a bug in a lowering, not in user input: it raises `IRError` (a ValueError).
"""
from __future__ import annotations

import hashlib
import re
from dataclasses import dataclass
from typing import Any, Callable, Iterable, Mapping, Protocol, Sequence

import numpy as np

STAGES = ("vertex", "fragment")
INPUT_KINDS = ("varying", "uniform", "builtin")
SAMPLER_KINDS = ("1d", "2d", "3d", "cube")
# Output names per stage, in the order programs keep and print them. Scalar outputs (depth, fog,
# psize) take the x component of their value.
OUTPUTS = {
    "fragment": ("color0", "color1", "color2", "color3", "depth"),
    "vertex": ("position", "color0", "color1", *(f"texcoord{i}" for i in range(8)), "fog",
               "psize"),
}
COMPONENTS = "xyzw"
FLT_MAX = float(np.finfo(np.float32).max)
_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
_GLSL_INF = "uintBitsToFloat(0x7F800000u)"  # GLSL 330 has no infinity literal


class IRError(ValueError):
    """Malformed IR: a lowering bug, never a user error (user errors are EffectErrors)."""


# --------------------------------------------------------------------------------------------
# Program representation


@dataclass(frozen=True)
class Input:
    """A program input. `semantic` is free text for the binder (`TEXCOORD0`, a parameter name);
    `components` is how many the source supplies; the rest read as (0, 0, 0, 1)."""

    name: str
    kind: str = "varying"
    semantic: str = ""
    components: int = 4


@dataclass(frozen=True)
class SamplerBinding:
    """A sampler slot a program samples, and the texture kind it expects there."""

    index: int
    kind: str = "2d"


@dataclass(frozen=True)
class Instr:
    """`dest = op(args...)` with `attrs` as (name, value) pairs in the op row's order, defaults
    filled in, so equal instructions compare and hash equal."""

    dest: int | None
    op: str
    args: tuple[int, ...] = ()
    attrs: tuple[tuple[str, Any], ...] = ()

    def attr(self, name: str) -> Any:
        for key, value in self.attrs:
            if key == name:
                return value
        raise KeyError(f"{self.op} has no attribute {name!r}")

    @property
    def attr_map(self) -> dict[str, Any]:
        return dict(self.attrs)


@dataclass(frozen=True)
class Program:
    """A program for one stage. Checked on construction (see `check_program`).
    `outputs` is (name, value id) pairs in the stage's output order. `clamp_colors` (vertex
    programs): the back end saturates the color0/color1 interpolators, as Direct3D does below
    Shader Model 3; a vs_3_0 program's colour outputs are not clamped."""

    stage: str
    inputs: tuple[Input, ...] = ()
    instrs: tuple[Instr, ...] = ()
    outputs: tuple[tuple[str, int], ...] = ()
    samplers: tuple[SamplerBinding, ...] = ()
    clamp_colors: bool = True

    def __post_init__(self) -> None:
        check_program(self)

    @property
    def output_map(self) -> dict[str, int]:
        return dict(self.outputs)

    def input(self, name: str) -> Input:
        for item in self.inputs:
            if item.name == name:
                return item
        raise KeyError(name)

    def sampler(self, index: int) -> SamplerBinding:
        for item in self.samplers:
            if item.index == index:
                return item
        raise KeyError(index)

    def key(self) -> str:
        """A digest of the printed program, stable across processes (for on-disk caches)."""
        return hashlib.sha256(format_program(self).encode()).hexdigest()

    def __str__(self) -> str:
        return format_program(self)


# --------------------------------------------------------------------------------------------
# The op table


class KernelContext(Protocol):
    """What a kernel may ask of the evaluator besides its arguments."""

    count: int

    def input(self, name: str) -> np.ndarray: ...

    def input_columns(self, name: str) -> list: ...

    def sample(self, index: int, coord: np.ndarray, kind: str, bias: np.ndarray | None,
               lod: np.ndarray | None, grad: tuple | None = None) -> np.ndarray: ...

    def kill(self, mask: np.ndarray) -> None: ...

    def derivative(self, x: np.ndarray, axis: int) -> np.ndarray: ...


Kernel = Callable[[KernelContext, Sequence[np.ndarray], Mapping[str, Any]], "np.ndarray | None"]
GlslFormat = Callable[[Sequence[str], Mapping[str, Any]], str]
REQUIRED = object()  # an attribute without a default

Columns = list  # four component columns, (N,) or (1,) float32, None where nothing reads them
Demand = Callable[[frozenset, Mapping[str, Any], int], "tuple[frozenset, ...]"]
ColumnKernel = Callable[[KernelContext, Sequence[Columns], Mapping[str, Any], frozenset], Columns]
_ALL = frozenset(range(4))
_XYZ = frozenset(range(3))


@dataclass(frozen=True)
class OpInfo:
    """One op. Besides its arity, kernel, GLSL template and attributes, the row says what the
    evaluator and the printers need without knowing the op by name:
    - `per_component`: component i of the result depends on component i of the arguments only
      (the evaluator then runs the kernel once per distinct column);
    - `demand(wanted, attrs, arity)`: the components of each argument read to produce the
      `wanted` components (0 = x) of the result; None means `wanted` for a per-component op
      and all four otherwise;
    - `columns`: the op's column form for the evaluator (moves, dots, inputs), None when it
      runs its kernel per column (per-component ops) or on whole (N, 4) rows;
    - `names_input` / `names_sampler`: its `name` attribute names a declared `Input`, its
      `sampler` attribute a declared `SamplerBinding`; `discards`: it may discard fragments;
    - `pure`: equal instructions may be one value; `flow`, `loop`: its place in structured
      control flow (opens / continues / closes a block, or 'exit': break), and whether the
      block is a loop; `needs_quads`: its result depends on the 2x2 quad (LOD, gradients);
    - `stages`: the program stages it may appear in."""

    name: str
    arity: int
    kernel: Kernel
    glsl: str | GlslFormat
    doc: str
    attrs: tuple[tuple[str, Any], ...] = ()        # (name, default or REQUIRED)
    check: Callable[[Mapping[str, Any]], None] | None = None
    has_result: bool = True
    per_component: bool = False
    demand: Demand | None = None
    columns: ColumnKernel | None = None
    names_input: bool = False
    names_sampler: bool = False
    discards: bool = False
    stages: tuple[str, ...] = STAGES
    pure: bool = True              # equal instructions are one value (var: each is its own)
    assigns: bool = False          # sets its first argument (a var) to its second
    flow: str | None = None        # 'open' | 'middle' | 'close' | 'exit' (structured flow)
    loop: bool = False             # the block it opens or closes is a loop
    needs_quads: bool = False      # reads neighbouring fragments: run over whole 2x2 quads
    # The column form of several of these instructions sharing their first argument whose
    # second arguments are each one row (uniforms): batch(a, [b, ...]) -> [result, ...], one
    # call over the stacked rows, each result as `columns` gives it, value for value; None
    # where some b is not one row after all (the evaluator then runs each on its own).
    batch: Callable[[Columns, Sequence[Columns]], list] | None = None

    def arg_demand(self, wanted: frozenset, attrs: Mapping[str, Any]) -> tuple[frozenset, ...]:
        """The components of each argument this op reads to produce `wanted` of its result."""
        if self.demand is not None:
            return self.demand(wanted, attrs, self.arity)
        return (wanted if self.per_component else _ALL,) * self.arity

    def format_glsl(self, args: Sequence[str], attrs: Mapping[str, Any] | None = None) -> str:
        """The GLSL 330 expression (a statement for `kill`) for this op over `args`."""
        if callable(self.glsl):
            return self.glsl(args, attrs or {})
        return self.glsl.format(*args)


def glsl_float(value: float) -> str:
    """A float literal valid in GLSL and in the printer: the shortest float32 round trip."""
    value = float(value)
    if not np.isfinite(value):
        raise IRError(f"non-finite literal {value!r}")
    text = str(np.float32(value))
    return text if any(c in text for c in ".e") else text + ".0"


def _vec4(values: Iterable[float]) -> str:
    return "vec4(" + ", ".join(glsl_float(v) for v in values) + ")"


def _replicate(x: np.ndarray) -> np.ndarray:
    return np.repeat(x, 4).reshape(-1, 4)


def _swizzle(a: np.ndarray, pattern: str) -> np.ndarray:
    # np.take / np.repeat, not a[:, idx]: fancy indexing returns a column-major array, and
    # NumPy's arithmetic on a mix of orders runs about four times slower.
    if len(set(pattern)) == 1:
        return _replicate(a[:, COMPONENTS.index(pattern[0])])
    return np.take(a, _indices(pattern), axis=1)


def dot3_columns(a: Sequence[np.ndarray], b: Sequence[np.ndarray]) -> np.ndarray:
    """a.xyz . b.xyz from component columns (a[0] is x). Explicit left-to-right sum, the
    order a GPU dot() uses; the evaluator's column form shares it, so values agree bit for bit."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def nrm_scale(f: np.ndarray) -> np.ndarray:
    """The factor nrm scales by, from f = xyz . xyz. D3D nrm: a zero-length xyz scales by
    FLT_MAX instead of dividing by zero (ps/vs docs)."""
    return np.where(f != 0, 1 / np.sqrt(f), np.float32(FLT_MAX)).astype(np.float32)


def _columns(a: np.ndarray) -> tuple[np.ndarray, ...]:
    return tuple(a[:, i] for i in range(a.shape[1]))


def _dot3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return dot3_columns(_columns(a), _columns(b))


def _nrm(x: np.ndarray) -> np.ndarray:
    return x * nrm_scale(_dot3(x, x))[:, None]


def _crs(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    out = np.zeros_like(a)
    out[:, :3] = np.cross(a[:, :3], b[:, :3])
    return out


def _rcp(x: np.ndarray) -> np.ndarray:
    # D3D rcp: 0 (either sign) gives +inf; IEEE 1/-0 would give -inf.
    return np.where(x == 0, np.float32(np.inf), 1 / x).astype(np.float32)


def _indices(components: str) -> list[int]:
    return [COMPONENTS.index(c) for c in components]


def _merge(old: np.ndarray, new: np.ndarray, mask: str) -> np.ndarray:
    out = np.array(old, dtype=np.float32, copy=True)
    for i in _indices(mask):       # column copies: faster than one fancy-indexed assignment
        out[:, i] = new[:, i]
    return out


def _quantize_params(attrs: Mapping[str, Any]) -> tuple[float, float, float]:
    """(lo, hi, steps per unit) of the fixed-point grid `quantize` rounds to."""
    bits, signed, scale = attrs["bits"], attrs["signed"], float(attrs["scale"])
    levels = 2 ** (bits - 1) - 1 if signed else 2 ** bits - 1
    return (-scale if signed else 0.0), scale, levels / scale


def _quantize(x: np.ndarray, attrs: Mapping[str, Any]) -> np.ndarray:
    lo, hi, k = _quantize_params(attrs)
    c = np.clip(x, np.float32(lo), np.float32(hi))
    k32 = np.float32(k)
    # Round half away from zero (sign * floor(|x| k + 1/2)); the GLSL template does the same.
    return (np.sign(c) * np.floor(np.abs(c) * k32 + np.float32(0.5)) / k32).astype(np.float32)


def _glsl_quantize(args: Sequence[str], attrs: Mapping[str, Any]) -> str:
    lo, hi, k = _quantize_params(attrs)
    c = f"clamp({args[0]}, {glsl_float(lo)}, {glsl_float(hi)})"
    ks = glsl_float(k)
    return f"(sign({c}) * floor(abs({c}) * {ks} + 0.5) / {ks})"


def _check_quantize(attrs: Mapping[str, Any]) -> None:
    bits = attrs["bits"]
    if not isinstance(bits, int) or not (2 if attrs["signed"] else 1) <= bits <= 24:
        raise IRError(f"quantize bits must be an int in 1..24 (2..24 signed), got {bits!r}")
    if not float(attrs["scale"]) > 0:
        raise IRError(f"quantize scale must be positive, got {attrs['scale']!r}")


def _check_clamp(attrs: Mapping[str, Any]) -> None:
    if not float(attrs["lo"]) <= float(attrs["hi"]):
        raise IRError(f"clamp needs lo <= hi, got {attrs['lo']} > {attrs['hi']}")


def _check_pattern(attrs: Mapping[str, Any]) -> None:
    pattern = attrs["pattern"]
    if not (isinstance(pattern, str) and len(pattern) == 4 and set(pattern) <= set(COMPONENTS)):
        raise IRError(f"swizzle pattern must be 4 of 'xyzw', got {pattern!r}")


def _check_components(name: str) -> Callable[[Mapping[str, Any]], None]:
    def check(attrs: Mapping[str, Any]) -> None:
        mask = attrs[name]
        if not (isinstance(mask, str) and mask and _is_ordered_subset(mask)):
            raise IRError(f"{name} must be an ordered subset of 'xyzw', got {mask!r}")
    return check


def _is_ordered_subset(mask: str) -> bool:
    return all(c in COMPONENTS for c in mask) and list(mask) == sorted(set(mask), key=COMPONENTS.index)


def _check_const(attrs: Mapping[str, Any]) -> None:
    value = attrs["value"]
    if not (isinstance(value, tuple) and len(value) == 4
            and all(isinstance(v, float) and np.isfinite(v) for v in value)):
        raise IRError(f"const value must be 4 finite floats, got {value!r}")


def _check_name(attrs: Mapping[str, Any]) -> None:
    if not isinstance(attrs["name"], str):
        raise IRError(f"input name must be a string, got {attrs['name']!r}")


def _check_sample(attrs: Mapping[str, Any]) -> None:
    if not isinstance(attrs["sampler"], int) or attrs["sampler"] < 0:
        raise IRError(f"sampler index must be a non-negative int, got {attrs['sampler']!r}")
    if attrs["kind"] not in SAMPLER_KINDS:
        raise IRError(f"sampler kind must be one of {SAMPLER_KINDS}, got {attrs['kind']!r}")
    if sum(bool(attrs[k]) for k in ("proj", "bias", "lod")) > 1:
        raise IRError("sample takes at most one of proj, bias, lod (each reads coord.w)")


def _check_sample_grad(attrs: Mapping[str, Any]) -> None:
    _check_sample({**attrs, "proj": False, "bias": False, "lod": False})


_COORD = {"1d": "x", "2d": "xy", "3d": "xyz", "cube": "xyz"}
_PROJ_COORD = {"1d": "xw", "2d": "xyw", "3d": "xyzw"}


def _sample(ctx: KernelContext, args: Sequence[np.ndarray], attrs: Mapping[str, Any]) -> np.ndarray:
    coord = np.array(args[0], dtype=np.float32, copy=True)
    w = coord[:, 3].copy()
    if attrs["proj"]:
        coord[:, :3] /= w[:, None]
        coord[:, 3] = 1
    return ctx.sample(attrs["sampler"], coord, attrs["kind"], w if attrs["bias"] else None,
                      w if attrs["lod"] else None)


def _glsl_sample(args: Sequence[str], attrs: Mapping[str, Any]) -> str:
    s, kind, c = f"sampler{attrs['sampler']}", attrs["kind"], args[0]
    if attrs["proj"]:
        if kind == "cube":  # GLSL has no textureProj for cube maps
            return f"texture({s}, {c}.xyz / {c}.w)"
        swz = _PROJ_COORD[kind]
        return f"textureProj({s}, {c})" if swz == "xyzw" else f"textureProj({s}, {c}.{swz})"
    coord = f"{c}.{_COORD[kind]}"
    if attrs["bias"]:
        return f"texture({s}, {coord}, {c}.w)"
    if attrs["lod"]:
        return f"textureLod({s}, {coord}, {c}.w)"
    return f"texture({s}, {coord})"


def _sample_grad(ctx: KernelContext, args: Sequence[np.ndarray], attrs: Mapping[str, Any]
                 ) -> np.ndarray:
    return ctx.sample(attrs["sampler"], np.asarray(args[0], np.float32), attrs["kind"], None,
                      None, grad=(np.asarray(args[1], np.float32),
                                  np.asarray(args[2], np.float32)))


def _glsl_sample_grad(args: Sequence[str], attrs: Mapping[str, Any]) -> str:
    swz = _COORD[attrs["kind"]]
    c, dx, dy = (f"{a}.{swz}" for a in args)
    return f"textureGrad(sampler{attrs['sampler']}, {c}, {dx}, {dy})"


def _kill(ctx: KernelContext, args: Sequence[np.ndarray], attrs: Mapping[str, Any]) -> None:
    ctx.kill(np.any(args[0][:, _indices(attrs["components"])] < 0, axis=1))


def _glsl_kill(args: Sequence[str], attrs: Mapping[str, Any]) -> str:
    mask = attrs["components"]
    if len(mask) == 1:
        return f"if ({args[0]}.{mask} < 0.0) discard;"
    return f"if (any(lessThan({args[0]}.{mask}, vec{len(mask)}(0.0)))) discard;"


def _no_kernel(ctx: KernelContext, args: Sequence[np.ndarray], attrs: Mapping[str, Any]) -> None:
    raise IRError("flow and assign ops are run by the evaluator's control, not a kernel")


def _glsl_loop(args: Sequence[str], attrs: Mapping[str, Any]) -> str:
    k = f"loop{attrs['level']}"
    return f"for (int {k} = 0; {k} < {attrs['count']}; ++{k}) {{"


MAX_LOOP_COUNT = 255   # D3D9: rep/loop run at most 255 times (integer constant range)


def _check_loop(attrs: Mapping[str, Any]) -> None:
    count, level = attrs["count"], attrs["level"]
    if not (isinstance(count, int) and 0 <= count <= MAX_LOOP_COUNT):
        raise IRError(f"loop count must be an int in 0..{MAX_LOOP_COUNT}, got {count!r}")
    if not (isinstance(level, int) and level >= 0):
        raise IRError(f"loop level must be a non-negative int, got {level!r}")


def _glsl_merge(args: Sequence[str], attrs: Mapping[str, Any]) -> str:
    old, new = args
    parts = [f"{new if c in attrs['mask'] else old}.{c}" for c in COMPONENTS]
    return "vec4(" + ", ".join(parts) + ")"


def _elementwise(fn: Callable[..., np.ndarray]) -> Kernel:
    return lambda ctx, args, attrs: fn(*args)


def _with_attrs(fn: Callable[..., np.ndarray]) -> Kernel:
    return lambda ctx, args, attrs: fn(*args, attrs)


def _op(name: str, arity: int, kernel: Kernel, glsl: str | GlslFormat, doc: str,
        **extra: Any) -> OpInfo:
    return OpInfo(name, arity, kernel, glsl, doc, **extra)


def _pc(name: str, arity: int, kernel: Kernel, glsl: str | GlslFormat, doc: str,
        **extra: Any) -> OpInfo:
    """A per-component op row."""
    return OpInfo(name, arity, kernel, glsl, doc, per_component=True, **extra)


# -- demand rules and column forms (see OpInfo)

def _demand_xyz(wanted: frozenset, attrs: Mapping[str, Any], arity: int) -> tuple[frozenset, ...]:
    return ((_XYZ if wanted else frozenset()),) * arity          # dp3, crs: xyz only


def _demand_nrm(wanted: frozenset, attrs: Mapping[str, Any], arity: int) -> tuple[frozenset, ...]:
    return (_XYZ | wanted if wanted else frozenset(),)            # the length, and w if wanted


def _demand_swizzle(wanted: frozenset, attrs: Mapping[str, Any], arity: int
                    ) -> tuple[frozenset, ...]:
    return (frozenset(COMPONENTS.index(attrs["pattern"][i]) for i in wanted),)


def _demand_merge(wanted: frozenset, attrs: Mapping[str, Any], arity: int
                  ) -> tuple[frozenset, ...]:
    mask = frozenset(COMPONENTS.index(c) for c in attrs["mask"])
    return (wanted - mask, wanted & mask)


def _const_columns(value: tuple) -> Columns:
    shared: dict[float, np.ndarray] = {}
    return [shared.setdefault(v, np.array([v], np.float32)) for v in value]


def _columns_dot(four: bool) -> ColumnKernel:
    def run(ctx: Any, args: Sequence[Columns], attrs: Mapping[str, Any], wanted: frozenset
            ) -> Columns:
        dot = dot3_columns(args[0], args[1])
        if four:
            dot = dot + args[0][3] * args[1][3]
        return [dot] * 4                   # one column shared by the four components
    return run


def _batch_dot(four: bool):
    """Dot products of one vector with several one-row vectors (a matrix of uniforms, as
    m4x4 / m3x3 lower): each product and sum of `_columns_dot`, in its order, over a
    (G, N) array at once, so G dots cost one dot's calls."""
    size = 4 if four else 3

    def run(a: Columns, bs: Sequence[Columns]) -> list | None:
        if any(c is None or c.shape != (1,) for b in bs for c in b[:size]):
            return None                          # not all one row: each on its own
        rows = np.concatenate([c for b in bs for c in b[:size]]).reshape(len(bs), size)
        dot = a[0] * rows[:, 0:1] + a[1] * rows[:, 1:2] + a[2] * rows[:, 2:3]
        if four:
            dot = dot + a[3] * rows[:, 3:4]
        return [[row] * 4 for row in dot]      # each row one column shared by the four
    return run


def _columns_nrm(ctx: Any, args: Sequence[Columns], attrs: Mapping[str, Any],
                 wanted: frozenset) -> Columns:
    x = args[0]
    scale = nrm_scale(dot3_columns(x, x))
    return [x[i] * scale if i in wanted else None for i in range(4)]


def _columns_swizzle(ctx: Any, args: Sequence[Columns], attrs: Mapping[str, Any],
                     wanted: frozenset) -> Columns:
    return [args[0][COMPONENTS.index(c)] for c in attrs["pattern"]]


def _columns_merge(ctx: Any, args: Sequence[Columns], attrs: Mapping[str, Any],
                   wanted: frozenset) -> Columns:
    mask = attrs["mask"]
    return [args[1][i] if c in mask else args[0][i] for i, c in enumerate(COMPONENTS)]


_OP_ROWS = [
    _op("input", 0, lambda ctx, args, attrs: ctx.input(attrs["name"]),
        lambda args, attrs: attrs["name"], "the declared input `name`",
        attrs=(("name", REQUIRED),), check=_check_name, names_input=True,
        columns=lambda ctx, args, attrs, wanted: ctx.input_columns(attrs["name"])),
    _op("const", 0, lambda ctx, args, attrs: np.broadcast_to(
            np.array(attrs["value"], dtype=np.float32), (ctx.count, 4)),
        lambda args, attrs: _vec4(attrs["value"]), "a literal vec4",
        attrs=(("value", REQUIRED),), check=_check_const,
        columns=lambda ctx, args, attrs, wanted: _const_columns(attrs["value"])),
    _pc("add", 2, _elementwise(lambda a, b: a + b), "({0} + {1})", "a + b"),
    _pc("sub", 2, _elementwise(lambda a, b: a - b), "({0} - {1})", "a - b"),
    _pc("mul", 2, _elementwise(lambda a, b: a * b), "({0} * {1})", "a * b"),
    _pc("mad", 3, _elementwise(lambda a, b, c: a * b + c), "({0} * {1} + {2})", "a * b + c"),
    _pc("neg", 1, _elementwise(lambda a: -a), "(-{0})", "-a (the source negate modifier)"),
    _op("dp3", 2, _elementwise(lambda a, b: _replicate(_dot3(a, b))),
        "vec4(dot({0}.xyz, {1}.xyz))", "a.xyz . b.xyz, replicated to all four", demand=_demand_xyz,
        columns=_columns_dot(False), batch=_batch_dot(False)),
    _op("dp4", 2, _elementwise(lambda a, b: _replicate(_dot3(a, b) + a[:, 3] * b[:, 3])),
        "vec4(dot({0}, {1}))", "a . b, replicated to all four", columns=_columns_dot(True),
        batch=_batch_dot(True)),
    _pc("min", 2, _elementwise(np.minimum), "min({0}, {1})", "per-component minimum"),
    _pc("max", 2, _elementwise(np.maximum), "max({0}, {1})", "per-component maximum"),
    _pc("rcp", 1, _elementwise(_rcp),
        "mix(1.0 / {0}, vec4(" + _GLSL_INF + "), equal({0}, vec4(0.0)))",
        "1/a per component; 0 -> +inf (D3D rcp)"),
    _pc("rsq", 1, _elementwise(lambda a: 1 / np.sqrt(np.abs(a))),
        "mix(inversesqrt(abs({0})), vec4(" + _GLSL_INF + "), equal({0}, vec4(0.0)))",
        "1/sqrt(|a|) per component; 0 -> +inf (D3D rsq)"),
    _pc("exp2", 1, _elementwise(np.exp2), "exp2({0})", "2^a per component (D3D exp)"),
    _pc("log2", 1, _elementwise(lambda a: np.log2(np.abs(a))),
        "mix(log2(abs({0})), vec4(-" + _GLSL_INF + "), equal({0}, vec4(0.0)))",
        "log2(|a|) per component; 0 -> -inf (D3D log)"),
    _pc("pow", 2, _elementwise(lambda a, b: np.power(np.abs(a), b)),
        # GLSL leaves pow(0, b <= 0) undefined: spell out IEEE's 0^0 = 1 and 0^-y = +inf.
        "mix(pow(abs({0}), {1}), mix(vec4(" + _GLSL_INF + "), vec4(1.0), equal({1}, vec4(0.0))), "
        "bvec4(vec4(lessThanEqual({1}, vec4(0.0))) * vec4(equal({0}, vec4(0.0)))))",
        "|a|^b per component (D3D pow). IEEE pow at |a| = 0: 0^0 = 1, 0^-y = +inf"),
    _pc("frc", 1, _elementwise(lambda a: a - np.floor(a)), "fract({0})", "a - floor(a)"),
    _pc("abs", 1, _elementwise(np.abs), "abs({0})", "|a|"),
    _pc("sign", 1, _elementwise(np.sign), "sign({0})", "-1, 0 or 1 per component (D3D sgn)"),
    _pc("sin", 1, _elementwise(np.sin), "sin({0})", "sin(a) radians (for sincos)"),
    _pc("cos", 1, _elementwise(np.cos), "cos({0})", "cos(a) radians (for sincos)"),
    _pc("cmp", 3, _elementwise(lambda a, b, c: np.where(a >= 0, b, c)),
        "mix({2}, {1}, greaterThanEqual({0}, vec4(0.0)))", "per component a >= 0 ? b : c"),
    _pc("cnd", 3, _elementwise(lambda a, b, c: np.where(a > 0.5, b, c)),
        "mix({2}, {1}, greaterThan({0}, vec4(0.5)))",
        "per component a > 0.5 ? b : c (ps.1.1-1.3 lower r0.a with a 'wwww' swizzle)"),
    _pc("lrp", 3, _elementwise(lambda f, a, b: f * a + (1 - f) * b), "mix({2}, {1}, {0})",
        "f * a + (1 - f) * b"),
    _op("nrm", 1, _elementwise(_nrm),
        "({0} * (dot({0}.xyz, {0}.xyz) != 0.0 ? inversesqrt(dot({0}.xyz, {0}.xyz)) : "
        + glsl_float(FLT_MAX) + "))",
        "a * rsq(a.xyz . a.xyz): w is scaled too; zero xyz scales by FLT_MAX (D3D nrm)",
        demand=_demand_nrm, columns=_columns_nrm),
    _op("crs", 2, _elementwise(_crs), "vec4(cross({0}.xyz, {1}.xyz), 0.0)",
        "(a.xyz x b.xyz, 0)", demand=_demand_xyz),
    _pc("slt", 2, _elementwise(lambda a, b: (a < b).astype(np.float32)),
        "vec4(lessThan({0}, {1}))", "per component a < b ? 1 : 0"),
    _pc("sge", 2, _elementwise(lambda a, b: (a >= b).astype(np.float32)),
        "vec4(greaterThanEqual({0}, {1}))", "per component a >= b ? 1 : 0"),
    _op("swizzle", 1, _with_attrs(lambda a, attrs: _swizzle(a, attrs["pattern"])),
        lambda args, attrs: f"{args[0]}.{attrs['pattern']}", "a.pattern (4 of xyzw)",
        attrs=(("pattern", REQUIRED),), check=_check_pattern, demand=_demand_swizzle,
        columns=_columns_swizzle),
    _op("merge", 2, _with_attrs(lambda old, new, attrs: _merge(old, new, attrs["mask"])),
        _glsl_merge, "write-mask merge: new where `mask` names a component, else old",
        attrs=(("mask", REQUIRED),), check=_check_components("mask"), demand=_demand_merge,
        columns=_columns_merge),
    _pc("saturate", 1, _elementwise(lambda a: np.clip(a, np.float32(0), np.float32(1))),
        "clamp({0}, 0.0, 1.0)", "clamp to [0, 1]"),
    _pc("clamp", 1, _with_attrs(lambda a, attrs: np.clip(
            a, np.float32(attrs["lo"]), np.float32(attrs["hi"]))),
        lambda args, attrs: (f"clamp({args[0]}, {glsl_float(attrs['lo'])}, "
                             f"{glsl_float(attrs['hi'])})"),
        "clamp to [lo, hi] (register range of fixed-point hardware)",
        attrs=(("lo", REQUIRED), ("hi", REQUIRED)), check=_check_clamp),
    _pc("quantize", 1, _with_attrs(_quantize), _glsl_quantize,
        "clamp to [0, scale] (signed: [-scale, scale]) and round, halves away from zero, to "
        "multiples of scale / L, L = 2^bits - 1 (signed: 2^(bits-1) - 1). bits=8 is UNORM8 "
        "(0.5 -> 128/255); bits=9 signed is the GeForce3 combiner grid (steps of 1/255)",
        attrs=(("bits", REQUIRED), ("signed", False), ("scale", 1.0)),
        check=_check_quantize),
    _op("sample", 1, _sample, _glsl_sample,
        "texel of sampler `sampler` (a `kind` texture) at coord. proj: xyz / w first; bias: "
        "LOD bias coord.w; lod: explicit LOD coord.w (the only form a vertex program may use: "
        "vs_3_0 texldl). Unbound samplers read (0, 0, 0, 1)",
        check=_check_sample, names_sampler=True, needs_quads=True,
        attrs=(("sampler", REQUIRED), ("kind", "2d"), ("proj", False), ("bias", False),
               ("lod", False))),
    _op("ddx", 1, lambda ctx, args, attrs: ctx.derivative(args[0], 0), "dFdx({0})",
        "screen-space gradient of a along x (D3D dsx): the quad's right minus left pixel",
        needs_quads=True, stages=("fragment",)),
    _op("ddy", 1, lambda ctx, args, attrs: ctx.derivative(args[0], 1), "dFdy({0})",
        "screen-space gradient of a along y (D3D dsy; y grows downward): the quad's lower "
        "minus upper pixel", needs_quads=True, stages=("fragment",)),
    _op("var", 1, lambda ctx, args, attrs: args[0], "{0}",
        "a mutable variable, initially a (set by assign)", pure=False,
        columns=lambda ctx, args, attrs, wanted: list(args[0])),
    _op("assign", 2, _no_kernel, "{0} = {1};",
        "variable a = b (in the evaluator: in the fragments the current mask runs)",
        has_result=False, assigns=True),
    _op("if", 1, _no_kernel, "if ({0}.x != 0.0) {{", "run the block where a.x != 0",
        has_result=False, flow="open"),
    _op("else", 0, _no_kernel, "}} else {{", "run the block where the if's a.x == 0",
        has_result=False, flow="middle"),
    _op("endif", 0, _no_kernel, "}}", "end of the if block", has_result=False, flow="close"),
    _op("loop", 0, _no_kernel, _glsl_loop,
        "run the block `count` times (0..255); `level` is the loop nesting depth, which names "
        "the GLSL counter", has_result=False, flow="open", loop=True,
        attrs=(("count", REQUIRED), ("level", 0)), check=_check_loop),
    _op("endloop", 0, _no_kernel, "}}", "end of the loop block", has_result=False,
        flow="close", loop=True),
    _op("break", 1, _no_kernel, "if ({0}.x != 0.0) break;",
        "leave the innermost loop where a.x != 0", has_result=False, flow="exit"),
    _op("sample_grad", 3, _sample_grad, _glsl_sample_grad,
        "texel of sampler `sampler` at coord a, its LOD from the explicit screen gradients b "
        "(d coord / dx) and c (d coord / dy) (D3D texldd; for a cube map, gradients of the "
        "direction, carried onto the selected face as GL's textureGrad does)", names_sampler=True,
        attrs=(("sampler", REQUIRED), ("kind", "2d")), check=_check_sample_grad),
    _op("kill", 1, _kill, _glsl_kill,
        "discard the fragment where any of `components` is < 0 (texkill: ps.1.x tests xyz, "
        "ps.2.0 xyzw)", attrs=(("components", "xyzw"),),
        check=_check_components("components"), has_result=False, discards=True,
        stages=("fragment",)),
]
OPS: dict[str, OpInfo] = {row.name: row for row in _OP_ROWS}


# --------------------------------------------------------------------------------------------
# Checking


def normalize_attrs(op: str, attrs: Mapping[str, Any]) -> tuple[tuple[str, Any], ...]:
    """`attrs` in the op row's order with defaults filled in, checked."""
    info = _op_info(op)
    known = {name for name, _ in info.attrs}
    unknown = set(attrs) - known
    if unknown:
        raise IRError(f"{op} has no attribute(s) {sorted(unknown)}")
    pairs = []
    for name, default in info.attrs:
        if name in attrs:
            pairs.append((name, attrs[name]))
        elif default is REQUIRED:
            raise IRError(f"{op} needs attribute {name!r}")
        else:
            pairs.append((name, default))
    if info.check is not None:
        info.check(dict(pairs))
    return tuple(pairs)


def _op_info(op: str) -> OpInfo:
    try:
        return OPS[op]
    except KeyError:
        raise IRError(f"unknown op {op!r}") from None


def check_program(program: Program) -> None:
    """Raise IRError unless `program` is well formed: SSA (every value defined once, before
    use), arities and attributes as in OPS, inputs and samplers declared, outputs valid."""
    if program.stage not in STAGES:
        raise IRError(f"stage must be one of {STAGES}, got {program.stage!r}")
    inputs = {}
    for item in program.inputs:
        if not _IDENTIFIER.match(item.name) or item.name.startswith("gl_"):
            raise IRError(f"input name {item.name!r} is not a usable identifier")
        if item.kind not in INPUT_KINDS:
            raise IRError(f"input {item.name}: kind must be one of {INPUT_KINDS}")
        if not 1 <= item.components <= 4:
            raise IRError(f"input {item.name}: components must be 1..4")
        if item.name in inputs:
            raise IRError(f"input {item.name} declared twice")
        inputs[item.name] = item
    samplers = {}
    for binding in program.samplers:
        if binding.kind not in SAMPLER_KINDS or binding.index in samplers:
            raise IRError(f"bad or repeated sampler binding {binding}")
        samplers[binding.index] = binding
    defined: set[int] = set()
    variables: set[int] = set()
    blocks: list[tuple[OpInfo, set[int]]] = []     # open blocks and the values defined in them
    for instr in program.instrs:
        info = _op_info(instr.op)
        _check_structure(instr, info, blocks, defined)
        if len(instr.args) != info.arity:
            raise IRError(f"{instr.op} takes {info.arity} argument(s), got {len(instr.args)}")
        for arg in instr.args:
            if arg not in defined:
                raise IRError(f"{instr.op} uses %{arg} before it is defined")
        if normalize_attrs(instr.op, instr.attr_map) != instr.attrs:
            raise IRError(f"{instr.op}: attributes not in canonical form: {instr.attrs}")
        if info.names_input and instr.attr("name") not in inputs:
            raise IRError(f"input {instr.attr('name')!r} is not declared")
        if info.names_sampler:
            binding = samplers.get(instr.attr("sampler"))
            if binding is None or binding.kind != instr.attr("kind"):
                raise IRError(f"sampler {instr.attr('sampler')} is not declared as "
                              f"{instr.attr('kind')}")
        if program.stage not in info.stages:
            raise IRError(f"{instr.op} is only valid in {' and '.join(info.stages)} programs")
        if program.stage == "vertex" and info.needs_quads and not instr.attr_map.get("lod"):
            # a vertex has no neighbours to difference: its lookups name their LOD (texldl)
            raise IRError(f"{instr.op} in a vertex program needs an explicit lod")
        if info.has_result != (instr.dest is not None):
            raise IRError(f"{instr.op}: dest must be {'an id' if info.has_result else 'None'}")
        if info.assigns and instr.args[0] not in variables:
            raise IRError(f"assign to %{instr.args[0]}, which is not a var")
        if instr.dest is not None:
            if instr.dest in defined:
                raise IRError(f"%{instr.dest} defined twice")
            defined.add(instr.dest)
            if blocks:
                blocks[-1][1].add(instr.dest)
            if not info.pure:
                variables.add(instr.dest)
    if blocks:
        raise IRError(f"{blocks[-1][0].name} block is not closed")
    allowed = OUTPUTS[program.stage]
    names = [name for name, _ in program.outputs]
    if any(name not in allowed for name in names) or len(set(names)) != len(names):
        raise IRError(f"{program.stage} outputs must be distinct names from {allowed}: {names}")
    if names != sorted(names, key=allowed.index):
        raise IRError(f"outputs must be in the order {allowed}")
    for name, value in program.outputs:
        if value not in defined:
            raise IRError(f"output {name} uses undefined %{value}")


def _check_structure(instr: Instr, info: OpInfo, blocks: list, defined: set[int]) -> None:
    """Blocks nest (if [else] endif, loop endloop), break is inside a loop, and a value defined
    inside a block is not used once the block (or its if-half) is closed."""
    if info.flow in ("middle", "close"):
        if not blocks or blocks[-1][0].loop != info.loop or (
                info.flow == "middle" and blocks[-1][0].flow != "open"):
            raise IRError(f"{instr.op} without its opening instruction")
        opened, inside = blocks.pop()
        defined -= inside                          # out of scope
        if info.flow == "middle":
            blocks.append((info, set()))
    if info.flow == "exit" and not any(b[0].loop for b in blocks):
        raise IRError(f"{instr.op} outside a loop")
    if info.flow == "open":
        blocks.append((info, set()))


def has_flow(program: Program) -> bool:
    """Whether the program has control flow or variables (so it is not straight-line)."""
    return any(OPS[i.op].flow or not OPS[i.op].pure for i in program.instrs)


# --------------------------------------------------------------------------------------------
# Builder


_SWIZZLE_ALIASES = str.maketrans("rgba", "xyzw")


def normalize_swizzle(pattern: str) -> str:
    """'rgba' letters read as xyzw; fewer than 4 components repeat the last (D3D rule)."""
    pattern = pattern.lower().translate(_SWIZZLE_ALIASES)
    if not 1 <= len(pattern) <= 4 or not set(pattern) <= set(COMPONENTS):
        raise IRError(f"bad swizzle {pattern!r}")
    return pattern + pattern[-1] * (4 - len(pattern))


def normalize_mask(mask: str) -> str:
    mask = mask.lower().translate(_SWIZZLE_ALIASES)
    if not mask or not _is_ordered_subset(mask):
        raise IRError(f"bad write mask {mask!r}")
    return mask


class Builder:
    """Builds a Program one op at a time. Identical pure instructions (equal constants included)
    are emitted once; identity swizzles and full-mask merges emit nothing."""

    def __init__(self, stage: str) -> None:
        if stage not in STAGES:
            raise IRError(f"stage must be one of {STAGES}, got {stage!r}")
        self.stage = stage
        self._inputs: dict[str, Input] = {}
        self._samplers: dict[int, SamplerBinding] = {}
        self._instrs: list[Instr] = []
        self._known: dict[tuple, int] = {}
        self._outputs: dict[str, int] = {}
        self._count = 0
        # Control flow: values that read a variable are never shared (the variable changes);
        # values first made inside a block are forgotten when it closes (out of scope).
        self._variable_dependent: set[int] = set()
        self._scopes: list[list[tuple]] = []
        self._loops = 0
        self.clamp_colors = True        # see Program.clamp_colors
        self.renumbered: dict[int, int] = {}   # set by build

    # -- the generic entry point
    def emit(self, op: str, *args: int, **attrs: Any) -> int | None:
        info = _op_info(op)
        if len(args) != info.arity:
            raise IRError(f"{op} takes {info.arity} argument(s), got {len(args)}")
        for arg in args:
            if not isinstance(arg, int) or not 0 <= arg < self._next_id():
                raise IRError(f"{op}: {arg!r} is not a value of this builder")
        canonical = normalize_attrs(op, attrs)
        if not info.has_result:
            self._instrs.append(Instr(None, op, tuple(args), canonical))
            self._flow(info)
            return None
        key = (op, tuple(args), canonical)
        if key in self._known:
            return self._known[key]
        dest = self._count
        self._count += 1
        self._instrs.append(Instr(dest, op, tuple(args), canonical))
        if not info.pure or any(a in self._variable_dependent for a in args):
            self._variable_dependent.add(dest)
        else:
            self._known[key] = dest
            if self._scopes:
                self._scopes[-1].append(key)
        return dest

    @classmethod
    def resume(cls, program: Program) -> "Builder":
        """A builder holding `program`'s inputs, samplers, instructions and outputs, to append
        to (fixed-function fog blended after a pixel shader's colour). Its values keep their
        numbers; nothing emitted before is shared with what is emitted next."""
        b = cls(program.stage)
        b._inputs = {i.name: i for i in program.inputs}
        b._samplers = {s.index: s for s in program.samplers}
        b._instrs = list(program.instrs)
        b._count = 1 + max((i.dest for i in program.instrs if i.dest is not None), default=-1)
        b._outputs = dict(program.outputs)
        b.clamp_colors = program.clamp_colors
        return b

    def _flow(self, info: OpInfo) -> None:
        if info.flow in ("middle", "close"):
            if not self._scopes:
                raise IRError(f"{info.name} without its opening instruction")
            for key in self._scopes.pop():
                self._known.pop(key, None)
            self._loops -= 1 if info.flow == "close" and info.loop else 0
        if info.flow in ("open", "middle"):
            self._scopes.append([])
            self._loops += 1 if info.flow == "open" and info.loop else 0

    def _next_id(self) -> int:
        return self._count

    # -- values from outside
    def input(self, name: str, kind: str = "varying", semantic: str = "",
              components: int = 4) -> int:
        declared = Input(name, kind, semantic, components)
        if self._inputs.setdefault(name, declared) != declared:
            raise IRError(f"input {name} redeclared as {declared} (was {self._inputs[name]})")
        return self.emit("input", name=name)

    def varying(self, name: str, semantic: str = "", components: int = 4) -> int:
        return self.input(name, "varying", semantic, components)

    def uniform(self, name: str, semantic: str = "") -> int:
        return self.input(name, "uniform", semantic)

    def builtin(self, name: str) -> int:
        return self.input(name, "builtin")

    def const(self, value: float | Sequence[float]) -> int:
        values = [value] * 4 if np.isscalar(value) else list(value)
        if len(values) != 4:
            raise IRError(f"const needs 1 or 4 components, got {value!r}")
        # Round to float32 first so values that are equal on the device deduplicate.
        return self.emit("const", value=tuple(float(np.float32(v)) for v in values))

    # -- arithmetic
    def add(self, a: int, b: int) -> int: return self.emit("add", a, b)
    def sub(self, a: int, b: int) -> int: return self.emit("sub", a, b)
    def mul(self, a: int, b: int) -> int: return self.emit("mul", a, b)
    def mad(self, a: int, b: int, c: int) -> int: return self.emit("mad", a, b, c)
    def neg(self, a: int) -> int: return self.emit("neg", a)
    def dp3(self, a: int, b: int) -> int: return self.emit("dp3", a, b)
    def dp4(self, a: int, b: int) -> int: return self.emit("dp4", a, b)
    def min(self, a: int, b: int) -> int: return self.emit("min", a, b)
    def max(self, a: int, b: int) -> int: return self.emit("max", a, b)
    def rcp(self, a: int) -> int: return self.emit("rcp", a)
    def rsq(self, a: int) -> int: return self.emit("rsq", a)
    def exp2(self, a: int) -> int: return self.emit("exp2", a)
    def log2(self, a: int) -> int: return self.emit("log2", a)
    def pow(self, a: int, b: int) -> int: return self.emit("pow", a, b)
    def frc(self, a: int) -> int: return self.emit("frc", a)
    def abs(self, a: int) -> int: return self.emit("abs", a)
    def sin(self, a: int) -> int: return self.emit("sin", a)
    def cos(self, a: int) -> int: return self.emit("cos", a)
    def cmp(self, a: int, b: int, c: int) -> int: return self.emit("cmp", a, b, c)
    def cnd(self, a: int, b: int, c: int) -> int: return self.emit("cnd", a, b, c)
    def lrp(self, f: int, a: int, b: int) -> int: return self.emit("lrp", f, a, b)
    def nrm(self, a: int) -> int: return self.emit("nrm", a)
    def crs(self, a: int, b: int) -> int: return self.emit("crs", a, b)
    def slt(self, a: int, b: int) -> int: return self.emit("slt", a, b)
    def sge(self, a: int, b: int) -> int: return self.emit("sge", a, b)

    # -- moves and precision
    def swizzle(self, a: int, pattern: str) -> int:
        pattern = normalize_swizzle(pattern)
        return a if pattern == COMPONENTS else self.emit("swizzle", a, pattern=pattern)

    def merge(self, old: int, new: int, mask: str) -> int:
        mask = normalize_mask(mask)
        return new if mask == COMPONENTS else self.emit("merge", old, new, mask=mask)

    def saturate(self, a: int) -> int: return self.emit("saturate", a)

    def clamp(self, a: int, lo: float, hi: float) -> int:
        return self.emit("clamp", a, lo=float(lo), hi=float(hi))

    def quantize(self, a: int, bits: int, signed: bool = False, scale: float = 1.0) -> int:
        return self.emit("quantize", a, bits=bits, signed=bool(signed), scale=float(scale))

    # -- textures and effects
    def sample(self, sampler: int, coord: int, kind: str = "2d", proj: bool = False,
               bias: bool = False, lod: bool = False) -> int:
        binding = SamplerBinding(sampler, kind)
        if self._samplers.setdefault(sampler, binding) != binding:
            raise IRError(f"sampler {sampler} used as {kind} and {self._samplers[sampler].kind}")
        return self.emit("sample", coord, sampler=sampler, kind=kind, proj=bool(proj),
                         bias=bool(bias), lod=bool(lod))

    # -- variables and structured control flow
    def var(self, init: int) -> int:
        return self.emit("var", init)

    def assign(self, variable: int, value: int) -> None:
        if variable != value:
            self.emit("assign", variable, value)

    def if_(self, cond: int) -> None: self.emit("if", cond)
    def else_(self) -> None: self.emit("else")
    def endif(self) -> None: self.emit("endif")

    def loop(self, count: int) -> None:
        self.emit("loop", count=int(min(max(count, 0), MAX_LOOP_COUNT)), level=self._loops)

    def endloop(self) -> None: self.emit("endloop")
    def break_(self, cond: int) -> None: self.emit("break", cond)

    def sample_grad(self, sampler: int, coord: int, ddx: int, ddy: int, kind: str = "2d"
                    ) -> int:
        binding = SamplerBinding(sampler, kind)
        if self._samplers.setdefault(sampler, binding) != binding:
            raise IRError(f"sampler {sampler} used as {kind} and {self._samplers[sampler].kind}")
        return self.emit("sample_grad", coord, ddx, ddy, sampler=sampler, kind=kind)

    def kill(self, a: int, components: str = "xyzw") -> None:
        if self.stage != "fragment":
            raise IRError("kill is only valid in fragment programs")
        self.emit("kill", a, components=normalize_mask(components))

    def output(self, name: str, value: int) -> None:
        if name not in OUTPUTS[self.stage]:
            raise IRError(f"{name!r} is not a {self.stage} output ({OUTPUTS[self.stage]})")
        self._outputs[name] = value

    def output_value(self, name: str) -> int:
        """The value output `name` was given (a resumed program's)."""
        if name not in self._outputs:
            raise IRError(f"the program has no {name!r} output")
        return self._outputs[name]

    def build(self, prune: bool = True) -> Program:
        """The program. `prune` drops instructions no output or kill needs (and the inputs and
        samplers only they used) and renumbers values densely in order; `renumbered` then maps
        each kept value of the builder to its number in the program (a lowering that names a
        value to a back end, as `PassProgram.lighting` does, names it by that number)."""
        order = OUTPUTS[self.stage]
        outputs = sorted(self._outputs.items(), key=lambda item: order.index(item[0]))
        instrs = self._instrs
        if prune:
            instrs, outputs, self.renumbered = _prune(instrs, outputs)
        else:
            self.renumbered = {i.dest: i.dest for i in instrs if i.dest is not None}
        used_inputs = {i.attr("name") for i in instrs if OPS[i.op].names_input}
        used_samplers = {i.attr("sampler") for i in instrs if OPS[i.op].names_sampler}
        return Program(
            stage=self.stage,
            inputs=tuple(v for k, v in self._inputs.items() if k in used_inputs),
            instrs=tuple(instrs),
            outputs=tuple(outputs),
            samplers=tuple(self._samplers[i] for i in sorted(used_samplers)),
            clamp_colors=self.clamp_colors)


def _prune(instrs: list[Instr], outputs: list[tuple[str, int]]
           ) -> tuple[list[Instr], list[tuple[str, int]], dict[int, int]]:
    live = {value for _, value in outputs}
    kept = []
    for instr in reversed(instrs):
        if instr.dest is None or instr.dest in live:
            kept.append(instr)
            live.update(instr.args)
    kept.reverse()
    renumber = {instr.dest: n for n, instr in enumerate(i for i in kept if i.dest is not None)}
    renumbered = [Instr(None if i.dest is None else renumber[i.dest], i.op,
                        tuple(renumber[a] for a in i.args), i.attrs) for i in kept]
    return renumbered, [(name, renumber[value]) for name, value in outputs], renumber


# --------------------------------------------------------------------------------------------
# Printer


def _format_attr(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return glsl_float(value)
    if isinstance(value, tuple):
        return "(" + ", ".join(_format_attr(v) for v in value) + ")"
    return str(value)


def format_instr(instr: Instr) -> str:
    """One instruction as text: `%3 = mad %0, %1, %2`, attributes that differ from their
    defaults after the arguments (`sampler=0 kind=cube`)."""
    info = _op_info(instr.op)
    defaults = dict(info.attrs)
    if instr.op == "input":
        operands = [instr.attr("name")]
    elif instr.op == "const":
        operands = [_format_attr(instr.attr("value"))]
    else:
        operands = [", ".join(f"%{a}" for a in instr.args)] if instr.args else []
        operands += [f"{k}={_format_attr(v)}" for k, v in instr.attrs
                     if defaults[k] is REQUIRED or v != defaults[k]]
    text = " ".join([instr.op, *operands])
    return text if instr.dest is None else f"%{instr.dest} = {text}"


def format_program(program: Program) -> str:
    """Readable, stable text for golden tests: header, declarations, body, outputs."""
    lines = [f"{program.stage} program"]
    if not program.clamp_colors:
        lines.append("colors unclamped")
    for item in program.inputs:
        extra = [f"semantic={item.semantic}"] if item.semantic else []
        extra += [f"components={item.components}"] if item.components != 4 else []
        lines.append(" ".join([f"input {item.name}: {item.kind}", *extra]))
    lines += [f"sampler {s.index}: {s.kind}" for s in program.samplers]
    lines += [format_instr(instr) for instr in program.instrs]
    lines += [f"output {name} = %{value}" for name, value in program.outputs]
    return "\n".join(lines) + "\n"
