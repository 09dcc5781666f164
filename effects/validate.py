"""Technique validation against a caps profile, collecting every reason a card cannot run it.

This plays the part of D3DX's ValidateTechnique + the driver's ValidateDevice: for each pass,
with the device state as the technique leaves it (earlier passes persist), every stage op,
argument, texture, filter, blend, compare, stencil op, shader version, shader limit and card
quirk is checked, and each failure becomes a `Reason` that names the pass, the state or
instruction, where it is, what it needs and what the card has.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Iterable

import numpy as np

from .caps import CapsProfile
from .device import MAX_SAMPLERS, MAX_STAGES, DeviceState, pass_states
from .errors import EffectError, Location
from . import states as state_table
from .model import (CompileShader, Effect, EnumValue, NullValue, Parameter, ParamRef, Pass,
                    ShaderBlock, Technique)


@dataclass(frozen=True)
class Reason:
    """Why a card cannot run a technique: one failed requirement, located."""

    technique: str | None
    pass_name: str
    location: Location
    subject: str       # what asked for it: "ColorOp[1] = BumpEnvMap", "ps_1_4", "texm3x3spec"
    requirement: str   # what it needs: "D3DTEXOPCAPS_BUMPENVMAP"
    card_value: str    # what the card has: "not in TextureOpCaps", "PixelShaderVersion 1.1"
    message: str       # one plain sentence

    def __str__(self) -> str:
        return f"pass {self.pass_name} (line {self.location.line}): {self.message}"


@dataclass
class PassReport:
    name: str
    index: int
    location: Location
    reasons: list[Reason] = field(default_factory=list)
    stages: int = 0             # fixed-function texture stages in use
    textures: int = 0           # textures bound at once
    pixel_shader: str | None = None
    vertex_shader: str | None = None

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


# ---------------------------------------------------------------------------------------------
# Tables: which caps field and bit a state value needs. Names are the enum names without
# prefix; the caps bit names are the D3D*CAPS_ names without prefix, which mostly coincide.

_FILTER_BITS = {  # (state, D3DTEXF name) -> D3DPTFILTERCAPS bit
    **{("MinFilter", f): f"MINF{f}" for f in ("POINT", "LINEAR", "ANISOTROPIC", "PYRAMIDALQUAD", "GAUSSIANQUAD")},
    **{("MagFilter", f): f"MAGF{f}" for f in ("POINT", "LINEAR", "ANISOTROPIC", "PYRAMIDALQUAD", "GAUSSIANQUAD")},
    **{("MipFilter", f): f"MIPF{f}" for f in ("POINT", "LINEAR")},
}
_TA_SELECT_MASK, _TA_COMPLEMENT, _TA_ALPHAREPLICATE = 0x0F, 0x10, 0x20
_TA_NAMES = {0: "DIFFUSE", 1: "CURRENT", 2: "TEXTURE", 3: "TFACTOR", 4: "SPECULAR", 5: "TEMP", 6: "CONSTANT"}
_OPS_READING_ARG0 = {"MULTIPLYADD", "LERP"}
_OPS_SAMPLING_WITHOUT_ARG = {"BLENDTEXTUREALPHA", "BLENDTEXTUREALPHAPM", "BUMPENVMAP", "BUMPENVMAPLUMINANCE"}
_STENCIL_OP_STATES = ("StencilFail", "StencilZFail", "StencilPass")
_CCW_STENCIL_OP_STATES = ("CCW_StencilFail", "CCW_StencilZFail", "CCW_StencilPass")
# vs versions a software (or mixed) vertex pipeline can run: the D3D9 runtime's emulation.
_SOFTWARE_VS_VERSION = (3, 0)


def _version(text: str | None) -> tuple[int, int]:
    if not text:
        return (0, 0)
    digits = [int(p) for p in text.replace("_", ".").split(".") if p.isdigit()]
    return (digits + [0, 0])[0], (digits + [0, 0])[1]


def _version_text(v: tuple[int, int]) -> str:
    return f"{v[0]}.{v[1]}"


class _PassChecker:
    """Runs every check for one pass and collects its reasons."""

    def __init__(self, effect: Effect, technique: Technique, p: Pass, index: int,
                 state: DeviceState, profile: CapsProfile) -> None:
        self.effect, self.technique, self.pass_, self.state, self.profile = effect, technique, p, state, profile
        self.report = PassReport(p.name or str(index), index, p.location)

    # -- reason helpers ---------------------------------------------------------------------
    def fail(self, location: Location, subject: str, requirement: str, card_value: str,
             message: str) -> None:
        self.report.reasons.append(Reason(self.technique.name, self.report.name, location,
                                          subject, requirement, card_value, message))

    def where(self, name: str, index: int | None = None) -> Location:
        a = self.state.assignment(name, index)
        return a.location if a is not None else self.pass_.location

    def card(self) -> str:
        return self.profile.display_name

    def need_bit(self, caps_field: str, bit: str, subject: str, location: Location,
                 prefix: str) -> None:
        if not self.profile.has(caps_field, bit):
            self.fail(location, subject, f"{prefix}{bit}", f"not in {caps_field}",
                      f"{subject} needs {prefix}{bit}; the {self.card()} does not have it")

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
        self.check_quirks()
        return self.report

    def shader(self, name: str) -> tuple[Any, Location] | None:
        a = self.state.assignment(name)
        if a is None:
            return None
        value = self.state.resolve(a.value)
        if isinstance(value, (NullValue, type(None))) or (isinstance(value, ParamRef)):
            return None if not isinstance(value, ParamRef) else (value, a.location)
        return value, a.location

    # fixed-function texture stages ----------------------------------------------------------
    def active_stages(self) -> list[int]:
        stages = []
        for stage in range(MAX_STAGES):
            if self.state.enum_name("ColorOp", stage) in (None, "DISABLE"):
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

    def check_stage(self, stage: int) -> None:
        for op_state, arg_prefix in (("ColorOp", "ColorArg"), ("AlphaOp", "AlphaArg")):
            op = self.state.enum_name(op_state, stage)
            if op is None or (op_state == "AlphaOp" and op == "DISABLE"):
                continue
            shown = self._shown(op_state, stage)
            self.need_bit("TextureOpCaps", op, f"{op_state}[{stage}] = {shown}",
                          self.where(op_state, stage), "D3DTEXOPCAPS_")
            used_args = (1, 2) if op not in _OPS_READING_ARG0 else (0, 1, 2)
            if op == "SELECTARG1":
                used_args = (1,)
            elif op == "SELECTARG2":
                used_args = (2,)
            for n in used_args:
                self.check_arg(f"{arg_prefix}{n}", stage)
        result = self.state.get("ResultArg", stage)
        if _ta_select(result) == 5:
            self.need_bit("PrimitiveMiscCaps", "TSSARGTEMP", f"ResultArg[{stage}] = Temp",
                          self.where("ResultArg", stage), "D3DPMISCCAPS_")

    def check_arg(self, state_name: str, stage: int) -> None:
        value = self.state.get(state_name, stage)
        select = _ta_select(value)
        if select == 5:
            self.need_bit("PrimitiveMiscCaps", "TSSARGTEMP", f"{state_name}[{stage}] = Temp",
                          self.where(state_name, stage), "D3DPMISCCAPS_")
        elif select == 6:
            self.need_bit("PrimitiveMiscCaps", "PERSTAGECONSTANT", f"{state_name}[{stage}] = Constant",
                          self.where(state_name, stage), "D3DPMISCCAPS_")

    def _shown(self, name: str, index: int | None = None) -> str:
        """A state's value as the docs spell it ('BumpEnvMap', 'Texture | Complement')."""
        return spelled(name, self.state.enum_name(name, index) or "default")

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
            ops = (self.state.enum_name("ColorOp", stage), self.state.enum_name("AlphaOp", stage))
            reads = any(op in _OPS_SAMPLING_WITHOUT_ARG for op in ops)
            for prefix in ("ColorArg", "AlphaArg"):
                for n in (0, 1, 2):
                    if _ta_select(self.state.get(f"{prefix}{n}", stage)) == 2:
                        reads = True
            if reads and self.state.assignment("Texture", stage) is not None:
                units.append(stage)
        return units

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
            self.check_texture_resource(unit)
            self.check_sampler_states(unit)

    def texture_parameter(self, unit: int) -> Parameter | None:
        a = self.state.assignment("Texture", unit)
        if a is None or not isinstance(a.value, ParamRef):
            return None
        return self.effect.parameter(a.value.name)

    def check_texture_resource(self, unit: int) -> None:
        param = self.texture_parameter(unit)
        if param is None:
            return
        loc = self.where("Texture", unit)
        subject = f"Texture[{unit}] = <{param.name}>"
        kind = texture_kind(param)
        if kind == "CUBE":
            self.need_bit("TextureCaps", "CUBEMAP", subject + " (a cube map)", loc, "D3DPTEXTURECAPS_")
        elif kind == "3D":
            self.need_bit("TextureCaps", "VOLUMEMAP", subject + " (a volume texture)", loc, "D3DPTEXTURECAPS_")
        width, height = _annotation_int(param, "Width"), _annotation_int(param, "Height")
        for value, cap in ((width, "MaxTextureWidth"), (height, "MaxTextureHeight")):
            if value is not None and value > int(self.profile.get(cap, 0)):
                self.fail(param.location, subject, f"{cap} >= {value}", f"{cap} {self.profile.get(cap)}",
                          f"{subject} is {value} texels along one side; the {self.card()} allows "
                          f"{self.profile.get(cap)} ({cap})")
        for value in (width, height):
            if value and value & (value - 1) and self.profile.has("TextureCaps", "POW2") \
                    and not self.profile.has("TextureCaps", "NONPOW2CONDITIONAL"):
                self.fail(param.location, subject, "non-power-of-two textures", "TextureCaps POW2",
                          f"{subject} is {value} texels wide or high, not a power of two; the "
                          f"{self.card()} needs power-of-two sizes")
                break
        fmt = _annotation_str(param, "Format")
        if fmt:
            usage = {"CUBE": "cube", "3D": "volume"}.get(kind or "", "texture")
            wanted = [usage] + (["rendertarget"] if _annotation_bool(param, "RenderTarget") else [])
            usages = self.profile.format_usages(fmt.upper())
            for use in wanted:
                if use not in usages:
                    what = {"rendertarget": "as a render target", "texture": "for a texture"}.get(
                        use, f"for a {use} texture")
                    self.fail(param.location, f"{subject} Format = {fmt}", f"format {fmt.upper()} ({use})",
                              "supported usages: " + (", ".join(sorted(usages)) or "none"),
                              f"{subject} uses the format {fmt.upper()} {what}; the {self.card()} "
                              f"does not support that")

    def check_sampler_states(self, unit: int) -> None:
        for name in ("MinFilter", "MagFilter", "MipFilter"):
            value = self.state.enum_name(name, unit)
            if value is None or value == "NONE":
                continue
            bit = _FILTER_BITS.get((name, value))
            if bit:
                self.need_bit("TextureFilterCaps", bit, f"{name}[{unit}] = {spelled(name, value)}",
                              self.where(name, unit), "D3DPTFILTERCAPS_")
        for name in ("AddressU", "AddressV", "AddressW"):
            if self.state.assignment(name, unit) is None:
                continue
            value = self.state.enum_name(name, unit)
            if value:
                self.need_bit("TextureAddressCaps", value, f"{name}[{unit}] = {spelled(name, value)}",
                              self.where(name, unit), "D3DPTADDRESSCAPS_")

    # frame-buffer operations ---------------------------------------------------------------------
    def enabled(self, name: str) -> bool:
        value = self.state.get(name)
        return bool(value) and not isinstance(value, ParamRef)

    def check_blending(self) -> None:
        if self.enabled("AlphaBlendEnable"):
            for name, caps_field in (("SrcBlend", "SrcBlendCaps"), ("DestBlend", "DestBlendCaps")):
                value = self.state.enum_name(name)
                if value:
                    self.need_bit(caps_field, value, f"{name} = {spelled(name, value)}", self.where(name), "D3DPBLENDCAPS_")
            op = self.state.enum_name("BlendOp")
            if op and op != "ADD":
                self.need_bit("PrimitiveMiscCaps", "BLENDOP", f"BlendOp = {spelled('BlendOp', op)}",
                              self.where("BlendOp"), "D3DPMISCCAPS_")
            if self.enabled("SeparateAlphaBlendEnable"):
                self.need_bit("PrimitiveMiscCaps", "SEPARATEALPHABLEND", "SeparateAlphaBlendEnable = True",
                              self.where("SeparateAlphaBlendEnable"), "D3DPMISCCAPS_")
        mask = self.state.assignment("ColorWriteEnable")
        if mask is not None and self.state.get("ColorWriteEnable") not in (0xF, None):
            self.need_bit("PrimitiveMiscCaps", "COLORWRITEENABLE", "ColorWriteEnable",
                          mask.location, "D3DPMISCCAPS_")

    def check_compares(self) -> None:
        if self.enabled("AlphaTestEnable"):
            value = self.state.enum_name("AlphaFunc")
            if value:
                self.need_bit("AlphaCmpCaps", value, f"AlphaFunc = {spelled('AlphaFunc', value)}", self.where("AlphaFunc"), "D3DPCMPCAPS_")
        if self.state.assignment("ZFunc") is not None:
            value = self.state.enum_name("ZFunc")
            if value:
                self.need_bit("ZCmpCaps", value, f"ZFunc = {spelled('ZFunc', value)}", self.where("ZFunc"), "D3DPCMPCAPS_")

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
            value = self.state.enum_name(name)
            if value and self.state.assignment(name) is not None:
                self.need_bit("StencilCaps", value, f"{name} = {spelled(name, value)}", self.where(name), "D3DSTENCILCAPS_")

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
        self.check_assembly(value, "PixelShader")

    def check_vertex_shader(self, shader: tuple[Any, Location]) -> None:
        value, loc = shader
        version = _shader_version(value)
        if version is None:
            return
        label = _version_label("vs", version)
        self.report.vertex_shader = label
        hardware = self.profile.vertex_shader_version
        processing = self.profile.vertex_processing
        software_ok = bool(processing & {"software", "mixed"}) and version <= _SOFTWARE_VS_VERSION
        if version > hardware and not software_ok:
            limit = (f"runs vertex shaders up to {_version_label('vs', hardware)}" if hardware > (0, 0)
                     else "has no vertex shader hardware")
            self.fail(_block_location(value, loc), f"VertexShader ({label})",
                      f"VertexShaderVersion >= {_version_text(version)} or software vertex processing",
                      f"VertexShaderVersion {_version_text(hardware)}, processing: {', '.join(sorted(processing))}",
                      f"VertexShader is {label}; the {self.card()} {limit} "
                      f"and offers no software vertex processing")
            return
        self.check_assembly(value, "VertexShader", software=version > hardware)

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
        for loc, subject, requirement, card_value, message in card_limit_violations(
                program, self.profile, software=software):
            self.fail(loc, subject, requirement, card_value, f"{message}; the {self.card()} has {card_value}")

    # card quirks ---------------------------------------------------------------------------------
    def check_quirks(self) -> None:
        """Driver rules beyond the caps bits (caps.py documents the rule vocabulary). Only
        rules of severity 'error' (ValidateDevice failed on the card) reject a technique."""
        for quirk in self.profile.quirks:
            rule = _QUIRK_CHECKS.get(quirk.rule)
            if rule is None or quirk.severity != "error":
                continue
            for loc, subject in rule(self, quirk):
                self.fail(loc, subject, f"driver rule {quirk.id}", quirk.text,
                          f"{subject}: {quirk.text} ({self.card()})")

    def _quirk_arg_not_texture(self, quirk) -> Iterable[tuple[Location, str]]:
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
                if _ta_select(self.state.get(arg, stage)) == 2:
                    yield self.where(arg, stage), f"{op_state}[{stage}] = {self._shown(op_state, stage)} with {arg}[{stage}] = Texture"

    def _quirk_textures_need_op(self, quirk) -> Iterable[tuple[Location, str]]:
        if self.shader("PixelShader") is not None:
            return
        units = self.sampled_units(False)
        if len(units) <= int(quirk.get("max_textures")):
            return
        ops = set(quirk.get("ops") or ())
        if not any(self.state.enum_name("ColorOp", s) in ops for s in self.active_stages()):
            yield self.where("Texture", units[-1]), f"{len(units)} textures in one pass"

    def _quirk_op_stages(self, quirk) -> Iterable[tuple[Location, str]]:
        allowed = set(quirk.get("stages") or ())
        for stage in self.active_stages():
            for op_state in ("ColorOp", "AlphaOp"):
                if self.state.enum_name(op_state, stage) == quirk.get("op") and stage not in allowed:
                    yield self.where(op_state, stage), f"{op_state}[{stage}] = {self._shown(op_state, stage)}"

    def _quirk_max_textures(self, quirk) -> Iterable[tuple[Location, str]]:
        units = self.sampled_units(self.shader("PixelShader") is not None)
        if len(units) > int(quirk.get("count")):
            yield self.where("Texture", units[-1]), f"{len(units)} textures in one pass"


_QUIRK_CHECKS: dict[str, Callable[[_PassChecker, Any], Iterable[tuple[Location, str]]]] = {
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


def _ta_select(value: Any) -> int | None:
    if isinstance(value, EnumValue):
        value = value.value
    if isinstance(value, (int, np.integer)):
        return int(value) & _TA_SELECT_MASK
    return None


def texture_kind(param: Parameter) -> str | None:
    """'2D', 'CUBE', '3D' or None (unknown) from the type or a `string Type` annotation."""
    ann = _annotation_str(param, "Type") or _annotation_str(param, "TextureType")
    if ann:
        ann = ann.upper()
        return {"VOLUME": "3D", "CUBE": "CUBE", "3D": "3D", "2D": "2D", "1D": "1D"}.get(ann, ann)
    return param.type.dim or None


def _annotation_str(param: Parameter, name: str) -> str | None:
    a = param.annotation(name)
    return a.value if a is not None and isinstance(a.value, str) else None


def _annotation_int(param: Parameter, name: str) -> int | None:
    a = param.annotation(name)
    if a is None or isinstance(a.value, str):
        return None
    return int(np.asarray(a.value).reshape(-1)[0])


def _annotation_bool(param: Parameter, name: str) -> bool:
    a = param.annotation(name)
    return a is not None and not isinstance(a.value, str) and bool(np.asarray(a.value).reshape(-1)[0])


def _shader_version(value: Any) -> tuple[int, int] | None:
    if isinstance(value, ShaderBlock):
        return _version(value.version) if value.version else None
    if isinstance(value, CompileShader):
        return _version(value.profile)
    return None


def _version_label(kind: str, version: tuple[int, int]) -> str:
    return f"{kind}_{version[0]}_{version[1]}"


def _block_location(value: Any, fallback: Location) -> Location:
    return getattr(value, "location", None) or fallback


def _shader_samplers(value: Any) -> list[int] | None:
    if not isinstance(value, ShaderBlock):
        return None
    from .asm import assemble_cached
    try:
        return sorted(assemble_cached(value).stats.samplers_used)
    except EffectError:
        return None


def validate_technique(effect: Effect, technique: Technique, profile: CapsProfile) -> Validation:
    """Validate every pass of `technique` on `profile`, collecting all reasons."""
    reports = [_PassChecker(effect, technique, p, i, state, profile).run()
               for i, (p, state) in enumerate(pass_states(effect, technique.passes))]
    return Validation(technique, profile, reports)
