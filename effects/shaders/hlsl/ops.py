"""The DAG's operations, one row each: how the code generator emits the op and whether the
compiler may fold it. dag.py (what folds, what never does) and codegen.py (how a node becomes
an instruction) read these rows instead of keeping sets of op names of their own; the fold
kernels (argument and result widths) are folding.FOLDS's rows, built on the IR's kernels.

Shapes:
- `lanes`: component-wise, one instruction whose lane L reads lane L of each source (add,
  mul, mad, cmp, lrp, mov ...); its result lanes can be placed anywhere;
- `scalar`: one replicated result from one component of each source (rcp, rsq, exp, log,
  pow), a lane of any register;
- `reduce`: one result from the first `reads` lanes of two sources (dp3, dp4, dp2add);
- `shaped`: whole-register operands and results (crs, nrm, sincos, lit);
- `texture`: a sampler read, emitted as `mnemonic` with the sampler;
- `leaf` / `flow`: registers the code generator places (inputs, uniforms, constants, packs,
  loop and branch values) and the flow control it emits (flowcode.py).

`ps1_lacks`: what ps_1_1-1_4 have no instruction for, as the X4532 refusal names it
(codegen_ps1.py, ps1_analysis.py); ps_1_x emits the other `lanes` rows component-wise.

`fxlc`: the op of one lane (of the first lane of each argument, for `scalar` rows) as scalar
FXLC preshader instructions (fxlc_compile.py, which writes `FogDensity = a * 3` into fx_2_0):
steps of (FXLC op, operands), an operand an argument's position, "prev" the step before, or a
number (a literal); the last step's result is the op's. None: FXLC has no form of it (a
`reduce` row is written as its products and sums).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

from effects.shaders.hlsl.folding import FOLDS


@dataclass(frozen=True)
class OpRow:
    name: str
    shape: str
    mnemonic: str | None = None      # the instruction it is emitted as ('sat': mov_sat)
    reads: int = 0                    # reduce: lanes read of each of its two vector sources
    opaque: bool = False              # never folded, even over constants (reads, side effects)
    ps1_lacks: str | None = None      # ps_1_x has no instruction for it: what X4532 names
    fxlc: tuple | None = None         # its FXLC steps (see the module's note)

    @property
    def folds(self) -> bool:
        """Whether the compiler computes it over constants (folding.fold)."""
        return not self.opaque and self.name in FOLDS


def _rows(shape: str, names: str, **kw) -> list[OpRow]:
    return [OpRow(n, shape, kw.pop("mnemonic", None) or (n if shape != "leaf" else None),
                  **kw) for n in names.split()]


OPS: dict[str, OpRow] = {row.name: row for row in [
    *_rows("lanes", "add mul mad min max frc abs cmp cnd lrp slt sge mov"),
    OpRow("sat", "lanes", "mov"),                            # mov_sat
    *_rows("lanes", "dsx dsy", opaque=True),                 # gradients: never constant
    *_rows("scalar", "rcp rsq exp log pow"),
    OpRow("dp3", "reduce", "dp3", reads=3),
    OpRow("dp4", "reduce", "dp4", reads=4),
    OpRow("dp2add", "reduce", "dp2add", reads=2),
    *_rows("shaped", "crs nrm sincos lit dst"),
    OpRow("tex", "texture", "texld", opaque=True),
    *[OpRow(n, "texture", n, opaque=True) for n in ("texldp", "texldb", "texldl", "texldd")],
    OpRow("const", "leaf"),
    *[OpRow(n, "leaf", opaque=True) for n in
      ("input", "uniform", "uniform_rel", "uniform_al", "pack", "phi")],
    *[OpRow(n, "flow", opaque=True) for n in ("kill", "loop", "loop_out", "if", "if_out")],
]}

_EQUALITY = "equality test (cnd orders values only; == and != need cmp, ps_1_2)"
for _name, _lacks in {
    "rcp": "per-pixel division or sqrt (rcp)", "rsq": "normalize, length or rsqrt (rsq)",
    "nrm": "normalize (nrm)", "exp": "exp/exp2 (exp)", "log": "log/log2 (log)",
    "pow": "pow of a non-constant exponent", "frc": "frac/floor/fmod (frc)",
    "min": "min (or a clamp/comparison built on it)",
    "max": "max (or a clamp/comparison built on it)", "abs": "abs",
    "slt": _EQUALITY, "sge": _EQUALITY, "dsx": "ddx", "dsy": "ddy", "crs": "cross (crs)",
    "sincos": "sin/cos", "dp2add": "dp2add", "texldp": "tex2Dproj", "texldb": "tex2Dbias",
    "texldl": "tex2Dlod", "texldd": "tex2Dgrad",
}.items():
    OPS[_name] = replace(OPS[_name], ps1_lacks=_lacks)


# FXLC lacks mad, abs, saturate, lrp, cnd and pow: each is built from the ops it has
for _name, _steps in {
    "add": (("add", (0, 1)),), "mul": (("mul", (0, 1)),), "min": (("min", (0, 1)),),
    "max": (("max", (0, 1)),), "mov": (("mov", (0,)),), "frc": (("frc", (0,)),),
    "slt": (("lt", (0, 1)),), "sge": (("ge", (0, 1)),), "cmp": (("cmp", (0, 1, 2)),),
    "mad": (("mul", (0, 1)), ("add", ("prev", 2))),
    "abs": (("neg", (0,)), ("max", (0, "prev"))),
    "sat": (("max", (0, 0.0)), ("min", ("prev", 1.0))),
    # lrp(a, b, c) = a * (b - c) + c
    "lrp": (("neg", (2,)), ("add", (1, "prev")), ("mul", (0, "prev")), ("add", ("prev", 2))),
    # cnd(a, b, c) = a > 0.5 ? b : c = cmp(0.5 - a, c, b)
    "cnd": (("neg", (0,)), ("add", ("prev", 0.5)), ("cmp", ("prev", 2, 1))),
    "rcp": (("rcp", (0,)),), "rsq": (("rsq", (0,)),), "exp": (("exp", (0,)),),
    "log": (("log", (0,)),),
    "pow": (("log", (0,)), ("mul", ("prev", 1)), ("exp", ("prev",))),
}.items():
    OPS[_name] = replace(OPS[_name], fxlc=_steps)


def shaped(op: str) -> bool:
    return op in OPS and OPS[op].shape == "shaped"


def ops_of(shape: str) -> frozenset[str]:
    return frozenset(n for n, row in OPS.items() if row.shape == shape)


LANEWISE = ops_of("lanes")
SCALAR = ops_of("scalar")
REDUCE = {n: row.reads for n, row in OPS.items() if row.shape == "reduce"}
TEXTURE = {n: row.mnemonic for n, row in OPS.items() if row.shape == "texture"}
OPAQUE = frozenset(n for n, row in OPS.items() if row.opaque)
PS1_LACKS = {n: row.ps1_lacks for n, row in OPS.items() if row.ps1_lacks}
PS1_LANEWISE = frozenset(n for n in LANEWISE if n not in PS1_LACKS)
