"""Vertex texture checks: a vs_3_0 shader that samples (texldl on s0-s3) reads the vertex
texture samplers D3DVERTEXTEXTURESAMPLER0-3 (samplers 257-260 of the pass), and a card runs it
only with a texture in a format it accepts for vertex texturing and with filters it reports.

Sources: DirectX 9 "Vertex Textures in vs_3_0" (four vertex samplers, SetTexture with stage
D3DVERTEXTEXTURESAMPLER0..3; a format is usable when CheckDeviceFormat with
D3DUSAGE_QUERY_VERTEXTEXTURE accepts it; VertexTextureFilterCaps says which filters these
samplers take, never anisotropic; the LOD is the shader's, as texldl gives it; software vertex
processing supports the feature, with the textures in the scratch pool). Which formats a card
accepts is its profile's `vertextexture` usage: the GeForce 6800 R32F and A32B32G32R32F
(docs/reference/caps.md 2.14); ATI's Radeon X1000 parts report vs_3_0 and
VertexTextureFilterCaps but accept no format (behardware.com "ATI's demos without vertex
texturing", 2006; the radeonx1800 profile), so a vertex texture fails there whatever its format.

Decisions:
- A texture whose format the file does not declare (`string Format = "R32F"`) is not judged by
  its format (as pixel textures are not), except on a card that accepts vertex textures in no
  format at all: there every vertex texture fails.
- A vertex shader run by software vertex processing samples in the runtime: its vertex
  textures are not held to the hardware's formats and filter caps (a note says so).
- A cube or volume vertex texture needs its format's `cube` / `volume` usage too.

Which samplers a vertex shader reads, and the device sampler each is, are the shader's bindings
(`effects.shaders.shader_value`), settled once for validation and lowering alike.

A mixin of `validate._PassChecker`: it uses the checker's state, profile, report and reason
helpers (fail, need_bit, where, note ...)."""
from __future__ import annotations

from typing import Any

from effects.base.errors import EffectError, Location
from effects.validate.textures import _annotation_str, texture_kind


class VertexTextureChecks:
    """The vertex texture checks of a pass with a vertex shader."""

    def check_vertex_textures(self, shader: tuple[Any, Location]) -> None:
        try:
            found = self.program(shader[0], "VertexShader")
        except EffectError:
            return                                   # the shader checks report it
        if found is None or found.kind != "vs":
            return
        # the vertex texture samplers the shader samples (texldl), as its bindings settle them
        reads = [b for b in found.samplers if b.read_at is not None]
        if not reads:
            return
        if self.report.software_vertex_processing:
            self.note("the vertex shader's textures are sampled by software vertex processing "
                      "(scratch-pool textures, any format the runtime reads)")
            return
        accepted = sorted(f for f in self.profile.caps.get("TextureFormats", {})
                          if "vertextexture" in self.profile.format_usages(f))
        for binding in reads:
            unit, where = binding.unit, binding.read_at
            subject = f"VertexShader texldl on s{binding.register} (vertex texture sampler {unit})"
            if not accepted:
                self.fail(where, subject, "a texture format with D3DUSAGE_QUERY_VERTEXTEXTURE",
                          "no vertex texture format",
                          f"{subject}: the {self.card()} reports vs_3_0 but accepts vertex "
                          "textures in no format, so no texture can be read here")
                continue
            param = self.texture_parameter(unit)
            kind = texture_kind(param, self.effect) if param is not None else None
            if param is not None:
                self.check_texture_resource(unit, param, kind)
                self.check_vertex_format(unit, param, kind, accepted)
            self.check_sampler_states(unit, kind, filter_field="VertexTextureFilterCaps")

    def check_vertex_format(self, unit: int, param: Any, kind: str | None,
                            accepted: list[str]) -> None:
        fmt = _annotation_str(param, "Format")
        if not fmt:
            return
        name = fmt.upper().removeprefix("D3DFMT_")
        usages = self.profile.format_usages(name)
        if not usages:
            return                                   # check_texture_format reported it
        ann = param.annotation("Format")
        loc = ann.location if ann is not None and ann.location.line else param.location
        subject = f"Texture[{unit}] = <{param.name}> Format = {name}"
        wanted = ["vertextexture"] + [u for k, u in (("CUBE", "cube"), ("3D", "volume"))
                                      if kind == k]
        missing = [u for u in wanted if u not in usages]
        if missing:
            what = "a vertex texture" + ("" if kind not in ("CUBE", "3D") else
                                         f" ({'cube' if kind == 'CUBE' else 'volume'})")
            self.fail(loc, subject, f"format {name} ({', '.join(missing)})",
                      "vertex texture formats: " + ", ".join(accepted),
                      f"{subject} is read as {what}; the {self.card()} takes vertex textures "
                      f"only in {', '.join(accepted)}")

