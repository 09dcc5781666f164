"""The Direct3D texture-stage vocabulary that validation and lowering share: the D3DTA_*
argument selectors and modifiers, the D3DTTFF_* flags, the D3DTSS_TCI_* texgen modes and the
stage count (each named here from its row in `effects.d3d9.states`, where it is defined once), and
one row per D3DTOP
(`STAGE_OPS`): the caps bit that validation checks, the arguments it reads (for the
missing-texture rule), whether it samples its texture without a TEXTURE argument, and its
formula over vec4 IR values (docs/reference/semantics.md section 1).

A formula takes the cascade being lowered (`effects.lower.stages`; it offers `.b`, the IR
builder, and the stage's `diffuse`, `current`, `texture()` and `tfactor()` values) and the
three argument values.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Mapping, Protocol

from effects.program.ir import Builder
from effects.d3d9.states import (D3DTA, D3DTEXTURETRANSFORMFLAGS, D3DTSS_TCI, MAX_SAMPLERS, MAX_STAGES,  # noqa: F401 (re-exported)
                            TCI_SHIFT)


class Cascade(Protocol):
    """What a formula reads of the stage being lowered (`effects.lower.stages._Cascade`)."""

    b: Builder
    diffuse: int
    current: int

    def texture(self) -> int: ...

    def tfactor(self) -> int: ...


# D3DTA_* selectors and modifier flags (the D3DTA enum table); D3DTA_SELECTMASK has no name
# of its own in an effect file, so it is defined here.
(TA_DIFFUSE, TA_CURRENT, TA_TEXTURE, TA_TFACTOR, TA_SPECULAR, TA_TEMP,
 TA_CONSTANT) = (D3DTA.values[n] for n in ("DIFFUSE", "CURRENT", "TEXTURE", "TFACTOR",
                                           "SPECULAR", "TEMP", "CONSTANT"))
TA_COMPLEMENT = D3DTA.values["COMPLEMENT"]
TA_ALPHAREPLICATE = D3DTA.values["ALPHAREPLICATE"]
TA_SELECTMASK = 0x0F
# D3DTTFF_*: the coordinate count in the low byte, PROJECTED above it.
TTFF_COUNT_MASK = 0xFF
TTFF_PROJECTED = D3DTEXTURETRANSFORMFLAGS.values["PROJECTED"]
# D3DTSS_TCI_*: the texgen mode in TexCoordIndex's high word, the coordinate set below it.
TCI_SET_MASK = (1 << TCI_SHIFT) - 1
TCI_MODES: Mapping[int, str] = {value >> TCI_SHIFT: name for name, value in D3DTSS_TCI.values.items()}
# The camera-space modes: with three coordinates they are the fixed-function cube lookups.
TCI_CAMERA_SPACE = frozenset(code for code, name in TCI_MODES.items()
                             if name.startswith("CAMERASPACE"))

Value = int  # an IR value id


@dataclass(frozen=True)
class StageOp:
    """One D3DTOP row. `args` are the argument numbers the op reads (0 = ARG0); `samples`
    means it reads this stage's texture without a TEXTURE argument (its alpha)."""

    name: str
    cap: str
    args: tuple[int, ...]
    formula: Callable[["Cascade", tuple[Value, Value, Value]], Value] | None
    samples: bool = False


def _sat(c: "Cascade", v: Value) -> Value:
    return c.b.saturate(v)


def _k(c: "Cascade", x: float) -> Value:
    return c.b.const(x)


def alpha_replicate(c: "Cascade", v: Value) -> Value:
    return c.b.swizzle(v, "wwww")


def complement(c: "Cascade", v: Value) -> Value:
    return c.b.sub(_k(c, 1.0), v)


def _blend(factor: Callable[["Cascade"], Value]):
    # Arg1 * F + Arg2 * (1 - F): inputs in range, so no saturate (semantics 1.4).
    return lambda c, a: c.b.lrp(alpha_replicate(c, factor(c)), a[1], a[2])


def _dot3(c: "Cascade", a: tuple[Value, Value, Value]) -> Value:
    half = _k(c, 0.5)
    d = c.b.dp3(c.b.sub(a[1], half), c.b.sub(a[2], half))
    return _sat(c, c.b.mul(d, _k(c, 4.0)))


_12 = (1, 2)
_OP_ROWS = (
    StageOp("SELECTARG1", "SELECTARG1", (1,), lambda c, a: a[1]),
    StageOp("SELECTARG2", "SELECTARG2", (2,), lambda c, a: a[2]),
    StageOp("MODULATE", "MODULATE", _12, lambda c, a: c.b.mul(a[1], a[2])),
    StageOp("MODULATE2X", "MODULATE2X", _12,
            lambda c, a: _sat(c, c.b.mul(c.b.mul(a[1], a[2]), _k(c, 2.0)))),
    StageOp("MODULATE4X", "MODULATE4X", _12,
            lambda c, a: _sat(c, c.b.mul(c.b.mul(a[1], a[2]), _k(c, 4.0)))),
    StageOp("ADD", "ADD", _12, lambda c, a: _sat(c, c.b.add(a[1], a[2]))),
    StageOp("ADDSIGNED", "ADDSIGNED", _12,
            lambda c, a: _sat(c, c.b.sub(c.b.add(a[1], a[2]), _k(c, 0.5)))),
    StageOp("ADDSIGNED2X", "ADDSIGNED2X", _12, lambda c, a: _sat(c, c.b.mul(
        c.b.sub(c.b.add(a[1], a[2]), _k(c, 0.5)), _k(c, 2.0)))),
    StageOp("SUBTRACT", "SUBTRACT", _12, lambda c, a: _sat(c, c.b.sub(a[1], a[2]))),
    # Arg1 + Arg2 - Arg1*Arg2 = Arg1 + (1 - Arg1) * Arg2
    StageOp("ADDSMOOTH", "ADDSMOOTH", _12,
            lambda c, a: _sat(c, c.b.mad(complement(c, a[1]), a[2], a[1]))),
    StageOp("BLENDDIFFUSEALPHA", "BLENDDIFFUSEALPHA", _12, _blend(lambda c: c.diffuse)),
    StageOp("BLENDTEXTUREALPHA", "BLENDTEXTUREALPHA", _12, _blend(lambda c: c.texture()),
            samples=True),
    StageOp("BLENDFACTORALPHA", "BLENDFACTORALPHA", _12, _blend(lambda c: c.tfactor())),
    StageOp("BLENDTEXTUREALPHAPM", "BLENDTEXTUREALPHAPM", _12, lambda c, a: _sat(
        c, c.b.mad(a[2], complement(c, alpha_replicate(c, c.texture())), a[1])), samples=True),
    StageOp("BLENDCURRENTALPHA", "BLENDCURRENTALPHA", _12, _blend(lambda c: c.current)),
    StageOp("PREMODULATE", "PREMODULATE", _12, lambda c, a: a[1]),
    StageOp("MODULATEALPHA_ADDCOLOR", "MODULATEALPHA_ADDCOLOR", _12,
            lambda c, a: _sat(c, c.b.mad(alpha_replicate(c, a[1]), a[2], a[1]))),
    StageOp("MODULATECOLOR_ADDALPHA", "MODULATECOLOR_ADDALPHA", _12,
            lambda c, a: _sat(c, c.b.mad(a[1], a[2], alpha_replicate(c, a[1])))),
    StageOp("MODULATEINVALPHA_ADDCOLOR", "MODULATEINVALPHA_ADDCOLOR", _12,
            lambda c, a: _sat(c, c.b.mad(complement(c, alpha_replicate(c, a[1])), a[2], a[1]))),
    StageOp("MODULATEINVCOLOR_ADDALPHA", "MODULATEINVCOLOR_ADDALPHA", _12,
            lambda c, a: _sat(c, c.b.mad(complement(c, a[1]), a[2], alpha_replicate(c, a[1])))),
    # The bump ops output nothing (handled by the cascade); they sample their own texture.
    StageOp("BUMPENVMAP", "BUMPENVMAP", _12, None, samples=True),
    StageOp("BUMPENVMAPLUMINANCE", "BUMPENVMAPLUMINANCE", _12, None, samples=True),
    StageOp("DOTPRODUCT3", "DOTPRODUCT3", _12, _dot3),
    StageOp("MULTIPLYADD", "MULTIPLYADD", (0, 1, 2),
            lambda c, a: _sat(c, c.b.mad(a[1], a[2], a[0]))),
    StageOp("LERP", "LERP", (0, 1, 2), lambda c, a: c.b.lrp(a[0], a[1], a[2])),
)
STAGE_OPS: Mapping[str, StageOp] = {row.name: row for row in _OP_ROWS}
BUMP_OPS = ("BUMPENVMAP", "BUMPENVMAPLUMINANCE")
