"""The fixed-function texture-stage cascade (D3DTSS_*) lowered to fragment IR.

The rules are docs/reference/semantics.md section 1 (Wine's FFP fragment generator and DXVK,
test-proven):
- `current` starts as the diffuse colour and `temp` as (0, 0, 0, 0); stages run 0..7 and the
  first COLOROP = DISABLE ends the cascade.
- Each stage computes rgb = colorop(colorargs) and a = alphaop(alphaargs), both reading the
  registers from before the stage; ALPHAOP = DISABLE passes current.a through.
- RESULTARG picks CURRENT or TEMP; the last active stage always writes CURRENT (DXVK).
- DOTPRODUCT3 as the colour op also writes its result to alpha (Wine: aop = cop, aargs = cargs).
- A stage whose used argument is TEXTURE with no texture bound runs SELECTARG1(CURRENT)
  instead, colour and alpha checked separately (Wine `is_invalid_op`).
- BUMPENVMAP / BUMPENVMAPLUMINANCE at stage n output nothing and perturb the coordinates of
  stage n + 1 with stage n's matrix; a projected stage n + 1 is divided before the offset; the
  luminance factor sat(L * LScale + LOffset) scales the whole texel.
- PREMODULATE returns Arg1, and the next stage reads CURRENT as current * its own texture
  (DXVK and Nine; Wine ignores it).

Every op is one row of `effects.d3d9.stage_ops.STAGE_OPS`: the caps bit that validation checks, the arguments it reads
(for the missing-texture rule), whether the texture is sampled without a TEXTURE argument, and
its formula over vec4 values. Saturation is written into the formulas exactly where the
semantics table says "sat"; a fixed-point card then quantises each stage result
(`LoweringOptions.stage_bits`).

Inputs the fragment program reads: varyings `color0` (diffuse), `color1` (specular),
`texcoord<n>` (stage n's coordinates, after TEXCOORDINDEX, texgen and the texture transform:
the vertex side produces them); uniforms `tfactor`, `stage<n>_constant`, `bumpenv<n>_mat`
(M00, M01, M10, M11 of bump stage n) and `bumpenv<n>_lum` (LScale, LOffset, 0, 0). Stage n
samples sampler n.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from effects.base.errors import EffectError, Location
from effects.program.ir import Builder
from effects.d3d9.precision import LoweringOptions

from effects.d3d9.stage_ops import (BUMP_OPS, MAX_STAGES, STAGE_OPS, TA_ALPHAREPLICATE,  # noqa: F401
                                TA_COMPLEMENT, TA_CONSTANT, TA_CURRENT, TA_DIFFUSE, TA_SELECTMASK,
                                TA_SPECULAR, TA_TEMP, TA_TEXTURE, TA_TFACTOR, TTFF_COUNT_MASK,
                                TTFF_PROJECTED, StageOp, Value, alpha_replicate,
                                complement)


@dataclass(frozen=True)
class StageSetup:
    """One texture stage's states, resolved from the device state. Args are D3DTA values
    (selector | modifier flags) indexed 0..2; `texture_kind` is None when no texture is bound.
    Float states are plain floats, colours (r, g, b, a)."""

    index: int
    color_op: str
    color_args: tuple[int, int, int]
    alpha_op: str
    alpha_args: tuple[int, int, int]
    result_arg: int = TA_CURRENT
    transform_flags: int = 0
    texture_kind: str | None = None
    bump_matrix: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)  # 00, 01, 10, 11
    bump_lscale: float = 0.0
    bump_loffset: float = 0.0
    constant: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)
    location: Location | None = None

    @property
    def texture_bound(self) -> bool:
        return self.texture_kind is not None

    @property
    def projected(self) -> bool:
        return bool(self.transform_flags & TTFF_PROJECTED)

    @property
    def count(self) -> int:
        return self.transform_flags & TTFF_COUNT_MASK


@dataclass
class FragmentInputs:
    """What the cascade needs besides the stages; `uniforms` collects the values of the
    uniforms the lowering declares (name -> vec4)."""

    tfactor: tuple[float, float, float, float] = (1.0, 1.0, 1.0, 1.0)
    specular_enable: bool = False
    uniforms: dict[str, tuple[float, ...]] = field(default_factory=dict)
    # (diffuse, specular) values computed in the fragment program (per-pixel lighting,
    # ShadeMode = Phong) instead of the interpolated vertex colours
    lit: tuple[int, int] | None = None


def effective_ops(stage: StageSetup) -> tuple[str, tuple[int, int, int], str, tuple[int, int, int]]:
    """(colour op, colour args, alpha op, alpha args) after the missing-texture rule and the
    DOTPRODUCT3 alpha override, in Wine's order (colour checked, dot3 copied, alpha checked)."""
    cop, cargs = stage.color_op, stage.color_args
    if _invalid_without_texture(stage, cop, cargs):
        cop, cargs = "SELECTARG1", (cargs[0], TA_CURRENT, cargs[2])
    if cop == "DOTPRODUCT3":
        return cop, cargs, cop, cargs
    aop, aargs = stage.alpha_op, stage.alpha_args
    if aop != "DISABLE" and _invalid_without_texture(stage, aop, aargs):
        aop, aargs = "SELECTARG1", (aargs[0], TA_CURRENT, aargs[2])
    return cop, cargs, aop, aargs


def _invalid_without_texture(stage: StageSetup, op: str, args: tuple[int, int, int]) -> bool:
    if stage.texture_bound or op == "DISABLE":
        return False
    return any(args[n] & TA_SELECTMASK == TA_TEXTURE for n in STAGE_OPS[op].args)


def active_stages(stages: list[StageSetup]) -> list[StageSetup]:
    """The stages before the first COLOROP = DISABLE."""
    active = []
    for stage in stages[:MAX_STAGES]:
        if stage.color_op == "DISABLE":
            break
        active.append(stage)
    return active


class _Cascade:
    """The registers and lazily sampled textures while lowering one cascade."""

    def __init__(self, b: Builder, stages: list[StageSetup], inputs: FragmentInputs,
                 options: LoweringOptions) -> None:
        self.b, self.stages, self.inputs, self.options = b, stages, inputs, options
        self.diffuse = inputs.lit[0] if inputs.lit else b.varying("color0", "COLOR0")
        self.current = self.diffuse
        self.temp = b.const(0.0)
        self.stage: StageSetup = stages[0] if stages else None  # type: ignore[assignment]
        self._textures: dict[int, Value] = {}
        self._bump_by_target: dict[int, StageSetup] = {}
        self._premodulated: set[int] = set()

    # -- argument sources
    def tfactor(self) -> Value:
        self.inputs.uniforms["tfactor"] = self.inputs.tfactor
        return self.b.uniform("tfactor", "TEXTUREFACTOR")

    def specular(self) -> Value:
        return self.inputs.lit[1] if self.inputs.lit else self.b.varying("color1", "COLOR1")

    def constant(self) -> Value:
        name = f"stage{self.stage.index}_constant"
        self.inputs.uniforms[name] = self.stage.constant
        return self.b.uniform(name, f"CONSTANT[{self.stage.index}]")

    def texture(self, stage: StageSetup | None = None) -> Value:
        stage = stage or self.stage
        if stage.index not in self._textures:
            self._textures[stage.index] = self._sample(stage)
        return self._textures[stage.index]

    def argument(self, selector: int) -> Value:
        select = selector & TA_SELECTMASK
        sources: dict[int, Callable[[], Value]] = {
            TA_DIFFUSE: lambda: self.diffuse, TA_CURRENT: self.read_current,
            TA_TEXTURE: self.texture, TA_TFACTOR: self.tfactor, TA_SPECULAR: self.specular,
            TA_TEMP: lambda: self.temp, TA_CONSTANT: self.constant}
        if select not in sources:
            raise EffectError(f"stage {self.stage.index}: D3DTA value {selector:#x} selects no "
                              "argument", self.stage.location or Location("<state>", 1, 1))
        value = sources[select]()
        # COMPLEMENT first, ALPHAREPLICATE second (Wine, DXVK).
        if selector & TA_COMPLEMENT:
            value = complement(self, value)
        if selector & TA_ALPHAREPLICATE:
            value = alpha_replicate(self, value)
        return value

    def read_current(self) -> Value:
        if self.stage.index in self._premodulated:
            return self.b.mul(self.current, self.texture())
        return self.current

    # -- texture coordinates and sampling
    def _coord(self, stage: StageSetup) -> Value:
        return self.b.varying(f"texcoord{stage.index}", f"TEXCOORD{stage.index}")

    def _sample(self, stage: StageSetup) -> Value:
        kind = stage.texture_kind or "2d"
        coord = self._coord(stage)
        projected = stage.projected
        if projected and stage.count in (2, 3):
            # TTFF_PROJECTED divides by the last counted component; the IR divides by w.
            coord = self.b.swizzle(coord, "xyz" + "xyzw"[stage.count - 1])
        bump = self._bump_by_target.get(stage.index)
        if bump is None:
            return self.b.sample(stage.index, coord, kind, proj=projected)
        if projected:  # the divide comes before the offset (semantics 1.6)
            coord = self.b.mul(coord, self.b.rcp(self.b.swizzle(coord, "wwww")))
        texel_n = self.texture(bump)
        mat_name = f"bumpenv{bump.index}_mat"
        self.inputs.uniforms[mat_name] = bump.bump_matrix
        mat = self.b.uniform(mat_name, f"BUMPENVMAT[{bump.index}]")
        # (u', v') = (u, v) + du * (M00, M01) + dv * (M10, M11)
        offset = self.b.mad(self.b.swizzle(texel_n, "xxxx"), self.b.swizzle(mat, "xyxy"),
                            self.b.mul(self.b.swizzle(texel_n, "yyyy"),
                                       self.b.swizzle(mat, "zwzw")))
        coord = self.b.add(coord, self.b.merge(self.b.const(0.0), offset, "xy"))
        texel = self.b.sample(stage.index, coord, kind)
        if bump.color_op == "BUMPENVMAPLUMINANCE":
            lum_name = f"bumpenv{bump.index}_lum"
            self.inputs.uniforms[lum_name] = (bump.bump_lscale, bump.bump_loffset, 0.0, 0.0)
            lum = self.b.uniform(lum_name, f"BUMPENVLSCALE/LOFFSET[{bump.index}]")
            factor = self.b.saturate(self.b.mad(self.b.swizzle(texel_n, "zzzz"),
                                                self.b.swizzle(lum, "xxxx"),
                                                self.b.swizzle(lum, "yyyy")))
            texel = self.b.mul(texel, factor)
        return texel

    # -- one stage
    def run(self) -> Value:
        active = active_stages(self.stages)
        for position, stage in enumerate(active):
            self.stage = stage
            cop, cargs, aop, aargs = effective_ops(stage)
            if cop in BUMP_OPS:
                if position + 1 < len(active):
                    self._bump_by_target[active[position + 1].index] = stage
                continue  # the bump stage itself outputs nothing
            color = self._op(cop, cargs)
            alpha = self._read_current_alpha() if aop == "DISABLE" else self._op(aop, aargs)
            result = color if color == alpha else self.b.merge(color, alpha, "w")
            if self.options.stage_bits is not None:
                result = self.b.quantize(result, self.options.stage_bits)
            if cop == "PREMODULATE" and position + 1 < len(active):
                self._premodulated.add(active[position + 1].index)
            last = position == len(active) - 1
            if stage.result_arg & TA_SELECTMASK == TA_TEMP and not last:
                self.temp = result
            else:
                self.current = result
        return self.current

    def _read_current_alpha(self) -> Value:
        return self.read_current()

    def _op(self, op: str, selectors: tuple[int, int, int]) -> Value:
        row = STAGE_OPS[op]
        args = [self.argument(selectors[n]) if n in row.args else None for n in range(3)]
        if row.formula is None:  # a bump op in the alpha slot: nothing to compute
            return self.read_current()
        return row.formula(self, tuple(args))  # type: ignore[arg-type]


def lower_cascade(b: Builder, stages: list[StageSetup], inputs: FragmentInputs,
                  options: LoweringOptions) -> Value:
    """Lower the cascade into `b`; returns the colour after the cascade and the specular add
    (rgb += specular.rgb when SpecularEnable, Wine's specular_enable = (1, 1, 1, 0))."""
    cascade = _Cascade(b, stages, inputs, options)
    color = cascade.run()
    if inputs.specular_enable:
        added = b.saturate(b.add(color, cascade.specular()))
        color = b.merge(color, added, "xyz")
        if options.stage_bits is not None:
            color = b.quantize(color, options.stage_bits)
    return color


# --------------------------------------------------------------------------------------------
# Fog, after the cascade (or after a pixel shader below ps_3_0)


FOG_MODES = ("NONE", "EXP", "EXP2", "LINEAR")
LOG2_E = 1.4426950408889634


@dataclass(frozen=True)
class FogSetup:
    """Fog as the device state asks for it. `source` says what the `fog` varying holds:
    'none' (fog off), 'vertex' (the per-vertex fog factor), 'table' (the fog distance; the
    factor is computed per pixel), 'specular' (FogEnable with both modes NONE: the factor is
    the specular alpha, Wine's FOGCOORD case)."""

    source: str = "none"
    table_mode: str = "NONE"
    vertex_mode: str = "NONE"
    color: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)
    start: float = 0.0
    end: float = 1.0
    density: float = 1.0
    range_fog: bool = False

    @property
    def params(self) -> tuple[float, float, float, float]:
        return (self.start, self.end, self.density, 0.0)


def fog_factor(b: Builder, distance: Value, mode: str, params: Value) -> Value:
    """The D3D fog factor (replicated, saturated) for `distance` (x) under `mode`
    ("Fog Formulas": LINEAR (end - d) / (end - start), EXP e^-(d density),
    EXP2 e^-((d density)^2)); `params` is the `fog_params` uniform (start, end, density, 0)."""
    d = b.swizzle(distance, "xxxx")
    if mode == "LINEAR":
        start, end = b.swizzle(params, "xxxx"), b.swizzle(params, "yyyy")
        f = b.mul(b.sub(end, d), b.rcp(b.sub(end, start)))
    elif mode in ("EXP", "EXP2"):
        x = b.mul(d, b.swizzle(params, "zzzz"))
        if mode == "EXP2":
            x = b.mul(x, x)
        f = b.exp2(b.mul(x, b.const(-LOG2_E)))
    else:
        raise ValueError(f"no fog formula for mode {mode!r}")
    return b.saturate(f)


def apply_fog(b: Builder, color: Value, fog: FogSetup, uniforms: dict[str, tuple[float, ...]],
              options: LoweringOptions) -> Value:
    """Blend `color` towards the fog colour: rgb = f * rgb + (1 - f) * fog colour; alpha is
    kept. The varying `fog` (1 component) comes from the vertex side (see FogSetup.source)."""
    if fog.source == "none":
        return color
    if fog.source == "specular":
        f = b.swizzle(b.varying("color1", "COLOR1"), "wwww")
    else:
        coord = b.varying("fog", "FOG", components=1)
        if fog.source == "vertex":
            f = b.saturate(b.swizzle(coord, "xxxx"))
        else:
            uniforms["fog_params"] = fog.params
            f = fog_factor(b, coord, fog.table_mode, b.uniform("fog_params", "FOG"))
    uniforms["fog_color"] = fog.color
    fogged = b.lrp(f, color, b.uniform("fog_color", "FOGCOLOR"))
    color = b.merge(color, fogged, "xyz")
    if options.stage_bits is not None:
        color = b.quantize(color, options.stage_bits)
    return color
