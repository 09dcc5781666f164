"""Shader constant states against the register files they write (`VertexShaderConstantF[n]`,
`PixelShaderConstantI[n]`, ... : n is the first register a value sets).

Direct3D 9 refuses a Set*ShaderConstant* call whose register range leaves the device's file
("the runtime validates that the specified register range lies within the legal range",
D3DHAL_DP2SETPIXELSHADERCONST and D3DHAL_DP2SETVERTEXSHADERCONST):
- integer and boolean registers: 16 of each, on every card (the states table refuses a first
  register past them when the effect loads; a value running past the last is judged here);
- vertex float registers: the card's MaxVertexShaderConst in hardware, 8192 when the pass's
  vertex shader runs in software vertex processing or the card has no vertex shader hardware
  but offers software processing;
- pixel float registers: those of the highest pixel shader version the card runs (8 for
  ps_1_x, 32 for ps_2_x, 224 for ps_3_0; none on a card without pixel shaders).
A parameter without a value fills the registers its type does.

A mixin of `validate._PassChecker`.
"""
from __future__ import annotations

from typing import Any

import numpy as np

from effects.d3d9 import states as state_table
from effects.model import Expression, NullValue, ParamRef
from effects.shaders.asm.limits import SOFTWARE_VS_CONSTANTS
from effects.shaders.asm.versions import VERSIONS
from effects.validate.shaders import software_vs_version

_KIND = {"I": ("i", "integer"), "B": ("b", "boolean")}   # else c#, float


class ConstantChecks:
    """The constant-register checks of a pass."""

    def check_constant_registers(self) -> None:
        for (name, index), assignment in self.state.items():
            info = state_table.lookup_state(name)
            if info is None or info.kind != "shader_const" or index is None:
                continue
            registers = self._registers_set(info, assignment.value)
            if registers is None:
                continue
            stage = "Vertex" if info.name.startswith("Vertex") else "Pixel"
            letter, kind = _KIND.get(info.name[-1], ("c", "float"))
            if letter == "c":
                file, why = self._float_file(stage)
            else:
                file = state_table.INT_BOOL_CONSTANT_REGISTERS
                why = f"Direct3D 9 has {file} {kind} registers ({letter}0..{letter}{file - 1})"
            last = index + max(registers, 1) - 1
            if last < file:
                continue
            shown = f"{letter}{index}" + (f"..{letter}{last}" if last > index else "")
            self.fail(assignment.location, f"{info.name}[{index}]",
                      f"{stage.lower()} shader {kind} registers up to {letter}{last}",
                      f"{file} registers",
                      f"{info.name}[{index}] sets {shown}; {why}")

    def _registers_set(self, info: Any, value: Any) -> int | None:
        """How many registers the value in force sets; None when that waits on the
        application (an expression) or nothing is set (NULL)."""
        resolved = self.state.resolve(value)
        if isinstance(resolved, (Expression, NullValue)) or resolved is None:
            return None
        if isinstance(resolved, ParamRef):   # no value yet: the registers its type fills
            param = self.effect.parameter(resolved.name)
            if param is None or not param.type.is_numeric:
                return None
            count = param.type.components * (1 if resolved.index is not None
                                             else int(np.prod(param.array or (1,))))
            return state_table.constant_register_count(info, count)
        try:
            count = np.asarray(resolved, dtype=np.float64).size
        except (TypeError, ValueError):
            return None   # not numbers: lowering says so, located
        return state_table.constant_register_count(info, count)

    def _float_file(self, stage: str) -> tuple[int, str]:
        """The card's float constant registers for `stage`, and the words that say so."""
        card = self.card()
        if stage == "Pixel":
            major, minor = self.profile.pixel_shader_version
            if major == 0:
                return 0, f"the {card} has no pixel shaders, so no pixel shader constant registers"
            version = f"ps_{major}_{minor}" if f"ps_{major}_{minor}" in VERSIONS else f"ps_{major}_0"
            file = VERSIONS[version].registers["c"]
            return file, f"the {card}'s pixel shaders ({version}) have c0..c{file - 1}"
        hardware = self.profile.get("MaxVertexShaderConst") or 0
        software = software_vs_version(self.profile) > (0, 0)
        if software and (self.report.software_vertex_processing
                         or self.profile.vertex_shader_version == (0, 0)):
            return SOFTWARE_VS_CONSTANTS, (f"software vertex processing has c0..c"
                                           f"{SOFTWARE_VS_CONSTANTS - 1}")
        if hardware == 0:
            return 0, f"the {card} has no vertex shader constant registers (MaxVertexShaderConst 0)"
        return hardware, f"the {card} has MaxVertexShaderConst {hardware} (c0..c{hardware - 1})"
