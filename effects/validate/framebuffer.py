"""Frame-buffer and render-state checks: every state whose row in the states table names the
caps field that limits it (`StateInfo.limit`: blend factors and ops, separate alpha blending,
alpha and depth compares, stencil ops, culling, depth writes, depth bias, scissor, table fog)
is checked by one loop over those rows; what no single caps bit covers (a stencil buffer at
all, blending into several render targets, write masks) is checked here by hand.

A mixin of `validate._PassChecker`: it uses the checker's state, profile, report
and reason helpers (fail, need_bit, where, unknown ...)."""
from __future__ import annotations

from typing import Any

import numpy as np

from effects.d3d9 import states as state_table
from effects.d3d9.device import is_on
from effects.model import EnumValue, Expression, ParamRef
from effects.validate.values import spelled



def _default_name(row: state_table.StateInfo) -> Any:
    default = state_table.default_value(row)
    return default.names[0] if isinstance(default, EnumValue) and default.names else default


# The limited render states in table order (the order their reasons are reported in), each
# with its D3D9 default and the bit that default needs (most need none, so most rows a pass
# leaves alone cost one dictionary lookup).
_LIMITED = tuple((row, _default_name(row), row.limit.bit_for(_default_name(row)))
                 for row in state_table.STATES if row.limit is not None and row.kind == "render")


class FrameBufferChecks:
    """The frame-buffer and render-state checks of a pass."""

    def enabled(self, name: str) -> bool:
        """Whether a bool state is on (a value the application has not set yet is off)."""
        value = self.state.get(name)
        if isinstance(value, (ParamRef, Expression)):
            return not self.unknown(name)   # notes why it is not checked; False
        return is_on(value)

    def check_framebuffer(self) -> None:
        stencil = self.check_stencil_buffer()
        for row, value, bit in self.card_free(("limited", stencil),
                                              lambda: self._limited_needs(stencil)):
            limit = row.limit
            if self.has_reliable_bit(limit.field, bit):
                continue   # the common case: nothing to say, no message built
            shown = spelled(row.name, value) if isinstance(value, str) else _shown_scalar(value)
            what = limit.describe(value)
            subject = f"{row.name} = {shown}" + (f" ({what})" if what else "")
            self.need_bit(limit.field, bit, subject, self.where(row.name))
        self.check_blend_targets()
        self.check_write_masks()

    def _limited_needs(self, stencil: bool) -> list[tuple[state_table.StateInfo, Any, str]]:
        """(row, value, bit) of each limited state the pass needs a caps bit for, in table
        order; the stencil states only where the card has a stencil buffer."""
        needs = []
        gates: dict[str, bool] = {}

        def gated(names: tuple[str, ...]) -> bool:
            for name in names:
                if name not in gates:
                    gates[name] = self.enabled(name)
                if not gates[name]:
                    return False
            return True

        assigned = self.state.values
        for row, default, default_bit in _LIMITED:
            limit = row.limit
            assert limit is not None
            if limit.field == "StencilCaps" and not stencil:
                continue
            if (row.name, None) in assigned:
                if not gated(limit.gate) or self.unknown(row.name):
                    continue
                value = self._limited_value(row)
                bit = limit.bit_for(value)
            else:
                # A default is checked only behind a gate, and only when it needs a bit.
                if not limit.gate or default_bit is None or not gated(limit.gate):
                    continue
                value, bit = default, default_bit
            if bit is not None:
                needs.append((row, value, bit))
        return needs

    def _limited_value(self, row: state_table.StateInfo) -> Any:
        if row.type == "enum":
            return self.state.get_enum(row.name, default=None)
        return _scalar(self.state.get(row.name))

    def check_stencil_buffer(self) -> bool:
        """False (with a reason) when the pass enables stencil on a card without a stencil
        buffer; the stencil ops are then not checked one by one."""
        if not self.enabled("StencilEnable"):
            return False
        if not self.profile.get("StencilCaps"):
            self.fail(self.where("StencilEnable"), "StencilEnable = True", "a stencil buffer",
                      "StencilCaps empty", f"StencilEnable needs a stencil buffer; the {self.card()} has none")
            return False
        return True

    def check_blend_targets(self) -> None:
        if self.enabled("AlphaBlendEnable") and self.report.render_targets > 1:
            self.need_bit("PrimitiveMiscCaps", "MRTPOSTPIXELSHADERBLENDING",
                          f"AlphaBlendEnable = True with {self.report.render_targets} render targets",
                          self.where("AlphaBlendEnable"))

    def check_write_masks(self) -> None:
        if self.state.assignment("ColorWriteEnable") is not None and not self.unknown("ColorWriteEnable"):
            if self.state.get_int("ColorWriteEnable", default=None) not in (0xF, None):
                self.need_bit("PrimitiveMiscCaps", "COLORWRITEENABLE",
                              f"ColorWriteEnable = {self._shown_flags('ColorWriteEnable')}",
                              self.where("ColorWriteEnable"))
        for n in (1, 2, 3):
            name = f"ColorWriteEnable{n}"
            if self.state.assignment(name) is None or self.unknown(name):
                continue
            if self.state.get_int(name, default=None) != self.state.get_int("ColorWriteEnable", default=None):
                self.need_bit("PrimitiveMiscCaps", "INDEPENDENTWRITEMASKS",
                              f"{name} = {self._shown_flags(name)}", self.where(name))


def _scalar(value: Any) -> Any:
    if isinstance(value, np.ndarray):
        return value.reshape(-1)[0].item() if value.size else None
    return value


def _shown_scalar(value: Any) -> str:
    if isinstance(value, bool):
        return "True" if value else "False"
    return str(value)
