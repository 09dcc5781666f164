"""Fixed-function texture stage checks: the number of stages, each ColorOp/AlphaOp against
TextureOpCaps, Temp/Constant arguments and ResultArg against PrimitiveMiscCaps, and the
ResultArg rules every card shares.

A mixin of `validate._PassChecker`: it uses the checker's state, profile, report
and reason helpers (fail, need_bit, where, unknown ...)."""
from __future__ import annotations

from typing import Any

from effects.d3d9.stage_ops import (MAX_STAGES, STAGE_OPS, TA_ALPHAREPLICATE, TA_COMPLEMENT, TA_CONSTANT,
                               TA_CURRENT, TA_SELECTMASK, TA_TEMP, StageOp)

def _stage_op(op: str) -> StageOp | None:
    """The lowering's row for a D3DTOP: the caps bit it needs, the arguments it reads, and
    whether it samples its texture without a TEXTURE argument. Validation reads the same
    table the lowering runs, so "valid" and "what runs" cannot drift apart."""
    return STAGE_OPS.get(op)


# Which arguments each op reads (D3DTEXTUREOP docs): most read 1 and 2.
def _args_read(op: str) -> tuple[int, ...]:
    row = _stage_op(op)
    return row.args if row is not None else ((1, 2) if op != "DISABLE" else ())


class StageChecks:
    """The fixed-function texture stage checks of a pass (used when it has no pixel shader)."""

    def arg_select(self, name: str, stage: int) -> int | None:
        """The D3DTA selector of an argument state (modifiers masked off), or None."""
        value = self.state.get_int(name, stage, default=None)
        return None if value is None else value & TA_SELECTMASK

    def active_stages(self) -> list[int]:
        """Stages up to the first disabled one (an unknown op counts as enabled)."""
        stages = []
        for stage in range(MAX_STAGES):
            if self.state.get_enum("ColorOp", stage, default=None) == "DISABLE":
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
        for field, bit, subject, location in self.card_free(
                ("stages", tuple(stages)), lambda: self._stage_needs(stages)):
            self.need_bit(field, bit, subject, location)
        if stages:
            self.check_result_args(stages)

    def _stage_needs(self, stages: list[int]) -> list[tuple[str, str, str, Any]]:
        """(caps field, bit, subject, location) each active stage's ops and arguments need,
        in stage order: what `check_texture_stages` asks of each card."""
        needs: list[tuple[str, str, str, Any]] = []
        for stage in stages:
            for op_state, arg_prefix in (("ColorOp", "ColorArg"), ("AlphaOp", "AlphaArg")):
                if self.unknown(op_state, stage):
                    continue
                op = self.state.get_enum(op_state, stage, default=None)
                if op is None or (op_state == "AlphaOp" and op == "DISABLE"):
                    continue
                shown = self._shown(op_state, stage)
                row = _stage_op(op)
                needs.append(("TextureOpCaps", row.cap if row is not None else op,
                              f"{op_state}[{stage}] = {shown}", self.where(op_state, stage)))
                for n in _args_read(op):
                    self._arg_needs(f"{arg_prefix}{n}", stage, needs)
        return needs

    def _arg_needs(self, state_name: str, stage: int, needs: list[tuple[str, str, str, Any]]) -> None:
        if self.unknown(state_name, stage):
            return
        select = self.arg_select(state_name, stage)
        if select == TA_TEMP:
            needs.append(("PrimitiveMiscCaps", "TSSARGTEMP", f"{state_name}[{stage}] = Temp",
                          self.where(state_name, stage)))
        elif select == TA_CONSTANT:
            needs.append(("PrimitiveMiscCaps", "PERSTAGECONSTANT", f"{state_name}[{stage}] = Constant",
                          self.where(state_name, stage)))

    def check_result_args(self, stages: list[int]) -> None:
        """ResultArg is Current (default) or Temp, never modified, and the last stage writes
        Current, which is what reaches the frame buffer (D3DTSS_RESULTARG docs)."""
        for stage in stages:
            if self.state.assignment("ResultArg", stage) is None or self.unknown("ResultArg", stage):
                continue
            value = self.state.get_int("ResultArg", stage, default=None)
            if value is None:
                continue
            subject = f"ResultArg[{stage}] = {self._shown_flags('ResultArg', stage)}"
            loc = self.where("ResultArg", stage)
            if value & (TA_COMPLEMENT | TA_ALPHAREPLICATE) or (value & TA_SELECTMASK) not in (TA_CURRENT, TA_TEMP):
                self.fail(loc, subject, "D3DTA_CURRENT or D3DTA_TEMP", "any card",
                          f"{subject}: a stage writes its result to Current or Temp only, without "
                          "modifiers; no card accepts this")
                continue
            if value == TA_TEMP:
                self.need_bit("PrimitiveMiscCaps", "TSSARGTEMP", subject, loc)
                if stage == stages[-1]:
                    self.fail(loc, subject, "D3DTA_CURRENT on the last active stage", "any card",
                              f"{subject} on the last active stage: its result never reaches the "
                              "frame buffer, which takes Current; no card accepts this")
