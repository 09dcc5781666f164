"""Lowering options derived from a caps profile: how values are held on the simulated card.

The profile chooses the precision; the lowering makes it explicit in the IR (saturate, clamp,
quantize); back ends never look at a profile (STYLE 2, after Mesa's
`nir_shader_compiler_options`). The fixed-function stage lowering and the shader-assembly
lowering both read the same `LoweringOptions`.

Derivation (`lowering_options`):
- A profile's `Precision` entry for a model (`fixed_function`, `ps_1_x`, `ps_1_4`, `ps_2_0`)
  wins: `{format: fixed, bits: N, range: R}` quantises to N bits in [-R, R] ([0, R] when
  unsigned); fp16 / fp24 / fp32 is float.
- Otherwise the generation decides: dx6 to dx8.1 cards hold fixed-function stage results at
  8 bits (the 8-bit colour combiners of the period); dx9 cards compute in float. Shader models
  without an entry run in float with no clamp (docs/reference/semantics.md 2.1 decision: fp32,
  Wine and DXVK behaviour). Nothing here looks at a profile's name: exact float pipelines
  (`refrast`, `modern`) say fp32 in their own Precision entries.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # pragma: no cover
    from effects.d3d9.caps import CapsProfile, Precision

# Generations whose fixed-function colour path is fixed point (stage results at 8 bits).
FIXED_POINT_GENERATIONS = ("dx6", "dx7", "dx8", "dx8.1")
DEFAULT_STAGE_BITS = 8


@dataclass(frozen=True)
class LoweringOptions:
    """How lowered programs hold values. None for a `*_bits` field means float (no
    quantisation).

    stage_bits      fixed-function texture stages: each stage result (and the specular add and
                    fog after the cascade) is quantised to this many bits, unsigned, in [0, 1].
                    Stage results are saturated to [0, 1] by the op table either way.
    ps1x_bits       ps_1_1-1_3: fraction bits each instruction result is held at.
    ps1x_signed     whether that grid is signed ([-range, range]) or unsigned ([0, range]).
    ps14_signed     as ps1x_signed, for ps_1_4.
    ps1x_range      ps_1_1-1_3 register range: results clamp to [-range, range] after each
                    instruction. None = no clamp (float pipeline).
    ps14_bits       as ps1x_bits, for ps_1_4.
    ps14_range      as ps1x_range, for ps_1_4 (at least 8 on real ps_1_4 hardware).
    ps20_float      'fp16' | 'fp24' | 'fp32': ps_2_0 arithmetic precision. Only fp32 is
                    modelled by the IR today; the field lets a lowering round to fp16 / fp24.
    constant_range  ps_1_x float constants (c#, def) clamp to [-constant_range,
                    constant_range] on every card (docs/reference/semantics.md 2.1: clamped
                    to [-1, 1]).
    """

    stage_bits: int | None = None
    ps1x_bits: int | None = None
    ps1x_signed: bool = True
    ps1x_range: float | None = None
    ps14_bits: int | None = None
    ps14_range: float | None = None
    ps14_signed: bool = True
    ps20_float: str = "fp32"
    constant_range: float = 1.0

    @property
    def stage_is_fixed(self) -> bool:
        return self.stage_bits is not None

    def register_grid(self, model: str) -> tuple[float | None, tuple[int, bool, float] | None]:
        """Where a `ps_1_x` or `ps_1_4` register write lands: (range, grid). `range` is the
        clamp bound (None: no clamp); `grid` is `Builder.quantize`'s (bits, signed, scale), or
        None for float. `*_bits` are fraction bits; the IR's grid needs the sign and the
        integer bits too: bits = fraction + ceil(log2(range)) + sign, so GeForce3's 8 fraction
        bits in [-1, 1] give quantize(bits=9, signed=True, scale=1)."""
        bits, rng, signed = {"ps_1_x": (self.ps1x_bits, self.ps1x_range, self.ps1x_signed),
                             "ps_1_4": (self.ps14_bits, self.ps14_range, self.ps14_signed)}[model]
        if bits is None:
            return rng, None
        scale = rng or 1.0
        integer_bits = max(0, math.ceil(math.log2(scale)))
        return rng, (bits + integer_bits + (1 if signed else 0), bool(signed), float(scale))


FLOAT_OPTIONS = LoweringOptions()


def lowering_options(profile: "CapsProfile") -> LoweringOptions:
    """The lowering options a profile implies (see the module docstring)."""
    ff = _precision(profile, "fixed_function")
    if ff is not None:
        stage_bits = None if ff.is_float else (ff.bits or DEFAULT_STAGE_BITS)
    else:
        stage_bits = DEFAULT_STAGE_BITS if profile.generation in FIXED_POINT_GENERATIONS else None
    ps1x = _precision(profile, "ps_1_x")
    ps14 = _precision(profile, "ps_1_4") or ps1x
    ps20 = _precision(profile, "ps_2_0")
    return LoweringOptions(
        stage_bits=stage_bits,
        ps1x_bits=_fixed_bits(ps1x),
        ps1x_signed=True if ps1x is None else bool(ps1x.signed),
        ps1x_range=_fixed_range(ps1x),
        ps14_bits=_fixed_bits(ps14),
        ps14_range=_fixed_range(ps14),
        ps14_signed=True if ps14 is None else bool(ps14.signed),
        ps20_float=ps20.format if ps20 is not None and ps20.is_float else "fp32",
    )


def _precision(profile: "CapsProfile", model: str) -> "Precision | None":
    getter = getattr(profile, "precision", None)
    return getter(model) if callable(getter) else None


def _fixed_bits(precision: "Precision | None") -> int | None:
    if precision is None or precision.is_float:
        return None
    return precision.bits


def _fixed_range(precision: "Precision | None") -> float | None:
    if precision is None or precision.is_float:
        return None
    return float(precision.range) if precision.range is not None else 1.0
