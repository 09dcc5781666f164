"""Frame-buffer and render-state checks for the states a pass assigns: blend factors and ops,
separate alpha blending, write masks, alpha and depth compares, stencil, and the render-state
table (culling, depth writes, depth bias, scissor, table fog).

A mixin of `validate._PassChecker`: it uses the checker's state, profile, report
and reason helpers (fail, need_bit, where, unknown ...)."""
from __future__ import annotations

from typing import Any, Callable

import numpy as np

from effects.model import EnumValue, NullValue, ParamRef
from effects.validate.values import _int_value, spelled

# Enum names are the states table's canonical names (no prefix); caps bits are the
# D3D*CAPS_ names without prefix, which mostly coincide. Sources: d3d9types.h / d3d9caps.h as
# documented (D3DBLEND, D3DPBLENDCAPS, D3DCMPFUNC, D3DSTENCILCAPS ...).

# Blend factors whose caps bit has another name.
_BLEND_BITS = {"INVBLENDFACTOR": "BLENDFACTOR"}
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


class FrameBufferChecks:
    """The frame-buffer and render-state checks of a pass."""

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


def _shown_scalar(value: Any) -> str:
    if isinstance(value, bool):
        return "True" if value else "False"
    return str(value)
