"""Technique validation against a caps profile, collecting every reason a card cannot run it.

This plays the part of D3DX's ValidateTechnique + the driver's ValidateDevice: for each pass,
with the device state as the technique leaves it (earlier passes persist), every stage op,
argument, texture, filter, blend, compare, stencil op, render target, shader version, shader
limit and card quirk is checked, and each failure becomes a `Reason` that names the pass, the
state or instruction, where it is, what it needs and what the card has.

What is checked, and what is not:
- Fixed-function stages: the highest enabled stage against MaxTextureBlendStages, each
  ColorOp/AlphaOp against TextureOpCaps, Temp/Constant arguments and ResultArg against
  PrimitiveMiscCaps, and the argument rules every card shares (ResultArg is Current or Temp,
  without modifiers, and the last active stage writes Current). The argument modifiers
  Complement and AlphaReplicate have no caps bit in D3DCAPS9: every card accepts them.
- Textures read in a pass: how many (MaxSimultaneousTextures, fixed function only: a pixel
  shader's version sets its own sampler count), the kind (cube, volume) against TextureCaps
  (declared by `string Type`, the texture or sampler type, or, for DX8 files that cannot
  declare it, implied by the lookup: `dcl_cube`, texm3x3tex/spec/vspec, or 3-component
  camera-space texture coordinates in a fixed-function stage),
  `int Width/Height/Depth` against the size limits, power-of-two and square rules, `string
  Format` (and `bool RenderTarget`) against the formats the card lists, and each sampler's
  filters, mip filter, anisotropy and address modes.
- Frame-buffer states a pass assigns: blend factors and ops, separate alpha blending, write
  masks, alpha test, depth test, stencil, culling, depth bias, scissor, table fog.
- Shaders: the version (a vertex shader newer than the hardware's runs when the card offers
  software or mixed vertex processing, up to the runtime's software version), every
  assembly rule of that version, and the card's own limits (instruction slots, temporaries,
  constants, dependent reads, render-target outputs; a vertex shader over the hardware's
  limits runs in software where the card offers it). An HLSL `compile ps_2_0 f()` is checked
  by its profile, and then rejected: the framework cannot compile HLSL yet, and D3DX rejects
  a technique whose shader fails to create.
- Card quirks (caps.py's vocabulary): severity `error` rejects, `warning` is reported in
  `Validation.warnings` and rejects nothing.
A state whose value is a parameter without a value (or a preshader expression) cannot be
checked before the application sets it: it is skipped with a note, never a crash.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Iterable

import numpy as np

from .caps import FIELDS, FORMATS, CapsProfile, Quirk
from .device import MAX_SAMPLERS, MAX_STAGES, DeviceState, pass_states
from .errors import EffectError, Location
from . import states as state_table
from .lower_stages import STAGE_OPS, StageOp
from .model import (CompileShader, Effect, EnumValue, Expression, NullValue, Parameter, ParamRef,
                    Pass, SamplerState, ShaderBlock, Technique)


@dataclass(frozen=True)
class Reason:
    """Why a card cannot run a technique (or, as a warning, what misbehaves): one requirement, located."""

    technique: str | None
    pass_name: str
    location: Location
    subject: str       # what asked for it: "ColorOp[1] = BumpEnvMap", "PixelShader (ps_1_4)"
    requirement: str   # what it needs: "D3DTEXOPCAPS_BUMPENVMAP"
    card_value: str    # what the card has: "not in TextureOpCaps", "PixelShaderVersion 1.1"
    message: str       # one plain sentence

    def __str__(self) -> str:
        return f"pass {self.pass_name} (line {self.location.line}): {self.message}"


@dataclass
class PassReport:
    """One pass on one card: its reasons and the resources it uses."""

    name: str
    index: int
    location: Location
    reasons: list[Reason] = field(default_factory=list)
    warnings: list[Reason] = field(default_factory=list)   # quirks of severity 'warning'
    notes: list[str] = field(default_factory=list)         # what could not be checked, and why
    stages: int = 0             # fixed-function texture stages in use
    textures: int = 0           # textures read at once
    render_targets: int = 1     # colour outputs written (oC0..oC3)
    pixel_shader: str | None = None     # 'ps_1_1', ...
    vertex_shader: str | None = None    # 'vs_1_1', ...
    software_vertex_processing: bool = False   # the vertex shader runs on the CPU

    @property
    def ok(self) -> bool:
        return not self.reasons


@dataclass
class Validation:
    """The validator's answer for one technique on one card (naga's ModuleInfo, in spirit)."""

    technique: Technique
    profile: CapsProfile
    pass_reports: list[PassReport]

    @property
    def ok(self) -> bool:
        return all(p.ok for p in self.pass_reports)

    @property
    def passes(self) -> int:
        """The pass count: what D3DX's Begin() returns."""
        return len(self.pass_reports)

    @property
    def reasons(self) -> list[Reason]:
        return [r for p in self.pass_reports for r in p.reasons]

    @property
    def warnings(self) -> list[Reason]:
        return [r for p in self.pass_reports for r in p.warnings]

    @property
    def notes(self) -> list[str]:
        return [f"pass {p.name}: {n}" for p in self.pass_reports for n in p.notes]


# ---------------------------------------------------------------------------------------------
# Tables. Enum names are the states table's canonical names (no prefix); caps bits are the
# D3D*CAPS_ names without prefix, which mostly coincide. Sources: d3d9types.h / d3d9caps.h as
# documented (D3DTEXTUREFILTERTYPE, D3DPTFILTERCAPS, D3DBLEND, D3DPBLENDCAPS ...).

_FILTER_BITS = {  # (state, D3DTEXF name) -> D3DPTFILTERCAPS bit; other pairs no card accepts
    **{("MinFilter", f): f"MINF{f}" for f in ("POINT", "LINEAR", "ANISOTROPIC", "PYRAMIDALQUAD", "GAUSSIANQUAD")},
    **{("MagFilter", f): f"MAGF{f}" for f in ("POINT", "LINEAR", "ANISOTROPIC", "PYRAMIDALQUAD", "GAUSSIANQUAD")},
    **{("MipFilter", f): f"MIPF{f}" for f in ("POINT", "LINEAR")},
}
# Filter caps field per texture kind (a card without the field uses TextureFilterCaps).
_FILTER_FIELD = {"CUBE": "CubeTextureFilterCaps", "3D": "VolumeTextureFilterCaps"}
# Blend factors whose caps bit has another name.
_BLEND_BITS = {"INVBLENDFACTOR": "BLENDFACTOR"}
_TA_SELECT_MASK, _TA_COMPLEMENT, _TA_ALPHAREPLICATE = 0x0F, 0x10, 0x20
_TA_CURRENT, _TA_TEXTURE, _TA_TEMP, _TA_CONSTANT = 1, 2, 5, 6
# Which arguments each op reads (D3DTEXTUREOP docs): most read 1 and 2.


def _stage_op(op: str) -> StageOp | None:
    """The lowering's row for a D3DTOP: the caps bit it needs, the arguments it reads, and
    whether it samples its texture without a TEXTURE argument. Validation reads the same
    table the lowering runs, so "valid" and "what runs" cannot drift apart."""
    return STAGE_OPS.get(op)


def _args_read(op: str) -> tuple[int, ...]:
    row = _stage_op(op)
    return row.args if row is not None else ((1, 2) if op != "DISABLE" else ())
_STENCIL_OP_STATES = ("StencilFail", "StencilZFail", "StencilPass")
_CCW_STENCIL_OP_STATES = ("CCW_StencilFail", "CCW_StencilZFail", "CCW_StencilPass")

# Render states that need one caps bit when a pass assigns them: (state, test on the value
# in force, caps field, bit, what the value does). Checked only when assigned, so a card is
# never rejected for a default.
_STATE_BITS: tuple[tuple[str, Callable[[Any], bool], str, str, str], ...] = (
    ("ZWriteEnable", lambda v: v is False or v == 0, "PrimitiveMiscCaps", "MASKZ", "turns depth writes off"),
    ("CullMode", lambda v: v == "NONE", "PrimitiveMiscCaps", "CULLNONE", "draws both faces"),
    ("CullMode", lambda v: v == "CW", "PrimitiveMiscCaps", "CULLCW", "culls clockwise faces"),
    ("CullMode", lambda v: v == "CCW", "PrimitiveMiscCaps", "CULLCCW", "culls counter-clockwise faces"),
    ("ScissorTestEnable", lambda v: bool(v), "RasterCaps", "SCISSORTEST", "clips to a scissor rectangle"),
    ("DepthBias", lambda v: bool(v), "RasterCaps", "DEPTHBIAS", "offsets depth"),
    ("SlopeScaleDepthBias", lambda v: bool(v), "RasterCaps", "SLOPESCALEDEPTHBIAS", "offsets depth by slope"),
    ("FogTableMode", lambda v: v not in (None, "NONE"), "RasterCaps", "FOGTABLE", "computes fog per pixel"),
)
# D3DTSS_TEXTURETRANSFORMFLAGS: D3DTTFF_PROJECTED.
_TTFF_PROJECTED = 0x100
# D3DTSS_TCI_CAMERASPACENORMAL / POSITION / REFLECTIONVECTOR (value >> 16): with three
# coordinates (D3DTTFF_COUNT3) they are the cube-map lookups of the fixed-function pipeline.
_CAMERA_SPACE_TEXGEN = (1, 2, 3)
# ps_1_1-1_3 instructions that look up a cube map (the ps_1_x instruction pages).
_CUBE_LOOKUPS_PS1 = frozenset({"texm3x3tex", "texm3x3spec", "texm3x3vspec"})


def _version(text: str | None) -> tuple[int, int]:
    if not text:
        return (0, 0)
    digits = [int(p) for p in text.replace("_", ".").split(".") if p.isdigit()]
    return (digits + [0, 0])[0], (digits + [0, 0])[1]


def _version_text(v: tuple[int, int]) -> str:
    return f"{v[0]}.{v[1]}"


def software_vs_version(profile: CapsProfile) -> tuple[int, int]:
    """The vertex shader version the runtime runs on the CPU for this card ((0, 0): none).
    Software and mixed devices both offer it (mixed switches between the two pipelines)."""
    if not profile.vertex_processing & {"software", "mixed"}:
        return (0, 0)
    return _version(profile.get("SoftwareVertexShaderVersion", "3.0"))


class _PassChecker:
    """Runs every check for one pass and collects its reasons."""

    def __init__(self, effect: Effect, technique: Technique, p: Pass, index: int,
                 state: DeviceState, profile: CapsProfile) -> None:
        self.effect, self.technique, self.pass_, self.state, self.profile = effect, technique, p, state, profile
        self.report = PassReport(p.name or str(index), index, p.location)
        # quirks that make a reported caps bit or format unusable: (field, bit) / (format, usage)
        self.unreliable_bits = {(q.get("field"), q.get("bit")): q for q in profile.quirks
                                if q.rule == "cap_unreliable"}
        self.unreliable_formats = {(q.get("format"), q.get("usage")): q for q in profile.quirks
                                   if q.rule == "format_unreliable"}

    # -- reason helpers ---------------------------------------------------------------------
    def fail(self, location: Location, subject: str, requirement: str, card_value: str,
             message: str) -> None:
        self.report.reasons.append(Reason(self.technique.name, self.report.name, location,
                                          subject, requirement, card_value, message))

    def warn(self, location: Location, subject: str, quirk: Quirk) -> None:
        reason = Reason(self.technique.name, self.report.name, location, subject,
                        f"driver rule {quirk.id}", quirk.text, f"{subject}: {quirk.text} ({self.card()})")
        if reason not in self.report.warnings:
            self.report.warnings.append(reason)

    def note(self, text: str) -> None:
        if text not in self.report.notes:
            self.report.notes.append(text)

    def where(self, name: str, index: int | None = None) -> Location:
        a = self.state.assignment(name, index)
        return a.location if a is not None else self.pass_.location

    def card(self) -> str:
        return self.profile.display_name or self.profile.name

    def need_bit(self, caps_field: str, bit: str, subject: str, location: Location,
                 prefix: str) -> None:
        """Fail unless the card reports `bit` in `caps_field` and no error quirk disowns it."""
        table = FIELDS[caps_field].table or {}
        if bit not in table:  # a value no caps bit covers (Direct3D 9Ex additions ...)
            self.fail(location, subject, f"{prefix}{bit}", f"not in {caps_field}",
                      f"{subject} needs {prefix}{bit}, which no Direct3D 9 caps report; "
                      f"the {self.card()} does not have it")
            return
        if not self.profile.has(caps_field, bit):
            self.fail(location, subject, f"{prefix}{bit}", f"not in {caps_field}",
                      f"{subject} needs {prefix}{bit}; the {self.card()} does not have it")
            return
        quirk = self.unreliable_bits.get((caps_field, bit))
        if quirk is not None:
            self.quirk_hit(quirk, location, subject)

    def quirk_hit(self, quirk: Quirk, location: Location, subject: str) -> None:
        if quirk.severity == "error":
            self.fail(location, subject, f"driver rule {quirk.id}", quirk.text,
                      f"{subject}: {quirk.text} ({self.card()})")
        else:
            self.warn(location, subject, quirk)

    def unknown(self, name: str, index: int | None = None) -> bool:
        """True (with a note) when the value in force cannot be known before the application
        sets it: an uninitialised parameter or a preshader expression."""
        value = self.state.get(name, index)
        if not isinstance(value, (ParamRef, Expression)):
            return False
        shown = f"{name}[{index}]" if index is not None and _is_indexed(name) else name
        what = (f"parameter {value.name}, which has no value" if isinstance(value, ParamRef)
                else f"the expression '{value.text}'")
        self.note(f"{shown} is set from {what}: not checked until the application sets it")
        return True

    # -- the checks -------------------------------------------------------------------------
    def run(self) -> PassReport:
        ps = self.shader("PixelShader")
        vs = self.shader("VertexShader")
        if ps is None:
            self.check_texture_stages()
        else:
            self.check_pixel_shader(ps)
        if vs is not None:
            self.check_vertex_shader(vs)
        self.check_textures(ps is not None)
        self.check_blending()
        self.check_compares()
        self.check_stencil()
        self.check_state_bits()
        self.check_quirks()
        return self.report

    def shader(self, name: str) -> tuple[Any, Location] | None:
        """The shader in force (None for the fixed-function pipeline), with its location."""
        a = self.state.assignment(name)
        if a is None:
            return None
        value = self.state.resolve(a.value)
        if isinstance(value, (NullValue, type(None))):
            return None
        if isinstance(value, (ParamRef, Expression)):
            self.unknown(name)
        return value, a.location

    # fixed-function texture stages ----------------------------------------------------------
    def active_stages(self) -> list[int]:
        """Stages up to the first disabled one (an unknown op counts as enabled)."""
        stages = []
        for stage in range(MAX_STAGES):
            if self.state.enum_name("ColorOp", stage) == "DISABLE":
                break
            stages.append(stage)
        return stages

    def check_texture_stages(self) -> None:
        stages = self.active_stages()
        self.report.stages = len(stages)
        limit = int(self.profile.get("MaxTextureBlendStages", 0))
        if stages and len(stages) > limit:
            top = stages[-1]
            self.fail(self.where("ColorOp", top), f"ColorOp[{top}]",
                      f"MaxTextureBlendStages >= {len(stages)}", f"MaxTextureBlendStages {limit}",
                      f"ColorOp[{top}] enables texture stage {top}, so {len(stages)} stages are "
                      f"needed; the {self.card()} has {limit}")
        for stage in stages:
            self.check_stage(stage)
        if stages:
            self.check_result_args(stages)

    def check_stage(self, stage: int) -> None:
        for op_state, arg_prefix in (("ColorOp", "ColorArg"), ("AlphaOp", "AlphaArg")):
            if self.unknown(op_state, stage):
                continue
            op = self.state.enum_name(op_state, stage)
            if op is None or (op_state == "AlphaOp" and op == "DISABLE"):
                continue
            shown = self._shown(op_state, stage)
            row = _stage_op(op)
            self.need_bit("TextureOpCaps", row.cap if row is not None else op,
                          f"{op_state}[{stage}] = {shown}", self.where(op_state, stage),
                          "D3DTEXOPCAPS_")
            for n in _args_read(op):
                self.check_arg(f"{arg_prefix}{n}", stage)

    def check_arg(self, state_name: str, stage: int) -> None:
        if self.unknown(state_name, stage):
            return
        select = _ta_select(self.state.get(state_name, stage))
        if select == _TA_TEMP:
            self.need_bit("PrimitiveMiscCaps", "TSSARGTEMP", f"{state_name}[{stage}] = Temp",
                          self.where(state_name, stage), "D3DPMISCCAPS_")
        elif select == _TA_CONSTANT:
            self.need_bit("PrimitiveMiscCaps", "PERSTAGECONSTANT", f"{state_name}[{stage}] = Constant",
                          self.where(state_name, stage), "D3DPMISCCAPS_")

    def check_result_args(self, stages: list[int]) -> None:
        """ResultArg is Current (default) or Temp, never modified, and the last stage writes
        Current, which is what reaches the frame buffer (D3DTSS_RESULTARG docs)."""
        for stage in stages:
            if self.state.assignment("ResultArg", stage) is None or self.unknown("ResultArg", stage):
                continue
            value = _int_value(self.state.get("ResultArg", stage))
            if value is None:
                continue
            subject = f"ResultArg[{stage}] = {self._shown_flags('ResultArg', stage)}"
            loc = self.where("ResultArg", stage)
            if value & (_TA_COMPLEMENT | _TA_ALPHAREPLICATE) or (value & _TA_SELECT_MASK) not in (_TA_CURRENT, _TA_TEMP):
                self.fail(loc, subject, "D3DTA_CURRENT or D3DTA_TEMP", "any card",
                          f"{subject}: a stage writes its result to Current or Temp only, without "
                          "modifiers; no card accepts this")
                continue
            if value == _TA_TEMP:
                self.need_bit("PrimitiveMiscCaps", "TSSARGTEMP", subject, loc, "D3DPMISCCAPS_")
                if stage == stages[-1]:
                    self.fail(loc, subject, "D3DTA_CURRENT on the last active stage", "any card",
                              f"{subject} on the last active stage: its result never reaches the "
                              "frame buffer, which takes Current; no card accepts this")

    def _shown(self, name: str, index: int | None = None) -> str:
        """A state's value as the docs spell it ('BumpEnvMap')."""
        return spelled(name, self.state.enum_name(name, index) or "default")

    def _shown_flags(self, name: str, index: int | None = None) -> str:
        value = self.state.get(name, index)
        if isinstance(value, EnumValue) and value.names:
            return " | ".join(spelled(name, n) for n in value.names)
        return self._shown(name, index)

    # textures and samplers ---------------------------------------------------------------------
    def sampled_units(self, shader: bool) -> list[int]:
        """Stages/samplers whose texture is read in this pass."""
        if shader:
            ps = self.shader("PixelShader")
            units = _shader_samplers(ps[0]) if ps else None
            if units is not None:
                return units
            return [n for n in range(MAX_SAMPLERS) if self.state.assignment("Texture", n)]
        units = []
        for stage in self.active_stages():
            if self.state.assignment("Texture", stage) is None:
                continue
            if self.stage_reads_texture(stage):
                units.append(stage)
        return units

    def stage_reads_texture(self, stage: int) -> bool:
        for op_state, arg_prefix in (("ColorOp", "ColorArg"), ("AlphaOp", "AlphaArg")):
            op = self.state.enum_name(op_state, stage)
            if op is None:
                return True   # unknown op: assume it reads what is bound
            row = _stage_op(op)
            if row is not None and row.samples:
                return True
            for n in _args_read(op):
                value = self.state.get(f"{arg_prefix}{n}", stage)
                if isinstance(value, (ParamRef, Expression)) or _ta_select(value) == _TA_TEXTURE:
                    return True
        return False

    def check_textures(self, shader: bool) -> None:
        units = self.sampled_units(shader)
        self.report.textures = len(units)
        limit = int(self.profile.get("MaxSimultaneousTextures", 0))
        if not shader and len(units) > limit:
            top = units[-1]
            self.fail(self.where("Texture", top), f"Texture[{top}]",
                      f"MaxSimultaneousTextures >= {len(units)}", f"MaxSimultaneousTextures {limit}",
                      f"this pass reads {len(units)} textures at once (stages "
                      f"{', '.join(map(str, units))}); the {self.card()} can bind {limit}")
        for unit in units:
            param = self.texture_parameter(unit)
            kind = texture_kind(param, self.effect) if param is not None else None
            how = ""
            if kind is None:
                kind, how = self.kind_from_use(unit, shader)
            if param is not None:
                self.check_texture_resource(unit, param, kind, how)
            self.check_sampler_states(unit, kind)

    def kind_from_use(self, unit: int, shader: bool) -> tuple[str | None, str]:
        """The kind a texture must be, from how the pass samples it, for a texture that does
        not declare its own (DX8 files cannot): ('CUBE', 'sampled by dcl_cube s0') or (None, '')."""
        if shader:
            ps = self.shader("PixelShader")
            program = _assembled(ps[0]) if ps else None
            if program is None:
                return None, ""
            for d in program.dcls:
                if d.register.kind == "s" and d.register.index == unit and d.sampler_type in ("cube", "volume"):
                    return ("CUBE" if d.sampler_type == "cube" else "3D"), f"declared by dcl_{d.sampler_type} s{unit}"
            for ins in program.instructions:
                if ins.opcode in _CUBE_LOOKUPS_PS1 and ins.dst is not None and ins.dst.index == unit:
                    return "CUBE", f"read by {ins.opcode} t{unit}"
            return None, ""
        tci = _int_value(self.state.get("TexCoordIndex", unit)) or 0
        flags = _int_value(self.state.get("TextureTransformFlags", unit)) or 0
        if (tci >> 16) in _CAMERA_SPACE_TEXGEN and flags & 0xFF == 3 and not flags & _TTFF_PROJECTED:
            return "CUBE", "looked up with 3-component camera-space texture coordinates"
        return None, ""

    def texture_parameter(self, unit: int) -> Parameter | None:
        a = self.state.assignment("Texture", unit)
        if a is None or not isinstance(a.value, ParamRef):
            return None
        return self.effect.parameter(a.value.name)

    def check_texture_resource(self, unit: int, param: Parameter, kind: str | None, how: str = "") -> None:
        loc = self.where("Texture", unit)
        subject = f"Texture[{unit}] = <{param.name}>"
        because = f", {how}" if how else ""
        if kind == "CUBE":
            self.need_bit("TextureCaps", "CUBEMAP", f"{subject} (a cube map{because})", loc, "D3DPTEXTURECAPS_")
        elif kind == "3D":
            self.need_bit("TextureCaps", "VOLUMEMAP", f"{subject} (a volume texture{because})", loc,
                          "D3DPTEXTURECAPS_")
        self.check_texture_size(unit, param, kind, subject)
        self.check_texture_format(unit, param, kind, subject)
        flags = _int_value(self.state.get("TextureTransformFlags", unit))
        if (self.state.assignment("TextureTransformFlags", unit) is not None and flags is not None
                and flags & _TTFF_PROJECTED):
            self.need_bit("TextureCaps", "PROJECTED", f"TextureTransformFlags[{unit}] = Projected",
                          self.where("TextureTransformFlags", unit), "D3DPTEXTURECAPS_")

    def check_texture_size(self, unit: int, param: Parameter, kind: str | None, subject: str) -> None:
        width, height = _annotation_int(param, "Width"), _annotation_int(param, "Height")
        depth = _annotation_int(param, "Depth")
        limits = [(width, "MaxTextureWidth"), (height, "MaxTextureHeight")]
        if kind == "3D":
            limits.append((depth, "MaxVolumeExtent"))
        for value, cap in limits:
            card_max = self.profile.get(cap)
            if value is not None and card_max is not None and value > int(card_max):
                self.fail(param.location, subject, f"{cap} >= {value}", f"{cap} {card_max}",
                          f"{subject} is {value} texels along one side; the {self.card()} allows "
                          f"{card_max} ({cap})")
        sides = [v for v in (width, height, depth if kind == "3D" else None) if v]
        if not sides:
            return
        if width and height and width != height and self.profile.has("TextureCaps", "SQUAREONLY"):
            self.fail(param.location, subject, "square textures", "TextureCaps SQUAREONLY",
                      f"{subject} is {width}x{height}; the {self.card()} needs square textures")
        ratio = self.profile.get("MaxTextureAspectRatio")
        if width and height and ratio and max(width, height) > ratio * min(width, height):
            self.fail(param.location, subject, f"MaxTextureAspectRatio >= {max(width, height) // min(width, height)}",
                      f"MaxTextureAspectRatio {ratio}",
                      f"{subject} is {width}x{height}; the {self.card()} allows an aspect ratio up to {ratio}")
        if all(v & (v - 1) == 0 for v in sides):
            return
        pow2_bit = {"CUBE": "CUBEMAP_POW2", "3D": "VOLUMEMAP_POW2"}.get(kind or "", "POW2")
        if not self.profile.has("TextureCaps", pow2_bit):
            return
        shown = "x".join(map(str, sides))
        if kind in ("CUBE", "3D") or not self.profile.has("TextureCaps", "NONPOW2CONDITIONAL"):
            self.fail(param.location, subject, "power-of-two sizes", f"TextureCaps {pow2_bit}",
                      f"{subject} is {shown}, not a power of two; the {self.card()} needs "
                      "power-of-two sizes")
            return
        # NONPOW2CONDITIONAL: allowed with clamped addressing and no mipmaps (D3DPTEXTURECAPS docs)
        for name in ("AddressU", "AddressV"):
            if self.state.enum_name(name, unit) != "CLAMP":
                self.fail(self.where(name, unit), f"{subject} with {name}[{unit}] = {self._shown(name, unit)}",
                          "D3DTADDRESS_CLAMP for a non-power-of-two texture", "TextureCaps NONPOW2CONDITIONAL",
                          f"{subject} is {shown}, not a power of two; the {self.card()} takes such "
                          f"a texture only with {name} = Clamp")
        if self.state.enum_name("MipFilter", unit) not in ("NONE", None):
            self.fail(self.where("MipFilter", unit), f"{subject} with MipFilter[{unit}] = {self._shown('MipFilter', unit)}",
                      "no mipmapping for a non-power-of-two texture", "TextureCaps NONPOW2CONDITIONAL",
                      f"{subject} is {shown}, not a power of two; the {self.card()} takes such a "
                      "texture only without mipmaps")

    def check_texture_format(self, unit: int, param: Parameter, kind: str | None, subject: str) -> None:
        fmt = _annotation_str(param, "Format")
        if not fmt:
            return
        name = fmt.upper().removeprefix("D3DFMT_")
        ann = param.annotation("Format")
        loc = ann.location if ann is not None and ann.location.line else param.location
        if name not in FORMATS:
            self.fail(loc, f"{subject} Format = {fmt}", "a D3DFORMAT name", "unknown format",
                      f"{subject} names the format '{fmt}', which is not a Direct3D 9 format; "
                      f"the {self.card()} cannot create it")
            return
        usage = {"CUBE": "cube", "3D": "volume"}.get(kind or "", "texture")
        wanted = [usage]
        if _annotation_bool(param, "RenderTarget"):
            wanted.append("rendertarget")
        if any(self.state.enum_name(f, unit) in ("LINEAR", "ANISOTROPIC", "PYRAMIDALQUAD", "GAUSSIANQUAD")
               for f in ("MinFilter", "MagFilter", "MipFilter")):
            wanted.append("filter")
        usages = self.profile.format_usages(name)
        if usage not in usages:   # the format is missing altogether: one reason is enough
            wanted = [usage]
        for use in wanted:
            if use not in usages:
                what = {"rendertarget": "as a render target", "texture": "for a texture",
                        "filter": "with linear filtering"}.get(use, f"for a {use} texture")
                self.fail(loc, f"{subject} Format = {name}", f"format {name} ({use})",
                          "supported usages: " + (", ".join(sorted(usages)) or "none"),
                          f"{subject} uses the format {name} {what}; the {self.card()} does not "
                          "support that")
            else:
                quirk = (self.unreliable_formats.get((name, use))
                         or self.unreliable_formats.get((name, None)))
                if quirk is not None:
                    self.quirk_hit(quirk, loc, f"{subject} Format = {name}")

    def check_sampler_states(self, unit: int, kind: str | None) -> None:
        filter_field = _FILTER_FIELD.get(kind or "", "TextureFilterCaps")
        if self.profile.get(filter_field) is None:
            filter_field = "TextureFilterCaps"
        for name in ("MinFilter", "MagFilter", "MipFilter"):
            if self.unknown(name, unit):
                continue
            value = self.state.enum_name(name, unit)
            if value is None or value == "NONE":
                continue
            subject = f"{name}[{unit}] = {spelled(name, value)}"
            bit = _FILTER_BITS.get((name, value))
            if bit is None:
                self.fail(self.where(name, unit), subject, f"a {name} the card filters with",
                          f"not in {filter_field}",
                          f"{subject} is not a {name[:3].lower()}ification filter a Direct3D 9 "
                          f"card reports; the {self.card()} does not have it")
                continue
            self.need_bit(filter_field, bit, subject, self.where(name, unit), "D3DPTFILTERCAPS_")
        mip = self.state.enum_name("MipFilter", unit)
        if mip not in (None, "NONE"):
            mip_bit = {"CUBE": "MIPCUBEMAP", "3D": "MIPVOLUMEMAP"}.get(kind or "", "MIPMAP")
            self.need_bit("TextureCaps", mip_bit, f"MipFilter[{unit}] = {spelled('MipFilter', mip)}",
                          self.where("MipFilter", unit), "D3DPTEXTURECAPS_")
        if self.state.assignment("MaxAnisotropy", unit) is not None and not self.unknown("MaxAnisotropy", unit):
            wanted = _int_value(self.state.get("MaxAnisotropy", unit))
            have = int(self.profile.get("MaxAnisotropy", 1) or 1)
            if wanted is not None and wanted > have:
                self.fail(self.where("MaxAnisotropy", unit), f"MaxAnisotropy[{unit}] = {wanted}",
                          f"MaxAnisotropy >= {wanted}", f"MaxAnisotropy {have}",
                          f"MaxAnisotropy[{unit}] = {wanted}; the {self.card()} filters with at most {have}")
        address_field = "VolumeTextureAddressCaps" if kind == "3D" and self.profile.get(
            "VolumeTextureAddressCaps") is not None else "TextureAddressCaps"
        names = ("AddressU", "AddressV", "AddressW") if kind == "3D" else ("AddressU", "AddressV")
        for name in names:
            if self.state.assignment(name, unit) is None or self.unknown(name, unit):
                continue
            value = self.state.enum_name(name, unit)
            if value:
                self.need_bit(address_field, value, f"{name}[{unit}] = {spelled(name, value)}",
                              self.where(name, unit), "D3DPTADDRESSCAPS_")

    # frame-buffer operations ---------------------------------------------------------------------
    def enabled(self, name: str) -> bool:
        if self.unknown(name):
            return False
        value = self.state.get(name)
        if isinstance(value, np.ndarray):
            return bool(value.size) and bool(value.reshape(-1)[0])
        return bool(value) and not isinstance(value, (ParamRef, NullValue))

    def check_blend_factor(self, name: str, caps_field: str) -> None:
        if self.unknown(name):
            return
        value = self.state.enum_name(name)
        if value:
            self.need_bit(caps_field, _BLEND_BITS.get(value, value), f"{name} = {spelled(name, value)}",
                          self.where(name), "D3DPBLENDCAPS_")

    def check_blend_op(self, name: str) -> None:
        op = None if self.unknown(name) else self.state.enum_name(name)
        if op and op != "ADD":
            self.need_bit("PrimitiveMiscCaps", "BLENDOP", f"{name} = {spelled(name, op)}",
                          self.where(name), "D3DPMISCCAPS_")

    def check_blending(self) -> None:
        if self.enabled("AlphaBlendEnable"):
            self.check_blend_factor("SrcBlend", "SrcBlendCaps")
            self.check_blend_factor("DestBlend", "DestBlendCaps")
            self.check_blend_op("BlendOp")
            if self.enabled("SeparateAlphaBlendEnable"):
                self.need_bit("PrimitiveMiscCaps", "SEPARATEALPHABLEND", "SeparateAlphaBlendEnable = True",
                              self.where("SeparateAlphaBlendEnable"), "D3DPMISCCAPS_")
                self.check_blend_factor("SrcBlendAlpha", "SrcBlendCaps")
                self.check_blend_factor("DestBlendAlpha", "DestBlendCaps")
                self.check_blend_op("BlendOpAlpha")
            if self.report.render_targets > 1:
                self.need_bit("PrimitiveMiscCaps", "MRTPOSTPIXELSHADERBLENDING",
                              f"AlphaBlendEnable = True with {self.report.render_targets} render targets",
                              self.where("AlphaBlendEnable"), "D3DPMISCCAPS_")
        if self.state.assignment("ColorWriteEnable") is not None and not self.unknown("ColorWriteEnable"):
            if _int_value(self.state.get("ColorWriteEnable")) not in (0xF, None):
                self.need_bit("PrimitiveMiscCaps", "COLORWRITEENABLE",
                              f"ColorWriteEnable = {self._shown_flags('ColorWriteEnable')}",
                              self.where("ColorWriteEnable"), "D3DPMISCCAPS_")
        for n in (1, 2, 3):
            name = f"ColorWriteEnable{n}"
            if self.state.assignment(name) is None or self.unknown(name):
                continue
            if _int_value(self.state.get(name)) != _int_value(self.state.get("ColorWriteEnable")):
                self.need_bit("PrimitiveMiscCaps", "INDEPENDENTWRITEMASKS",
                              f"{name} = {self._shown_flags(name)}", self.where(name), "D3DPMISCCAPS_")

    def check_compares(self) -> None:
        if self.enabled("AlphaTestEnable") and not self.unknown("AlphaFunc"):
            value = self.state.enum_name("AlphaFunc")
            if value:
                self.need_bit("AlphaCmpCaps", value, f"AlphaFunc = {spelled('AlphaFunc', value)}",
                              self.where("AlphaFunc"), "D3DPCMPCAPS_")
        if self.state.assignment("ZFunc") is not None and not self.unknown("ZFunc"):
            value = self.state.enum_name("ZFunc")
            if value:
                self.need_bit("ZCmpCaps", value, f"ZFunc = {spelled('ZFunc', value)}", self.where("ZFunc"),
                              "D3DPCMPCAPS_")

    def check_stencil(self) -> None:
        if not self.enabled("StencilEnable"):
            return
        if not self.profile.get("StencilCaps"):
            self.fail(self.where("StencilEnable"), "StencilEnable = True", "a stencil buffer",
                      "StencilCaps empty", f"StencilEnable needs a stencil buffer; the {self.card()} has none")
            return
        names = list(_STENCIL_OP_STATES)
        if self.enabled("TwoSidedStencilMode"):
            self.need_bit("StencilCaps", "TWOSIDED", "TwoSidedStencilMode = True",
                          self.where("TwoSidedStencilMode"), "D3DSTENCILCAPS_")
            names += _CCW_STENCIL_OP_STATES
        for name in names:
            if self.state.assignment(name) is None or self.unknown(name):
                continue
            value = self.state.enum_name(name)
            if value:
                self.need_bit("StencilCaps", value, f"{name} = {spelled(name, value)}", self.where(name),
                              "D3DSTENCILCAPS_")

    def check_state_bits(self) -> None:
        for name, needed, caps_field, bit, what in _STATE_BITS:
            if self.state.assignment(name) is None or self.unknown(name):
                continue
            if name == "FogTableMode" and not self.enabled("FogEnable"):
                continue
            value = self.state.get(name)
            if isinstance(value, EnumValue):
                value = self.state.enum_name(name)
            elif isinstance(value, np.ndarray):
                value = value.reshape(-1)[0].item() if value.size else None
            if not needed(value):
                continue
            shown = spelled(name, value) if isinstance(value, str) else _shown_scalar(value)
            prefix = {"PrimitiveMiscCaps": "D3DPMISCCAPS_", "RasterCaps": "D3DPRASTERCAPS_"}[caps_field]
            self.need_bit(caps_field, bit, f"{name} = {shown} ({what})", self.where(name), prefix)

    # shaders ------------------------------------------------------------------------------------
    def check_pixel_shader(self, shader: tuple[Any, Location]) -> None:
        value, loc = shader
        have = self.profile.pixel_shader_version
        version = _shader_version(value)
        if version is None:
            return
        self.report.pixel_shader = _version_label("ps", version)
        if version > have:
            label = self.report.pixel_shader
            limit = (f"runs pixel shaders up to {_version_label('ps', have)}" if have > (0, 0)
                     else "has no pixel shader hardware")
            self.fail(_block_location(value, loc), f"PixelShader ({label})",
                      f"PixelShaderVersion >= {_version_text(version)}",
                      f"PixelShaderVersion {_version_text(have)}",
                      f"PixelShader is {label}; the {self.card()} {limit}")
            return
        if isinstance(value, CompileShader):
            self.note_hlsl("PixelShader", value)
            return
        self.check_assembly(value, "PixelShader")

    def check_vertex_shader(self, shader: tuple[Any, Location]) -> None:
        value, loc = shader
        version = _shader_version(value)
        if version is None:
            return
        label = _version_label("vs", version)
        self.report.vertex_shader = label
        hardware = self.profile.vertex_shader_version
        software = software_vs_version(self.profile)
        if version > hardware and version > software:
            limit = (f"runs vertex shaders up to {_version_label('vs', hardware)}" if hardware > (0, 0)
                     else "has no vertex shader hardware")
            offer = (f"its software vertex processing runs up to {_version_label('vs', software)}"
                     if software > (0, 0) else "it offers no software vertex processing")
            self.fail(_block_location(value, loc), f"VertexShader ({label})",
                      f"VertexShaderVersion >= {_version_text(version)} or software vertex processing",
                      f"VertexShaderVersion {_version_text(hardware)}, processing: "
                      f"{', '.join(sorted(self.profile.vertex_processing))}",
                      f"VertexShader is {label}; the {self.card()} {limit} and {offer}")
            return
        in_software = version > hardware
        if isinstance(value, CompileShader):
            self.report.software_vertex_processing = in_software
            self.note_hlsl("VertexShader", value)
            return
        if not in_software and software >= version and self.assembly_problems(value, software=False):
            # over the hardware's limits (constants, temporaries): software processing runs it
            if not self.assembly_problems(value, software=True):
                in_software = True
                self.note("the vertex shader exceeds the hardware's limits and runs in software "
                          "vertex processing")
        self.report.software_vertex_processing = in_software
        self.check_assembly(value, "VertexShader", software=in_software)

    def assembly_problems(self, value: Any, software: bool) -> bool:
        """Whether an asm shader breaks its version's rules or the card's limits."""
        if not isinstance(value, ShaderBlock):
            return False
        from .asm import assemble_cached, card_limit_violations, check_cached
        try:
            program = assemble_cached(value)
        except EffectError:
            return True
        return bool(check_cached(program)) or any(
            True for _ in card_limit_violations(program, self.profile, software=software))

    def note_hlsl(self, state_name: str, value: CompileShader) -> None:
        # D3DX rejects a technique whose shader fails to create (Wine's ValidateTechnique);
        # this framework captures HLSL functions but cannot compile them yet, so it cannot
        # create the shader on any card. Saying so beats selecting a technique nothing can draw.
        self.fail(value.location, f"{state_name} = compile {value.profile} {value.function}()",
                  "an HLSL compiler", "none in this framework yet",
                  f"{state_name} = compile {value.profile} {value.function}() needs HLSL "
                  "compilation, which this framework does not do yet, so the shader cannot be "
                  "created")

    def check_assembly(self, value: Any, state_name: str, software: bool = False) -> None:
        if not isinstance(value, ShaderBlock):
            return
        from .asm import assemble_cached, card_limit_violations, check_cached
        try:
            program = assemble_cached(value)
        except EffectError as err:
            self.fail(err.location, state_name, "valid shader assembly", "assembly error", err.message)
            return
        for err in check_cached(program):
            self.fail(err.location, state_name, "valid shader assembly", "assembly error", err.message)
        if program.kind == "ps":
            self.report.render_targets = max(1, program.stats.highest.get("oC", 0) + 1)
        for loc, subject, requirement, card_value, message in card_limit_violations(
                program, self.profile, software=software):
            self.fail(loc, subject, requirement, card_value, f"{message}; the {self.card()} has {card_value}")

    # card quirks ---------------------------------------------------------------------------------
    def check_quirks(self) -> None:
        """Driver rules beyond the caps bits (caps.py documents the rule vocabulary). Rules of
        severity 'error' (ValidateDevice failed on the card) reject a technique; 'warning'
        rules are reported as warnings. cap_unreliable and format_unreliable are applied where
        the bit or format is checked."""
        for quirk in self.profile.quirks:
            rule = _QUIRK_CHECKS.get(quirk.rule)
            if rule is None:
                continue
            for loc, subject in rule(self, quirk):
                self.quirk_hit(quirk, loc, subject)

    def _quirk_arg_not_texture(self, quirk: Quirk) -> Iterable[tuple[Location, str]]:
        if self.shader("PixelShader") is not None:
            return
        channel = quirk.get("channel") or "both"
        prefixes = {"color": [("ColorOp", "ColorArg")], "alpha": [("AlphaOp", "AlphaArg")]}.get(
            channel, [("ColorOp", "ColorArg"), ("AlphaOp", "AlphaArg")])
        for stage in self.active_stages():
            for op_state, arg_prefix in prefixes:
                if self.state.enum_name(op_state, stage) != quirk.get("op"):
                    continue
                arg = f"{arg_prefix}{quirk.get('arg')}"
                if _ta_select(self.state.get(arg, stage)) == _TA_TEXTURE:
                    yield (self.where(arg, stage),
                           f"{op_state}[{stage}] = {self._shown(op_state, stage)} with {arg}[{stage}] = Texture")

    def _quirk_textures_need_op(self, quirk: Quirk) -> Iterable[tuple[Location, str]]:
        if self.shader("PixelShader") is not None:
            return
        units = self.sampled_units(False)
        if len(units) <= int(quirk.get("max_textures")):
            return
        ops = set(quirk.get("ops") or ())
        if not any(self.state.enum_name("ColorOp", s) in ops for s in self.active_stages()):
            yield self.where("Texture", units[-1]), f"{len(units)} textures in one pass"

    def _quirk_op_stages(self, quirk: Quirk) -> Iterable[tuple[Location, str]]:
        if self.shader("PixelShader") is not None:
            return
        allowed = set(quirk.get("stages") or ())
        for stage in self.active_stages():
            for op_state in ("ColorOp", "AlphaOp"):
                if self.state.enum_name(op_state, stage) == quirk.get("op") and stage not in allowed:
                    yield self.where(op_state, stage), f"{op_state}[{stage}] = {self._shown(op_state, stage)}"

    def _quirk_max_textures(self, quirk: Quirk) -> Iterable[tuple[Location, str]]:
        units = self.sampled_units(self.shader("PixelShader") is not None)
        if len(units) > int(quirk.get("count")):
            yield self.where("Texture", units[-1]), f"{len(units)} textures in one pass"


_QUIRK_CHECKS: dict[str, Callable[[_PassChecker, Quirk], Iterable[tuple[Location, str]]]] = {
    "arg_not_texture": _PassChecker._quirk_arg_not_texture,
    "textures_need_op": _PassChecker._quirk_textures_need_op,
    "op_stages": _PassChecker._quirk_op_stages,
    "max_textures": _PassChecker._quirk_max_textures,
}


def spelled(state_name: str, enum_name: str) -> str:
    """An enum value of a state as the D3D docs spell it ('BUMPENVMAP' → 'BumpEnvMap')."""
    info = state_table.lookup_state(state_name)
    if info is None or info.enum is None:
        return enum_name
    return info.enum.spelling(enum_name)


def _is_indexed(name: str) -> bool:
    info = state_table.lookup_state(name)
    return info is not None and info.index != "none"


def _int_value(value: Any) -> int | None:
    """An integer state value (enum, flags, bool, number) or None when it is not one."""
    if isinstance(value, EnumValue):
        value = value.value
    if isinstance(value, np.ndarray):
        if value.size != 1 or value.dtype.kind not in "biuf":
            return None
        value = value.reshape(-1)[0].item()
    if isinstance(value, (bool, int, np.integer)):
        return int(value)
    if isinstance(value, float) and value.is_integer():
        return int(value)
    return None


def _shown_scalar(value: Any) -> str:
    if isinstance(value, bool):
        return "True" if value else "False"
    return str(value)


def _ta_select(value: Any) -> int | None:
    v = _int_value(value)
    return None if v is None else v & _TA_SELECT_MASK


def texture_kind(param: Parameter, effect: Effect | None = None) -> str | None:
    """'2D', 'CUBE', '3D' or None (unknown): from a `string Type` annotation, the texture's own
    type (textureCUBE), or the type of a sampler whose sampler_state binds it (samplerCUBE)."""
    ann = _annotation_str(param, "Type") or _annotation_str(param, "TextureType")
    if ann:
        ann = ann.upper()
        return {"VOLUME": "3D", "CUBE": "CUBE", "3D": "3D", "2D": "2D", "1D": "1D"}.get(ann, ann)
    if param.type.dim:
        return param.type.dim
    if effect is not None:
        for sampler in effect.parameters:
            if sampler.type.base != "sampler" or not sampler.type.dim:
                continue
            values = sampler.value if isinstance(sampler.value, list) else [sampler.value]
            for s in values:
                bound = s.get("Texture") if isinstance(s, SamplerState) else None
                if bound is not None and isinstance(bound.value, ParamRef) and bound.value.name == param.name:
                    return sampler.type.dim
    return None


def _annotation_str(param: Parameter, name: str) -> str | None:
    a = param.annotation(name)
    return a.value if a is not None and isinstance(a.value, str) else None


def _annotation_int(param: Parameter, name: str) -> int | None:
    a = param.annotation(name)
    if a is None or isinstance(a.value, str):
        return None
    try:
        return int(np.asarray(a.value).reshape(-1)[0])
    except (IndexError, TypeError, ValueError):
        return None


def _annotation_bool(param: Parameter, name: str) -> bool:
    a = param.annotation(name)
    if a is None or isinstance(a.value, str):
        return False
    flat = np.asarray(a.value).reshape(-1)
    return bool(flat.size) and bool(flat[0])


def _shader_version(value: Any) -> tuple[int, int] | None:
    if isinstance(value, ShaderBlock):
        return _version(value.version) if value.version else None
    if isinstance(value, CompileShader):
        return _version(value.profile)
    return None


def _version_label(kind: str, version: tuple[int, int]) -> str:
    return f"{kind}_{version[0]}_{version[1]}"


def _block_location(value: Any, fallback: Location) -> Location:
    """Where a shader's version is written (the first token of an asm block), else where the
    shader is (a `compile` expression), else the assignment."""
    loc = getattr(value, "location", None)
    if loc is None or not loc.line:
        return fallback
    if isinstance(value, ShaderBlock):
        text = value.source
        start = len(text) - len(text.lstrip())
        if start < len(text):
            before = text[:start]
            lines = before.count("\n")
            if lines == 0:
                return Location(loc.path, loc.line, loc.column + start)
            return Location(loc.path, loc.line + lines, start - before.rfind("\n"))
    return loc


def _assembled(value: Any):
    """The assembled program of an asm shader, or None (not asm, or it does not assemble)."""
    if not isinstance(value, ShaderBlock):
        return None
    from .asm import assemble_cached
    try:
        return assemble_cached(value)
    except EffectError:
        return None


def _shader_samplers(value: Any) -> list[int] | None:
    program = _assembled(value)
    return None if program is None else sorted(program.stats.samplers_used)


def validate_technique(effect: Effect, technique: Technique, profile: CapsProfile) -> Validation:
    """Validate every pass of `technique` on `profile`, collecting all reasons."""
    reports = [_PassChecker(effect, technique, p, i, state, profile).run()
               for i, (p, state) in enumerate(pass_states(effect, technique.passes))]
    return Validation(technique, profile, reports)
