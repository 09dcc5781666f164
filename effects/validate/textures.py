"""Texture, sampler and format checks: how many textures a pass reads, their kind (cube,
volume) against TextureCaps, their declared size and format, and each sampler's filters,
mip filter, anisotropy and address modes.

A mixin of `validate._PassChecker`: it uses the checker's state, profile, report
and reason helpers (fail, need_bit, where, unknown ...)."""
from __future__ import annotations

from typing import Any

import numpy as np

from effects.d3d9 import states as state_table
from effects.d3d9.caps import FIELDS, FORMATS
from effects.base.errors import EffectError
from effects.model import Effect, Parameter, ParamRef, ShaderBlock
from effects.d3d9.stage_ops import (MAX_SAMPLERS, TA_TEXTURE, TCI_CAMERA_SPACE, TCI_SHIFT,
                               TTFF_COUNT_MASK, TTFF_PROJECTED)
from effects.validate.stages import _args_read, _stage_op
from effects.validate.values import spelled

# The filter and address bits each value needs are the sampler states' rows in effects.d3d9.states
# (StateInfo.limit); the field depends on the texture's kind. Filter caps field per texture
# kind (a card without the field uses TextureFilterCaps).
_LIMITS = {name: state_table.lookup_state(name).limit
           for name in ("MinFilter", "MagFilter", "MipFilter", "AddressU", "AddressV", "AddressW")}
_FILTER_FIELD = {"CUBE": "CubeTextureFilterCaps", "3D": "VolumeTextureFilterCaps"}
# What a sampler state asks of a card besides a fixed field's bit (`_sampler_needs`).
_FILTER, _NO_FILTER, _ANISOTROPY, _ADDRESS = (object() for _ in range(4))
# ps_1_1-1_3 instructions that look up a cube map (the ps_1_x instruction pages).
_CUBE_LOOKUPS_PS1 = frozenset({"texm3x3tex", "texm3x3spec", "texm3x3vspec"})


class TextureChecks:
    """The texture and sampler checks of a pass."""

    def sampled_units(self, shader: bool) -> list[int]:
        """Stages/samplers whose texture is read in this pass."""
        if shader:
            ps = self.shader("PixelShader")
            asm = self.asm_shader(ps[0]) if ps else None
            if asm is not None:
                return [b.register for b in asm.samplers]
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
            op = self.state.get_enum(op_state, stage, default=None)
            if op is None:
                return True   # unknown op: assume it reads what is bound
            row = _stage_op(op)
            if row is not None and row.samples:
                return True
            for n in _args_read(op):
                arg = f"{arg_prefix}{n}"
                if not self.state.known(arg, stage) or self.arg_select(arg, stage) == TA_TEXTURE:
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
            asm = self.asm_shader(ps[0]) if ps else None
            if asm is None:
                return None, ""
            program = asm.program
            for d in program.dcls:
                if d.register.kind == "s" and d.register.index == unit and d.sampler_type in ("cube", "volume"):
                    return ("CUBE" if d.sampler_type == "cube" else "3D"), f"declared by dcl_{d.sampler_type} s{unit}"
            for ins in program.instructions:
                if ins.opcode in _CUBE_LOOKUPS_PS1 and ins.dst is not None and ins.dst.index == unit:
                    return "CUBE", f"read by {ins.opcode} t{unit}"
            return None, ""
        tci = self.state.get_int("TexCoordIndex", unit, default=None) or 0
        flags = self.state.get_int("TextureTransformFlags", unit, default=None) or 0
        # camera-space texgen with three coordinates (COUNT3): a fixed-function cube lookup
        if (tci >> TCI_SHIFT) in TCI_CAMERA_SPACE and flags & TTFF_COUNT_MASK == 3 \
                and not flags & TTFF_PROJECTED:
            return "CUBE", "looked up with 3-component camera-space texture coordinates"
        return None, ""

    def asm_shader(self, value: Any) -> Any:
        """The Shader of a pixel shader's asm block (`program`), or None: not assembly, or
        it does not assemble (the shader checks say why). For an HLSL shader the units are
        read from the pass's Texture states."""
        if not isinstance(value, ShaderBlock):
            return None
        try:
            return self.program(value, "PixelShader")
        except EffectError:
            return None

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
            self.need_bit("TextureCaps", "CUBEMAP", f"{subject} (a cube map{because})", loc)
        elif kind == "3D":
            self.need_bit("TextureCaps", "VOLUMEMAP", f"{subject} (a volume texture{because})", loc)
        self.check_texture_size(unit, param, kind, subject)
        self.check_texture_format(unit, param, kind, subject)
        flags = self.state.get_int("TextureTransformFlags", unit, default=None)
        if (self.state.assignment("TextureTransformFlags", unit) is not None and flags is not None
                and flags & TTFF_PROJECTED):
            self.need_bit("TextureCaps", "PROJECTED", f"TextureTransformFlags[{unit}] = Projected",
                          self.where("TextureTransformFlags", unit))

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
            if self.state.get_enum(name, unit, default=None) != "CLAMP":
                self.fail(self.where(name, unit), f"{subject} with {name}[{unit}] = {self._shown(name, unit)}",
                          "D3DTADDRESS_CLAMP for a non-power-of-two texture", "TextureCaps NONPOW2CONDITIONAL",
                          f"{subject} is {shown}, not a power of two; the {self.card()} takes such "
                          f"a texture only with {name} = Clamp")
        if self.state.get_enum("MipFilter", unit, default=None) not in ("NONE", None):
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
        # a render target: `bool RenderTarget = true`, or a DXSAS script's target (semantic
        # RENDERCOLORTARGET), which the card must create with D3DUSAGE_RENDERTARGET
        if _annotation_bool(param, "RenderTarget") or \
                (param.semantic or "").upper() == "RENDERCOLORTARGET":
            wanted.append("rendertarget")
        if any(self.state.get_enum(f, unit, default=None) in ("LINEAR", "ANISOTROPIC", "PYRAMIDALQUAD", "GAUSSIANQUAD")
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

    def check_sampler_states(self, unit: int, kind: str | None,
                             filter_field: str | None = None) -> None:
        """Filters against the kind's filter caps (or `filter_field`: a vertex texture's are
        VertexTextureFilterCaps), mipmapping, anisotropy and address modes."""
        filter_field = filter_field or _FILTER_FIELD.get(kind or "", "TextureFilterCaps")
        if self.profile.get(filter_field) is None:
            filter_field = "TextureFilterCaps"
        address_field = "VolumeTextureAddressCaps" if kind == "3D" and self.profile.get(
            "VolumeTextureAddressCaps") is not None else "TextureAddressCaps"
        for what, name, bit, subject, location in self.card_free(
                ("samplers", unit, kind), lambda: self._sampler_needs(unit, kind)):
            if what is _FILTER:
                self.need_bit(filter_field, bit, subject, location)
            elif what is _NO_FILTER:
                self.fail(location, subject, f"a {name} the card filters with",
                          f"not in {filter_field}",
                          f"{subject} is not a {name[:3].lower()}ification filter a Direct3D 9 "
                          f"card reports; the {self.card()} does not have it")
            elif what is _ADDRESS:
                self.need_bit(address_field, bit, subject, location)
            elif what is _ANISOTROPY:
                wanted = bit
                have = int(self.profile.get("MaxAnisotropy", 1) or 1)
                if wanted > have:
                    self.fail(location, subject, f"MaxAnisotropy >= {wanted}", f"MaxAnisotropy {have}",
                              f"{subject}; the {self.card()} filters with at most {have}")
            else:   # a bit of a field that does not depend on the texture's kind
                self.need_bit(what, bit, subject, location)

    def _sampler_needs(self, unit: int, kind: str | None) -> list[tuple[Any, str, Any, str, Any]]:
        """What `check_sampler_states` asks of each card, in its order: (what, state name, bit
        or value, subject, location); `what` is a caps field or _FILTER (the kind's filter
        field), _NO_FILTER (a value no card filters with), _ANISOTROPY, _ADDRESS (the kind's
        address field)."""
        needs: list[tuple[Any, str, Any, str, Any]] = []
        for name in ("MinFilter", "MagFilter", "MipFilter"):
            if self.unknown(name, unit):
                continue
            value = self.state.get_enum(name, unit, default=None)
            if value is None or value == "NONE":
                continue
            subject = f"{name}[{unit}] = {spelled(name, value)}"
            bit = _LIMITS[name].bit_for(value)
            if bit not in (FIELDS["TextureFilterCaps"].table or {}):
                needs.append((_NO_FILTER, name, bit, subject, self.where(name, unit)))
                continue
            needs.append((_FILTER, name, bit, subject, self.where(name, unit)))
        mip = self.state.get_enum("MipFilter", unit, default=None)
        if mip not in (None, "NONE"):
            mip_bit = {"CUBE": "MIPCUBEMAP", "3D": "MIPVOLUMEMAP"}.get(kind or "", "MIPMAP")
            needs.append(("TextureCaps", "MipFilter", mip_bit,
                          f"MipFilter[{unit}] = {spelled('MipFilter', mip)}",
                          self.where("MipFilter", unit)))
        if self.state.assignment("MaxAnisotropy", unit) is not None and not self.unknown("MaxAnisotropy", unit):
            wanted = self.state.get_int("MaxAnisotropy", unit, default=None)
            if wanted is not None:
                needs.append((_ANISOTROPY, "MaxAnisotropy", wanted,
                              f"MaxAnisotropy[{unit}] = {wanted}", self.where("MaxAnisotropy", unit)))
        names = ("AddressU", "AddressV", "AddressW") if kind == "3D" else ("AddressU", "AddressV")
        for name in names:
            if self.state.assignment(name, unit) is None or self.unknown(name, unit):
                continue
            value = self.state.get_enum(name, unit, default=None)
            if value:
                needs.append((_ADDRESS, name, _LIMITS[name].bit_for(value),
                              f"{name}[{unit}] = {spelled(name, value)}", self.where(name, unit)))
        return needs


def texture_kind(param: Parameter, effect: Effect | None = None) -> str | None:
    """'2D', 'CUBE', '3D' or None (unknown): from a `string Type` annotation, the texture's own
    type (textureCUBE), or the type of a sampler whose sampler_state binds it (samplerCUBE)."""
    ann = _annotation_str(param, "Type") or _annotation_str(param, "TextureType")
    if ann:
        ann = ann.upper()
        return {"VOLUME": "3D", "CUBE": "CUBE", "3D": "3D", "2D": "2D", "1D": "1D"}.get(ann, ann)
    if param.type.dim:
        return param.type.dim
    if effect is not None:   # a map built once per effect, not a scan per texture
        return effect.sampler_dim_of(param.name)
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

